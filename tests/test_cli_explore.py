"""``crankbalance explore``: the command end to end, its outputs and its errors."""

from __future__ import annotations

import csv
import io
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from crankbalance.io.parquet import read_parquet
from crankbalance.physics.explore import orders

from .conftest import run_cli

ZERO_1_2 = "F1 == 0 and M1 == 0 and F2 == 0 and M2 == 0"


def test_inline6_without_free_forces_or_moments_of_orders_1_2(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    out = tmp_path / "six.parquet"
    args = ["explore", "--layout", "inline", "--cylinders", "6", "--filter", ZERO_1_2]
    code, text, err = run_cli([*args, "--format", "json", "--output", str(out)], capsys)
    assert code == 0, err
    data = json.loads(text)
    assert data["schema"] == "crankbalance.explore/1"
    problem = orders.problem("inline", 6, 4)
    counts = data["counts"]
    assert counts["orders"] == orders.count(problem) == 120
    assert counts["distinct_engines"] == orders.chunk(problem, 0, 120).size
    assert 0 < counts["kept_by_filter"] < counts["distinct_engines"]
    assert data["torsion_assumption"]
    # every row kept has no free force or moment of orders 1 and 2, and the usual
    # 1-5-3-6-2-4 is one of them (as itself or an equivalent order)
    for row in data["top"] + data["pareto"]:
        assert row["F1_N"] == row["M1_Nm"] == row["F2_N"] == row["M2_Nm"] == 0
    kept = read_parquet(out)
    assert kept["index"].size == counts["kept_by_filter"]
    usual = {tuple(o) for o in orders.equivalent_orders(problem, (1, 5, 3, 6, 2, 4))}
    assert usual & {tuple(int(c) for c in o) for o in kept["firing_order"]}
    assert (kept["F2_N"] == 0).all() and (kept["M1_Nm"] == 0).all()


def test_table_and_csv_agree(capsys: pytest.CaptureFixture[str]) -> None:
    args = ["explore", "--cylinders", "4", "--top", "3", "--objectives", "F2,M2"]
    code, table, err = run_cli(args, capsys)
    assert code == 0, err
    assert "firing orders" in table and "Assumption:" in table
    code, text, err = run_cli([*args, "--format", "csv"], capsys)
    assert code == 0, err
    rows = list(csv.DictReader(io.StringIO(text)))
    assert 1 <= len(rows) <= 3
    key = np.array([float(r["residual_M_Nm"]) for r in rows])
    assert (np.diff(key) >= 0).all()  # the top-N by the default key, best first
    for r in rows:
        assert r["firing_order"] in table


@pytest.mark.parametrize(
    ("args", "named"),
    [
        (["--strokes", "3"], "--strokes"),
        (["--cylinders", "0"], "--cylinders"),
        (["--layout", "vee", "--cylinders", "8"], "--bank-angle"),
        (["--objectives", "F1,nonsense"], "--objectives"),
        (["--top-key", "nonsense"], "--top-key"),
        (["--filter", "F1 <"], "--filter"),
        (["--filter", "__import__('os')"], "--filter"),
        (["--mode-shape", "wavy"], "--mode-shape"),
        (["--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], "--workers"),
        (["--output", "/no/such/folder/x.parquet"], "--output"),
        (["--output", "."], "--output"),
        (["--engine", "inline4", "--cylinders", "6"], "--engine"),
        (["--scheduler", "tcp://"], "--scheduler"),
    ],
)
def test_bad_options_are_one_line(
    args: list[str], named: str, capsys: pytest.CaptureFixture[str]
) -> None:
    code, out, err = run_cli(["explore", *args], capsys)
    assert code == 2 and out == ""
    assert err.startswith("error: ") and named in err and err.count("\n") == 1


def test_an_in_process_run_loads_neither_dask_nor_pyarrow() -> None:
    probe = (
        "import sys\n"
        "from crankbalance.cli import main\n"
        "main(['explore', '--cylinders', '4', '--format', 'json'])\n"
        "loaded = {'dask', 'distributed', 'pyarrow'} & {m.split('.')[0] for m in sys.modules}\n"
        "print(sorted(loaded))\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", probe], capture_output=True, text=True, check=True
    ).stdout
    assert out.rstrip().endswith("[]")


VEE8 = ["explore", "--layout", "vee", "--cylinders", "8", "--bank-angle", "90 deg"]


@pytest.mark.parametrize(
    ("options", "mirror", "reversal"),
    [([], True, False), (["--no-mirror"], False, False), (["--reversal"], True, True)],
)
def test_what_counts_as_one_engine(
    capsys: pytest.CaptureFixture[str], options: list[str], mirror: bool, reversal: bool
) -> None:
    """--no-mirror makes the mirror image a distinct engine, --reversal an engine run
    backwards the same: the counts of the Python API's problem (V8: 40, 72, 26)."""
    code, text, err = run_cli([*VEE8, *options, "--format", "json"], capsys)
    assert code == 0, err
    data = json.loads(text)
    problem = orders.problem("vee", 8, 4, np.pi / 2, mirror=mirror, reversal=reversal)
    expected = orders.chunk(problem, 0, orders.count(problem)).size
    assert data["counts"]["distinct_engines"] == expected
    assert data["problem"]["mirror"] is mirror and data["problem"]["reversal"] is reversal
    assert expected == {(True, False): 40, (False, False): 72, (True, True): 26}[mirror, reversal]


def test_a_fixed_crank(capsys: pytest.CaptureFixture[str]) -> None:
    """The flat inline-4's crank allows two firing orders, 1-2-4-3 and 1-3-4-2; the table
    says the crank is fixed; a crank of the wrong length is one line naming the option."""
    args = ["explore", "--cylinders", "4", "--fixed-crank", "0,180,180,0 deg"]
    code, text, err = run_cli([*args, "--format", "json"], capsys)
    assert code == 0, err
    data = json.loads(text)
    assert sorted(r["firing_order"] for r in data["top"]) == ["1-2-4-3", "1-3-4-2"]
    assert data["problem"]["fixed_crank"] == pytest.approx([0, np.pi, np.pi, 0])
    code, table, err = run_cli(args, capsys)
    assert code == 0, err
    assert "fixed at 0, 180, 180, 0 deg" in table.splitlines()[0]
    code, _, err = run_cli(["explore", "--cylinders", "4", "--fixed-crank", "0,180 deg"], capsys)
    assert code == 2
    assert err.strip() == "error: --fixed-crank = '0,180 deg': 4 finite angles, one per throw"


def test_each_engine_lists_the_orders_it_stands_for(capsys: pytest.CaptureFixture[str]) -> None:
    """--list-orders: every row names its equivalent orders (the API's equivalent_orders),
    as many as its equivalents, its own first; in the table and the CSV too."""
    args = [*VEE8, "--list-orders", "--top", "40"]
    code, text, err = run_cli([*args, "--format", "json"], capsys)
    assert code == 0, err
    data = json.loads(text)
    problem = orders.problem("vee", 8, 4, np.pi / 2)
    rows = data["top"] + data["pareto"]
    assert len(data["top"]) == 40 and any(r["equivalents"] > 1 for r in rows)
    for row in rows:
        order = tuple(int(c) for c in row["firing_order"].split("-"))
        listed = ["-".join(map(str, o)) for o in orders.equivalent_orders(problem, order)]
        assert row["orders"] == listed and len(listed) == row["equivalents"]
        assert listed[0] == row["firing_order"]
    code, table, err = run_cli(args, capsys)
    assert code == 0, err
    assert "stands for" in table
    code, text, err = run_cli([*args, "--format", "csv"], capsys)
    assert code == 0, err
    first = next(csv.DictReader(io.StringIO(text)))
    assert first["orders"].split(" ") == data["top"][0]["orders"]
    code, text, err = run_cli([*VEE8, "--format", "json"], capsys)
    assert "orders" not in json.loads(text)["top"][0]  # not asked: not listed


def test_the_inline5_front_keeps_engines_equal_to_round_off(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """Issue 27: every one of the inline-5's 12 engines is on its (M1, M2) front, the pairs
    whose figures differ by round-off among them (exact dominance kept 9)."""
    args = ["explore", "--cylinders", "5", "--objectives", "M1,M2", "--target", "none"]
    code, text, err = run_cli([*args, "--format", "json"], capsys)
    assert code == 0, err
    data = json.loads(text)
    assert data["counts"]["distinct_engines"] == data["counts"]["pareto"] == 12
