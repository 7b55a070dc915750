"""``crankbalance analyze`` and ``crankbalance presets``."""

from __future__ import annotations

import math
from typing import Any

import click

from ..output.format import json_text, moment_point, number, plural, text
from ._common import echo_notes, echo_table, format_option, run_study, study_options


@click.command()
@click.argument("engine")
@format_option(("table", "json", "csv"))
@study_options("analyze")
def analyze(engine: str, fmt: str, **values: Any) -> None:
    """Free forces and moments of ENGINE (an engine file or a preset name)."""
    result = run_study("analyze", engine, values, engine_option=False)
    if fmt == "json":
        click.echo(json_text(result.to_dict()))
        return
    if fmt == "csv":
        click.echo(curves_csv(result), nl=False)
        return
    data = result.to_dict()
    e = data["engine"]
    click.echo(f"{e['name']}")
    click.echo(
        f"{plural(e['cylinders'], 'cylinder')} on {plural(e['throws'], 'throw')}, "
        f"{text(e['speed_rad_s'], 'speed')}, "
        f"r/l = {number(e['rod_ratio'])}, kinematics: {e['kinematics']}"
    )
    for key, words in (
        ("cylinder_offset_m", "Offset per cylinder"),
        ("cylinder_axial_m", "Rod position on its pin per cylinder"),
    ):
        if any(e[key]):
            click.echo(f"{words}: " + ", ".join(text(v, "length") for v in e[key]))
    if "firing_order_maker" in e:
        pairs = sorted(zip(e["maker_number"], range(1, e["cylinders"] + 1), strict=True))
        click.echo(
            "Firing order " + "-".join(map(str, e["firing_order_maker"])) + " in the maker's "
            "numbering, " + "-".join(map(str, e["firing_order"])) + " in crankbalance's "
            "(maker's cylinder: crankbalance's " + ", ".join(f"{a}: {b}" for a, b in pairs) + ")"
        )
    elif "firing_order" in e:
        click.echo("Firing order " + "-".join(map(str, e["firing_order"])))
    click.echo(_firing_text(result.model))
    if "articulated" in e:
        art = e["articulated"]
        click.echo(
            f"Master-and-link rods: master cylinder {art['master_cylinder']}, link pins at "
            f"{text(max(art['link_pin_radius_m']), 'length')}; strokes "
            + _distinct([1e3 * s for s in art["stroke_m"]])
            + " mm"
        )
    masses = data["masses"]
    click.echo(
        "Masses: reciprocating per cylinder "
        + _distinct(masses["reciprocating_kg"])
        + " kg; rotating per throw (at the crank radius, big ends included) "
        + _distinct(masses["rotating_kg"])
        + " kg"
    )
    rods = masses["conrods"]
    if len({(r["mass_kg"], r["rotating_kg"], r["inertia_error_kg_m2"]) for r in rods}) == 1:
        rods = rods[:1]  # all conrods alike: show one
    for rod in rods:
        line = (
            f"Conrod {rod['cylinder']}: {text(rod['mass_kg'], 'mass')} = "
            f"{text(rod['rotating_kg'], 'mass')} at the big end + "
            f"{text(rod['reciprocating_kg'], 'mass')} at the small end; two-mass inertia "
            f"{text(rod['inertia_two_mass_kg_m2'], 'inertia')}"
        )
        if rod["inertia_error_kg_m2"] is not None:
            line += f" (error {text(rod['inertia_error_kg_m2'], 'inertia')} against the real one)"
        click.echo(line)
    click.echo(
        "Free forces and moments of the reciprocating masses "
        f"(moments about {moment_point(e['moment_point_m'])}; roll: about y):"
    )
    rows = [
        [
            str(f["order"]),
            number(f["amplitude_N"]),
            number(f["forward_N"]),
            number(f["backward_N"]),
            number(m["amplitude_Nm"]),
            number(m["forward_Nm"]),
            number(m["backward_Nm"]),
            number(y["amplitude_Nm"]),
        ]
        for f, m, y in zip(
            data["free_forces"], data["free_moments"], data["roll_moments"], strict=True
        )
    ]
    echo_table(
        ["order", "force N", "fwd N", "bwd N", "moment N·m", "fwd N·m", "bwd N·m", "roll N·m"],
        rows,
    )
    rot = data["rotating"]
    roll = f", roll {text(rot['roll_Nm'], 'moment')}" if rot["roll_Nm"] else ""
    click.echo(
        "Rotating masses (bare crank, no counterweights): "
        f"force {text(rot['force_N'], 'force')}, moment {text(rot['moment_Nm'], 'moment')}" + roll
    )
    echo_notes(engine)


