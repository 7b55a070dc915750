"""Fuzzing of every subcommand's options (issue 12): random subsets of each command's options
with hostile values (NaN, infinities, 1e308, -1, 0, subnormal numbers, huge integers, wrong
units, empty texts, ranges where one value is expected), run in-process through
``crankbalance.cli.main``.

Each run must end in exit status 2 with exactly one line on stderr, or in exit status 0 with
no NaN or infinity in the output. Deterministic (``derandomize=True``, no database); each
example has a generous hang guard (``signal.alarm``, 120 s), not a timing assertion: the work
of every command is bounded by the documented caps of :mod:`crankbalance.schema.settings`. Valid
values are kept cheap (small presets, one or two optimiser rounds, short bench runs).

The commands that read a cylinder-pressure table (``bearings``, ``bearings-sweep``,
``torsional``, ``cycle --engine``, ``sensitivity``) also get mutated tables (values out of
range or not finite, unsorted or repeated angles, too few rows, more than one cycle, extra
or missing columns, damaged bytes, beyond the size limit): :func:`test_fuzz_pressure_tables`.

``pytest -s`` prints the examples tried and clean per command (docs/reliability.md).
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import tempfile
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import click
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from crankbalance.cli import COMMANDS, cli, main
from crankbalance.io.pressure_csv import MAX_FILE_BYTES as MAX_TABLE_BYTES
from crankbalance.schema.settings import RANGES
from crankbalance.units import KINDS, format_quantity

from ..conftest import hang_guard

ROOT = Path(__file__).resolve().parents[2]
PARTS = str(ROOT / "examples" / "crf250r_rebalance.toml")
#: examples per command; 20 commands and subcommands, so 10 give about 200 combinations (a longer
#: exploration: CRANKBALANCE_FUZZ_EXAMPLES=200, still deterministic)
EXAMPLES = int(os.environ.get("CRANKBALANCE_FUZZ_EXAMPLES", "10"))
#: the hang guard of one example [s]: generous, the slowest valid example takes a few seconds
HANG_GUARD = 120
#: NaN or an infinity in an output, as Python, JSON or a table would print it
NON_FINITE = re.compile(r"(?<![A-Za-z])(nan|inf|infinity)(?![A-Za-z])", re.IGNORECASE)

#: hostile plain numbers, then numbers at the edges of the ranges options accept
NUMBERS = ["nan", "inf", "-inf", "1e308", "-1", "0", "1e-320", "9" * 30, "", "abc", "1..2"]
EDGES = ["1e-300", "0.999999", "1.000001", "100", "10000", "1e6"]


def number(*valid: str) -> list[str]:
    """Valid values and the hostile ones of a plain number."""
    return [*valid, *NUMBERS, *EDGES]


def quantity(kind: str, *valid: str) -> list[str]:
    """Valid values and the hostile ones of a quantity of ``kind`` (units.KINDS), written in
    its display unit, with the two ends of its physical range (options.RANGES)."""
    unit = KINDS[kind][1].replace("**", "^")
    hostile = [f"{v} {unit}" for v in NUMBERS[:8]] + [f"1..2 {unit}"]
    edges = [format_quantity(v, kind, 6) for v in RANGES.get(kind, ())]
    return [*valid, *hostile, *edges, "", "abc", "42", "3 kg", "5 parsec", "2 s"]


#: the hostile words of a choice and of a file name
CHOICE = ["", "x", "nan"]
FLAG = None  # an option without a value


@dataclass
class Command:
    """How one command is called: its words, its positional arguments (choices), the
    options that make a valid call, and every option with its valid and hostile values."""

    words: list[str]
    positionals: list[list[str]] = field(default_factory=list)
    base: list[str] = field(default_factory=list)
    options: dict[str, list[str | None]] = field(default_factory=dict)


LENGTH = quantity("length", "20 mm")
MASS = quantity("mass", "300 g")
SPEED = quantity("speed", "3000 rpm")
FORMATS = ["table", "json", *CHOICE]
FORMATS_CSV = ["table", "json", "csv", *CHOICE]
PROFILE = {
    "--web-radius": quantity("length", "20 mm", "10..20 mm"),
    "--rectangle-height": quantity("length", "20 mm", "0 mm"),
    "--trapezoid-angle": quantity("angle", "20 deg"),
    "--segment-radius": quantity("length", "50 mm"),
    "--segment-angle": quantity("angle", "120 deg", "60..170 deg"),
    "--thickness": quantity("length", "8 mm"),
}
PROFILE_BASE = [
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
REQUIREMENT = {
    "--first-moment": quantity("unbalance", "7880 g*mm"),
    "--cw-mass": MASS,
    "--cg-radius": LENGTH,
    "--engine": ["inline4", "single", "no-such-engine", ""],
}
SECTION = {
    "--length": quantity("length", "300 mm"),
    "--diameter": quantity("length", "25 mm"),
    "--bore": quantity("length", "0 mm", "10 mm"),
    "--modulus": quantity("modulus", "210 GPa"),
    "--density": quantity("density", "7850 kg/m^3"),
    "--poisson": number("0.3"),
    "--unbalance-radius": quantity("length", "20 mm"),
    "--bearing-stiffness": quantity("stiffness", "2e8 N/m"),
    "--theory": ["euler-bernoulli", "timoshenko", *CHOICE],
}
STUDY = {
    "--engine": ["inline4", "single", "no-such-engine"],
    "--unbalance": quantity("unbalance", "3 g*m"),
    "--speed": quantity("speed", "12000 rpm"),
    "--weight": number("2"),
    "--weights": ["1,2", "1,nan", "0.5", *NUMBERS],
    "--points": number("3", "21"),
    "--secondary": ["reaction-difference", "inverse-frequency", *CHOICE],
}
#: a pressure table (crank angle [deg], absolute pressure [bar]): a crude firing peak in
#: 10 deg steps over one cycle
PRESSURE_ROWS = [(float(a), 1.0 + 40.0 * (abs(a) < 20)) for a in range(-360, 360, 10)]
#: hostile pressure tables the workspace holds, by name: what a test bench's export may
#: hold by mistake (a gauge reading, a unit slip, a table sorted the wrong way)
HOSTILE_TABLES: dict[str, list[tuple[float, float]]] = {
    "huge": [(a, p * 1e300) for a, p in PRESSURE_ROWS],
    "negative": [(a, p - 2.0) for a, p in PRESSURE_ROWS],
    "nan": [*PRESSURE_ROWS[:5], (PRESSURE_ROWS[5][0], float("nan")), *PRESSURE_ROWS[6:]],
    "unsorted": PRESSURE_ROWS[::-1],
    "short": PRESSURE_ROWS[:3],
    "two cycles": [(a + k * 360.0, p) for k in (0, 1) for a, p in PRESSURE_ROWS],
}
#: the --pressure-csv values: the valid table, the hostile ones (in the workspace, the
#: example's folder's parent), one over the size limit, a missing file, a folder, nothing
PRESSURE_CSV = [
    "OUT/p.csv",
    *(f"OUT/../p-{name.replace(' ', '-')}.csv" for name in HOSTILE_TABLES),
    "OUT/../p-overlong.csv",
    "OUT/missing.csv",
    "OUT",
    "",
]


def table_text(rows: list[tuple[float, float]]) -> str:
    """A pressure table's text with its header."""
    return "angle_deg,pressure_bar\n" + "".join(f"{a!r},{p!r}\n" for a, p in rows)


