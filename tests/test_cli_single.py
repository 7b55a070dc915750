"""CLI tests of balance-factor, rebalance and tolerance (in-process)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from crankbalance.cli import main

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "crf250r_rebalance.toml"
CRF = ["--reciprocating-mass", "282.12 g", "--crank-radius", "26.9 mm"]


def run(capsys, args: list[str]) -> tuple[int, str, str]:
    try:
        main(args)
        code = 0
    except SystemExit as exit_:
        code = int(exit_.code or 0)
    out, err = capsys.readouterr()
    return code, out, err


def test_balance_factor_json(capsys) -> None:
    code, out, _ = run(
        capsys,
        [
            "balance-factor",
            *CRF,
            "--rotating-mass",
            "282.69 g",
            "--cw-mass",
            "2020.40 g",
            "--cw-radius",
            "6.16 mm",
            "--speed",
            "15200 rpm",
            "--kinematics",
            "first-order",
            "--target",
            "28%",
            "--format",
            "json",
        ],
    )
    assert code == 0
    data = json.loads(out)
    assert data["schema"] == "crankbalance.balance_factor/2"
    assert data["mass_properties"]["balance_factor"] == pytest.approx(0.6379, abs=1e-4)
    assert data["bob_weight"]["mass_kg"] == pytest.approx(0.28269 + 0.28 * 0.28212)
    study = data["study"]
    p = study["primary_force_N"]
    fb = data["balance_factor"]
    assert study["peak_resultant_N"] == pytest.approx(max(fb, 1 - fb) * p, rel=1e-9)
    assert study["optimum_balance_factor"] == pytest.approx(0.5, abs=1e-6)


def test_balance_factor_table(capsys) -> None:
    code, out, _ = run(
        capsys,
        [
            "balance-factor",
            *CRF,
            "--speed",
            "9000 rpm",
            "--rod-length",
            "105 mm",
            "--balance-factor",
            "0.5",
        ],
    )
    assert code == 0 and "peak resultant" in out and "exact" in out
    assert "on top of 100 % of the rotating mass" in out


@pytest.mark.parametrize(
    "args, field",
    [
        (["balance-factor", *CRF, "--balance-factor", "2.5"], "--balance-factor"),
        (["balance-factor", *CRF, "--balance-factor", "-10%"], "--balance-factor"),
        (
            [
                "balance-factor",
                "--reciprocating-mass",
                "-282 g",
                "--crank-radius",
                "26.9 mm",
                "--speed",
                "1000 rpm",
            ],
            "--reciprocating-mass",
        ),
        (
            [
                "balance-factor",
                "--reciprocating-mass",
                "282 g",
                "--crank-radius",
                "0 mm",
                "--speed",
                "1000 rpm",
            ],
            "--crank-radius",
        ),
        (["balance-factor", *CRF, "--cw-mass", "2 kg"], "--cw-mass"),
        (["tolerance", "--grade", "G7", "--rotor-mass", "2.7 kg", "--speed", "15200 rpm"], "grade"),
        (
            ["tolerance", "--grade", "G6.3", "--rotor-mass", "2.7", "--speed", "15200 rpm"],
            "--rotor-mass",
        ),
        (["rebalance", "--parts", str(EXAMPLE), "--target", "250%"], "target"),
        (
            ["rebalance", "--parts", str(EXAMPLE), "--new-rotating-mass", "-3 g"],
            "--new-rotating-mass",
        ),
        (["rebalance", "--parts", "no/such/file.toml"], "parts"),
        # checked even without --speed (no force study): was silently accepted
        (
            ["balance-factor", "--reciprocating-mass", "-282 g", "--crank-radius", "26.9 mm"],
            "--reciprocating-mass",
        ),
        (
            ["balance-factor", "--reciprocating-mass", "282 g", "--crank-radius", "0 mm"],
            "--crank-radius",
        ),
        # options that would be ignored
        (["balance-factor", *CRF, "--speed", "1000 rpm", "--offset", "5 mm"], "offset"),
        (["balance-factor", *CRF, "--rod-length", "105 mm"], "--rod-length"),
        (["balance-factor", *CRF, "--target", "0.3"], "target"),
        (["rebalance", "--parts", str(EXAMPLE), "--hole-diameter", "8 mm"], "--hole-diameter"),
        # the option at fault is named, not a derived quantity
        (["balance-factor", *CRF, "--rotating-mass", "282 g", "--target", "5"], "target"),
        (
            [
                "balance-factor",
                *CRF,
                "--rotating-mass",
                "280 g",
                "--cw-mass",
                "0.1 kg",
                "--cw-radius",
                "6 mm",
            ],
            "--cw-mass",
        ),
        (["rebalance", "--parts", str(EXAMPLE), "--cw-mass", "1 kg"], "too light"),
    ],
)
def test_bad_input_exit_2(capsys, args: list[str], field: str) -> None:
    code, _, err = run(capsys, args)
    assert code == 2
    assert err.startswith("error: ") and field in err
    assert "Traceback" not in err


def test_rebalance_table_and_override(capsys) -> None:
    code, out, _ = run(
        capsys, ["rebalance", "--parts", str(EXAMPLE), "--target", "0.5", "--tolerance", "5 g*mm"]
    )
    assert code == 0
    assert "target f_b = 0.5000" in out and "PASS" in out and "5 g·mm" in out


def test_rebalance_options_only_holes(capsys) -> None:
    code, out, _ = run(
        capsys,
        [
            "rebalance",
            "--crank-radius",
            "26.9 mm",
            "--cw-mass",
            "2020.40 g",
            "--cw-radius",
            "6.16 mm",
            "--old-rotating-mass",
            "282.69 g",
            "--old-reciprocating-mass",
            "282.12 g",
            "--new-rotating-mass",
            "248.69 g",
            "--new-reciprocating-mass",
            "261.50 g",
            "--target",
            "factory",
            "--method",
            "holes",
            "--hole-diameter",
            "8 mm",
            "--holes",
            "2",
            "--correction-radius",
            "38 mm",
            "--hole-direction",
            "axial",
            "--grade",
            "G6.3",
            "--rotor-mass",
            "2.7 kg",
            "--speed",
            "15200 rpm",
            "--format",
            "json",
        ],
    )
    assert code == 0
    case = json.loads(out)["cases"][0]
    assert case["passed"] and case["correction"]["kind"] == "holes"


def test_rebalance_unknown_key(tmp_path, capsys) -> None:
    text = EXAMPLE.read_text().replace("[counterweight]", "colour = 'red'\n[counterweight]")
    path = tmp_path / "bad.toml"
    path.write_text(text)
    code, _, err = run(capsys, ["rebalance", "--parts", str(path)])
    assert code == 2 and "colour" in err


def test_tolerance_json_and_list(capsys) -> None:
    code, out, _ = run(
        capsys,
        [
            "tolerance",
            "--grade",
            "G6.3",
            "--rotor-mass",
            "2.7 kg",
            "--speed",
            "15200 rpm",
            "--residual",
            "7.39 g*mm",
            "--bearing-a",
            "0 mm",
            "--bearing-b",
            "120 mm",
            "--center-of-mass",
            "60 mm",
            "--format",
            "json",
        ],
    )
    assert code == 0
    data = json.loads(out)
    assert data["schema"] == "crankbalance.tolerance/2"
    assert data["permissible_unbalance_kg_m"] * 1e6 == pytest.approx(10.69, abs=0.01)
    assert data["verdict"]["passed"] is True
    assert data["planes"]["plane_1_kg_m"] * 1e6 == pytest.approx(10.686 / 2, abs=0.01)
    code, out, _ = run(capsys, ["tolerance", "--list"])
    assert code == 0 and "G 4000" in out and "G 0.4" in out


def test_balance_factor_from_engine_preset(capsys) -> None:
    code, out, _ = run(capsys, ["balance-factor", "--engine", "single", "--format", "json"])
    assert code == 0
    data = json.loads(out)
    # the preset's masses: piston 230 g + pin 60 g + 30 % of the 330 g conrod
    assert data["reciprocating_mass_kg"] == pytest.approx(0.230 + 0.060 + 0.3 * 0.330)
    assert data["study"]["speed_rad_s"] == pytest.approx(9000 * 3.141592653589793 / 30)
    code, _, err = run(capsys, ["balance-factor", "--engine", "single", "--cylinder", "2"])
    assert code == 2 and "cylinder" in err


def test_rebalance_method_option_replaces_the_files_correction(capsys) -> None:
    """--method holes on a file with a face correction drops the file's face keys."""
    code, out, err = run(
        capsys,
        [
            "rebalance",
            "--parts",
            str(EXAMPLE),
            "--method",
            "holes",
            "--hole-diameter",
            "8 mm",
            "--holes",
            "2",
            "--format",
            "json",
        ],
    )
    assert code == 0, err
    cases = json.loads(out)["cases"]
    assert all(case["correction"]["kind"] == "holes" and case["passed"] for case in cases)


