"""The powertrain on its mounts as a study of the registry (``mounts``, docs/mounts.md).

The engine file's ``[powertrain]`` table (or a :class:`~crankbalance.physics.mounts.Powertrain`
given in Python) is the rigid body; the engine's free forces and moments of every order
(:func:`crankbalance.studies.engine.analyze`, about the crank's reference point), or those
of a given balancing (``forces``), drive it. The statics under weight and the mean torque,
the six modes with their kinetic-energy table and the torque-roll axis, the crossings of
the orders with the modes in the speed range, and the forced response with the force
every mount transmits.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..physics import mounts as pm
from ..physics import mounts_estimate as pe
from ..physics import mounts_optimize as po
from ..physics.model import EngineModel
from ..physics.shaking import FreeForces
from ..records import record
from ..results import ResultMixin, to_jsonable
from ..schema.engine import EngineSpec
from ..schema.engine import Powertrain as PowertrainTable
from ..schema.settings import MountsOptions
from .engine import EngineLike, analyze

if TYPE_CHECKING:
    from ..physics.balance_types import CounterweightOptions, ShaftOptions

SCHEMA = "crankbalance.mounts/1"
#: Most balancing choices of one comparison (:func:`compare`); each is one balancing and
#: one mount study.
MAX_CHOICES = 32
_RPM = 30.0 / math.pi  # rad/s -> rpm
#: A gas-torque harmonic below this fraction of the largest is round-off of the sum over
#: the cylinders (an order the firing cancels) and is taken as zero.
GAS_ROUND_OFF = 1e-9


def estimate_parts(table: PowertrainTable, model: EngineModel) -> tuple[pe.Part, ...]:
    """The parts of ``[powertrain.estimate]``: the block's box, the crank train's masses at
    their places (:func:`crankbalance.physics.mounts_estimate.crank_train_parts`) and the
    gearbox's box; empty without the table."""
    e = table.estimate
    if e is None:
        return ()
    parts = [pe.box_part("block", e.block_mass, e.block_size, e.block_center)]
    parts += pe.crank_train_parts(model)
    if e.gearbox_mass is not None and e.gearbox_size is not None and e.gearbox_center is not None:
        parts.append(pe.box_part("gearbox", e.gearbox_mass, e.gearbox_size, e.gearbox_center))
    return tuple(parts)


def powertrain_of(table: PowertrainTable, model: EngineModel | None = None) -> pm.Powertrain:
    """The physics' powertrain from the engine file's ``[powertrain]`` table (SI values);
    with ``[powertrain.estimate]`` its mass, centre of gravity and inertia are the sum of
    :func:`estimate_parts` (``model`` needed).

    Parameters
    ----------
    table : schema.engine.Powertrain
        The validated table.
    model : EngineModel, optional
        The engine's model, for an estimate.

    Returns
    -------
    physics.mounts.Powertrain
    """
    mounts = tuple(
        pm.Mount(
            name=m.name or f"mount {k + 1}",
            position=np.array(m.position, dtype=float),
            stiffness=np.array(m.stiffness, dtype=float),
            orientation=np.array(m.orientation or (0.0, 0.0, 0.0), dtype=float),
            loss_factor=float(m.loss_factor),
        )
        for k, m in enumerate(table.mount)
    )
    if table.estimate is not None:
        if model is None:
            raise ValueError("an estimated powertrain needs the engine's model")
        mass, cg, inertia = pe.combine(estimate_parts(table, model))
    else:
        assert table.mass is not None and table.cg is not None and table.inertia is not None
        mass, cg = float(table.mass), np.array(table.cg, dtype=float)
        inertia = pm.inertia_tensor(table.inertia, table.products or (0.0, 0.0, 0.0))
    return pm.Powertrain(
        mass=mass,
        cg=cg,
        inertia=inertia,
        mounts=mounts,
        up=np.array(table.up or (0.0, 0.0, 1.0), dtype=float),
    )


