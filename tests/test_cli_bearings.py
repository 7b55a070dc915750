"""``crankbalance bearings``: JSON contract, table, plot, refusals; and the inline-4
four-versus-eight-counterweight case against the lever rule worked by hand."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from crankbalance.physics import friction

from .conftest import run_cli

FOUR = "1,0,0,1,1,0,0,1"  # outer webs of each half: webs 1, 4, 5, 8


def _json(args: list[str], capsys: pytest.CaptureFixture[str]) -> dict:
    code, out, err = run_cli(["bearings", *args, "--format", "json"], capsys)
    assert code == 0, err
    return json.loads(out)


def test_json_contract(capsys: pytest.CaptureFixture[str]) -> None:
    data = _json(["inline4", "--samples", "72", "--curves"], capsys)
    assert data["schema"] == "crankbalance.bearings/1"
    assert data["bearing_position_m"] == pytest.approx([-0.184, -0.092, 0.0, 0.092, 0.184])
    assert data["counterweights"]["count"] == 8
    assert "approximation" in data["stiffness"]["note"]
    samples = 72 * 2  # a four-stroke cycle is two revolutions
    assert len(data["crank_angle_rad"]) == samples
    for name in ("determinate", "indeterminate"):
        model = data["models"][name]
        assert [b["bearing"] for b in model["bearings"]] == [1, 2, 3, 4, 5]
        for bearing in model["bearings"]:
            assert bearing["max_load_N"] >= bearing["equivalent_load_N"] >= bearing["mean_load_N"]
            assert bearing["mean_load_N"] > 0
        curves = model["curves"]
        assert np.shape(curves["load_z_N"]) == (5, samples)
        assert np.shape(curves["pin_moment_x_Nm"]) == (4, samples)
        # the table's numbers are those of the curves
        load = np.array(curves["load_z_N"]) + 1j * np.array(curves["load_x_N"])
        np.testing.assert_allclose(
            [b["max_load_N"] for b in model["bearings"]], np.abs(load).max(axis=1), rtol=1e-9
        )
    # the determinate crank is hinged at the journals
    assert all(b["max_journal_moment_Nm"] == 0 for b in data["models"]["determinate"]["bearings"])
    assert data["models"]["indeterminate"]["bearings"][2]["max_journal_moment_Nm"] > 0
    # the crank is symmetric about its mid-point: so are the loads' magnitudes
    mean = [b["mean_load_N"] for b in data["models"]["indeterminate"]["bearings"]]
    np.testing.assert_allclose(mean, mean[::-1], rtol=1e-9)


def test_friction_of_each_bearing(capsys: pytest.CaptureFixture[str]) -> None:
    """Coulomb friction per bearing is mu * mean|F| * d/2 (friction.friction_torque of the
    mean load: the mean is linear), Petroff's torque is friction.petroff_torque."""
    data = _json(
        [
            "inline4",
            "--samples",
            "72",
            "--journal-diameter",
            "50 mm",
            "--friction-coefficient",
            "0.01",
            "--viscosity",
            "0.01 Pa*s",
            "--bearing-length",
            "20 mm",
            "--clearance",
            "25 um",
        ],
        capsys,
    )
    speed = data["settings"]["speed_rad_s"]
    petroff = float(friction.petroff_torque(0.01, 0.05, 0.02, 25e-6, speed))
    for bearing in data["models"]["indeterminate"]["bearings"]:
        expected = float(friction.friction_torque(0.01, bearing["mean_load_N"], 0.05))
        assert bearing["coulomb_friction_torque_Nm"] == pytest.approx(expected, rel=1e-9)
        assert bearing["petroff_friction_torque_Nm"] == pytest.approx(petroff, rel=1e-6)


