"""Free forces and moments against textbook closed forms.

References: any machine-dynamics text (e.g. Den Hartog, Mechanical Vibrations, ch. 5;
Taylor, The Internal-Combustion Engine in Theory and Practice, vol. 2, ch. 8);
2021 paper Eqs. 1-3 for the inline-3 crank.
"""

from __future__ import annotations

import math

import pytest

from crankbalance.physics.kinematics import harmonic_coefficients
from crankbalance.schema.engine import spec_from_dict
from crankbalance.studies.engine import analyze

R, L, PITCH, RPM = 0.043, 0.145, 0.092, 6000.0
W = RPM * math.pi / 30


def inline(
    cylinders: int,
    firing: list[int],
    kinematics: str = "exact",
    throw_angles: list[float] | None = None,
) -> dict:
    ct = {
        "layout": "inline",
        "cylinders": cylinders,
        "firing_order": firing,
        "crank_radius": f"{R * 1e3} mm",
        "rod_length": f"{L * 1e3} mm",
        "crank_pitch": f"{PITCH * 1e3} mm",
    }
    if throw_angles is not None:
        ct["throw_angles"] = [f"{a} deg" for a in throw_angles]
    return {
        "speed": f"{RPM} rpm",
        "kinematics": kinematics,
        "crank_train": ct,
        "masses": {"reciprocating": "600 g", "rotating": "900 g"},
    }


def primary(mass: float = 0.6) -> float:
    return mass * R * W**2


@pytest.mark.parametrize("kinematics", ["exact", "first-order"])
def test_inline4_flat_crank(kinematics: str) -> None:
    result = analyze(spec_from_dict(inline(4, [1, 3, 4, 2], kinematics)))
    f = result.forces
    lam = R / L
    a2 = harmonic_coefficients(lam, 2, 0.0, kinematics)[1].real  # type: ignore[arg-type]
    p = primary()
    assert f.force_amplitude[0] < 1e-9 * p, "inline-4: F1 = 0 (textbook)"
    assert f.moment_amplitude[0] < 1e-9 * p, "inline-4: M1 = 0 (textbook)"
    assert f.moment_amplitude[1] < 1e-9 * p, "inline-4: M2 = 0 (textbook)"
    assert f.force_amplitude[1] == pytest.approx(4 * a2 * p, rel=1e-12), "inline-4: F2 = 4 A2 P"
    assert abs(f.rotating_force) < 1e-9 * p and abs(f.rotating_couple) < 1e-9 * p


def test_inline3_primary_couple() -> None:
    result = analyze(spec_from_dict(inline(3, [1, 3, 2])))
    f, p = result.forces, primary()
    assert f.force_amplitude[0] < 1e-9 * p, "inline-3: F1 = 0 (textbook)"
    assert f.force_amplitude[1] < 1e-9 * p, "inline-3: F2 = 0 (textbook)"
    assert f.moment_amplitude[0] == pytest.approx(math.sqrt(3) * PITCH * p, rel=1e-12), (
        "inline-3: M1 = sqrt(3) a P (textbook)"
    )
    # the primary couple of an inline-3 splits equally into forward and backward phasors
    assert abs(f.couple_forward[0]) == pytest.approx(abs(f.couple_backward[0]), rel=1e-12)


def test_inline6_balanced_in_orders_1_2_4() -> None:
    result = analyze(spec_from_dict(inline(6, [1, 5, 3, 6, 2, 4])))
    f, p = result.forces, primary()
    for order in (1, 2, 4):
        k = f.order(order)
        assert f.force_amplitude[k] < 1e-9 * p, f"inline-6: no free force of order {order}"
        assert f.moment_amplitude[k] < 1e-9 * p * PITCH, f"inline-6: no couple of order {order}"
    k6 = f.order(6)
    assert f.force_amplitude[k6] > 1e-6 * p, "inline-6: the sixth order adds up (all in phase)"


@pytest.mark.parametrize("kinematics", ["exact", "series", "first-order"])
def test_single_cylinder(kinematics: str) -> None:
    data = inline(1, [1], kinematics)
    result = analyze(spec_from_dict(data))
    f, p, lam = result.forces, primary(), R / L
    a2 = {"exact": None, "series": lam + lam**3 / 4 + 15 * lam**5 / 128, "first-order": lam}[
        kinematics
    ]
    assert f.force_amplitude[0] == pytest.approx(p, rel=1e-12), "single: primary force P"
    if a2 is not None:
        assert f.force_amplitude[1] == pytest.approx(a2 * p, rel=1e-12), "single: secondary A2 P"
    # each order of a single cylinder acts along the cylinder axis: equal phasors
    assert abs(f.force_forward[0]) == pytest.approx(abs(f.force_backward[0]), rel=1e-12)
    assert abs(f.rotating_force) == pytest.approx(0.9 * R * W**2, rel=1e-12)


def test_vee90_twin_primary_is_a_constant_rotating_force() -> None:
    """90-degree V-twin on one pin: the primary is a forward phasor of P, no backward one
    (textbook; the reason a counterweight of one cylinder's reciprocating mass balances it)."""
    data = inline(1, [1])
    data["crank_train"] = dict(
        data["crank_train"], layout="vee", cylinders=2, bank_angle="90 deg", firing_order=None
    )
    del data["crank_train"]["firing_order"]
    f = analyze(spec_from_dict(data)).forces
    assert abs(f.force_forward[0]) == pytest.approx(primary(), rel=1e-12)
    assert abs(f.force_backward[0]) < 1e-9 * primary()


def test_radial_primary_is_n_over_2_forward() -> None:
    """Radial engine of n >= 3 cylinders on one pin: primary = n P / 2, forward only;
    no second order (textbook)."""
    data = inline(1, [1])
    data["crank_train"] = {
        "layout": "radial",
        "cylinders": 5,
        "crank_radius": f"{R * 1e3} mm",
        "rod_length": f"{L * 1e3} mm",
    }
    f = analyze(spec_from_dict(data)).forces
    assert abs(f.force_forward[0]) == pytest.approx(2.5 * primary(), rel=1e-12)
    assert abs(f.force_backward[0]) < 1e-9 * primary()
    assert f.force_amplitude[1] < 1e-9 * primary()


def test_crossplane_v8_has_primary_couple_only() -> None:
    result = analyze("v8-crossplane")
    f = result.forces
    scale = (
        float(result.model.reciprocating_mass.sum())
        * result.model.crank_radius
        * result.model.speed**2
    )
    assert f.force_amplitude[0] < 1e-9 * scale and f.force_amplitude[1] < 1e-9 * scale
    assert f.moment_amplitude[1] < 1e-9 * scale, "crossplane V8: no secondary couple"
    assert f.moment_amplitude[0] > 0.01 * scale * 0.1
    # the primary couple of a 90-degree crossplane V8 is a pure forward phasor (textbook:
    # it is cancelled by crank counterweights alone)
    assert abs(f.couple_backward[0]) < 1e-9 * abs(f.couple_forward[0])
