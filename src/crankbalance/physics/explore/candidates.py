"""The batch of candidate engines that the explorer's stages pass on."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ...records import record
from ..model import EngineModel


@record
class Candidates:
    """B candidate engines of one topology: one crank and one firing order each.

    The topology (throws' axial positions, each cylinder's throw and bank angle, masses,
    geometry, speed, strokes) is shared; what differs is the crank and the firing order.

    Parameters
    ----------
    topology : EngineModel
        The shared layout; its own throw angles and firing order are not used.
    throw_angle : ndarray, shape (B, T)
        Throw angles [rad] in [0, 2π), as ``studies.build`` derives them with cylinder 1
        firing at crank angle 0 (the crank's rigid rotation removed): throw 1 sits at
        cylinder 1's bank angle (0 for in-line engines).
    firing_order : ndarray of int, shape (B, C)
        Cylinder numbers (1-based, crankbalance's numbering) in firing sequence, starting
        with cylinder 1.
    fire_angle : ndarray, shape (B, C)
        Crank angle [rad] at which each cylinder (column c is cylinder c + 1) fires, in
        [0, 4π) for 4-stroke and [0, 2π) for 2-stroke; cylinder 1 fires at 0.
    equivalents : ndarray of int, shape (B,)
        How many firing orders (renumbered, mirrored or rotated) describe the same engine;
        :func:`crankbalance.physics.explore.orders.equivalent_orders` lists them.
    index : ndarray of int, shape (B,)
        Each candidate's index in the problem's enumeration (stable across chunks, workers
        and runs), so results from different chunks can be merged and compared exactly.
    """

    topology: EngineModel
    throw_angle: NDArray[np.float64]
    firing_order: NDArray[np.int64]
    fire_angle: NDArray[np.float64]
    equivalents: NDArray[np.int64]
    index: NDArray[np.int64]

    @property
    def size(self) -> int:
        """Number of candidates B."""
        return int(self.index.size)

    def take(self, which: NDArray[np.int64]) -> Candidates:
        """The candidates at positions ``which`` (copies).

        Parameters
        ----------
        which : ndarray of int, shape (D,)
            Positions in the batch [-].

        Returns
        -------
        Candidates
            Those candidates, in the order of ``which``.
        """
        return Candidates(
            topology=self.topology,
            throw_angle=self.throw_angle[which],
            firing_order=self.firing_order[which],
            fire_angle=self.fire_angle[which],
            equivalents=self.equivalents[which],
            index=self.index[which],
        )

    def part(self, start: int, stop: int) -> Candidates:
        """The candidates from position ``start`` to before ``stop`` (views, no copy).

        Parameters
        ----------
        start, stop : int
            Positions in the batch [-].

        Returns
        -------
        Candidates
            The slice of the batch.
        """
        return Candidates(
            topology=self.topology,
            throw_angle=self.throw_angle[start:stop],
            firing_order=self.firing_order[start:stop],
            fire_angle=self.fire_angle[start:stop],
            equivalents=self.equivalents[start:stop],
            index=self.index[start:stop],
        )