def spec_of(engine: EngineLike) -> EngineSpec | None:
    """The engine file's spec of a preset name, a path or a spec (read once); None for a
    built model, which has no ``[powertrain]``."""
    if isinstance(engine, EngineSpec):
        return engine
    if isinstance(engine, EngineModel):
        return None
    from ..io.engine_file import load_engine

    return load_engine(engine)


def engine_loads(forces: FreeForces, rotating: str) -> NDArray[np.complex128]:
    """The six load amplitudes of every order at the reference point (K, 6), the rotating
    masses' first order added when ``rotating == "bare"``."""
    ff, cf, roll = forces.force_forward.copy(), forces.couple_forward.copy(), forces.roll.copy()
    if rotating == "bare":
        ff[0] += forces.rotating_force
        cf[0] += forces.rotating_couple
        roll[0] += forces.rotating_roll
    return pm.order_loads(ff, forces.force_backward, cf, forces.couple_backward, roll)


@record(repr=False)
class MountsResult(ResultMixin):
    """The mount study of one engine.

    Attributes
    ----------
    name : str
        The engine's name.
    model : EngineModel
    powertrain : physics.mounts.Powertrain
    statics : physics.mounts.Statics
    modes : physics.mounts.Modes
    crossings : tuple of physics.mounts.Crossing
    response : physics.mounts.Response
    point : ndarray, shape (3,)
        The point whose displacement is shown [m].
    loads : ndarray of complex, shape (K, 6)
        The inertia load amplitudes of each order at the engine's speed [N], [N·m].
    comparison : tuple of (str, MountsResult)
        The balancing choices compared, when asked (``compare_*`` settings).
    optimum : physics.mounts.MountOptimum or None
        The mount optimiser's answer, when asked (``optimize``).
    optimum_modes : physics.mounts.Modes or None
        The modes of the optimised mounts.
    optimum_response : physics.mounts.Response or None
        The forced response of the optimised mounts on the study's speeds.
    parts : tuple of physics.mounts_estimate.Part
        The parts the powertrain was estimated from (``[powertrain.estimate]``), else empty.
    gas_loads : ndarray of complex, shape (K, 6), or None
        The gas torque's reaction of each order (``gas_torque``), the same at every speed
        [N·m]; ``loads`` then holds zeros at the half orders.
    settings : MountsOptions or None
        The settings of the run.
    """

    name: str
    model: EngineModel
    powertrain: pm.Powertrain
    statics: pm.Statics
    modes: pm.Modes
    crossings: tuple[pm.Crossing, ...]
    response: pm.Response
    point: NDArray[np.float64]
    loads: NDArray[np.complex128]
    comparison: tuple[tuple[str, MountsResult], ...] = ()
    optimum: po.MountOptimum | None = None
    optimum_modes: pm.Modes | None = None
    optimum_response: pm.Response | None = None
    parts: tuple[pe.Part, ...] = ()
    gas_loads: NDArray[np.complex128] | None = None
    settings: MountsOptions | None = None

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.mounts/1`` (SI units in the keys, speeds in rpm)."""
        out = to_jsonable({"schema": SCHEMA, **payload(self)})
        assert isinstance(out, dict)
        return out


def mounts(
    engine: EngineLike,
    settings: MountsOptions,
    powertrain: pm.Powertrain | None = None,
    forces: FreeForces | None = None,
    *,
    progress: Callable[[int, int, float], None] | None = None,
) -> MountsResult:
    """The powertrain of ``engine`` on its mounts: statics, modes, crossings and the forced
    response to the engine's free forces and moments; with the ``compare_*`` settings the
    same study under each balancing choice (:func:`compare`), with ``optimize`` the mount
    optimiser's answer (:func:`crankbalance.physics.mounts.optimize_mounts`; ``progress``
    is called after each of its generations with (generation, generations, best)).

    ``powertrain`` replaces the engine file's ``[powertrain]`` table; ``forces`` replaces the
    engine's free forces (those of a balancing, say: comparing balancing choices is a loop
    over them), taken about the model's reference point at its speed. The work is bounded
    before it starts (speed samples x orders at most
    :data:`~crankbalance.physics.mounts.MAX_RESPONSE_POINTS`).
    """
    o = settings
    refuse_combustion_without_gas(o)
    n_orders = o.orders * (2 if o.gas_torque else 1)  # a four-stroke's gas: half orders
    n_points = pm.response_size(o.speed_samples, n_orders)
    if n_points > pm.MAX_RESPONSE_POINTS:
        raise InputError(
            "speed_samples",
            o.speed_samples,
            f"speed samples x orders ({n_orders}) must be at most {pm.MAX_RESPONSE_POINTS}",
        )
    if powertrain is None:
        spec = spec_of(engine)
        if spec is None or spec.powertrain is None:
            raise InputError(
                "engine",
                getattr(engine, "name", engine),
                "needs a [powertrain] table with its mounts (docs/mounts.md)",
            )
        engine = spec
    analysis = analyze(engine, orders=o.orders)
    model = analysis.model
    parts: tuple[pe.Part, ...] = ()
    if powertrain is None:
        assert isinstance(engine, EngineSpec) and engine.powertrain is not None
        parts = estimate_parts(engine.powertrain, model)
        powertrain = powertrain_of(engine.powertrain, model)
    if o.optimize is not None:  # bounded before any work
        goals = goals_of(o)
        po.check_optimizer_work(powertrain, goals)
    if forces is None:
        forces = analysis.forces
    elif forces.orders.size < o.orders:
        raise InputError("orders", o.orders, f"the forces given have {forces.orders.size} orders")
    loads = engine_loads(forces, o.rotating)[: o.orders]
    high = o.speed_max if o.speed_max is not None else model.speed
    if high <= o.speed_min:
        raise InputError("speed_min", o.speed_min, "must be below the engine's speed")
    speeds = np.linspace(o.speed_min, high, o.speed_samples)
    orders = np.asarray(forces.orders[: o.orders], dtype=float)
    gas: NDArray[np.complex128] | None = None
    if o.gas_torque:
        orders, loads, gas = with_gas(model, o, orders, loads)
    statics = pm.statics(powertrain, o.mean_torque)
    modes = pm.modes(powertrain)
    response = pm.forced_response(powertrain, loads, orders, model.speed, speeds, gas)
    point = np.array(o.point if o.point is not None else powertrain.cg, dtype=float)
    comparison: tuple[tuple[str, MountsResult], ...] = ()
    if o.comparing():
        comparison = tuple(compare(engine, o, choices_of(engine, o), powertrain))
    optimum = optimum_modes = optimum_response = None
    if o.optimize is not None:
        coarse = np.linspace(o.speed_min, high, min(po.OPTIMIZER_SPEEDS, o.speed_samples))
        optimum = po.optimize_mounts(
            powertrain, goals, loads, orders, model.speed, coarse, progress=progress, gas=gas
        )
        optimum_modes = pm.modes(optimum.powertrain)
        optimum_response = pm.forced_response(
            optimum.powertrain, loads, orders, model.speed, speeds, gas
        )
    result = MountsResult(
        model.name,
        model,
        powertrain,
        statics,
        modes,
        pm.crossings(modes.frequencies, orders, o.speed_min, high),
        response,
        point,
        loads,
        comparison,
        optimum,
        optimum_modes,
        optimum_response,
        parts,
        gas,
        o,
    )
    result.to_dict()  # checked finite
    return result


def payload(r: MountsResult) -> dict[str, Any]:
    """The JSON of a mount study without its schema key."""
    pt, st, md, rs = r.powertrain, r.statics, r.modes, r.response
    names = [m.name for m in pt.mounts]
    speeds_rpm = rs.speeds * _RPM
    point = np.abs(rs.point(pt.cg, r.point))  # (S, K, 3)
    point_peak = pm.peak_magnitude(rs.point(pt.cg, r.point))
    orders = []
    for k, n in enumerate(rs.orders):
        per_mount: list[dict[str, Any]] = []
        for i, name in enumerate(names):
            s = int(np.argmax(rs.mount_peak[:, k, i]))
            per_mount.append(
                {
                    "mount": name,
                    "force_N": float(rs.mount_peak[s, k, i]),
                    "speed_rpm": float(speeds_rpm[s]),
                }
            )
        top = max(per_mount, key=lambda e: float(e["force_N"]))
        s = int(np.argmax(point_peak[:, k]))
        orders.append(
            {
                "order": order_number(n),
                "loads_at_engine_speed": dict(
                    zip(
                        ("fx_N", "fy_N", "fz_N", "mx_Nm", "my_Nm", "mz_Nm"),
                        (float(abs(v)) for v in r.loads[k]),
                        strict=True,
                    )
                ),
                "largest": top,
                "mounts": per_mount,
                "point_displacement_m": float(point_peak[s, k]),
                "point_xyz_m": [float(v) for v in point[s, k]],
                "point_speed_rpm": float(speeds_rpm[s]),
            }
        )
    out: dict[str, Any] = {
        "engine": {"name": r.name, "speed_rpm": r.model.speed * _RPM},
        "reference_point_m": list(r.model.moment_point),
        "powertrain": {
            "mass_kg": pt.mass,
            "cg_m": pt.cg,
            "inertia_kg_m2": pt.inertia,
            "up": pt.up / np.linalg.norm(pt.up),
        },
        "mounts": [
            {
                "name": m.name,
                "position_m": m.position,
                "stiffness_N_m": {
                    "compression": m.stiffness[0],
                    "shear1": m.stiffness[1],
                    "shear2": m.stiffness[2],
                },
                "orientation_deg": np.degrees(m.orientation),
                "loss_factor": m.loss_factor,
            }
            for m in pt.mounts
        ],
        "statics": {
            "mean_torque_Nm": -st.load[4],
            "cg_displacement_m": st.displacement[:3],
            "rotation_rad": st.displacement[3:],
            "mount_loads": [
                {
                    "mount": name,
                    "force_N": st.mount_loads[i],
                    "axial_N": st.mount_loads_local[i, 0],
                    "shear1_N": st.mount_loads_local[i, 1],
                    "shear2_N": st.mount_loads_local[i, 2],
                }
                for i, name in enumerate(names)
            ],
        },
        "modes": [
            {
                "mode": r_ + 1,
                "frequency_Hz": md.frequencies[r_],
                "energy_percent": dict(zip(pm.ENERGY_NAMES, md.energy[r_], strict=True)),
                "shape": dict(zip(pm.COORDINATES, md.shapes[:, r_], strict=True)),
            }
            for r_ in range(6)
        ],
        "torque_roll_axis": md.torque_roll_axis,
        "roll_mode": md.roll_mode + 1,
        "roll_mode_angle_to_torque_roll_axis_deg": math.degrees(md.roll_axis_angle),
        "crossings": [
            {"mode": c.mode + 1, "order": order_number(c.order), "speed_rpm": c.speed * _RPM}
            for c in r.crossings
        ],
        "point_m": r.point,
        "orders": orders,
        "sweep": {
            "speed_rpm": speeds_rpm,
            "mount_force_N": {
                name: {f"{n:g}": rs.mount_peak[:, k, i] for k, n in enumerate(rs.orders)}
                for i, name in enumerate(names)
            },
        },
    }
    if r.gas_loads is not None:
        from .performance import combustion_summary

        out["gas_torque"] = {
            "speed_dependence": "none: a pressure over the crank angle, the same at every speed",
            "combustion": combustion_summary(r.settings) if r.settings is not None else None,
            "roll_Nm": [
                {"order": order_number(n), "amplitude_Nm": float(abs(r.gas_loads[k, 4]))}
                for k, n in enumerate(rs.orders)
            ],
        }
    if r.parts:
        out["powertrain"]["estimated_from"] = [
            {"part": p.name, "mass_kg": p.mass, "centre_m": p.centre} for p in r.parts
        ]
    if r.comparison:
        out["comparison"] = comparison_table(list(r.comparison))
    if r.optimum is not None:
        out["optimum"] = optimum_payload(r)
    return out


def order_number(n: float) -> int | float:
    """An engine order as the JSON shows it: a whole number, or a half order as 0.5, 1.5."""
    return int(n) if float(n).is_integer() else float(n)


def with_gas(
    model: EngineModel,
    settings: MountsOptions,
    orders: NDArray[np.float64],
    loads: NDArray[np.complex128],
) -> tuple[NDArray[np.float64], NDArray[np.complex128], NDArray[np.complex128]]:
    """The orders of the engine's cycle up to ``settings.orders`` (half orders of a
    four-stroke), the inertia loads at them (zeros at the half orders) and the gas torque's
    reaction on the block: :math:`M_y = -\\mathrm{Re}\\sum_n G_n e^{in\\theta}` with
    :math:`G_n` the harmonics of the engine cycle's gas torque on the crank
    (:func:`crankbalance.physics.engine_cycle_all.engine_cycle_all` with the combustion of
    the settings, :func:`crankbalance.physics.torsional.order_harmonics` over the first
    throw's crank angle). The mean gas torque is not in it (``mean_torque`` is the statics').
    """
    from ..physics.engine_cycle_all import engine_cycle_all
    from ..physics.torsional import engine_orders, order_harmonics
    from .crank import rotating_inertia
    from .performance import pressure_source

    o = settings
    every = engine_orders(model.strokes, float(o.orders))
    # the gas torque does not depend on the speed or the crank's inertia (a pressure over
    # the crank angle); the cycle needs one to integrate its speed
    cycle = engine_cycle_all(
        model,
        pressure_source(o, model.cylinders, model.strokes),
        bore=o.bore if o.bore is not None else 2.0 * model.crank_radius,
        crank_inertia=rotating_inertia(model),
    )
    harmonics = order_harmonics(cycle.crank_angle, cycle.gas_torque, every)
    # orders the firing cancels come out of the sum as round-off: zero, as the free forces'
    harmonics[np.abs(harmonics) < GAS_ROUND_OFF * np.abs(harmonics).max(initial=0.0)] = 0.0
    gas = np.zeros((every.size, 6), dtype=complex)
    gas[:, 4] = -harmonics
    inertia = np.zeros((every.size, 6), dtype=complex)
    for k, n in enumerate(orders):
        inertia[int(np.argmin(np.abs(every - n)))] = loads[k]
    return np.asarray(every, dtype=float), inertia, gas


def refuse_combustion_without_gas(settings: MountsOptions) -> None:
    """A combustion setting given without ``gas_torque``, or a Wiebe setting beside
    pressure tables, would not act: refused, naming it."""
    from .performance import WIEBE_OPTIONS

    typed = settings.given()
    for name in (*WIEBE_OPTIONS, "pressure_csv", "bore"):
        if name in typed and not settings.gas_torque:
            raise InputError(name, getattr(settings, name), "only acts with --gas-torque")
    for name in WIEBE_OPTIONS:
        if name in typed and settings.pressure_csv:
            raise InputError(
                name, getattr(settings, name), "only acts on the Wiebe model, not with tables"
            )


def goals_of(settings: MountsOptions) -> po.MountGoals:
    """The mount optimiser's goals from the settings (``optimize`` given)."""
    o = settings
    low, high = o.stiffness_range
    return po.MountGoals(
        variables=tuple(o.optimize or ()),
        stiffness_range=(float(low), float(high)),
        position_range=float(o.position_range),
        band=None if o.frequency_band is None else (o.frequency_band[0], o.frequency_band[1]),
        roll_energy=o.roll_energy,
        roll_axis_angle=o.roll_axis_angle,
        objective=o.objective,
        iterations=o.optimize_iterations,
    )


