r"""From a validated engine spec to SI arrays: throws, cylinders and the mass split.

Geometry conventions (``docs/theory.md``): y along the crank axis from the crankshaft
mid-point, z along the cylinder axis of an in-line engine, x across. A throw at angle
:math:`\varphi` has its crankpin at :math:`r(\sin(\theta+\varphi), \cos(\theta+\varphi))`
in (x, z) when the first throw is at crank angle :math:`\theta`. A cylinder's bank angle
:math:`\beta` is the angle of its axis from z about the crank axis, in the same sense.
The cylinder is at top dead centre when :math:`\theta + \varphi - \beta = 0`.

Numbering of cylinders (docs/engine_file.md): in-line and boxer: one per throw from the
y < 0 end; vee: bank A (bank angle :math:`-V/2`) is 1..T, bank B (:math:`+V/2`) is T+1..2T,
cylinders k and k+T share throw k; W: banks :math:`-V, 0, +V` numbered bank after bank;
radial: cylinder k at bank angle :math:`(k-1)\,360°/n`; custom: throw after throw.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from .errors import InputError
from .results import ResultMixin
from .spec import EngineSpec, MassOverride, throw_count


@dataclass(frozen=True)
class ConrodSplit(ResultMixin):
    r"""Two-mass equivalent of one conrod (mass and centre of gravity kept).

    ``inertia_two_mass`` is the inertia about the CG the two point masses have,
    :math:`m\,d\,(l-d)`; ``inertia_error`` is that minus the real inertia, when the real
    one is given (None otherwise).
    """

    cylinder: int
    mass: float
    rotating: float
    reciprocating: float
    cg_from_big_end: float
    inertia_two_mass: float
    inertia_given: float | None
    inertia_error: float | None


@dataclass(frozen=True)
class EngineModel:
    """An engine as SI arrays: the input of every physics function.

    Attributes
    ----------
    crank_radius, rod_length, offset : float
        [m]; ``offset`` is crank offset plus wrist-pin offset.
    speed : float
        Crank speed [rad/s].
    throw_angle, throw_position, throw_rotating_mass : ndarray, shape (T,)
        [rad], [m along the crank axis from the mid-point], [kg at the crank radius,
        crankpin, webs reduced to the crank radius and all big ends on the pin].
    cylinder_throw : ndarray of int, shape (C,)
        Index of the throw each cylinder sits on.
    cylinder_bank, reciprocating_mass : ndarray, shape (C,)
        [rad], [kg].
    """

    name: str
    speed: float
    kinematics: str
    crank_radius: float
    rod_length: float
    offset: float
    strokes: int
    throw_angle: NDArray[np.float64]
    throw_position: NDArray[np.float64]
    throw_rotating_mass: NDArray[np.float64]
    cylinder_throw: NDArray[np.int64]
    cylinder_bank: NDArray[np.float64]
    reciprocating_mass: NDArray[np.float64]
    firing_order: tuple[int, ...]
    conrods: tuple[ConrodSplit, ...] = field(default=())
    firing_order_given: bool = True

    @property
    def rod_ratio(self) -> float:
        return self.crank_radius / self.rod_length

    @property
    def cylinders(self) -> int:
        return int(self.cylinder_bank.size)

    @property
    def throws(self) -> int:
        return int(self.throw_angle.size)

    @property
    def cylinder_angle(self) -> NDArray[np.float64]:
        """Throw angle of each cylinder's crankpin [rad]."""
        return self.throw_angle[self.cylinder_throw]

    @property
    def cylinder_position(self) -> NDArray[np.float64]:
        """Axial position of each cylinder [m]."""
        return self.throw_position[self.cylinder_throw]


def build_model(spec: EngineSpec) -> EngineModel:
    """Turn a validated :class:`~crankbalance.spec.EngineSpec` into an :class:`EngineModel`."""
    ct = spec.crank_train
    positions, cylinder_throw, banks = _layout(spec)
    angles = _throw_angles(spec, cylinder_throw, banks, positions.size)
    rec, big_ends, conrods = _cylinder_masses(spec, cylinder_throw.size)
    rot, from_parts = _throw_masses(spec, positions.size)
    for c, t in enumerate(cylinder_throw):  # every big end on the pin turns with it
        if from_parts[t]:
            rot[t] += big_ends[c]
    n = cylinder_throw.size
    return EngineModel(
        name=spec.name,
        speed=spec.speed,
        kinematics=spec.kinematics,
        crank_radius=ct.crank_radius,
        rod_length=ct.rod_length,
        offset=ct.pin_offset + ct.crank_offset,
        strokes=ct.strokes,
        throw_angle=angles,
        throw_position=positions,
        throw_rotating_mass=rot,
        cylinder_throw=cylinder_throw,
        cylinder_bank=banks,
        reciprocating_mass=rec,
        firing_order=tuple(ct.firing_order or range(1, n + 1)),
        conrods=tuple(conrods),
        firing_order_given=ct.firing_order is not None,
    )