@pytest.mark.parametrize(
    "edit, field",
    [
        (('crankpin = "114.65 g"', 'crankpin = "114.65 N"'), "old.rotating.crankpin"),
        (("area = ", "areas = "), "correction.areas"),
        (('targets = [0.28, "factory"]', 'targets = [0.28, "fact"]'), "targets[1]"),
        (('grade = "G6.3"', 'grade = "G6.3"\nunbalance = "5 g*mm"'), "tolerance.grade"),
        (('mass = "2020.40 g"', 'mass = "0 g"'), "counterweight.mass"),
    ],
)
def test_rebalance_file_errors_name_the_key(tmp_path, capsys, edit, field) -> None:
    text = EXAMPLE.read_text(encoding="utf-8")
    assert edit[0] in text
    path = tmp_path / "parts.toml"
    path.write_text(text.replace(edit[0], edit[1], 1), encoding="utf-8")
    code, _, err = run(capsys, ["rebalance", "--parts", str(path)])
    assert code == 2 and err.startswith(f"error: {field} = "), err


def test_rebalance_file_bounded_read(tmp_path, capsys) -> None:
    big = tmp_path / "big.toml"
    big.write_text("#" * 1_000_001)
    binary = tmp_path / "binary.toml"
    binary.write_bytes(b"\xff\xfe\x00name")
    for path, words in ((big, "larger than"), (binary, "UTF-8"), (tmp_path, "folder")):
        code, _, err = run(capsys, ["rebalance", "--parts", str(path)])
        assert code == 2 and err.startswith("error: --parts = ") and words in err, err


