"""From a validated engine spec to the SI arrays of
:class:`~crankbalance.physics.model.EngineModel`.

This is the one place where the engine file's words (layout, firing order, parts or
totals, overrides) become throws, cylinders and masses; the physics modules only ever see
the model. Numbering of cylinders and throws: ``docs/engine_file.md``.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from typing import TYPE_CHECKING

import numpy as np

from ..errors import InputError
from ..physics.firing import check_firing_order, firing_tdc_angles, to_crankbalance_order
from ..physics.model import ConrodSplit, EngineModel, standard_layout, tdc_angle, vr_rows
from ..schema.engine import EngineSpec

if TYPE_CHECKING:  # imported where a spec has master-and-link rods
    from numpy.typing import NDArray

    from ..physics.articulated import Articulation

#: built models kept for the specs seen last (a spec is frozen and hashable, a model frozen
#: with read-only arrays: a study of an engine seen before skips the build, issue 30)
BUILD_CACHE = 64


def build_model(spec: EngineSpec) -> EngineModel:
    """Turn a validated :class:`~crankbalance.schema.engine.EngineSpec` into an
    :class:`EngineModel` (the same, read-only model for an equal spec seen among the last
    :data:`BUILD_CACHE`)."""
    return _built(spec)


@functools.lru_cache(maxsize=BUILD_CACHE)
def _built(spec: EngineSpec) -> EngineModel:
    """:func:`build_model`, kept by the spec; every array of the model made read-only."""
    model = _build(spec)
    for f in dataclasses.fields(model):
        value = getattr(model, f.name)
        if isinstance(value, np.ndarray):
            value.flags.writeable = False
    return model


def _build(spec: EngineSpec) -> EngineModel:
    """The model of ``spec`` (its arrays are new)."""
    ct = spec.crank_train
    positions, cylinder_throw, banks = _layout(spec)
    n = cylinder_throw.size
    offsets = cylinder_offsets(spec)
    angles = _throw_angles(spec, cylinder_throw, banks, positions.size, offsets)
    _check_given_crank(spec, angles[cylinder_throw], banks, offsets, positions.size)
    rec, big_ends, conrods = _cylinder_masses(spec, _rod_lengths(spec, n))
    rot, from_parts = _throw_masses(spec, positions.size)
    for c, t in enumerate(cylinder_throw):  # every big end on the pin turns with it
        if from_parts[t]:
            rot[t] += big_ends[c]
    axial = _rod_positions(spec, n)
    if ct.split_vee:  # each rod sits in the middle of its own pin, placed by its position
        axial = np.zeros(n)
    missing = np.flatnonzero((axial != 0) & ~np.array(_has_conrod(spec, n)))
    if missing.size:
        c = int(missing[0])
        raise InputError(
            "crank_train.rod_positions",
            f"{axial[c] * 1e3:g} mm (cylinder {c + 1})",
            "a rod off its throw's mid-plane needs its conrod mass and split (masses.conrod "
            "with conrod_rotating_fraction or conrod_cg_from_big_end): its big end turns at "
            "the rod's place and makes a rotating couple",
        )
    # moments about the crank's mid-point (the middle of the throws' extent), or the point
    # moment_reference (or moment_point) from it: every axial position of the model is
    # measured from there, and a point off the axis moves the roll moment (model docs)
    middle = 0.5 * (positions.min() + positions.max())
    point = ct.moment_point or [0.0, ct.moment_reference, 0.0]
    return EngineModel(
        name=spec.name,
        speed=spec.speed,
        kinematics=spec.kinematics,
        crank_radius=ct.crank_radius,
        rod_length=ct.rod_length,
        strokes=ct.strokes,
        throw_angle=angles,
        throw_position=positions - (middle + point[1]),
        throw_rotating_mass=rot,
        cylinder_throw=cylinder_throw,
        cylinder_bank=banks,
        reciprocating_mass=rec,
        cylinder_offset=offsets,
        cylinder_axial=axial,
        cylinder_rotating_mass=big_ends,
        firing_order=tuple(firing_order(spec) or range(1, n + 1)),
        conrods=tuple(conrods),
        firing_order_given=ct.firing_order is not None,
        articulation=_articulation(spec, banks),
        maker_number=maker_numbers(spec),
        reference_x=point[0],
        reference_z=point[2],
    )


def cylinder_offsets(spec: EngineSpec) -> NDArray[np.float64]:
    """Each cylinder's total offset [m]: ``pin_offset + crank_offset`` plus its bank's
    entry of ``bank_offsets`` or its own entry of ``cylinder_offsets``, and in VR rows
    (layout vr, or w with w_type vr) the rows' ``bore_offset``, negative in row A and
    positive in row B (the sign of :mod:`crankbalance.physics.kinematics`: the rows' bore axes meet
    beyond the crank axis when ``bore_offset`` is positive).

    Banks (docs/engine_file.md): vee A (cylinders 1..T) and B (T+1..2T); W the banks at
    -V, 0, +V, numbered bank after bank; boxer the odd cylinders (bank -90 deg) and the
    even ones (+90 deg).
    """
    ct = spec.crank_train
    n = ct.cylinder_count
    out = np.full(n, ct.pin_offset + ct.crank_offset)
    if ct.has_vr_rows:
        out += _vr_row_of(spec) * ct.bore_offset
    if ct.cylinder_offsets is not None:
        out += np.array(ct.cylinder_offsets, dtype=float)
    elif ct.bank_offsets is not None:
        if ct.layout == "boxer":
            bank = np.arange(n) % 2
        else:
            bank = np.arange(n) // (n // len(ct.bank_offsets))
        out += np.array(ct.bank_offsets, dtype=float)[bank]
    return out


def _rod_positions(spec: EngineSpec, n: int) -> NDArray:
    """Each cylinder's ``rod_positions`` entry [m] (0 when not given)."""
    rods = spec.crank_train.rod_positions
    return np.zeros(n) if rods is None else np.array(rods, dtype=float)


