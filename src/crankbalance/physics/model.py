r"""The engine model: throws, cylinders and the mass split as SI arrays, the input of every
physics function (built from an engine spec by :mod:`crankbalance.studies.build`).

Geometry conventions (``docs/theory.md``): y along the crank axis from the crankshaft
mid-point, z along the cylinder axis of an in-line engine, x across. A throw at angle
:math:`\varphi` has its crankpin at :math:`r(\sin(\theta+\varphi), \cos(\theta+\varphi))`
in (x, z) when the first throw is at crank angle :math:`\theta`. A cylinder's bank angle
:math:`\beta` is the angle of its axis from z about the crank axis, in the same sense.
A cylinder without offset is at top dead centre when :math:`\theta + \varphi - \beta = 0`;
with the offset e (``cylinder_offset``) at :math:`\theta + \varphi - \beta =
\arcsin(e/(l+r))` (:func:`tdc_angle`).

Each cylinder has its own offset (crank offset, wrist-pin offset and the bore offset of its
bank) and its own axial position: its throw's position plus ``cylinder_axial``, the place
of its rod on a pin it shares side by side with other rods. Axial positions are measured
from the moment reference point (the crank's mid-point unless the engine file moves it,
docs/engine_file.md): every lever arm of a moment is a position of the model.

Numbering of cylinders (docs/engine_file.md): in-line and boxer: one per throw from the
y < 0 end; vee: bank A (bank angle :math:`-V/2`) is 1..T, bank B (:math:`+V/2`) is T+1..2T,
cylinders k and k+T share throw k; W: banks :math:`-V, 0, +V` numbered bank after bank;
radial: cylinder k at bank angle :math:`(k-1)\,360°/n`; custom: throw after throw;
VR (narrow-angle vee with one crankpin per cylinder): cylinder k on throw k, odd cylinders in
row A (:math:`-V/2`), even in row B (:math:`+V/2`); W from VR banks (``w_type = "vr"``): VR
bank 1 (centre :math:`-V/2`) holds cylinders 1..n/2, VR bank 2 (:math:`+V/2`) n/2+1..n, each
a VR engine of narrow angle :math:`v` (its rows at :math:`\mp v/2` about the bank centre, odd
cylinders of the bank in row A); cylinder k on throw k, and cylinders k and k + n/2 on two
throws at the same axial place (one pin, or a pin split in two).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import field, fields, replace
from functools import cached_property
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from ..errors import InputError
from ..records import record
from ..results import ResultMixin

if TYPE_CHECKING:  # the master-and-link rods are imported where they are used
    from numpy.typing import ArrayLike, NDArray

    from .articulated import ArticulatedRods, Articulation
from .firing import firing_angles
from .kinematics import KinematicsModel


@record
class ConrodSplit(ResultMixin):
    r"""Two-mass equivalent of one conrod (mass and centre of gravity kept).

    ``inertia_two_mass`` is the inertia about the CG the two point masses have,
    :math:`m\,d\,(l-d)`; ``inertia_error`` is that minus the real inertia, when the real
    one is given (None otherwise).

    Parameters
    ----------
    cylinder : int
        Number of the cylinder the conrod belongs to (1-based, docs/engine_file.md).
    mass : float
        Conrod mass [kg].
    rotating : float
        Mass at the big end, :math:`m\,(l-d)/l` [kg].
    reciprocating : float
        Mass at the small end, :math:`m\,d/l` [kg].
    cg_from_big_end : float
        :math:`d`, distance of the conrod's centre of gravity from the big-end centre [m].
    inertia_two_mass : float
        Moment of inertia of the two point masses about the centre of gravity,
        :math:`m\,d\,(l-d)` [kg m^2].
    inertia_given : float or None
        Real moment of inertia of the conrod about its centre of gravity [kg m^2], None
        when not given.
    inertia_error : float or None
        ``inertia_two_mass - inertia_given`` [kg m^2], None when the real inertia is not
        given.

    References
    ----------
    The two-mass equivalent conrod of machine-dynamics texts, e.g. Den Hartog (1956) ch. 5.
    """

    cylinder: int
    mass: float
    rotating: float
    reciprocating: float
    cg_from_big_end: float
    inertia_two_mass: float
    inertia_given: float | None
    inertia_error: float | None


def _read_only(array: NDArray[Any]) -> NDArray[Any]:
    """``array``, made read-only (a derived array a model keeps and hands out)."""
    array.flags.writeable = False
    return array


@record
class EngineModel:
    """An engine as SI arrays: the input of every physics function.

    Attributes
    ----------
    name : str
        Engine name, for reports.
    kinematics : {"exact", "series", "first-order"}
        Piston kinematics model, see :func:`crankbalance.physics.kinematics.harmonic_coefficients`.
    strokes : int
        Strokes per working cycle (2 or 4).
    crank_radius, rod_length : float
        [m].
    speed : float
        Crank speed [rad/s].
    throw_angle, throw_position, throw_rotating_mass : ndarray, shape (T,)
        [rad], [m along the crank axis from the moment reference point (the crank's
        mid-point by default)], [kg at the crank radius, crankpin, webs reduced to the
        crank radius and all big ends on the pin].
    cylinder_throw : ndarray of int, shape (C,)
        Index of the throw each cylinder sits on.
    cylinder_bank, reciprocating_mass : ndarray, shape (C,)
        [rad], [kg].
    cylinder_offset : ndarray, shape (C,)
        Each cylinder's total offset [m]: crank offset plus wrist-pin offset plus the bore
        offset of its bank, the lateral distance of its wrist-pin path from the crank axis
        (sign as in :mod:`crankbalance.physics.kinematics`).
    cylinder_axial : ndarray, shape (C,)
        Axial position of each cylinder's rod on its crankpin, from the throw's centre
        along the crank axis [m] (0: in the throw's mid-plane).
    cylinder_rotating_mass : ndarray, shape (C,)
        The rotating part of each rod's big end [kg] that ``throw_rotating_mass`` includes
        and that sits at the rod's own axial position (0 where the big end is not known
        apart from the throw's total); it moves no mass, only where the throw's rotating
        mass acts along the crank axis (:attr:`throw_rotating_moment`).
    firing_order : tuple of int
        Cylinder numbers (1-based) in firing order.
    conrods : tuple of ConrodSplit
        The two-mass split of each conrod given by its mass, empty when none is.
    firing_order_given : bool
        False when the spec gave no firing order and ``firing_order`` is the cylinder order.
    articulation : Articulation or None
        Master-and-link rods of a radial (:mod:`crankbalance.physics.articulated`): the master
        cylinder, link rod lengths, link pin radii and angles; None when every rod's big
        end is on its crankpin. When given, the pistons follow the exact articulated
        motion (:func:`crankbalance.physics.shaking.cylinder_coefficients`), and the link rods'
        big ends (``cylinder_rotating_mass``, counted in ``throw_rotating_mass`` like
        every big end) add their motion relative to the crankpin.
    maker_number : tuple of int or None
        The maker's number of each cylinder (by crankbalance's number) when the engine
        file gives its firing order in a maker's numbering (``crank_train.numbering`` or
        ``maker_numbers``); only shown in outputs, no computation uses it. None otherwise.
    reference_x, reference_z : float
        The moment reference point's distance from the crank axis [m], across (x) and
        along the cylinder axis of an in-line engine (z); its place along the crank is
        the origin of the axial positions. They move only the roll moment (about y): the
        forces have no y component (:func:`with_moment_point`).
    """

    name: str
    speed: float
    kinematics: KinematicsModel
    crank_radius: float
    rod_length: float
    strokes: int
    throw_angle: NDArray[np.float64]
    throw_position: NDArray[np.float64]
    throw_rotating_mass: NDArray[np.float64]
    cylinder_throw: NDArray[np.int64]
    cylinder_bank: NDArray[np.float64]
    reciprocating_mass: NDArray[np.float64]
    cylinder_offset: NDArray[np.float64]
    cylinder_axial: NDArray[np.float64]
    cylinder_rotating_mass: NDArray[np.float64]
    firing_order: tuple[int, ...]
    conrods: tuple[ConrodSplit, ...] = field(default=())
    firing_order_given: bool = True
    articulation: Articulation | None = None
    maker_number: tuple[int, ...] | None = None
    reference_x: float = 0.0
    reference_z: float = 0.0

    @property
    def rod_ratio(self) -> float:
        return self.crank_radius / self.rod_length

    @property
    def cylinders(self) -> int:
        return int(self.cylinder_bank.size)

    @property
    def throws(self) -> int:
        return int(self.throw_angle.size)

    # The derived arrays below are computed once per model (a frozen model: its arrays are
    # read-only when studies.build made them) and returned read-only.
    @cached_property
    def cylinder_angle(self) -> NDArray[np.float64]:
        """Throw angle of each cylinder's crankpin [rad]."""
        return _read_only(self.throw_angle[self.cylinder_throw])

    @cached_property
    def cylinder_position(self) -> NDArray[np.float64]:
        """Axial position of each cylinder's rod [m]: its throw's plus ``cylinder_axial``."""
        return _read_only(self.throw_position[self.cylinder_throw] + self.cylinder_axial)

    @property
    def moment_reference(self) -> float:
        """Position of the moment reference point from the crank's mid-point (the middle of
        the throws' extent) along the crank axis [m]; 0 unless the engine file moves it."""
        return -0.5 * float(self.throw_position.min() + self.throw_position.max())

    @property
    def moment_point(self) -> tuple[float, float, float]:
        """The moment reference point (x, y, z) [m], y from the crank's mid-point."""
        return (self.reference_x, self.moment_reference, self.reference_z)

    @cached_property
    def throw_axial_moment(self) -> NDArray[np.float64]:
        r"""First moment of each throw's big ends about the throw's centre,
        :math:`\sum_c m_{b,c}\,a_c` over the rods on the throw [kg m], shape (T,)."""
        return _read_only(
            np.bincount(
                self.cylinder_throw,
                self.cylinder_rotating_mass * self.cylinder_axial,
                minlength=self.throws,
            ).astype(float)
        )

    @cached_property
    def throw_rotating_moment(self) -> NDArray[np.float64]:
        r"""First moment of each throw's rotating mass about the moment reference point,
        :math:`m_t y_t + \sum_c m_{b,c} a_c` [kg m], shape (T,): the lever arm of the
        rotating couple, with the big ends of side-by-side rods at their own positions."""
        return _read_only(self.throw_rotating_mass * self.throw_position + self.throw_axial_moment)

    @cached_property
    def derived(self) -> dict[tuple[object, ...], Any]:
        """Read-only arrays (or frozen records of them) that functions derive from this
        model alone and keep for the next call on it, keyed by the function's name and
        arguments (the harmonic coefficient rows of
        :func:`crankbalance.physics.shaking.cylinder_coefficients`, the roll harmonics and
        weights of :func:`crankbalance.physics.shaking.roll_phasors`, the weights of the
        sums and the rotating masses' phasors of
        :func:`crankbalance.physics.shaking.free_forces`, the round-off levels of
        :func:`crankbalance.studies.engine.without_round_off`, the balancing solver's
        input of :func:`crankbalance.physics.balance_solver.model_input`): a model is
        frozen, so they hold as long as it lives."""
        return {}

    @property
    def articulated_rods(self) -> ArticulatedRods | None:
        """The full geometry of the master-and-link rods (None without ``articulation``)."""
        if self.articulation is None:
            return None
        return self.articulation.rods(
            self.crank_radius, self.rod_length, self.cylinder_bank, self.cylinder_offset
        )

    def __post_init__(self) -> None:
        c = self.cylinder_bank.shape
        for name in ("cylinder_offset", "cylinder_axial", "cylinder_rotating_mass"):
            if np.shape(getattr(self, name)) != c:
                raise ValueError(f"EngineModel.{name}: shape {c} (one per cylinder) expected")