ENGINE_CYCLE = {
    "--engine": ["single", "inline4", "no-such-engine", ""],
    "--cylinder": number("1", "2"),
    "--bore": quantity("length", "76.8 mm"),
    "--stroke": quantity("length", "53.8 mm"),
    "--rod-length": quantity("length", "103.5 mm"),
    "--reciprocating-mass": quantity("mass", "282 g"),
    "--crank-inertia": quantity("inertia", "0.006 kg*m^2"),
    "--journal-diameter": quantity("length", "30 mm"),
    "--friction-coefficient": number("0.005"),
    "--speed": quantity("speed", "9000 rpm"),
    "--strokes": ["2", "4", "3", *CHOICE],
    "--compression-ratio": number("13.5"),
    "--ignition": quantity("angle", "-25 deg"),
    "--burn-duration": quantity("angle", "50 deg"),
    "--intake-pressure": quantity("pressure", "1 bar"),
    "--heat-release": quantity("energy", "600 J"),
    "--fuel-mass": quantity("mass", "20 mg"),
    "--heating-value": quantity("specific_energy", "44 MJ/kg"),
    "--combustion-efficiency": number("0.8", "1"),
    "--gamma": number("1.3", "1.01", "1.67"),
    "--exhaust-pressure": quantity("pressure", "1.2 bar"),
    "--burn-end": ["complete", "stop", *CHOICE],
    "--pressure-csv": PRESSURE_CSV,
}
#: a torsional stiffness (options.TorsionalStiffness): valid, the ends, hostile
TORSIONAL_STIFFNESS = [
    "5e5 N*m/rad",
    "1 N*m/rad",
    "1e11 N*m/rad",
    "1e12 N*m/rad",
    "5e5 N*m",
    "nan N*m/rad",
    "inf N*m/rad",
    "-1 N*m/rad",
    "0 N*m/rad",
    "1..2 N*m/rad",
    "5 parsec/rad",
    "",
    "abc",
]
OUTPUT = ["OUT/x.html", "OUT/x.txt", "/no/such/folder/x.html", "OUT", ""]

V8_PARTS = str(ROOT / "examples" / "v8_parts.csv")
SHOP_ENGINE = {"--engine": ["v8-crossplane", "inline4", "no-such-engine", ""]}
SHOP_PARTS = {
    "--method": ["as-listed", "pairing", "milp", *CHOICE],
    "--time-limit": quantity("time", "5 s"),
    "--fraction": number("0.5", "50%"),
    "--journals": ["paired", "joint", "as-listed", *CHOICE],
}
SHOP_PLAN = {
    "--reading": [
        "12.5 g @ 40 mm, 35 deg",
        "nan g @ 40 mm, 0 deg",
        "12.5 g",
        "1e308 g @ 1 mm, 0 deg",
    ],
    "--convention": ["heavy", "light", *CHOICE],
    "--measuring-planes": ["0 mm, 400 mm", "0 mm, 0 mm", "0 mm", "nan mm, 1 mm", ""],
    "--correction-planes": ["50 mm, 350 mm", "50 mm, 50 mm", "1e308 mm, 0 mm", ""],
    "--hole-diameter": quantity("length", "8 mm"),
    "--hole-radius": quantity("length", "45 mm"),
    "--max-depth": quantity("length", "15 mm"),
    "--web-thickness": quantity("length", "20 mm", "2 mm"),
    "--depth-to": ["tip", "shoulder", *CHOICE],
    "--point-angle": quantity("angle", "118 deg", "180 deg"),
    "--direction": ["axial", "radial", *CHOICE],
    "--spacing": quantity("length", "2 mm", "0 mm"),
    "--depth-resolution": quantity("length", "0.1 mm", "0 mm"),
    "--density": quantity("density", "7850 kg/m^3"),
    "--slug-density": quantity("density", "18000 kg/m^3", "1000 kg/m^3"),
    "--grade": ["G6.3", "G2.5", "G7", ""],
    "--rotor-mass": quantity("mass", "25 kg"),
    "--speed": quantity("speed", "5500 rpm"),
    "--bearings": ["-20 mm, 420 mm", "0 mm, 0 mm", ""],
    "--center-of-mass": quantity("length", "200 mm"),
}
SHOP_PLAN_BASE = [
    "--reading",
    "12.5 g @ 40 mm, 35 deg",
    "--reading",
    "8 g @ 40 mm, 200 deg",
    "--measuring-planes",
    "0 mm, 400 mm",
    "--correction-planes",
    "50 mm, 350 mm",
    "--hole-radius",
    "45 mm",
    "--depth-to",
    "tip",
    "--rotor-mass",
    "25 kg",
    "--speed",  # the ISO check's (shop plan has no engine to take it from)
    "5500 rpm",
]
SHOP = {
    "match": {**SHOP_ENGINE, **SHOP_PARTS},
    "bobweights": {**SHOP_ENGINE, **SHOP_PARTS},
    "plan": {**SHOP_ENGINE, **SHOP_PLAN},
    "scatter": {
        **SHOP_ENGINE,
        "--fraction": number("0.5"),
        "--correction-planes": SHOP_PLAN["--correction-planes"],
        "--rotor-mass": SHOP_PLAN["--rotor-mass"],
        "--grade": SHOP_PLAN["--grade"],
        "--speed": SHOP_PLAN["--speed"],
        "--bearings": SHOP_PLAN["--bearings"],
        "--samples": number("1000"),
        "--seed": number("0", "7"),
        "--scale-step": quantity("mass", "0.1 g", "0"),
    },
    "sheet": {
        **SHOP_ENGINE,
        **SHOP_PARTS,
        **SHOP_PLAN,
        "--output": OUTPUT,
        "--chromium": ["/no/such/chromium", ""],
    },
}

