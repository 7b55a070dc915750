"""Figures: one builder per figure, shared by the web app, the report and
``crankbalance plot``. Each builder takes a result object (compute apart from plot) and
returns a ``plotly.graph_objects.Figure``; plotly is imported inside the functions, so
importing this package loads numpy but not plotly.

The figures of a study live in the module of that study; :mod:`.common` holds what they
share (the palette, the template, the title style, the round-off level below which a value
is drawn as zero, the drawing of one crank web):

========================  ===============================================================
module                    figures of
========================  ===============================================================
:mod:`.engine`            the engine analysis: orders bar, curves, polar diagram
:mod:`.balancing`         the engine after balancing: residuals, the balanced curves
:mod:`.crank3d`           the 3-D crank (analysis and balancing) and its framing
:mod:`.crank_flat`        the 3-D crank drawn flat in three views, for print
:mod:`.single`            the single cylinder, the balance-factor sweep, the drilling plan
:mod:`.counterweight`     the counterweight design and optimisation
:mod:`.shaft`             the balance shafts
:mod:`.performance`       the friction bench, the cycle, the whole engine's cycle, the
                          sensitivity to the balance factor
:mod:`.loads`             the main-bearing loads and their sweep against balance
:mod:`.torsional`         the torsional vibration study
:mod:`.mounts`            the powertrain on its mounts
:mod:`.explore`           the design-space explorer
:mod:`.shop`              the balance shop: matched sets, bob-weights, scatter, hole plan
:mod:`.study`             :func:`plot`: the figures of any study's result
========================  ===============================================================

Every public builder is also a name of this package (``from crankbalance.output.figures
import orders_bar``, ``figures.orders_bar(analysis)`` in a notebook); code inside
crankbalance imports it from its module.

This package owns how results look (traces, axes, titles, colours) and nothing else: the
numbers come from the result objects and the physics modules (the balancing masses' time
histories from :func:`crankbalance.physics.balancing.point_mass_history`), and turning a
figure into a PNG, SVG or HTML file is :mod:`crankbalance.output.render`'s job.

Conventions
-----------
Vectors across the crank axis are complex ``z + i x`` (:mod:`crankbalance.physics.shaking`);
the diagrams draw x horizontally and z (cylinder axis of an in-line engine) vertically. The
3-D view puts the crank axis y horizontally. Angles are shown in degrees, forces in N,
moments in N·m, lengths in mm, masses in kg.
"""

from __future__ import annotations

from .balancing import BalancedCurves, balanced_curves, residuals_bar
from .counterweight import counterweight_profile, pareto_front
from .crank3d import crank_3d
from .crank_flat import crank_views
from .engine import curves_figure, orders_bar, polar_figure
from .explore import explore_candidate, explore_scatter
from .loads import bearing_loads_figure, bearing_sweep_figure
from .mounts import mode_shapes_figure, mounts_figure, mounts_layout_figure
from .performance import bench_figure, cycle_figure, engine_torque_figure, sensitivity_figure
from .shaft import shaft_response_figure, shaft_study
from .shop import bob_weights_figure, hole_plan, matched_sets, scatter_histograms
from .single import (
    balance_factor_sweep,
    drilling_plan,
    rebalance_unbalance,
    single_cylinder_forces,
    single_cylinder_polar,
)
from .study import plot
from .torsional import torsional_figure

__all__ = [
    "BalancedCurves",
    "balance_factor_sweep",
    "balanced_curves",
    "bearing_loads_figure",
    "bearing_sweep_figure",
    "bench_figure",
    "bob_weights_figure",
    "counterweight_profile",
    "crank_3d",
    "crank_views",
    "curves_figure",
    "cycle_figure",
    "drilling_plan",
    "engine_torque_figure",
    "explore_candidate",
    "explore_scatter",
    "hole_plan",
    "matched_sets",
    "mode_shapes_figure",
    "mounts_figure",
    "mounts_layout_figure",
    "orders_bar",
    "pareto_front",
    "plot",
    "polar_figure",
    "rebalance_unbalance",
    "residuals_bar",
    "scatter_histograms",
    "sensitivity_figure",
    "shaft_response_figure",
    "shaft_study",
    "single_cylinder_forces",
    "single_cylinder_polar",
    "torsional_figure",
]
