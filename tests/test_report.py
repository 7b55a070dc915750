"""Reports: the HTML and the PDF show the API's numbers; HTML is self-contained."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

pytest.importorskip("plotly", reason="plotly is in the web/test extras")

from crankbalance.errors import InputError  # noqa: E402
from crankbalance.output.report import build_report, report_html, write_report  # noqa: E402
from crankbalance.studies.engine import analyze, balance_engine  # noqa: E402

HAS_CHROMIUM = bool(shutil.which("chromium") or Path("/usr/bin/chromium").exists())


def g5(value: float) -> str:
    """How the report prints a number (5 significant figures), written out independently."""
    return "0" if value == 0 else f"{value:.5g}"


@pytest.fixture(scope="module")
def paper_html() -> str:
    return report_html(build_report("paper-inline3"))


def test_html_shows_balance_numbers(paper_html: str) -> None:
    data = balance_engine("paper-inline3").to_dict()
    cw = data["counterweight"]
    assert f"<td>{g5(cw['mass_kg'])}</td>" in paper_html
    assert g5(cw["mass_kg"]) == "1.2413", "Appl. Sci. 2021, Table 2: m_c = 1.2413 kg"
    assert f"<td>{g5(data['primary_shafts']['mass_kg'])}</td>" in paper_html
    assert f"<td>{g5(data['secondary_shafts']['mass_kg'])}</td>" in paper_html
    for web in cw["webs"]:
        assert f"<td>{g5(web['position_m'] * 1e3)}</td>" in paper_html
    for comp in data["components"]:
        assert f"<td>{comp['component']}</td>" in paper_html
    moments = analyze("paper-inline3").to_dict()["free_moments"]
    for row in moments[:2]:
        assert f"<td>{g5(row['amplitude_Nm'])}</td>" in paper_html
    # the sixth component (issue 27): the roll moment of each order
    assert "roll [N·m]" in paper_html
    rolls = [r for r in analyze("paper-inline3").to_dict()["roll_moments"] if r["amplitude_Nm"]]
    assert rolls and all(f"<td>{g5(r['amplitude_Nm'])}</td>" in paper_html for r in rolls)
    assert "first-order" in paper_html and "[counterweights]" in paper_html  # settings used


def test_html_embeds_the_api_json(paper_html: str) -> None:
    match = re.search(
        r'<script type="application/json" id="crankbalance-data">(.*?)</script>', paper_html, re.S
    )
    assert match
    data = json.loads(match.group(1))
    assert data["schema"] == "crankbalance.report/4"
    assert data["balance"] == json.loads(json.dumps(balance_engine("paper-inline3").to_dict()))
    assert data["analysis"] == json.loads(json.dumps(analyze("paper-inline3").to_dict()))
    assert data["settings"]["counterweights"]["cg_radius"] == pytest.approx(0.03)


def test_html_is_self_contained(paper_html: str) -> None:
    assert not re.search(r"<script[^>]*\ssrc=", paper_html), "plotly.js must be inlined"
    assert not re.search(r"<link[^>]*href=\"?http", paper_html)
    assert paper_html.count("Plotly.newPlot") >= 6  # interactive figures
    # plotly.js included once, not once per figure
    assert paper_html.count("define&&define.amd") <= 2


def test_overrides_reach_the_report() -> None:
    r = build_report("inline3", balance_factor=0.5)
    assert r.settings["counterweights"]["balance_factor"] == 0.5
    html = report_html(r, figures=False)
    mass = balance_engine("inline3", balance_factor=0.5).to_dict()["counterweight"]["mass_kg"]
    assert f"<td>{g5(mass)}</td>" in html
    assert mass > balance_engine("inline3").to_dict()["counterweight"]["mass_kg"]


def test_write_report_html_and_bad_suffix(tmp_path: Path) -> None:
    out = write_report("inline3", tmp_path / "r.html")
    assert out.read_text().lstrip().startswith("<!DOCTYPE html>")
    with pytest.raises(InputError, match="output"):
        write_report("inline3", tmp_path / "r.docx")
    assert not (tmp_path / "r.docx").exists()


@pytest.mark.skipif(
    not HAS_CHROMIUM, reason="printing the PDF needs Chromium (apt package chromium)"
)
def test_pdf_has_the_numbers(tmp_path: Path) -> None:
    out = write_report("paper-inline3", tmp_path / "r.pdf")
    pdf = out.read_bytes()
    assert pdf.startswith(b"%PDF")
    if not shutil.which("pdftotext"):
        pytest.skip("pdftotext (apt package poppler-utils) is needed to read the PDF text")
    text = subprocess.run(
        ["pdftotext", "-layout", str(out), "-"], capture_output=True, text=True, check=True
    ).stdout
    data = balance_engine("paper-inline3").to_dict()
    assert g5(data["counterweight"]["mass_kg"]) in text, "Appl. Sci. 2021, Table 2: m_c = 1.2413 kg"
    assert g5(data["primary_shafts"]["mass_kg"]) in text, (
        "Appl. Sci. 2021, Table 2: m_c1 = 0.4884 kg"
    )
    assert "Residuals" in text and "Figures" in text
    # the figures are printed as images (static SVG), so their titles are in the text too
    assert "rotating-vector" in text.lower() or "Rotating-vector" in text


def test_pdf_with_missing_chromium(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="chromium"):
        write_report("inline3", tmp_path / "r.pdf", chromium=str(tmp_path / "no-browser"))
    assert not (tmp_path / "r.pdf").exists()
