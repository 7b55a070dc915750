"""What the balancing solver takes and gives: its options, its input arrays and its
results, for E engines of one layout at once (E = 1 for one engine).

:mod:`crankbalance.physics.balance_solver` solves (its docstring has the equations and
sources), :mod:`crankbalance.physics.balance_counterweights` sizes the crank
counterweights; :mod:`crankbalance.physics.balancing` turns a result of one engine into
:class:`~crankbalance.physics.balancing.BalanceResult`, and
:mod:`crankbalance.physics.balance_batch` gathers the chunks of a batch.
"""

from __future__ import annotations

from dataclasses import field
from functools import cached_property
from typing import TYPE_CHECKING, Any, ClassVar, Literal

import numpy as np

from ..errors import InputError
from ..records import record
from ..results import ResultMixin
from .shaking import BatchFreeForces

if TYPE_CHECKING:  # annotations only: numpy.typing costs every command's start
    from numpy.typing import NDArray

Method = Literal["pattern", "individual"]
Scope = Literal["auto", "whole", "halves"]
Arrangement = Literal["pair", "counter-rotating"]


# --------------------------------------------------------------------------- options
@record
class CounterweightOptions:
    """Crank counterweights: web pattern, CG radius, angle, balance factor, scope.

    ``webs`` holds 0/1 for each web, two per throw (None: all webs). ``angle`` is the
    turn :math:`\\alpha` [rad] from the position opposite the crankpin, or ``"optimal"``.
    ``web_offset`` is the axial distance of each web from its throw mid-plane [m]
    (the paper's a/4 when None).

    Parameters
    ----------
    cg_radius : float
        Radius of the counterweights' centre of gravity, :math:`r_c` [m].
    webs : tuple of int, optional
        0/1 per web, two per throw from the y < 0 end (the paper's :math:`Y_{cw}`); None:
        a counterweight on every web.
    angle : float or "optimal"
        Turn :math:`\\alpha` of the pattern from the position opposite the crankpin [rad],
        or ``"optimal"`` for the least-mass angle that balances.
    balance_factor : float
        Share :math:`f_b` of the reciprocating masses the counterweights carry on top of
        the rotating masses [-].
    scope : {"auto", "whole", "halves"}
        Balance the crank as a whole or each half on its own; ``"auto"`` (the default) is
        the whole crank, and a crank already balanced as a whole gets no counterweight
        mass (``"halves"`` gives each half its own, to relieve the main bearings).
    method : {"pattern", "individual"}
        The paper's equal-mass pattern, or each counterweight its own mass and angle
        (least :math:`\\sum m_j^2`).
    web_offset : float, optional
        Axial distance of each web from its throw mid-plane [m]; default a quarter of the
        throw pitch, half the crank radius for one throw
        (:func:`crankbalance.physics.balance_counterweights.web_geometry`).

    References
    ----------
    Appl. Sci. 2021, section 2 (Eqs. 6-11), with the sign-rule reading of
    docs/references.md.
    """

    cg_radius: float
    webs: tuple[int, ...] | None = None
    angle: float | Literal["optimal"] = 0.0
    balance_factor: float = 0.0
    scope: Scope = "auto"
    method: Method = "pattern"
    web_offset: float | None = None


@record
class ShaftOptions:
    """Balance shafts of one order: ``pair`` (co- and counter-rotating) or a single
    ``counter-rotating`` shaft; CG radius of their masses and distance between the outer
    masses [m]. The shafts' mid-point is taken in the crank's mid-plane (y = 0).

    Parameters
    ----------
    cg_radius : float
        Radius of the centre of gravity of the shaft masses, :math:`r_{c1}` or
        :math:`r_{c2}` [m].
    length : float
        Axial distance between the outer masses, :math:`l_{sh}` [m].
    arrangement : {"pair", "counter-rotating"}
        A co- and a counter-rotating shaft, or a single counter-rotating shaft.

    References
    ----------
    Appl. Sci. 2021, section 3 (Eqs. 13-22), with the errata of docs/references.md.
    """

    cg_radius: float
    length: float
    arrangement: Arrangement = "pair"


