r"""The time-domain verification of a balancing result: an optional, independent check.

The solver (:mod:`crankbalance.physics.balance_solver`) reports the residual of every
component from the phasors it solved with. :func:`verify` measures the same amplitudes a
second way that shares no algebra with it: the time history of every mass over a
revolution, then a discrete Fourier transform. The crank train's reciprocating forces come
straight from the slider-crank motion (exact kinematics, and the exact articulated motion
of master-and-link rods; :func:`crankbalance.physics.shaking.exact_time_domain`) or from
the model's harmonic series; the rotating masses, every counterweight and every
shaft mass are point masses evaluated at every crank angle
(:func:`crankbalance.physics.balancing.point_mass_history`). The amplitude of order k of a
history :math:`h` sampled at N angles is :math:`|H_k| + |H_{-k}|` with
:math:`H_k = \frac{1}{N}\sum_j h_j e^{-2\pi i jk/N}`.

It costs about 36 Fourier transforms of 256 samples, more than the solution itself, so it
runs only when asked: ``balance_engine(..., verify=True)`` and ``crankbalance balance
--verify`` (docs/json.md, ``verification``). On every preset the two agree to round-off
(tests/test_balance_check.py).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError
from ..records import record
from ..results import ResultMixin, below_round_off, round_off
from .balancing import BalanceResult, ComponentResidual, point_mass_history
from .model import EngineModel
from .shaking import exact_time_domain, free_forces, phasor_curve

#: crank angles per revolution of the time histories
SAMPLES = 256


@record
class Verification(ResultMixin):
    """The time-domain amplitudes of a balancing result and how far they are from the
    solver's.

    Parameters
    ----------
    samples : int
        Crank angles per revolution of the time histories.
    residuals : tuple of ComponentResidual
        ``"rotating"``, then ``"order1"``, ... as the result's, measured in the time domain
        (zero at most the round-off) [N], [N·m].
    force_difference : float
        Largest difference of a force, before or after (and the forward and backward parts after),
        between the time domain and the solver [N].
    moment_difference : float
        The same for the moments [N·m].
    force_round_off, moment_round_off : float
        The engine's round-off levels (:func:`crankbalance.results.round_off`) [N], [N·m].
    """

    samples: int
    residuals: tuple[ComponentResidual, ...]
    force_difference: float
    moment_difference: float
    force_round_off: float
    moment_round_off: float

    @property
    def agrees(self) -> bool:
        """Whether every difference is within the engine's round-off."""
        return (
            self.force_difference <= self.force_round_off
            and self.moment_difference <= self.moment_round_off
        )


