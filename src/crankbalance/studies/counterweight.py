"""The counterweight studies of the registry (Appl. Sci. 2021, Sec. 4-5): the optimiser's
feasible designs, Pareto front and least-mass and least-radius designs
(``counterweight-optimize``), and the mass properties of one design
(``counterweight-show``, whose design ``counterweight export`` writes and against whose
requirement ``counterweight check`` weighs a CAD part).

The requirement m_c r_c is given (``first_moment``, or ``cw_mass`` with ``cg_radius``) or
comes from the balancing of the study's engine
(:func:`crankbalance.studies.requirements.counterweight_requirement`).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from ..errors import InputError
from ..physics.counterweight import CounterweightDesign, CounterweightProperties
from ..physics.counterweight_optimize import CounterweightOptimum, OptimizationProgress
from ..records import record
from ..results import ResultMixin, require_finite, to_jsonable
from ..schema.settings import (
    COUNTERWEIGHT_CHILDREN,
    PROFILE_PARAMETERS,
    CounterweightDesignOptions,
    CounterweightOptimizeOptions,
    CounterweightRequirementOptions,
    parse_options,
)
from .engine import EngineLike, engine_label

if TYPE_CHECKING:  # pragma: no cover
    from ..io.cad import MeshMassProperties
    from ..physics.model import EngineModel

#: the settings that may state a counterweight's requirement (:func:`requirement`)
RequirementSettings = CounterweightRequirementOptions | CounterweightDesignOptions

SCHEMA = "crankbalance.counterweight/2"

#: profile parameter -> (quantity kind, display factor, display unit)
PARAMETERS: dict[str, tuple[str, float, str]] = {
    "web_radius": ("length", 1e3, "mm"),
    "rectangle_height": ("length", 1e3, "mm"),
    "trapezoid_angle": ("angle", 180 / math.pi, "°"),
    "segment_radius": ("length", 1e3, "mm"),
    "segment_angle": ("angle", 180 / math.pi, "°"),
    "thickness": ("length", 1e3, "mm"),
}
assert tuple(PARAMETERS) == PROFILE_PARAMETERS
#: the SI unit of a parameter's JSON key
_SI_UNIT = {"length": "m", "angle": "deg"}
#: factor from the SI value of a parameter to its JSON value (angles in degrees)
_JSON_FACTOR = {"length": 1.0, "angle": 180.0 / math.pi}
#: JSON keys of a design's properties
_DESIGN_KEYS = {
    "mass": "mass_kg",
    "outer_radius": "outer_radius_m",
    "radius_bound": "r_min_bound_m",
    "inertia": "inertia_kg_m2",
    "cg_radius": "cg_radius_m",
    "first_moment": "first_moment_kg_m",
    "balance": "balance_percent",
}


def design_row(values: dict[str, float]) -> dict[str, float]:
    """A design's parameters and properties with the SI unit in each key."""
    out: dict[str, float] = {}
    for name, value in values.items():
        if name in PARAMETERS:
            kind = PARAMETERS[name][0]
            out[f"{name}_{_SI_UNIT[kind]}"] = float(value) * _JSON_FACTOR[kind]
        elif name in _DESIGN_KEYS:
            out[_DESIGN_KEYS[name]] = float(value)
    return out


def requirement(engine: EngineLike | None, settings: RequirementSettings) -> float | None:
    """The first moment m_c r_c [kg m] a counterweight must carry: ``first_moment``, or
    ``cw_mass`` times ``cg_radius``, or the heaviest crank counterweight of the engine's
    balancing; None when none is given. More than one is refused."""
    given_ = [
        settings.first_moment is not None,
        settings.cw_mass is not None or settings.cg_radius is not None,
        engine is not None,
    ]
    if sum(given_) > 1:
        raise InputError(
            "first_moment",
            settings.first_moment,
            "give only one of --first-moment, --cw-mass with --cg-radius, or --engine",
        )
    if engine is not None:
        from .engine import balance_engine
        from .requirements import counterweight_requirement

        study = balance_engine(engine, halves_if_balanced=True)  # type: ignore[arg-type]
        try:
            return counterweight_requirement(study)
        except InputError as error:
            raise InputError("engine", engine_label(engine), error.allowed) from None
    if settings.first_moment is not None:
        return float(settings.first_moment)
    if settings.cw_mass is None and settings.cg_radius is None:
        return None
    return _required(None, settings)


