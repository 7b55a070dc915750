"""The commands whose JSON output the golden tier pins, value by value.

Every preset is analysed and balanced; the other studies run once each on an example.
Regenerate the files after a deliberate change with::

    python tests/golden/regenerate.py

and list the change in the commit message.
"""

from __future__ import annotations

import io
import json
from contextlib import redirect_stdout
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
DATA = HERE / "data"
EXAMPLES = ROOT / "examples"


def cases() -> dict[str, list[str]]:
    """Case name -> CLI arguments (every case prints one JSON object)."""
    from crankbalance.io.engine_file import list_presets

    out: dict[str, list[str]] = {}
    for preset in list_presets():
        out[f"analyze-{preset}"] = ["analyze", preset, "--format", "json"]
        out[f"balance-{preset}"] = ["balance", preset, "--format", "json"]
    out["balance-factor-crf250r"] = [
        "balance-factor",
        "--reciprocating-mass",
        "282.12 g",
        "--crank-radius",
        "26.9 mm",
        "--rotating-mass",
        "282.69 g",
        "--cw-mass",
        "2020.40 g",
        "--cw-radius",
        "6.16 mm",
        "--speed",
        "15200 rpm",
        "--rod-length",
        "105 mm",
        "--format",
        "json",
    ]
    out["balance-factor-engine-inline4"] = [
        "balance-factor",
        "--engine",
        "inline4",
        "--format",
        "json",
    ]
    out["rebalance-crf250r"] = [
        "rebalance",
        "--parts",
        str(EXAMPLES / "crf250r_rebalance.toml"),
        "--format",
        "json",
    ]
    out["tolerance-crf250r"] = [
        "tolerance",
        "--grade",
        "G6.3",
        "--rotor-mass",
        "2.7 kg",
        "--speed",
        "15200 rpm",
        "--bearing-a",
        "0 mm",
        "--bearing-b",
        "120 mm",
        "--center-of-mass",
        "60 mm",
        "--format",
        "json",
    ]
    out["shaft-inline4-engine"] = [
        "shaft",
        "inline4",
        "--engine",
        "inline4",
        "--length",
        "300 mm",
        "--diameter",
        "25 mm",
        "--points",
        "21",
        "--format",
        "json",
    ]
    out["shaft-inline3-engine"] = [
        "shaft",
        "inline3",
        "--engine",
        "paper-inline3",
        "--length",
        "300 mm",
        "--diameter",
        "25 mm",
        "--points",
        "21",
        "--format",
        "json",
    ]
    out["shaft-check"] = [
        "shaft",
        "check",
        "--length",
        "300 mm",
        "--diameter",
        "25 mm",
        "--bearing",
        "0 mm",
        "--bearing",
        "300 mm",
        "--mass",
        "200 mm",
        "--unbalance",
        "3.3 kg*mm",
        "--speed",
        "6000 rpm",
        "--format",
        "json",
    ]
    out["counterweight-show"] = [
        "counterweight",
        "show",
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
        "--format",
        "json",
    ]
    out["counterweight-optimize-engine"] = [
        "counterweight",
        "optimize",
        "--engine",
        "paper-inline3",
        "--iterations",
        "3",
        "--population",
        "256",
        "--seed",
        "7",
        "--quiet",
        "--format",
        "json",
    ]
    out["friction"] = [
        "friction",
        "--load",
        "25 N",
        "--rotating-load",
        "42.2 N",
        "--journal-diameter",
        "20 mm",
        "--friction-coefficient",
        "0.005",
        "--format",
        "json",
    ]
    # cycle/3: --engine alone runs every cylinder; the golden file is of one cylinder
    out["cycle-engine"] = ["cycle", "--engine", "single", "--cylinder", "1", "--format", "json"]
    out["sensitivity-engine"] = ["sensitivity", "--engine", "single", "--format", "json"]
    out["mounts-inline4-car"] = [
        "mounts",
        str(EXAMPLES / "mounts_inline4_car.toml"),
        "--speed-samples",
        "40",
        "--mean-torque",
        "120 N*m",
        "--format",
        "json",
    ]
    out["bench"] = [
        "bench",
        "--speed",
        "3000 rpm",
        "--friction-coefficient",
        "0.005",
        "--hold-time",
        "0.5 s",
        "--format",
        "json",
    ]
    return out


def run(args: list[str]) -> dict[str, Any]:
    """Run the CLI in this process and parse the JSON it prints."""
    from crankbalance.cli import main

    buffer = io.StringIO()
    with redirect_stdout(buffer):
        try:
            code = main(args)
        except SystemExit as stop:
            code = stop.code
    assert not code, f"crankbalance {' '.join(args)} exited with {code}: {buffer.getvalue()}"
    value = json.loads(buffer.getvalue())
    assert isinstance(value, dict)
    return value
