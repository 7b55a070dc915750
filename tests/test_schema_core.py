"""The schema machinery (crankbalance.schema.core): parsing from files and from text,
messages that name the field as written, bounds, unknown keys, checks across fields,
writing back, and the JSON Schema."""

from __future__ import annotations

import math

import pytest

from crankbalance.errors import InputError
from crankbalance.schema.core import FieldProblem, Schema, allowed, entry, field, json_schema


class Part(Schema):
    """A part of an example."""

    mass: float = field("mass", title="Mass")
    count: int = field("whole", default=1, ge=1, le=8)


class Example(Schema):
    """An example input."""

    DOC = "docs/example.md"
    radius: float = field("length", title="Radius", description="of the crank")
    offset: float = field("length", default=0.0, zero=True)
    factor: float = field("factor", default=0.5, ge=0, le=2)
    kind: str = field("choice", default="pattern", choices=("pattern", "individual"))
    speeds: list[float] = field("list", default=[], item=entry("speed"), max_items=3)
    part: Part | None = field("table", default=None, table=Part)
    parts: list[Part] = field("list", default=[], item=entry("table", table=Part), max_items=4)

    def check(self) -> None:
        if self.offset > self.radius:
            raise FieldProblem("offset", "must not exceed the radius")


def error(data: object, **kwargs: object) -> str:
    with pytest.raises(InputError) as caught:
        Example.parse(data, **kwargs)  # type: ignore[arg-type]
    return str(caught.value)


def test_values_parse_to_si_with_defaults() -> None:
    e = Example.parse({"radius": "40 mm", "speeds": ["1000 rpm"], "part": {"mass": "500 g"}})
    assert e.radius == pytest.approx(0.04)
    assert e.offset == 0.0 and e.factor == 0.5 and e.kind == "pattern"
    assert e.speeds == [pytest.approx(1000 * math.pi / 30)]
    assert e.part is not None and e.part.mass == pytest.approx(0.5) and e.part.count == 1


def test_text_source_reads_numbers_and_lists() -> None:
    e = Example.parse(
        {"radius": "40 mm", "factor": "28%", "speeds": "1000 rpm, 2000 rpm", "kind": "Individual"},
        source="text",
    )
    assert e.factor == pytest.approx(0.28)
    assert len(e.speeds) == 2 and e.kind == "individual"


def test_file_source_keeps_types_strict() -> None:
    assert "whole number" in error({"radius": "40 mm", "part": {"mass": "1 g", "count": "2"}})
    assert "whole number" in error({"radius": "40 mm", "part": {"mass": "1 g", "count": True}})


def test_unknown_key_named_with_the_closest() -> None:
    message = error({"radius": "40 mm", "ofset": "1 mm"})
    assert message == "ofset = '1 mm': unknown key; did you mean 'offset'?"
    message = error({"radius": "40 mm", "part": {"mas": "1 g"}})
    assert message == "part.mas = '1 g': unknown key; did you mean 'mass'?"


def test_a_typo_of_a_required_key_is_named_before_it_is_missing() -> None:
    assert error({"raduis": "40 mm"}) == "raduis = '40 mm': unknown key; did you mean 'radius'?"
    assert error({}) == "radius: is missing; it is required (see docs/example.md)"


def test_bounds_and_ranges() -> None:
    assert "from 0 to 2" in error({"radius": "40 mm", "factor": 3})
    assert error({"radius": "1e308 km"}) == "radius = '1e308 km': must lie between 1 um and 100 m"
    assert "0, or" in allowed(Example.FIELDS["offset"])
    Example.parse({"radius": "40 mm", "offset": "0 mm"})
    assert error({"radius": "40 mm", "speeds": ["1 rpm"] * 4}).startswith(
        "speeds = '4 entries': takes at most 3 entries"
    )


def test_choice_suggests_the_closest() -> None:
    assert "did you mean 'pattern'" in error({"radius": "40 mm", "kind": "patern"})