def _required(engine: EngineLike | None, settings: RequirementSettings) -> float:
    """The requirement of a study that needs one (:func:`requirement`)."""
    if engine is not None or settings.first_moment is not None:
        found = requirement(engine, settings)
        assert found is not None
        return found
    if settings.cw_mass is None or settings.cg_radius is None:
        raise InputError(
            "first_moment",
            None,
            "required: e.g. --first-moment '7880 g*mm', or --cw-mass '263 g' with "
            "--cg-radius '30 mm', or --engine FILE (the balancing solver's counterweight)",
        )
    return float(settings.cw_mass * settings.cg_radius)


def _value(name: str, text: str) -> float:
    """One value of a profile parameter, in SI and in its physical range."""
    value = getattr(parse_options(CounterweightDesignOptions, {name: text}), name)
    assert isinstance(value, float)
    return value


def value_or_range(name: str, text: str) -> float | tuple[float, float]:
    """'20 mm' -> 0.02; '10..20 mm' or '10 mm..20 mm' -> (0.01, 0.02)."""
    if ".." not in text:
        return _value(name, text)
    low, high = (part.strip() for part in text.split("..", 1))
    if ".." in high:
        raise InputError(name, text, "a value or one range 'LOW..HIGH', e.g. '10..20 mm'")
    if re.fullmatch(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?", low):
        # a bare lower number takes the unit of the upper value: '10..20 mm'
        unit = high.lstrip("0123456789.eE+- ")
        low = f"{low} {unit}" if unit else low
    return (_value(name, low), _value(name, high))


# --------------------------------------------------------------------------- optimize
@record(repr=False)
class OptimizeResult(ResultMixin):
    """A counterweight optimisation: the requirement, its settings, the parameter bounds
    searched and the optimiser's result, with the Pareto designs listed.

    Attributes
    ----------
    required : float
        First moment m_c r_c [kg m].
    settings : CounterweightOptimizeOptions
    bounds : dict of str to float or (float, float)
        Every parameter's value or range [SI].
    optimum : CounterweightOptimum
    listed : tuple of int
        The indices of the Pareto designs listed (evenly spread along the front).
    """

    required: float
    settings: CounterweightOptimizeOptions
    bounds: dict[str, float | tuple[float, float]]
    optimum: CounterweightOptimum
    listed: tuple[int, ...]

    def rows(self) -> list[dict[str, float]]:
        """The least-mass and least-radius designs, then the listed Pareto designs."""
        res = self.optimum
        return [res.row(res.least_mass), res.row(res.least_radius)] + [
            res.row(i) for i in self.listed
        ]

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.counterweight/2`` (mode ``optimize``)."""
        res, o = self.optimum, self.settings
        out = {
            "schema": SCHEMA,
            "mode": "optimize",
            "required_first_moment_kg_m": self.required,
            "density_kg_m3": res.density,
            "constraints": {
                "max_mass_kg": o.max_mass,
                "max_radius_m": o.max_radius,
                "min_balance_percent": o.min_balance,
                "radius_measure": o.radius_measure,
            },
            "bounds": {
                f"{n}_{_SI_UNIT[PARAMETERS[n][0]]}": (
                    [v * _JSON_FACTOR[PARAMETERS[n][0]] for v in value]
                    if isinstance(value, tuple)
                    else value * _JSON_FACTOR[PARAMETERS[n][0]]
                )
                for n, value in self.bounds.items()
            },
            "free": list(res.free),
            "objectives": list(res.objectives),
            "n_feasible": len(res.designs),
            "n_pareto": len(res.pareto),
            "nfev": res.nfev,
            "elapsed_s": res.elapsed,
            "least_mass": design_row(res.row(res.least_mass)),
            "least_radius": design_row(res.row(res.least_radius)),
            "pareto": [design_row(res.row(i)) for i in self.listed],
        }
        result = to_jsonable(out)
        assert isinstance(result, dict)
        return result


def _spread(n: int, k: int) -> list[float]:
    return [0.0] if k == 1 else [i * (n - 1) / (k - 1) for i in range(k)]


def optimize(
    engine: EngineLike | None,
    settings: CounterweightOptimizeOptions,
    *,
    progress: Callable[[OptimizationProgress], bool | None] | None = None,
) -> OptimizeResult:
    """Feasible counterweights, their Pareto front, least-mass and least-radius designs
    (:func:`~crankbalance.physics.counterweight_optimize.optimize_counterweight`, with
    :data:`~crankbalance.schema.settings.COUNTERWEIGHT_CHILDREN` designs per round):
    each profile parameter given as a value is fixed, as ``LOW..HIGH`` free in that range,
    not given free in the optimiser's range; the web circle r_cw clears the main journal
    (``journal_diameter``, else the engine's, :func:`crank_outline`;
    :func:`~crankbalance.physics.counterweight_optimize.clear_of_journal`); ``pareto``
    designs of the front are listed, evenly spread. ``progress`` is called after each round."""
    from ..physics.counterweight_optimize import (
        DEFAULT_BOUNDS,
        clear_of_journal,
        optimize_counterweight,
    )

    o = settings
    required = _required(engine, o)
    bounds: dict[str, float | tuple[float, float]] = {}
    for name in PARAMETERS:
        text = getattr(o, name)
        if text is not None:
            bounds[name] = value_or_range(name, text)
    journal = (
        o.journal_diameter
        if o.journal_diameter is not None or engine is None
        else crank_outline(engine).journal_diameter
    )
    if journal is not None:  # the web circle clears the main journal
        try:
            bounds = clear_of_journal(bounds, journal / 2)
        except InputError as error:
            raise InputError("web_radius", o.web_radius, error.allowed) from None
    res = optimize_counterweight(
        required,
        bounds,
        density=o.density,
        max_mass=o.max_mass,
        max_radius=o.max_radius,
        min_balance=o.min_balance,
        radius_measure=o.radius_measure,
        objectives=("mass", "radius", "inertia") if o.inertia else ("mass", "radius"),
        population=o.population,
        iterations=o.iterations,
        children=COUNTERWEIGHT_CHILDREN,
        rng=o.seed,
        callback=progress,
    )
    pick = [int(i) for i in res.pareto]
    if o.pareto < len(pick):
        pick = [pick[k] for k in sorted({round(x) for x in _spread(len(pick), o.pareto)})]
        pick = pick if o.pareto else []
    full = {n: DEFAULT_BOUNDS[n] for n in PARAMETERS} | bounds
    result = OptimizeResult(required, o, full, res, tuple(pick))
    require_finite({"required_first_moment": required, "designs": result.rows()})
    return result


# --------------------------------------------------------------------------- the crank
def radial_space(model: EngineModel) -> float:
    """The radial space the engine allows a crank counterweight [m]: the wrist pin's distance
    from the crank axis at bottom dead centre, rod length - crank radius (the piston skirt
    below the pin and a running clearance take more; the designer's own limit wins)."""
    return float(model.rod_length) - float(model.crank_radius)


@record
class CrankOutline:
    """The parts of the crank that give a counterweight drawing its scale
    (:func:`crankbalance.output.figures.counterweight.counterweight_profile`).

    Attributes
    ----------
    crank_radius : float
        Crank radius r, the crankpin's centre from the crank axis [m].
    pin_diameter, journal_diameter : float
        Diameters of the crankpin and the main journal [m]: the crank studies' defaults
        (1.1 r and 1.3 r, :data:`crankbalance.studies.crank.DEFAULT_PROPORTIONS`).
    radial_limit : float
        The largest radial space the counterweight may take [m].
    limit_source : str
        Where the limit comes from: "typed" (*Largest radial space*) or "engine" (rod
        length - crank radius, :func:`radial_space`).
    """

    crank_radius: float
    pin_diameter: float
    journal_diameter: float
    radial_limit: float
    limit_source: str


def crank_outline(engine: EngineLike, max_radius: float | None = None) -> CrankOutline:
    """The crank's outline of ``engine`` for a counterweight drawing: its crankpin and
    journal, and the radial limit ``max_radius`` [m] when typed, else the engine's
    :func:`radial_space`."""
    from .crank import DEFAULT_PROPORTIONS
    from .engine import as_model

    model = as_model(engine)
    r = float(model.crank_radius)
    return CrankOutline(
        crank_radius=r,
        pin_diameter=DEFAULT_PROPORTIONS["pin_diameter"] * r,
        journal_diameter=DEFAULT_PROPORTIONS["journal_diameter"] * r,
        radial_limit=radial_space(model) if max_radius is None else float(max_radius),
        limit_source="engine" if max_radius is None else "typed",
    )


# --------------------------------------------------------------------------- show
@record(repr=False)
class DesignResult(ResultMixin):
    """One counterweight design and its mass properties.

    Attributes
    ----------
    required : float, optional
        First moment m_c r_c it is sized or checked for [kg m].
    design : CounterweightDesign
    properties : CounterweightProperties
    crank : CrankOutline, optional
        The engine's crankpin, journal and radial limit, when the design is for an engine
        (drawn with the profile).
    """

    required: float | None
    design: CounterweightDesign
    properties: CounterweightProperties
    crank: CrankOutline | None = None

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.counterweight/2`` (mode ``design``)."""
        props, design = self.properties, self.design
        values = {n: getattr(design, n) for n in PARAMETERS}
        values.update(
            mass=props.mass,
            outer_radius=props.outer_radius,
            radius_bound=props.radius_bound,
            inertia=props.inertia,
            cg_radius=props.cg_radius,
            first_moment=props.first_moment,
        )
        if props.balance is not None:
            values["balance"] = props.balance
        out = {
            "schema": SCHEMA,
            "mode": "design",
            "density_kg_m3": design.density,
            "required_first_moment_kg_m": self.required,
            "design": design_row(values),
            "area_m2": props.area,
            "volume_m3": props.volume,
            "overhang_m": props.overhang,
            "gamma_deg": math.degrees(props.gamma),
            "lambda_deg": math.degrees(props.lam),
            "hub_protrusion": bool(props.hub_protrusion),
        }
        result = to_jsonable(out)
        assert isinstance(result, dict)
        return result


def design(engine: EngineLike | None, settings: CounterweightDesignOptions) -> DesignResult:
    """One design of the settings: every profile parameter given; the thickness may be left
    out with a requirement, and is then sized for it (100 % balance)."""
    o = settings
    required = requirement(engine, o)
    values: dict[str, float] = {}
    for name, (kind, _factor, unit) in PARAMETERS.items():
        value = getattr(o, name)
        if value is None:
            if name == "thickness" and required is not None:
                continue
            raise InputError(
                name,
                None,
                f"required ({kind}, e.g. '20 {unit}')"
                + ("; or give the requirement to size it" if name == "thickness" else ""),
            )
        values[name] = value
    if "thickness" not in values:
        assert required is not None
        probe = CounterweightDesign(**values, thickness=1.0, density=o.density)
        made = probe.with_thickness_for(required)
    else:
        made = CounterweightDesign(**values, density=o.density)
    props = made.properties(required)
    crank = None if engine is None else crank_outline(engine)
    return DesignResult(required, made, props, crank)


def show(engine: EngineLike | None, settings: CounterweightDesignOptions) -> DesignResult:
    """The mass properties of one counterweight design (:func:`design`), checked finite."""
    result = design(engine, settings)
    require_finite(result.to_dict())
    return result


# --------------------------------------------------------------------------- a CAD part
#: JSON keys of a part's mass properties (``counterweight check``)
PART_KEYS: dict[str, str | tuple[str, float]] = {
    "volume": "volume_m3",
    "mass": "mass_kg",
    "centre_of_gravity": "centre_of_gravity_m",
    "cg_radius": "cg_radius_m",
    "first_moment": "first_moment_kg_m",
    "inertia": "inertia_kg_m2",
    "balance": "balance_percent",
}


@record(repr=False)
class PartResult(ResultMixin):
    """The mass properties of a CAD part about the crank axis, against a requirement.

    Attributes
    ----------
    path : str
        The part's file.
    properties : MeshMassProperties
        Volume, mass, centre of gravity, first moment, inertia, balance [SI].
    """

    path: str
    properties: MeshMassProperties

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.counterweight/2`` (mode ``part``)."""
        from ..output.format import keyed

        out = to_jsonable(
            {
                "schema": SCHEMA,
                "mode": "part",
                "path": self.path,
                **keyed(self.properties.to_dict(), PART_KEYS),
            }
        )
        assert isinstance(out, dict)
        return out


def part(engine: EngineLike | None, settings: CounterweightDesignOptions, path: str) -> PartResult:
    """The mass properties of an STL or STEP part (``path``, its length unit ``unit``)
    about the crank axis (the file's z axis), of the settings' density, against the
    requirement of :func:`requirement` (its balance [%])."""
    from ..io.cad import mesh_mass_properties

    required = requirement(engine, settings)
    props = mesh_mass_properties(
        path, settings.density, length_unit=settings.unit, required_first_moment=required
    )
    result = PartResult(str(path), props)
    result.to_dict()  # checked finite
    return result