def with_moment_point(model: EngineModel, point: Sequence[float]) -> EngineModel:
    """The same engine with its moments taken about another point.

    Parameters
    ----------
    model : EngineModel
        The engine.
    point : sequence of three floats
        The new reference point (x, y, z) [m]: y along the crank axis from the crank's
        mid-point, x and z across it (the axes of ``docs/theory.md``).

    Returns
    -------
    EngineModel
        ``model`` with its axial positions measured from the new point's y and the
        point's x and z as ``reference_x`` and ``reference_z``.
    """
    x, y, z = (float(v) for v in point)
    shift = model.moment_reference - y  # old reference minus new, along +y
    return replace(
        model,
        throw_position=model.throw_position + shift,
        reference_x=x,
        reference_z=z,
    )


def tdc_angle(
    offset: ArrayLike, crank_radius: ArrayLike, rod_length: ArrayLike
) -> NDArray[np.float64]:
    r"""Crank angle from the cylinder axis at which an offset piston is at top dead centre.

    Parameters
    ----------
    offset : array_like
        Lateral distance of the wrist-pin path from the crank axis [m], signed as in
        :mod:`crankbalance.physics.kinematics`.
    crank_radius : array_like
        Crank radius [m].
    rod_length : array_like
        Conrod length [m].

    Returns
    -------
    ndarray
        :math:`\psi_{TDC} = \arcsin(e/(l+r))` [rad]: crankpin, big end and wrist pin in
        one line, the piston farthest from the crank axis.

    References
    ----------
    The desaxé slider-crank of machine-dynamics texts, e.g. Taylor (1985) ch. 8.
    """
    e = np.asarray(offset, dtype=float)
    return np.arcsin(e / (np.asarray(rod_length, dtype=float) + np.asarray(crank_radius)))


