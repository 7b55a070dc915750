"""``crankbalance mounts``: the powertrain on its elastic mounts (docs/mounts.md).

The engine file's ``[powertrain]`` table: statics under weight and the mean torque, the six
rigid-body modes with their kinetic-energy table and the torque-roll axis, the crossings of
the engine orders with the modes, and the force every mount transmits over the speed range.
"""

from __future__ import annotations

import math
from typing import Any

import click

from ..output.format import json_text
from ._common import echo_table, format_option, run_study, study_options
from .plot import check_figure, write_figure


@click.command()
@click.argument("engine")
@study_options("mounts")
@click.option(
    "--plot",
    type=click.Path(dir_okay=False),
    help="Campbell diagram and mount forces over speed (.png, .svg or .html).",
)
@click.option("--quiet", is_flag=True, help="No progress of the mount optimiser on stderr.")
@format_option(("table", "json"))
def mounts(engine: str, fmt: str, plot: str | None, quiet: bool, **values: Any) -> None:
    """The powertrain of ENGINE (an engine file with a [powertrain] table) on its mounts.

    Prints the static deflection and each mount's load under the weight and --mean-torque,
    the six rigid-body modes with the share of each mode's kinetic energy in x, y, z, roll
    (about the crank axis), pitch (about x) and yaw (about z), the torque-roll axis and the
    roll mode's angle to it, the engine orders crossing a mode in the speed range, and per
    order the largest force a mount transmits and the speed where it occurs. With
    --compare-pattern, --compare-balance-factors or --compare-shafts, the largest mount
    force of each order under each balancing choice; with --optimize, the mount optimiser's
    stiffnesses or positions toward the goals (--frequency-band, --roll-energy,
    --roll-axis-angle, --objective).
    """
    if plot is not None:
        check_figure(plot)

    def progress(generation: int, generations: int, best: float) -> None:
        if not quiet:
            shown = f"best {best:.6g}" if math.isfinite(best) else "no layout meets the goals yet"
            click.echo(
                f"\rmount optimiser: generation {generation}/{generations}  {shown}   ",
                err=True,
                nl=False,
            )

    result = run_study("mounts", engine, values, engine_option=False, progress=progress)
    if result.optimum is not None and not quiet:
        click.echo("", err=True)
    data = result.to_dict()
    if plot is not None:
        from ..output.figures.mounts import mounts_figure

        write_figure(plot, mounts_figure(result))
    if fmt == "json":
        click.echo(json_text(data))
        return
    _echo(data)


def _echo(d: dict[str, Any]) -> None:
    pt = d["powertrain"]
    click.echo(
        f"{d['engine']['name']}: powertrain {pt['mass_kg']:.4g} kg on {len(d['mounts'])} mounts"
    )
    parts = pt.get("estimated_from")
    if parts:
        crank = sum(p["mass_kg"] for p in parts if p["part"] not in ("block", "gearbox"))
        boxes = [
            f"{p['part']} {p['mass_kg']:.4g} kg" for p in parts if p["part"] in ("block", "gearbox")
        ]
        c, i = pt["cg_m"], pt["inertia_kg_m2"]
        click.echo(
            f"Estimated ([powertrain.estimate]) from {', '.join(boxes)} and the crank train's "
            f"masses {crank:.3g} kg: centre of gravity {1e3 * c[0]:+.1f}, {1e3 * c[1]:+.1f}, "
            f"{1e3 * c[2]:+.1f} mm; Ixx, Iyy, Izz {i[0][0]:.3g}, {i[1][1]:.3g}, {i[2][2]:.3g} "
            f"kg·m²; Ixy, Iyz, Ixz {i[0][1]:.3g}, {i[1][2]:.3g}, {i[0][2]:.3g} kg·m²"
        )
    st = d["statics"]
    u, t = st["cg_displacement_m"], st["rotation_rad"]
    click.echo(
        f"Statics (weight, mean torque {st['mean_torque_Nm']:.4g} N·m): centre of gravity "
        f"moves x {1e3 * u[0]:+.3f}, y {1e3 * u[1]:+.3f}, z {1e3 * u[2]:+.3f} mm; rotation "
        f"x {1e3 * t[0]:+.3f}, y {1e3 * t[1]:+.3f}, z {1e3 * t[2]:+.3f} mrad"
    )
    echo_table(
        ["mount", "Fx [N]", "Fy [N]", "Fz [N]", "axial [N]", "shear 1 [N]", "shear 2 [N]"],
        [
            [
                m["mount"],
                *(f"{v:+.1f}" for v in m["force_N"]),
                f"{m['axial_N']:+.1f}",
                f"{m['shear1_N']:+.1f}",
                f"{m['shear2_N']:+.1f}",
            ]
            for m in st["mount_loads"]
        ],
    )
    click.echo("Rigid-body modes (kinetic energy, per cent):")
    echo_table(
        ["mode", "f [Hz]", "x", "y", "z", "roll", "pitch", "yaw"],
        [
            [str(m["mode"]), f"{m['frequency_Hz']:.2f}"]
            + [_percent(v) for v in m["energy_percent"].values()]
            for m in d["modes"]
        ],
    )
    a = d["torque_roll_axis"]
    click.echo(
        f"Torque-roll axis ({a[0]:+.3f}, {a[1]:+.3f}, {a[2]:+.3f}); the roll mode (mode "
        f"{d['roll_mode']}) turns {d['roll_mode_angle_to_torque_roll_axis_deg']:.1f} deg "
        "from it"
    )
    if d["crossings"]:
        click.echo(
            "Orders crossing a mode in the speed range: "
            + ", ".join(
                f"order {c['order']} x mode {c['mode']} at {c['speed_rpm']:.0f} rpm"
                for c in d["crossings"]
            )
        )
    else:
        click.echo("No order crosses a mode in the speed range.")
    click.echo("Largest mount force per order over the speed range:")
    echo_table(
        ["order", "mount", "force [N]", "at [rpm]", "point moves [mm]", "at [rpm]"],
        [
            [
                str(o["order"]),
                o["largest"]["mount"],
                f"{o['largest']['force_N']:.4g}",
                f"{o['largest']['speed_rpm']:.0f}",
                f"{1e3 * o['point_displacement_m']:.4g}",
                f"{o['point_speed_rpm']:.0f}",
            ]
            for o in d["orders"]
        ],
    )
    if "comparison" in d:
        _echo_comparison(d["comparison"], [o["order"] for o in d["orders"]])
    if "optimum" in d:
        _echo_optimum(d["optimum"])


