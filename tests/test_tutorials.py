"""The tutorials of the documentation site (``docs/tutorials/``, MyST text notebooks that the
site's build executes with myst-nb) run here in a real Jupyter kernel, in their own folder as
the build runs them, and what each computes is checked against the API called in this
process: a broken or stale tutorial fails the suite, not only the site's build.

A last cell, added to each notebook here, prints the tutorial's values as JSON. The kernel's
temporary folder (``TMPDIR``) is a fresh folder of the test's: a tutorial that leaves a
scratch file or folder behind (as ``tempfile.mkdtemp`` did in ``/tmp`` at every build) fails
its test."""

from __future__ import annotations

import json
import os
import re
from pathlib import Path
from typing import Any

import pytest

import crankbalance

from .conftest import ROOT

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")
pytest.importorskip("ipykernel")
myst_nb_read = pytest.importorskip("myst_nb.core.read")

TUTORIALS = ROOT / "docs" / "tutorials"
NAMES = ("first_engine", "crossplane_flatplane", "single_rebalance", "explorer_shop")
#: hang guard [s] of one cell (the build's is docs/conf.py's NOTEBOOK_GUARD)
CELL_GUARD = 600


def _execute(name: str, probe: str, scratch: Path) -> tuple[Any, dict[str, Any]]:
    """Run tutorial ``name`` with ``probe`` as its last cell, in a kernel whose temporary
    folder is the empty folder ``scratch``; its cells and the probe's JSON. Fails if the run
    leaves anything in ``scratch``."""
    text = (TUTORIALS / f"{name}.md").read_text(encoding="utf-8")
    notebook = myst_nb_read.read_myst_markdown_notebook(text)
    last = (
        "import json, tempfile\n"
        f"print(json.dumps({{'probe': {probe}, 'tmp': tempfile.gettempdir()}}))"
    )
    notebook.cells.append(nbformat.v4.new_code_cell(last))
    client = nbclient.NotebookClient(
        notebook,
        timeout=CELL_GUARD,
        kernel_name="python3",
        resources={"metadata": {"path": str(TUTORIALS)}},
    )
    client.execute(env={**os.environ, "TMPDIR": str(scratch)})
    (printed,) = [o for o in notebook.cells[-1].outputs if o.get("name") == "stdout"]
    got = json.loads(printed["text"])
    assert got["tmp"] == str(scratch), "the kernel's temporary folder is the test's"
    assert sorted(p.name for p in scratch.iterdir()) == [], f"{name} leaves files in TMPDIR"
    return notebook, got["probe"]


def _scratch(tmp_path: Path) -> Path:
    """An empty folder for a kernel's temporary files."""
    folder = tmp_path / "kernel-tmp"
    folder.mkdir()
    return folder


def _outputs(notebook: Any, kind: str) -> list[str]:
    """Every output of the code cells of ``kind``: "stdout" or a mime type."""
    found = []
    for cell in notebook.cells:
        for output in cell.get("outputs", ()):
            if kind == "stdout" and output.get("name") == "stdout":
                found.append(output["text"])
            elif kind in output.get("data", {}):
                found.append(output["data"][kind])
    return found


def test_every_tutorial_is_in_the_site() -> None:
    assert sorted(p.stem for p in TUTORIALS.glob("*.md")) == sorted(NAMES)
    index = (ROOT / "docs" / "index.md").read_text(encoding="utf-8")
    for name in NAMES:
        assert f"tutorials/{name}\n" in index, f"{name} is not in the toctree of docs/index.md"


def test_first_engine(tmp_path: Path) -> None:
    notebook, got = _execute(
        "first_engine",
        "{'file': ENGINE, 'force': list(forces.force_amplitude), "
        "'moment': list(forces.moment_amplitude), 'balance': balance, 'half': half, "
        "'figures': len(figures)}",
        _scratch(tmp_path),
    )
    engine_file = tmp_path / "triple.toml"  # the notebook's, removed with its scratch folder
    engine_file.write_text(got["file"], encoding="utf-8")
    analysis = crankbalance.analyze(engine_file)
    assert got["force"] == list(analysis.forces.force_amplitude)
    assert got["moment"] == list(analysis.forces.moment_amplitude)
    # what the text says of a 120 deg triple: no force of orders 1 and 2, couples of both
    assert got["force"][:2] == [0.0, 0.0] and min(got["moment"][:2]) > 100.0
    balance = crankbalance.balance_engine(engine_file).to_dict()
    assert got["balance"] == json.loads(json.dumps(balance))
    half = crankbalance.balance_engine(engine_file, balance_factor=0.5).to_dict()
    assert got["half"]["residual"]["order1_moment_Nm"] == pytest.approx(
        half["residual"]["order1_moment_Nm"], rel=1e-12
    )
    assert got["half"]["residual"]["order1_moment_Nm"] == pytest.approx(got["moment"][0] / 2)
    assert got["figures"] == len(crankbalance.plot(analysis))
    printed = "".join(_outputs(notebook, "stdout"))
    assert "crank_train.crank_radius = '26 kg'" in printed, "the mistake is named"
    html = _outputs(notebook, "text/html")
    assert any("<th>amplitude [N]</th>" in h for h in html), "the analysis displays its tables"
    assert len(_outputs(notebook, "application/vnd.plotly.v1+json")) == 2, "two figures shown"


