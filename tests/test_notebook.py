"""Results at home in a notebook (issue 29): the public API as ``dir()`` shows it, every
study result's short ``repr`` and HTML display (tables with units, the key verdicts), the
figures of :func:`crankbalance.plot`, pint quantities where a number with a unit is, and
the round-off shown as 0 as the command line prints it."""

from __future__ import annotations

import inspect
import re
import sys

import pytest

import crankbalance
from crankbalance.results import ResultMixin, key_label, summarize
from crankbalance.studies.registry import STUDIES


def test_dir_shows_the_public_api() -> None:
    names = dir(crankbalance)
    assert "analyze" in names and "plot" in names and "run" in names
    assert "Any" not in names and "annotations" not in names
    for name in crankbalance.__all__:
        assert callable(getattr(crankbalance, name)), name


def _result_classes() -> dict[str, type]:
    found = {}
    for name, entry in STUDIES.items():
        function = entry.load()
        annotation = inspect.signature(function).return_annotation
        found[name] = getattr(sys.modules[function.__module__], annotation)
    return found


@pytest.mark.parametrize("study", sorted(STUDIES))
def test_every_study_result_displays_itself(study: str) -> None:
    """Every result of the registry's studies takes the one display of ResultMixin (its
    dataclass made with repr=False, so that the 4 KB dump of fields is gone)."""
    cls = _result_classes()[study]
    assert issubclass(cls, ResultMixin), cls
    assert cls.__repr__ is ResultMixin.__repr__, f"{cls.__name__} has a repr of its own"
    assert cls._repr_html_ is ResultMixin._repr_html_


def test_a_key_names_its_unit() -> None:
    assert key_label("amplitude_N") == ("amplitude [N]", "force")
    assert key_label("amplitude_Nm") == ("amplitude [N·m]", "moment")
    assert key_label("inertia_two_mass_kg_m2") == ("inertia two mass [kg·m²]", "inertia")
    assert key_label("speed_rad_s") == ("speed [rpm]", "speed")
    assert key_label("crank_radius_m") == ("crank radius [mm]", "length")
    assert key_label("cylinders") == ("cylinders", "")


def test_a_summary_shows_si_values_in_display_units() -> None:
    summary = summarize(
        "T",
        {
            "schema": "x/1",
            "speed_rad_s": 314.1592653589793,
            "rows": [{"order": 1, "amplitude_N": 1e-13 * 0}, {"order": 2, "amplitude_N": 5.0}],
            "notes": ["a note"],
        },
    )
    assert ("speed [rpm]", "3000") in summary.values
    assert summary.verdicts == ("notes: a note",)
    (table,) = summary.tables
    assert table.header == ("order", "amplitude [N]")
    assert table.rows == (("1", "0"), ("2", "5"))


def _display(obj: object) -> dict[str, str]:
    """What a notebook shows of ``obj``: its text and, when it has one, its HTML (the hooks
    Jupyter's display calls)."""
    shown = {"text/plain": repr(obj)}
    html = getattr(obj, "_repr_html_", None)
    if html is not None:
        shown["text/html"] = html()
    return shown


def test_a_notebook_session() -> None:
    """An analysis, a balance study and a figure, as a notebook displays them."""
    analysis = crankbalance.analyze("inline4")
    shown = _display(analysis)
    text = shown["text/plain"]
    assert len(text.splitlines()) <= 8 and len(text) < 1000, text
    assert text.startswith("Analysis: Inline-4, flat crank")
    assert "free force 12804 N (order 2), free moment 0 N·m" in text
    assert "engine · speed [rpm] 6000" in text
    html = shown["text/html"]
    assert "<table>" in html and "<th>amplitude [N]</th>" in html
    assert "<th>amplitude [N·m]</th>" in html
    assert "12804" in html and "e-1" not in html  # round-off shown as 0, not 2.6e-12

    study = crankbalance.balance_engine("v8-crossplane")
    shown = _display(study)
    assert shown["text/plain"].startswith("BalanceStudy: V8 90 deg, crossplane crank")
    assert len(shown["text/plain"].splitlines()) <= 10
    assert "unbalanced: order4: force 489.9 N, moment 0 N·m" in shown["text/plain"]
    assert "<caption>components</caption>" in shown["text/html"]
    assert "<th>force after [N]</th>" in shown["text/html"]

    pio = pytest.importorskip("plotly.io")
    figures = crankbalance.plot(analysis)
    assert len(figures) == 5
    # what JupyterLab's renderer is given (plotly's renderer of the notebook's mimetype)
    bundle = pio.renderers["plotly_mimetype"].to_mimebundle(figures[0].to_dict())
    assert bundle["application/vnd.plotly.v1+json"]["data"], "a figure with no trace"
    assert len(crankbalance.plot(study)) == 2


def test_plot_of_a_result_without_figures_says_which_have_them() -> None:
    with pytest.raises(crankbalance.InputError, match="a study result with figures: Analysis"):
        crankbalance.plot(object())


def test_round_off_is_zero_in_the_result_as_in_the_cli() -> None:
    """``forces.force_amplitude[0]`` of an inline four was 2.58e-12 where the CLI prints 0:
    the result holds the forces of the one round-off rule (results.round_off)."""
    forces = crankbalance.analyze("inline4").forces
    assert forces.force_amplitude[0] == 0.0
    assert forces.moment_amplitude[1] == 0.0
    assert forces.force_amplitude[1] > 1e4


def test_pint_quantities_are_accepted_where_a_number_with_a_unit_is() -> None:
    pint = pytest.importorskip("pint")
    ureg = pint.UnitRegistry()  # the user's own registry, not crankbalance's
    from crankbalance.schema.settings import ToleranceOptions, parse_options

    with_pint = parse_options(
        ToleranceOptions, {"grade": "G6.3", "rotor_mass": ureg("12 kg"), "speed": ureg("6000 rpm")}
    )
    with_text = parse_options(
        ToleranceOptions, {"grade": "G6.3", "rotor_mass": "12 kg", "speed": "6000 RPM"}
    )
    assert with_pint == with_text
    values = {"grade": "G6.3", "rotor_mass": ureg("12 kg"), "speed": ureg("6000 rpm")}
    result = crankbalance.run("tolerance", None, values)
    assert re.search(r"permissible", repr(result))


def test_a_notebook_executed_by_jupyter() -> None:
    """The same session in a real kernel, when the documentation's notebook tools are
    installed (nbclient, ipykernel: the docs extra): the analysis and the balance study
    display as HTML tables with units, the figure as plotly's notebook output."""
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    pytest.importorskip("plotly")
    cells = [
        "import crankbalance\nanalysis = crankbalance.analyze('inline4')\nanalysis",
        "crankbalance.balance_engine('v8-crossplane')",
        "crankbalance.plot(analysis)[0]",
    ]
    notebook = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(c) for c in cells])
    nbclient.NotebookClient(notebook, timeout=600, kernel_name="python3").execute()
    shown = [cell.outputs[-1]["data"] for cell in notebook.cells]
    assert "<th>amplitude [N]</th>" in shown[0]["text/html"]
    assert "<caption>components</caption>" in shown[1]["text/html"]
    assert "application/vnd.plotly.v1+json" in shown[2] or "text/html" in shown[2]
