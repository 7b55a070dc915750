"""The input limits of physics models that the settings schema checks too, in a module
without numpy.

The settings schema (:mod:`crankbalance.schema.settings`) checks a study's settings
against the same ranges its physics refuses beyond, and is imported by every command of
the command line; importing the physics modules that own these ranges would load numpy
and those modules on every start (issue 30: the cold start). So the ranges live here,
where both take them from; each physics module re-exports its own under the same name.
"""

from __future__ import annotations

import math

#: Range of balance factors accepted as input (0 = rotating mass only, 2 = 200 %).
BALANCE_FACTOR_RANGE: tuple[float, float] = (0.0, 2.0)

#: start of combustion the Wiebe model takes, from firing TDC [rad]: 90 deg before to
#: 45 deg after (:class:`crankbalance.physics.engine_cycle.WiebeCombustion`; the study
#: settings take the same range)
IGNITION_RANGE = (-math.pi / 2, math.pi / 4)
#: burn duration the Wiebe model takes [rad]: from 0.001 rad (0.06 deg) to 180 deg
BURN_DURATION_RANGE = (1e-3, math.pi)
#: the Wiebe model's conventions for the end of the burn
#: (:func:`crankbalance.physics.engine_cycle.wiebe_burn_fraction`): ``"complete"`` lets the
#: exponential tail run on past the burn duration to a complete burn; ``"stop"`` ends the
#: burn at the end of the duration, at :math:`1 - e^{-a}`
BURN_ENDS = ("complete", "stop")
#: ratio of specific heats the single-zone model takes [-]
GAMMA_RANGE = (1.01, 1.67)

#: the largest target speed fluctuation a flywheel is sized for [-]. The energy method
#: assumes a small fluctuation (omega_max + omega_min = 2 omega_mean); at 0.2 its check
#: re-integration of every preset lands within 10 % of the target, while from about 0.4
#: the inertia it gives lets the speed swing by more than half its mean and the check is
#: refused (docs/engine_cycle.md; 0.5 before, a documented value that could not compute)
MAX_FLUCTUATION_TARGET = 0.2
#: the smallest one [-] (below, the inertia found is beyond any machine)
MIN_FLUCTUATION_TARGET = 1e-6

# the firing-order explorer's bounds of work (crankbalance.physics.explore.work), which
# the explorer's settings check too
#: candidates one run may evaluate: about 4 hours of one process at the 3 300 candidates/s
#: measured for the 12-cylinder two-stroke (benchmarks/bench_explore.py); every
#: 12-cylinder enumeration (39.9 million indices) fits, a 13-cylinder one (479 million)
#: does not
MAX_CANDIDATES = 50_000_000

#: the cost of one random draw, in indices of a range: measured 7 to 24 when each draw was
#: its own enumeration call, about 0.5 since orders.at takes them all at once (issue 30);
#: kept as an upper bound (docs/explorer.md)
DRAW_COST = 20
#: random draws one run may make (``--sample``): the time of :data:`MAX_CANDIDATES`
MAX_DRAWS = MAX_CANDIDATES // DRAW_COST

#: the largest chunk [indices]: the largest index space, 20!
LARGEST_CHUNK = math.factorial(20)
