"""The engine form is derived from the engine file's schema: every field's label, hint,
choices and check are the schema's (nothing written twice in the web)."""

from __future__ import annotations

import pytest

from crankbalance.errors import InputError
from crankbalance.schema.core import default_text, parse_value
from crankbalance.schema.engine import CrankTrain, EngineSpec, ShaftSet
from crankbalance.web.form import FIELDS, NO_SHAFTS, form_message, schema_field


@pytest.mark.parametrize("f", FIELDS, ids=lambda f: f.key)
def test_every_field_is_described_by_the_schema(f) -> None:
    spec = schema_field(f.path)
    assert f.spec is spec
    assert f.hint == spec.hint
    if f.group in ("primary", "secondary"):  # one schema for both sets: named with its set
        assert f.label == f"{f.group.capitalize()} {spec.title[0].lower()}{spec.title[1:]}"
    else:
        assert f.label == spec.title
    if spec.kind == "choice":
        choices = {str(c) for c in spec.choices}
        assert set(f.options) - {NO_SHAFTS} == choices
        if spec.default is not None and not spec.required:
            assert f.options[0] in (str(spec.default), NO_SHAFTS)


def test_labels_and_hints_follow_the_schema() -> None:
    by_key = {f.key: f for f in FIELDS}
    assert by_key["rod_length"].label == CrankTrain.FIELDS["rod_length"].title == "Rod length"
    assert by_key["strokes"].options == ("4", "2")  # the schema's default first
    assert by_key["primary_arrangement"].options == (
        NO_SHAFTS,
        *ShaftSet.FIELDS["arrangement"].choices,
    )
    assert by_key["speed"].hint == EngineSpec.FIELDS["speed"].hint == "e.g. 2000 rpm"


@pytest.mark.parametrize(
    ("key", "text"),
    [
        ("crank_radius", "40"),
        ("crank_radius", "1 km"),
        ("cylinders", "65"),
        ("cylinders", "2.5"),
        ("cw_balance_factor", "3"),
        ("firing_order", "1, x, 3"),
        ("rod_positions", "1 mm, 12 parsecs"),
        ("cw_angle", "steep"),
        ("layout", "sideways"),
    ],
)
def test_the_check_is_the_schema_s_parse_of_a_text(key: str, text: str) -> None:
    """A field refuses a text exactly as the schema's parse of a typed text does, with the
    schema's words; the form's message names the field by its label."""
    f = next(f for f in FIELDS if f.key == key)
    with pytest.raises(InputError) as form:
        f.check(text)
    with pytest.raises(InputError) as schema:
        parse_value(f.spec, text, f.dotted)
    assert (form.value.field, form.value.allowed) == (schema.value.field, schema.value.allowed)
    assert form_message(form.value).startswith(f.label)


def test_a_good_text_gives_the_schema_s_value() -> None:
    by_key = {f.key: f for f in FIELDS}
    assert by_key["crank_radius"].check(" 40 mm ") == pytest.approx(0.04)
    assert by_key["firing_order"].check("1, 3, 2") == [1, 3, 2]
    assert by_key["strokes"].check("4") == 4
    assert by_key["cw_angle"].check("optimal") == "optimal"


def test_the_study_settings_start_at_the_schema_s_defaults() -> None:
    """Every study setting of the page starts at its schema's default (no edge decides a
    default: the page starts where the command line does), the optimiser's run and the
    Crank loads sweep included."""
    from crankbalance.schema.settings import (
        BearingOptions,
        BearingSweepOptions,
        CounterweightOptions,
        PerformanceOptions,
    )
    from crankbalance.web import tab_loads
    from crankbalance.web.project import DEFAULT_SETTINGS, STUDY_SETTINGS

    assert set(STUDY_SETTINGS) <= set(DEFAULT_SETTINGS)
    assert DEFAULT_SETTINGS["cw_density"] == default_text(CounterweightOptions.FIELDS["density"])
    assert DEFAULT_SETTINGS["pf_balance_factors"] == default_text(
        PerformanceOptions.FIELDS["balance_factors"]
    )
    for name in ("iterations", "population", "seed"):
        assert DEFAULT_SETTINGS[f"cw_{name}"] == default_text(CounterweightOptions.FIELDS[name])
    loads = {key: default for key, (_label, default, _hint) in tab_loads.SETTINGS.items()}
    assert loads["samples"] == default_text(BearingOptions.FIELDS["samples"])
    assert loads["balance_factors"] == default_text(BearingSweepOptions.FIELDS["balance_factors"])
    assert loads["patterns"] == "; ".join(BearingSweepOptions.FIELDS["patterns"].default)
    assert loads["gas"] == ("on" if BearingOptions.FIELDS["gas"].default else "off")


def test_the_study_tabs_own_settings_are_the_schema_s() -> None:
    """The Crank loads, Balance shop and Explorer tabs label their settings with the
    schema's titles and offer its choices; a default of their own is the page's choice."""
    from crankbalance.schema.settings import (
        BearingOptions,
        BearingSweepOptions,
        ExploreOptions,
        ShopOptions,
    )
    from crankbalance.web import tab_explore, tab_loads, tab_shop

    for tab, model in (
        (tab_loads, BearingOptions),
        (tab_shop, ShopOptions),
        (tab_explore, ExploreOptions),
    ):
        for key, (label, _default, hint) in tab.SETTINGS.items():
            # the shop tab's parts are pasted CSV text; the schema's parts is a file's name
            if key in model.FIELDS and key != "parts":
                assert label == model.FIELDS[key].title, key
                assert hint
    assert tab_loads.SETTINGS["crank_model"][0] == BearingSweepOptions.FIELDS["crank_model"].title
    assert tab_shop.CHOICES["convention"] == tuple(ShopOptions.FIELDS["convention"].choices)
    assert tab_explore.SETTINGS["top"][1] == default_text(ExploreOptions.FIELDS["top"])
    assert tab_loads.SETTINGS["samples"][2] == "a whole number from 36 to 3600"  # the schema's
