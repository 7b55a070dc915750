"""Bounded command-line options (issue 12): NaN and infinities refused, values checked after
unit conversion against a physical range, counts and seeds range-checked, options that would
be ignored refused, results checked finite before they are printed, missing extras named.

Every refusal ends in exit status 2 with exactly one line on stderr naming the option as it
was typed, and nothing on stdout.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import pytest

from crankbalance.errors import InputError, ResultError, check_range
from crankbalance.results import require_finite, to_jsonable
from crankbalance.schema.settings import (
    RANGES,
    BenchOptions,
    CycleOptions,
    allowed,
    parse_options,
)

from .conftest import EXAMPLES, run_cli

SHAFT = ["--length", "300 mm", "--diameter", "25 mm"]
CHECK = [
    "shaft",
    "check",
    *SHAFT,
    "--bearing",
    "0 mm",
    "--bearing",
    "300 mm",
    "--mass",
    "150 mm",
    "--unbalance",
    "3 g*m",
    "--speed",
    "3000 rpm",
]
FRICTION = ["friction", "--journal-diameter", "20 mm", "--rotating-load", "42.2 N"]
CRF = ["--reciprocating-mass", "282.12 g", "--crank-radius", "26.9 mm"]
OPTIMIZE = ["counterweight", "optimize", "--first-moment", "7880 g*mm", "--quiet"]


#: a counterweight profile given by its requirement and shape (counterweight export)
PROFILE = [
    "--first-moment",
    "7880 g*mm",
    "--web-radius",
    "20 mm",
    "--rectangle-height",
    "20 mm",
    "--trapezoid-angle",
    "20 deg",
    "--segment-radius",
    "50 mm",
    "--segment-angle",
    "120 deg",
]


def refused(args: list[str], needle: str, capsys: pytest.CaptureFixture[str]) -> str:
    """Run the CLI; assert exit 2, one line on stderr that names ``needle``, no output."""
    code, out, err = run_cli(args, capsys)
    lines = err.splitlines()
    assert code == 2, (code, out, err)
    assert len(lines) == 1 and lines[0].startswith("error: "), err
    assert needle in lines[0], lines[0]
    assert out == ""
    return lines[0]


# ------------------------------------------------------------------------------------------
# the examples of the issue
# ------------------------------------------------------------------------------------------

ISSUE_EXAMPLES = [
    # exit 0 with NaN or Infinity before
    (
        [*FRICTION, "--friction-coefficient", "1e308", "--format", "json"],
        "--friction-coefficient",
    ),
    (["sensitivity", "--rod-length", "5 parsec"], "--rod-length"),
    (["cycle", "--bore", "1e-320 mm"], "--bore"),
    # tracebacks before
    (["balance", "inline4", "--balance-factor", "nan"], "--balance-factor"),
    ([*CHECK, "--bearing-stiffness", "1e308 N/m"], "--bearing-stiffness"),
    (["bench", "--friction-coefficient", "0.1", "--ramp-time", "1e308 s"], "--ramp-time"),
    ([*OPTIMIZE, "--seed", "-1", "--iterations", "1", "--population", "16"], "--seed"),
    # ran on and on before
    (["bench", "--friction-coefficient", "0.1", "--hold-time", "1e9 s"], "--hold-time"),
    # silently accepted before
    (["balance-factor", *CRF, "--cylinder", "99"], "--cylinder"),
]


@pytest.mark.parametrize(
    "args,needle", ISSUE_EXAMPLES, ids=[" ".join(a) for a, _ in ISSUE_EXAMPLES]
)
def test_issue_examples_are_refused(
    args: list[str], needle: str, capsys: pytest.CaptureFixture[str]
) -> None:
    refused(args, needle, capsys)


def test_rebalance_parts_directory_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    refused(["rebalance", "--parts", str(tmp_path)], "folder", capsys)


def test_bench_hold_time_is_capped_by_revolutions(capsys: pytest.CaptureFixture[str]) -> None:
    """Within the 600 s cap, a long hold at a high speed is refused by the revolution cap."""
    line = refused(
        ["bench", "--friction-coefficient", "0.1", "--hold-time", "500 s"], "--hold-time", capsys
    )
    assert "revolutions" in line


# ------------------------------------------------------------------------------------------
# NaN, infinities, huge and tiny values of every kind of option
# ------------------------------------------------------------------------------------------

NON_FINITE = [
    (["analyze", "inline4", "--orders", "nan"], "--orders"),
    (["analyze", "inline4", "--orders", "1e400"], "--orders"),
    (["analyze", "inline4", "--orders", "9" * 400], "--orders"),
    (["balance", "inline4", "--balance-factor", "inf"], "--balance-factor"),
    (["balance", "inline4", "--angle", "1e308 deg"], "--angle"),
    ([*FRICTION, "--friction-coefficient", "nan"], "--friction-coefficient"),
    ([*FRICTION, "--friction-coefficient", "-inf"], "--friction-coefficient"),
    (["friction", "--journal-diameter", "1e308 km", "--friction-coefficient", "0.1"], "--journal"),
    (["bench", "--friction-coefficient", "0.1", "--kp", "nan"], "--kp"),
    (["bench", "--friction-coefficient", "0.1", "--ki", "inf"], "--ki"),
    (["bench", "--friction-coefficient", "0.1", "--speed", "1e9 rpm"], "--speed"),
    (["cycle", "--compression-ratio", "nan"], "--compression-ratio"),
    (["cycle", "--speed", "1e-300 rpm"], "--speed"),
    (["cycle", "--balance-factor", "nan"], "--balance-factor"),
    (["sensitivity", "--balance-factors", "0:inf:1"], "--balance-factors"),
    (["sensitivity", "--balance-factors", "0,nan"], "--balance-factors"),
    (["sensitivity", "--mass-scales", "1e308"], "--mass-scales"),
    ([*CHECK, "--margin", "inf"], "--margin"),
    ([*CHECK, "--poisson", "nan"], "--poisson"),
    ([*CHECK, "--max-speed", "1e308 rpm"], "--max-speed"),
    (["shaft", "inline4", *SHAFT, "--unbalance", "3 g*m", "--speed", "1e308 rpm"], "--speed"),
    (["shaft", "inline4", *SHAFT, "--unbalance", "1e-300 g*mm", "--speed", "1 rpm"], "--unb"),
    (
        ["shaft", "inline3", *SHAFT, "--unbalance", "3 g*m", "--speed", "1 rpm", "--z-min", "nan"],
        "--z-min",
    ),
    (["balance-factor", *CRF, "--target", "inf"], "--target"),
    (["balance-factor", *CRF, "--speed", "1e308 rpm"], "--speed"),
    (["tolerance", "--grade", "G6.3", "--rotor-mass", "1e308 kg", "--speed", "1 rpm"], "--rotor"),
    ([*OPTIMIZE, "--min-balance", "nan"], "--min-balance"),
    ([*OPTIMIZE, "--web-radius", "1e308 km"], "--web-radius"),
    (["plot", "single", "inline4", "--balance-factor", "nan", "-o", "x.html"], "--balance-factor"),
    (["report", "inline4", "--balance-factor", "nan", "-o", "x.html"], "--balance-factor"),
]


@pytest.mark.parametrize("args,needle", NON_FINITE, ids=[" ".join(a) for a, _ in NON_FINITE])
def test_non_finite_and_out_of_range_options(
    args: list[str],
    needle: str,
    capsys: pytest.CaptureFixture[str],
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.chdir(tmp_path)  # plot/report would write x.html here
    refused(args, needle, capsys)
    assert not (tmp_path / "x.html").exists()


# ------------------------------------------------------------------------------------------
# seeds, counts and indices
# ------------------------------------------------------------------------------------------

COUNTS = [
    ([*OPTIMIZE, "--seed", str(2**32)], "--seed"),
    ([*OPTIMIZE, "--seed", "1.5"], "--seed"),
    ([*OPTIMIZE, "--population", "15"], "--population"),
    ([*OPTIMIZE, "--iterations", "1001"], "--iterations"),
    (["shaft", "inline4", *SHAFT, "--engine", "inline4", "--points", "2"], "--points"),
    (["shaft", "inline4", *SHAFT, "--engine", "inline4", "--weights", ",".join("1" * 22)], "--we"),
    ([*CHECK, *(["--bearing", "1 mm"] * 63)], "--bearing"),
    (["cycle", "--engine", "single", "--cylinder", "0"], "--cylinder"),
    (["cycle", "--engine", "single", "--cylinder", "2"], "--cylinder"),
    (["balance-factor", "--engine", "inline4", "--cylinder", "5"], "--cylinder"),
    (["plot", "single", "inline4", "--cylinder", "-1", "-o", "x.html"], "--cylinder"),
    (["plot", "polar", "inline4", "--order", "65", "-o", "x.html"], "--order"),
    (["bench", "--friction-coefficient", "0.1", *(["--speed", "100 rpm"] * 11)], "--speed"),
    (["sensitivity", "--balance-factors", "0:2:0.05"], "--balance-factors"),
]


@pytest.mark.parametrize("args,needle", COUNTS, ids=[" ".join(a)[:60] for a, _ in COUNTS])
def test_counts_seeds_and_indices(
    args: list[str],
    needle: str,
    capsys: pytest.CaptureFixture[str],
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.chdir(tmp_path)
    refused(args, needle, capsys)


def test_bench_controller_and_solver_work_are_bounded(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """A controller far faster than the rotor is refused before the run; what a stiff rotor
    still needs is stopped by the evaluation budget of the solver."""
    refused(["bench", "--friction-coefficient", "0.1", "--kp", "1e4"], "--kp", capsys)
    refused(["bench", "--friction-coefficient", "0.1", "--ki", "1e6"], "--ki", capsys)
    from crankbalance.physics import rotor_bench

    monkeypatch.setattr(rotor_bench, "MAX_BENCH_EVALUATIONS", 200)
    refused(["bench", "--friction-coefficient", "0.1"], "evaluations", capsys)


# ------------------------------------------------------------------------------------------
# an option that would be ignored is refused
# ------------------------------------------------------------------------------------------

IGNORED = [
    (["balance-factor", *CRF, "--cylinder", "2"], "--cylinder"),
    (
        [
            "balance-factor",
            *CRF,
            "--speed",
            "100 rpm",
            "--kinematics",
            "first-order",
            "--rod-length",
            "100 mm",
        ],
        "--rod-length",
    ),
    (["cycle", "--cylinder", "2"], "--cylinder"),
    (["sensitivity", "--cylinder", "1"], "--cylinder"),
    (["cycle", "--pressure-csv", "PRESSURE", "--ignition", "-20 deg"], "--ignition"),
    (["cycle", "--pressure-csv", "PRESSURE", "--compression-ratio", "10"], "--compression"),
    (["balance", "inline4", "--method", "individual", "--angle", "10 deg"], "--angle"),
    (["tolerance", "--list", "--grade", "G6.3"], "--grade"),
    (["tolerance", "--list", "--plane-1", "10 mm"], "--plane-1"),
    (["report", "inline4", "-o", "x.html", "--chromium", "/usr/bin/chromium"], "--chromium"),
    (["rebalance", "--parts", "PARTS", "--tolerance", "5 g*mm", "--grade", "G2.5"], "--tol"),
    ([*FRICTION, "--friction-coefficient", "0.1", "--clearance", "20 um"], "--clearance"),
    ([*FRICTION, "--friction-coefficient", "0.1", "--speed", "100 rpm"], "--speed"),
    (
        [
            "counterweight",
            "export",
            *PROFILE,
            "--thickness",
            "5 mm",
            "-o",
            "x.svg",
        ],
        "--first-moment",
    ),
]


@pytest.mark.parametrize("args,needle", IGNORED, ids=[" ".join(a)[:60] for a, _ in IGNORED])
def test_ignored_options_are_refused(
    args: list[str],
    needle: str,
    capsys: pytest.CaptureFixture[str],
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.chdir(tmp_path)
    table = tmp_path / "p.csv"
    table.write_text(
        "angle_deg,pressure_bar\n" + "\n".join(f"{a},{1 + (a == 0)}" for a in range(-360, 360, 10))
    )
    names = {"PRESSURE": str(table), "PARTS": str(EXAMPLES / "crf250r_rebalance.toml")}
    refused([names.get(a, a) for a in args], needle, capsys)


def test_empty_option_is_not_ignored(capsys: pytest.CaptureFixture[str]) -> None:
    """An empty text is refused, not taken for "not given"."""
    refused(
        ["rebalance", "--parts", str(EXAMPLES / "crf250r_rebalance.toml"), "--crank-radius", ""],
        "--crank-radius",
        capsys,
    )
    refused(["cycle", "--bore", ""], "--bore", capsys)


# ------------------------------------------------------------------------------------------
# every result is checked finite before it is printed
# ------------------------------------------------------------------------------------------


def test_check_range_refuses_nan_and_infinities_with_infinite_bounds() -> None:
    for value in (math.nan, math.inf, -math.inf):
        with pytest.raises(InputError):
            check_range("x", value, -math.inf, math.inf)
    assert check_range("x", 1e300, -math.inf, math.inf) == 1e300


def test_to_jsonable_names_the_quantity_that_is_not_finite() -> None:
    with pytest.raises(ResultError) as info:
        to_jsonable({"summary": {"torque_Nm": [1.0, math.nan]}})
    assert info.value.quantity == "summary.torque_Nm[1]"
    assert "summary.torque_Nm[1]" in str(info.value)
    with pytest.raises(ResultError, match=r"re"):
        require_finite([complex(math.inf, 0.0)])
    require_finite({"a": [1.0, 2], "b": None, "c": "text", "d": True})


@pytest.mark.parametrize("fmt", ["table", "json", "csv"])
def test_a_non_finite_result_is_one_line_not_output(
    fmt: str, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """A physics result that is not finite (simulated here) gives one honest line naming the
    quantity, exit 2, and no output in any format."""
    from crankbalance.physics import friction

    monkeypatch.setattr(friction, "friction_torque", lambda *args: math.nan)
    line = refused([*FRICTION, "--friction-coefficient", "0.1", "--format", fmt], "torque", capsys)
    assert "coulomb[0].torque_Nm" in line and "not a finite number" in line


def test_valid_options_still_give_finite_results(capsys: pytest.CaptureFixture[str]) -> None:
    """The limits keep the documented examples: the thesis' friction case and the extremes
    of a range."""
    code, out, err = run_cli(
        [*FRICTION, "--load", "25 N", "--friction-coefficient", "1", "--format", "json"], capsys
    )
    assert code == 0, err
    data = json.loads(out)
    assert data["coulomb"][0]["torque_Nm"] > 0
    code, out, err = run_cli(
        [*CHECK, "--bearing-stiffness", "1e12 N/m", "--format", "json"], capsys
    )
    assert code == 0, err
    assert "NaN" not in out and "Infinity" not in out


# ------------------------------------------------------------------------------------------
# the limits are in one place and read in words
# ------------------------------------------------------------------------------------------


def test_limits_apply_after_unit_conversion() -> None:
    low, high = RANGES["length"]
    assert parse_options(CycleOptions, {"bore": f"{high * 1e3} mm"}).bore == pytest.approx(high)
    for text in (f"{high * 1.01} m", f"{low / 2} m", "1e308 km", "5 parsec"):
        with pytest.raises(InputError, match="from 0.001 mm to 100000 mm"):
            parse_options(CycleOptions, {"bore": text})


def test_allowed_reads_the_schema() -> None:
    assert (
        allowed(BenchOptions, "hold_time")
        == "a time with a unit, e.g. '2 s', from 0.001 s to 600 s"
    )
    assert allowed(BenchOptions, "kp") == "a number, greater than 0 and at most 10000"
    assert allowed(BenchOptions, "speed").startswith("1 to 10 values, each a speed")


# ------------------------------------------------------------------------------------------
# a missing extra is named in one line
# ------------------------------------------------------------------------------------------

EXTRAS = [
    (["plot", "orders", "inline4", "-o", "x.html"], "plotly", "web"),
    (["plot", "orders", "inline4", "-o", "x.png"], "kaleido", "web"),
    (["report", "inline4", "-o", "x.html"], "plotly", "web"),
    (["report", "inline4", "-o", "x.pdf"], "kaleido", "web"),
    (["web", "--port", "8999"], "nicegui", "web"),
    (["counterweight", "check", "PART"], "trimesh", "geometry"),
    (["counterweight", "check", "PART.step"], "build123d", "cad"),
    (
        [
            "counterweight",
            "export",
            *PROFILE,
            "-o",
            "x.step",
        ],
        "build123d",
        "cad",
    ),
]


@pytest.mark.parametrize(
    "args,module,extra", EXTRAS, ids=[" ".join(a[:3]) + f" {m}" for a, m, _ in EXTRAS]
)
def test_missing_extra_is_one_line(
    args: list[str],
    module: str,
    extra: str,
    capsys: pytest.CaptureFixture[str],
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The module is made unimportable (``sys.modules[name] = None``), as when the extra is
    not installed: one line names the extra to install, exit 2, nothing written."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setitem(sys.modules, module, None)
    part = tmp_path / "part.stl"
    part.write_bytes(b"")
    args = [
        str(part) if a == "PART" else str(tmp_path / "part.step") if a == "PART.step" else a
        for a in args
    ]
    line = refused(args, f"pip install 'crankbalance[{extra}]'", capsys)
    assert module in line
    assert sorted(p.name for p in tmp_path.iterdir()) == ["part.stl"]


# ------------------------------------------------------------------------------------------
# found by the fuzzing suite (tests/fuzz/test_fuzz_options.py); warnings are errors here
# ------------------------------------------------------------------------------------------

FOUND = [
    (["bench", "--friction-coefficient", "0.1", "--unbalance", "1e11 g*mm"], "--unbalance"),
    ([*OPTIMIZE, "--min-balance", "1e-320"], "--min-balance"),
    (
        [
            "shaft",
            "inline3",
            "--length",
            "0.001 mm",
            "--diameter",
            "25 mm",
            "--unbalance",
            "3 g*m",
            "--speed",
            "6000 rpm",
        ],
        "--length",
    ),
    (
        [
            "rebalance",
            "--parts",
            str(EXAMPLES / "crf250r_rebalance.toml"),
            "--depth-resolution",
            "1e-320 mm",
        ],
        "--depth-resolution",
    ),
    (
        ["rebalance", "--parts", str(EXAMPLES / "crf250r_rebalance.toml"), "--speed", "1e308 rpm"],
        "--speed",
    ),
    (
        ["friction", "--journal-diameter", "0.001 mm", "--load", "1e-300 N", "--torque", "1e7 N*m"],
        "--torque",
    ),
]


@pytest.mark.parametrize("args,needle", FOUND, ids=[" ".join(a)[:60] for a, _ in FOUND])
def test_found_by_the_fuzz(
    args: list[str], needle: str, capsys: pytest.CaptureFixture[str]
) -> None:
    refused(args, needle, capsys)


def test_extremes_inside_the_ranges_compute(capsys: pytest.CaptureFixture[str]) -> None:
    """Values at the ends of the documented ranges give finite results (no warning either:
    warnings are errors in the tests)."""
    calls = [
        [*FRICTION[:3], "--rotating-load", "1e-320 N", "--friction-coefficient", "0.1"],
        [*FRICTION[:3], "--load", "1e9 N", "--rotating-load", "1e9 N", "--torque", "1e7 N*m"],
        [
            "shaft",
            "check",
            "--length",
            "100000 mm",
            "--diameter",
            "0.001 mm",
            "--bearing",
            "0 mm",
            "--bearing",
            "100000 mm",
            "--mass",
            "50000 mm",
            "--unbalance",
            "1e11 g*mm",
            "--speed",
            "100000 rpm",
            "--format",
            "json",
        ],
        ["cycle", "--stroke", "0.001 mm", "--rod-length", "100000 mm", "--bore", "0.001 mm"],
    ]
    for args in calls:
        code, out, err = run_cli(args, capsys)
        assert code == 0, (args, err)
        assert "nan" not in out.lower() and "inf" not in out.lower().replace("info", "")


def test_the_inertia_objective_has_its_own_budget(capsys: pytest.CaptureFixture[str]) -> None:
    """With the inertia as a third objective the optimiser's work grows faster than its
    designs (the three-objective front is far larger): its budget is smaller, and the
    message says which budget was exceeded."""
    from crankbalance.schema.settings import MAX_THREE_OBJECTIVE_DESIGNS, CounterweightOptions

    args = ["counterweight", "optimize", "--engine", "paper-inline3", "--quiet"]
    code, _, err = run_cli([*args, "--iterations", "60", "--inertia"], capsys)
    assert code == 2
    assert err.strip() == (
        "error: --iterations = '60': must keep population + iterations x 4096 at most "
        f"{MAX_THREE_OBJECTIVE_DESIGNS:,} designs, the optimiser's work budget with 3 "
        "objectives (here 4,096 + 60 x 4096 = 249,856): lower the iterations or the population"
    )
    settings = CounterweightOptions.parse({"iterations": 60})  # two objectives: fine
    assert settings.iterations == 60