def optimum_payload(r: MountsResult) -> dict[str, Any]:
    """The JSON of the mount optimiser's answer: the mounts found, the goals and their
    margins before and after, the modes and the largest mount force per order."""
    opt, md, rs = r.optimum, r.optimum_modes, r.optimum_response
    assert opt is not None and md is not None and rs is not None
    g = opt.goals
    scale = (
        np.exp(opt.variables[: len(r.powertrain.mounts)]) if "stiffness" in g.variables else None
    )
    return {
        "variables": list(g.variables),
        "objective": g.objective,
        "objective_before": opt.objective_before,
        "objective_after": opt.objective_after,
        "objective_unit": "N" if g.objective == "force" else "-",
        "goals": {
            "frequency_band_Hz": g.band,
            "roll_energy_percent": g.roll_energy,
            "roll_axis_angle_deg": None
            if g.roll_axis_angle is None
            else math.degrees(g.roll_axis_angle),
        },
        "margins_before": opt.margins_before,
        "margins_after": opt.margins_after,
        "feasible": opt.feasible,
        "evaluations": opt.evaluations,
        "generations": opt.generations,
        "mounts": [
            {
                "name": m.name,
                "position_m": m.position,
                "moved_m": m.position - r.powertrain.mounts[i].position,
                "stiffness_factor": None if scale is None else float(scale[i]),
                "stiffness_N_m": {
                    "compression": m.stiffness[0],
                    "shear1": m.stiffness[1],
                    "shear2": m.stiffness[2],
                },
            }
            for i, m in enumerate(opt.powertrain.mounts)
        ],
        "frequencies_Hz": md.frequencies,
        "roll_mode_energy_percent": md.energy[md.roll_mode, 3],
        "roll_mode_angle_to_torque_roll_axis_deg": math.degrees(md.roll_axis_angle),
        "largest_mount_force_N": {
            f"{n:g}": float(rs.mount_peak[:, k, :].max()) for k, n in enumerate(rs.orders)
        },
    }


