"""A vee with split crankpins given by ``crank_train.pin_split`` (issue 28, review finding 21).

Reference: the same engine written as six custom throws by hand (the ``v6-60`` preset);
firing intervals read from the built model's top dead centres.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import crankbalance
from crankbalance.errors import InputError
from crankbalance.io.engine_file import load_engine
from crankbalance.physics.firing import firing_tdc_angles
from crankbalance.physics.model import EngineModel, tdc_angle
from crankbalance.physics.shaking import exact_time_domain
from crankbalance.schema.engine import spec_from_dict
from crankbalance.studies.build import build_model
from crankbalance.studies.engine import analyze

PRESET = Path(crankbalance.__file__).parent / "presets" / "v6-60.toml"

#: the v6-60 preset's masses (each split pin a throw of its own)
MASSES = {
    "piston": "340 g",
    "wrist_pin": "110 g",
    "conrod": "520 g",
    "conrod_rotating_fraction": 0.67,
    "crankpin": "140 g",
    "crank_web": "350 g",
    "crank_web_cg_radius": "17 mm",
}


def vee(cylinders: int = 6, bank: float = 60.0, **train: Any) -> dict[str, Any]:
    """An engine-file dictionary of a vee; ``train`` adds or replaces crank_train keys."""
    crank_train = {
        "layout": "vee",
        "cylinders": cylinders,
        "bank_angle": f"{bank} deg",
        "crank_pitch": "110 mm",
        "strokes": 4,
        "crank_radius": "43 mm",
        "rod_length": "145 mm",
    }
    crank_train.update(train)
    return {"name": "split vee", "speed": "6000 rpm", "crank_train": crank_train, "masses": MASSES}


def v6_60_as_vee() -> dict[str, Any]:
    """The v6-60 preset as a vee: bank A (cylinders 1-3, -30 deg) at -12 mm of each pair's
    mid-plane, bank B (4-6) at +12 mm; the preset's order 1..6 (throw after throw) in the
    vee's numbering."""
    return vee(
        pin_split="60 deg",
        rod_positions=["-12 mm"] * 3 + ["12 mm"] * 3,
        firing_order=[1, 4, 2, 5, 3, 6],
    )


def firing_intervals(model: EngineModel) -> np.ndarray:
    """Crank angle from each cylinder's top dead centre to the next one's in the firing
    order, modulo one turn [deg] (a 4-stroke's firing TDC is one of the two)."""
    angle = model.throw_angle[model.cylinder_throw]
    shift = tdc_angle(model.cylinder_offset, model.crank_radius, model.rod_length)
    tdc = firing_tdc_angles(angle, model.cylinder_bank, shift)
    order = np.array(model.firing_order) - 1
    # cylinder c is at TDC when theta = tdc[c]: the next in the order comes one interval later
    steps = np.degrees(np.mod(tdc[np.roll(order, -1)] - tdc[order], 2 * np.pi))
    return np.where(np.isclose(steps, 360.0), 0.0, steps)


