"""One question, one answer (issue 26): every study of the registry answers the same JSON
on the command line (``--format json``, in-process through ``cli.main``), over the JSON API
(through its handler, :func:`crankbalance.web.api.compute_study`) and from its Python
function (``to_dict()`` after a JSON round trip), for at least two engines (or two sets of
settings for a study without an engine); and every command that computes something is a
study of the registry or is named, with the reason, in ``NOT_STUDIES``.

A case is a study, its engine and its options as the command line takes them (option name
without dashes -> text, a list for a repeated option, True for a flag); a file option names
a file of ``examples/``, copied into the test's folder, which is the working directory, so
that the command line, the API (which takes the file's content) and the function all name
it alike. Values that depend on the run (``elapsed_s``, the explorer's ``seconds``) are left
out of the comparison. tests/web/test_web_study_api.py sends some of these cases over real
HTTP.
"""

from __future__ import annotations

import contextlib
import io
import json
import shutil
import tomllib
from pathlib import Path
from typing import Any

import click
import pytest

from crankbalance.cli import cli, main
from crankbalance.studies.registry import NOT_STUDIES, STUDIES, run
from crankbalance.web import api

from .conftest import hang_guard

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
#: the commands whose engine is an argument (ENGINE), not ``--engine``
ENGINE_ARGUMENT = {"analyze", "balance", "bearings", "bearings-sweep", "mounts"}
#: the studies whose parts file is an argument (PARTS), not ``--parts``
PARTS_ARGUMENT = {"shop-match", "shop-bobweights", "shop-scatter"}
#: keys whose value depends on the run, not on the inputs
VOLATILE = {"elapsed_s", "seconds"}
#: a shop's hole plan (tests/test_shop_cli.py)
PLAN = {
    "reading": ["12.5 g @ 40 mm, 35 deg", "8 g @ 40 mm, 200 deg"],
    "measuring-planes": "0 mm, 400 mm",
    "correction-planes": "50 mm, 350 mm",
    "hole-radius": "45 mm",
    "depth-to": "tip",
    "rotor-mass": "25 kg",
    "bearings": "-20 mm, 420 mm",
}
#: a pressure table, written by the test (crank angle [deg], absolute pressure [bar])
TABLE = "angle_deg,pressure_bar\n-360,1\n-180,1\n-30,20\n0,60\n30,35\n180,3\n360,1\n"

