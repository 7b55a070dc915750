"""One schema for the settings of every study, with one set of limits.

The command line and the web form both validate a study's settings through these pydantic
models, so that a setting has the same default, the same limits and the same message
everywhere. Quantities are unit strings (``"8000 kg/m^3"``, ``"400 g"``) parsed to SI
floats; plain numbers stay numbers. Every field has a default (``None`` where the study
derives the value from the engine when it is not given).

An edge names the fields as its users write them: the CLI as ``--max-mass``, the web form
by its setting key; :func:`parse_options` takes that naming as a function, so that an
error names the field the user typed.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from functools import partial
from typing import Annotated, Any, Literal, TypeVar, get_args

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, ValidationError

from .errors import InputError
from .single_cylinder import BALANCE_FACTOR_RANGE
from .units import KINDS, parse_quantity

#: the balance factors every study accepts (share of the reciprocating mass) [-]
BALANCE_FACTOR_LIMITS = BALANCE_FACTOR_RANGE


def _quantity(kind: str) -> Any:
    return BeforeValidator(partial(parse_quantity, kind=kind, field=""))


def _number(value: Any) -> Any:
    """A plain number: refuse NaN, infinities and booleans."""
    if isinstance(value, bool):
        raise ValueError("must be a number, not true/false")
    if isinstance(value, str):
        try:
            value = float(value.strip())
        except ValueError:
            raise ValueError("must be a plain number") from None
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError("must be a finite number")
    return value


Length = Annotated[float, _quantity("length")]
Mass = Annotated[float, _quantity("mass")]
Density = Annotated[float, _quantity("density")]
Inertia = Annotated[float, _quantity("inertia")]
Unbalance = Annotated[float, _quantity("unbalance")]
Number = Annotated[float, BeforeValidator(_number)]
Whole = Annotated[int, BeforeValidator(_number)]


class StudyOptions(BaseModel):
    """Base of the study settings: unknown keys are errors, values are frozen."""

    model_config = ConfigDict(extra="forbid", frozen=True)


class AnalysisOptions(StudyOptions):
    """Free forces and moments: how many harmonic orders."""

    orders: Whole = Field(8, ge=1, le=64, title="Highest order")


class CounterweightOptions(StudyOptions):
    """Counterweight shape optimisation (Appl. Sci. 2021, Sec. 4-5)."""

    density: Density = Field(8000.0, gt=0, title="Density", description="e.g. 8000 kg/m^3")
    max_mass: Mass | None = Field(None, gt=0, title="Largest mass", description="e.g. 400 g")
    max_radius: Length | None = Field(
        None, gt=0, title="Largest radial space", description="e.g. 80 mm"
    )
    min_balance: Number = Field(100.0, gt=0, le=1000, title="Smallest balance [%]")
    iterations: Whole = Field(40, ge=0, le=1000, title="Iterations")
    population: Whole = Field(4096, ge=16, le=100_000, title="Population")
    seed: Whole | None = Field(None, ge=0, le=2**32 - 1, title="Random seed")


class SingleCylinderOptions(StudyOptions):
    """One cylinder of an engine: balance factor study and the ISO 21940-11 check."""

    cylinder: Whole = Field(1, ge=1, title="Cylinder", description="1..number of cylinders")
    balance_factor: Number = Field(
        0.5, ge=BALANCE_FACTOR_LIMITS[0], le=BALANCE_FACTOR_LIMITS[1], title="Balance factor"
    )
    grade: str = Field("G6.3", title="ISO 21940-11 grade", description="e.g. G6.3")
    rotor_mass: Mass | None = Field(
        None, gt=0, title="Rotor mass", description="empty: the crank's rotating masses"
    )
    residual: Unbalance | None = Field(
        None, ge=0, title="Measured residual unbalance", description="optional, e.g. 8 g*mm"
    )


class RebalanceOptions(StudyOptions):
    """Rebalancing one cylinder's throw after new parts (Hoem and Røsholm 2016, Sec. 6.4)."""

    new_reciprocating: Mass | None = Field(
        None, gt=0, title="New reciprocating mass", description="empty: unchanged"
    )
    new_rotating: Mass | None = Field(
        None, gt=0, title="New rotating mass", description="empty: unchanged"
    )
    cw_mass: Mass | None = Field(
        None,
        gt=0,
        title="Counterweight mass (webs incl.)",
        description="empty: what the balance factor needs at the CG radius",
    )
    cw_radius: Length | None = Field(
        None, gt=0, title="Counterweight CG radius", description="empty: crank radius"
    )
    hole_diameter: Length = Field(0.008, gt=0, title="Drill diameter", description="e.g. 8 mm")
    hole_radius: Length | None = Field(
        None, gt=0, title="Hole radius", description="empty: counterweight CG radius"
    )


class ShaftPlacementOptions(StudyOptions):
    """Unbalance-mass placement on a balance shaft with end bearings (Kim 2018, Sec. 3.1)."""

    length: Length = Field(
        0.3, gt=0, title="Shaft length (between bearings)", description="e.g. 300 mm"
    )
    diameter: Length = Field(0.025, gt=0, title="Shaft diameter", description="e.g. 25 mm")
    weight: Number = Field(2.0, ge=0, le=1000, title="Objective weight w", description="e.g. 2")
    points: Whole = Field(41, ge=3, le=2001, title="Design points along the shaft")


