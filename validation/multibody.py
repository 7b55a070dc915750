r"""Cross-check of crankbalance's free forces and moments with an EXUDYN multibody model.

From an :class:`~crankbalance.physics.model.EngineModel` this builds a 3-D multibody model of the
same crank train in EXUDYN (Gerstmayr's open-source multibody code, PyPI ``exudyn``):

- the crank, one rigid body: a shaft on the crank axis (y) plus, at each throw, a point
  mass at the crank radius carrying the throw's rotating mass less the big ends of the
  rods on it (those are in the rods). Two main bearings hold it (a ball joint at
  :math:`y = -L` and a joint free along y at :math:`y = +L`); a third joint prescribes
  its rotation about y: a smooth start from rest over the first revolution (the angular
  acceleration a cosine bump, zero at both ends), then constant speed;
- each conrod, a rigid body with the two-mass-equivalent distribution crankbalance
  assumes: its mass :math:`m` with the centre of gravity at :math:`d` from the big end and
  the moment of inertia :math:`m\,d\,(l - d)` about it (so rod and two-mass pair have the
  same mass, centre and inertia: the same mechanism); a revolute joint on the crankpin at
  the rod's axial position;
- each piston (piston, wrist pin: the cylinder's reciprocating mass less the rod's
  small-end share), a body on a prismatic joint to the ground along its bank axis, its
  path offset sideways by the cylinder's offset (crank offset plus wrist-pin offset,
  positive toward where the crankpin moves after top dead centre); the rod's small end
  is held to it in the rod's plane (two constraints, so the closed loop is not
  overconstrained).

The reaction forces of every joint to the ground, and the moments of those forces about
the crankshaft mid-point (y = 0) plus the joints' reaction torques, summed, are the
shaking force and moment the crank train puts on the block. The roll moment about y
(issue 27) is that sum's y part without the drive (whose torque goes to the driven
machine), each piston's side force taken where the piston is. Over the last revolution
(uniform steps of the constant-speed part), their Fourier series gives, by order, the
forward and backward phasors of :math:`F_z + iF_x` and of the couple
:math:`C = -i\,(M_z + iM_x)`, the convention of :mod:`crankbalance.physics.shaking`; they are
compared with :func:`crankbalance.physics.shaking.free_forces` (its order-1 forward phasors with
the rotating masses' force and couple added, since the multibody model has both).

Acceptance (issue 17): each order's force and moment amplitude :math:`|X^+| + |X^-|`
within 0.5 % of crankbalance's, or within 1e-4 of the largest first-order amplitude where
the order is smaller; the phasors themselves (phase and sense of rotation) are held to
the same limit. Where an engine is balanced in the first order, "the largest first-order
amplitude" is that of one cylinder or throw (:func:`first_order_scales`).

Usage::

    python validation/multibody.py                       # every engine, summary
    python validation/multibody.py --write validation/results.md   # the results table
    python validation/multibody.py --convergence v2-45   # error against steps per revolution

``docs/validation.md`` describes the model, the checks and the step-size convergence.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from crankbalance.io.engine_file import parse_engine_text, preset_text
from crankbalance.physics.model import EngineModel
from crankbalance.physics.shaking import FreeForces, free_forces
from crankbalance.studies.build import build_model

#: the default steps per revolution: the error of generalized-alpha falls as the square of
#: the step (docs/validation.md); at 240 the order-n phasors are within about
#: (2 pi n / 240)**2 / 6 of the exact ones, 1.1e-4 for the first order
STEPS = 240
ORDERS = 8
#: acceptance of issue 17: relative to the order's own amplitude, and the floor as a
#: fraction of the largest first-order amplitude
RELATIVE = 5e-3
FLOOR = 1e-4


# --------------------------------------------------------------------------- engines
def _engine(text: str) -> EngineModel:
    return build_model(parse_engine_text(text, source="validation engine"))


def _desaxe_single() -> EngineModel:
    text = preset_text("single").replace(
        'rod_length = "110 mm"', 'rod_length = "110 mm"\ncrank_offset = "6 mm"\npin_offset = "2 mm"'
    )
    text = text.replace(
        'name = "Single cylinder, four-stroke (motorcycle)"', 'name = "desaxe single"'
    )
    return _engine(text)


def _side_by_side_twin() -> EngineModel:
    """The 45 deg twin of the preset with its two rods side by side on the pin, 20 mm apart
    (as a Ducati's), by the engine file's ``rod_positions``."""
    return _engine(
        preset_text("v2-45")
        .replace('name = "V-twin 45 deg, common crankpin"', 'name = "v2-45 side-by-side"')
        .replace(
            'bank_angle = "45 deg"', 'bank_angle = "45 deg"\nrod_positions = ["-10 mm", "10 mm"]'
        )
    )


#: presets run as they are: name: what each checks
PRESETS: dict[str, str] = {
    "inline4": "flat-crank inline-4 (preset)",
    "v8-crossplane": "90 deg crossplane V8 (preset): first-order rotating couple",
    "v2-45": "45 deg V-twin on one pin, rods in one plane (preset)",
    "boxer6": "boxer-6 (preset): opposed cylinders on their own throws",
    "w12": "W12 broad arrow, three rods on each of four pins (preset)",
    "ducati-916": "90 deg L-twin, rods side by side 20 mm apart (preset: Ducati 916)",
    "harley-45": "45 deg twin, knife-and-fork rods in one plane (preset: Harley Evolution)",
    "vr6": "VR6 15 deg (preset): one pin per cylinder split 22 deg, rows' bores offset -/+12.5 mm",
    "w12-vw": "W12 from two VR banks (preset): 72 deg between the banks, rows offset in each",
    "w8": "W8 from two VR banks (preset)",
    "w16": "W16 from two VR banks (preset)",
    "radial5-kinner": "5-cylinder radial, master and link rods (preset: Kinner K-5)",
    "radial7-scarab": "7-cylinder radial, master and link rods (preset: Warner Scarab)",
    "radial9-r985": "9-cylinder radial, master and link rods (preset: P&W R-985)",
}


def _preset(name: str) -> Callable[[], EngineModel]:
    return lambda: _engine(preset_text(name))


#: name: (what it checks, model builder)
ENGINES: dict[str, tuple[str, Callable[[], EngineModel]]] = {
    "single-desaxe": (
        "single cylinder, crank offset 6 mm + wrist-pin offset 2 mm (odd orders appear)",
        _desaxe_single,
    ),
    "v2-45-side-by-side": (
        "45 deg V-twin on one pin, rods side by side 20 mm apart (rocking couple)",
        _side_by_side_twin,
    ),
    **{name: (what, _preset(name)) for name, what in PRESETS.items()},
}
#: the engines the test runs (issue 17 item 6 names the side-by-side V-twin, the
#: articulated radial-5 and the VR6; the others are in the results table)
TEST_ENGINES: tuple[str, ...] = (
    "single-desaxe",
    "v8-crossplane",
    "v2-45-side-by-side",
    "radial5-kinner",
    "vr6",
)


# --------------------------------------------------------------------------- the model
#: Phasors by order are crankbalance's own :class:`~crankbalance.physics.shaking.FreeForces`, with
#: the
#: rotating masses inside order 1 (``rotating_force`` and ``rotating_couple`` zero): the
#: multibody model carries them and cannot tell them apart.
Phasors = FreeForces


def _phasors(
    force_forward: NDArray,
    force_backward: NDArray,
    couple_forward: NDArray,
    couple_backward: NDArray,
    roll: NDArray,
) -> FreeForces:
    return FreeForces(
        orders=np.arange(1, np.size(force_forward) + 1),
        force_forward=force_forward,
        force_backward=force_backward,
        couple_forward=couple_forward,
        couple_backward=couple_backward,
        rotating_force=0j,
        rotating_couple=0j,
        roll=roll,
        rotating_roll=0j,
    )


@dataclass(frozen=True)
class Simulation:
    """The multibody result of one engine.

    ``phasors``: Richardson's extrapolation of the runs with ``steps`` and ``steps // 2``
    steps per revolution, (4 X(h) - X(2h)) / 3, which removes the integrator's error in h**2
    (docs/validation.md, "Step size and convergence"); ``raw``: the run with ``steps``
    alone. ``seconds``: the solver's time of both runs.
    """

    phasors: Phasors
    raw: Phasors
    steps: int
    bodies: int
    seconds: float


def reference(model: EngineModel, orders: int = ORDERS) -> Phasors:
    """crankbalance's phasors with the rotating masses added to the first order."""
    f = free_forces(model, orders)
    ff, cf = f.force_forward.copy(), f.couple_forward.copy()
    ff[0] += f.rotating_force
    cf[0] += f.rotating_couple
    roll = f.roll.copy()
    roll[0] += f.rotating_roll
    return _phasors(ff, f.force_backward.copy(), cf, f.couple_backward.copy(), roll)


def _about_centre(points: list[tuple[float, NDArray, NDArray]]) -> tuple[float, NDArray, NDArray]:
    """Mass, centre of mass and inertia tensor about it of point masses with own inertia."""
    mass = sum(m for m, _p, _i in points)
    com = sum((m * p for m, p, _i in points), np.zeros(3)) / mass
    tensor = np.zeros((3, 3))
    for m, p, own in points:
        d = p - com
        tensor += m * (d @ d * np.eye(3) - np.outer(d, d)) + own
    return mass, com, tensor


def crank_angle(t: float, speed: float) -> float:
    """Prescribed crank angle [rad] at time t [s]: from rest, the angular acceleration a
    cosine bump over the first revolution's time T (speed w at t = T, angle w T / 2), then
    constant speed."""
    ramp = 2.0 * math.pi / speed
    if t < ramp:
        return (speed / ramp) * (
            0.5 * t * t + (ramp / (2 * math.pi)) ** 2 * (math.cos(2 * math.pi * t / ramp) - 1.0)
        )
    return 0.5 * speed * ramp + speed * (t - ramp)


def simulate(model: EngineModel, steps: int = STEPS, orders: int = ORDERS) -> Simulation:
    """Run the EXUDYN model of ``model`` with ``steps`` and ``steps // 2`` steps per
    revolution and extrapolate (:class:`Simulation`)."""
    if steps < 8 or steps % 2:
        raise ValueError(f"steps per revolution must be even and at least 8, not {steps}")
    fine, bodies, seconds = solve(model, steps, orders)
    coarse, _bodies, more = solve(model, steps // 2, orders)
    return Simulation(extrapolate(fine, coarse), fine, steps, bodies, seconds + more)


def about(phasors: Phasors, point: float) -> Phasors:
    """The same loads with the moments taken about the point ``point`` [m] along the crank
    axis instead of y = 0: the couple of a force F at y becomes (y - point) F."""
    return _phasors(
        phasors.force_forward,
        phasors.force_backward,
        phasors.couple_forward - point * phasors.force_forward,
        phasors.couple_backward - point * phasors.force_backward,
        phasors.roll,
    )


def extrapolate(fine: Phasors, coarse: Phasors) -> Phasors:
    """Richardson's extrapolation (4 X(h) - X(2h)) / 3 of phasors whose error is in h**2."""
    names = ("force_forward", "force_backward", "couple_forward", "couple_backward", "roll")
    return _phasors(*((4 * getattr(fine, k) - getattr(coarse, k)) / 3 for k in names))


def solve(
    model: EngineModel, steps: int = STEPS, orders: int = ORDERS
) -> tuple[Phasors, int, float]:
    """Run the EXUDYN model of ``model`` once and take the Fourier series of its ground loads.

    One revolution's start from rest, one at constant speed, ``steps`` steps per
    revolution (generalized-alpha, spectral radius 0.9, full Newton, sparse solver).
    Returns the phasors, the number of bodies and the solver's time [s].
    """
    import exudyn as exu
    from exudyn.utilities import ObjectGround, RigidBodyInertia, SensorBody, SensorObject

    if len(model.conrods) != model.cylinders:
        raise ValueError(
            f"{model.name}: the multibody model needs every conrod's mass "
            f"(masses.conrod), {len(model.conrods)} of {model.cylinders} given"
        )
    r, l, w = model.crank_radius, model.rod_length, model.speed
    period = 2.0 * math.pi / w
    system = exu.SystemContainer()
    mbs = system.AddSystem()
    ground = mbs.AddObject(ObjectGround())
    y_axis = np.array([0.0, 1.0, 0.0])

    rods = {c.cylinder - 1: c for c in model.conrods}
    big_end = np.zeros(model.throws)
    for c, rod in rods.items():
        big_end[model.cylinder_throw[c]] += rod.rotating
    points = []
    for t in range(model.throws):
        m = float(model.throw_rotating_mass[t] - big_end[t])
        if m < -1e-12:
            raise ValueError(
                f"{model.name}: throw {t + 1} has less rotating mass "
                f"({model.throw_rotating_mass[t]:g} kg) than the big ends on it "
                f"({big_end[t]:g} kg)"
            )
        phi = model.throw_angle[t]
        pin = np.array([r * math.sin(phi), model.throw_position[t], r * math.cos(phi)])
        points.append((max(m, 0.0), pin, np.zeros((3, 3))))
    # a shaft on the axis: symmetric about y, so at constant speed it adds no load
    points.append((1.0, np.zeros(3), np.diag([2e-3, 3e-3, 2e-3])))
    mass, com, tensor = _about_centre(points)
    crank = mbs.CreateRigidBody(
        inertia=RigidBodyInertia(mass, tensor), referencePosition=com.tolist(), show=False
    )
    bodies = 1

    def drive(_mbs: object, t: float, _item: int, _par: object) -> list[float]:
        return [0.0, 0.0, 0.0, 0.0, crank_angle(t, w), 0.0]

    # only the rotation about y: its reaction is a torque about the crank axis alone (its
    # frame turns about y with the prescribed angle, which leaves a y component one)
    drive_joint = mbs.CreateGenericJoint(
        itemNumbers=[ground, crank],
        position=[0.0, 0.0, 0.0],
        constrainedAxes=[0, 0, 0, 0, 1, 0],
        offsetUserFunction=drive,
        show=False,
    )
    span = 0.1 + float(np.max(np.abs(model.throw_position)))
    # every joint to the ground: (joint, its axes, its position)
    ground_joints: list[tuple[int, NDArray, NDArray]] = [(drive_joint, np.eye(3), np.zeros(3))]
    for position, fixed in (([0.0, -span, 0.0], [1, 1, 1]), ([0.0, span, 0.0], [1, 0, 1])):
        joint = mbs.CreateGenericJoint(
            itemNumbers=[ground, crank],
            position=position,
            constrainedAxes=fixed + [0, 0, 0],
            show=False,
        )
        ground_joints.append((joint, np.eye(3), np.array(position)))

    offsets, axial = model.cylinder_offset, model.cylinder_position
    art = model.articulated_rods  # the full geometry: rod lengths, link pins
    lengths = np.full(model.cylinders, l) if art is None else np.asarray(art.rod_length)
    # the master rod first: the link rods hang on it
    order = list(range(model.cylinders))
    if art is not None:
        order.remove(art.master)
        order.insert(0, art.master)
    moving: dict[int, Any] = {}  # the piston each cylinder's joint to the ground holds
    master_body: Any = None  # the master rod, its crankpin and its axis (unit vector)
    master_pin, master_axis = np.zeros(3), np.zeros(3)
    for c in order:
        phi = float(model.cylinder_angle[c])
        beta = float(model.cylinder_bank[c])
        y, e, rod_l = float(axial[c]), float(offsets[c]), float(lengths[c])
        along = np.array([math.sin(beta), 0.0, math.cos(beta)])  # bank axis
        side = np.array([math.cos(beta), 0.0, -math.sin(beta)])  # toward increasing angle
        crankpin = np.array([r * math.sin(phi), y, r * math.cos(phi)])
        link = art is not None and c != art.master
        if link:
            assert art is not None
            # link pin: on the master rod at rho from its big-end centre, gamma from its
            # axis in the sense of rotation (a turn about +y)
            rho, gamma = float(art.link_pin_radius[c]), float(art.link_pin_angle[c])
            turn = np.array(
                [
                    [math.cos(gamma), 0.0, math.sin(gamma)],
                    [0.0, 1.0, 0.0],
                    [-math.sin(gamma), 0.0, math.cos(gamma)],
                ]
            )
            big_end = master_pin + rho * (turn @ master_axis)
        else:
            big_end = crankpin
        # the wrist pin where the rod from its big end meets the cylinder's path
        lateral = e - float(big_end @ side)
        s = float(big_end @ along) + math.sqrt(rod_l * rod_l - lateral * lateral)
        wrist = s * along + e * side + y * y_axis
        u = (wrist - big_end) / rod_l
        rod = rods[c]
        d = rod.cg_from_big_end
        across = rod.mass * d * (rod_l - d)  # the two-mass inertia, about y and the other normal
        rod_tensor = across * (np.eye(3) - np.outer(u, u)) + 1e-2 * across * np.outer(u, u)
        rod_body = mbs.CreateRigidBody(
            inertia=RigidBodyInertia(rod.mass, rod_tensor),
            referencePosition=(big_end + d * u).tolist(),
            show=False,
        )
        if art is not None and c == art.master:
            master_body, master_pin, master_axis = rod_body, crankpin, u
        piston_mass = float(model.reciprocating_mass[c] - rod.reciprocating)
        if piston_mass <= 0:
            raise ValueError(
                f"{model.name}: cylinder {c + 1} has no piston mass beyond its rod's small end"
            )
        piston = mbs.CreateRigidBody(
            inertia=RigidBodyInertia(piston_mass, 1e-4 * piston_mass * np.eye(3)),
            referencePosition=wrist.tolist(),
            show=False,
        )
        bodies += 2
        mbs.CreateRevoluteJoint(
            itemNumbers=[master_body if link else crank, rod_body],
            position=big_end.tolist(),
            axis=y_axis.tolist(),
            show=False,
        )
        mbs.CreateGenericJoint(
            itemNumbers=[piston, rod_body],
            position=wrist.tolist(),
            constrainedAxes=[1, 0, 1, 0, 0, 0],
            show=False,
        )
        axes = np.column_stack([along, y_axis, np.cross(along, y_axis)])
        joint = mbs.CreateGenericJoint(
            itemNumbers=[ground, piston],
            position=wrist.tolist(),
            rotationMatrixAxes=axes,
            constrainedAxes=[0, 1, 1, 1, 1, 1],
            show=False,
        )
        ground_joints.append((joint, axes, wrist))
        moving[joint] = piston

    sensors = [
        tuple(
            mbs.AddSensor(
                SensorObject(
                    objectNumber=joint,
                    storeInternal=True,
                    writeToFile=False,
                    outputVariableType=kind,
                )
            )
            for kind in (exu.OutputVariableType.ForceLocal, exu.OutputVariableType.TorqueLocal)
        )
        for joint, _axes, _pos in ground_joints
    ]
    places = {
        joint: mbs.AddSensor(
            SensorBody(
                bodyNumber=body,
                storeInternal=True,
                writeToFile=False,
                outputVariableType=exu.OutputVariableType.Position,
            )
        )
        for joint, body in moving.items()
    }
    mbs.Assemble()
    h = period / steps
    settings = exu.SimulationSettings()
    settings.timeIntegration.numberOfSteps = 2 * steps
    settings.timeIntegration.endTime = 2 * steps * h
    settings.timeIntegration.verboseMode = 0
    settings.timeIntegration.generalizedAlpha.spectralRadius = 0.9
    settings.timeIntegration.newton.useModifiedNewton = False
    settings.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = h
    settings.parallel.numberOfThreads = 1
    start = time.perf_counter()
    if not mbs.SolveDynamic(settings):
        raise RuntimeError(f"{model.name}: EXUDYN's solver did not converge")
    seconds = time.perf_counter() - start

    force = np.zeros(0)
    moment = np.zeros(0)
    times = np.zeros(0)
    roll = np.zeros(0)
    for (f_sensor, m_sensor), (joint, frame, origin) in zip(sensors, ground_joints, strict=True):
        f_data = np.asarray(mbs.GetSensorStoredData(f_sensor))
        m_data = np.asarray(mbs.GetSensorStoredData(m_sensor))
        f_global = f_data[:, 1:4] @ frame.T
        m_global = m_data[:, 1:4] @ frame.T + np.cross(origin, f_global)
        # the roll moment on the block: every joint to the ground but the drive, whose
        # torque about y is what the crank passes to the machine it drives. A piston's
        # joint reports its force at the ground's marker (the wrist pin's first place):
        # the wall's side force acts where the piston is, which moves the roll (and not
        # the moments across the axis: the piston moves in the x-z plane, without a force
        # along y)
        block_roll = np.zeros(len(m_global)) if joint == drive_joint else m_global[:, 1]
        if joint in places:
            where = np.asarray(mbs.GetSensorStoredData(places[joint]))[:, 1:4]
            block_roll = block_roll + np.cross(where - origin, f_global)[:, 1]
        if not times.size:
            times, force, moment, roll = f_data[:, 0], f_global, m_global, block_roll
        else:
            force, moment, roll = force + f_global, moment + m_global, roll + block_roll
    return _fourier(times, force, moment, w, orders, roll), bodies, seconds


def _fourier(
    times: NDArray,
    force: NDArray,
    moment: NDArray,
    speed: float,
    orders: int,
    roll: NDArray | None = None,
) -> Phasors:
    """Phasors of the last revolution's samples (times at whole steps, the last one in);
    the roll moment about y on the block (``roll``, default none) as R_n of
    M_y = Re(R_n exp(i n theta))."""
    theta = np.array([crank_angle(float(t), speed) for t in times])
    last = theta > theta[-1] - 2 * math.pi + 1e-9 * (2 * math.pi)
    theta = theta[last]
    f = force[last, 2] + 1j * force[last, 0]  # z + i x
    c = -1j * (moment[last, 2] + 1j * moment[last, 0])  # couple C, M = iC
    turn = np.exp(-1j * np.arange(1, orders + 1)[:, None] * theta[None, :])
    n = theta.size
    y = np.zeros(n) if roll is None else roll[last]
    return _phasors(
        turn @ f / n, turn.conj() @ f / n, turn @ c / n, turn.conj() @ c / n, 2 * turn @ y / n
    )


# --------------------------------------------------------------------------- comparison
@dataclass(frozen=True)
class Row:
    """One order of one quantity: amplitudes [N or N m], the limit and the phasor error."""

    engine: str
    quantity: str  # "force", "moment" or "roll" (about y)
    order: int
    crankbalance: float
    exudyn: float
    phasor_error: float  # max |difference| of the forward and backward phasors
    limit: float
    floor: float  # 1e-4 of the largest first-order amplitude

    @property
    def difference(self) -> float:
        return abs(self.exudyn - self.crankbalance)

    @property
    def passed(self) -> bool:
        return self.difference <= self.limit and self.phasor_error <= self.limit


def first_order_scales(model: EngineModel, ref: Phasors) -> tuple[float, float]:
    """The largest first-order amplitudes the floor of the acceptance is taken from.

    Force [N]: the engine's first-order force, or one cylinder's reciprocating or one
    throw's rotating first-order force where that is larger (an engine balanced in the
    first order has none of its own). Moment [N m]: the engine's first-order moment, or
    that force scale times the larger of the crank radius and the farthest cylinder's
    axial distance from the mid-point (an engine in one plane has no moment of its own).
    """
    accel = model.crank_radius * model.speed**2
    force = max(
        float(ref.force_amplitude[0]),
        accel * float(np.max(model.reciprocating_mass)),
        accel * float(np.max(model.throw_rotating_mass)),
    )
    arm = max(model.crank_radius, float(np.max(np.abs(model.cylinder_position))))
    return force, max(float(ref.moment_amplitude[0]), force * arm)


def roll_scale(model: EngineModel, ref: Phasors) -> float:
    """The roll moment's scale the floor of its acceptance is taken from [N m]: the
    engine's largest roll order, or one cylinder's inertia torque, m r^2 w^2 / 2 (the
    engine's may cancel)."""
    one = 0.5 * float(np.max(model.reciprocating_mass)) * (model.crank_radius * model.speed) ** 2
    return max(float(np.max(ref.roll_amplitude)), one)


def compare(engine: str, model: EngineModel, simulated: Phasors, orders: int = ORDERS) -> list[Row]:
    """The acceptance of issue 17, order by order, for force and moment, and of issue 27
    for the roll moment about y (the same limits, its floor from :func:`roll_scale`)."""
    ref = reference(model, orders)
    scale_force, scale_moment = first_order_scales(model, ref)
    floors = {
        "force": FLOOR * scale_force,
        "moment": FLOOR * scale_moment,
        "roll": FLOOR * roll_scale(model, ref),
    }
    rows = []
    for quantity in ("force", "moment", "roll"):
        a_ref = getattr(ref, f"{quantity}_amplitude")
        a_sim = getattr(simulated, f"{quantity}_amplitude")
        if quantity == "roll":  # one real curve per order: its phasor R_n
            err = np.abs(ref.roll - simulated.roll)
        else:
            kind = "force" if quantity == "force" else "couple"
            err = np.maximum(
                np.abs(getattr(ref, f"{kind}_forward") - getattr(simulated, f"{kind}_forward")),
                np.abs(getattr(ref, f"{kind}_backward") - getattr(simulated, f"{kind}_backward")),
            )
        for k in range(orders):
            rows.append(
                Row(
                    engine=engine,
                    quantity=quantity,
                    order=k + 1,
                    crankbalance=float(a_ref[k]),
                    exudyn=float(a_sim[k]),
                    phasor_error=float(err[k]),
                    limit=max(RELATIVE * float(a_ref[k]), floors[quantity]),
                    floor=floors[quantity],
                )
            )
    return rows


def run(engine: str, steps: int = STEPS) -> tuple[Simulation, list[Row]]:
    """Simulate one engine of :data:`ENGINES` and compare it order by order."""
    model = ENGINES[engine][1]()
    sim = simulate(model, steps)
    return sim, compare(engine, model, sim.phasors)


# --------------------------------------------------------------------------- output
def _number(value: float) -> str:
    return f"{value:.6g}"


def table(results: Sequence[tuple[str, Simulation, list[Row]]]) -> str:
    """The results table in Markdown."""
    lines = [
        "# Multibody cross-check: crankbalance against EXUDYN",
        "",
        "Written by `python validation/multibody.py --write validation/results.md`",
        "(model and acceptance: `docs/validation.md`). Amplitude of each order, the largest",
        "magnitude over a revolution, |X+| + |X-| of its forward and backward phasors; forces",
        "in N, moments in N·m about the crankshaft mid-point (*roll*: about the crank axis,",
        "|R_n| of one real curve per order); order 1 includes the rotating",
        "masses. EXUDYN's phasors are extrapolated from runs with N and N/2 steps per",
        "revolution (docs/validation.md). *rel. diff.* is |EXUDYN - crankbalance| /",
        "crankbalance (blank where",
        "crankbalance's amplitude is zero); *phasor diff.* the larger difference of the",
        "forward and backward phasors; *limit* 0.5 % of the order's amplitude or 1e-4 of the",
        "largest first-order amplitude, whichever is larger.",
        "",
    ]
    for engine, sim, rows in results:
        worst = max(r.phasor_error / r.limit for r in rows)
        lines.append(
            f"- **{engine}**: {ENGINES[engine][0]}; {sim.bodies} bodies, N = {sim.steps} "
            f"steps per revolution; largest phasor difference {worst:.2g} of its limit"
        )
    lines += [
        "",
        "| engine | quantity | order | crankbalance | EXUDYN | rel. diff. | phasor diff. "
        "| limit | ok |",
        "|---|---|---:|---:|---:|---:|---:|---:|---|",
    ]
    for _engine, _sim, rows in results:
        for row in rows:
            rel = f"{row.difference / row.crankbalance:.2e}" if row.crankbalance > 0 else ""
            lines.append(
                f"| {row.engine} | {row.quantity} | {row.order} | {_number(row.crankbalance)} "
                f"| {_number(row.exudyn)} | {rel} | {row.phasor_error:.3g} | {row.limit:.3g} "
                f"| {'yes' if row.passed else '**NO**'} |"
            )
    return "\n".join(lines) + "\n"


def convergence(engine: str, steps: Sequence[int]) -> str:
    """Against the steps per revolution: the worst phasor difference relative to its limit,
    and the worst relative difference of the orders whose limit is 0.5 % of their own
    amplitude, of a single run and of the extrapolation from it and the run with half the
    steps."""
    model = ENGINES[engine][1]()
    lines = [
        f"step-size convergence, {engine}",
        "steps/rev  single run: worst/limit  worst relative  |  extrapolated: worst/limit  "
        "worst relative",
    ]

    def worst(phasors: Phasors) -> tuple[float, float]:
        rows = compare(engine, model, phasors)
        own = [r.phasor_error / r.crankbalance for r in rows if r.limit > r.floor]
        return max(r.phasor_error / r.limit for r in rows), max(own, default=0.0)

    runs = {n: solve(model, n)[0] for n in sorted({*steps, *(n // 2 for n in steps)})}
    for n in steps:
        (a, b), (c, d) = worst(runs[n]), worst(extrapolate(runs[n], runs[n // 2]))
        lines.append(f"{n:9d}  {a:22.3g}  {b:14.2e}  |  {c:25.3g}  {d:14.2e}")
    return "\n".join(lines) + "\n"


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("engines", nargs="*", help=f"engines (default all): {', '.join(ENGINES)}")
    parser.add_argument("--steps", type=int, default=STEPS, help="steps per revolution")
    parser.add_argument("--table", action="store_true", help="print the Markdown table")
    parser.add_argument("--write", metavar="FILE", help="write the table to FILE (atomically)")
    parser.add_argument(
        "--convergence", action="store_true", help="error against steps per revolution"
    )
    args = parser.parse_args(argv)
    names = args.engines or list(ENGINES)
    unknown = [n for n in names if n not in ENGINES]
    if unknown:
        parser.error(f"unknown engine {unknown[0]!r}; known: {', '.join(ENGINES)}")
    if args.convergence:
        for name in names:
            print(convergence(name, (60, 120, 240, 480)))
        return 0
    results = []
    for name in names:
        sim, rows = run(name, args.steps)
        results.append((name, sim, rows))
        bad = [r for r in rows if not r.passed]
        print(
            f"{name}: {'ok' if not bad else f'{len(bad)} orders outside the limit'} "
            f"({sim.bodies} bodies, {sim.seconds:.1f} s)",
            file=sys.stderr,
        )
    text = table(results)
    if args.write:
        from crankbalance.io.files import write_atomic

        write_atomic(args.write, text)
    elif args.table:
        print(text, end="")
    return 0 if all(r.passed for _n, _s, rows in results for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