# --------------------------------------------------------------------------- the input
@record
class SolverInput:
    """What the solver needs of E engines of one layout: arrays with a leading engine
    axis (E = 1 for one engine). Build it with
    :func:`crankbalance.physics.balance_solver.solver_input`.

    Parameters
    ----------
    throw_position : ndarray, shape (T,)
        Axial position of each throw from the moment reference point [m].
    throw_angle : ndarray, shape (E, T)
        Throw angles [rad].
    rotating, rotating_couple : ndarray of complex, shape (E, T)
        First moment of each throw's rotating masses, :math:`m_t r e^{i\\varphi_t}` [kg·m],
        and its moment along the crank (big ends of side-by-side rods at their own places)
        [kg·m²].
    reciprocating, reciprocating_couple : ndarray of complex, shape (E, T)
        The same for the reciprocating masses on each throw's pin [kg·m], [kg·m²].
    forces : BatchFreeForces
        The free forces of every engine, orders 1..K (K at least 2) [N], [N·m].
    crank_radius, speed : ndarray, shape (E,)
        Crank radius [m] and crank speed [rad/s].
    length : ndarray, shape (E,)
        Length scale of each engine [m] (:func:`crankbalance.results.engine_scales`).
    force_round_off, moment_round_off : ndarray, shape (E,)
        Round-off levels of forces [N] and moments [N·m]
        (:func:`crankbalance.results.round_off`).
    memo : dict
        What the solver derives from these engines alone (the webs and the equations of
        the counterweights of each web choice), kept for the next solve of the same input:
        one engine's input is kept by its model
        (:func:`crankbalance.physics.balance_solver.model_input`).
    """

    throw_position: NDArray[np.float64]
    throw_angle: NDArray[np.float64]
    rotating: NDArray[np.complex128]
    rotating_couple: NDArray[np.complex128]
    reciprocating: NDArray[np.complex128]
    reciprocating_couple: NDArray[np.complex128]
    forces: BatchFreeForces
    crank_radius: NDArray[np.float64]
    speed: NDArray[np.float64]
    length: NDArray[np.float64]
    force_round_off: NDArray[np.float64]
    moment_round_off: NDArray[np.float64]
    memo: dict[tuple[object, ...], Any] = field(default_factory=dict, compare=False, repr=False)

    @property
    def size(self) -> int:
        """Number of engines E."""
        return int(self.speed.size)

    @cached_property
    def speed_squared(self) -> NDArray[np.float64]:
        """``speed**2`` of every engine, shape (E,) [rad²/s²]: computed once per input
        (one engine's is kept by its model), read-only."""
        found = self.speed**2
        found.flags.writeable = False
        return found


# --------------------------------------------------------------------------- errors
class EngineFailed(Exception):
    """An :class:`~crankbalance.errors.InputError` of one engine of a solver call:
    the one-engine solver raises ``error`` itself, the batch names the engine.

    Parameters
    ----------
    error : InputError
        What is wrong, as for one engine.
    engine : int
        Index of the engine in the :class:`SolverInput` [-].
    """

    def __init__(self, error: InputError, engine: int) -> None:
        super().__init__(str(error))
        self.error = error
        self.engine = engine


