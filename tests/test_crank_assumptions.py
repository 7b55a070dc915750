"""One answer for what the studies of an engine assume when the user does not type it
(docs/torsional.md, "What is assumed when not typed"): the crank dimensions of ``bearings``
and ``torsional``, the crank + flywheel inertia of ``cycle --engine``, ``bearings`` and
``torsional``, and the combustion of all of them; the typed value wins."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy import integrate

from crankbalance.errors import InputError
from crankbalance.output.format import text
from crankbalance.physics import torsional as tv
from crankbalance.schema.settings import (
    BearingOptions,
    CombustionOptions,
    CycleOptions,
    TorsionalOptions,
)
from crankbalance.studies.crank import crank_dimensions, rotating_inertia
from crankbalance.studies.engine import as_model
from crankbalance.studies.loads import bearing_loads

from .conftest import run_cli

#: the inline4 preset by hand: crank radius, throw pitch [m]; masses [kg]
R, PITCH = 0.043, 0.092
ROD = 0.145
M_ROT = 0.280 + 2 * 0.700 * 17 / 43 + 0.67 * 0.520  # crankpin, webs at r, big end
M_REC = 0.340 + 0.110 + 0.33 * 0.520  # piston, wrist pin, small end
#: the inline4's dimensions by hand: web offset a/4, journal 1.3 r, pin 1.1 r, web 2.2 r x
#: 0.75 o, pin 2 o - h between the webs, journal a - 2 o - h between neighbouring throws
O = PITCH / 4
H = 0.75 * O
HAND = {
    "journal_diameter_m": 1.3 * R,
    "pin_diameter_m": 1.1 * R,
    "web_width_m": 2.2 * R,
    "web_thickness_m": H,
    "pin_length_m": 2 * O - H,
    "journal_length_m": PITCH - 2 * O - H,
}
FAST = ["--speed-points", "20", "--format", "json"]


def _json(capsys, args: list[str]) -> dict:
    code, out, err = run_cli(args, capsys)
    assert code == 0, err
    return json.loads(out)


@pytest.fixture(scope="module")
def bearings() -> dict:
    return bearing_loads("inline4", {"samples": 72}).to_dict()["settings"]


def test_bearings_and_torsional_take_the_same_dimensions(capsys, bearings: dict) -> None:
    """The inline-4: the dimensions bearings and torsional print are the hand values, and
    the throws' stiffness is Carter's formula of them."""
    torsional = _json(capsys, ["torsional", "--engine", "inline4", *FAST])
    dims = torsional["crank"]["dimensions"]
    assert dims["typed"] == [] and bearings["dimensions_typed"] == []
    for key, value in HAND.items():
        assert dims[key] == pytest.approx(value, rel=1e-12), key
        if key in bearings:
            assert bearings[key] == pytest.approx(value, rel=1e-12), key
    assert dims["web_offset_m"] == bearings["web_offset_m"] == pytest.approx(O)
    k = tv.carter_stiffness(
        *(HAND[k] for k in ("journal_diameter_m", "pin_diameter_m", "journal_length_m")),
        *(HAND[k] for k in ("pin_length_m", "web_thickness_m", "web_width_m")),
        R,
    )
    for section in torsional["sections"]:
        assert section["stiffness_Nm_rad"] == pytest.approx(k, rel=1e-12)


def _mean_slope2() -> float:
    """The mean of s'^2 over a turn, by quadrature of the slider-crank velocity
    s' = r sin(a) (1 + lambda cos(a) / sqrt(1 - lambda^2 sin^2(a))) written here."""
    lam = R / ROD

    def slope2(a: float) -> float:
        s = R * math.sin(a) * (1 + lam * math.cos(a) / math.sqrt(1 - (lam * math.sin(a)) ** 2))
        return s * s

    mean = integrate.quad(slope2, 0.0, 2 * math.pi, epsabs=1e-14)[0] / (2 * math.pi)
    # the series of docs/torsional.md as a sanity check of the quadrature
    assert mean == pytest.approx(R**2 / 2 * (1 + lam**2 / 4), rel=2e-3)
    return mean


def test_rotating_inertia_against_the_closed_form() -> None:
    """front + throws + flywheel: m_rot r^2 per throw, no pistons (the cycles add their
    inertia m s'^2 as it varies over the turn); the torsional chain adds the pistons' mean
    share m mean(s'^2) to each throw."""
    expected = 0.010 + 4 * M_ROT * R**2 + 0.15
    model = as_model("inline4")
    assert rotating_inertia(model) == pytest.approx(expected, rel=1e-12)
    typed = rotating_inertia(model, 0.004, 0.02, 0.3)
    assert typed == pytest.approx(0.02 + 4 * 0.004 + 0.3, rel=1e-12)
    chain = tv.throw_inertias(model).sum()
    assert chain == pytest.approx(4 * (M_ROT * R**2 + M_REC * _mean_slope2()), rel=1e-6)


def test_cycle_bearings_and_torsional_take_the_same_inertia(capsys, bearings: dict) -> None:
    cycle = _json(capsys, ["cycle", "--engine", "inline4", "--format", "json"])
    torsional = _json(capsys, ["torsional", "--engine", "inline4", *FAST])
    engine = rotating_inertia(as_model("inline4"))
    assert cycle["engine"]["crank_inertia_kg_m2"] == pytest.approx(engine, rel=1e-12)
    assert cycle["engine"]["crank_inertia_from"] == "engine"
    assert bearings["crank_inertia_kg_m2"] == pytest.approx(engine, rel=1e-12)
    assert bearings["crank_inertia_from"] == "engine"
    assert torsional["crank"]["rotating_inertia_kg_m2"] == pytest.approx(engine, rel=1e-12)
    chain = sum(m["inertia_kg_m2"] for m in torsional["masses"])  # no damper, no load
    assert chain == pytest.approx(engine + 4 * M_REC * _mean_slope2(), rel=1e-6)