#: the options of ``bearings`` that ``bearings-sweep`` takes too: the cycle's ...
BEARING_LOADS = {
    "--speed": SPEED,
    "--samples": number("72", "36"),
    "--gas": [FLAG],
    "--no-gas": [FLAG],
    "--bore": quantity("length", "86 mm"),
    "--compression-ratio": number("10.5"),
    "--ignition": quantity("angle", "-20 deg"),
    "--burn-duration": quantity("angle", "50 deg"),
    "--intake-pressure": quantity("pressure", "1 bar"),
    "--heat-release": quantity("energy", "600 J"),
    "--fuel-mass": quantity("mass", "20 mg"),
    "--heating-value": quantity("specific_energy", "44 MJ/kg"),
    "--combustion-efficiency": number("0.8", "1"),
    "--gamma": number("1.3", "1.01", "1.67"),
    "--exhaust-pressure": quantity("pressure", "1.2 bar"),
    "--burn-end": ["complete", "stop", *CHOICE],
    "--pressure-csv": PRESSURE_CSV,
    "--crank-inertia": quantity("inertia", "0.15 kg*m^2"),
}
#: ... and the crank's and the bearings'
BEARING_CRANK = {
    "--journal-diameter": LENGTH,
    "--pin-diameter": LENGTH,
    "--web-thickness": quantity("length", "15 mm"),
    "--web-width": LENGTH,
    "--modulus": quantity("modulus", "170 GPa"),
    "--poisson": number("0.3"),
    "--bearing": quantity("length", "-200 mm", "200 mm", "0 mm"),
    "--bearing-stiffness": quantity("stiffness", "5e8 N/m"),
    "--friction-coefficient": number("0.005"),
    "--viscosity": quantity("viscosity", "0.01 Pa*s"),
    "--bearing-length": quantity("length", "20 mm"),
    "--clearance": quantity("length", "30 um"),
}


