r"""The powertrain's mass, centre of gravity and inertia tensor estimated from parts
(docs/mounts.md, "Estimating the powertrain").

Every part is a mass with its centre and its inertia tensor about that centre, in the
engine axes with the origin at the crank's reference point P (:mod:`.mounts`). The parts:

* a **box** of uniform density (the block, the gearbox): edges a, b, c along x, y, z,
  :math:`I = \frac{m}{12}\,\mathrm{diag}(b^2 + c^2,\ a^2 + c^2,\ a^2 + b^2)`;
* each throw's **rotating mass** :math:`m_r` at the crank radius r, averaged over a
  revolution: a thin ring about the crank axis in the throw's plane, centre on the axis,
  :math:`I = m_r r^2\,\mathrm{diag}(1/2, 1, 1/2)`;
* each cylinder's **reciprocating mass** as a point on its cylinder axis at the rod
  length l from the crank axis (the mean of its dead centres, l ± r), no inertia of its own;
  the wrist-pin offset is left out.

They are summed with the parallel-axis theorem: :math:`m = \sum m_k`,
:math:`G = \sum m_k c_k / m`, :math:`I_G = \sum [I_k + m_k (|d_k|^2 E - d_k d_k^T)]` with
:math:`d_k = c_k - G`. The tensor's off-diagonal entries are :math:`-\int xy\,dm` etc., as
everywhere in :mod:`.mounts`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..records import record
from ..results import ResultMixin
from .model import EngineModel


@record
class Part(ResultMixin):
    """One part of an estimated powertrain.

    Parameters
    ----------
    name : str
        What it is ("block", "gearbox", "throw 1 rotating", "cylinder 2 reciprocating").
    mass : float
        [kg].
    centre : ndarray, shape (3,)
        Its centre of gravity from the reference point [m].
    inertia : ndarray, shape (3, 3)
        Its inertia tensor about its own centre [kg·m²].
    """

    name: str
    mass: float
    centre: NDArray[np.float64]
    inertia: NDArray[np.float64]


def box_inertia(mass: float, size: ArrayLike) -> NDArray[np.float64]:
    """The inertia tensor of a solid box of uniform density about its centre.

    Parameters
    ----------
    mass : float
        [kg].
    size : array_like, shape (3,)
        Its edges a, b, c along x, y, z [m].

    Returns
    -------
    ndarray, shape (3, 3)
        :math:`\\frac{m}{12}\\mathrm{diag}(b^2 + c^2, a^2 + c^2, a^2 + b^2)` [kg·m²].
    """
    a, b, c = np.asarray(size, dtype=float) ** 2
    return np.asarray(mass / 12.0 * np.diag([b + c, a + c, a + b]), dtype=float)


def parallel_axis(mass: float, offset: ArrayLike) -> NDArray[np.float64]:
    """What a mass at ``offset`` from a point adds to the inertia tensor about that point
    beyond its own: :math:`m(|d|^2 E - d d^T)`.

    Parameters
    ----------
    mass : float
        [kg].
    offset : array_like, shape (3,)
        d, from the point to the mass's centre [m].

    Returns
    -------
    ndarray, shape (3, 3)
        [kg·m²].
    """
    d = np.asarray(offset, dtype=float)
    return np.asarray(mass * (float(d @ d) * np.eye(3) - np.outer(d, d)), dtype=float)


def combine(parts: tuple[Part, ...]) -> tuple[float, NDArray[np.float64], NDArray[np.float64]]:
    """The mass, centre of gravity and inertia tensor about it of parts taken as one body.

    Parameters
    ----------
    parts : tuple of Part
        The parts (at least one with mass).

    Returns
    -------
    mass : float
        [kg].
    cg : ndarray, shape (3,)
        [m].
    inertia : ndarray, shape (3, 3)
        About the centre of gravity [kg·m²].
    """
    mass = float(sum(p.mass for p in parts))
    cg = sum((p.mass * p.centre for p in parts), np.zeros(3)) / mass
    inertia = sum(
        (p.inertia + parallel_axis(p.mass, p.centre - cg) for p in parts), np.zeros((3, 3))
    )
    return mass, np.asarray(cg, dtype=float), np.asarray(inertia, dtype=float)


def crank_train_parts(model: EngineModel) -> tuple[Part, ...]:
    """The crank train's masses at their places, averaged over a revolution: each throw's
    rotating mass as a ring of the crank radius about the crank axis, each cylinder's
    reciprocating mass as a point on its cylinder axis at the rod length from the crank
    axis (module docstring).

    Parameters
    ----------
    model : EngineModel
        The engine (its reference point: :attr:`EngineModel.reference_x`,
        :attr:`~EngineModel.reference_z`).

    Returns
    -------
    tuple of Part
        The throws' rings, then the cylinders' points.
    """
    axis_x, axis_z = -model.reference_x, -model.reference_z  # the crank axis from P
    r, rod = model.crank_radius, model.rod_length
    out = []
    for k, (y, m) in enumerate(zip(model.throw_position, model.throw_rotating_mass, strict=True)):
        if m > 0:
            ring = m * r**2 * np.diag([0.5, 1.0, 0.5])
            out.append(
                Part(f"throw {k + 1} rotating", float(m), np.array([axis_x, y, axis_z]), ring)
            )
    for c, (throw, bank, m) in enumerate(
        zip(model.cylinder_throw, model.cylinder_bank, model.reciprocating_mass, strict=True)
    ):
        if m > 0:
            y = model.throw_position[throw] + model.cylinder_axial[c]
            centre = np.array([axis_x + rod * np.sin(bank), y, axis_z + rod * np.cos(bank)])
            out.append(Part(f"cylinder {c + 1} reciprocating", float(m), centre, np.zeros((3, 3))))
    return tuple(out)


def box_part(name: str, mass: float, size: ArrayLike, centre: ArrayLike) -> Part:
    """A box part (:func:`box_inertia`).

    Parameters
    ----------
    name : str
        Its name.
    mass : float
        [kg].
    size : array_like, shape (3,)
        Edges along x, y, z [m].
    centre : array_like, shape (3,)
        Its centre from the reference point [m].

    Returns
    -------
    Part
    """
    return Part(name, float(mass), np.asarray(centre, dtype=float), box_inertia(mass, size))
