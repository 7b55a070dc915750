"""The built model is kept per spec, and what a model derives is kept per model (issue 30:
a study of an engine seen before skips the build; ``free_forces`` takes its coefficient
rows from the model). Nothing here is timed."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from crankbalance.io.engine_file import load_engine
from crankbalance.physics.shaking import cylinder_coefficients, free_forces, roll_phasors
from crankbalance.studies.build import build_model
from crankbalance.studies.engine import analyze, balance_options


def test_an_equal_spec_gets_the_same_model() -> None:
    first = build_model(load_engine("v12-60"))
    again = build_model(load_engine("v12-60"))  # parsed afresh: equal, not the same object
    assert again is first
    other = build_model(load_engine("inline4"))
    assert other is not first


def test_a_changed_spec_gets_its_own_model() -> None:
    spec = load_engine("inline4")
    model = build_model(spec)
    faster = spec.replace(speed=2 * spec.speed)
    assert hash(faster) != hash(spec)
    assert build_model(faster).speed == 2 * model.speed
    assert build_model(spec) is model


def test_an_equal_spec_gets_the_same_balancing_options_a_changed_one_its_own() -> None:
    spec = load_engine("paper-inline3")  # a preset with a [counterweights] table
    first = balance_options(spec)
    assert balance_options(load_engine("paper-inline3")) is first  # frozen options, kept
    counterweights = spec.counterweights
    assert counterweights is not None
    wider = spec.replace(counterweights=counterweights.replace(cg_radius=0.06))
    assert balance_options(wider)[0].cg_radius == 0.06
    assert first[0].cg_radius == counterweights.cg_radius  # the kept ones did not change


def test_a_kept_model_cannot_be_changed_in_place() -> None:
    model = build_model(load_engine("v8-crossplane"))
    for f in dataclasses.fields(model):
        value = getattr(model, f.name)
        if isinstance(value, np.ndarray):
            with pytest.raises(ValueError, match="read-only"):
                value[...] = 0
    for derived in (model.cylinder_angle, model.cylinder_position, model.throw_rotating_moment):
        with pytest.raises(ValueError, match="read-only"):
            derived[...] = 0


def test_a_spec_hash_is_kept_and_equals_a_fresh_one() -> None:
    spec = load_engine("v6-60")
    kept = hash(spec)
    assert hash(load_engine("v6-60")) == kept == hash(spec)


def test_coefficient_rows_are_computed_once_per_model_and_order() -> None:
    model = build_model(load_engine("v12-60"))
    rows = cylinder_coefficients(model, 8)
    assert cylinder_coefficients(model, 8) is rows
    assert not rows.flags.writeable
    assert cylinder_coefficients(model, 6) is not rows
    assert cylinder_coefficients(model, 8, "series") is not rows


PHASORS = ("force_forward", "force_backward", "couple_forward", "couple_backward", "roll")
ROTATING = ("rotating_force", "rotating_couple", "rotating_roll")


@pytest.mark.parametrize("name", ["v6-60", "w8", "radial5-kinner"])  # w8: two offsets
def test_analysis_of_a_kept_model_is_that_of_a_fresh_one(name: str) -> None:
    spec = load_engine(name)
    kept_model = build_model(spec)
    modes = ("exact",) if kept_model.articulation is not None else ("exact", "series")
    for mode in modes:
        for orders in (8, 3):
            free_forces(kept_model, orders, mode)  # derives what the model keeps
            kept = free_forces(kept_model, orders, mode)  # from what it kept
            fresh_model = dataclasses.replace(kept_model)  # a new model: nothing derived yet
            assert not fresh_model.derived
            fresh = free_forces(fresh_model, orders, mode)
            for field in PHASORS:  # the same bits
                assert getattr(kept, field).tobytes() == getattr(fresh, field).tobytes()
            for field in ROTATING:
                assert getattr(kept, field) == getattr(fresh, field)


def test_roll_rows_and_sum_weights_are_kept_per_model_read_only() -> None:
    model = dataclasses.replace(build_model(load_engine("w8")))  # nothing derived yet
    first = roll_phasors(model, 8)
    kept = {key: value for key, value in model.derived.items() if key[0] == "roll_rows"}
    assert list(kept) == [("roll_rows", 8, "exact")]
    rows, angle, scale = kept["roll_rows", 8, "exact"]
    assert rows.shape == (1, model.cylinders, 8)  # two offsets: a row per cylinder
    for array in (rows, angle, scale):
        assert not array.flags.writeable
    assert np.array_equal(roll_phasors(model, 8), first)
    assert model.derived["roll_rows", 8, "exact"][0] is rows  # not computed again
    roll_phasors(model, 8, "series")
    assert model.derived["roll_rows", 8, "series"][0] is not rows
    free_forces(model, 8)
    for array in model.derived["free_forces.weights",]:
        assert not array.flags.writeable


def test_analysis_of_a_kept_model_zeroes_the_same_round_off_as_a_fresh_one() -> None:
    spec = load_engine("inline4")  # second-order forces only: many entries at round-off
    kept = analyze(spec, 5).forces
    again = analyze(spec, 5).forces  # the model, its levels and the orders check kept
    fresh = analyze(dataclasses.replace(build_model(spec)), 5).forces
    for field in PHASORS:
        assert getattr(again, field).tobytes() == getattr(kept, field).tobytes()
        assert getattr(fresh, field).tobytes() == getattr(kept, field).tobytes()
    assert kept.force_forward[0] == 0 and kept.couple_forward[1] == 0  # zeroed
    for field in ROTATING:
        assert type(getattr(kept, field)) is complex
        assert getattr(again, field) == getattr(fresh, field) == getattr(kept, field)


def test_an_engine_text_read_again_gives_the_spec_made_the_first_time() -> None:
    from crankbalance.errors import InputError
    from crankbalance.io.engine_file import parse_engine_text, preset_text

    assert load_engine("v6-60") is load_engine("v6-60")
    text = preset_text("inline4")
    spec = parse_engine_text(text, "a.toml")
    assert parse_engine_text(text, "a.toml") is spec
    changed = parse_engine_text(text.replace("6000 rpm", "3000 rpm"), "a.toml")
    assert changed is not spec and changed.speed == spec.speed / 2
    bad = text.replace("6000 rpm", "-1 rpm")
    for _ in range(2):  # a refused text is refused every time, with its message
        with pytest.raises(InputError, match="a.toml|speed"):
            parse_engine_text(bad, "a.toml")