def test_check_across_fields_names_the_field_with_the_value_as_written() -> None:
    assert error({"radius": "40 mm", "offset": "50 mm"}) == (
        "offset = '50 mm': must not exceed the radius"
    )


def test_nested_list_paths_and_a_namer() -> None:
    message = error({"radius": "40 mm", "parts": [{"mass": "1 g"}, {"mass": "1 g", "count": 9}]})
    assert message.startswith("parts[1].count = 9: must be a whole number from 1 to 8")
    message = error({"radius": "x"}, source="text", name=lambda p: "--" + str(p[0]))
    assert message.startswith("--radius = 'x':")


def test_replace_checks_again_and_to_data_writes_units() -> None:
    e = Example.parse({"radius": "40 mm", "part": {"mass": "500 g"}})
    with pytest.raises(InputError, match="offset"):
        e.replace(offset=0.05)
    assert e.to_data() == {"radius": "40 mm", "part": {"mass": "500 g"}}
    assert Example.parse(e.to_data()) == e


def test_json_schema() -> None:
    schema = json_schema(Example, title="Example")
    assert schema["required"] == ["radius"]
    assert schema["additionalProperties"] is False
    assert schema["properties"]["part"]["properties"]["count"]["maximum"] == 8
    assert schema["properties"]["kind"]["enum"] == ["pattern", "individual"]


class Shaft(Schema):
    """An example with the engine file's rules on quantities."""

    radius: float = field("length", gt=0)
    mass: float = field("mass", default=0.0, ge=0)
    offset: float = field("length", default=0.0, zero=True)


class Left(Schema):
    left: int = field("whole", default=1)


class Right(Schema):
    right: int = field("whole", default=2)


class Both(Left, Right):
    both: int = field("whole", default=3)


class Outer(Schema):
    """An example with tables, for keys put in the wrong one."""

    speed: float = field("speed")
    inner: Part = field("table", table=Part)
    parts: list[Part] = field("list", default=[], item=entry("table", table=Part), max_items=2)


def test_quantities_in_size_with_a_sign_rule() -> None:
    """Without full bounds a quantity is checked in size against its physical range, zero
    and the sign by its rule (the engine file's messages)."""
    assert Shaft.parse({"radius": "40 mm", "offset": "-5 mm"}).offset == pytest.approx(-0.005)
    for data, words in (
        ({"radius": "0 mm"}, "radius = '0 mm': must be greater than zero"),
        ({"radius": "-4 mm"}, "radius = '-4 mm': must be greater than zero"),
        ({"radius": "1e308 km"}, "radius = '1e308 km': must lie between 1 um and 100 m"),
        ({"radius": "40 mm", "mass": "-1 g"}, "mass = '-1 g': must not be negative"),
        ({"radius": "40 mm", "offset": "-1e9 m"}, "must lie between 1 um and 100 m in size"),
    ):
        with pytest.raises(InputError) as caught:
            Shaft.parse(data)
        assert str(caught.value).endswith(words), caught.value
    assert Shaft.parse({"radius": "40 mm", "mass": "0 g"}).mass == 0.0
    assert (
        allowed(Shaft.FIELDS["radius"]) == "a length with a unit, e.g. '40 mm', from 1 um to 100 m"
    )
    assert allowed(Shaft.FIELDS["mass"]).startswith("0, or a mass")
    assert "of either sign" in allowed(Shaft.FIELDS["offset"])


def test_a_decimal_comma_is_named() -> None:
    assert error({"radius": "1,5 mm"}) == "radius = '1,5 mm': has a decimal comma; write '1.5 mm'"
    message = error({"radius": "40 mm", "factor": "0,5"}, source="text")
    assert message == "factor = '0,5': has a decimal comma; write '0.5'"
    assert "decimal comma" in error({"radius": "40 mm", "part": {"mass": "2,5 kg"}})