#: study -> [(engine or None, options)]: two engines each, or two sets of settings
CASES: dict[str, list[tuple[str | None, dict[str, Any]]]] = {
    "analyze": [("inline4", {"orders": "4"}), ("v8-crossplane", {})],
    "balance": [("paper-inline3", {}), ("v6-60", {"balance-factor": "50%"})],
    "balance-factor": [
        ("inline4", {"balance-factor": "0.4"}),
        ("v2-90", {"cylinder": "2", "target": "0.5", "rod-length": "140 mm"}),
        (None, {"reciprocating-mass": "282.12 g", "crank-radius": "26.9 mm", "speed": "9000 rpm"}),
    ],
    "rebalance": [
        (None, {"parts": "crf250r_rebalance.toml"}),
        (None, {"parts": "crf250r_rebalance.toml", "target": ["0.28", "factory"]}),
    ],
    "tolerance": [
        (None, {"grade": "G6.3", "rotor-mass": "2.7 kg", "speed": "15200 rpm"}),
        ("inline4", {"grade": "G2.5", "residual": "20 g*mm"}),
        (None, {"list": True}),
    ],
    "counterweight-optimize": [
        ("paper-inline3", {"iterations": "1", "population": "64", "seed": "7"}),
        ("inline4", {"iterations": "1", "population": "64", "seed": "1", "pareto": "3"}),
    ],
    "counterweight-show": [
        (
            None,
            {
                "first-moment": "7880 g*mm",
                "web-radius": "20 mm",
                "rectangle-height": "20 mm",
                "trapezoid-angle": "20 deg",
                "segment-radius": "50 mm",
                "segment-angle": "120 deg",
            },
        ),
        (
            "paper-inline3",
            {
                "web-radius": "22 mm",
                "rectangle-height": "15 mm",
                "trapezoid-angle": "10 deg",
                "segment-radius": "45 mm",
                "segment-angle": "100 deg",
            },
        ),
    ],
    "shaft-inline4": [("inline4", {"points": "11"}), ("paper-inline3", {"points": "11"})],
    "shaft-inline3": [
        ("paper-inline3", {"points": "11", "type": "III"}),
        ("inline3", {"points": "11", "hold": "unbalance"}),
    ],
    "shaft-check": [
        (
            None,
            {
                "bearing": ["0 mm", "300 mm"],
                "mass": ["200 mm"],
                "unbalance": ["3.3 kg*mm"],
                "speed": "6000 rpm",
            },
        ),
        (
            None,
            {
                "bearing": ["0 mm", "300 mm"],
                "mass": ["50 mm", "250 mm"],
                "unbalance": ["3 kg*mm"],
                "phase": ["0 deg", "180 deg"],
                "speed": "9000 rpm",
                "theory": "timoshenko",
            },
        ),
    ],
    "friction": [
        (
            None,
            {
                "load": "25 N",
                "rotating-load": "42.2 N",
                "journal-diameter": "20 mm",
                "friction-coefficient": "0.005",
            },
        ),
        (
            None,
            {
                "unbalance": "427 g*mm",
                "speed": "3000 rpm",
                "journal-diameter": "20 mm",
                "torque": "0.01 N*m",
                "load": "25 N",
            },
        ),
    ],
    "bench": [
        (None, {"friction-coefficient": "0.005", "hold-time": "0.2 s", "ramp-time": "0.3 s"}),
        (
            None,
            {
                "friction-coefficient": "0.01",
                "speed": ["1000 rpm", "2000 rpm"],
                "hold-time": "0.1 s",
                "ramp-time": "0.2 s",
            },
        ),
    ],
    "cycle": [
        ("single", {"cylinder": "1"}),
        ("inline4", {"speed-fluctuation-target": "0.05"}),
        (None, {"pressure-csv": ["table.csv"], "speed": "6000 rpm"}),
    ],
    "sensitivity": [
        ("single", {"balance-factors": "0,0.5,1"}),
        ("inline4", {"balance-factors": "0.5", "mass-scales": "1,0.9"}),
    ],
    "bearings": [("inline4", {"samples": "72"}), ("v6-60", {"samples": "72", "gas": False})],
    "bearings-sweep": [
        ("inline4", {"samples": "36", "balance-factors": "0.5", "pattern": ["all", "none"]}),
        ("paper-inline3", {"samples": "36", "balance-factors": "0.4,0.6"}),
    ],
    "torsional": [("inline4", {"speed-points": "20"}), ("inline6", {"speed-points": "20"})],
    "mounts": [
        ("mounts_inline4_car.toml", {"speed-samples": "20"}),
        (
            "mounts_vtwin_motorcycle.toml",
            {"speed-samples": "20", "orders": "2", "rotating": "bare"},
        ),
    ],
    "explore": [(None, {"cylinders": "3"}), ("inline4", {"cylinders": "4", "top": "5"})],
    "shop-match": [
        ("v8-crossplane", {"parts": "v8_parts.csv"}),
        ("v8-flatplane", {"parts": "v8_parts.csv", "method": "as-listed"}),
    ],
    "shop-bobweights": [
        ("v8-crossplane", {"parts": "v8_parts.csv", "method": "as-listed"}),
        ("v8-flatplane", {"parts": "v8_parts.csv", "fraction": "0.45", "method": "as-listed"}),
    ],
    "shop-plan": [(None, {**PLAN, "speed": "5500 rpm"}), ("v8-crossplane", PLAN)],
    "shop-scatter": [
        (
            "v8-crossplane",
            {"parts": "v8_parts.csv", "correction-planes": "-200 mm, 200 mm", "samples": "500"},
        ),
        (
            "v8-flatplane",
            {
                "parts": "v8_parts.csv",
                "correction-planes": "-200 mm, 200 mm",
                "samples": "300",
                "rotor-mass": "25 kg",
                "seed": "3",
            },
        ),
    ],
}
#: the files of the cases, by the name a case gives
FILES = {
    "crf250r_rebalance.toml",
    "v8_parts.csv",
    "table.csv",
    "mounts_inline4_car.toml",
    "mounts_vtwin_motorcycle.toml",
}


