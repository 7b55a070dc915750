"""The 3-D crank frames every part and label, for every preset (issue 17 item 7): the
scene's axis ranges hold every point of every trace with room to spare, the box is drawn to
scale, the camera sees the whole box (a perspective projection of its corners, checked
against a closed form), and the tick labels stay few and away from the corners."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("plotly", reason="plotly is in the web/test extras")

from crankbalance.io.engine_file import list_presets  # noqa: E402
from crankbalance.output.figures.crank3d import (  # noqa: E402
    SCENE_FILL,
    SCENE_FOV,
    SCENE_MARGIN,
    SCENE_MIN_ASPECT,
    SCENE_TICK_EDGE,
    SCENE_TICKS,
    crank_3d,
    scene_box_fits,
)
from crankbalance.studies.engine import balance_engine  # noqa: E402

AXES = ("x", "y", "z")


def _points(fig) -> dict[str, np.ndarray]:  # type: ignore[no-untyped-def]
    """Every coordinate drawn, per scene axis (the None breaks between segments dropped)."""
    out = {}
    for key in AXES:
        values = [v for t in fig.data for v in (getattr(t, key) or ()) if v is not None]
        out[key] = np.asarray(values, dtype=float)
    return out


@pytest.mark.parametrize("preset", list_presets())
def test_every_part_inside_the_frame(preset: str) -> None:
    study = balance_engine(preset)
    fig = crank_3d(study.model, study)
    scene = fig.layout.scene
    points = _points(fig)
    largest = max(float(np.ptp(points[k])) for k in AXES)
    room = SCENE_MARGIN * largest
    lengths = []
    for key in AXES:
        axis = scene[f"{key}axis"]
        low, high = axis.range
        lengths.append(high - low)
        # every point inside, with the margin on both sides
        assert low <= points[key].min() - room * (1 - 1e-9), (preset, key)
        assert high >= points[key].max() + room * (1 - 1e-9), (preset, key)
        # the tick labels: inside, away from the corners, evenly spaced, few
        ticks = np.asarray(axis.tickvals, dtype=float)
        edge = SCENE_TICK_EDGE * (high - low)
        assert 1 <= len(ticks) <= SCENE_TICKS + 1, (preset, key, ticks)
        assert np.all(ticks >= low + edge * (1 - 1e-9)) and np.all(ticks <= high - edge), ticks
        if len(ticks) > 1:
            np.testing.assert_allclose(np.diff(ticks), np.diff(ticks)[0], rtol=1e-9)
    # to scale: the box's sides are the ranges' lengths; the shortest not too thin
    ratios = [scene.aspectratio[k] for k in AXES]
    np.testing.assert_allclose(ratios, np.array(lengths) / max(lengths), rtol=1e-12)
    assert scene.aspectmode == "manual" and min(ratios) >= SCENE_MIN_ASPECT - 1e-12
    # the camera sees every corner of the box, with room
    eye = [scene.camera.eye[k] for k in AXES]
    assert scene_box_fits(ratios, eye), (preset, eye)
    assert math.dist(eye, (0, 0, 0)) > math.hypot(*ratios) / 2


def test_box_fit_against_the_closed_form() -> None:
    """A unit cube seen along x from distance D: its nearest face's corners sit 1/2 aside
    and 1/2 up at depth D - 1/2, so it fits the view (fill f, half-angle a) exactly when
    (1/2) / (D - 1/2) <= f tan(a) (the height binds: the view is wider than high)."""
    t = SCENE_FILL * math.tan(SCENE_FOV / 2)
    least = 0.5 + 0.5 / t
    assert scene_box_fits((1, 1, 1), (least * (1 + 1e-9), 0, 0))
    assert not scene_box_fits((1, 1, 1), (least * (1 - 1e-6), 0, 0))
    assert not scene_box_fits((1, 1, 1), (0.3, 0, 0))  # inside the box


def test_camera_is_fitted_not_fixed() -> None:
    """A long crank (V12) and a tall one (radial 9) get the nearest camera that fits."""
    for preset in ("v12-60", "radial9"):
        study = balance_engine(preset)
        scene = crank_3d(study.model, study).layout.scene
        ratios = [scene.aspectratio[k] for k in AXES]
        eye = np.array([scene.camera.eye[k] for k in AXES])
        assert scene_box_fits(ratios, eye)
        assert not scene_box_fits(ratios, eye * 0.97)