def _has_conrod(spec: EngineSpec, n: int) -> list[bool]:
    return [row["conrod"] is not None for row in _overrides(spec, "cylinders", n)]


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
    positions, cylinder_throw, banks = standard_layout(
        ct.layout,
        ct.cylinder_count,
        ct.bank_angle or 0.0,
        ct.crank_pitch or 0.0,
        ct.vr_angle if ct.layout == "w" and ct.has_vr_rows else None,
    )
    if ct.split_vee:
        return _split_pins(positions, cylinder_throw, banks, _rod_positions(spec, banks.size))
    return positions, cylinder_throw, banks


def _split_pins(
    positions: NDArray, cylinder_throw: NDArray, banks: NDArray, rods: NDArray
) -> tuple[NDArray, NDArray, NDArray]:
    """A vee's throws split into one pin per cylinder (``pin_split``): each pin centred
    under its rod (its throw's position plus its ``rod_positions`` entry), the pins
    numbered along the crank, throw after throw and within a throw by position (bank A
    first where the two coincide)."""
    pin_at = positions[cylinder_throw] + rods
    order = np.lexsort((banks, pin_at, cylinder_throw))  # throw, position, bank A first
    pin_of = np.empty(banks.size, dtype=np.int64)
    pin_of[order] = np.arange(banks.size)
    return pin_at[order], pin_of, banks


def _throw_angles(
    spec: EngineSpec, cylinder_throw: NDArray, banks: NDArray, throws: int, offsets: NDArray
) -> NDArray:
    ct = spec.crank_train
    if ct.layout == "custom":
        assert ct.throw is not None
        return np.array([t.angle for t in ct.throw])
    if ct.throw_angles is not None:
        return np.array(ct.throw_angles, dtype=float)
    if ct.has_vr_rows and ct.pin_split is not None:
        return _vr_pin_split_angles(spec, banks)
    if ct.split_vee:
        return _vee_pin_split_angles(spec, cylinder_throw, banks, offsets)
    if throws == 1:
        return np.zeros(1)
    n = cylinder_throw.size
    order = firing_order(spec) or list(range(1, n + 1))
    interval = (2 * np.pi if ct.strokes == 2 else 4 * np.pi) / n
    fire_time = _fire_times(spec)
    # cylinder c is at its firing TDC at crank angle t_c + t0: theta + phi - beta = psi_c,
    # psi_c = asin(e_c / (l + r)) its offset slider-crank's TDC angle (0 without offset);
    # t0 = psi of the first cylinder to fire, so one offset for all changes no throw angle
    tdc = tdc_angle(offsets, ct.crank_radius, ct.rod_length)
    first = int(order[0]) - 1
    cyl_angle = np.mod(banks + (tdc - tdc[first]) - fire_time, 2 * np.pi)
    angles = np.full(throws, np.nan)
    for c in range(n):
        t = cylinder_throw[c]
        if np.isnan(angles[t]):
            angles[t] = cyl_angle[c]
            continue
        gap = math.remainder(cyl_angle[c] - angles[t], 2 * np.pi)
        if abs(gap) > 1e-9:
            other = int(np.flatnonzero(cylinder_throw == t)[0])
            if abs(math.remainder(gap - (tdc[c] - tdc[other]), 2 * np.pi)) < 1e-9:
                raise InputError(
                    "crank_train.firing_order",
                    ct.firing_order or list(order),
                    f"cylinders {other + 1} and {c + 1} share throw {t + 1} but their offsets "
                    f"({offsets[other] * 1e3:g} and {offsets[c] * 1e3:g} mm) put their top dead "
                    f"centres {math.degrees(abs(tdc[c] - tdc[other])):.4g} deg apart, so they "
                    "cannot fire at even intervals; give the crank as crank_train.throw_angles",
                )
            raise InputError(
                "crank_train.firing_order",
                ct.firing_order or list(order),
                f"with even firing intervals of {math.degrees(interval):g} deg this order puts the "
                f"cylinders on throw {t + 1} at different throw angles; give the crank as "
                "crank_train.throw_angles (the firing order then only names the sequence)",
            )
    return angles