COMMAND_TABLE: dict[str, Command] = {
    "analyze": Command(
        ["analyze"],
        [["inline4", "single", "no-such-engine", ""]],
        [],
        {
            "--orders": number("1", "8", "64"),
            "--moment-point": [
                "0 mm, 40 mm, 120 mm",
                "-1 m, 0, 2 m",
                "1 mm, 2 mm",
                "1 mm, 2 mm, 3 mm, 4 mm",
                "nan mm, 0, 0",
                "1e300 m, 0, 0",
                *quantity("length", "40 mm"),
            ],
            "--format": FORMATS_CSV,
        },
    ),
    "presets": Command(["presets"], [], [], {"--format": FORMATS}),
    "balance": Command(
        ["balance"],
        [["inline4", "single", "v8-crossplane", "no-such-engine"]],
        [],
        {
            "--angle": quantity("angle", "optimal", "30 deg"),
            "--balance-factor": number("0.5", "50%", "2"),
            "--method": ["pattern", "individual", *CHOICE],
            "--scope": ["auto", "whole", "halves", *CHOICE],
            "--verify": [FLAG],
            "--format": FORMATS,
        },
    ),
    "counterweight optimize": Command(
        ["counterweight", "optimize"],
        [],
        ["--first-moment", "7880 g*mm", "--iterations", "1", "--population", "64", "--quiet"],
        {
            **REQUIREMENT,
            **PROFILE,
            "--density": quantity("density", "8000 kg/m^3"),
            "--max-mass": quantity("mass", "400 g"),
            "--max-radius": quantity("length", "80 mm"),
            "--journal-diameter": quantity("length", "20 mm", "52 mm"),
            "--min-balance": number("100"),
            "--radius-measure": ["true", "paper", *CHOICE],
            "--inertia": [FLAG],
            # valid values kept cheap: no long optimisation
            "--iterations": number("0", "2"),
            "--population": number("16", "64"),
            "--seed": number("7", "4294967295"),
            "--pareto": number("3"),
            "--quiet": [FLAG],
            "--format": FORMATS,
        },
    ),
    "counterweight show": Command(
        ["counterweight", "show"],
        [],
        ["--first-moment", "7880 g*mm", *PROFILE_BASE],
        {
            **REQUIREMENT,
            **PROFILE,
            "--density": quantity("density"),
            "--plot": ["OUT/x.html", "OUT/x.txt", "/no/such/folder/x.svg", "OUT", ""],
            "--format": FORMATS,
        },
    ),
    "counterweight export": Command(
        ["counterweight", "export"],
        [],
        ["--first-moment", "7880 g*mm", *PROFILE_BASE, "--output", "OUT/cw.svg"],
        {
            **REQUIREMENT,
            **PROFILE,
            "--density": quantity("density"),
            "--output": ["OUT/cw.dxf", "OUT/cw.stl", "OUT/cw.txt", "/no/such/cw.svg", "OUT", ""],
        },
    ),
    "counterweight check": Command(
        ["counterweight", "check"],
        [["OUT/part.stl", "OUT/missing.stl", "OUT", ""]],
        [],
        {
            **REQUIREMENT,
            "--density": quantity("density", "8000 kg/m^3"),
            "--unit": ["mm", "m", "inch", "parsec", "kg", "nan", ""],
            "--format": FORMATS,
        },
    ),
    "shaft inline4": Command(
        ["shaft", "inline4"],
        [],
        [
            "--length",
            "300 mm",
            "--diameter",
            "25 mm",
            "--unbalance",
            "3 g*m",
            "--speed",
            "12000 rpm",
            "--points",
            "21",
        ],
        {**SECTION, **STUDY, "--order": number("1", "2"), "--format": FORMATS},
    ),
    "shaft inline3": Command(
        ["shaft", "inline3"],
        [],
        [
            "--length",
            "300 mm",
            "--diameter",
            "25 mm",
            "--unbalance",
            "3 g*m",
            "--speed",
            "6000 rpm",
            "--points",
            "11",
        ],
        {
            **SECTION,
            **STUDY,
            "--type": ["I", "II", "III", "all", *CHOICE],
            "--hold": ["couple", "unbalance", *CHOICE],
            "--bearing-offset": quantity("length", "30 mm"),
            "--z-min": number("0.3"),
            "--format": FORMATS,
        },
    ),
    "shaft check": Command(
        ["shaft", "check"],
        [],
        [
            "--length",
            "300 mm",
            "--diameter",
            "25 mm",
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
        ],
        {
            **SECTION,
            "--bearing": quantity("length", "100 mm"),
            "--mass": quantity("length", "200 mm"),
            "--unbalance": quantity("unbalance", "3 g*m"),
            "--phase": quantity("angle", "180 deg"),
            "--speed": SPEED,
            "--max-speed": SPEED,
            "--margin": number("0.25"),
            "--bearing-capacity": quantity("force", "5 kN"),
            "--deflection-limit": quantity("length", "50 um"),
            "--format": FORMATS,
        },
    ),
    "balance-factor": Command(
        ["balance-factor"],
        [],
        ["--reciprocating-mass", "282.12 g", "--crank-radius", "26.9 mm"],
        {
            "--reciprocating-mass": MASS,
            "--crank-radius": LENGTH,
            "--rotating-mass": MASS,
            "--cw-mass": quantity("mass", "2020 g"),
            "--cw-radius": quantity("length", "6.16 mm"),
            "--balance-factor": number("0.5", "28%"),
            "--target": number("0.3"),
            "--speed": SPEED,
            "--rod-length": quantity("length", "105 mm"),
            "--offset": quantity("length", "0 mm", "2 mm"),
            "--kinematics": ["exact", "series", "first-order", *CHOICE],
            "--engine": ["single", "inline4", "no-such-engine"],
            "--cylinder": number("1", "2"),
            "--format": FORMATS,
        },
    ),
    "rebalance": Command(
        ["rebalance"],
        [],
        ["--parts", PARTS],
        {
            "--parts": [PARTS, "OUT", "OUT/missing.toml", ""],
            "--crank-radius": quantity("length", "26.9 mm"),
            "--cw-mass": quantity("mass", "2020.4 g"),
            "--cw-radius": quantity("length", "6.16 mm"),
            "--old-rotating-mass": MASS,
            "--old-reciprocating-mass": MASS,
            "--new-rotating-mass": quantity("mass", "248.69 g"),
            "--new-reciprocating-mass": quantity("mass", "261.5 g"),
            "--target": number("0.28", "factory", "28%"),
            "--method": ["face", "holes", *CHOICE],
            "--correction-radius": quantity("length", "40 mm"),
            "--face-area": quantity("area", "2157 mm^2"),
            "--face-orientation": ["radial", "axial", *CHOICE],
            "--hole-diameter": quantity("length", "8 mm"),
            "--holes": number("2"),
            "--hole-direction": ["axial", "radial", *CHOICE],
            "--point-angle": quantity("angle", "118 deg", "180 deg"),
            "--depth-to": ["shoulder", "tip", *CHOICE],
            "--web-thickness": quantity("length", "15 mm"),
            "--drill-length": quantity("length", "60 mm"),
            "--density": quantity("density", "7850 kg/m^3"),
            "--depth-resolution": quantity("length", "0.001 mm"),
            "--grade": ["G6.3", "G2.5", "G7", ""],
            "--rotor-mass": quantity("mass", "2.7 kg"),
            "--speed": quantity("speed", "15200 rpm"),
            "--tolerance": quantity("unbalance", "10 g*mm"),
            "--format": FORMATS,
        },
    ),
    "tolerance": Command(
        ["tolerance"],
        [],
        ["--grade", "G6.3", "--rotor-mass", "2.7 kg", "--speed", "15200 rpm"],
        {
            "--grade": ["G6.3", "G2.5", "G7", "", "nan"],
            "--rotor-mass": quantity("mass", "2.7 kg"),
            "--speed": quantity("speed", "15200 rpm"),
            "--residual": quantity("unbalance", "7.39 g*mm"),
            "--bearing-a": quantity("length", "0 mm"),
            "--bearing-b": quantity("length", "120 mm"),
            "--center-of-mass": quantity("length", "60 mm"),
            "--plane-1": quantity("length", "10 mm"),
            "--plane-2": quantity("length", "110 mm"),
            "--engine": ["single", "inline4", "nope", ""],
            "--list": [FLAG],
            "--format": FORMATS,
        },
    ),
    "friction": Command(
        ["friction"],
        [],
        [
            "--journal-diameter",
            "20 mm",
            "--rotating-load",
            "42.2 N",
            "--friction-coefficient",
            "0.1",
        ],
        {
            "--load": quantity("force", "25 N"),
            "--rotating-load": quantity("force", "42.2 N"),
            "--unbalance": quantity("unbalance", "427 g*mm"),
            "--speed": SPEED,
            "--journal-diameter": LENGTH,
            "--friction-coefficient": number("0.1", "1"),
            "--torque": quantity("torque", "0.2 N*m"),
            "--viscosity": quantity("viscosity", "0.01 Pa*s"),
            "--bearing-length": quantity("length", "20 mm"),
            "--clearance": quantity("length", "20 um"),
            "--eccentricity": number("0.5"),
            "--attitude-angle": quantity("angle", "30 deg"),
            "--format": FORMATS_CSV,
        },
    ),
    "bench": Command(
        ["bench"],
        [],
        [
            "--friction-coefficient",
            "0.1",
            "--ramp-time",
            "0.2 s",
            "--hold-time",
            "0.1 s",
            "--speed",
            "1000 rpm",
        ],
        {
            "--mass": quantity("mass", "2.5 kg"),
            "--inertia": quantity("inertia", "0.003 kg*m^2"),
            "--unbalance": quantity("unbalance", "400 g*mm"),
            "--journal-diameter": LENGTH,
            "--friction-coefficient": number("0.1"),
            "--speed": quantity("speed", "1000 rpm", "2000 rpm"),
            "--ramp-time": quantity("time", "0.2 s"),
            "--hold-time": quantity("time", "0.1 s"),
            "--kp": number("0.2"),
            "--ki": number("10"),
            "--history": ["OUT/h.csv", "/no/such/h.csv", "OUT", ""],
            "--format": FORMATS_CSV,
        },
    ),
    "cycle": Command(
        ["cycle"],
        [],
        [],
        {
            **ENGINE_CYCLE,
            "--balance-factor": number("0.5"),
            "--flywheel-inertia": quantity("inertia", "0.05 kg*m^2"),
            "--speed-fluctuation-target": number("0.01", "2%"),
            "--plot": OUTPUT,
            "--format": FORMATS_CSV,
        },
    ),
    "sensitivity": Command(
        ["sensitivity"],
        [],
        ["--balance-factors", "0:1:0.5"],
        {
            **ENGINE_CYCLE,
            "--balance-factors": ["0:1:0.5", "0,0.5", "0:inf:1", "0:2:0.01", "1:0:0.1", *NUMBERS],
            "--mass-scales": ["1", "0.5,1", *NUMBERS],
            "--format": FORMATS_CSV,
        },
    ),
    "torsional": Command(
        ["torsional"],
        [],
        ["--engine", "inline6", "--speed-points", "20"],
        {
            "--engine": ["inline6", "single", "v8-crossplane", "no-such-engine", ""],
            "--speed-min": SPEED,
            "--speed-max": quantity("speed", "6000 rpm"),
            "--speed-points": number("20", "2001", "2002"),
            "--highest-order": number("12", "0.5", "64", "65"),
            "--throw-inertia": quantity("inertia", "0.005 kg*m^2"),
            "--throw-stiffness": TORSIONAL_STIFFNESS,
            "--journal-diameter": quantity("length", "60 mm"),
            "--pin-diameter": quantity("length", "50 mm"),
            "--journal-length": quantity("length", "25 mm"),
            "--pin-length": quantity("length", "25 mm"),
            "--web-thickness": quantity("length", "20 mm"),
            "--web-width": quantity("length", "90 mm"),
            "--shear-modulus": quantity("modulus", "80 GPa"),
            "--front-inertia": quantity("inertia", "0.01 kg*m^2"),
            "--front-stiffness": TORSIONAL_STIFFNESS,
            "--flywheel-inertia": quantity("inertia", "0.15 kg*m^2"),
            "--flywheel-stiffness": TORSIONAL_STIFFNESS,
            "--damper-inertia": quantity("inertia", "0.004 kg*m^2"),
            "--damper-frequency": quantity("frequency", "330 Hz"),
            "--damper-damping-ratio": number("0.15", "0.5", "0.6"),
            "--damper-allowed-power": quantity("power", "200 W"),
            "--load-inertia": quantity("inertia", "0.5 kg*m^2"),
            "--load-stiffness": TORSIONAL_STIFFNESS,
            "--shaft-damping-ratio": number("0.02"),
            "--bore": quantity("length", "86 mm"),
            "--compression-ratio": number("13.5"),
            "--ignition": quantity("angle", "-25 deg"),
            "--burn-duration": quantity("angle", "50 deg"),
            "--intake-pressure": quantity("pressure", "1 bar"),
            "--heat-release": quantity("energy", "600 J"),
            "--fuel-mass": quantity("mass", "20 mg"),
            "--heating-value": quantity("specific_energy", "44 MJ/kg"),
            "--combustion-efficiency": number("0.8", "1"),
            "--gamma": number("1.3", "1.01", "1.67"),
            "--exhaust-pressure": quantity("pressure", "1.2 bar"),
            "--burn-end": ["complete", "stop", *CHOICE],
            "--pressure-csv": ENGINE_CYCLE["--pressure-csv"],
            "--plot": OUTPUT,
            "--format": FORMATS_CSV,
        },
    ),
    "mounts": Command(
        ["mounts"],
        [
            [
                str(ROOT / "examples" / "mounts_inline4_car.toml"),
                str(ROOT / "examples" / "mounts_vtwin_motorcycle.toml"),
                "inline4",
                "no-such-engine",
                "",
            ]
        ],
        ["--speed-samples", "20"],
        {
            "--speed-min": SPEED,
            "--speed-max": quantity("speed", "6000 rpm"),
            "--speed-samples": number("2", "20", "10001", "10002"),
            "--orders": number("1", "4", "64", "65"),
            "--mean-torque": quantity("torque", "120 N*m"),
            "--rotating": ["balanced", "bare", *CHOICE],
            "--point": ["0 mm, 330 mm, 260 mm", "1 mm, 2 mm", "nan mm, 0, 0", "1e300 m, 0, 0"],
            "--compare-pattern": [
                "all",
                "none",
                "file",
                "1,0,0,1,1,0,0,1",
                "1,1",
                "2,0",
                "0,0",
                "x",
            ],
            "--compare-balance-factors": ["0,0.5", "0:1:0.5", "0:inf:1", "0.5,0.5", *NUMBERS],
            "--compare-shafts": [FLAG],
            "--optimize": [
                "stiffness",
                "position",
                "stiffness, position",
                "stiffness, stiffness",
                *CHOICE,
            ],
            "--objective": ["force", "change", *CHOICE],
            "--stiffness-range": ["0.5, 2", "2, 0.5", "0, 1", "1", "1, 1e300", *NUMBERS],
            "--position-range": quantity("length", "10 mm"),
            "--frequency-band": [
                "5 Hz, 14 Hz",
                "14 Hz, 5 Hz",
                "5 Hz",
                "nan Hz, 1 Hz",
                "0 Hz, 1e300 Hz",
            ],
            "--roll-energy": number("70", "100", "101"),
            "--roll-axis-angle": quantity("angle", "10 deg", "90 deg", "91 deg"),
            "--optimize-iterations": number("1", "3", "500", "501"),
            "--quiet": [FLAG],
            "--gas-torque": [FLAG],
            "--bore": quantity("length", "86 mm"),
            "--compression-ratio": number("13.5"),
            "--ignition": quantity("angle", "-25 deg"),
            "--burn-duration": quantity("angle", "50 deg"),
            "--intake-pressure": quantity("pressure", "1 bar"),
            "--heat-release": quantity("energy", "600 J"),
            "--fuel-mass": quantity("mass", "20 mg"),
            "--heating-value": quantity("specific_energy", "44 MJ/kg"),
            "--combustion-efficiency": number("0.8", "1"),
            "--gamma": number("1.3", "1.01", "1.67"),
            "--exhaust-pressure": quantity("pressure", "1.2 bar"),
            "--burn-end": ["complete", "stop", *CHOICE],
            "--pressure-csv": ENGINE_CYCLE["--pressure-csv"],
            "--plot": OUTPUT,
            "--format": FORMATS,
        },
    ),
    "bearings": Command(
        ["bearings"],
        [["inline4", "single", "v8-crossplane", "no-such-engine", ""]],
        ["--samples", "72"],
        {
            "--format": FORMATS,
            **BEARING_LOADS,
            "--balance-factor": number("0.5", "50%"),
            "--webs": ["1,0,0,1,1,0,0,1", "1,1", "2,0,0,1,1,0,0,1", "0,0,0,0,0,0,0,0", *NUMBERS],
            **BEARING_CRANK,
            "--curves": [FLAG],
            "--plot": ["OUT/x.html", "OUT/x.txt", "/no/such/folder/x.svg", "OUT", ""],
        },
    ),
    "bearings-sweep": Command(
        ["bearings-sweep"],
        [["inline4", "single", "v8-crossplane", "no-such-engine", ""]],
        ["--samples", "36", "--balance-factors", "0.5"],
        {
            "--format": FORMATS_CSV,
            "--pattern": ["all", "none", "file", "1,0,0,1,1,0,0,1", "1,1", "2,0", "0,0", "", "x"],
            "--balance-factors": ["0.4,0.5", "0:1:0.5", "0:inf:1", "1:0:0.1", "0.5,0.5", *NUMBERS],
            "--crank-model": ["determinate", "indeterminate", "both", ""],
            **BEARING_LOADS,
            **BEARING_CRANK,
            "--plot": ["OUT/x.html", "OUT/x.txt", "/no/such/folder/x.svg", "OUT", ""],
        },
    ),
    "web": Command(
        ["web"],
        [],
        [],
        {
            "--port": number("8080", "65535"),
            "--preset": ["paper-inline3", "single", "no-such-engine", ""],
            "--show": [FLAG],
            "--no-show": [FLAG],
        },
    ),
    "plot": Command(
        ["plot"],
        [
            ["orders", "curves", "polar", "crank", "residuals", "single", "bad", ""],
            ["inline4", "single", "no-such-engine"],
        ],
        ["--output", "OUT/x.html"],
        {
            "--output": OUTPUT,
            "--order": number("1", "2", "rotating", "65"),
            "--quantity": ["force", "moment", *CHOICE],
            "--balance": [FLAG],
            "--no-balance": [FLAG],
            "--cylinder": number("1", "2"),
            "--balance-factor": number("0.5"),
            "--width": number("800"),
            "--height": number("600"),
        },
    ),
    "explore": Command(
        ["explore"],
        [],
        [],
        {
            "--layout": ["inline", "vee", "boxer", "w", *CHOICE],
            "--cylinders": number("4", "6"),
            "--strokes": ["2", "4", "3", *CHOICE],
            "--bank-angle": quantity("angle", "90 deg"),
            "--crank": ["any", "flat", "cross", "split", *CHOICE],
            "--engine": ["inline4", "no-such-engine", ""],
            "--target": ["none", "counterweights", "primary", "secondary", *CHOICE],
            "--balance-factor": number("0.5"),
            "--mode-shape": ["uniform", "linear", "1,0.5,0.5,1", "nan,1,1,1", *CHOICE],
            "--orders": number("4"),
            "--objectives": ["F1,M1", "M2,X2", "nonsense", "F1,,M1", ""],
            "--filter": ["F1 == 0", "M1 <= 1e-6 and F2 == 0", "F1 <", "__import__('os')", ""],
            "--top": number("3"),
            "--top-key": ["M2", "nonsense", ""],
            "--chunk": number("64"),
            # no valid worker count or scheduler: a cluster per example is too slow here
            # (tests/test_explore_run.py runs them)
            "--workers": ["0", "-1", "abc", ""],
            "--scheduler": ["", "not-an-address", "tcp://"],
            "--connect-timeout": quantity("time", "2 s"),
            "--sample": ["10", *NUMBERS],
            "--seed": number("1"),
            "--output": ["OUT/x.parquet", "/no/such/folder/x.parquet", "OUT", ""],
            "--plot": ["OUT/x.png", "OUT/x.html", "OUT/x.txt", "/no/such/folder/x.svg", ""],
            "--fixed-crank": ["0,180,180,0 deg", "0,180 deg", "nonsense", "0,180,180,nan deg"],
            "--mirror": [FLAG],
            "--no-mirror": [FLAG],
            "--reversal": [FLAG],
            "--list-orders": [FLAG],
            "--progress": [FLAG],
            "--no-progress": [FLAG],
            "--format": FORMATS_CSV,
        },
    ),
    **{
        f"shop {name}": Command(
            ["shop", name],
            [[V8_PARTS, "OUT/missing.csv", "OUT", ""]] if name != "plan" else [],
            (["--engine", "v8-crossplane"] if name != "plan" else [])
            + (["--method", "as-listed"] if name in ("match", "bobweights", "sheet") else [])
            + (SHOP_PLAN_BASE if name in ("plan", "sheet") else [])
            + (["--correction-planes", "-200 mm, 200 mm"] if name == "scatter" else [])
            + (["--output", "OUT/s.html"] if name == "sheet" else []),
            {**options, "--format": FORMATS} if name != "sheet" else options,
        )
        for name, options in SHOP.items()
    },
    "report": Command(
        ["report"],
        [["inline4", "single", "no-such-engine"]],
        ["--output", "OUT/r.html"],
        {
            "--output": OUTPUT,
            "--orders": number("4"),
            "--balance-factor": number("0.5"),
            "--angle": quantity("angle", "optimal", "30 deg"),
            "--chromium": ["/no/such/chromium", ""],
        },
    ),
}