def tdc_shift(model: EngineModel) -> NDArray[np.float64]:
    """Each cylinder's top dead centre past its axis (its offset slider-crank).

    Parameters
    ----------
    model : EngineModel
        The engine: offsets [m], crank radius [m], rod length [m].

    Returns
    -------
    ndarray, shape (C,)
        :func:`tdc_angle` of each cylinder [rad].
    """
    return np.asarray(
        tdc_angle(model.cylinder_offset, model.crank_radius, model.rod_length), dtype=float
    ).reshape(-1)


def model_fire_angles(model: EngineModel) -> NDArray[np.float64]:
    """Crank angle of the first throw at which each cylinder of an engine fires.

    Its firing order when the engine gives one, else the most even firing its crank
    allows (:func:`crankbalance.physics.firing.firing_angles`, with each cylinder's top
    dead centre past its axis).

    Parameters
    ----------
    model : EngineModel
        The engine: throw [rad] and bank angles [rad] per cylinder, offsets [m], crank
        radius [m], rod length [m], strokes, firing order.

    Returns
    -------
    ndarray, shape (C,)
        Firing angle of each cylinder [rad], in [0, 2π·strokes/2).
    """
    order = model.firing_order if model.firing_order_given else None
    return firing_angles(
        model.cylinder_angle, model.cylinder_bank, order, model.strokes, tdc_shift(model)
    )


