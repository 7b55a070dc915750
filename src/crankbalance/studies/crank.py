"""What a study assumes of an engine's crank when the user does not type it: one answer for
``cycle --engine``, ``bearings`` / ``bearings-sweep`` and ``torsional``.

* :func:`web_offset` -- the axial distance of a web from its throw's mid-plane: the engine
  file's ``[counterweights] web_offset``, else a quarter of the throw pitch
  (:func:`crankbalance.physics.balancing.default_web_offset`);
* :func:`crank_dimensions` -- main journal, crankpin and web dimensions: those typed, the
  rest in :data:`DEFAULT_PROPORTIONS` of the crank radius and the web offset (an
  automotive crank's proportions, docs/main_bearings.md), the crankpin and journal lengths
  the stretches between the webs of the bearings' stepped-beam model;
* :func:`rotating_inertia` -- the inertia of everything that turns with the crank: front
  end, throws (their rotating masses at the crank radius) and flywheel, the torsional
  model's chain without damper ring, load and the pistons' mean share (the cycles add the
  pistons' inertia as it varies over the turn).

The main-bearing study takes the dimensions for the crank's bending stiffness and the
inertia for the speed fluctuation; the torsional study the dimensions for Carter's
stiffness and the same front end, throws and flywheel as its chain; the whole-engine
``cycle`` the inertia for its speed fluctuation (docs/torsional.md, "What is assumed").
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..errors import InputError
from ..physics.model import EngineModel
from ..records import record
from ..schema.engine import EngineSpec
from ..schema.settings import DEFAULT_FLYWHEEL_INERTIA, DEFAULT_FRONT_INERTIA
from .build import build_model

#: default crank proportions when a dimension is not given (docs/main_bearings.md): main
#: journal and crankpin diameters and web width as multiples of the crank radius, web
#: thickness as a multiple of the web offset
DEFAULT_PROPORTIONS = {
    "journal_diameter": 1.3,
    "pin_diameter": 1.1,
    "web_width": 2.2,
    "web_thickness": 0.75,
}
#: the dimensions a study may type (the four of the proportions and the two lengths)
DIMENSIONS = (*DEFAULT_PROPORTIONS, "journal_length", "pin_length")


def web_offset(spec: EngineSpec, model: EngineModel | None = None) -> float:
    """Axial distance of a web from its throw's mid-plane [m]: the engine file's
    ``[counterweights] web_offset``, else a quarter of the throw pitch (half the crank
    radius for one throw; :func:`crankbalance.physics.balancing.default_web_offset`)."""
    from ..physics.balancing import default_web_offset

    given = spec.counterweights.web_offset if spec.counterweights is not None else None
    if given is not None:
        return float(given)
    return float(default_web_offset(model if model is not None else build_model(spec)))


@record
class CrankDimensions:
    """The crank's dimensions a study used (typed, or from :func:`crank_dimensions`).

    Attributes
    ----------
    journal_diameter, pin_diameter : float
        Main-journal and crankpin diameters [m].
    journal_length, pin_length : float
        Length of one main journal and of one crankpin between the webs [m].
    web_thickness, web_width : float
        Axial thickness and width across the arm of one web [m].
    web_offset : float
        Axial distance of a web's mid-plane from its throw's mid-plane [m].
    typed : tuple of str
        The dimensions the user gave; the others were derived.
    """

    journal_diameter: float
    pin_diameter: float
    journal_length: float
    pin_length: float
    web_thickness: float
    web_width: float
    web_offset: float
    typed: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """The dimensions with their units in the keys (``journal_diameter_m``) and the
        names of the typed ones (``typed``); the others are the engine's defaults."""
        out: dict[str, Any] = {f"{name}_m": float(getattr(self, name)) for name in DIMENSIONS}
        out["web_offset_m"] = float(self.web_offset)
        out["typed"] = list(self.typed)
        return out


def _pitch(model: EngineModel) -> float | None:
    """Smallest axial distance between two crank planes [m] (None for one plane)."""
    from ..physics.main_bearings import crank_planes

    planes = crank_planes(model.throw_position)[0]
    steps = np.diff(np.sort(planes))
    return float(steps.min()) if steps.size else None


