"""Bearing loads against balance (``studies.balance_loads``, ``crankbalance
bearings-sweep``): a case is the single ``bearings`` run; the friction power is the sum of
the bearings'; the counterweights' share of the loads is the lever rule of their
centrifugal forces; the counterweight mass and the free first-order moment against closed
forms; refusals."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.physics import friction
from crankbalance.studies.balance_loads import bearing_sweep

from .conftest import run_cli

FOUR = "1,0,0,1,1,0,0,1"  # outer webs of each half: webs 1, 4, 5, 8
FAST = {"samples": 72}


def _cli(args: list[str], capsys: pytest.CaptureFixture[str]) -> dict:
    code, out, err = run_cli([*args, "--format", "json"], capsys)
    assert code == 0, err
    return json.loads(out)


def test_a_case_is_the_bearings_run(capsys: pytest.CaptureFixture[str]) -> None:
    """The sweep's case and ``crankbalance bearings`` with the same pattern, balance factor
    and settings give the same numbers for both crank models."""
    common = ["--samples", "72", "--bearing-stiffness", "5e8 N/m"]
    sweep = _cli(
        ["bearings-sweep", "inline4", "--pattern", FOUR, "--balance-factors", "0.5", *common],
        capsys,
    )
    single = _cli(
        ["bearings", "inline4", "--webs", FOUR, "--balance-factor", "0.5", *common], capsys
    )
    assert sweep["schema"] == "crankbalance.bearings-sweep/1"
    (case,) = sweep["cases"]
    assert case["pattern"] == FOUR and case["balance_factor"] == 0.5
    assert case["counterweight_mass_kg"] == pytest.approx(
        single["counterweights"]["total_mass_kg"], rel=1e-12
    )
    assert case["webs"] == single["counterweights"]["webs"]
    assert sweep["settings"] == single["settings"]
    for name in ("determinate", "indeterminate"):
        a, b = case["models"][name], single["models"][name]
        for key in ("largest_load_N", "largest_journal_moment_Nm", "largest_pin_moment_Nm"):
            assert a[key] == pytest.approx(b[key], rel=1e-12), key
        assert a["coulomb_friction_power_W"] == pytest.approx(
            b["coulomb_friction_power_W"], rel=1e-12
        )
        for x, y in zip(a["bearings"], b["bearings"], strict=True):
            for key in ("max_load_N", "mean_load_N", "max_journal_moment_Nm"):
                assert x[key] == pytest.approx(y[key], rel=1e-12), key
            assert x["coulomb_friction_power_W"] == pytest.approx(
                y["coulomb_friction_power_W"], rel=1e-12
            )
        worst = max(b["bearings"], key=lambda bearing: bearing["max_load_N"])
        assert a["largest_load_N"] == pytest.approx(worst["max_load_N"], rel=1e-12)


def test_friction_power_is_the_sum_of_the_bearings() -> None:
    """A case's friction power is the sum of the per-bearing friction of the bearing-load
    result, and each bearing's is mu mean|F| d/2 times the mean speed
    (friction.friction_torque at every angle, averaged)."""
    sweep = bearing_sweep(
        "v8-crossplane", {"patterns": ["all", "none"], "balance_factors": [0.4, 0.6]}, FAST
    )
    data = sweep.to_dict()
    assert len(sweep.cases) == 3  # none once
    for case, out in zip(sweep.cases, data["cases"], strict=True):
        study = case.study
        for name, r in study.results.items():
            fr = r.friction
            assert fr is not None
            m = out["models"][name]
            assert m["coulomb_friction_power_W"] == pytest.approx(
                float(fr.coulomb_power.sum()),
                rel=1e-10,  # JSON: 12 digits
            )
            torque = friction.friction_torque(
                study.options.friction_coefficient,
                np.abs(r.load),
                study.section.journal_diameter,
            ).mean(axis=1)
            np.testing.assert_allclose(
                [b["coulomb_friction_power_W"] for b in m["bearings"]],
                torque * study.cycle.speed_mean,
                rtol=1e-10,
            )


def test_counterweights_add_their_lever_rule_share() -> None:
    """The counterweights' share of the bearing loads of the determinate crank: the loads
    of a case less those of ``none`` are the lever rule of the counterweights' d'Alembert
    forces m r_cw (omega^2 - i alpha) e^{i(theta + psi)} between the two bearings either side
    of each web (worked here by hand); ``none`` has no counterweight mass."""
    sweep = bearing_sweep("inline4", {"patterns": [FOUR, "none"], "balance_factors": [0.5]}, FAST)
    four, none = sweep.cases
    assert none.pattern == "none" and none.balance_factor is None
    assert none.counterweight_mass == 0.0 and none.study.balance.counterweights is None
    assert four.counterweight_mass > 0
    cw = four.study.balance.counterweights
    cycle = four.study.cycle
    bearings = four.study.bearing_positions
    theta = cycle.crank_angle
    centrifugal = cycle.speed**2 - 1j * cycle.crank_acceleration
    expected = np.zeros((bearings.size, theta.size), complex)
    for m, y, psi in zip(cw.mass, cw.position, cw.direction, strict=True):
        force = m * cw.cg_radius * centrifugal * np.exp(1j * (theta + psi))
        right = int(np.searchsorted(bearings, y))
        left = right - 1
        share = (y - bearings[left]) / (bearings[right] - bearings[left])
        expected[left] += (1 - share) * force
        expected[right] += share * force
    got = four.study.results["determinate"].load - none.study.results["determinate"].load
    scale = np.abs(expected).max()
    assert scale > 100.0
    np.testing.assert_allclose(got, expected, atol=1e-9 * scale)


def test_counterweight_mass_of_every_web_closed_form() -> None:
    """inline4 preset, a counterweight on every web opposite its pin: each throw balances its
    own rotating mass and f_b of its reciprocating mass, so the total is
    4 (m_rot + f_b m_rec) r / r_cw; masses from the preset file (crankpin 280 g, webs
    2 x 700 g at 17 mm, rod 520 g with 0.67 rotating; piston 340 g, pin 110 g), r = r_cw =
    43 mm."""
    m_rot = 0.280 + 2 * 0.700 * 17 / 43 + 0.520 * 0.67
    m_rec = 0.340 + 0.110 + 0.520 * (1 - 0.67)
    factors = [0.0, 0.3, 1.0]
    sweep = bearing_sweep("inline4", {"patterns": ["all"], "balance_factors": factors}, FAST)
    for case, f in zip(sweep.cases, factors, strict=True):
        assert case.counterweight_mass == pytest.approx(4 * (m_rot + f * m_rec), rel=1e-9)


def test_v8_free_first_order_moment_vanishes_at_half() -> None:
    """Crossplane V8 (90 deg): the counterweights carry the rotating masses and f_b of the
    reciprocating ones; the first-order couple of the pistons is a rotating couple of half
    the reciprocating masses, so it is cancelled at f_b = 0.5 and grows as |f_b - 0.5|
    (Taylor (1985), vol. 2, the balance of vee engines)."""
    sweep = bearing_sweep(
        "v8-crossplane", {"patterns": ["all"], "balance_factors": [0.3, 0.4, 0.5, 0.6]}, FAST
    )
    moment = [c.free_forces()["order1_moment_Nm"] for c in sweep.cases]
    assert moment[0] > 1.0
    assert moment[2] < 1e-9 * moment[0]
    assert moment[1] == pytest.approx(moment[3], rel=1e-9)
    assert moment[0] == pytest.approx(2 * moment[1], rel=1e-9)
    # the free forces of a case are its balancing result's residuals
    for case in sweep.cases:
        c = case.study.balance.residual("order1")
        assert case.free_forces()["order1_force_N"] == c.force_after


def test_cli_table_csv_and_plot(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    args = [
        "bearings-sweep",
        "inline4",
        "--pattern",
        "all",
        "--pattern",
        FOUR,
        "--pattern",
        "none",
        "--balance-factors",
        "0:1:0.5",
        "--samples",
        "72",
    ]
    code, out, err = run_cli([*args, "--plot", str(tmp_path / "s.html")], capsys)
    assert code == 0, err
    assert "Inline-4" in out and "indeterminate crank" in out
    assert out.count("\nall ") == 3 and out.count("\nnone ") == 1
    html = (tmp_path / "s.html").read_text()
    assert "largest bearing load" in html and "bearing 5" in html
    assert "free first-order couple left" in html
    code, out, err = run_cli([*args, "--format", "csv", "--crank-model", "determinate"], capsys)
    assert code == 0, err
    lines = out.strip().splitlines()
    assert lines[0].startswith("pattern,balance_factor,counterweight_mass_kg,worst_bearing")
    assert len(lines) == 1 + 7
    assert lines[-1].startswith("none,,0.0,")


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--pattern", "1,0,1"], ["--pattern", "1,0,1", "8 entries"]),
        (["--pattern", "2,0,0,1,1,0,0,1"], ["--pattern", "0/1 per web"]),
        (["--pattern", "0,0,0,0,0,0,0,0"], ["--pattern", "write none"]),
        (["--pattern", "all", "--pattern", "ALL"], ["--pattern", "once"]),
        (["--balance-factors", "0.5,0.5"], ["--balance-factors", "once"]),
        (["--balance-factors", "0:3:0.5"], ["--balance-factors"]),
        (
            [
                "--pattern",
                "all",
                "--pattern",
                "file",
                "--pattern",
                FOUR,
                "--pattern",
                "0,1,1,0,0,1,1,0",
                "--balance-factors",
                "0:1:0.05",
            ],
            ["--pattern", "at most 64 cases", "84"],
        ),
        (["--webs", FOUR], ["--webs"]),
        (["--viscosity", "0.01 Pa*s"], ["--viscosity", "bearing length"]),
        (["--ignition", "-10 deg", "--no-gas"], ["--ignition", "Wiebe"]),
        (["--plot", "x.txt"], ["--plot"]),
    ],
)
def test_cli_refusals(
    args: list[str], words: list[str], capsys: pytest.CaptureFixture[str]
) -> None:
    code, out, err = run_cli(["bearings-sweep", "inline4", "--samples", "72", *args], capsys)
    assert code == 2, (out, err)
    assert err.startswith("error:") and "Traceback" not in err
    for word in words:
        assert word in err, (word, err)


def test_swept_settings_are_refused_in_the_loads_options() -> None:
    with pytest.raises(InputError, match="swept"):
        bearing_sweep("inline4", {"patterns": ["all"]}, {"balance_factor": 0.5})
    with pytest.raises(InputError, match="swept"):
        bearing_sweep("inline4", {"patterns": ["all"]}, {"webs": [1] * 8})


@pytest.mark.parametrize("preset", ["inline3", "v8-crossplane"])
def test_free_forces_left_are_the_analysis_plus_the_counterweights(preset: str) -> None:
    """What a case reports left (rotating masses, first order forward and backward, force
    and couple) agrees with a second method: the analysis's phasors
    (``studies.engine.analyze``) plus the centrifugal forces of the case's counterweights
    as built (mass, CG radius, direction, axial position; their share carrying the
    rotating masses to the rotating component, the rest to the first order), 1e-9."""
    from crankbalance.studies.engine import analyze

    sweep = bearing_sweep(
        preset,
        {
            "patterns": [
                "all",
                "none",
                "1,0,0,0,0,1" if preset == "inline3" else FOUR,
            ],
            "balance_factors": [0.0, 0.5, 0.8],
        },
        FAST,
    )
    for case in sweep.cases:
        m = case.study.model
        f = analyze(m).forces
        w2 = m.speed**2
        b = case.study.balance
        assert b.extra_counterweights is None and b.primary is None and b.secondary is None
        if b.counterweights is None:
            rot = bal = np.zeros(1, dtype=complex)
            y = np.zeros(1)
        else:
            cw = b.counterweights
            total = cw.mass * cw.cg_radius * np.exp(1j * cw.direction)
            assert b.rotating_share is not None
            rot, bal, y = b.rotating_share, total - b.rotating_share, cw.position
        expected = {
            "rotating_force_N": abs(f.rotating_force + w2 * rot.sum()),
            "rotating_moment_Nm": abs(f.rotating_couple + w2 * (y * rot).sum()),
            "order1_force_forward_N": abs(f.force_forward[0] + w2 * bal.sum()),
            "order1_force_backward_N": abs(f.force_backward[0]),
            "order1_moment_forward_Nm": abs(f.couple_forward[0] + w2 * (y * bal).sum()),
            "order1_moment_backward_Nm": abs(f.couple_backward[0]),
        }
        left = case.free_forces()
        scale = abs(f.rotating_force) + abs(f.force_forward[0]) + 1.0
        for key, value in expected.items():
            tol = 1e-9 * (scale if key.endswith("_N") else scale * 0.5)
            assert left[key] == pytest.approx(value, abs=max(tol, 1e-9 * value)), (case.label, key)
        # the sum the summary weighs: the rotating and first-order parts, no less than the
        # first-order force of everything together
        together = abs(f.rotating_force + f.force_forward[0] + w2 * (rot.sum() + bal.sum()))
        assert left["first_order_force_N"] >= together + abs(f.force_backward[0]) - 1e-9 * scale


def test_summary_weighs_the_free_forces_not_the_peak_load_alone(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """Inline-3: the crank without counterweights has the lowest peak bearing load but
    leaves its whole rotating and first-order couple; the summary suggests the pattern
    that leaves least (every web at 0.5, only the backward half of the primary couple),
    keeps the bare crank in the Pareto set and warns about it, in the JSON and the table
    alike (one text, the study's)."""
    sweep = bearing_sweep(
        "inline3", {"patterns": ["all", "none"], "balance_factors": [0.0, 0.5, 1.0]}, FAST
    )
    s = sweep.summary()
    labels = [c.label for c in sweep.cases]
    assert labels[s.lowest_load] == "no counterweights (none)"
    assert labels[s.suggested] == "all at balance factor 0.5"
    assert s.lowest_load in s.pareto and s.suggested in s.pareto
    assert labels.index("all at balance factor 1") not in s.pareto  # 0 has a lower load
    left = sweep.cases[s.suggested].free_forces()
    assert left["order1_moment_forward_Nm"] == 0.0 and left["order1_moment_backward_Nm"] > 800
    assert "no counterweights" in s.warning and "4879 N·m" in s.warning
    data = _cli(
        [
            "bearings-sweep",
            "inline3",
            "--pattern",
            "all",
            "--pattern",
            "none",
            "--balance-factors",
            "0,0.5,1",
            "--samples",
            "72",
        ],
        capsys,
    )
    assert data["summary"]["suggested"] == s.suggested
    assert data["summary"]["text"] == list(s.text)
    code, out, err = run_cli(
        [
            "bearings-sweep",
            "inline3",
            "--pattern",
            "all",
            "--pattern",
            "none",
            "--balance-factors",
            "0,0.5,1",
            "--samples",
            "72",
        ],
        capsys,
    )
    assert code == 0, err
    assert f"Warning: {s.warning}." in out and "M1- N·m" in out


def test_summary_of_an_engine_without_free_first_order() -> None:
    """Inline-4: no pattern leaves a free first-order force or couple, so the peak bearing
    load decides and nothing is warned."""
    sweep = bearing_sweep(
        "inline4", {"patterns": ["all", FOUR, "none"], "balance_factors": [0.25, 0.5]}, FAST
    )
    s = sweep.summary()
    assert s.suggested == s.lowest_load and s.warning == ""
    loads = [c.metrics("indeterminate")["largest_load_N"] for c in sweep.cases]
    assert loads[s.suggested] == min(loads)


def test_sweep_figure_groups_the_peak_bars_per_balance_factor() -> None:
    """The peak-load bars (issue 28, item 4): grouped per balance factor, the factor on the
    axis under its pattern, one bar per bearing named in the legend, its heights that
    bearing's peak in each case; the axes say what they are, with units."""
    pytest.importorskip("plotly")
    from crankbalance.output.figures.loads import bearing_sweep_figure

    sweep = bearing_sweep(
        "v8-crossplane", {"patterns": ["all", "none"], "balance_factors": [0.4, 0.6]}, FAST
    )
    fig = bearing_sweep_figure(sweep)
    bars = [t for t in fig.data if t.type == "bar"]
    data = sweep.to_dict()
    bearings = data["cases"][0]["models"]["indeterminate"]["bearings"]
    assert [b.name for b in bars] == [f"bearing {b['bearing']}" for b in bearings]
    assert all(b.showlegend is not False for b in bars)
    assert fig.layout.barmode == "group"
    for k, bar in enumerate(bars):
        assert [list(level) for level in bar.x] == [
            ["all", "all", "none"],
            ["f_b 0.4", "f_b 0.6", "no counterweights"],
        ]
        peaks = [c["models"]["indeterminate"]["bearings"][k]["max_load_N"] for c in data["cases"]]
        assert list(bar.y) == pytest.approx(peaks)
    n = bars[0].xaxis[1:]
    assert fig.layout[f"xaxis{n}"].title.text.startswith("balance factor f_b [-]")
    assert fig.layout[f"yaxis{n}"].title.text == "peak bearing load [N]"
    one = bearing_sweep_figure(
        bearing_sweep("v8-crossplane", {"patterns": ["all"], "balance_factors": [0.4, 0.6]}, FAST)
    )
    assert list(next(t for t in one.data if t.type == "bar").x) == ["f_b 0.4", "f_b 0.6"]


def test_summary_text_has_no_e_notation() -> None:
    """The single cylinder's bare crank leaves a free first-order force of about 10.7 kN:
    the warning says 10712 N (the output vocabulary), not 1.071e+04 N."""
    sweep = bearing_sweep("single", {"balance_factors": [0.0, 0.5, 1.0]}, FAST)
    s = sweep.summary()
    assert s.warning and "first-order force of 10712 N" in s.warning
    assert not any("e+" in line for line in s.text)


def test_sweep_figure_says_a_flat_zero_and_heads_the_lines_apart() -> None:
    """The inline-4 has no first-order force or couple left: those panels say "0 ...
    everywhere" (issue 28 review, finding 15); the pattern's line entry ("all") stands under
    its own legend heading, apart from the bearings' "peak load of"."""
    pytest.importorskip("plotly")
    from crankbalance.output.figures.loads import PATTERN_HEADING, bearing_sweep_figure

    fig = bearing_sweep_figure(
        bearing_sweep("inline4", {"patterns": ["all"], "balance_factors": [0.0, 0.5]}, FAST)
    )
    notes = [(a.text, a.xref) for a in fig.layout.annotations if "everywhere" in a.text]
    assert notes == [
        ("0 N everywhere<br>(balanced)", "x5 domain"),
        ("0 N·m everywhere<br>(balanced)", "x6 domain"),
    ]
    shown = [t for t in fig.data if t.showlegend is not False]
    assert [(t.name, t.legendgrouptitle.text) for t in shown[:2]] == [
        ("all", PATTERN_HEADING),
        ("bearing 1", "peak load of"),
    ]


def test_sweep_figure_panel_titles_are_one_line() -> None:
    """Stacked on a phone, a two-line panel title ran into the x-axis title of the panel
    above (the couple's "balance factor" into "peak load of each main bearing", issue 28
    review, finding 19): every panel title is one line."""
    pytest.importorskip("plotly")
    from crankbalance.output.figures.loads import SWEEP_PANELS, bearing_sweep_figure

    fig = bearing_sweep_figure(
        bearing_sweep("inline4", {"patterns": ["all"], "balance_factors": [0.5]}, FAST)
    )
    titles = [a.text for a in fig.layout.annotations if a.yref == "paper"]
    assert titles == [t for _, t in SWEEP_PANELS] + ["peak load of each main bearing"]
    assert "indeterminate crank" in fig.layout.title.text  # the crank model, said once