def standard_layout(
    layout: str,
    cylinders: int,
    bank_angle: float = 0.0,
    pitch: float = 0.0,
    vr_angle: float | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.float64]]:
    """Throws and cylinders of a standard layout, numbered as in the module docstring.

    Parameters
    ----------
    layout : {"inline", "boxer", "vee", "w", "radial", "vr"}
        Layout name, as in the engine file.
    cylinders : int
        Number of cylinders (even for vee, boxer and a W from VR banks, a multiple of 3 for
        a broad-arrow W).
    bank_angle : float
        Vee angle V, the angle between neighbouring banks of a broad-arrow W, the angle
        between the two VR banks of a W from VR banks, or the narrow angle between the two
        rows of a VR engine [rad]; not used for the other layouts.
    pitch : float
        Distance between neighbouring throws along the crank axis [m]; for a W from VR banks
        the distance between neighbouring pairs of throws.
    vr_angle : float, optional
        Layout "w" only: when given, the W is built from two VR banks and this is the narrow
        angle v between the two rows of each VR bank [rad]; None for a broad-arrow W.

    Returns
    -------
    throw_position : ndarray, shape (T,)
        Axial position of each throw [m from the crank's mid-point].
    cylinder_throw : ndarray of int, shape (C,)
        Index of the throw each cylinder sits on.
    cylinder_bank : ndarray, shape (C,)
        Bank angle of each cylinder [rad].
    """
    if layout == "vr" or (layout == "w" and vr_angle is not None):
        return _vr_layout(cylinders, bank_angle, pitch, vr_angle)
    n = cylinders
    t = {"vee": n // 2, "w": n // 3, "radial": 1}.get(layout, n)
    positions = ((np.arange(t) - (t - 1) / 2.0) * pitch).astype(float)
    v = bank_angle
    throw_of: NDArray
    banks: NDArray
    if layout == "inline":
        throw_of, banks = np.arange(n), np.zeros(n)
    elif layout == "boxer":
        throw_of = np.arange(n)
        banks = np.where(np.arange(n) % 2 == 0, -np.pi / 2, np.pi / 2)
    elif layout == "vee":
        throw_of = np.tile(np.arange(t), 2)
        banks = np.repeat([-v / 2, v / 2], t)
    elif layout == "w":
        throw_of = np.tile(np.arange(t), 3)
        banks = np.repeat([-v, 0.0, v], t)
    else:  # radial
        throw_of = np.zeros(n, dtype=np.int64)
        banks = 2 * np.pi * np.arange(n) / n
    return positions, throw_of.astype(np.int64), banks.astype(np.float64)


def vr_rows(cylinders: int, vr_banks: int = 1) -> NDArray[np.int64]:
    """Row of each cylinder of a VR engine or of a W from VR banks: -1 for row A, +1 for row B.

    Parameters
    ----------
    cylinders : int
        Number of cylinders (even when ``vr_banks`` is 2).
    vr_banks : {1, 2}
        1 for layout "vr", 2 for a W from VR banks.

    Returns
    -------
    ndarray of int, shape (C,)
        -1 for the row at minus half the narrow angle about its VR bank's centre line, +1
        for the row at plus half: odd cylinders of each VR bank (counted from its first
        cylinder) in row A, even in row B.
    """
    per_bank = cylinders // vr_banks
    k = np.tile(np.arange(per_bank), vr_banks)
    return np.where(k % 2 == 0, -1, 1).astype(np.int64)


def _vr_layout(
    cylinders: int, bank_angle: float, pitch: float, vr_angle: float | None
) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.float64]]:
    """:func:`standard_layout` of a VR engine (``vr_angle`` None, ``bank_angle`` its narrow
    angle) or of a W from two VR banks (``bank_angle`` between the banks, ``vr_angle``)."""
    n = cylinders
    if vr_angle is None:  # VR: one row of throws, rows alternating along the crank
        rows = vr_rows(n, 1)
        positions = (np.arange(n) - (n - 1) / 2.0) * pitch
        banks = rows * bank_angle / 2
    else:  # W: VR bank 1 on throws 1..n/2, VR bank 2 on n/2+1..n, pairs at one place
        half = n // 2
        rows = vr_rows(n, 2)
        positions = np.tile((np.arange(half) - (half - 1) / 2.0) * pitch, 2)
        banks = np.repeat([-bank_angle / 2, bank_angle / 2], half) + rows * vr_angle / 2
    return (
        positions.astype(np.float64),
        np.arange(n, dtype=np.int64),
        banks.astype(np.float64),
    )