# --------------------------------------------------------------------------- layout
def _layout(spec: EngineSpec) -> tuple[NDArray, NDArray, NDArray]:
    ct = spec.crank_train
    if ct.layout == "custom":
        assert ct.throw is not None
        positions = np.array([t.position for t in ct.throw])
        return (
            positions,
            np.array([k for k, t in enumerate(ct.throw) for _ in t.banks]),
            np.array([b for t in ct.throw for b in t.banks], dtype=float),
        )
    n = ct.cylinder_count
    t = throw_count(ct.layout, n)
    pitch = ct.crank_pitch or 0.0
    positions = (np.arange(t) - (t - 1) / 2.0) * pitch
    v = ct.bank_angle or 0.0
    throw_of: NDArray
    banks: NDArray
    if ct.layout == "inline":
        throw_of, banks = np.arange(n), np.zeros(n)
    elif ct.layout == "boxer":
        throw_of = np.arange(n)
        banks = np.where(np.arange(n) % 2 == 0, -np.pi / 2, np.pi / 2)
    elif ct.layout == "vee":
        throw_of = np.tile(np.arange(t), 2)
        banks = np.repeat([-v / 2, v / 2], t)
    elif ct.layout == "w":
        throw_of = np.tile(np.arange(t), 3)
        banks = np.repeat([-v, 0.0, v], t)
    else:  # radial
        throw_of = np.zeros(n, dtype=np.int64)
        banks = 2 * np.pi * np.arange(n) / n
    return positions, throw_of.astype(np.int64), banks.astype(float)


def _throw_angles(
    spec: EngineSpec, cylinder_throw: NDArray, banks: NDArray, throws: int
) -> NDArray:
    ct = spec.crank_train
    if ct.layout == "custom":
        assert ct.throw is not None
        return np.array([t.angle for t in ct.throw])
    if ct.throw_angles is not None:
        return np.array(ct.throw_angles, dtype=float)
    if throws == 1:
        return np.zeros(1)
    n = cylinder_throw.size
    order = ct.firing_order or list(range(1, n + 1))
    interval = (2 * np.pi if ct.strokes == 2 else 4 * np.pi) / n
    fire_time = np.empty(n)
    fire_time[np.array(order) - 1] = np.arange(n) * interval
    # cylinder c is at its firing TDC at crank angle t_c: theta + phi - beta = 0
    cyl_angle = np.mod(banks - fire_time, 2 * np.pi)
    angles = np.full(throws, np.nan)
    for c in range(n):
        t = cylinder_throw[c]
        if np.isnan(angles[t]):
            angles[t] = cyl_angle[c]
            continue
        gap = math.remainder(cyl_angle[c] - angles[t], 2 * np.pi)
        if abs(gap) > 1e-9:
            raise InputError(
                "crank_train.firing_order",
                list(order),
                f"with even firing intervals of {math.degrees(interval):g} deg this order puts the "
                f"cylinders on throw {t + 1} at different throw angles; give the crank as "
                "crank_train.throw_angles (the firing order then only names the sequence)",
            )
    return angles


# --------------------------------------------------------------------------- masses
def _overrides(spec: EngineSpec, kind: str, count: int) -> list[dict[str, float]]:
    """For each cylinder (or throw), the mass fields that apply after overrides."""
    base = spec.masses.model_dump(exclude={"override"})
    rows = [dict(base) for _ in range(count)]
    for item in spec.masses.override:
        targets = item.cylinders if kind == "cylinders" else item.throws
        if not targets:
            continue
        changed = {
            k: v
            for k, v in item.model_dump(exclude={"cylinders", "throws"}).items()
            if v is not None and k in MassOverride.model_fields
        }
        for number in targets:
            rows[number - 1].update(changed)
            if kind == "cylinders" and "conrod_rotating_fraction" in changed:
                rows[number - 1]["conrod_cg_from_big_end"] = None
            if kind == "cylinders" and "conrod_cg_from_big_end" in changed:
                rows[number - 1]["conrod_rotating_fraction"] = None
    return rows


def _cylinder_masses(spec: EngineSpec, n: int) -> tuple[NDArray, NDArray, list[ConrodSplit]]:
    rod = spec.crank_train.rod_length
    rec = np.zeros(n)
    big_end = np.zeros(n)
    conrods: list[ConrodSplit] = []
    for c, row in enumerate(_overrides(spec, "cylinders", n)):
        conrod = row["conrod"]
        if conrod is not None:
            if row["conrod_cg_from_big_end"] is not None:
                d = row["conrod_cg_from_big_end"]
                if d > rod:
                    raise InputError(
                        "masses.conrod_cg_from_big_end",
                        f"{d * 1e3:g} mm",
                        f"must not exceed the rod length ({rod * 1e3:g} mm)",
                    )
            else:
                d = rod * (1.0 - row["conrod_rotating_fraction"])
            rotating = conrod * (rod - d) / rod
            two_mass = conrod * d * (rod - d)
            given = row["conrod_inertia"]
            conrods.append(
                ConrodSplit(
                    cylinder=c + 1,
                    mass=conrod,
                    rotating=rotating,
                    reciprocating=conrod - rotating,
                    cg_from_big_end=d,
                    inertia_two_mass=two_mass,
                    inertia_given=given,
                    inertia_error=None if given is None else two_mass - given,
                )
            )
            big_end[c] = rotating
        if row["reciprocating"] is not None:
            rec[c] = row["reciprocating"]
        else:
            rec[c] = row["piston"] + row["wrist_pin"] + (conrod - big_end[c])
    return rec, big_end, conrods


def _throw_masses(spec: EngineSpec, t: int) -> tuple[NDArray, NDArray]:
    """Rotating mass per throw and whether it came from parts (then big ends are added)."""
    r = spec.crank_train.crank_radius
    rot = np.zeros(t)
    from_parts = np.zeros(t, dtype=bool)
    for k, row in enumerate(_overrides(spec, "throws", t)):
        if row["rotating"] is not None:
            rot[k] = row["rotating"]
        else:
            from_parts[k] = True
            if row["crankpin"] is None:
                raise InputError(
                    f"masses.override (throw {k + 1})",
                    None,
                    "the rotating side needs crankpin (and crank_web) or `rotating`",
                )
            web = row["crank_web"] or 0.0
            web_r = row["crank_web_cg_radius"] or 0.0
            rot[k] = row["crankpin"] + 2.0 * web * web_r / r
    return rot, from_parts