def test_crossplane_against_flatplane(tmp_path: Path) -> None:
    notebook, got = _execute(
        "crossplane_flatplane",
        "{name: {'force': list(a.forces.force_amplitude), 'moment': "
        "list(a.forces.moment_amplitude)} for name, a in analyses.items()} | "
        "{'needs': needs}",
        _scratch(tmp_path),
    )
    for name, preset in (("crossplane", "v8-crossplane"), ("flat-plane", "v8-flatplane")):
        forces = crankbalance.analyze(preset).forces
        assert got[name]["force"] == list(forces.force_amplitude), name
        assert got[name]["moment"] == list(forces.moment_amplitude), name
    cross, flat = got["crossplane"], got["flat-plane"]
    assert cross["force"][:2] == [0.0, 0.0] and cross["moment"][0] > 4000.0
    assert flat["moment"][:2] == [0.0, 0.0] and flat["force"][0] == 0.0
    assert 20e3 < flat["force"][1] < 21e3, "about 20 kN at 5500 rpm, as the text says"

    from crankbalance.physics.balancing import ShaftOptions

    crossplane = crankbalance.balance_engine("v8-crossplane", balance_factor=0.5).to_dict()
    lanchester = ShaftOptions(arrangement="pair", cg_radius=0.030, length=0.200)
    flatplane = crankbalance.balance_engine("v8-flatplane", secondary=lanchester).to_dict()
    expected = json.loads(json.dumps({"crossplane": crossplane, "flat-plane": flatplane}))
    assert got["needs"] == expected
    for study in expected.values():
        assert set(study["residual"].values()) == {0.0}, "nothing left of orders 1 and 2"
    assert flatplane["counterweight"]["mass_kg"] == 0.0 and crossplane["secondary_shafts"] is None
    assert len(_outputs(notebook, "application/vnd.plotly.v1+json")) == 3


def test_single_rebalanced_after_a_lighter_piston(tmp_path: Path) -> None:
    notebook, got = _execute(
        "single_rebalance", "{'file': PARTS, 'stock': stock, 'light': light}", _scratch(tmp_path)
    )
    parts_file = tmp_path / "light_piston.toml"  # the notebook's, removed with its scratch
    parts_file.write_text(got["file"], encoding="utf-8")
    from crankbalance.physics.single_cylinder import balance_factor_from_mass_properties

    result = crankbalance.run("rebalance", None, {"parts": str(parts_file)}).to_dict()
    (case,) = result["cases"]
    assert got["stock"] == pytest.approx(case["original_balance_factor"], rel=1e-9)
    assert got["stock"] == pytest.approx(0.6379, abs=5e-5), "the factory's, Hoem and Røsholm"
    new = result["new"]
    light = balance_factor_from_mass_properties(
        2.02040, 0.00616, 0.0269, new["rotating_mass_kg"], new["reciprocating_mass_kg"]
    )
    assert got["light"] == pytest.approx(light, rel=1e-12)
    assert got["light"] > got["stock"] + 0.04, "the light piston raises the factor"
    assert case["passed"]
    assert case["achieved_balance_factor"] == pytest.approx(got["stock"], abs=1e-3)
    printed = "".join(_outputs(notebook, "stdout"))
    depth = case["iterations"][-1]["depth_m"] * 1e3
    assert f"grind {depth:.3f} mm deep in total" in printed
    assert f"with the light piston {light:.1%}" in printed
    assert len(_outputs(notebook, "application/vnd.plotly.v1+json")) == 1


def test_explorer_and_shop(tmp_path: Path) -> None:
    notebook, got = _execute(
        "explorer_shop",
        "{'top': [{k: row[k] for k in ('firing_order', *search.objectives)} for row in top], "
        "'counts': counts, 'ids': [list(i) for i in matching.ids], "
        "'spread': [matching.reciprocating_spread, matching.rotating_spread], "
        "'bob': [float(w) for w in bob.bob_weight]}",
        _scratch(tmp_path),
    )
    search = crankbalance.run(
        "explore", None, {"layout": "inline", "cylinders": 5, "strokes": 4, "top": 5}
    )
    expected = [
        {k: float(row[k]) if k != "firing_order" else row[k] for k in got["top"][0]}
        for row in search.top()
    ]
    assert got["top"] == expected
    assert got["counts"]["orders"] == search.counts()["orders"] == 24
    assert all(row["F1_N"] == 0.0 and row["F2_N"] == 0.0 for row in got["top"])

    parts = ROOT / "examples" / "v8_parts.csv"
    shop = crankbalance.run("shop-match", "v8-crossplane", {"parts": str(parts), "fraction": "50%"})
    matching = shop.result.matching
    assert matching.optimal, "the matching is proven optimal, so the notebook's is the same"
    assert got["ids"] == [list(ids) for ids in matching.ids]
    assert got["spread"] == [matching.reciprocating_spread, matching.rotating_spread]
    assert got["bob"] == [float(w) for w in shop.result.bob_weights.bob_weight]
    printed = "".join(_outputs(notebook, "stdout"))
    assert re.search(r"cylinder 8: P\d W\d G\d L\d R\d S\d", printed)
    assert len(_outputs(notebook, "application/vnd.plotly.v1+json")) == 1
