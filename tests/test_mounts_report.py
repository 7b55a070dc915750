"""Issue 31 item 6, the report: an engine file with a [powertrain] gets a section "The
powertrain on its mounts" (modes, torque-roll axis, crossings, largest mount force per
order) and its figure, under the forces the report's balancing leaves."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from crankbalance.output.report import build_report, report_figures, report_html
from crankbalance.schema.settings import MountsOptions
from crankbalance.studies.mounts import mounts

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "examples" / "mounts_inline4_car.toml"


def _data(page: str) -> dict:
    found = re.search(
        r'<script type="application/json" id="crankbalance-data">(.*?)</script>', page, re.S
    )
    assert found is not None
    return json.loads(found.group(1))


def test_a_powertrain_gives_the_report_its_mounts_section_and_figure() -> None:
    report = build_report(CAR, orders=4)
    assert report.mounts is not None
    page = report_html(report, figures=False)
    assert "<h2>The powertrain on its mounts</h2>" in page
    assert 'class="mount-modes"' in page and 'class="mount-forces"' in page
    assert "torque-roll axis" in page
    assert "mounts" in [fig_id for fig_id, _, _ in report_figures(report)]
    data = _data(page)["mounts"]
    assert data["schema"] == "crankbalance.mounts/1" and len(data["modes"]) == 6
    # an inline-4 is balanced for its rotating masses as a whole: the balancing leaves the
    # engine's reciprocating forces, which the mount study applies alone by default; the
    # report's section (through the balancing solver) gives the same mount forces
    plain = mounts(CAR, MountsOptions.parse({})).to_dict()
    for mine, theirs in zip(data["orders"], plain["orders"], strict=True):
        assert mine["order"] == theirs["order"]
        assert mine["largest"]["force_N"] == pytest.approx(
            theirs["largest"]["force_N"], rel=1e-6, abs=1e-6
        )
    for mine, theirs in zip(data["modes"], plain["modes"], strict=True):
        assert mine["frequency_Hz"] == pytest.approx(theirs["frequency_Hz"], rel=1e-12)


def test_an_engine_without_a_powertrain_has_no_mounts_section() -> None:
    report = build_report("inline4", orders=2)
    assert report.mounts is None
    page = report_html(report, figures=False)
    assert "The powertrain on its mounts" not in page
    assert "mounts" not in _data(page)