# --------------------------------------------------------------------------- results
@record
class BatchCounterweights(ResultMixin):
    """Crank counterweights of E engines (W per engine; one engine's are
    :class:`crankbalance.physics.balancing.Counterweights`).

    Parameters
    ----------
    method : {"pattern", "individual"}
        How the counterweights were sized.
    cg_radius : float
        Radius of the counterweights' centre of gravity [m].
    web : ndarray of int, shape (W,)
        Web number of each counterweight (1-based, two per throw).
    throw : ndarray of int, shape (W,)
        Throw number of each counterweight (1-based).
    position : ndarray, shape (E, W)
        Axial position from the crankshaft mid-point [m].
    mass : ndarray, shape (E, W)
        Mass at ``cg_radius`` [kg].
    direction : ndarray, shape (E, W)
        Direction at crank angle 0, from +z toward +x [rad].
    alpha : ndarray, shape (E,)
        Turn angle of the pattern [rad]; 0 for ``individual`` and where the crank needed
        no counterweight (the one-engine solver's None).
    halves : ndarray of bool, shape (E,)
        Whether each half of the crank was balanced on its own (else the whole crank).
    flipped : ndarray of bool, shape (E,)
        Whether the pattern pointed toward the crankpins and was flipped.
    already_balanced : ndarray of bool, shape (E,)
        Whether there was nothing to cancel (all masses zero).
    missed_force : ndarray, shape (E,)
        How far the counterweights fall short of their target, the crank-speed forward
        force the target asked them to cancel and they leave (zero at most the engine's
        round-off; more where an equal-mass pattern at a given angle cannot reach it) [N].
    missed_moment : ndarray, shape (E,)
        The same for the moment [N·m].
    """

    method: str
    cg_radius: float
    web: NDArray[np.int64]
    throw: NDArray[np.int64]
    position: NDArray[np.float64]
    mass: NDArray[np.float64]
    direction: NDArray[np.float64]
    alpha: NDArray[np.float64]
    halves: NDArray[np.bool_]
    flipped: NDArray[np.bool_]
    already_balanced: NDArray[np.bool_]
    missed_force: NDArray[np.float64]
    missed_moment: NDArray[np.float64]

    PER_ENGINE: ClassVar[tuple[str, ...]] = (
        "position",
        "mass",
        "direction",
        "alpha",
        "halves",
        "flipped",
        "already_balanced",
        "missed_force",
        "missed_moment",
    )

    @cached_property
    def moments(self) -> NDArray[np.complex128]:
        """Complex first moments :math:`m\\rho e^{i\\psi}`, shape (E, W) [kg·m]; computed
        once per record (or handed in by the solver, which computed them) and read-only."""
        found = self.mass * self.cg_radius * np.exp(1j * self.direction)
        found.flags.writeable = False
        return found

    @cached_property
    def moment_sums(self) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
        """Each engine's sum of :attr:`moments` [kg·m] and of their moments along the crank,
        :math:`\\sum m\\rho e^{i\\psi} y` [kg·m²], shapes (E,); computed once per record (or
        handed in by the solver) and read-only."""
        sums = (self.moments.sum(axis=-1), (self.moments * self.position).sum(axis=-1))
        for array in sums:
            array.flags.writeable = False
        return sums


@record
class BatchShafts(ResultMixin):
    """The balance shafts of one order of E engines (one engine's are
    :class:`crankbalance.physics.balancing.ShaftSet`).

    Each shaft has three mass slots at the axial positions :math:`-l/2, 0, +l/2`; its
    ``layout`` says which hold a mass: 0 nothing to cancel (no mass), 1 a force only (one
    mass mid-shaft), 2 a couple (the two outer masses, sized together with the force).

    Parameters
    ----------
    order : int
        1 (primary) or 2 (secondary).
    arrangement : {"pair", "counter-rotating"}
        As :class:`ShaftOptions`.
    length : float
        Axial distance between the outer masses [m].
    cg_radius : float
        Radius of the centre of gravity of the shaft masses [m].
    sense : ndarray of int, shape (S,)
        +1 co-rotating, -1 counter-rotating, one per shaft (``pair``: +1, -1).
    position : ndarray, shape (3,)
        Axial positions of the three slots [m].
    layout : ndarray of int, shape (E, S)
        0, 1 or 2 (see above) per engine and shaft.
    mass : ndarray, shape (E, S, 3)
        Mass in each slot [kg], 0 where none.
    phase : ndarray, shape (E, S, 3)
        Direction of each mass at crank angle 0, from +z toward +x [rad].
    """

    order: int
    arrangement: str
    length: float
    cg_radius: float
    sense: NDArray[np.int64]
    position: NDArray[np.float64]
    layout: NDArray[np.int64]
    mass: NDArray[np.float64]
    phase: NDArray[np.float64]

    PER_ENGINE: ClassVar[tuple[str, ...]] = ("layout", "mass", "phase")

    @property
    def largest(self) -> NDArray[np.float64]:
        """Largest single mass of each shaft, shape (E, S) [kg] (:attr:`Shaft.mass`)."""
        return self.mass.max(axis=-1)


