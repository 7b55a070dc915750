"""Web app, the text of the Results, Engine and Single cylinder tabs as Markdown (issue 28
screenshot review): the "What is left" list, a crank balanced as a whole, f_b."""

from __future__ import annotations

import pytest
from markdown_it import MarkdownIt

from crankbalance.web.project import Project
from crankbalance.web.tab_results import balance_lines, balance_rows, left_lines


@pytest.fixture(scope="module")
def inline4() -> dict:
    computed = Project.from_preset("inline4").compute()
    assert computed is not None
    return computed.study.to_dict()


def test_what_is_left_is_a_markdown_list(inline4: dict) -> None:
    """The bold heading, then a list (one item per free component), then the notes, each
    a paragraph of its own (not the last item's continuation)."""
    tokens = MarkdownIt().parse("\n".join(left_lines(inline4)))
    items = [t for t in tokens if t.type == "list_item_open"]
    assert len(items) == len(inline4["remaining"]) > 0
    last_item = max(i for i, t in enumerate(tokens) if t.type == "list_item_close")
    assert any(t.type == "inline" and "no counterweights" in t.content for t in tokens[last_item:])


def test_a_crank_balanced_as_a_whole_lists_no_0_g_counterweights(inline4: dict) -> None:
    """The inline-4 needs no counterweights: one row "none needed", not eight 0 g rows, and
    the key line gives the balancing's reason."""
    rows = balance_rows(inline4)
    assert [r["mass"] for r in rows] == ["none needed"]
    assert not any("0 g" in line for line in balance_lines(inline4))
    assert (
        "**Crank counterweights:** none needed (the rotating masses leave no free first-order "
        "force or couple on the whole crank)" in balance_lines(inline4)
    )


def test_counterweights_with_mass_keep_their_rows(inline4: dict) -> None:
    b = {**inline4, "notes": []}
    b["counterweight"] = {
        **b["counterweight"],
        "total_mass_kg": 1.0,
        "webs": [{**w, "mass_kg": 0.125} for w in b["counterweight"]["webs"]],
    }
    assert [r["mass"] for r in balance_rows(b)] == ["125 g"] * 8
    assert "**Crank counterweights:** 8, 1000 g in all (pattern)" in balance_lines(b)


def markdown_html(content: str) -> str:
    """``content`` as ``ui.markdown`` shows it (NiceGUI's own converter and extras)."""
    from nicegui import ui
    from nicegui.elements.markdown import prepare_content

    return prepare_content(content, " ".join(ui.markdown.default_extras))


def test_f_b_is_not_italics_in_the_single_cylinder_cards() -> None:
    """Two f_b in one line of Markdown made the text between them italic (and ate the
    underscores): the web writes the balance factor's symbol escaped."""
    from types import SimpleNamespace

    from crankbalance.web.tab_single import rebalance_summary, single_summary

    study = SimpleNamespace(
        primary_force=10550.0,
        balance_factor=0.5,
        peak_resultant=8405.3,
        in_line_amplitude=8405.3,
        transverse_amplitude=5275.0,
        optimum_balance_factor=0.61,
        optimum_peak_resultant=8000.0,
    )
    reb = SimpleNamespace(
        unbalance=1e-3,
        achieved_balance_factor=0.5,
        residual=1e-6,
        passed=True,
        status="optimal",
        bob_weight=1.2,
    )
    for html in (markdown_html(single_summary(study)), markdown_html(rebalance_summary(reb))):
        assert "<em>" not in html and "f_b" in html
    assert markdown_html(single_summary(study)).count("f_b") == 2


def test_what_is_left_names_the_balance_factor_as_each_surface_does() -> None:
    """Review finding 18: the crossplane V8 at balance factor 0 keeps its forward primary
    couple; the next step names the setting as the reader's surface does: the JSON and the
    command line the option, the web the Engine form's field (one text, the name passed
    in)."""
    from crankbalance.web.form import label_of

    study = Project.from_preset("v8-crossplane").compute().study
    label = label_of("counterweights.balance_factor")
    assert label == "Balance factor"
    cli = study.to_dict()["remaining"][0]["next_step"]
    web = study.to_dict(factor_name=label)["remaining"][0]["next_step"]
    assert "(--balance-factor 0.5; now 0)" in cli
    assert "(Balance factor 0.5; now 0)" in web and "--" not in web
    assert web.replace(label, "--balance-factor") == cli  # the same text otherwise


def test_crank_loads_summary_names_the_form_field() -> None:
    """The Crank loads tab's summary says its next step in the web's words (the tab calls
    SweepStudy.summary with the form's label); the JSON keeps the option."""
    from crankbalance.studies.balance_loads import bearing_sweep
    from crankbalance.web.form import label_of

    study = bearing_sweep("single", {"patterns": ["all"], "balance_factors": [0.0]})
    web = " ".join(study.summary(label_of("counterweights.balance_factor")).text)
    assert "(Balance factor 0.5; now 0)" in web and "--balance-factor" not in web
    assert "(--balance-factor 0.5; now 0)" in " ".join(study.to_dict()["summary"]["text"])


def test_single_cylinder_states_the_engines_balance_factor() -> None:
    """Review finding 29: the tab's study (0.5 by default) and the engine's balancing (its
    own factor, the Results tab's) are named apart, or said to be the same."""
    from crankbalance.web.tab_single import engine_factor_note

    apart = engine_factor_note(0.0, 0.5)
    assert "This study is at f\\_b = 0.5" in apart and "balanced at f\\_b = 0 " in apart
    assert "two different balancings" in apart and "f_b = 0.5" in markdown_html(apart)
    same = engine_factor_note(0.5, 0.5)
    assert same.startswith("This study's f\\_b = 0.5 is the engine's own")
    assert "no crank counterweights" in engine_factor_note(None, 0.5)
