"""The one rule of round-off (issue 26): a force or moment at most 1e-12 of an engine's
scale is zero; the scales from the engine's masses, crank radius, speed and extent."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankbalance.physics.model import engine_batch
from crankbalance.results import ROUND_OFF, below_round_off, engine_scales, round_off
from crankbalance.schema.engine import spec_from_dict
from crankbalance.studies.build import build_model


def twin(cylinders: int = 2) -> dict[str, object]:
    return {
        "speed": "6000 rpm",
        "crank_train": {
            "layout": "inline",
            "cylinders": cylinders,
            "crank_radius": "40 mm",
            "rod_length": "140 mm",
            "crank_pitch": "90 mm",
            **({"throw_angles": ["0 deg", "180 deg"]} if cylinders == 2 else {}),
        },
        "masses": {"reciprocating": "400 g", "rotating": "1000 g"},
    }


def test_levels_of_a_twin_by_hand() -> None:
    """Two cylinders: 0.4 kg reciprocating and 1 kg rotating each, r = 40 mm, 6000 rpm,
    throws 90 mm apart: F = 2.8 kg * 0.04 m * (200 pi/s)^2, L = 0.09 m (the extent)."""
    model = build_model(spec_from_dict(twin()))
    w = 6000 * 2 * math.pi / 60
    force = (2 * 0.4 + 2 * 1.0) * 0.04 * w**2  # 44 214 N
    f, m = round_off(model)
    assert f == pytest.approx(1e-12 * force, rel=1e-12)
    assert m == pytest.approx(1e-12 * force * 0.09, rel=1e-12)
    assert engine_scales(model)[1] == pytest.approx(0.09, rel=1e-12)


def test_a_single_throw_takes_the_crank_radius_as_its_length() -> None:
    model = build_model(spec_from_dict(twin(1)))
    w = 6000 * 2 * math.pi / 60
    force = 1.4 * 0.04 * w**2
    f, m = round_off(model)
    assert f == pytest.approx(ROUND_OFF * force, rel=1e-12)
    assert m == pytest.approx(ROUND_OFF * force * 0.04, rel=1e-12), "extent zero: the radius"


def test_levels_of_a_batch_engine_by_engine() -> None:
    model = build_model(spec_from_dict(twin()))
    batch = engine_batch(model, 3, crank_radius=[0.03, 0.04, 0.1], speed=[100.0, 200.0, 300.0])
    f, m = round_off(batch)
    assert f.shape == m.shape == (3,)
    for k in range(3):
        one_f, one_m = round_off(batch.model(k))
        assert f[k] == pytest.approx(one_f, rel=1e-15)
        assert m[k] == pytest.approx(one_m, rel=1e-15)
    # the third engine's radius exceeds the extent: its length is the radius
    assert engine_scales(batch)[1].tolist() == pytest.approx([0.09, 0.09, 0.1])


def test_below_round_off_is_exactly_zero() -> None:
    values = np.array([1e-9, -2e-9, 3e-9 + 1j, 0.0])
    out = below_round_off(values, 2e-9)
    assert out.tolist() == [0.0, 0.0, 3e-9 + 1j, 0.0]
    assert below_round_off([1.0, 2.0], np.array([1.5, 1.5])).tolist() == [0.0, 2.0]