def test_an_unknown_key_anywhere_comes_first_and_a_misplaced_key_names_its_table() -> None:
    def outer(data: object) -> str:
        with pytest.raises(InputError) as caught:
            Outer.parse(data)
        return str(caught.value)

    # the typo deep in a list of tables is named although speed is missing too
    assert outer({"inner": {"mass": "1 g"}, "parts": [{"mass": "1 g"}, {"mas": "2 g"}]}) == (
        "parts[1].mas = '2 g': unknown key; did you mean 'mass'?"
    )
    assert outer({"inner": {"mass": "1 g", "speed": "1 rpm"}}) == (
        "inner.speed = '1 rpm': unknown key here; speed belongs at the top level, before any "
        "[table]"
    )
    assert outer({"speed": "1 rpm", "count": 2, "inner": {"mass": "1 g"}}) == (
        "count = 2: unknown key here; count belongs in [inner]"
    )
    assert outer({"speed": "1 rpm", "iner": {"mass": "1 g"}}) == (
        "iner: unknown key; did you mean 'inner'?"
    )
    assert outer({"speed": "1 rpm"}) == "inner: is missing; it is required"


def test_whole_numbers_from_text_and_from_files() -> None:
    """From text (the command line, a form) a whole number may be written as '1e3' or come
    as 8.0 from JSON; from a file it is an integer as written."""
    text = Part.parse({"mass": "1 g", "count": "8.0"}, source="text")
    assert text.count == 8 and isinstance(text.count, int)
    for raw in ("1.5", "nan", "x", True):
        with pytest.raises(InputError):
            Part.parse({"mass": "1 g", "count": raw}, source="text")
    with pytest.raises(InputError, match="without a decimal point"):
        Part.parse({"mass": "1 g", "count": 4.0})
    with pytest.raises(InputError, match=r"from 1 to 8, written without quotes"):
        Part.parse({"mass": "1 g", "count": "4"})


def test_inherited_fields_from_every_base() -> None:
    assert list(Both.FIELDS) == ["right", "left", "both"]
    assert Both().left == 1 and Both(right=5).right == 5


def test_values_pickling_and_copies() -> None:
    import copy
    import pickle

    e = Example.parse({"radius": "40 mm", "parts": [{"mass": "500 g"}]})
    assert e.values()["parts"] == [{"mass": pytest.approx(0.5), "count": 1}]
    assert e.values()["radius"] == pytest.approx(0.04)
    assert pickle.loads(pickle.dumps(e)) == e and copy.deepcopy(e) == e
    assert hash(e) == hash(Example.parse(e.to_data()))
    with pytest.raises(AttributeError, match="frozen"):
        e.radius = 1.0  # type: ignore[misc]


def test_hints_say_the_kind_in_words_and_round_a_limit_outward() -> None:
    """A kind's identifier in words ("a specific energy", not "a specific_energy"); a
    limit of 0.001 rad shown in degrees reads 0.0573 deg, not 0.0572958 deg, rounded
    outward (a lower limit up, an upper one down) so that the words stay true."""

    class Burn(Schema):
        """A burn."""

        duration: float = field("angle", default=0.5, ge=0.001, le=math.pi)
        sweep: float = field("angle", default=0.5, ge=0.0, le=1.0)
        heat: float = field("specific_energy", default=4.4e7, ge=1e6, le=2e8)

    assert allowed(Burn.FIELDS["duration"]).endswith("from 0.0573 deg to 180 deg")
    assert allowed(Burn.FIELDS["sweep"]).endswith("from 0 deg to 57.29 deg")  # 57.2958 down
    assert allowed(Burn.FIELDS["heat"]).startswith("a specific energy with a unit")
    # a value just below the rounded lower limit is refused, the words hold
    with pytest.raises(InputError) as caught:
        Burn.parse({"duration": "0.0572 deg"})
    assert "must be an angle" in str(caught.value)