def test_four_and_eight_counterweights_lever_rule(capsys: pytest.CaptureFixture[str]) -> None:
    """Inline-4 with webs at a quarter pitch from their throws. Eight counterweights
    balance every throw (m_cw = m_rot / 2 per web); four (webs 1, 4, 5, 8, each half
    balanced) need m_cw = 2 m_rot / 3 per web (the halves' couple). By the lever rule, each
    outer-web counterweight gives 3/4 of its force to the near bearing and 1/4 to the far
    one, the rotating mass 1/2 to each: m_rot/2 - 3/4 * 2/3 m_rot = 0 at bearings 1, 3, 5,
    and m_rot/2 - 1/4 * 2/3 m_rot = m_rot/3 from each throw, opposite, at bearings 2 and 4.
    So the statically determinate crank cannot tell the two apart (identical bearing loads),
    while the continuous crank bends differently: the difference is crank bending."""
    eight = _json(["inline4", "--samples", "72"], capsys)
    four = _json(["inline4", "--samples", "72", "--webs", FOUR], capsys)
    rot = 1.18188837  # the preset's rotating mass per throw [kg], model.throw_rotating_mass
    assert eight["counterweights"]["mass_kg"] == pytest.approx([rot / 2] * 8, rel=1e-6)
    assert four["counterweights"]["mass_kg"] == pytest.approx([2 * rot / 3] * 4, rel=1e-6)
    for key in ("max_load_N", "mean_load_N", "equivalent_load_N"):
        a = [b[key] for b in eight["models"]["determinate"]["bearings"]]
        b = [b[key] for b in four["models"]["determinate"]["bearings"]]
        np.testing.assert_allclose(a, b, rtol=1e-9)
    centre8 = eight["models"]["indeterminate"]["bearings"][2]
    centre4 = four["models"]["indeterminate"]["bearings"][2]
    assert centre4["mean_load_N"] > centre8["mean_load_N"]
    assert centre4["max_journal_moment_Nm"] > centre8["max_journal_moment_Nm"]