def crank_dimensions(
    model: EngineModel, offset: float, given: dict[str, float | None] | None = None
) -> CrankDimensions:
    r"""The crank's dimensions: those given, the rest from the crank radius r and the web
    offset o.

    Diameters and web width are :data:`DEFAULT_PROPORTIONS` of r (journal 1.3 r,
    crankpin 1.1 r, web width 2.2 r), the web thickness h = 0.75 o. The lengths are the
    stretches of the bearings' stepped beam (:func:`crankbalance.physics.main_bearings.
    crank_stiffness`): the crankpin between the two webs of a throw, :math:`l_p = 2o - h`,
    the journal between the webs of neighbouring throws, :math:`l_j = a - 2o - h` with the
    smallest throw pitch a (4 o for one throw: the pitch the default web offset a/4
    implies).

    Parameters
    ----------
    model : EngineModel
        The engine (crank radius, throw positions).
    offset : float
        Web offset o [m] (:func:`web_offset`).
    given : dict of str to float or None, optional
        Typed dimensions by name (:data:`DIMENSIONS`); None or absent: derived.

    Returns
    -------
    CrankDimensions
        The six dimensions, the web offset and the names of the typed ones.
    """
    typed = {k: float(v) for k, v in (given or {}).items() if v is not None}
    unknown = set(typed) - set(DIMENSIONS)
    if unknown:
        raise InputError(sorted(unknown)[0], None, f"is not a crank dimension ({DIMENSIONS})")
    r = model.crank_radius
    base = {"journal_diameter": r, "pin_diameter": r, "web_width": r, "web_thickness": offset}
    values = {
        name: typed.get(name, DEFAULT_PROPORTIONS[name] * base[name])
        for name in DEFAULT_PROPORTIONS
    }
    h = values["web_thickness"]
    pitch = _pitch(model)
    lengths = {
        "pin_length": 2.0 * offset - h,
        "journal_length": (pitch if pitch is not None else 4.0 * offset) - 2.0 * offset - h,
    }
    for name, length in lengths.items():
        if name in typed:
            values[name] = typed[name]
        elif length <= 0.0:
            room = (
                f"leaves no {name.replace('_length', '')} between the webs (web offset "
                f"{offset:g} m{'' if pitch is None else f', throw pitch {pitch:g} m'})"
            )
            if "web_thickness" in typed:
                raise InputError("web_thickness", h, f"{room}: give a thinner web")
            # the web thickness was derived from the engine file's web offset: name that
            raise InputError(
                "counterweights.web_offset",
                offset,
                f"{room} with the default web thickness "
                f"{DEFAULT_PROPORTIONS['web_thickness']:g} x web offset: give a smaller web "
                "offset or type the web thickness",
            )
        else:
            values[name] = length
    return CrankDimensions(
        **values, web_offset=float(offset), typed=tuple(n for n in DIMENSIONS if n in typed)
    )


def rotating_inertia(
    model: EngineModel,
    throw_inertia: ArrayLike | None = None,
    front_inertia: float | None = None,
    flywheel_inertia: float | None = None,
) -> float:
    r"""Inertia of everything that turns with the crank [kg m^2]: front end, throws and
    flywheel, without the pistons (the cycles add the reciprocating parts' inertia
    :math:`m\,s'^2(\alpha)` as it varies over the turn; the torsional model's chain holds
    its mean share on top, :func:`crankbalance.physics.torsional.throw_inertias`).

    .. math:: J = J_{front} + \sum_t J_{throw,t} + J_{flywheel}

    with :math:`J_{throw,t}` of :func:`crankbalance.physics.torsional.rotating_throw_inertia` (the
    throw's rotating masses at the crank radius, or ``throw_inertia``) and the torsional
    study's defaults for the front end (:data:`~crankbalance.schema.settings.
    DEFAULT_FRONT_INERTIA`, pulley, timing gear and damper hub) and the flywheel
    (:data:`~crankbalance.schema.settings.DEFAULT_FLYWHEEL_INERTIA`, flywheel and clutch) when
    not given.

    Parameters
    ----------
    model : EngineModel
        The engine.
    throw_inertia : float or array_like, optional
        Inertia of each throw without its pistons' share [kg m^2]; default
        :math:`m_{rot,t} r^2`.
    front_inertia, flywheel_inertia : float, optional
        Front end and flywheel [kg m^2].

    Returns
    -------
    float
        The total [kg m^2].
    """
    from ..physics.torsional import rotating_throw_inertia

    front = DEFAULT_FRONT_INERTIA if front_inertia is None else float(front_inertia)
    flywheel = DEFAULT_FLYWHEEL_INERTIA if flywheel_inertia is None else float(flywheel_inertia)
    return float(front + rotating_throw_inertia(model, throw_inertia).sum() + flywheel)
