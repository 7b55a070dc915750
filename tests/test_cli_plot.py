"""CLI: ``crankbalance plot`` and ``crankbalance report``."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from .conftest import EXAMPLES, run_cli

pytest.importorskip("plotly", reason="plotly is in the web/test extras")

HAS_CHROMIUM = bool(shutil.which("chromium") or Path("/usr/bin/chromium").exists())
needs_chromium = pytest.mark.skipif(
    not HAS_CHROMIUM, reason="static images need Chromium (apt package chromium)"
)


@pytest.mark.parametrize("kind", ["orders", "curves", "polar", "crank", "residuals", "single"])
def test_plot_html_every_kind(
    kind: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / f"{kind}.html"
    code, _, err = run_cli(
        ["plot", kind, str(EXAMPLES / "paper_inline3.toml"), "-o", str(out)], capsys
    )
    assert code == 0, err
    text = out.read_text()
    assert "Plotly.newPlot" in text and "Inline-3" in text


@needs_chromium
def test_plot_png_and_svg(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    png = tmp_path / "o.png"
    code, _, err = run_cli(
        ["plot", "orders", "inline4", "-o", str(png), "--width", "400", "--height", "300"], capsys
    )
    assert code == 0, err
    data = png.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert int.from_bytes(data[16:20], "big") == 400
    svg = tmp_path / "p.svg"
    code, _, err = run_cli(["plot", "polar", "inline4", "--order", "2", "-o", str(svg)], capsys)
    assert code == 0, err
    assert svg.read_bytes().lstrip().startswith(b"<svg")


@pytest.mark.parametrize(
    "args, message",
    [
        (["plot", "polar", "inline4", "--order", "12", "-o", "x.html"], "order"),
        (["plot", "polar", "inline4", "--order", "two", "-o", "x.html"], "order"),
        (["plot", "orders", "inline4", "-o", "x.gif"], "--output"),
        (["plot", "orders", "no-such-engine", "-o", "x.html"], "engine"),
        (["plot", "single", "inline4", "--cylinder", "9", "-o", "x.html"], "--cylinder"),
        (["report", "inline4", "-o", "x.docx"], "output"),
        (["report", "inline4", "-o", "x.html", "--balance-factor", "3"], "--balance-factor"),
        (["report", "inline4", "-o", "x.html", "--angle", "thirty"], "--angle"),
        (["report", "inline4", "-o", "x.pdf", "--chromium", "/no/such/chromium"], "chromium"),
        # unwritable outputs, unknown kinds and options that the figure would ignore
        (
            ["plot", "orders", "inline4", "-o", "missing/x.html"],
            "error: --output = 'missing/x.html'",
        ),
        (["plot", "orders", "inline4", "-o", "."], "error: --output"),
        (["report", "inline4", "-o", "missing/r.html"], "error: --output = 'missing/r.html'"),
        (["plot", "bars", "inline4", "-o", "x.html"], "error: KIND = 'bars'"),
        (["plot", "polar", "inline4", "--order", "0", "-o", "x.html"], "error: --order"),
        (["plot", "orders", "inline4", "--order", "2", "-o", "x.html"], "error: --order"),
        (["plot", "residuals", "inline4", "--no-balance", "-o", "x.html"], "error: --balance"),
        (["plot", "curves", "inline4", "--cylinder", "2", "-o", "x.html"], "error: --cylinder"),
        (
            ["plot", "polar", "inline4", "--balance-factor", "0.3", "-o", "x.html"],
            "error: --balance-factor",
        ),
        (["plot", "orders", "inline4", "--width", "400", "-o", "x.html"], "error: --width"),
    ],
)
def test_bad_input_exits_2(
    args: list[str],
    message: str,
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli(args, capsys)
    assert code == 2, err
    assert message in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1, f"one error line, got {err!r}"
    assert not any(tmp_path.iterdir()), "nothing written on bad input"


def test_report_html_cli(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from crankbalance.studies.engine import balance_engine

    out = tmp_path / "r.html"
    code, _, err = run_cli(
        ["report", "inline4", "-o", str(out), "--angle", "optimal", "--balance-factor", "0.5"],
        capsys,
    )
    assert code == 0, err
    mass = balance_engine("inline4", angle="optimal", balance_factor=0.5).to_dict()[
        "counterweight"
    ]["mass_kg"]
    assert f"<td>{mass:.5g}</td>" in out.read_text()


def test_report_with_one_order(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """--orders 1 is allowed: the balancing still reports orders 1 and 2 (was a KeyError)."""
    from crankbalance.studies.engine import analyze

    out = tmp_path / "r.html"
    code, _, err = run_cli(["report", "inline3", "-o", str(out), "--orders", "1"], capsys)
    assert code == 0, err
    moment = analyze("inline3", orders=1).to_dict()["free_moments"][0]["amplitude_Nm"]
    assert f"<td>{moment:.5g}</td>" in out.read_text()