# --------------------------------------------------------------------------- batches
@record
class EngineBatch:
    """Many engines of one topology: arrays with a leading engine axis (E engines).

    The ``topology`` fixes what the engines share: the throws' axial positions, the throw
    and bank angle of each cylinder and the kinematics model. Each engine has its own throw
    angles, masses, crank radius, conrod length, cylinder offsets and speed. Rods side by
    side on a pin keep the topology's places (``cylinder_axial``) and big-end masses
    (``cylinder_rotating_mass``). Build it with :func:`engine_batch` or
    :func:`stack_models`; master-and-link rods (``articulation``) are refused there (each
    engine's rods would need their own geometry).

    Parameters
    ----------
    topology : EngineModel
        The shared layout (its throw angles, masses, radius, rod length, offset and speed
        are not used).
    throw_angle : ndarray, shape (E, T)
        Throw angles [rad].
    throw_rotating_mass : ndarray, shape (E, T)
        Rotating mass of each throw at the crank radius [kg].
    reciprocating_mass : ndarray, shape (E, C)
        Reciprocating mass of each cylinder [kg].
    crank_radius, rod_length : ndarray, shape (E,)
        Crank radius and conrod length [m].
    cylinder_offset : ndarray, shape (E, C)
        Each cylinder's total offset (crank, wrist-pin and bank offsets) [m].
    speed : ndarray, shape (E,)
        Crank speed [rad/s].
    """

    topology: EngineModel
    throw_angle: NDArray[np.float64]
    throw_rotating_mass: NDArray[np.float64]
    reciprocating_mass: NDArray[np.float64]
    crank_radius: NDArray[np.float64]
    rod_length: NDArray[np.float64]
    cylinder_offset: NDArray[np.float64]
    speed: NDArray[np.float64]

    @property
    def size(self) -> int:
        """Number of engines E."""
        return int(self.crank_radius.size)

    def model(self, index: int) -> EngineModel:
        """Engine ``index`` as an :class:`EngineModel`, for the one-engine functions."""
        return replace(
            self.topology,
            throw_angle=self.throw_angle[index].copy(),
            throw_rotating_mass=self.throw_rotating_mass[index].copy(),
            reciprocating_mass=self.reciprocating_mass[index].copy(),
            crank_radius=float(self.crank_radius[index]),
            rod_length=float(self.rod_length[index]),
            cylinder_offset=self.cylinder_offset[index].copy(),
            speed=float(self.speed[index]),
        )

    def take(self, index: slice | NDArray[np.int64]) -> EngineBatch:
        """The engines ``index`` (a slice or integer indices) as a batch."""
        return take(self, index)

    @property
    def throw_position(self) -> NDArray[np.float64]:
        """Axial position of each throw, shared by the engines (the topology's) [m]."""
        return self.topology.throw_position

    PER_ENGINE: ClassVar[tuple[str, ...]] = (
        "throw_angle",
        "throw_rotating_mass",
        "reciprocating_mass",
        "crank_radius",
        "rod_length",
        "cylinder_offset",
        "speed",
    )


