"""results.record: a frozen dataclass built without its __init__ is the same record."""

from __future__ import annotations

import dataclasses
import pickle

import pytest

from crankbalance.physics.balance_remaining import Remaining
from crankbalance.physics.balancing import ComponentResidual
from crankbalance.results import record
from crankbalance.studies.engine import analyze, balance_engine


def test_a_record_equals_the_one_its_init_builds() -> None:
    values = ("order2", False, 1.5, 0.25, -0.0, 3.0, 0.125, 0.0, 2.0, 1e-300)
    fast, slow = record(ComponentResidual, *values), ComponentResidual(*values)
    assert fast == slow
    assert repr(fast) == repr(slow)
    assert pickle.dumps(fast) == pickle.dumps(slow)
    assert hash(fast) == hash(slow)
    with pytest.raises(dataclasses.FrozenInstanceError):
        fast.force_after = 0.0  # type: ignore[misc]


def test_a_record_needs_every_field() -> None:
    with pytest.raises(TypeError, match="Remaining takes 7 fields, not 6"):
        record(Remaining, "rotating", 1, "force", "forward", 1.0, "text")


def test_the_records_of_one_engine_equal_those_init_builds() -> None:
    result = balance_engine("v8-crossplane").result
    for entry in (*result.residuals, *result.remaining):
        assert entry == dataclasses.replace(entry)
        assert repr(entry) == repr(dataclasses.replace(entry))
    forces = analyze("inline4").forces
    assert repr(forces) == repr(dataclasses.replace(forces))