def _echo_comparison(rows: list[dict[str, Any]], orders: list[int]) -> None:
    click.echo("Balancing choices at the mounts (largest mount force per order, its mount, rpm):")
    echo_table(
        ["choice", *(f"order {n} [N]" for n in orders), "largest [N]"],
        [
            [
                row["choice"],
                *(
                    f"{row[f'order_{n}_N']:.4g} {row[f'order_{n}_mount']} "
                    f"{row[f'order_{n}_rpm']:.0f}"
                    for n in orders
                ),
                f"{row['largest_N']:.4g}",
            ]
            for row in rows
        ],
    )


def _echo_optimum(o: dict[str, Any]) -> None:
    unit = " N" if o["objective_unit"] == "N" else ""
    state = "every goal met" if o["feasible"] else "NOT every goal met"
    click.echo(
        f"Mount optimiser ({', '.join(o['variables'])}; objective {o['objective']}): "
        f"{o['objective_before']:.4g}{unit} -> {o['objective_after']:.4g}{unit}, {state} "
        f"({o['evaluations']} evaluations, {o['generations']} generations)"
    )
    for name, after in o["margins_after"].items():
        before = o["margins_before"][name]
        click.echo(f"  goal {name}: margin {_margin(before)} -> {_margin(after)}")
    echo_table(
        ["mount", "stiffness x", "moved x, y, z [mm]", "compression [N/mm]"],
        [
            [
                m["name"],
                "-" if m["stiffness_factor"] is None else f"{m['stiffness_factor']:.3f}",
                ", ".join(f"{1e3 * v:+.1f}" for v in m["moved_m"]),
                f"{m['stiffness_N_m']['compression'] / 1e3:.1f}",
            ]
            for m in o["mounts"]
        ],
    )
    click.echo(
        "  frequencies [Hz]: "
        + ", ".join(f"{f:.2f}" for f in o["frequencies_Hz"])
        + f"; roll mode {o['roll_mode_energy_percent']:.1f} % roll, "
        f"{o['roll_mode_angle_to_torque_roll_axis_deg']:.1f} deg from the torque-roll axis"
    )


def _percent(value: float) -> str:
    """A share in per cent to 0.1, a rounded negative zero as 0.0 (products of inertia give
    a rotation's share a small negative part)."""
    shown = f"{value:.1f}"
    return "0.0" if shown == "-0.0" else shown


def _margin(value: float) -> str:
    """A goal's margin to three digits, a round-off of the local search (|v| < 1e-6) as 0."""
    return "+0" if abs(value) < 1e-6 else f"{value:+.3g}"
