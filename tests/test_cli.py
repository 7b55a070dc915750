"""The command line: analyze (table, JSON contract, CSV) and presets."""

from __future__ import annotations

import csv
import io
import json
import math

import pytest

from .conftest import EXAMPLES, run_cli


def test_analyze_json_contract(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run_cli(
        ["analyze", str(EXAMPLES / "paper_inline3.toml"), "--format", "json"], capsys
    )
    assert code == 0, err
    data = json.loads(out)
    assert data["schema"] == "crankbalance.analysis/4"
    assert [f["order"] for f in data["free_forces"]] == list(range(1, 9))
    for row in data["free_forces"]:
        assert {"order", "amplitude_N", "forward_N", "backward_N"} <= set(row)
    for row in data["free_moments"]:
        assert {"order", "amplitude_Nm", "forward_Nm", "backward_Nm"} <= set(row)
    assert {"force_N", "moment_Nm"} <= set(data["rotating"])
    # inline-3 of the paper, first-order model: M1 = sqrt(3) a m_alt r w^2 (textbook)
    w = 2000 * math.pi / 30
    p = 0.94 * 0.04 * w**2
    assert data["free_moments"][0]["amplitude_Nm"] == pytest.approx(math.sqrt(3) * 0.09 * p)
    assert data["free_moments"][1]["amplitude_Nm"] == pytest.approx(
        math.sqrt(3) * 0.09 * p * 0.04 / 0.135
    )
    assert data["masses"]["rotating_kg"] == pytest.approx([2.15] * 3), "docs/references.md: m_rot"
    assert data["masses"]["reciprocating_kg"] == pytest.approx([0.94] * 3), (
        "docs/references.md: m_alt"
    )


def test_analyze_table(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_cli(["analyze", "inline4", "--orders", "4"], capsys)
    assert code == 0
    assert "order" in out and "force N" in out
    lines = out.splitlines()
    start = next(k for k, line in enumerate(lines) if line.startswith("-----")) + 1
    assert [line.split()[0] for line in lines[start : start + 4]] == ["1", "2", "3", "4"]


def test_analyze_csv_curves(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_cli(["analyze", "single", "--format", "csv", "--orders", "2"], capsys)
    assert code == 0
    rows = list(csv.DictReader(io.StringIO(out)))
    assert len(rows) == 720
    # a single cylinder at crank angle 0 (TDC): the total force is along +z, no x part
    assert float(rows[0]["fx_total_N"]) == pytest.approx(0.0, abs=1e-6)
    assert float(rows[0]["fz_total_N"]) > 0


def test_presets_command(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run_cli(["presets", "--format", "json"], capsys)
    assert code == 0
    names = [p["name"] for p in json.loads(out)["presets"]]
    assert "v8-crossplane" in names and len(names) >= 20