def engine_batch(
    topology: EngineModel,
    size: int | None = None,
    *,
    throw_angle: ArrayLike | None = None,
    throw_rotating_mass: ArrayLike | None = None,
    reciprocating_mass: ArrayLike | None = None,
    crank_radius: ArrayLike | None = None,
    rod_length: ArrayLike | None = None,
    cylinder_offset: ArrayLike | None = None,
    speed: ArrayLike | None = None,
) -> EngineBatch:
    """Engines of one topology from arrays; what is not given is the topology's value.

    An array with a leading engine axis gives one value per engine; without it (per-throw
    and per-cylinder arrays of one dimension, scalars) the value is shared by all engines.

    Parameters
    ----------
    topology : EngineModel
        The shared layout and the default of every value not given.
    size : int, optional
        Number of engines E; default the leading axis of the arrays given (1 if none has
        one).
    throw_angle : array_like, shape (E, T) or (T,), optional
        Throw angles [rad].
    throw_rotating_mass : array_like, shape (E, T) or (T,), optional
        Rotating mass of each throw at the crank radius [kg].
    reciprocating_mass : array_like, shape (E, C) or (C,), optional
        Reciprocating mass of each cylinder [kg].
    crank_radius, rod_length : array_like, shape (E,) or scalar, optional
        Crank radius and conrod length [m].
    cylinder_offset : array_like, shape (E, C) or (C,), optional
        Each cylinder's total offset (crank, wrist-pin and bank offsets) [m].
    speed : array_like, shape (E,) or scalar, optional
        Crank speed [rad/s].

    Returns
    -------
    EngineBatch
        The engines, every array with its leading engine axis.

    Raises
    ------
    InputError
        If the arrays disagree on the number of engines or have the wrong shape, or an
        engine has a non-finite value, a crank radius or speed not above zero, a negative
        mass, or a conrod not longer than the crank radius plus the offset; or the
        topology has master-and-link rods.
    """
    if topology.articulation is not None:
        raise InputError(
            "articulation",
            topology.name,
            "master-and-link rods are not modelled for a batch of engines; analyse and "
            "balance this engine on its own",
        )
    tails = {
        "throw_angle": (topology.throws,),
        "throw_rotating_mass": (topology.throws,),
        "reciprocating_mass": (topology.cylinders,),
        "crank_radius": (),
        "rod_length": (),
        "cylinder_offset": (topology.cylinders,),
        "speed": (),
    }
    arguments = {
        "throw_angle": throw_angle,
        "throw_rotating_mass": throw_rotating_mass,
        "reciprocating_mass": reciprocating_mass,
        "crank_radius": crank_radius,
        "rod_length": rod_length,
        "cylinder_offset": cylinder_offset,
        "speed": speed,
    }
    given = {k: np.asarray(v, dtype=float) for k, v in arguments.items() if v is not None}
    sizes = {a.shape[0] for k, a in given.items() if a.ndim == len(tails[k]) + 1}
    if size is not None:
        sizes.add(size)
    if len(sizes) > 1 or min(sizes, default=1) < 1:
        raise InputError(
            "engine_batch", sorted(sizes), "one number of engines, 1 or more, for every array"
        )
    n = sizes.pop() if sizes else 1
    values: dict[str, NDArray] = {}
    for name, tail in tails.items():
        value = given.get(name, np.asarray(getattr(topology, name), dtype=float))
        try:
            values[name] = np.array(np.broadcast_to(value, (n, *tail)), dtype=float)
        except ValueError:
            raise InputError(name, list(np.shape(value)), f"shape {(n, *tail)} or {tail}") from None
    _check_batch(values)
    return EngineBatch(topology, **values)


