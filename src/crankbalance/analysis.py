"""The analysis study: from an engine (file, preset, spec or model) to its free forces and
moments, in the JSON contract ``crankbalance.analysis/1`` of DESIGN.md."""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import Any

import numpy as np

from .io import load_engine
from .model import EngineModel, build_model
from .results import to_jsonable
from .shaking import Curves, FreeForces, curves, free_forces
from .spec import EngineSpec

SCHEMA = "crankbalance.analysis/1"
EngineLike = str | os.PathLike[str] | EngineSpec | EngineModel


def as_model(engine: EngineLike) -> EngineModel:
    """Accept a preset name, a file path, a spec or a model."""
    if isinstance(engine, EngineModel):
        return engine
    if not isinstance(engine, EngineSpec):
        engine = load_engine(engine)
    return build_model(engine)


@dataclass(frozen=True)
class Analysis:
    """Free forces and moments of one engine (see :func:`analyze`)."""

    model: EngineModel
    forces: FreeForces

    def curves(self, angle: Any = None) -> Curves:
        """Curves versus crank angle (720 points over a revolution by default)."""
        return curves(self.model, self.forces, angle)

    def to_dict(self) -> dict[str, Any]:
        m, f = self.model, self.forces
        # what is below round-off of the engine's force scale is reported as exactly zero
        scale = float(np.sum(m.reciprocating_mass) + np.sum(m.throw_rotating_mass)) * (
            m.crank_radius * m.speed**2) * max(1.0, float(np.ptp(m.throw_position)))
        tiny = 1e-12 * scale

        def clean(value: complex) -> complex:
            return 0j if abs(value) < tiny else complex(value)

        f = FreeForces(orders=f.orders,
                       force_forward=np.array([clean(v) for v in f.force_forward]),
                       force_backward=np.array([clean(v) for v in f.force_backward]),
                       couple_forward=np.array([clean(v) for v in f.couple_forward]),
                       couple_backward=np.array([clean(v) for v in f.couple_backward]),
                       rotating_force=clean(f.rotating_force),
                       rotating_couple=clean(f.rotating_couple))
        rows_f, rows_m = [], []
        for k, order in enumerate(f.orders):
            rows_f.append({
                "order": int(order),
                "amplitude_N": float(f.force_amplitude[k]),
                "forward_N": float(abs(f.force_forward[k])),
                "backward_N": float(abs(f.force_backward[k])),
                "forward_phase_deg": _phase(f.force_forward[k]),
                "backward_phase_deg": _phase(f.force_backward[k]),
            })
            rows_m.append({
                "order": int(order),
                "amplitude_Nm": float(f.moment_amplitude[k]),
                "forward_Nm": float(abs(f.couple_forward[k])),
                "backward_Nm": float(abs(f.couple_backward[k])),
                "forward_phase_deg": _phase(1j * f.couple_forward[k]),
                "backward_phase_deg": _phase(1j * f.couple_backward[k]),
            })
        out = {
            "schema": SCHEMA,
            "engine": {
                "name": m.name,
                "cylinders": m.cylinders,
                "throws": m.throws,
                "speed_rpm": m.speed * 30 / math.pi,
                "kinematics": m.kinematics,
                "crank_radius_m": m.crank_radius,
                "rod_length_m": m.rod_length,
                "rod_ratio": m.rod_ratio,
                "offset_m": m.offset,
                "throw_angle_deg": np.degrees(m.throw_angle),
                "throw_position_m": m.throw_position,
                "cylinder_throw": m.cylinder_throw + 1,
                "cylinder_bank_deg": np.degrees(m.cylinder_bank),
            },
            "masses": {
                "reciprocating_kg": m.reciprocating_mass,
                "rotating_kg": m.throw_rotating_mass,
                "conrods": [c.to_dict() for c in m.conrods],
            },
            "free_forces": rows_f,
            "free_moments": rows_m,
            "rotating": {
                "force_N": abs(f.rotating_force),
                "moment_Nm": abs(f.rotating_couple),
                "force_phase_deg": _phase(f.rotating_force),
                "moment_phase_deg": _phase(1j * f.rotating_couple),
            },
            "conventions": "phases: direction at crank angle 0, degrees from +z toward +x; "
                           "moments about the crankshaft mid-point",
        }
        result = to_jsonable(out)
        assert isinstance(result, dict)
        return result


def _phase(value: complex) -> float:
    """Direction of a phasor in degrees from +z toward +x (0 for a zero phasor)."""
    if abs(value) < 1e-12:
        return 0.0
    return float(np.degrees(np.arctan2(value.imag, value.real)))


def analyze(engine: EngineLike, orders: int = 8) -> Analysis:
    """Free forces and moments of an engine (orders 1..``orders``) and of its rotating masses.

    Parameters
    ----------
    engine : str, path, EngineSpec or EngineModel
        Preset name, engine file, validated spec or built model.
    orders : int
        Highest harmonic order (1..64).
    """
    from .errors import InputError

    if not isinstance(orders, int) or not 1 <= orders <= 64:
        raise InputError("orders", orders, "must be a whole number from 1 to 64")
    model = as_model(engine)
    return Analysis(model=model, forces=free_forces(model, orders))
