r"""Tolerance statistics: what part-weight scatter and scale resolution leave in a crank.

The crank of an N-cylinder engine is balanced for the nominal parts (its counterweights
drilled with nominal bob-weights). Each part actually fitted differs from its nominal mass
by

* its scatter, :math:`\delta`, normal or uniform with the standard deviation
  :math:`\sigma` of its part type (the spread of the parts as matched), and
* the resolution of the scale it was weighed and matched on: a part that reads a value
  is anywhere within half a scale step :math:`q` of it, an error uniform over one step
  (standard deviation :math:`q/\sqrt{12}`), independent of the scatter.

A part is *rotating* (big end, bearing shells: on the crankpin) or *reciprocating*
(piston, pin, rings, locks, small end). With :math:`d^{rot}_c, d^{rec}_c` the sums of the
deviations of cylinder c's parts of each kind [kg], crank radius :math:`r`, speed
:math:`\omega`, throw angle :math:`\varphi_c`, axial position :math:`y_c` and balance
factor :math:`f_b`:

* the residual unbalance, what the balancing machine would show with the actual parts
  as bob-weights (:math:`m_{bob} = m_{rot} + f_b m_{rec}`), transferred to the two
  correction planes (:func:`crankbalance.physics.shop.planes.transfer_matrix`, :math:`T`):
  :math:`U_j = \sum_c T_{jc}\,(d^{rot}_c + f_b d^{rec}_c)\,r\,e^{i\varphi_c}`;
* the free forces the deviations add to those of the nominal engine: the rotating ones
  :math:`\sum_c d^{rot}_c r\omega^2 e^{i\varphi_c}` (order 1, forward), the reciprocating
  ones the phasors of :func:`crankbalance.physics.shaking.reciprocating_phasors` for masses
  :math:`d^{rec}_c` (orders 1 and 2, forward and backward), and their couples about the
  crankshaft mid-point.

Every output is a linear sum of independent zero-mean deviations,
:math:`X = \sum_c d_c\,s_c` with complex sensitivities :math:`s_c`, so its second moments
are known exactly: :math:`E[(\mathrm{Re}X)^2] = \sum_c \mathrm{Var}(d_c)(\mathrm{Re}\,s_c)^2`,
the same with the imaginary part, and :math:`E|X|^2 = \sum_c \mathrm{Var}(d_c)|s_c|^2`
(the variance of a phasor sum). These give the check of the Monte Carlo and the share of
the mean square each part type's tolerance causes (its *variance share*). The magnitudes
(residual per plane, force and moment amplitude :math:`|X^+| + |X^-|` per order) and the
probabilities of meeting a tolerance are what the Monte Carlo adds: their distributions
are not normal.

The Monte Carlo draws a chunk of complete engines at a time (bounded memory), maps the
deviations to the outputs with one matrix product and keeps histograms, so any number of
samples runs in the memory of one chunk. A seed makes it reproducible (numpy's PCG64).
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...errors import InputError, check_nonnegative
from ...records import record
from ...results import ResultMixin
from ..model import EngineModel
from ..shaking import cylinder_coefficients, reciprocating_phasors
from ..single_cylinder import check_balance_factor
from .planes import axial_pair, transfer_matrix

Kind = Literal["rotating", "reciprocating"]
Distribution = Literal["normal", "uniform"]
KINDS: tuple[str, ...] = ("rotating", "reciprocating")
DISTRIBUTIONS: tuple[str, ...] = ("normal", "uniform")

#: complex outputs of the Monte Carlo, the columns of the sensitivity matrix
PHASORS: tuple[str, ...] = (
    "plane_1",
    "plane_2",
    "force_order1_forward",
    "force_order1_backward",
    "force_order2_forward",
    "force_order2_backward",
    "couple_order1_forward",
    "couple_order1_backward",
    "couple_order2_forward",
    "couple_order2_backward",
)
#: magnitudes reported, each from the phasors at these indices of PHASORS
OUTPUTS: tuple[str, ...] = (
    "residual_plane_1",
    "residual_plane_2",
    "force_order1",
    "force_order2",
    "moment_order1",
    "moment_order2",
)
_GROUPS: tuple[tuple[int, ...], ...] = ((0,), (1,), (2, 3), (4, 5), (6, 7), (8, 9))
#: probabilities at which the quantiles of the magnitudes are reported [-]
QUANTILE_LEVELS: tuple[float, ...] = (0.5, 0.9, 0.95, 0.99, 0.999)
#: histogram bins per output; the range is HISTOGRAM_RMS times the analytic RMS
BINS = 1000
HISTOGRAM_RMS = 10.0
#: engines drawn at once (memory of one chunk: about 1 kB per engine of 8 cylinders)
CHUNK = 32768
#: most random numbers one study draws (samples times the numbers per engine: two normal
#: deviations per cylinder and one uniform per cylinder and uniform term), checked before
#: any is drawn; measured (docs/balance_shop.md, "Tolerance statistics"): about 10^8 a
#: second, so at most about 10 s on an idle machine (10^7 samples of a V8 with seven part
#: types weighed on a scale: 7.2 * 10^8)
MAX_RANDOM_NUMBERS = 1_000_000_000
#: most parts of one type per cylinder (two bearing shells, two locks: a few)
MAX_COUNT = 64
#: most random numbers drawn at once (a chunk of engines: 128 MB in single precision)
MAX_CHUNK_NUMBERS = 2**25


@record
class PartScatter:
    """Scatter of one part type, one or more parts per cylinder.

    Parameters
    ----------
    name : str
        Part type, e.g. ``"piston"``, ``"big end"``.
    kind : {"rotating", "reciprocating"}
        On the crankpin (big end, bearing shells) or moving with the piston.
    sigma : float
        Standard deviation of one part's mass about its nominal [kg].
    distribution : {"normal", "uniform"}
        Shape of the scatter; uniform over :math:`\\pm\\sqrt{3}\\,\\sigma`.
    count : int
        Parts of this type per cylinder (e.g. 2 bearing shells) [-].
    weighed : bool
        Whether each part was weighed and matched on the scale (its reading error
        counts); False for an allowance such as oil.
    """

    name: str
    kind: Kind
    sigma: float
    distribution: Distribution = "normal"
    count: int = 1
    weighed: bool = True


def _check_parts(parts: tuple[PartScatter, ...]) -> None:
    if not parts:
        raise InputError("parts", [], "must name at least one part type")
    for k, part in enumerate(parts):
        field = f"parts[{k}]"
        if part.kind not in KINDS:
            raise InputError(f"{field}.kind", part.kind, "must be 'rotating' or 'reciprocating'")
        if part.distribution not in DISTRIBUTIONS:
            raise InputError(
                f"{field}.distribution", part.distribution, "must be 'normal' or 'uniform'"
            )
        check_nonnegative(f"{field}.sigma", part.sigma)
        if (
            isinstance(part.count, bool)
            or not isinstance(part.count, int)
            or not 1 <= part.count <= MAX_COUNT
        ):
            raise InputError(
                f"{field}.count", part.count, f"must be a whole number from 1 to {MAX_COUNT}"
            )


def sensitivities(
    model: EngineModel, correction_planes: ArrayLike, balance_factor: float
) -> NDArray[np.complex128]:
    r"""The outputs per kilogram of deviation of each cylinder's rotating and reciprocating mass.

    Parameters
    ----------
    model : EngineModel
        The engine: throw angles, positions, banks, crank radius, rod length, speed.
    correction_planes : array_like, shape (2,)
        Axial positions of the crank's correction planes, measured like the throw
        positions (from the crankshaft mid-point) [m].
    balance_factor : float
        Share of the reciprocating mass in the bob-weights the crank was balanced with [-].

    Returns
    -------
    ndarray of complex, shape (2 C, 10)
        Rows: rotating mass of cylinders 1..C, then their reciprocating mass; columns:
        :data:`PHASORS`, residual unbalance per plane [kg m/kg], forces [N/kg], couples
        [N m/kg], phasors at crank angle 0 (:mod:`crankbalance.physics.shaking`).
    """
    planes = axial_pair("correction_planes", correction_planes)
    f_b = check_balance_factor(balance_factor)
    r, w = model.crank_radius, model.speed
    turn = np.exp(1j * model.cylinder_angle)  # (C,)
    y = model.cylinder_position
    c = model.cylinders
    lever = transfer_matrix(y, planes)  # (2, C)
    # C engines, each with 1 kg in one cylinder: engine k has cylinder k's coefficients
    coefficients = cylinder_coefficients(model, 2)
    unit = np.eye(c)
    fwd, bwd, cfwd, cbwd = reciprocating_phasors(
        coefficients, unit, model.cylinder_angle, model.cylinder_bank, y, r, w
    )
    out = np.zeros((2 * c, len(PHASORS)), dtype=complex)
    bob = (lever * r * turn).T  # (C, 2): residual per kg of bob-weight on each pin
    out[:c, 0:2] = bob
    out[:c, 2] = r * w**2 * turn
    out[:c, 6] = y * r * w**2 * turn
    out[c:, 0:2] = f_b * bob
    out[c:, 2:6] = np.stack([fwd[:, 0], bwd[:, 0], fwd[:, 1], bwd[:, 1]], axis=1)
    out[c:, 6:10] = np.stack([cfwd[:, 0], cbwd[:, 0], cfwd[:, 1], cbwd[:, 1]], axis=1)
    return out


def _source_variances(
    parts: tuple[PartScatter, ...], scale_step: float
) -> tuple[tuple[str, ...], NDArray[np.float64]]:
    """Names of the sources (part types, then the scale) and each one's variance per
    cylinder [kg^2], shape (sources, 2): rotating, reciprocating."""
    names = tuple(p.name for p in parts) + ("scale",)
    var = np.zeros((len(names), 2))
    for k, part in enumerate(parts):
        var[k, KINDS.index(part.kind)] = part.count * part.sigma**2
        if part.weighed:
            var[-1, KINDS.index(part.kind)] += part.count * scale_step**2 / 12.0
    return names, var


@record
class ScatterStudy(ResultMixin):
    """Distribution of the residual unbalance and free forces that part scatter leaves.

    Attributes
    ----------
    samples : int
        Engines drawn (complete sets of parts).
    seed : int or None
        Seed of the random generator (None: fresh entropy, not reproducible).
    outputs : tuple of str
        Names of the magnitudes, :data:`OUTPUTS`: residual per correction plane [kg m],
        force amplitude :math:`|F^+|+|F^-|` of orders 1 and 2 [N], moment amplitude of
        orders 1 and 2 [N m].
    mean, rms, maximum : ndarray, shape (6,)
        Of each magnitude over the samples [kg m, N, N m as in ``outputs``].
    quantile_levels : ndarray, shape (L,)
        Probabilities [-] of :data:`QUANTILE_LEVELS`.
    quantiles : ndarray, shape (6, L)
        Magnitude not exceeded with each probability (from the histogram, resolution
        ``histogram_upper / BINS``) [kg m, N, N m].
    histogram : ndarray of int, shape (6, BINS)
        Samples per bin of ``[0, histogram_upper)``.
    histogram_upper : ndarray, shape (6,)
        Upper edge of each histogram [kg m, N, N m].
    overflow : ndarray of int, shape (6,)
        Samples at or beyond the upper edge.
    phasors : tuple of str
        :data:`PHASORS`, the complex outputs behind the magnitudes.
    moments, moments_analytic : ndarray, shape (10, 3)
        :math:`E[(\\mathrm{Re}X)^2], E[(\\mathrm{Im}X)^2], E[\\mathrm{Re}X\\,\\mathrm{Im}X]`
        of each phasor, from the samples and exact [kg^2 m^2 for the planes, N^2 for forces,
        N^2 m^2 for couples].
    sources : tuple of str
        Part types, then ``"scale"``.
    variance_share : ndarray, shape (sources, 6)
        Share of each source in the mean square of each output's phasors [-]; a column
        sums to 1 (0 when the output cannot vary).
    dominant : tuple of str
        The source with the largest share, per output (``"none"`` when it cannot vary).
    plane_tolerance : ndarray, shape (2,), or None
        Permissible residual per correction plane [kg m].
    force_limit, moment_limit : ndarray, shape (2,), or None
        Largest force [N] and moment [N m] amplitude allowed for orders 1 and 2.
    p_grade : float or None
        Probability that both planes meet ``plane_tolerance`` [-].
    p_free : float or None
        Probability that orders 1 and 2 meet the force and moment limits given [-].
    p_all : float or None
        Probability that every tolerance given is met [-].
    """

    samples: int
    seed: int | None
    outputs: tuple[str, ...]
    mean: NDArray[np.float64]
    rms: NDArray[np.float64]
    maximum: NDArray[np.float64]
    quantile_levels: NDArray[np.float64]
    quantiles: NDArray[np.float64]
    histogram: NDArray[np.int64]
    histogram_upper: NDArray[np.float64]
    overflow: NDArray[np.int64]
    phasors: tuple[str, ...]
    moments: NDArray[np.float64]
    moments_analytic: NDArray[np.float64]
    sources: tuple[str, ...]
    variance_share: NDArray[np.float64]
    dominant: tuple[str, ...]
    plane_tolerance: NDArray[np.float64] | None
    force_limit: NDArray[np.float64] | None
    moment_limit: NDArray[np.float64] | None
    p_grade: float | None
    p_free: float | None
    p_all: float | None


def _limit(field: str, value: ArrayLike | None) -> NDArray[np.float64] | None:
    if value is None:
        return None
    out = np.broadcast_to(np.asarray(value, dtype=float), (2,)).copy()
    if not np.all(out >= 0):  # inf allowed: no limit on that order
        raise InputError(field, value, "must be two limits >= 0, one per plane or order")
    return out


class _Sampler:
    """Draws the per-cylinder deviations of one chunk of engines, shape (S, 2 C) [kg], in
    single precision (the sampling error of any statistic is far above its round-off)."""

    def __init__(self, parts: tuple[PartScatter, ...], scale_step: float, cylinders: int):
        self.cylinders = cylinders
        normal = np.zeros(2)
        widths: list[list[float]] = [[], []]  # uniform terms per kind: full widths [kg]
        for part in parts:
            kind = KINDS.index(part.kind)
            if part.distribution == "normal":
                normal[kind] += part.count * part.sigma**2
            elif part.sigma > 0:
                widths[kind] += [np.sqrt(12.0) * part.sigma] * part.count
            if part.weighed and scale_step > 0:
                widths[kind] += [scale_step] * part.count
        self.normal = np.sqrt(normal).repeat(cylinders).astype(np.float32)  # (2C,)
        self.any_normal = bool(np.any(normal > 0))
        self.widths = [np.array(w, dtype=np.float32) for w in widths]
        #: random numbers drawn per engine
        self.numbers = (2 * cylinders if self.any_normal else 0) + cylinders * sum(
            w.size for w in self.widths
        )

    def draw(self, rng: np.random.Generator, size: int) -> NDArray[np.float32]:
        c = self.cylinders
        if self.any_normal:
            out = rng.standard_normal((size, 2 * c), dtype=np.float32)
            out *= self.normal
        else:
            out = np.zeros((size, 2 * c), dtype=np.float32)
        for kind, width in enumerate(self.widths):
            if width.size:  # sum of w (u - 1/2), u uniform on [0, 1)
                u = rng.random((width.size, size, c), dtype=np.float32)
                block = np.tensordot(width, u, axes=1)
                block -= 0.5 * width.sum()
                out[:, kind * c : (kind + 1) * c] += block
        return out


class _Tally:
    """Sums, histograms and pass counts over the chunks of a Monte Carlo."""

    def __init__(
        self,
        upper: NDArray[np.float64],
        tolerance: NDArray | None,
        forces: NDArray | None,
        moments: NDArray | None,
    ):
        k = len(OUTPUTS)
        self.limits = (tolerance, forces, moments)
        self.bin_scale = (BINS / upper).astype(np.float32)
        self.offsets = np.arange(k) * (BINS + 1)
        self.counts = np.zeros(k * (BINS + 1), dtype=np.int64)
        self.sum = np.zeros(k)
        self.sum_squares = np.zeros(k)
        self.peak = np.zeros(k)
        self.second = np.zeros((len(PHASORS), 3))
        self.passed = np.zeros(3, dtype=np.int64)  # grade, free, all

    def add(self, x: NDArray[np.float32]) -> None:
        """Count one chunk of phasors, shape (S, 20): real parts, then imaginary parts."""
        q = len(PHASORS)
        re, im = x[:, :q], x[:, q:]
        self.second[:, 0] += np.einsum("ij,ij->j", re, re, dtype=float)
        self.second[:, 1] += np.einsum("ij,ij->j", im, im, dtype=float)
        self.second[:, 2] += np.einsum("ij,ij->j", re, im, dtype=float)
        size = np.sqrt(re * re + im * im)  # (S, 10)
        mag = np.empty((x.shape[0], len(OUTPUTS)), dtype=np.float32)
        mag[:, :2] = size[:, :2]  # planes
        mag[:, 2:] = size[:, 2::2] + size[:, 3::2]  # |forward| + |backward|
        self.sum += mag.sum(axis=0, dtype=float)
        self.sum_squares += np.einsum("ij,ij->j", mag, mag, dtype=float)
        np.maximum(self.peak, mag.max(axis=0), out=self.peak)
        index = np.minimum((mag * self.bin_scale).astype(np.int64), BINS) + self.offsets
        self.counts += np.bincount(index.ravel(), minlength=self.counts.size)
        tolerance, forces, moments = self.limits
        ok_grade = np.ones(x.shape[0], dtype=bool)
        if tolerance is not None:
            ok_grade = np.all(mag[:, :2] <= tolerance, axis=1)
        ok_free = np.ones(x.shape[0], dtype=bool)
        if forces is not None:
            ok_free &= np.all(mag[:, 2:4] <= forces, axis=1)
        if moments is not None:
            ok_free &= np.all(mag[:, 4:6] <= moments, axis=1)
        self.passed += [ok_grade.sum(), ok_free.sum(), (ok_grade & ok_free).sum()]


def scatter_study(
    model: EngineModel,
    parts: tuple[PartScatter, ...] | list[PartScatter],
    correction_planes: ArrayLike,
    balance_factor: float,
    samples: int,
    seed: int | None = 0,
    scale_step: float = 0.0,
    plane_tolerance: ArrayLike | None = None,
    force_limit: ArrayLike | None = None,
    moment_limit: ArrayLike | None = None,
    chunk: int = CHUNK,
) -> ScatterStudy:
    r"""Monte Carlo of part-weight scatter and scale resolution for a crank balanced for
    the nominal parts.

    Parameters
    ----------
    model : EngineModel
        The engine (in-line, vee, boxer, ...): throws, cylinders, crank radius, speed.
    parts : sequence of PartScatter
        The part types fitted to every cylinder and their scatter.
    correction_planes : array_like, shape (2,)
        Axial positions of the correction planes from the crankshaft mid-point [m].
    balance_factor : float
        Share of the reciprocating mass in the bob-weights [-] (0.5 for a 90° V8).
    samples : int
        Engines to draw [-]; at most :data:`MAX_RANDOM_NUMBERS` random numbers in all,
        checked before any is drawn.
    seed : int or None
        Seed of the random generator (PCG64); None draws fresh entropy.
    scale_step : float
        Resolution of the scale the parts were weighed on [kg] (0: exact).
    plane_tolerance : array_like, shape (2,), optional
        Permissible residual per correction plane [kg m], e.g. the ``tolerance`` of
        :func:`crankbalance.physics.shop.planes.plane_tolerances`.
    force_limit, moment_limit : float or array_like, shape (2,), optional
        Largest force amplitude [N] and moment amplitude [N m] the scatter may add, for
        orders 1 and 2 (``inf``: no limit on that order).
    chunk : int
        Engines drawn at once [-]; bounds the memory (at most :data:`MAX_CHUNK_NUMBERS`
        random numbers), changes no statistic's meaning.

    Returns
    -------
    ScatterStudy
        Distributions, exact and sampled second moments, variance shares, probabilities.

    Notes
    -----
    Model and formulas in the module docstring. The variance shares are exact
    (:math:`E|X|^2 = \sum_{sources} \sum_c \mathrm{Var}(d_c)\,|s_c|^2`); the magnitudes'
    distributions and the probabilities are sampled (standard error of a probability
    :math:`\sqrt{p(1-p)/N}`).
    """
    parts = tuple(parts)
    _check_parts(parts)
    check_nonnegative("scale_step", scale_step)
    if isinstance(samples, bool) or not isinstance(samples, int | np.integer) or samples < 1:
        raise InputError("samples", samples, "must be a whole number, 1 or more")
    if isinstance(chunk, bool) or not isinstance(chunk, int | np.integer) or chunk < 1:
        raise InputError("chunk", chunk, "must be a whole number, 1 or more")
    tolerance = _limit("plane_tolerance", plane_tolerance)
    forces = _limit("force_limit", force_limit)
    moments = _limit("moment_limit", moment_limit)

    c = model.cylinders
    sampler = _Sampler(parts, scale_step, c)
    if int(samples) * sampler.numbers > MAX_RANDOM_NUMBERS:
        raise InputError(
            "samples",
            samples,
            f"would draw {int(samples) * sampler.numbers:.3g} random numbers ("
            f"{sampler.numbers} per engine of {c} cylinders); at most "
            f"{MAX_RANDOM_NUMBERS:.0e} are drawn: give at most "
            f"{MAX_RANDOM_NUMBERS // sampler.numbers} samples",
        )
    if int(chunk) * sampler.numbers > MAX_CHUNK_NUMBERS:
        raise InputError(
            "chunk",
            chunk,
            f"engines of {sampler.numbers} random numbers each; at most "
            f"{MAX_CHUNK_NUMBERS // sampler.numbers} are drawn at once",
        )
    s = sensitivities(model, correction_planes, balance_factor)
    sources, source_var = _source_variances(parts, scale_step)
    row_var = source_var.sum(axis=0).repeat(c)  # (2C,): rotating rows, reciprocating rows
    analytic = np.stack(
        [
            row_var @ s.real**2,
            row_var @ s.imag**2,
            row_var @ (s.real * s.imag),
        ],
        axis=1,
    )  # (10, 3)
    # mean square of each output group per source -> shares
    per_source = source_var.repeat(c, axis=1) @ np.abs(s) ** 2  # (sources, 10)
    group = np.stack([per_source[:, list(g)].sum(axis=1) for g in _GROUPS], axis=1)
    total = group.sum(axis=0)
    share = np.divide(group, total, out=np.zeros_like(group), where=total > 0)
    dominant = tuple(
        sources[int(k)] if t > 0 else "none"
        for k, t in zip(np.argmax(share, axis=0), total, strict=True)
    )
    # histogram range: HISTOGRAM_RMS times the RMS a magnitude can have at most
    rms_bound = np.sqrt([sum(analytic[k, :2].sum() for k in g) * len(g) for g in _GROUPS])
    upper = np.where(rms_bound > 0, HISTOGRAM_RMS * rms_bound, 1.0)

    rng = np.random.default_rng(seed)
    matrix = np.concatenate([s.real, s.imag], axis=1).astype(np.float32)  # (2C, 20)
    tally = _Tally(upper, tolerance, forces, moments)
    for start in range(0, int(samples), int(chunk)):
        size = min(int(chunk), int(samples) - start)
        tally.add(sampler.draw(rng, size) @ matrix)

    n = int(samples)
    table = tally.counts.reshape(len(OUTPUTS), BINS + 1)
    levels = np.array(QUANTILE_LEVELS)
    grade_given = tolerance is not None
    free_given = forces is not None or moments is not None
    return ScatterStudy(
        samples=n,
        seed=seed,
        outputs=OUTPUTS,
        mean=tally.sum / n,
        rms=np.sqrt(tally.sum_squares / n),
        maximum=tally.peak,
        quantile_levels=levels,
        quantiles=np.array(
            [_quantiles(row, u, levels) for row, u in zip(table, upper, strict=True)]
        ),
        histogram=table[:, :BINS],
        histogram_upper=upper,
        overflow=table[:, BINS],
        phasors=PHASORS,
        moments=tally.second / n,
        moments_analytic=analytic,
        sources=sources,
        variance_share=share,
        dominant=dominant,
        plane_tolerance=tolerance,
        force_limit=forces,
        moment_limit=moments,
        p_grade=float(tally.passed[0] / n) if grade_given else None,
        p_free=float(tally.passed[1] / n) if free_given else None,
        p_all=float(tally.passed[2] / n) if grade_given or free_given else None,
    )


def _quantiles(counts: NDArray, upper: float, levels: NDArray) -> NDArray[np.float64]:
    """Quantiles of a histogram over [0, upper) with an overflow bin last, linear within a
    bin; a quantile in the overflow is reported as ``upper``."""
    cdf = np.cumsum(counts) / counts.sum()
    width = upper / (counts.size - 1)
    k = np.minimum(np.searchsorted(cdf, levels), counts.size - 1)
    below = np.where(k > 0, cdf[k - 1], 0.0)
    step = cdf[k] - below
    inside = np.divide(levels - below, step, out=np.ones_like(levels), where=step > 0)
    return np.minimum((k + inside) * width, upper)