def _check_batch(values: dict[str, NDArray]) -> None:
    """Raise :class:`InputError` for the first engine with an impossible value."""
    r, length = values["crank_radius"], values["rod_length"]
    e = np.abs(values["cylinder_offset"]).max(axis=-1, initial=0.0)
    checks = [(name, np.isfinite(a), "must be finite") for name, a in values.items()]
    checks += [
        ("crank_radius", r > 0, "must be greater than zero"),
        ("speed", values["speed"] > 0, "must be greater than zero"),
        ("throw_rotating_mass", values["throw_rotating_mass"] >= 0, "must be zero or more"),
        ("reciprocating_mass", values["reciprocating_mass"] >= 0, "must be zero or more"),
        ("rod_length", length > r + np.abs(e), "must exceed the crank radius plus the offset"),
    ]
    for name, ok, allowed in checks:
        bad = np.flatnonzero(~ok.reshape(ok.shape[0], -1).all(axis=1))
        if bad.size:
            i = int(bad[0])
            raise InputError(name, values[name][i].tolist(), f"{allowed} (engine {i})")


def stack_models(models: Sequence[EngineModel]) -> EngineBatch:
    """Engine models of one topology stacked into a batch.

    Parameters
    ----------
    models : sequence of EngineModel
        The engines; all have the throw positions, cylinder throws and bank angles and the
        kinematics model of the first.

    Returns
    -------
    EngineBatch
        The engines in the order given (the first is the topology).

    Raises
    ------
    InputError
        If ``models`` is empty, an engine has master-and-link rods or its topology differs
        from the first's.
    """
    if not models:
        raise InputError("models", [], "at least one engine")
    for i, m in enumerate(models):
        if m.articulation is not None:
            raise InputError(
                f"models[{i}]",
                m.name,
                "has master-and-link rods, which the batch solver does not model; "
                "balance it on its own (balance)",
            )
    first = models[0]
    for i, m in enumerate(models):
        same = (
            m.kinematics == first.kinematics
            and np.array_equal(m.throw_position, first.throw_position)
            and np.array_equal(m.cylinder_throw, first.cylinder_throw)
            and np.array_equal(m.cylinder_bank, first.cylinder_bank)
            and np.array_equal(m.cylinder_axial, first.cylinder_axial)
            and np.array_equal(m.cylinder_rotating_mass, first.cylinder_rotating_mass)
        )
        if not same:
            raise InputError(
                "models",
                f"engine {i} ({m.name})",
                "engines of one topology: the throw positions, cylinder throws, bank "
                "angles, rod places, big ends and kinematics of the first",
            )
    return engine_batch(
        first,
        len(models),
        throw_angle=[m.throw_angle for m in models],
        throw_rotating_mass=[m.throw_rotating_mass for m in models],
        reciprocating_mass=[m.reciprocating_mass for m in models],
        crank_radius=[m.crank_radius for m in models],
        rod_length=[m.rod_length for m in models],
        cylinder_offset=[m.cylinder_offset for m in models],
        speed=[m.speed for m in models],
    )


