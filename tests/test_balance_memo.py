"""One engine's balance keeps what it derives from the model alone (issue 30): the solver's
input (free forces, unbalance, scales) per model, the webs, equations and pattern factors
per web choice. A result from a model that kept them is the result of a fresh model, to
the last bit, whatever options came before."""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np
import pytest

from crankbalance.io.engine_file import load_engine
from crankbalance.physics.balance_solver import model_input, solve
from crankbalance.physics.balancing import CounterweightOptions, ShaftOptions, balance
from crankbalance.studies.build import build_model
from crankbalance.studies.engine import balance_options

VARIANTS: list[dict[str, object]] = [
    {},
    {"balance_factor": 0.5},
    {"method": "individual", "balance_factor": 0.5},
    {"scope": "halves"},
    {"angle": 0.3, "scope": "whole", "balance_factor": 0.3},
    {"webs": None, "web_offset": 0.01},
]
SHAFTS = [(None, None), (ShaftOptions(0.03, 0.3), ShaftOptions(0.03, 0.3, "counter-rotating"))]


def _fresh(name: str):  # noqa: ANN202
    """A model built anew (not the one ``build_model`` keeps)."""
    spec = load_engine(name)
    return dataclasses.replace(build_model(spec)), spec


def _result(model, options, shafts):  # noqa: ANN001, ANN202
    try:
        with np.printoptions(floatmode="unique", precision=17, threshold=10**6):
            return repr(balance(model, options, *shafts))  # every bit of every number
    except Exception as error:  # the same error, or the same result  # noqa: BLE001
        return f"{type(error).__name__}: {error}"


@pytest.mark.parametrize("name", ["v8-crossplane", "inline4", "w12", "v6-90", "boxer4"])
def test_a_model_that_kept_its_derived_arrays_balances_as_a_fresh_one(name: str) -> None:
    kept, spec = _fresh(name)
    base = balance_options(spec)[0] or CounterweightOptions(cg_radius=0.04)
    cases = [
        (dataclasses.replace(base, **variant), shafts)
        for variant, shafts in itertools.product(VARIANTS, SHAFTS)
    ]
    for options, shafts in cases + cases[::-1]:  # each after every other, both ways
        fresh, _ = _fresh(name)
        assert _result(kept, options, shafts) == _result(fresh, options, shafts)


def test_the_solver_input_is_kept_by_the_model_read_only() -> None:
    model, _ = _fresh("v8-crossplane")
    first = model_input(model, 8)
    assert model_input(model, 8) is first
    assert model_input(model, 4) is not first
    for value in [*vars(first).values(), *vars(first.forces).values()]:
        if isinstance(value, np.ndarray):
            assert not value.flags.writeable
    balance(model, CounterweightOptions(cg_radius=0.04))
    kinds = {key[0] for key in first.memo}  # kept for the next call, read-only
    assert kinds == {"webs", "equations", "pattern", "residuals", "halves"}
    webs = next(v for k, v in first.memo.items() if k[0] == "webs")
    assert not webs.position.flags.writeable
    assert not first.memo[("halves", False)].flags.writeable
    assert not any(a.flags.writeable for a in first.memo[("residuals",)])


def test_a_result_owns_its_arrays() -> None:
    """The webs the input keeps are read-only; a result's counterweights are its own."""
    model, _ = _fresh("v8-crossplane")
    result = balance(model, CounterweightOptions(cg_radius=0.04))
    assert result.counterweights is not None
    for array in (result.counterweights.web, result.counterweights.position):
        assert array.flags.writeable
        array[...] = 0
    again = balance(model, CounterweightOptions(cg_radius=0.04))
    assert again.counterweights is not None and again.counterweights.position.any()


@pytest.mark.parametrize("variant", VARIANTS)
def test_the_counterweights_moments_are_computed_once_read_only(variant: dict) -> None:
    """``BatchCounterweights.moments`` and ``moment_sums`` are kept by the record (the solver
    hands over the ones it computed): the same arrays on every access, read-only, every bit
    as their formulas."""
    model, _ = _fresh("v8-crossplane")
    options = dataclasses.replace(CounterweightOptions(cg_radius=0.04), **variant)
    cw = solve(model_input(model, 8), options).counterweights
    assert cw is not None
    assert cw.moments is cw.moments
    assert not cw.moments.flags.writeable
    formula = cw.mass * cw.cg_radius * np.exp(1j * cw.direction)
    assert cw.moments.tobytes() == formula.tobytes()
    total, couple = cw.moment_sums
    assert cw.moment_sums is cw.moment_sums
    assert not total.flags.writeable and not couple.flags.writeable
    assert total.tobytes() == formula.sum(axis=-1).tobytes()
    assert couple.tobytes() == (formula * cw.position).sum(axis=-1).tobytes()
    fresh = dataclasses.replace(cw)  # a record built anew computes them on first access
    assert "moments" not in vars(fresh) and "moment_sums" not in vars(fresh)
    assert fresh.moments.tobytes() == formula.tobytes() and fresh.moments is fresh.moments
    assert [a.tobytes() for a in fresh.moment_sums] == [total.tobytes(), couple.tobytes()]


def test_the_squared_speed_is_kept_by_the_input_read_only() -> None:
    inputs = model_input(build_model(load_engine("v8-crossplane")), 8)
    kept = inputs.speed_squared
    assert kept is inputs.speed_squared  # computed once
    assert np.array_equal(kept, inputs.speed**2)
    assert not kept.flags.writeable