def test_table_and_plot(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("plotly")
    target = tmp_path / "loads.html"
    code, out, err = run_cli(
        ["bearings", "inline4", "--samples", "72", "--plot", str(target)], capsys
    )
    assert code == 0, err
    assert "bearing" in out and "pin |M|" in out and "approximation" in out
    assert target.stat().st_size > 1000
    assert "plotly" in target.read_text()


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--webs", "1,0,1"], "--webs"),
        (["--webs", "0,0,0,0,0,0,0,0"], "--webs"),
        (["--bearing", "0 mm", "--bearing", "10 mm"], "--bearing"),
        (["--bearing", "0 mm"], "--bearing"),
        (["--web-thickness", "50 mm"], "--web-thickness"),
        (["--viscosity", "0.01 Pa*s"], "--viscosity"),
        (["--no-gas", "--ignition", "-10 deg"], "--ignition"),
        (["--curves"], "--curves"),
        (["--samples", "10"], "--samples"),
        (["--bearing-stiffness", "-1 N/m"], "--bearing-stiffness"),
        (["--plot", "x.txt"], "--plot"),
        (["--clearance", "30 um"], "--clearance"),
        (["--clearance", "30 um", "--bearing-stiffness", "1e11 N/m"], "--bearing-stiffness"),
        (["--bearing-length", "20 mm"], "--bearing-length"),
    ],
)
def test_refusals(args: list[str], needle: str, capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli(["bearings", "inline4", *args], capsys)
    lines = err.strip().splitlines()
    assert code == 2, (code, out, err)
    assert len(lines) == 1 and lines[0].startswith("error: ") and needle in lines[0], err
    assert out == ""


def test_figure_overlays_studies() -> None:
    """One trace per bearing and study in the polar row, one per journal and study below;
    the labels name the studies."""
    pytest.importorskip("plotly")
    from crankbalance.errors import InputError
    from crankbalance.output.figures.loads import bearing_loads_figure
    from crankbalance.studies.loads import bearing_loads

    eight = bearing_loads("inline4", {"samples": 36, "gas": False})
    four = bearing_loads("inline4", {"samples": 36, "gas": False, "webs": [1, 0, 0, 1] * 2})
    fig = bearing_loads_figure([eight, four], "determinate", ("8 CW", "4 CW"))
    assert len(fig.data) == 2 * (5 + 5)
    assert {t.name for t in fig.data if t.showlegend} >= {"8 CW", "4 CW", "journal 3"}
    polar = [t for t in fig.data if t.name == "4 CW"]
    load = four.results["determinate"].load
    np.testing.assert_allclose(polar[2].y, load[2].real)  # z vertically
    np.testing.assert_allclose(polar[2].x, load[2].imag)  # x across
    with pytest.raises(InputError, match="labels"):
        bearing_loads_figure([eight, four], labels=("one",))
    with pytest.raises(InputError, match="model"):
        bearing_loads_figure(eight, "rigid")


def test_study_takes_a_balancing_result() -> None:
    """A balancing result given to the study is used as it is: the same numbers as the
    pattern given as an option; a pattern given twice is refused."""
    from crankbalance.errors import InputError
    from crankbalance.studies.engine import balance_engine
    from crankbalance.studies.loads import bearing_loads

    webs = [1, 0, 0, 1] * 2
    settings = {"samples": 36}
    # the study balances each half of a crank balanced as a whole, as scope = "halves"
    solved = balance_engine("inline4", webs=tuple(webs), scope="halves")
    given = bearing_loads("inline4", settings, balance=solved)
    typed = bearing_loads("inline4", {**settings, "webs": webs})
    for name in ("determinate", "indeterminate"):
        np.testing.assert_allclose(given.results[name].load, typed.results[name].load)
    with pytest.raises(InputError, match="webs"):
        bearing_loads("inline4", {**settings, "webs": webs}, balance=solved)
    with pytest.raises(InputError, match="balance"):
        bearing_loads("inline3", settings, balance=solved)


def test_clearance_in_the_contact_model(capsys: pytest.CaptureFixture[str]) -> None:
    """--clearance with --bearing-stiffness acts on the indeterminate crank only; with the
    Petroff inputs too it also sets the Petroff torque."""
    base = ["inline4", "--samples", "36", "--bearing-stiffness", "5e8 N/m"]
    elastic = _json(base, capsys)
    ring = _json([*base, "--clearance", "30 um"], capsys)
    assert ring["settings"]["clearance_in_contact_model"] is True
    assert elastic["settings"]["clearance_in_contact_model"] is False
    assert ring["models"]["determinate"] == elastic["models"]["determinate"]
    a = [b["mean_load_N"] for b in elastic["models"]["indeterminate"]["bearings"]]
    b = [b["mean_load_N"] for b in ring["models"]["indeterminate"]["bearings"]]
    assert not np.allclose(a, b, rtol=1e-3)
    both = _json(
        [*base, "--clearance", "30 um", "--viscosity", "0.01 Pa*s", "--bearing-length", "2 cm"],
        capsys,
    )
    assert both["models"]["indeterminate"]["bearings"][0]["petroff_friction_torque_Nm"] > 0
    assert (
        both["models"]["indeterminate"]["bearings"]
        != elastic["models"]["indeterminate"]["bearings"]
    )


@pytest.mark.parametrize("engine", ["w8", "w12-vw", "w16"])
@pytest.mark.parametrize("given", [False, True])
def test_w_engines_with_throws_sharing_a_plane(
    engine: str, given: bool, capsys: pytest.CaptureFixture[str]
) -> None:
    """W engines built from VR banks have two throws in every plane: one bearing bay per
    plane (default or given bearings), and the bearing loads carry the crank (their mean
    over the cycle of the sum is the loads', checked in the physics tests; here each
    model's loads are finite and every bearing between two planes is loaded)."""
    from crankbalance.physics.main_bearings import crank_planes
    from crankbalance.studies.engine import as_model

    planes = crank_planes(as_model(engine).throw_position)[0]
    pitch = float(np.diff(planes).min())
    bearings = np.concatenate([[planes[0] - pitch / 2], (planes[1:] + planes[:-1]) / 2])
    bearings = np.concatenate([bearings, [planes[-1] + pitch / 2]])
    extra = [a for b in bearings for a in ("--bearing", f"{b * 1000:.6f} mm")] if given else []
    data = _json([engine, "--samples", "72", *extra], capsys)
    np.testing.assert_allclose(data["bearing_position_m"], bearings, atol=1e-8)
    for name in ("determinate", "indeterminate"):
        loads = [b["mean_load_N"] for b in data["models"][name]["bearings"]]
        assert len(loads) == planes.size + 1 and min(loads) > 0