# --------------------------------------------------------------------------- balancing choices
def balanced_forces(
    model: EngineModel,
    counterweights: CounterweightOptions | None,
    primary: ShaftOptions | None = None,
    secondary: ShaftOptions | None = None,
    orders: int = 4,
) -> FreeForces:
    """The free forces and moments an engine leaves with the balancing masses the solver
    finds for these options (:func:`crankbalance.physics.balance_solver.solve`), as one
    :class:`FreeForces` the mount study takes (``forces=``).

    The balancing masses (crank counterweights and balance shafts, all on the crank axis as
    the solver places them) change the forces and the couples; their roll about the
    reference point is the moment of their forces, :math:`qF` with :math:`q = p_x + ip_z`
    (zero about a point on the crank axis). The reciprocating roll is the engine's.
    """
    from ..physics.balance_solver import batch_of_one, residual_phasors, solve, solver_input
    from ..physics.balance_types import EngineFailed

    forces = analyze(model, orders=max(orders, 2)).forces
    inputs = solver_input(model, batch_of_one(forces))
    try:
        found = solve(inputs, counterweights, primary, secondary)
    except EngineFailed as failed:
        raise failed.error from None
    rot_f, rot_c, fwd, bwd, cfwd, cbwd = residual_phasors(
        inputs,
        found.counterweights,
        found.rotating_share,
        found.extra_counterweights,
        found.primary,
        found.secondary,
    )
    q = complex(model.reference_x, model.reference_z)
    added_f, added_b = fwd[0] - forces.force_forward, bwd[0] - forces.force_backward
    roll = forces.roll + q * added_f + np.conj(q * added_b)
    return FreeForces(
        orders=forces.orders,
        force_forward=fwd[0],
        force_backward=bwd[0],
        couple_forward=cfwd[0],
        couple_backward=cbwd[0],
        rotating_force=complex(rot_f[0]),
        rotating_couple=complex(rot_c[0]),
        roll=roll,
        rotating_roll=complex(q * rot_f[0]),
    )


