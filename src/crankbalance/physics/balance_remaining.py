"""What a balancing result leaves, in words (issue 27): one :class:`Remaining` per free
force or couple left, forward and backward apart, and the next step that would remove it
(:func:`next_step`). :func:`crankbalance.physics.balancing.what_is_left` lists them for a
result; the balance table and JSON (``remaining``) show them.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..results import ResultMixin
from .balance_types import CounterweightOptions, ShaftOptions


@dataclass(frozen=True)
class Remaining(ResultMixin):
    """One free force or couple a balancing result leaves, in words, with the next step
    that would remove it.

    Parameters
    ----------
    component : str
        ``"rotating"`` or ``"order1"``, ``"order2"``, ... as :class:`ComponentResidual`.
    order : int
        Its order (1 for the rotating masses) [-].
    quantity : {"force", "couple"}
        A free force [N] or a free couple (moment) [N·m].
    rotation : {"forward", "backward"}
        Turning with the crank (co-rotating) or against it (counter-rotating).
    amount : float
        Its size, :math:`|F_n^{+}|` or :math:`|F_n^{-}|` [N], :math:`|C_n^{+}|` or
        :math:`|C_n^{-}|` [N·m].
    text : str
        What remains, in words, with its amount and unit.
    next_step : str
        What would remove it: a balance factor, a balance shaft, a counterweight pattern
        or another crank.
    """

    component: str
    order: int
    quantity: str
    rotation: str
    amount: float
    text: str
    next_step: str


def next_step(
    component: str,
    order: int,
    rotation: str,
    counterweights: CounterweightOptions | None,
    primary: ShaftOptions | None,
    missed: bool,
) -> str:
    """What would remove a free force or couple a balancing result leaves.

    Parameters
    ----------
    component : str
        ``"rotating"`` or ``"order1"``, ``"order2"``, ...
    order : int
        Its order [-].
    rotation : {"forward", "backward"}
        Its sense of rotation.
    counterweights : CounterweightOptions or None
        The crank counterweights asked for.
    primary : ShaftOptions or None
        The primary balance shafts asked for.
    missed : bool
        Whether the counterweights fell short of their target.

    Returns
    -------
    str
        The next step, in words: a balance factor, a balance shaft, a counterweight
        pattern or another crank.
    """
    reach = (
        'crank counterweights that reach their target (angle = "optimal" or method = "individual")'
    )
    if component == "rotating":
        return reach if counterweights is not None else "crank counterweights ([counterweights])"
    if order == 1 and rotation == "forward":
        if counterweights is None:
            return (
                "crank counterweights with a balance factor of 0.5 (--balance-factor 0.5), "
                "or a co-rotating primary balance shaft"
            )
        factor = counterweights.balance_factor
        if missed:
            return reach
        if factor != 0.5:
            return (
                f"a balance factor of 0.5 (--balance-factor 0.5; now {factor:g}) puts the "
                "forward primary on the crank counterweights, or a co-rotating primary "
                "balance shaft"
            )
        return "a co-rotating primary balance shaft"
    if order == 1:
        return (
            "a counter-rotating primary balance shaft (balance_shafts.primary; a balance "
            "factor only moves the forward half)"
            if primary is None
            else "a counter-rotating primary balance shaft"
        )
    if order == 2:
        return f"a {'co' if rotation == 'forward' else 'counter'}-rotating secondary balance shaft"
    return (
        f"no balance shaft of order {order} here: another crank or firing order "
        "(crankbalance explore)"
    )
