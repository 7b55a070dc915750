"""``crankbalance analyze`` and ``crankbalance presets``."""

from __future__ import annotations

import json

import click

from ._common import echo_table, format_option, option_name


@click.command()
@click.argument("engine")
@format_option(("table", "json", "csv"))
@click.option("--orders", default="8", show_default=True, help="Highest harmonic order (1-64).")
def analyze(engine: str, fmt: str, orders: str) -> None:
    """Free forces and moments of ENGINE (an engine file or a preset name)."""
    from ..options import AnalysisOptions, parse_options
    from ..studies.engine import analyze as run

    result = run(engine, parse_options(AnalysisOptions, {"orders": orders}, option_name).orders)
    if fmt == "json":
        click.echo(json.dumps(result.to_dict(), indent=2))
        return
    if fmt == "csv":
        click.echo(curves_csv(result), nl=False)
        return
    data = result.to_dict()
    e = data["engine"]
    click.echo(f"{e['name']}")
    click.echo(
        f"{e['cylinders']} cylinders on {e['throws']} throws, {e['speed_rpm']:.0f} rpm, "
        f"r/l = {e['rod_ratio']:.4f}, kinematics: {e['kinematics']}"
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
    if len({(r["mass"], r["rotating"], r["inertia_error"]) for r in rods}) == 1:
        rods = rods[:1]  # all conrods alike: show one
    for rod in rods:
        line = (
            f"Conrod {rod['cylinder']}: {rod['mass'] * 1e3:.1f} g = "
            f"{rod['rotating'] * 1e3:.1f} g at the big end + "
            f"{rod['reciprocating'] * 1e3:.1f} g at the small end; two-mass inertia "
            f"{rod['inertia_two_mass'] * 1e6:.0f} kg*mm^2"
        )
        if rod["inertia_error"] is not None:
            line += f" (error {rod['inertia_error'] * 1e6:+.0f} kg*mm^2 against the real one)"
        click.echo(line)
    click.echo(
        "Free forces and moments of the reciprocating masses "
        "(moments about the crankshaft mid-point):"
    )
    rows = [
        [
            str(f["order"]),
            f"{f['amplitude_N']:.4g}",
            f"{f['forward_N']:.4g}",
            f"{f['backward_N']:.4g}",
            f"{m['amplitude_Nm']:.4g}",
            f"{m['forward_Nm']:.4g}",
            f"{m['backward_Nm']:.4g}",
        ]
        for f, m in zip(data["free_forces"], data["free_moments"], strict=True)
    ]
    echo_table(["order", "force N", "fwd N", "bwd N", "moment N·m", "fwd N·m", "bwd N·m"], rows)
    rot = data["rotating"]
    click.echo(
        f"Rotating masses (bare crank, no counterweights): force {rot['force_N']:.4g} N, "
        f"moment {rot['moment_Nm']:.4g} N·m"
    )


def _distinct(values: list[float]) -> str:
    """One value if all are equal, else the list (for per-cylinder masses)."""
    if max(values) - min(values) <= 1e-12 * max(abs(v) for v in values):
        return f"{values[0]:.4g}"
    return "[" + ", ".join(f"{v:.4g}" for v in values) + "]"


def curves_csv(result: object) -> str:
    """CSV of the curves: crank angle, each order's components, total and rotating."""
    from ..studies.engine import Analysis

    assert isinstance(result, Analysis)
    c = result.curves()
    header = ["crank_angle_deg"]
    columns = [c.angle * 180 / 3.141592653589793]
    for k, order in enumerate(c.orders):
        header += [f"fx_{order}_N", f"fz_{order}_N", f"mx_{order}_Nm", f"mz_{order}_Nm"]
        columns += [c.fx[k], c.fz[k], c.mx[k], c.mz[k]]
    header += [
        "fx_total_N",
        "fz_total_N",
        "mx_total_Nm",
        "mz_total_Nm",
        "fx_rotating_N",
        "fz_rotating_N",
        "mx_rotating_Nm",
        "mz_rotating_Nm",
    ]
    columns += [
        c.total_fx,
        c.total_fz,
        c.total_mx,
        c.total_mz,
        c.rotating_fx,
        c.rotating_fz,
        c.rotating_mx,
        c.rotating_mz,
    ]
    lines = [",".join(header)]
    for row in zip(*columns, strict=True):
        lines.append(",".join(f"{v:.9g}" for v in row))
    return "\n".join(lines) + "\n"


@click.command()
@format_option(("table", "json"))
def presets(fmt: str) -> None:
    """List the built-in engines (use a name wherever an engine file is expected)."""
    from ..io.engine_file import list_presets, load_engine

    names = list_presets()
    if fmt == "json":
        click.echo(
            json.dumps(
                {
                    "schema": "crankbalance.presets/1",
                    "presets": [{"name": n, "title": load_engine(n).name} for n in names],
                },
                indent=2,
            )
        )
        return
    echo_table(["preset", "engine"], [[n, load_engine(n).name] for n in names])
