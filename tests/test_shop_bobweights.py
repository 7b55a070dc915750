"""Bob-weights per crankpin and the free forces a bob-weight fraction leaves
(crankbalance.physics.shop.bobweights), against hand calculations written here."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine
from crankbalance.physics.shop.bobweights import best_fraction, bob_weights, remaining_forces
from crankbalance.studies.build import build_model

#: relative agreement of a computed force with its hand value (float round-off only)
CLOSE = 1e-9


def model(preset: str):
    return build_model(load_engine(preset))


def test_v8_bob_weights_by_hand() -> None:
    """90° V8, cylinders k and k + 4 on pin k (docs/engine_file.md). Per rod: big end
    455.0 g + shells 48.0 g + oil 4.0 g = 507.0 g rotating; cylinder 1 has 860.0 g
    reciprocating, the others 862.0 g. Pin 1 (cylinders 1 and 5), 50 %:
    2 x 507.0 + 0.5 x (860.0 + 862.0) = 1014.0 + 861.0 = 1875.0 g; pins 2-4:
    1014.0 + 862.0 = 1876.0 g."""
    v8 = model("v8-crossplane")
    rotating = np.full(8, 0.507)
    reciprocating = np.full(8, 0.862)
    reciprocating[0] = 0.860
    weights = bob_weights(v8, 0.5, rotating, reciprocating)
    assert weights.rods_on_pin.tolist() == [2, 2, 2, 2]
    assert weights.bob_weight == pytest.approx([1.875, 1.876, 1.876, 1.876], rel=1e-12)
    assert weights.rotating == pytest.approx([1.014] * 4, rel=1e-12)
    assert weights.reciprocating == pytest.approx([1.722, 1.724, 1.724, 1.724], rel=1e-12)
    # fraction 0: the rotating share alone; fraction 1: all of it
    assert bob_weights(v8, 0.0, rotating, reciprocating).bob_weight == pytest.approx([1.014] * 4)
    assert bob_weights(v8, 1.0, rotating, reciprocating).bob_weight[1] == pytest.approx(2.738)


def test_split_pin_v6_has_one_rod_per_pin() -> None:
    """60° split-pin V6: six pins, one rod each: B = R + f M = 0.5 + 0.5 x 0.6 = 0.8 kg."""
    v6 = model("v6-60")
    weights = bob_weights(v6, 0.5, np.full(6, 0.5), np.full(6, 0.6))
    assert weights.rods_on_pin.tolist() == [1] * 6
    assert weights.bob_weight == pytest.approx([0.8] * 6)


def test_w12_has_three_rods_per_pin() -> None:
    """W12 on four throws: three rods per pin, B = 3 R + f 3 M = 1.5 + 0.5 x 1.8 = 2.4 kg."""
    w12 = model("w12")
    weights = bob_weights(w12, 0.5, np.full(12, 0.5), np.full(12, 0.6))
    assert weights.rods_on_pin.tolist() == [3, 3, 3, 3]
    assert weights.bob_weight == pytest.approx([2.4] * 4)


def primary(preset: str) -> float:
    """m r w^2 of one cylinder [N]."""
    m = model(preset)
    return float(m.reciprocating_mass[0] * m.crank_radius * m.speed**2)


@pytest.mark.parametrize("fraction", [0.0, 0.25, 0.5, 0.8, 1.0])
@pytest.mark.parametrize(("preset", "vee"), [("v2-90", 90.0), ("v2-45", 45.0)])
def test_common_pin_vee_twin_by_hand(preset: str, vee: float, fraction: float) -> None:
    """Two cylinders at +-V/2 on one pin, no offset (first harmonic exactly cos): the
    primary forces add to a forward phasor m r w^2 and a backward one m r w^2 cos V; the
    crank balanced with bob-weights of fraction f carries -2 f m at the pin, so the
    largest first-order force is m r w^2 (|1 - 2 f| + |cos V|)."""
    hand = primary(preset) * (abs(1 - 2 * fraction) + abs(math.cos(math.radians(vee))))
    left = remaining_forces(model(preset), fraction)
    assert left.force_amplitude[0] == pytest.approx(hand, rel=CLOSE, abs=CLOSE * primary(preset))
    assert left.couple_amplitude[0] == pytest.approx(0.0, abs=1e-12)


def test_single_cylinder_half_balance() -> None:
    """One cylinder: forward and backward phasors m r w^2 / 2 each; f = 0.5 cancels the
    forward one and leaves m r w^2 / 2, the least peak (Hoem and Røsholm 2016, Sec. 3.2)."""
    single = model("single")
    left = remaining_forces(single, 0.5)
    assert left.force_amplitude[0] == pytest.approx(0.5 * primary("single"), rel=CLOSE)
    assert best_fraction(single) == pytest.approx(0.5, rel=1e-12)


def test_crossplane_v8_primary_couple_by_hand() -> None:
    """Crossplane V8: pins at 315°, 45°, 225°, 135° at y = -168, -56, 56, 168 mm. With
    f = 0 the primary couple is m r w^2 |sum y e^(i phi)|:
    re = cos 45° (-168 - 56 - 56 - 168) = -316.78 mm, im = sin 45° (168 - 56 - 56 + 168)
    = 158.39 mm, |.| = 354.18 mm = sqrt(10) x 112 mm (the textbook sqrt(10) m r w^2 a of
    Taylor 1985, ch. 8). With f = 0.5 the counterweights cancel it and the force."""
    v8 = model("v8-crossplane")
    unit = primary("v8-crossplane")
    bare = remaining_forces(v8, 0.0)
    assert bare.couple_amplitude[0] == pytest.approx(unit * math.sqrt(10) * 0.112, rel=CLOSE)
    assert bare.force_amplitude[0] == pytest.approx(0.0, abs=CLOSE * unit)
    half = remaining_forces(v8, 0.5)
    assert half.couple_amplitude[0] == pytest.approx(0.0, abs=CLOSE * unit)
    assert half.force_amplitude[0] == pytest.approx(0.0, abs=CLOSE * unit)
    assert best_fraction(v8, quantity="couple") == pytest.approx(0.5, rel=1e-9)
    assert best_fraction(v8) is None  # the pins' forces cancel: no fraction changes them


@pytest.mark.parametrize("preset", ["boxer2", "w12", "v6-60", "v8-flatplane"])
def test_fraction_changes_only_the_forward_first_order(preset: str) -> None:
    """The counterweights turn with the crank: the backward first-order phasor and every
    higher order do not depend on the fraction."""
    engine = model(preset)
    a, b = remaining_forces(engine, 0.0, orders=4), remaining_forces(engine, 1.0, orders=4)
    scale = primary(preset)
    assert np.allclose(a.force_backward, b.force_backward, rtol=0, atol=CLOSE * scale)
    assert np.allclose(a.force_forward[1:], b.force_forward[1:], rtol=0, atol=CLOSE * scale)
    assert np.allclose(a.couple_forward[1:], b.couple_forward[1:], rtol=0, atol=CLOSE * scale)


def test_best_fraction_minimises_the_first_order_peak() -> None:
    """A sweep of the fraction finds no lower first-order couple peak than best_fraction
    (60° split-pin V6, uneven parts)."""
    v6 = model("v6-60")
    parts = np.array([0.60, 0.61, 0.59, 0.62, 0.60, 0.58])
    best = best_fraction(v6, parts, quantity="couple")
    assert best is not None
    peak = remaining_forces(v6, best, parts).couple_amplitude[0]
    sweep = [remaining_forces(v6, f, parts).couple_amplitude[0] for f in np.linspace(0, 1, 101)]
    assert peak <= min(sweep) * (1 + 1e-12)


def test_inline4_fraction_has_no_effect() -> None:
    assert best_fraction(model("inline4")) is None
    assert best_fraction(model("inline4"), quantity="couple") is None


def test_bad_input() -> None:
    v8 = model("v8-crossplane")
    with pytest.raises(InputError, match="fraction"):
        bob_weights(v8, 2.5, np.zeros(8))
    with pytest.raises(InputError, match=r"rotating.*one mass per cylinder \(8\)"):
        bob_weights(v8, 0.5, np.zeros(7))
    with pytest.raises(InputError, match=r"reciprocating\[3\]"):
        bob_weights(v8, 0.5, np.zeros(8), [0.8, 0.8, -0.1, 0.8, 0.8, 0.8, 0.8, 0.8])
    with pytest.raises(InputError, match="quantity"):
        best_fraction(v8, quantity="torque")
    with pytest.raises(InputError, match="orders"):
        remaining_forces(v8, 0.5, orders=0)
