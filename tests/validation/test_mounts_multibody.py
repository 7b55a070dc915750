"""Issue 31 item 7: the powertrain on its mounts against a multibody simulation.

EXUDYN builds the V-twin of ``examples/mounts_vtwin_motorcycle.toml`` as one rigid body
(its mass and inertia tensor, products included) on four Cartesian spring-dampers to the
ground at the mounts, loaded at the crank's reference point by the engine's free forces and
moments of orders 1 and 2 (the forces at that point and the moments as a torque), each
as the real curve crankbalance's order phasors give (``shaking.phasor_curve``: x the
imaginary part, z the real part; M = iC; the roll Re(R e^{inθ})). It runs from rest until
the transient has died; the Fourier coefficients of each spring-damper's force over the
last revolutions must agree with :func:`crankbalance.physics.mounts.forced_response`
(viscous mounts: EXUDYN's spring-dampers have no hysteretic damping) within 0.2 % of the
largest mount force.

EXUDYN is in the ``validation`` extra, which ``.ci/run`` installs: where it is missing the
test fails (it is not skipped), saying how to install it.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from crankbalance.io.engine_file import load_engine
from crankbalance.physics import mounts as pm
from crankbalance.physics.shaking import phasor_curve
from crankbalance.studies.engine import analyze
from crankbalance.studies.mounts import engine_loads, powertrain_of

ROOT = Path(__file__).resolve().parents[2]
BIKE = ROOT / "examples" / "mounts_vtwin_motorcycle.toml"
#: viscous damping of every mount, c = TAU k [s]
TAU = 2e-3
SPEED = 1200 * math.pi / 30  # crank [rad/s]: between the modes and above them
REVOLUTIONS = 40  # from rest: the slowest mode's transient falls below e^-10
STEPS = 200  # per revolution


def _powertrain() -> pm.Powertrain:
    table = load_engine(str(BIKE)).powertrain
    assert table is not None
    pt = powertrain_of(table)
    mounts = tuple(
        pm.Mount(m.name, m.position, m.stiffness, m.orientation, 0.0, TAU * m.stiffness)
        for m in pt.mounts
    )
    assert all(not np.any(m.orientation) for m in mounts)  # Cartesian spring-dampers
    return pm.Powertrain(pt.mass, pt.cg, pt.inertia, mounts, pt.up)


def _exudyn(pt: pm.Powertrain, curve: object) -> tuple[np.ndarray, np.ndarray]:
    """Time and the force of each spring-damper (T, N, 3)."""
    try:
        import exudyn as exu
        from exudyn.utilities import ObjectGround, RigidBodyInertia, SensorObject
    except ImportError as missing:
        pytest.fail(
            f"EXUDYN is not installed ({missing}); the multibody cross-check needs the "
            "validation extra: pip install -e .[validation]  (.ci/run installs it)"
        )
    system = exu.SystemContainer()
    mbs = system.AddSystem()
    ground = mbs.AddObject(ObjectGround())
    body = mbs.CreateRigidBody(
        inertia=RigidBodyInertia(pt.mass, pt.inertia),
        referencePosition=pt.cg.tolist(),
        show=False,
    )
    sensors = []
    for mount in pt.mounts:
        k = mount.body_stiffness()
        c = mount.body_damping()
        spring = mbs.CreateCartesianSpringDamper(
            itemNumbers=[ground, body],
            localPosition0=mount.position.tolist(),
            localPosition1=(mount.position - pt.cg).tolist(),
            stiffness=np.diag(k).tolist(),
            damping=np.diag(c).tolist(),
            show=False,
        )
        sensors.append(
            mbs.AddSensor(
                SensorObject(
                    objectNumber=spring,
                    storeInternal=True,
                    outputVariableType=exu.OutputVariableType.Force,
                )
            )
        )

    def force(_mbs: object, t: float, _load: object) -> list[float]:
        return list(curve(t)[:3])  # type: ignore[operator]

    def torque(_mbs: object, t: float, _load: object) -> list[float]:
        return list(curve(t)[3:])  # type: ignore[operator]

    mbs.CreateForce(
        itemNumber=body,
        localPosition=(-pt.cg).tolist(),  # the reference point
        loadVectorUserFunction=force,
        show=False,
    )
    mbs.CreateTorque(itemNumber=body, loadVectorUserFunction=torque, show=False)
    mbs.Assemble()
    settings = exu.SimulationSettings()
    period = 2 * math.pi / SPEED
    settings.timeIntegration.numberOfSteps = REVOLUTIONS * STEPS
    settings.timeIntegration.endTime = REVOLUTIONS * period
    settings.timeIntegration.verboseMode = 0
    settings.timeIntegration.generalizedAlpha.spectralRadius = 1.0
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = period / STEPS
    settings.parallel.numberOfThreads = 1
    assert mbs.SolveDynamic(settings), "EXUDYN's solver did not converge"
    data = [np.asarray(mbs.GetSensorStoredData(s)) for s in sensors]
    return data[0][:, 0], np.stack([d[:, 1:4] for d in data], axis=1)


def test_mount_forces_agree_with_exudyn() -> None:
    pt = _powertrain()
    forces = analyze(str(BIKE), orders=2).forces
    orders = forces.orders[:2]
    scale = (SPEED / analyze(str(BIKE), orders=2).model.speed) ** 2

    def curve(t: float) -> np.ndarray:
        theta = np.array([SPEED * t])
        f = phasor_curve(forces.force_forward, forces.force_backward, orders, theta).sum()
        m = (1j * phasor_curve(forces.couple_forward, forces.couple_backward, orders, theta)).sum()
        roll = (forces.roll[:2] * np.exp(1j * orders * theta[0])).real.sum()
        return scale * np.array([f.imag, 0.0, f.real, m.imag, roll, m.real])

    time, spring = _exudyn(pt, curve)
    model_speed = analyze(str(BIKE), orders=2).model.speed
    response = pm.forced_response(
        pt, engine_loads(forces, "balanced")[:2], orders, model_speed, [SPEED]
    )
    period = 2 * math.pi / SPEED
    last = time >= time[-1] - 10 * period - 1e-12
    t, f = time[last][:-1], spring[last][:-1]  # ten whole revolutions
    largest = response.mount_peak.max()
    for k, n in enumerate(orders):
        # Re(X e^{inωt}) -> X = 2 mean(f e^{-inωt})
        found = 2 * np.mean(f * np.exp(-1j * n * SPEED * t)[:, None, None], axis=0)
        expected = response.mount_forces[0, k]
        assert np.abs(found - expected).max() < 2e-3 * largest, (n, found, expected)