# --------------------------------------------------------------------------- numbering
def firing_order(spec: EngineSpec) -> list[int] | None:
    """The firing order in crankbalance's numbering (``crank_train.firing_order`` mapped
    from the maker's numbers by ``numbering`` or ``maker_numbers``), None when not given."""
    ct = spec.crank_train
    if ct.firing_order is None:
        return None
    to_ours = ct.maker_map()
    if to_ours is None:
        return [int(c) for c in ct.firing_order]
    return to_crankbalance_order(ct.firing_order, to_ours)


def maker_numbers(spec: EngineSpec) -> tuple[int, ...] | None:
    """The maker's number of each cylinder, by crankbalance's number; None without a
    maker's numbering."""
    to_ours = spec.crank_train.maker_map()
    if to_ours is None:
        return None
    maker = [0] * len(to_ours)
    for m, c in enumerate(to_ours, start=1):
        maker[c - 1] = m
    return tuple(maker)


def _check_given_crank(
    spec: EngineSpec, cylinder_angle: NDArray, banks: NDArray, offsets: NDArray, throws: int
) -> None:
    """A firing order given with a crank it does not set evenly (``throw_angles``, custom
    throws, one throw, VR rows' ``pin_split``) must be one that crank fires in
    (:func:`numbering.check_firing_order`)."""
    ct = spec.crank_train
    split = ct.pin_split is not None  # VR rows or a vee with split pins
    derived = ct.layout != "custom" and ct.throw_angles is None and not split and throws > 1
    order = firing_order(spec)
    if order is None or derived:
        return
    tdc = firing_tdc_angles(
        cylinder_angle, banks, tdc_angle(offsets, ct.crank_radius, ct.rod_length)
    )
    check_firing_order(
        tdc, order, ct.strokes, "crank_train.firing_order", ct.firing_order, maker_numbers(spec)
    )


def _fire_times(spec: EngineSpec) -> NDArray:
    """Crank angle at which each cylinder reaches its firing top dead centre, with even
    firing intervals in the order of ``firing_order`` (cylinder 1 first by default) [rad]."""
    ct = spec.crank_train
    n = ct.cylinder_count
    order = firing_order(spec) or list(range(1, n + 1))
    interval = (2 * np.pi if ct.strokes == 2 else 4 * np.pi) / n
    fire_time = np.empty(n)
    fire_time[np.array(order) - 1] = np.arange(n) * interval
    return fire_time


# --------------------------------------------------------------------------- VR rows
def _vr_row_of(spec: EngineSpec) -> NDArray:
    """Row (-1: A, +1: B) of each cylinder of a VR engine or a W from VR banks."""
    ct = spec.crank_train
    return vr_rows(ct.cylinder_count, 2 if ct.layout == "w" else 1)


def _vr_pin_split_angles(spec: EngineSpec, banks: NDArray) -> NDArray:
    """Throw angles of a VR engine or a W from VR banks whose crank is given by its
    ``pin_split`` (one throw per cylinder).

    The pins sit ``pin_split / 2`` either side of the angle a cylinder on its VR bank's
    centre line would need at its even firing time, -t + gamma -+ pin_split / 2 (rows A, B),
    the whole crank turned so that the first cylinder to fire has its pin where even firing
    puts it; the firing is even only when the split is the one even firing needs,
    v + 2 asin(e / (l + r)) (docs/engine_file.md, "VR and W from VR banks")."""
    ct = spec.crank_train
    assert ct.pin_split is not None
    fire_time = _fire_times(spec)
    rows = _vr_row_of(spec)
    narrow = ct.vr_angle if ct.layout == "w" else ct.bank_angle
    assert narrow is not None
    raw = banks - rows * narrow / 2 + rows * ct.pin_split / 2 - fire_time
    first = (firing_order(spec) or [1])[0] - 1
    return np.mod(raw + (banks[first] - fire_time[first] - raw[first]), 2 * np.pi)