@record
class Choice:
    """One balancing choice of a comparison at the mounts.

    Attributes
    ----------
    label : str
        Its name in the table.
    counterweights : CounterweightOptions or None
        Crank counterweights (None: a bare crank, the rotating masses left free).
    primary, secondary : ShaftOptions or None
        Balance shafts of order 1 and 2.
    """

    label: str
    counterweights: CounterweightOptions | None
    primary: ShaftOptions | None = None
    secondary: ShaftOptions | None = None


def compare(
    engine: EngineLike,
    settings: MountsOptions,
    choices: list[Choice],
    powertrain: pm.Powertrain | None = None,
) -> list[tuple[str, MountsResult]]:
    """The mount study of ``engine`` under each balancing choice: one loop over
    :func:`balanced_forces` and :func:`mounts` (the rotating masses as the balancing leaves
    them: ``settings.rotating`` is taken as ``bare``, the forces already hold the
    counterweights).

    Returns
    -------
    list of (label, MountsResult)
    """
    if not choices:
        raise InputError("choices", choices, "at least one balancing choice")
    if len(choices) > MAX_CHOICES:
        raise InputError("choices", len(choices), f"at most {MAX_CHOICES} balancing choices")
    spec = spec_of(engine)
    source: EngineLike = spec if spec is not None else engine
    model = analyze(source, orders=settings.orders).model
    bare = settings.replace(
        rotating="bare",
        compare_patterns=None,
        compare_balance_factors=None,
        compare_shafts=False,
        optimize=None,
    )
    out = []
    for choice in choices:
        forces = balanced_forces(
            model, choice.counterweights, choice.primary, choice.secondary, settings.orders
        )
        out.append((choice.label, mounts(source, bare, powertrain, forces=forces)))
    return out