@pytest.fixture
def folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """The test's folder with the cases' files, as the working directory."""
    for name in FILES - {"table.csv"}:
        shutil.copy(EXAMPLES / name, tmp_path / name)
    (tmp_path / "table.csv").write_text(TABLE)
    monkeypatch.chdir(tmp_path)
    return tmp_path


def cli_args(name: str, engine: str | None, options: dict[str, Any]) -> list[str]:
    """The command line of a case."""
    entry = STUDIES[name]
    args = list(entry.command)
    rest = dict(options)
    if name in PARTS_ARGUMENT:
        args.append(rest.pop("parts"))
    if engine is not None:
        args += [engine] if name in ENGINE_ARGUMENT else ["--engine", engine]
    for option, value in rest.items():
        if value is True:
            args.append(f"--{option}")
        elif value is False:
            args.append(f"--no-{option}")
        elif isinstance(value, list):
            for item in value:
                args += [f"--{option}", item]
        else:
            args += [f"--{option}", value]
    return [*args, "--format", "json"]


def run_cli(args: list[str]) -> dict[str, Any]:
    """The JSON the command line prints (in this process)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(args)
        except SystemExit as stop:
            code = stop.code
    assert not code, f"crankbalance {' '.join(args)}: exit {code}: {err.getvalue()}"
    value = json.loads(out.getvalue())
    assert isinstance(value, dict)
    return value


def api_body(name: str, engine: str | None, options: dict[str, Any]) -> bytes:
    """The API body of a case: a file option's content sent with it."""
    entry = STUDIES[name]
    body: dict[str, Any] = {} if engine is None else {"engine": engine}
    if engine is not None and engine.endswith(".toml"):  # an engine file: sent as an object
        body["engine"] = tomllib.loads(Path(engine).read_text())
    for option, value in options.items():
        if entry.field_of(option) in entry.files:
            names = value if isinstance(value, list) else [value]
            sent = [{"name": n, "text": Path(n).read_text()} for n in names]
            value = sent if isinstance(value, list) else sent[0]
        body[option] = value
    return json.dumps(body).encode()


def python(name: str, engine: str | None, options: dict[str, Any]) -> dict[str, Any]:
    """The study function's ``to_dict()`` after a JSON round trip."""
    entry = STUDIES[name]
    values = {entry.field_of(option): value for option, value in options.items()}
    assert None not in values, options
    result = run(name, engine, values)
    value = json.loads(json.dumps(result.to_dict()))
    assert isinstance(value, dict)
    return value


def steady(value: Any) -> Any:
    """``value`` without the keys whose value depends on the run."""
    if isinstance(value, dict):
        return {k: steady(v) for k, v in value.items() if k not in VOLATILE}
    if isinstance(value, list):
        return [steady(v) for v in value]
    return value


def test_every_study_has_two_cases() -> None:
    assert set(CASES) == set(STUDIES)
    for name, cases in CASES.items():
        engines = {engine for engine, _ in cases}
        assert len(cases) >= 2, name
        if STUDIES[name].engine != "none":
            assert len(engines - {None}) >= 1 and len(engines) >= 2, name


@pytest.mark.parametrize(
    ("name", "engine", "options"),
    [(name, engine, options) for name, cases in CASES.items() for engine, options in cases],
    ids=lambda v: v if isinstance(v, str) else None,
)
def test_cli_api_and_python_answer_alike(
    name: str, engine: str | None, options: dict[str, Any], folder: Path
) -> None:
    with hang_guard(300):
        on_the_command_line = steady(run_cli(cli_args(name, engine, options)))
        status, over_the_api = api.compute_study(
            name, api_body(name, engine, options), "application/json"
        )
        assert status == 200, over_the_api
        from_python = steady(python(name, engine, options))
    assert on_the_command_line["schema"].startswith("crankbalance.")
    assert steady(over_the_api) == on_the_command_line
    assert from_python == on_the_command_line


