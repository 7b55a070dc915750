"""What a balancing result leaves, in words (issue 27): one :class:`Remaining` per free
force or couple left, forward and backward apart, and the next step that would remove it
(:func:`next_step`). :func:`crankbalance.physics.balancing.what_is_left` lists them for a
result; the balance table and JSON (``remaining``) show them.
"""

from __future__ import annotations

from ..records import record
from ..results import ResultMixin
from .balance_types import CounterweightOptions, ShaftOptions

#: how the command line (and the JSON's ``next_step``) names the balance factor in a next
#: step; the web passes its form's label instead (:func:`step_words`)
FACTOR_OPTION = "--balance-factor"
#: where a next step's words name the balance factor setting (:attr:`Remaining.step_format`)
NAME = "{name}"


@record
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
        or another crank, in the command line's words (:data:`FACTOR_OPTION`).
    step_format : str
        The same with :data:`NAME` where the balance factor setting is named, for
        :func:`step_words` (each surface names it its own way).
    """

    component: str
    order: int
    quantity: str
    rotation: str
    amount: float
    text: str
    next_step: str
    step_format: str = ""


def step_words(step_format: str, name: str) -> str:
    """A next step in the words of the reader's surface.

    Parameters
    ----------
    step_format : str
        The next step with :data:`NAME` for the balance factor setting
        (:attr:`Remaining.step_format`).
    name : str
        How the surface names that setting: the command line's option
        :data:`FACTOR_OPTION`, the web form's label "Balance factor".

    Returns
    -------
    str
        The next step with ``name`` in place.
    """
    return step_format.replace(NAME, name)


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
        pattern or another crank; :data:`NAME` where it names the balance factor setting
        (:func:`step_words` puts the surface's name there).
    """
    reach = (
        'crank counterweights that reach their target (angle = "optimal" or method = "individual")'
    )
    if component == "rotating":
        return reach if counterweights is not None else "crank counterweights ([counterweights])"
    if order == 1 and rotation == "forward":
        if counterweights is None:
            return (
                f"crank counterweights with a balance factor of 0.5 ({NAME} 0.5), "
                "or a co-rotating primary balance shaft"
            )
        factor = counterweights.balance_factor
        if missed:
            return reach
        if factor != 0.5:
            return (
                f"a balance factor of 0.5 ({NAME} 0.5; now {factor:g}) puts the "
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