def test_the_split_vee_is_the_v6_60_preset_throw_by_throw() -> None:
    preset = build_model(load_engine(PRESET))
    split = build_model(spec_from_dict(v6_60_as_vee()))
    # the preset numbers its cylinders throw after throw (A, B, A, B, ...); the vee bank A
    # 1-3, bank B 4-6: vee cylinder c is preset cylinder ours[c]
    ours = np.array([0, 2, 4, 1, 3, 5])
    np.testing.assert_allclose(split.throw_position, preset.throw_position, rtol=0, atol=1e-15)
    gap = np.remainder(split.throw_angle - preset.throw_angle + np.pi, 2 * np.pi) - np.pi
    np.testing.assert_allclose(gap, 0.0, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(split.cylinder_throw, preset.cylinder_throw[ours])
    np.testing.assert_array_equal(split.cylinder_bank, preset.cylinder_bank[ours])
    np.testing.assert_array_equal(split.cylinder_axial, np.zeros(6))
    np.testing.assert_allclose(split.throw_rotating_mass, preset.throw_rotating_mass, rtol=1e-15)
    np.testing.assert_allclose(
        split.reciprocating_mass, preset.reciprocating_mass[ours], rtol=1e-15
    )
    assert [int(ours[c - 1]) + 1 for c in split.firing_order] == list(preset.firing_order)


def test_the_split_vee_has_the_presets_free_forces_and_moments() -> None:
    preset = analyze(load_engine(PRESET)).forces
    split = analyze(spec_from_dict(v6_60_as_vee())).forces
    for f in dataclasses.fields(preset):
        a, b = np.asarray(getattr(preset, f.name)), np.asarray(getattr(split, f.name))
        if a.dtype.kind in "fc":
            scale = max(float(np.max(np.abs(a), initial=0.0)), 1.0)
            np.testing.assert_allclose(b, a, rtol=0, atol=1e-9 * scale, err_msg=f.name)
        else:
            np.testing.assert_array_equal(b, a, err_msg=f.name)
    # and the exact time domain, force and moment at every crank angle
    angle = np.linspace(0, 4 * np.pi, 721)
    for a, b in zip(
        exact_time_domain(build_model(load_engine(PRESET)), angle),
        exact_time_domain(build_model(spec_from_dict(v6_60_as_vee())), angle),
        strict=True,
    ):
        np.testing.assert_allclose(b, a, rtol=0, atol=1e-9 * float(np.max(np.abs(a))))


@pytest.mark.parametrize(
    ("cylinders", "bank", "split"),
    [(6, 60.0, 60.0), (6, 90.0, 30.0), (10, 90.0, -18.0), (8, 90.0, 0.0), (2, 90.0, 270.0)],
)
def test_the_split_of_even_firing_is_the_interval_minus_the_bank_angle(
    cylinders: int, bank: float, split: float
) -> None:
    """Bank B's cylinder of each throw one interval (720/n deg) after bank A's: even
    firing needs the split 720/n - V (wrapped to (-180, 180]); any other split does not
    fire evenly."""
    t = cylinders // 2
    assert math.isclose(split, 720.0 / cylinders - bank)
    split = math.remainder(split, 360.0)
    order = [c for k in range(1, t + 1) for c in (k, k + t)]
    rods = ["-10 mm"] * t + ["10 mm"] * t
    even = build_model(
        spec_from_dict(
            vee(cylinders, bank, pin_split=f"{split} deg", rod_positions=rods, firing_order=order)
        )
    )
    assert even.throws == cylinders
    interval = (720.0 / cylinders) % 360.0  # a V-twin's 360 deg: 0 deg modulo one turn
    np.testing.assert_allclose(firing_intervals(even), interval, rtol=0, atol=1e-9)
    pins = even.throw_angle[even.cylinder_throw]
    np.testing.assert_allclose(
        np.remainder(np.degrees(pins[:t] - pins[t:]) - split + 180, 360) - 180, 0, atol=1e-9
    )
    uneven = build_model(
        spec_from_dict(vee(cylinders, bank, pin_split=f"{split + 5} deg", rod_positions=rods))
    )
    assert np.ptp(firing_intervals(uneven)) > 1.0


def test_a_v6_90_with_30_deg_split_pins_fires_every_120_deg() -> None:
    model = build_model(
        spec_from_dict(vee(6, 90.0, pin_split="30 deg", firing_order=[1, 4, 2, 5, 3, 6]))
    )
    np.testing.assert_allclose(firing_intervals(model), 120.0, rtol=0, atol=1e-9)
    # without rod positions both pins of a throw sit in its mid-plane
    np.testing.assert_allclose(
        model.throw_position, np.repeat([-0.11, 0.0, 0.11], 2), rtol=0, atol=1e-15
    )


def test_the_pins_are_numbered_along_the_crank() -> None:
    """Throws after the split: pair after pair, within a pair by position."""
    model = build_model(
        spec_from_dict(
            vee(
                4,
                90.0,
                pin_split="-90 deg",
                rod_positions=["10 mm", "-10 mm", "-10 mm", "10 mm"],
            )
        )
    )
    np.testing.assert_allclose(
        model.throw_position, [-0.065, -0.045, 0.045, 0.065], rtol=0, atol=1e-15
    )
    np.testing.assert_array_equal(model.cylinder_throw, [1, 2, 0, 3])


def test_overrides_count_the_split_pins_as_throws() -> None:
    data = v6_60_as_vee()
    data["masses"] = dict(MASSES, override=[{"throws": [6], "crank_web": "400 g"}])
    model = build_model(spec_from_dict(data))
    assert model.throw_rotating_mass[5] > model.throw_rotating_mass[4]
    data["masses"]["override"] = [{"throws": [7], "crank_web": "400 g"}]
    with pytest.raises(InputError) as err:
        spec_from_dict(data)
    assert err.value.field == "masses.override[0].throws"
    assert "(1..6)" in str(err.value)


@pytest.mark.parametrize(
    ("change", "words"),
    [
        ({"pin_split": "200 deg"}, "(-180, 180] deg for a vee"),
        ({"pin_split": "-180 deg"}, "(-180, 180] deg for a vee"),
        ({"throw_angles": ["0 deg", "120 deg", "240 deg"]}, "not both"),
        ({"layout": "inline", "bank_angle": None}, "only used with layout 'vee'"),
        ({"layout": "boxer", "bank_angle": None}, "not 'boxer'"),
    ],
)
def test_a_bad_split_names_the_field(change: dict[str, Any], words: str) -> None:
    data = v6_60_as_vee()
    data["crank_train"].update(change)
    data["crank_train"] = {k: v for k, v in data["crank_train"].items() if v is not None}
    with pytest.raises(InputError) as err:
        spec_from_dict(data)
    assert err.value.field == "crank_train.pin_split"
    assert words in str(err.value)


def test_a_split_on_custom_throws_names_the_field() -> None:
    data = v6_60_as_vee()
    data["crank_train"] = {
        "layout": "custom",
        "crank_radius": "43 mm",
        "rod_length": "145 mm",
        "pin_split": "60 deg",
        "throw": [{"position": "0 mm", "angle": "0 deg", "banks": ["-30 deg", "30 deg"]}],
    }
    with pytest.raises(InputError) as err:
        spec_from_dict(data)
    assert err.value.field == "crank_train.pin_split"
    assert "gives each throw's angle itself" in str(err.value)