def take(obj: Any, index: slice | NDArray[np.int64]) -> Any:
    """The engines ``index`` (a slice or integer indices) of a batch dataclass: an
    :class:`EngineBatch` or a batch result (its ``PER_ENGINE`` arrays, recursively).

    Parameters
    ----------
    obj : dataclass with PER_ENGINE, or None
        The batch (None gives None).
    index : slice or ndarray of int
        Which engines [-].

    Returns
    -------
    dataclass or None
        The same type, every per-engine array indexed.
    """
    return per_engine(obj, lambda a: a[index])


def per_engine(obj: Any, func: Callable[[NDArray[Any]], NDArray[Any]]) -> Any:
    """A batch dataclass with ``func`` applied to its ``PER_ENGINE`` arrays, recursively
    (into fields that are batch dataclasses themselves).

    Parameters
    ----------
    obj : dataclass with PER_ENGINE, or None
        The batch (None gives None).
    func : callable
        Applied to each per-engine array (leading engine axis) [-].

    Returns
    -------
    dataclass or None
        The same type with the arrays ``func`` returned.
    """
    if obj is None:
        return None
    changes = {}
    for f in fields(obj):
        value = getattr(obj, f.name)
        if f.name in obj.PER_ENGINE and value is not None:
            changes[f.name] = func(value)
        elif hasattr(value, "PER_ENGINE"):
            changes[f.name] = per_engine(value, func)
    return replace(obj, **changes)