def test_rebalance_file_and_api_agree() -> None:
    from crankbalance.io.rebalance_file import load_rebalance_file
    from crankbalance.studies.rebalance import rebalance_parts

    study = rebalance_parts(load_rebalance_file(EXAMPLE))
    assert [case.target_balance_factor for case in study.cases][0] == 0.28
    assert study.tolerance_source == "ISO 21940-11 G 6.3, 2.7 kg, 15200 rpm"
    assert study.old.rotating_mass == pytest.approx(0.28269)


#: the example's crank drilled instead of ground: two 8 mm axial holes per web at 40 mm
HOLES = ["--method", "holes", "--correction-radius", "40 mm", "--hole-diameter", "8 mm"]
HOLES += ["--holes", "2"]


def _rebalance_json(capsys, extra: list[str]) -> dict:  # type: ignore[type-arg]
    """The rebalance of the example with holes and ``extra``: its table prints, its JSON."""
    args = ["rebalance", "--parts", str(EXAMPLE), *HOLES, *extra]
    code, _, err = run(capsys, args)
    assert code == 0, err
    code, out, err = run(capsys, [*args, "--format", "json"])
    assert code == 0, err
    return json.loads(out)


def test_rebalance_drill_point_options_against_the_closed_form(capsys) -> None:
    """--point-angle and --depth-to drill pointed holes: the unbalance removed is that of
    the closed-form volume (a cylinder plus a cone of height h = (d/2)/tan(point/2), read
    to the shoulder; a cylinder h shorter plus the cone, read to the tip), and the same
    correction needs h/3 less depth read to the shoulder, 2h/3 more read to the tip, than
    flat-bottomed holes (docs/balance_shop.md, "Holes")."""
    import math

    a, density, radius, holes = 4e-3, 7850.0, 40e-3, 4  # 2 webs x 2 holes
    h = a / math.tan(math.radians(118.0 / 2))
    cone = math.pi * a**2 * h / 3

    def volume(depth: float, depth_to: str | None) -> float:
        if depth_to is None:
            return math.pi * a**2 * depth
        shank = depth if depth_to == "shoulder" else depth - h
        return math.pi * a**2 * shank + cone

    first: dict[str | None, float] = {}
    for depth_to in (None, "shoulder", "tip"):
        extra = [] if depth_to is None else ["--point-angle", "118 deg", "--depth-to", depth_to]
        payload = _rebalance_json(capsys, extra)
        for case in payload["cases"]:
            assert case["passed"]
            correction = case["correction"]
            if depth_to is None:  # flat-bottomed: no point, no reference to state
                assert "point_angle_deg" not in correction and "depth_to" not in correction
            else:
                assert correction["point_angle_deg"] == pytest.approx(118.0)
                assert correction["depth_to"] == depth_to
            for it in case["iterations"]:
                exact = holes * density * volume(it["depth_m"], depth_to) * radius
                assert it["removed_unbalance_kg_m"] == pytest.approx(exact, rel=1e-9)
        first[depth_to] = payload["cases"][0]["iterations"][0]["depth_m"]
    step = 1e-6 + 1e-12  # the example's machining step, 0.001 mm
    assert first[None] - first["shoulder"] == pytest.approx(h / 3, abs=step)
    assert first["tip"] - first[None] == pytest.approx(2 * h / 3, abs=step)