def verify(model: EngineModel, result: BalanceResult, samples: int = SAMPLES) -> Verification:
    """Rebuild the time history of every mass of ``result`` and measure what is left,
    order by order, against the residuals the solver reported.

    ``result.rotating_share`` (the first moments of the counterweights' share that carries
    the rotating masses) counts to the rotating component, the rest of the counterweights
    (the balance-factor share) and the Eq. 17 extra set to the first order.

    Parameters
    ----------
    model : EngineModel
        The engine ``result`` was solved for.
    result : BalanceResult
        The solver's result (:func:`crankbalance.physics.balancing.balance`).
    samples : int
        Crank angles per revolution, more than twice the highest order of the result.

    Returns
    -------
    Verification
        The time-domain residuals [N], [N·m] and their largest differences from the
        solver's.

    Raises
    ------
    InputError
        If ``samples`` is not more than twice the highest order.

    References
    ----------
    The discrete Fourier transform of the time histories (any signal-processing text);
    the slider-crank motion of machine-dynamics texts, e.g. Taylor (1985) ch. 8.
    """
    orders = len(result.residuals) - 1
    if not (isinstance(samples, int | np.integer) and samples > 2 * orders):
        raise InputError("samples", samples, f"an integer above {2 * orders} (twice the orders)")
    theta = 2 * np.pi * np.arange(samples) / samples
    w = model.speed
    crank_turn = np.exp(1j * theta)

    # the rotating masses (their big ends at their own axial places)
    turn = np.exp(1j * model.throw_angle) * model.crank_radius * w**2
    rot_f = (model.throw_rotating_mass * turn).sum() * crank_turn
    rot_c = (model.throw_rotating_moment * turn).sum() * crank_turn
    # the reciprocating masses: the slider-crank motion itself, or the model's series
    if model.kinematics == "exact":
        rec_f, rec_c = exact_time_domain(model, theta)
    else:
        forces = free_forces(model, orders)
        rec_f = phasor_curve(forces.force_forward, forces.force_backward, forces.orders, theta)
        rec_c = phasor_curve(forces.couple_forward, forces.couple_backward, forces.orders, theta)
        rec_f, rec_c = rec_f.sum(axis=0), rec_c.sum(axis=0)

    # counterweights: the share that carries the rotating masses, and the rest (the
    # balance-factor share and the Eq. 17 extra set) that counts to the first order
    cw, share = result.counterweights, result.rotating_share
    zero = np.zeros(samples, complex)
    cw_rot_f, cw_rot_c = zero, zero
    beyond: list[tuple[ArrayLike, ArrayLike]] = []
    if cw is not None and share is not None:
        cw_rot_f, cw_rot_c = point_mass_history(w, theta, [(share, cw.position)])
        beyond.append((cw.moments - share, cw.position))
    if result.extra_counterweights is not None:
        extra = result.extra_counterweights
        beyond.append((extra.moments, extra.position))
    cw_rec_f, cw_rec_c = point_mass_history(w, theta, beyond)
    shaft_f: dict[int, NDArray] = {}
    shaft_c: dict[int, NDArray] = {}
    for order, group in ((1, result.primary), (2, result.secondary)):
        shaft_f[order], shaft_c[order] = point_mass_history(w, theta, shafts=(group,))

    def amplitude(series: NDArray, order: int) -> float:
        spectrum = np.fft.fft(series) / samples
        return float(abs(spectrum[order]) + abs(spectrum[-order]))

    def parts(series: NDArray, order: int) -> tuple[float, float]:
        """The co-rotating and counter-rotating parts of order ``order``: the spectrum
        at +order and at -order."""
        spectrum = np.fft.fft(series) / samples
        return float(abs(spectrum[order])), float(abs(spectrum[-order]))

    force_level, moment_level = (float(x) for x in round_off(model))

    def measured(force: float, moment: float) -> tuple[float, float]:
        return (
            float(below_round_off(force, force_level)),
            float(below_round_off(moment, moment_level)),
        )

    def after(force: NDArray, couple: NDArray, order: int) -> tuple[float, ...]:
        """Amplitudes of force and moment after, then their forward and backward parts
        (force forward, force backward, moment forward, moment backward)."""
        (f_fwd, f_bwd), (c_fwd, c_bwd) = parts(force, order), parts(couple, order)
        return (
            measured(amplitude(force, order), amplitude(couple, order))
            + measured(f_fwd, c_fwd)
            + measured(f_bwd, c_bwd)
        )

    rows = [
        (
            result.residuals[0],
            measured(amplitude(rot_f, 1), amplitude(rot_c, 1)),
            after(rot_f + cw_rot_f, rot_c + cw_rot_c, 1),
        )
    ]
    for order in range(1, orders + 1):
        after_f = rec_f + (cw_rec_f if order == 1 else 0) + shaft_f.get(order, 0)
        after_c = rec_c + (cw_rec_c if order == 1 else 0) + shaft_c.get(order, 0)
        rows.append(
            (
                result.residuals[order],
                measured(amplitude(rec_f, order), amplitude(rec_c, order)),
                after(after_f, after_c, order),
            )
        )
    residuals = tuple(
        ComponentResidual(
            solver.component,
            solver.targeted,
            before[0],
            left[0],
            before[1],
            left[1],
            left[2],
            left[4],
            left[3],
            left[5],
        )
        for solver, before, left in rows
    )
    force_difference = max(
        max(
            abs(t.force_before - s.force_before),
            abs(t.force_after - s.force_after),
            abs(t.force_forward_after - s.force_forward_after),
            abs(t.force_backward_after - s.force_backward_after),
        )
        for t, s in zip(residuals, result.residuals, strict=True)
    )
    moment_difference = max(
        max(
            abs(t.moment_before - s.moment_before),
            abs(t.moment_after - s.moment_after),
            abs(t.moment_forward_after - s.moment_forward_after),
            abs(t.moment_backward_after - s.moment_backward_after),
        )
        for t, s in zip(residuals, result.residuals, strict=True)
    )
    return Verification(
        samples,
        residuals,
        force_difference,
        moment_difference,
        force_level,
        moment_level,
    )