def _leaf_commands() -> dict[str, click.Command]:
    """Every command and subcommand of the CLI, by its words."""
    ctx = click.Context(cli)
    out: dict[str, click.Command] = {}
    for name in COMMANDS:
        command = cli.get_command(ctx, name)
        assert command is not None
        if isinstance(command, click.Group):
            for sub in command.commands.values():
                out[f"{name} {sub.name}"] = sub
        else:
            out[name] = command
    return out


def test_every_command_and_option_is_fuzzed() -> None:
    """A new command or option must be added to the fuzz table."""
    leaves = _leaf_commands()
    assert set(COMMAND_TABLE) == set(leaves)
    for name, command in leaves.items():
        options = {
            opt
            for p in command.params
            if isinstance(p, click.Option)
            for opt in [*p.opts, *p.secondary_opts]
            if opt.startswith("--") and opt != "--help"
        }
        table = COMMAND_TABLE[name]
        positionals = [p for p in command.params if isinstance(p, click.Argument)]
        assert len(positionals) == len(table.positionals), name
        assert options == set(table.options), (name, options ^ set(table.options))


@st.composite
def invocations(draw: Any, name: str) -> list[str]:
    """One call of command ``name``: its positionals, the valid base options (mostly), then
    a random subset of its options with drawn values (a later option wins)."""
    table = COMMAND_TABLE[name]
    args = list(table.words)
    args += [draw(st.sampled_from(choices)) for choices in table.positionals]
    if draw(st.integers(0, 3)) < 3:  # the base three times in four (and in the simplest call)
        args += table.base
    chosen = draw(st.lists(st.sampled_from(sorted(table.options)), unique=True, max_size=4))
    for option in chosen:
        value = draw(st.sampled_from(table.options[option]))
        args += [option] if value is None else [option, value]
    return args