def comparison_table(results: list[tuple[str, MountsResult]]) -> list[dict[str, Any]]:
    """One row per choice: the largest mount force of each order over the speed range,
    the mount and the speed [N], [rpm].

    Parameters
    ----------
    results : list of (label, MountsResult)
        From :func:`compare`.

    Returns
    -------
    list of dict
        ``{"choice", "order_<n>_N", "order_<n>_mount", "order_<n>_rpm", "largest_N"}``.
    """
    rows = []
    for label, result in results:
        row: dict[str, Any] = {"choice": label}
        for entry in payload(result)["orders"]:
            n = entry["order"]
            row[f"order_{n}_N"] = entry["largest"]["force_N"]
            row[f"order_{n}_mount"] = entry["largest"]["mount"]
            row[f"order_{n}_rpm"] = entry["largest"]["speed_rpm"]
        row["largest_N"] = float(result.response.mount_peak.max())
        rows.append(row)
    return rows


def choices_of(engine: EngineLike, settings: MountsOptions) -> list[Choice]:
    """The balancing choices of the ``compare_*`` settings: every counterweight pattern
    (``compare_patterns``, default the engine file's) with every balance factor
    (``compare_balance_factors``, default the engine file's), ``none`` once as a bare
    crank, each without and (``compare_shafts``) with the engine file's balance shafts;
    the other counterweight options are the engine file's (:func:`balance_options`)."""
    from dataclasses import replace

    from .engine import balance_options

    spec = spec_of(engine)
    if spec is None:
        raise InputError("engine", getattr(engine, "name", engine), "an engine file or preset")
    base, primary, secondary = balance_options(spec)
    if settings.compare_shafts and primary is None and secondary is None:
        raise InputError(
            "compare_shafts", True, "needs a [balance_shafts] table in the engine file"
        )
    patterns = settings.compare_patterns or ["file"]
    factors = settings.compare_balance_factors or [base.balance_factor]
    shafts = [False, True] if settings.compare_shafts else [False]
    count = len(shafts) * sum(1 if p == "none" else len(factors) for p in patterns)
    if count > MAX_CHOICES:
        raise InputError(
            "compare_patterns",
            ", ".join(patterns),
            f"with the balance factors and shafts must make at most {MAX_CHOICES} "
            f"balancing choices: here {count}",
        )
    out = []
    for pattern in patterns:
        for factor in [None] if pattern == "none" else factors:
            for on in shafts:
                words = "shafts" if on else ""
                if factor is None:
                    cw = None
                    label = "no counterweights"
                else:
                    webs = base.webs
                    if pattern == "all":
                        webs = None
                    elif pattern != "file":
                        webs = tuple(int(v) for v in pattern.split(","))
                    cw = replace(base, webs=webs, balance_factor=float(factor))
                    label = f"{pattern} bf {float(factor):g}"
                label = f"{label}, {words}" if words else label
                out.append(Choice(label, cw, primary if on else None, secondary if on else None))
    return out