def test_one_cylinder_of_an_engine_turns_the_engines_inertia(capsys) -> None:
    one = _json(capsys, ["cycle", "--engine", "inline4", "--cylinder", "2", "--format", "json"])
    assert one["crank_inertia_from"] == "engine"
    assert one["cylinder"]["crank_inertia_kg_m2"] == pytest.approx(
        rotating_inertia(as_model("inline4")), rel=1e-12
    )
    sweep = _json(
        capsys,
        ["sensitivity", "--engine", "inline4", "--balance-factors", "0.5", "--format", "json"],
    )
    assert sweep["crank_inertia_from"] == "engine"
    assert sweep["crank_inertia_kg_m2"] == pytest.approx(
        rotating_inertia(as_model("inline4")), rel=1e-12
    )
    assert sweep["combustion"] == one["combustion"]


def test_the_single_cylinder_cycle_keeps_the_thesis_inertia(capsys) -> None:
    data = _json(capsys, ["cycle", "--format", "json"])
    assert data["cylinder"]["crank_inertia_kg_m2"] == 0.006
    assert data["crank_inertia_from"] == "thesis"
    assert CycleOptions().crank_inertia is None


def test_typed_values_win(capsys) -> None:
    settings = bearing_loads(
        "inline4",
        {"samples": 72, "crank_inertia": "0.3 kg*m^2", "journal_diameter": "70 mm"},
    ).to_dict()["settings"]
    assert settings["crank_inertia_kg_m2"] == 0.3 and settings["crank_inertia_from"] == "typed"
    assert settings["journal_diameter_m"] == pytest.approx(0.070)
    assert settings["dimensions_typed"] == ["journal_diameter"]
    assert settings["pin_diameter_m"] == pytest.approx(HAND["pin_diameter_m"])
    cycle = _json(
        capsys,
        ["cycle", "--engine", "inline4", "--crank-inertia", "0.3 kg*m^2", "--format", "json"],
    )
    assert cycle["engine"]["crank_inertia_kg_m2"] == 0.3
    assert cycle["engine"]["crank_inertia_from"] == "typed"
    torsional = _json(capsys, ["torsional", "--engine", "inline4", "--pin-length", "40 mm", *FAST])
    dims = torsional["crank"]["dimensions"]
    assert dims["typed"] == ["pin_length"] and dims["pin_length_m"] == pytest.approx(0.040)
    assert dims["journal_length_m"] == pytest.approx(HAND["journal_length_m"])


def test_one_combustion_for_every_study(capsys, bearings: dict) -> None:
    """The Wiebe defaults of bearings, torsional and cycle are CombustionOptions' (the
    thesis' combustion, docs/engine_cycle.md) and each output says so."""
    base = CombustionOptions()
    for options in (BearingOptions(), CycleOptions(), TorsionalOptions()):
        assert options.compression_ratio == base.compression_ratio == 13.5
        assert options.ignition == base.ignition == pytest.approx(math.radians(-25.0))
    cycle = _json(capsys, ["cycle", "--engine", "inline4", "--format", "json"])
    torsional = _json(capsys, ["torsional", "--engine", "inline4", *FAST])
    assert bearings["combustion"] == cycle["combustion"] == torsional["crank"]["combustion"]
    assert bearings["combustion"]["compression_ratio"] == 13.5


def test_text_outputs_show_what_was_assumed(capsys) -> None:
    for args in (
        ["bearings", "inline4", "--samples", "72"],
        ["torsional", "--engine", "inline4", "--speed-points", "20"],
        ["cycle", "--engine", "inline4"],
        ["sensitivity", "--engine", "inline4", "--balance-factors", "0.5"],
    ):
        code, out, err = run_cli(args, capsys)
        assert code == 0, err
        assert "kg·m²" in out and "compression 13.5, ignition -25°" in out, out
    # a typed flywheel is named apart from the engine's inertia, for one cylinder too
    engine = rotating_inertia(as_model("single"))
    args = ["cycle", "--engine", "single", "--cylinder", "1", "--flywheel-inertia", "0.05 kg*m^2"]
    code, out, err = run_cli(args, capsys)
    assert code == 0, err
    shown = f"crank + flywheel {text(engine, 'inertia')} + flywheel 0.05 kg·m² (the engine's"
    assert shown in out, out


def test_a_web_too_thick_for_the_derived_lengths_is_named() -> None:
    model = as_model("inline4")
    with pytest.raises(InputError, match="journal") as error:
        crank_dimensions(model, 0.040)  # 0.092 - 0.08 - 0.03 < 0
    # the web thickness was derived from the web offset: the message names the offset
    assert error.value.field == "counterweights.web_offset"
    with pytest.raises(InputError, match="journal") as error:
        crank_dimensions(model, 0.030, {"web_thickness": 0.04})  # 0.092 - 0.06 - 0.04 < 0
    assert error.value.field == "web_thickness"
    typed = crank_dimensions(model, 0.040, {"journal_length": 0.01})
    assert typed.journal_length == 0.01 and typed.pin_length == pytest.approx(0.08 - 0.03)
    np.testing.assert_allclose(typed.web_thickness, 0.03)