def test_rebalance_flat_point_keeps_the_thesis_numbers(capsys) -> None:
    """A 180 deg point is the flat bottom of the default: the same output, number for
    number (the thesis' Table 6.2 stays reproducible with the default)."""
    default = _rebalance_json(capsys, [])
    flat = _rebalance_json(capsys, ["--point-angle", "180 deg"])
    assert flat == default


@pytest.mark.parametrize(
    ("extra", "option", "words"),
    [
        (HOLES + ["--point-angle", "200 deg", "--depth-to", "tip"], "--point-angle",
         "greater than 0 deg and at most 180 deg"),
        (HOLES + ["--point-angle", "0 deg", "--depth-to", "tip"], "--point-angle",
         "greater than 0 deg"),
        (HOLES + ["--point-angle", "nan deg", "--depth-to", "tip"], "--point-angle", "one number"),
        (HOLES + ["--point-angle", "118 mm", "--depth-to", "tip"], "--point-angle", "angle"),
        (HOLES + ["--point-angle", "118 deg"], "--point-angle", "needs --depth-to"),
        (HOLES + ["--depth-to", "tip"], "--depth-to", "pointed holes only"),
        (HOLES + ["--point-angle", "180 deg", "--depth-to", "tip"], "--depth-to",
         "pointed holes only"),
        (["--point-angle", "118 deg", "--depth-to", "tip"], "--point-angle",
         "does not apply to method 'face'"),
        (["--depth-to", "shoulder"], "--depth-to", "does not apply to method 'face'"),
    ],
)  # fmt: skip
def test_rebalance_drill_point_refused_where_ignored(capsys, extra, option, words) -> None:
    """Bad or ignored drill-point options: one line naming the option, exit 2."""
    code, out, err = run(capsys, ["rebalance", "--parts", str(EXAMPLE), *extra])
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and option in err and words in err, err