def _vee_pin_split_angles(
    spec: EngineSpec, cylinder_throw: NDArray, banks: NDArray, offsets: NDArray
) -> NDArray:
    """Pin angles of a vee whose throws are split by ``pin_split`` (one pin per cylinder,
    ``cylinder_throw`` its pin).

    Each cylinder's even-firing angle is the one a standard vee gives it,
    beta + psi - t (bank, offset's TDC angle, firing time, as :func:`_throw_angles`); the
    two cylinders k and k + T of standard throw k (banks A and B) sit ``pin_split / 2``
    either side of the middle of their even-firing angles, A's pin ahead: A at
    m + s / 2 and B at m - s / 2 with m = a_A - s_k / 2 and s_k = a_A - a_B wrapped to
    (-pi, pi]; the whole crank is then turned so that the first cylinder to fire has its
    even-firing angle. The firing is even only when ``pin_split`` is s_k for every throw:
    the interval minus the bank angle when B fires one interval after A on every throw
    (docs/engine_file.md, "Split crankpins in a vee")."""
    ct = spec.crank_train
    assert ct.pin_split is not None
    n = banks.size
    t = n // 2
    fire_time = _fire_times(spec)
    tdc = tdc_angle(offsets, ct.crank_radius, ct.rod_length)
    order = firing_order(spec) or [1]
    first = int(order[0]) - 1
    even = banks + (tdc - tdc[first]) - fire_time
    a, b = even[:t], even[t:]
    need = np.remainder(a - b + np.pi, 2 * np.pi) - np.pi  # s_k in [-pi, pi)
    need = np.where(need == -np.pi, np.pi, need)
    middle = a - need / 2
    cylinder_angle = np.concatenate((middle + ct.pin_split / 2, middle - ct.pin_split / 2))
    cylinder_angle += even[first] - cylinder_angle[first]
    angles = np.empty(n)
    angles[cylinder_throw] = np.mod(cylinder_angle, 2 * np.pi)
    return angles


# --------------------------------------------------------------------------- masses
def _overrides(spec: EngineSpec, kind: str, count: int) -> list[dict[str, float]]:
    """For each cylinder (or throw), the mass fields that apply after overrides."""
    base = spec.masses.values()
    del base["override"]
    rows = [dict(base) for _ in range(count)]
    for item in spec.masses.override:
        targets = item.cylinders if kind == "cylinders" else item.throws
        if not targets:
            continue
        changed = {
            k: v
            for k, v in item.values().items()
            if v is not None and k not in ("cylinders", "throws")
        }
        for number in targets:
            rows[number - 1].update(changed)
            if kind == "cylinders" and "conrod_rotating_fraction" in changed:
                rows[number - 1]["conrod_cg_from_big_end"] = None
            if kind == "cylinders" and "conrod_cg_from_big_end" in changed:
                rows[number - 1]["conrod_rotating_fraction"] = None
    return rows


def _cylinder_masses(spec: EngineSpec, rods: NDArray) -> tuple[NDArray, NDArray, list[ConrodSplit]]:
    n = rods.size
    rec = np.zeros(n)
    big_end = np.zeros(n)
    conrods: list[ConrodSplit] = []
    for c, row in enumerate(_overrides(spec, "cylinders", n)):
        conrod = row["conrod"]
        rod = float(rods[c])
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


# --------------------------------------------------------------------------- articulated rods
def _rod_lengths(spec: EngineSpec, n: int) -> NDArray:
    """Centre distance of each cylinder's rod: the link rods' for the link cylinders of an
    articulated radial, ``rod_length`` otherwise."""
    ct = spec.crank_train
    rods = np.full(n, ct.rod_length)
    art = ct.articulated
    if art is not None:
        rods[:] = art.link_rod_length
        rods[art.master_cylinder - 1] = ct.rod_length
    return rods


def _articulation(spec: EngineSpec, banks: NDArray) -> Articulation | None:
    """The master-and-link rods of ``[crank_train.articulated]`` (None without it)."""
    art = spec.crank_train.articulated
    if art is None:
        return None
    from ..physics.articulated import Articulation, default_link_pin_angles

    n = banks.size
    master = art.master_cylinder - 1
    links = np.arange(n) != master
    angles = (
        np.array(art.link_pin_angles, dtype=float)
        if art.link_pin_angles is not None
        else default_link_pin_angles(banks, master)
    )
    return Articulation(
        master=master,
        link_rod_length=np.where(links, art.link_rod_length, 0.0),
        link_pin_radius=np.where(links, art.link_pin_radius, 0.0),
        link_pin_angle=np.where(links, angles, 0.0),
    )