def run(args: list[str]) -> tuple[int, str, str]:
    """Run the CLI in this process; (exit status, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = int(main(args) or 0)
        except SystemExit as stop:
            code = stop.code if isinstance(stop.code, int) else 1
    return code, out.getvalue(), err.getvalue()


def assert_clean(
    call: list[str], code: int, out: str, err: str, echoed: Iterable[str] = ()
) -> None:
    """A run ended cleanly: exit 2 with one line ``error: ...`` on stderr, or exit 0 with
    no NaN or infinity in the output (``echoed``: texts of the input the output may repeat,
    such as a part's id ``nan``, left out of that search)."""
    lines = err.strip().splitlines()
    if code == 2:
        assert len(lines) == 1 and lines[0].startswith("error: "), (call, err)
        assert "Traceback" not in err
    else:
        assert code == 0, (call, code, err)
        for text in sorted(echoed, key=len, reverse=True):
            out = out.replace(text, "")
        assert not NON_FINITE.search(out), (call, out[:2000])


@pytest.fixture(scope="module")
def workspace() -> Iterator[Path]:
    """A folder with the files some options name: a pressure table and an STL part."""
    from crankbalance.io.cad import write_stl
    from crankbalance.physics.counterweight import CounterweightDesign

    with tempfile.TemporaryDirectory() as folder:
        root = Path(folder)
        (root / "p.csv").write_text(table_text(PRESSURE_ROWS))
        for name, rows in HOSTILE_TABLES.items():
            (root / f"p-{name.replace(' ', '-')}.csv").write_text(table_text(rows))
        overlong = "# " + "x" * (MAX_TABLE_BYTES // 2) + "\n"
        (root / "p-overlong.csv").write_text(2 * overlong + table_text(PRESSURE_ROWS))
        design = CounterweightDesign(0.02, 0.02, 0.35, 0.05, 2.1, 0.008, 8000.0)
        write_stl(design, root / "part.stl")
        yield root


TALLY: dict[str, dict[str, int]] = {}


@pytest.mark.parametrize("name", sorted(COMMAND_TABLE))
def test_fuzz_options(name: str, workspace: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import crankbalance.web.server

    # a valid `web` call would serve until stopped: it only records that it would serve
    monkeypatch.setattr(crankbalance.web.server, "serve", lambda **kwargs: None)
    tally = TALLY.setdefault(name, {"tried": 0, "clean": 0, "exit 0": 0, "exit 2": 0})

    @settings(
        max_examples=EXAMPLES,
        derandomize=True,
        database=None,
        deadline=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    )
    @given(args=invocations(name))
    def example(args: list[str]) -> None:
        with tempfile.TemporaryDirectory(dir=workspace) as folder:
            (Path(folder) / "p.csv").write_bytes((workspace / "p.csv").read_bytes())
            (Path(folder) / "part.stl").write_bytes((workspace / "part.stl").read_bytes())
            call = [a.replace("OUT", folder) for a in args]
            tally["tried"] += 1
            with hang_guard(HANG_GUARD):
                code, out, err = run(call)
            assert_clean(call, code, out, err)
            tally["clean"] += 1
            tally[f"exit {code}"] += 1

    example()
    print(
        f"\nfuzz options {name}: tried {tally['tried']}, clean {tally['clean']} "
        f"(exit 0: {tally['exit 0']}, exit 2: {tally['exit 2']})"
    )


# --------------------------------------------------------------------------- pressure tables
#: the commands that read a pressure table, with the options of a cheap valid call
TABLE_COMMANDS = {
    "bearings": ["bearings", "inline4", "--samples", "36"],
    "bearings-sweep": ["bearings-sweep", "inline4", "--samples", "36", "--balance-factors", "0.5"],
    "torsional": ["torsional", "--engine", "inline6", "--speed-points", "20"],
    "cycle --engine": ["cycle", "--engine", "single"],
    "sensitivity": ["sensitivity", "--engine", "single", "--balance-factors", "0,1"],
}
#: what a table's cell may be made: numbers out of range, not finite, not numbers at all
CELLS = [
    *("nan", "inf", "-inf", "1e300", "-1e300", "1e999", "-1", "0", "-0", "1e-320", "1000"),
    *("1000.0001", "-720", "720", "720.5", "9" * 400, "", " ", "abc", "1,5", "0x10", "1_000"),
    *(" 5 ", "+5", "\uff15", "1e", "--1", '"1"', "1\x00", "\x1b[31m1"),
]
#: a table as text: every row's cells joined by commas, rows by newlines
Table = list[list[str]]


def shifted(cell: str, by: float = 0.0, times: float = 1.0) -> str:
    """A cell's number times ``times`` plus ``by``; a cell that is no number is kept."""
    try:
        return repr(float(cell) * times + by)
    except ValueError:
        return cell


def mutate_cells(rows: Table, draw: Any) -> Table:
    for _ in range(draw(st.integers(1, 3))):
        row = draw(st.integers(1, len(rows) - 1))
        rows[row][draw(st.integers(0, 1))] = draw(st.sampled_from(CELLS))
    return rows


def mutate_scale(rows: Table, draw: Any) -> Table:
    factor = draw(st.sampled_from([1e300, 1e6, 1e3, 30.0, 10.0, 0.5, -1.0, 0.0, 1e-300, 1e-6]))
    column = draw(st.integers(0, 1))  # the pressures, or the angles
    return [rows[0]] + [
        [shifted(c, times=factor) if k == column else c for k, c in enumerate(r)] for r in rows[1:]
    ]


def mutate_order(rows: Table, draw: Any) -> Table:
    body = rows[1:]
    how = draw(st.sampled_from(["reverse", "swap", "duplicate", "shift", "sort by pressure"]))
    if how == "reverse":
        body.reverse()
    elif how == "swap":
        i, j = draw(st.integers(0, len(body) - 1)), draw(st.integers(0, len(body) - 1))
        body[i], body[j] = body[j], body[i]
    elif how == "duplicate":
        i = draw(st.integers(0, len(body) - 1))
        body.insert(i, list(body[i]))
    elif how == "shift":
        shift = draw(st.sampled_from([360.0, 720.0, -720.0, 1e-9, 400.0]))
        body = [[shifted(r[0], shift), *r[1:]] for r in body]
    else:
        body.sort(key=lambda r: r[-1])
    return [rows[0], *body]


def mutate_rows(rows: Table, draw: Any) -> Table:
    how = draw(st.sampled_from(["few", "two cycles", "fine", "header only", "no header"]))
    if how == "few":
        return rows[: draw(st.integers(0, 5))]
    if how == "two cycles":
        return rows + [[shifted(r[0], 720.0), *r[1:]] for r in rows[1:]]
    if how == "fine":  # a valid table of many rows (under the size limit)
        count = draw(st.sampled_from([721, 7201, 100_000, 250_000]))
        step = 720.0 / count
        return [rows[0]] + [
            [f"{-360 + k * step:.6f}", "41.0" if abs(-360 + k * step) < 20 else "1.0"]
            for k in range(count)
        ]
    return rows[:1] if how == "header only" else rows[1:]


def mutate_columns(rows: Table, draw: Any) -> Table:
    row = draw(st.integers(0, len(rows) - 1))
    how = draw(st.sampled_from(["extra", "missing", "empty row", "header"]))
    if how == "extra":
        rows[row] = [*rows[row], draw(st.sampled_from(["1", "", "x"]))]
    elif how == "missing":
        rows[row] = rows[row][:1]
    elif how == "empty row":
        rows.insert(row, [""])
    else:
        rows[0] = draw(
            st.sampled_from(
                [["pressure_bar", "angle_deg"], ["angle", "p"], ["1", "2"], ["", ""], ["a"] * 3]
            )
        )
    return rows


MUTATIONS = {
    "cells": mutate_cells,
    "scale": mutate_scale,
    "order": mutate_order,
    "rows": mutate_rows,
    "columns": mutate_columns,
}
#: the bytes a table's text may be damaged with, and where
BYTES = [b"\x00", b"\xff", b"\xef\xbb\xbf", b"\r\n", b"\r", b'"', b"\t", b"#", b",,", b"\n\n"]


@st.composite
def pressure_tables(draw: Any) -> tuple[list[str], bytes]:
    """(mutations, table bytes): the workspace's valid table with one to three mutations of
    its rows, then perhaps a few bytes inserted, or padded beyond the size limit."""
    rows: Table = [["angle_deg", "pressure_bar"]] + [[repr(a), repr(p)] for a, p in PRESSURE_ROWS]
    names = draw(st.lists(st.sampled_from(sorted(MUTATIONS)), min_size=1, max_size=2))
    for name in names:
        if len(rows) > 1:
            rows = MUTATIONS[name](rows, draw)
    raw = "".join(",".join(r) + "\n" for r in rows).encode("utf-8", "surrogatepass")
    how = draw(st.sampled_from(["none", "none", "insert", "overlong"]))
    if how == "insert":
        names.append("bytes")
        for _ in range(draw(st.integers(1, 3))):
            at = draw(st.integers(0, len(raw)))
            raw = raw[:at] + draw(st.sampled_from(BYTES)) + raw[at:]
    elif how == "overlong":
        names.append("overlong")
        raw = b"#" * MAX_TABLE_BYTES + b"\n" + raw
    return names, raw


TABLE_TALLY: dict[str, dict[str, int]] = {}


@pytest.mark.parametrize("name", list(TABLE_COMMANDS))
def test_fuzz_pressure_tables(name: str, tmp_path: Path) -> None:
    """Mutated pressure tables through every command that reads one: exit 2 with one line,
    or exit 0 with finite numbers."""
    tally = TABLE_TALLY.setdefault(name, {"tried": 0, "clean": 0, "exit 0": 0, "exit 2": 0})
    table = tmp_path / "p.csv"

    @settings(
        max_examples=EXAMPLES,
        derandomize=True,
        database=None,
        deadline=None,
        suppress_health_check=list(HealthCheck),
    )
    @given(case=pressure_tables())
    def example(case: tuple[list[str], bytes]) -> None:
        mutations, raw = case
        table.write_bytes(raw)
        call = [*TABLE_COMMANDS[name], "--pressure-csv", str(table)]
        tally["tried"] += 1
        with hang_guard(HANG_GUARD):
            code, out, err = run(call)
        assert_clean([*call, f"(table: {mutations}, {raw[:200]!r})"], code, out, err)
        tally["clean"] += 1
        tally[f"exit {code}"] += 1

    example()
    print(
        f"\nfuzz pressure tables {name}: tried {tally['tried']}, clean {tally['clean']} "
        f"(exit 0: {tally['exit 0']}, exit 2: {tally['exit 2']})"
    )


#: the commands that take a table per cylinder, for a two-cylinder engine
PER_CYLINDER = {
    "bearings": ["bearings", "inline2-360", "--samples", "36"],
    "bearings-sweep": ["bearings-sweep", "inline2-360", "--samples", "36"]
    + ["--balance-factors", "0.5"],
    "torsional": ["torsional", "--engine", "inline2-360", "--speed-points", "20"],
    "cycle --engine": ["cycle", "--engine", "inline2-360"],
}


@pytest.mark.parametrize("name", list(PER_CYLINDER))
def test_the_bad_table_of_several_is_named(name: str, workspace: Path, tmp_path: Path) -> None:
    """Found by this fuzzing: of two tables, the one too short or not a file was shown as
    the tuple of every file given (``--pressure-csv = ('p.csv', 'short.csv')``), so the
    line did not say which; torsional showed the settings' field ``pressure_csv``."""
    good, short, fifo = str(workspace / "p.csv"), str(workspace / "p-short.csv"), tmp_path / "f"
    os.mkfifo(fifo)
    for bad, allowed in [
        (short, "must hold at least 4 rows of: angle_deg, pressure_bar (found 3)"),
        (str(fifo), "is a pipe (FIFO), not a file"),
    ]:
        call = [*PER_CYLINDER[name], "--pressure-csv", good, "--pressure-csv", bad]
        code, _, err = run(call)
        assert code == 2 and err.startswith(f"error: --pressure-csv = {bad!r}: {allowed}"), err
        assert_clean(call, code, "", err)


def test_sensitivity_says_it_takes_one_table(workspace: Path) -> None:
    """Found by this fuzzing: ``sensitivity`` given two tables said it takes "0 to 1
    numbers, separated by commas"."""
    table = str(workspace / "p.csv")
    call = ["sensitivity", "--engine", "inline2-360", "--pressure-csv", table]
    code, _, err = run([*call, "--pressure-csv", table])
    assert code == 2
    assert err.rstrip().endswith("must be at most 1 file, the option given once for each"), err


@pytest.mark.parametrize("unit", ["oz", "lb", "ton", "grain"])
def test_a_huge_number_in_a_unit_pint_converts_is_one_line(unit: str) -> None:
    """Found by this fuzzing (a shop reading of 400 nines in oz): a number beyond a float
    in a unit outside crankbalance's own table went to pint as an integer, and pint's
    conversion raised OverflowError, a traceback; ``units.parse_quantity`` now refuses it
    first, as it did in g and kg."""
    huge = "9" * 400
    finite = "must be a finite mass, e.g. '500 g'"
    for call in (
        ["balance-factor", "--reciprocating-mass", f"{huge} {unit}", "--crank-radius", "27 mm"],
        ["shop", "plan", *SHOP_PLAN_BASE[2:], "--reading", f"{huge} {unit} @ 40 mm, 35 deg"],
    ):
        code, _, err = run(call)
        assert code == 2 and err.rstrip().endswith(finite), (call, err)
        assert_clean(call, code, "", err)