def _firing_text(model: Any) -> str:
    """The firing intervals in words: "Firing intervals 180-180-180-180° (crank angle from
    each cylinder of the order to the next)", and for an engine without a firing order the
    order they assume."""
    from ..errors import InputError
    from ..studies.engine import firing

    try:
        order, intervals = firing(model)
    except InputError as error:  # no order given and too many firings to try
        return f"Firing intervals not derived: {error.allowed}"
    steps = "-".join(number(math.degrees(a)) for a in intervals)
    text = f"Firing intervals {steps}° (crank angle from each cylinder of the order to the next"
    if not model.firing_order_given:
        text += "; no firing order given: the most even this crank allows, order "
        text += "-".join(map(str, order))
    return text + ")"


def _distinct(values: list[float]) -> str:
    """One value if all are equal, else the list (for per-cylinder masses)."""
    if max(values) - min(values) <= 1e-12 * max(abs(v) for v in values):
        return number(values[0])
    return "[" + ", ".join(number(v) for v in values) + "]"


def curves_csv(result: object) -> str:
    """CSV of the curves: crank angle, each order's components, total and rotating."""
    from ..studies.engine import Analysis

    assert isinstance(result, Analysis)
    c = result.curves()
    header = ["crank_angle_deg"]
    columns = [c.angle * 180 / 3.141592653589793]
    for k, order in enumerate(c.orders):
        header += [
            f"fx_{order}_N",
            f"fz_{order}_N",
            f"mx_{order}_Nm",
            f"my_{order}_Nm",
            f"mz_{order}_Nm",
        ]
        columns += [c.fx[k], c.fz[k], c.mx[k], c.my[k], c.mz[k]]
    header += [
        "fx_total_N",
        "fz_total_N",
        "mx_total_Nm",
        "my_total_Nm",
        "mz_total_Nm",
        "fx_rotating_N",
        "fz_rotating_N",
        "mx_rotating_Nm",
        "my_rotating_Nm",
        "mz_rotating_Nm",
    ]
    columns += [
        c.total_fx,
        c.total_fz,
        c.total_mx,
        c.total_my,
        c.total_mz,
        c.rotating_fx,
        c.rotating_fz,
        c.rotating_mx,
        c.rotating_my,
        c.rotating_mz,
    ]
    from ..results import below_round_off, require_finite, round_off

    require_finite(dict(zip(header, columns, strict=True)), "curves")
    # what is at most the engine's round-off is 0, as in the text and the JSON (no 6.9e-14,
    # no -0)
    force, moment = round_off(result.model)
    columns = [columns[0]] + [
        below_round_off(c, moment if name.endswith("_Nm") else force) + 0.0
        for name, c in zip(header[1:], columns[1:], strict=True)
    ]
    lines = [",".join(header)]
    for row in zip(*columns, strict=True):
        lines.append(",".join(f"{v:.9g}" for v in row))
    return "\n".join(lines) + "\n"


@click.command()
@format_option(("table", "json"))
def presets(fmt: str) -> None:
    """List the built-in engines (use a name wherever an engine file is expected)."""
    from ..studies.engine import preset_titles, presets_listing

    if fmt == "json":
        click.echo(json_text(presets_listing()))
        return
    echo_table(["preset", "engine"], [[name, title] for name, title in preset_titles()])
