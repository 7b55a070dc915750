"""crankbalance.records.record against the second method it stands for: the standard
library's ``dataclasses.dataclass(frozen=True)``. Each class is made both ways from one
body; every behaviour a caller sees (construction, defaults, errors, comparison, hashing,
repr, immutability, ``replace``, ``asdict``, pickling, the signature) must be the same."""

from __future__ import annotations

import copy
import dataclasses
import inspect
import pickle
from typing import Any

import pytest

from crankbalance.records import record


def _both(body: Any, **options: Any) -> tuple[type, type]:
    """The class made by dataclasses and by record from one body (a function returning
    the class, so that each decorator sees a fresh class)."""
    reference = dataclasses.dataclass(frozen=True, **options)(body())
    ours = record(**options)(body()) if options else record(body())
    return reference, ours


def _point() -> type:
    class Point:
        """A point."""

        x: float
        y: float = 2.0
        tags: list[str] = dataclasses.field(default_factory=list)
        note: str = dataclasses.field(default="", compare=False, repr=False)

    return Point


def _checked() -> type:
    class Checked:
        """A record with a field its __post_init__ sets."""

        a: int
        doubled: int = dataclasses.field(init=False)

        def __post_init__(self) -> None:
            object.__setattr__(self, "doubled", 2 * self.a)

    return Checked


def _outcome(call: Any) -> Any:
    """What ``call()`` returns, or the type and message of what it raises (the class name
    cut out of the message: the two classes share it)."""
    try:
        return ("value", call())
    except Exception as error:  # compared below between the two ways
        return (type(error).__name__, str(error).split("(")[0].split(".")[-1])


@pytest.mark.parametrize(
    "make",
    [
        lambda c: c(1.0),
        lambda c: c(1.0, 3.0),
        lambda c: c(x=1.0, y=3.0, tags=["a"], note="n"),
        lambda c: c(1.0, 3.0, ["a"], "n"),
    ],
    ids=["default", "positional", "keywords", "all positional"],
)
def test_construction_and_value_behaviour_match_a_frozen_dataclass(make: Any) -> None:
    reference, ours = _both(_point)
    a, b = make(reference), make(ours)
    assert dataclasses.asdict(a) == dataclasses.asdict(b)
    assert repr(a).replace(reference.__qualname__, "") == repr(b).replace(ours.__qualname__, "")
    assert [f.name for f in dataclasses.fields(ours)] == ["x", "y", "tags", "note"]
    assert make(ours) == b
    assert _outcome(lambda: hash(a))[0] == _outcome(lambda: hash(b))[0], "a list is unhashable"
    assert dataclasses.replace(b, note="other") == b, "note is not compared"
    assert dataclasses.replace(b, y=9.0) != b
    assert copy.deepcopy(b) == b
    assert dataclasses.is_dataclass(b)


@record
class Stored:
    """A record at module level, which pickle finds by name."""

    a: int
    b: tuple[int, ...] = ()


def test_a_record_pickles_and_copies() -> None:
    stored = Stored(1, (2, 3))
    assert pickle.loads(pickle.dumps(stored)) == stored
    assert copy.copy(stored) == stored and copy.deepcopy(stored) == stored


def test_a_default_factory_gives_each_record_its_own_value() -> None:
    _, ours = _both(_point)
    first, second = ours(1.0), ours(1.0)
    assert first.tags == [] and first.tags is not second.tags


@pytest.mark.parametrize(
    "call",
    [
        lambda c: c(),
        lambda c: c(1.0, 2.0, [], "", 5),
        lambda c: c(1.0, x=2.0),
        lambda c: c(1.0, z=2.0),
    ],
    ids=["missing", "too many", "twice", "unknown"],
)
def test_bad_arguments_raise_what_a_dataclass_raises(call: Any) -> None:
    reference, ours = _both(_point)
    theirs, mine = _outcome(lambda: call(reference)), _outcome(lambda: call(ours))
    assert theirs[0] == mine[0] == "TypeError", (theirs, mine)


@pytest.mark.parametrize("action", ["assign", "delete", "assign a new name"])
def test_a_record_is_frozen(action: str) -> None:
    for cls in _both(_point):
        point = cls(1.0)
        with pytest.raises(dataclasses.FrozenInstanceError):
            if action == "assign":
                point.x = 3.0
            elif action == "delete":
                del point.x
            else:
                point.other = 1


def test_hash_and_equality_follow_the_compared_fields() -> None:
    reference, ours = _both(_point)
    for cls in (reference, ours):
        assert cls(1.0, tags=()) == cls(1.0, tags=(), note="x")
        assert hash(cls(1.0, tags=())) == hash(cls(1.0, tags=(), note="x"))
        assert cls(1.0) != cls(2.0)
        assert cls(1.0).__eq__(object()) is NotImplemented
    assert ours(1.0) != reference(1.0), "records of two classes are not equal"


def test_eq_false_compares_by_identity_and_repr_false_keeps_objects() -> None:
    reference, ours = _both(_point, eq=False, repr=False)
    for cls in (reference, ours):
        a = cls(1.0)
        assert a != cls(1.0) and a == a and hash(a) == object.__hash__(a)
        assert repr(a).startswith("<")


def _labelled() -> type:
    class Labelled:
        """A record with a field left out of __init__ that has a default."""

        a: int
        b: int = 0
        label: str = dataclasses.field(default="set", init=False)

    return Labelled


@pytest.mark.parametrize("args", [(1, 2), (1,)], ids=["every field by position", "one"])
def test_a_field_left_out_of_init_takes_its_default(args: tuple[int, ...]) -> None:
    reference, ours = _both(_labelled)
    assert dataclasses.asdict(reference(*args)) == dataclasses.asdict(ours(*args))
    assert ours(*args).label == "set"


def test_post_init_and_a_field_left_out_of_init() -> None:
    reference, ours = _both(_checked)
    assert reference(3).doubled == ours(3).doubled == 6
    assert _outcome(lambda: ours(3, 6))[0] == "TypeError"
    assert dataclasses.replace(ours(3), a=4).doubled == 8


def test_the_signature_is_the_dataclass_signature() -> None:
    reference, ours = _both(_point)
    assert str(inspect.signature(ours)) == str(inspect.signature(reference))
    assert ours.__doc__ == "A point."


def test_a_method_of_the_class_body_is_kept() -> None:
    @record
    class Shown:
        """A record with a repr of its own."""

        a: int

        def __repr__(self) -> str:
            return "mine"

    assert repr(Shown(1)) == "mine" and Shown(1) == Shown(1)


def test_a_subclass_record_adds_fields_after_its_base() -> None:
    @record
    class Base:
        """A base."""

        a: int

    @record
    class Child(Base):
        """A child."""

        b: int = 0

    child = Child(1, 2)
    assert (child.a, child.b) == (1, 2) and Child(1) == Child(a=1, b=0)
    assert Base(1) != Child(1)
    with pytest.raises(dataclasses.FrozenInstanceError):
        child.a = 2