def test_a_file_option_of_the_api_reads_no_file_of_the_server(folder: Path) -> None:
    """The API takes a file's content: a path, even of a file that exists, is refused, and
    a name sent with a content is never looked up on the disk."""
    body = json.dumps({"parts": "crf250r_rebalance.toml"}).encode()
    status, answer = api.compute_study("rebalance", body, "application/json")
    assert status == 422 and answer["field"] == "parts"
    assert '{"name": "parts.csv", "text": "..."}' in answer["error"]
    (folder / "secret.toml").write_text("crank_radius = '1 mm'\n")
    text = (folder / "crf250r_rebalance.toml").read_text()
    body = json.dumps({"parts": {"name": "secret.toml", "text": text}}).encode()
    status, answer = api.compute_study("rebalance", body, "application/json")
    assert status == 200, answer
    assert answer == python("rebalance", None, {"parts": "crf250r_rebalance.toml"})


@pytest.mark.parametrize(
    ("name", "body", "field", "words"),
    [
        (
            "balance-factor",
            {"engine": "inline4", "balance-factor": "5"},
            "balance-factor",
            "0 to 2",
        ),
        ("cycle", {"engine": "/etc/hostname"}, "engine", "preset name"),
        ("explore", {"workers": 2}, "workers", "machine that computes"),
        ("bench", {"friction-coefficient": "0.1", "history": "x.csv"}, "history", "command line"),
        ("friction", {"journal-diameter": "20 mm", "nope": 1}, "nope", "not an option"),
        ("analyze", {"engine": 4}, "engine", "preset name"),
        ("bearings", {}, "engine", "needed"),
        ("friction", {"engine": "inline4"}, "engine", "takes no engine"),
        ("cycle", {"engine": "single", "pressure-csv": "/etc/hostname"}, "pressure-csv", "name"),
    ],
)
def test_the_api_names_the_option_as_sent(
    name: str, body: dict[str, Any], field: str, words: str
) -> None:
    status, answer = api.compute_study(name, json.dumps(body).encode(), "application/json")
    assert status == 422, answer
    assert answer["field"] == field and words in answer["error"], answer


def test_analyze_and_balance_take_an_engine_file_or_settings() -> None:
    """The former bodies of /api/analyze and /api/balance (an engine file) still answer."""
    from crankbalance.io.engine_file import preset_text

    for kind in ("analyze", "balance"):
        status, as_file = api.compute(kind, preset_text("inline4").encode(), "application/toml")
        assert status == 200
        body = json.dumps({"engine": "inline4"}).encode()
        status, as_settings = api.compute(kind, body, "application/json")
        assert status == 200 and as_settings == as_file


def _commands(group: click.Group, words: tuple[str, ...] = ()) -> list[tuple[str, ...]]:
    ctx = click.Context(group)
    out: list[tuple[str, ...]] = []
    for name in group.list_commands(ctx):
        command = group.get_command(ctx, name)
        assert command is not None
        if isinstance(command, click.Group):
            out += _commands(command, (*words, name))
        else:
            out.append((*words, name))
    return out


def test_every_command_is_a_study_or_says_why_not() -> None:
    """A command that computes something is in the registry (under its words), or named in
    NOT_STUDIES with the reason; every option of a study's command is a setting of its
    model or one of the command's own (its output, its files, its progress)."""
    commands = set(_commands(cli))
    studies = {entry.command: entry for entry in STUDIES.values()}
    assert commands == set(studies) | set(NOT_STUDIES)
    assert not set(studies) & set(NOT_STUDIES)
    ctx = click.Context(cli)
    for words, entry in studies.items():
        command: Any = cli
        for word in words:
            command = command.get_command(ctx, word)
        options = {
            p.opts[0].removeprefix("--")
            for p in command.params
            if isinstance(p, click.Option) and p.opts[0].startswith("--") and p.name != "help"
        }
        options |= {p.name for p in command.params if isinstance(p, click.Argument)}
        settings = {entry.option(n) for n in entry.field_names()}
        assert options - {"engine", "version"} == (settings | set(entry.edge)) - {"engine"}, (
            words,
            options ^ (settings | set(entry.edge)),
        )


def test_the_engine_library_is_one_answer() -> None:
    """``presets --format json`` is the listing ``GET /api/presets`` answers."""
    from crankbalance.studies.engine import presets_listing

    assert run_cli(["presets", "--format", "json"]) == presets_listing()
    assert {"name": "v8-crossplane", "title": "V8 90 deg, crossplane crank"} in (
        presets_listing()["presets"]
    )