@record
class BatchResiduals(ResultMixin):
    """What the balancing masses of E engines leave, component by component
    (:func:`crankbalance.physics.balance_solver.balance_residuals`).

    Parameters
    ----------
    components : tuple of str
        ``"rotating"``, then ``"order1"`` .. ``"order<K>"`` (the columns).
    targeted : ndarray of bool, shape (K + 1,)
        Whether a counterweight or shaft was asked to cancel each component.
    force_before, force_after : ndarray, shape (E, K + 1)
        Largest force of each component over a revolution, without and with the balancing
        masses [N] (zero at most the engine's round-off,
        :func:`crankbalance.results.round_off`).
    moment_before, moment_after : ndarray, shape (E, K + 1)
        The same for the moment about the crankshaft mid-point [N·m].
    force_forward_after, force_backward_after : ndarray, shape (E, K + 1)
        The forward- and backward-rotating parts of ``force_after``, :math:`|F_n^+|` and
        :math:`|F_n^-|` (the rotating component is all forward), each zero at most the
        round-off [N].
    moment_forward_after, moment_backward_after : ndarray, shape (E, K + 1)
        The same of ``moment_after``, :math:`|C_n^{+}|` and :math:`|C_n^{-}|` [N·m].
    balanced : ndarray of bool, shape (E,)
        The residual check: every targeted component is cancelled, its force and moment
        after balancing below :data:`CHECK_TOLERANCE` of the engine's force scale (times
        the crank length for moments).
    """

    components: tuple[str, ...]
    targeted: NDArray[np.bool_]
    force_before: NDArray[np.float64]
    force_after: NDArray[np.float64]
    moment_before: NDArray[np.float64]
    moment_after: NDArray[np.float64]
    force_forward_after: NDArray[np.float64]
    force_backward_after: NDArray[np.float64]
    moment_forward_after: NDArray[np.float64]
    moment_backward_after: NDArray[np.float64]
    balanced: NDArray[np.bool_]

    PER_ENGINE: ClassVar[tuple[str, ...]] = (
        "force_before",
        "force_after",
        "moment_before",
        "moment_after",
        "force_forward_after",
        "force_backward_after",
        "moment_forward_after",
        "moment_backward_after",
        "balanced",
    )

    def column(self, component: str) -> int:
        """Index of ``component`` in the columns."""
        return self.components.index(component)


@record
class BatchBalance(ResultMixin):
    """Counterweights, balance shafts and residuals of E engines
    (:func:`crankbalance.physics.balance_solver.solve`).

    Parameters
    ----------
    counterweights : BatchCounterweights or None
        Crank counterweights, None when none were asked for.
    extra_counterweights : BatchCounterweights or None
        The Eq. 17 extra crank masses of a single counter-rotating primary shaft, else None.
    primary, secondary : BatchShafts or None
        Balance shafts of order 1 and 2, None when none were asked for.
    rotating_share : ndarray of complex, shape (E, W), or None
        First moments of the counterweights' share that carries the rotating masses
        [kg·m] (the rest, the balance-factor share, counts to the first order).
    residuals : BatchResiduals
        Forces and moments before and after, per component, and the residual check.
    """

    counterweights: BatchCounterweights | None
    extra_counterweights: BatchCounterweights | None
    primary: BatchShafts | None
    secondary: BatchShafts | None
    rotating_share: NDArray[np.complex128] | None
    residuals: BatchResiduals

    PER_ENGINE: ClassVar[tuple[str, ...]] = ("rotating_share",)

    @property
    def size(self) -> int:
        """Number of engines E."""
        return int(self.residuals.balanced.size)