class PerformanceOptions(StudyOptions):
    """Friction, bearing loads and shaking against the balance factor (Hoem and Røsholm
    2016, Sec. 5)."""

    bore: Length | None = Field(
        None, gt=0, title="Bore", description="empty: square engine (bore = stroke)"
    )
    balance_factors: list[
        Annotated[Number, Field(ge=BALANCE_FACTOR_LIMITS[0], le=BALANCE_FACTOR_LIMITS[1])]
    ] = Field(
        [0.0, 0.25, 0.5, 0.75, 1.0],
        min_length=1,
        max_length=21,
        title="Balance factors",
        description="e.g. 0, 0.25, 0.5, 0.75, 1",
    )
    crank_inertia: Inertia = Field(
        0.006, gt=0, title="Crank + flywheel inertia", description="e.g. 0.006 kg*m^2"
    )
    friction_coefficient: Number = Field(
        0.005, gt=0, le=1, title="Bearing friction coefficient", description="e.g. 0.005"
    )
    journal_diameter: Length = Field(
        0.03, gt=0, title="Main journal diameter", description="e.g. 30 mm"
    )


Options = TypeVar("Options", bound=StudyOptions)
Kind = Literal["quantity", "number", "whole", "text", "list"]


def _metadata(model: type[StudyOptions], name: str) -> list[Any]:
    """The field's constraints and validators, also those inside ``X | None``."""
    info = model.model_fields[name]
    found = list(info.metadata)
    for arg in get_args(info.annotation):
        found += list(getattr(arg, "__metadata__", ()))
    return found


def _show(value: float) -> str:
    return str(value) if isinstance(value, int) else f"{value:g}"


def field_kind(model: type[StudyOptions], name: str) -> tuple[Kind, str | None]:
    """How a field is written: its kind and, for a quantity, the quantity kind."""
    info = model.model_fields[name]
    for meta in _metadata(model, name):
        func = getattr(meta, "func", None)
        if isinstance(func, partial) and func.func is parse_quantity:
            return "quantity", str(func.keywords["kind"])
    annotation = str(info.annotation)
    if "list" in annotation:
        return "list", None
    if "int" in annotation:
        return "whole", None
    if "float" in annotation:
        return "number", None
    return "text", None


def allowed(model: type[StudyOptions], name: str) -> str:
    """What a field accepts, in words: "a whole number from 16 to 100000", ..."""
    info = model.model_fields[name]
    low = high = None
    low_open = high_open = False
    for meta in _metadata(model, name):
        for attr, is_open in (("ge", False), ("gt", True)):
            if getattr(meta, attr, None) is not None:
                low, low_open = getattr(meta, attr), is_open
        for attr, is_open in (("le", False), ("lt", True)):
            if getattr(meta, attr, None) is not None:
                high, high_open = getattr(meta, attr), is_open
    kind, quantity = field_kind(model, name)
    if kind == "list":
        longest = next((m.max_length for m in info.metadata if hasattr(m, "max_length")), None)
        return (
            f"1 to {longest} numbers from {BALANCE_FACTOR_LIMITS[0]:g} to "
            f"{BALANCE_FACTOR_LIMITS[1]:g}, separated by commas"
        )
    if kind == "text":
        return "a text"
    if kind == "quantity":
        article = "an" if str(quantity)[0] in "aeiou" else "a"
        what = f"{article} {quantity} with a unit, e.g. '{KINDS[str(quantity)][2]}'"
    else:
        what = "a whole number" if kind == "whole" else "a number"
    if low is not None and high is not None and not low_open and not high_open:
        return f"{what} from {_show(low)} to {_show(high)}"
    parts = []
    if low is not None:
        parts.append(f"{'greater than' if low_open else 'at least'} {_show(low)}")
    if high is not None:
        parts.append(f"{'less than' if high_open else 'at most'} {_show(high)}")
    return what + (", " + " and ".join(parts) if parts else "")


def parse_options(
    model: type[Options],
    values: Mapping[str, Any],
    name: Callable[[str], str] = str,
) -> Options:
    """Validate a study's settings; raise :class:`InputError` naming the field as the user
    wrote it (``name(field)``), the value given and what is allowed.

    Values that are ``None`` are left out, so that the schema's default applies.
    """
    given = {key: value for key, value in values.items() if value is not None}
    try:
        return model.model_validate(given)
    except ValidationError as error:
        first = error.errors(include_url=False)[0]
        loc = [str(p) for p in first["loc"]]
        key = loc[0] if loc else ""
        value = given.get(key, first.get("input"))
        if first["type"] == "extra_forbidden":
            raise InputError(
                name(key), value, f"unknown setting; known: {', '.join(model.model_fields)}"
            ) from None
        if key not in model.model_fields:
            raise InputError(name(key), value, str(first.get("msg", ""))) from None
        inner = (first.get("ctx") or {}).get("error")
        text = allowed(model, key)
        if isinstance(inner, InputError):
            text = inner.allowed
        elif isinstance(inner, ValueError) and "finite" in str(inner):
            text = f"{text} (finite)"
        if not text.startswith("must"):
            text = f"must be {text}"
        raise InputError(name(key), value, text) from None


def default_text(model: type[StudyOptions], name: str) -> str:
    """A field's default as a user would type it ("" for a default of None)."""
    from .units import format_quantity

    value = model.model_fields[name].default
    if value is None:
        return ""
    kind, quantity = field_kind(model, name)
    if kind == "quantity":
        return format_quantity(float(value), quantity or "length", digits=6)
    if kind == "list":
        return ", ".join(f"{v:g}" for v in value)
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)
