"""Makers' numbering and the firing order checked against the crank (issue 17, item 5).

References: the makers' numbering rules and orders written out here by hand from their
descriptions (Porsche 911 flat-6, 1964, bank after bank as DIN 73021, firing
1-6-2-4-3-5; Chevrolet small-block V8, 1955, odd cylinders left, even right, firing
1-8-4-3-6-5-7-2; Ford 289/302, 1963/1968, right bank 1-4, left 5-8, firing 1-5-4-2-6-3-7-8;
Ford 351W, 1969, firing 1-3-7-2-6-5-4-8), independently of the rule functions of
``crankbalance.physics.firing``; the firing intervals against the crank's top dead centres
computed here from the throw angles (theta_c = beta_c - phi_c) and against
``studies.build``'s even-firing crank.
"""

from __future__ import annotations

import math
import re
import tomllib
from typing import Any

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from crankbalance.cli.analyze import analyze as cli_analyze
from crankbalance.errors import InputError
from crankbalance.io.engine_file import list_presets, preset_text
from crankbalance.physics.firing import SCHEMES, crank_order, order_intervals
from crankbalance.schema.engine import spec_from_dict
from crankbalance.studies.build import build_model
from crankbalance.studies.engine import analyze

PROPERTY = settings(
    derandomize=True,
    database=None,
    deadline=None,
    max_examples=60,
    suppress_health_check=[HealthCheck.too_slow],
)


def preset(name: str) -> dict[str, Any]:
    data: dict[str, Any] = tomllib.loads(preset_text(name))
    return data


def model_of(data: dict[str, Any]) -> Any:
    return build_model(spec_from_dict(data))


def degrees(values: Any) -> list[str]:
    return [f"{float(a)!r} deg" for a in np.degrees(values)]


def from_one(order: tuple[int, ...]) -> tuple[int, ...]:
    k = order.index(1)
    return order[k:] + order[:k]


def same_engine(a: Any, b: Any, turned: bool = False) -> None:
    """Every number the physics sees is the same (the maker's numbers only label); with
    ``turned``, up to a turn of the whole crank and the cylinder the order starts from."""
    if turned:
        turn = a.throw_angle - b.throw_angle - (a.throw_angle[0] - b.throw_angle[0])
        np.testing.assert_allclose(np.sin(turn), 0, atol=1e-12)
        np.testing.assert_allclose(np.cos(turn), 1, atol=1e-12)
        assert from_one(a.firing_order) == from_one(b.firing_order)
    else:
        np.testing.assert_array_equal(a.throw_angle, b.throw_angle)
        assert a.firing_order == b.firing_order
    for name in (
        "throw_position",
        "throw_rotating_mass",
        "cylinder_throw",
        "cylinder_bank",
        "reciprocating_mass",
        "cylinder_offset",
    ):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)


# --------------------------------------------------------------------------- the maps
def test_maps_against_the_makers_words() -> None:
    # Porsche: maker's 1-2-3 along one bank, 4-5-6 along the other; crankbalance alternates
    # sides along the crank (odd at -90 deg): 1, 2, 3 -> 1, 3, 5 and 4, 5, 6 -> 2, 4, 6
    assert SCHEMES["porsche-boxer"].to_crankbalance(6) == (1, 3, 5, 2, 4, 6)
    # GM: right bank (bank A, reached first turning clockwise seen from the front) is
    # 2-4-6-8 front to rear -> 1..4; the left bank 1-3-5-7 -> 5..8
    gm = {2: 1, 4: 2, 6: 3, 8: 4, 1: 5, 3: 6, 5: 7, 7: 8}
    assert SCHEMES["gm-vee"].to_crankbalance(8) == tuple(gm[m] for m in range(1, 9))
    assert SCHEMES["gm-vee"].to_crankbalance(6) == (4, 1, 5, 2, 6, 3)
    assert SCHEMES["ford-vee"].to_crankbalance(8) == tuple(range(1, 9))


def test_porsche_order_is_the_crankbalance_order() -> None:
    """Porsche's 1-6-2-4-3-5 with ``numbering = "porsche-boxer"`` is crankbalance's
    1-6-3-2-5-4: the same engine, on the preset's crank and on the crank derived from it."""
    porsche = preset("boxer6")
    assert porsche["crank_train"]["numbering"] == "porsche-boxer"
    assert porsche["crank_train"]["firing_order"] == [1, 6, 2, 4, 3, 5]
    ours = preset("boxer6")
    del ours["crank_train"]["numbering"]
    ours["crank_train"]["firing_order"] = [1, 6, 3, 2, 5, 4]
    a, b = model_of(porsche), model_of(ours)
    same_engine(a, b)
    assert a.maker_number == (1, 4, 2, 5, 3, 6) and b.maker_number is None
    assert analyze(a).to_dict()["free_moments"] == analyze(b).to_dict()["free_moments"]
    # the crank from the order (even firing): opposed pairs on throws 180 deg apart,
    # neighbouring pairs 120 deg apart: the flat-six crank of the preset, turned
    for data in (porsche, ours):
        del data["crank_train"]["throw_angles"]
    a, b = model_of(porsche), model_of(ours)
    same_engine(a, b)
    phi = np.degrees(a.throw_angle)
    np.testing.assert_allclose(np.mod(phi[1::2] - phi[0::2], 360), 180, atol=1e-9)
    preset_phi = np.array([0, 180, 120, 300, 240, 60])
    np.testing.assert_allclose(np.mod(phi - preset_phi - (phi[0] - 0), 360), 0, atol=1e-9)
    # the outputs name both
    engine = analyze(a).to_dict()["engine"]
    assert engine["firing_order"] == [1, 6, 3, 2, 5, 4]
    assert engine["firing_order_maker"] == [1, 6, 2, 4, 3, 5]
    assert engine["maker_number"] == [1, 4, 2, 5, 3, 6]
    from crankbalance.output.report import maker_order

    assert maker_order(a) == " (maker's numbering: 1-6-2-4-3-5)" and maker_order(b) == ""
    table = CliRunner().invoke(cli_analyze, ["boxer6"])
    assert table.exit_code == 0, table.output
    assert (
        "Firing order 1-6-2-4-3-5 in the maker's numbering, 1-6-3-2-5-4 in crankbalance's "
        "(maker's cylinder: crankbalance's 1: 1, 2: 3, 3: 5, 4: 2, 5: 4, 6: 6)"
    ) in table.output


def v8(order: list[int], numbering: str | None) -> dict[str, Any]:
    data = preset("v8-crossplane")
    data["crank_train"]["firing_order"] = order
    if numbering:
        data["crank_train"]["numbering"] = numbering
    return data


def test_gm_and_ford_are_one_engine() -> None:
    gm = model_of(v8([1, 8, 4, 3, 6, 5, 7, 2], "gm-vee"))
    ford = model_of(v8([1, 5, 4, 2, 6, 3, 7, 8], "ford-vee"))
    same_engine(gm, ford, turned=True)  # GM's 1 is crankbalance's 5: it fires first
    assert gm.firing_order == (5, 4, 2, 6, 3, 7, 8, 1)
    # a crossplane crank: throws 90 deg apart, not in one plane
    phi = np.degrees(gm.throw_angle - gm.throw_angle[0])
    assert np.allclose(np.mod(phi + 1e-9, 90), 1e-9) and not np.allclose(np.mod(phi, 180), 0)
    # the 351W's order is the 302's from the other end: its crank is the mirror image
    w351 = model_of(v8([1, 3, 7, 2, 6, 5, 4, 8], "ford-vee"))
    np.testing.assert_allclose(
        np.sort(np.mod(np.degrees(w351.throw_angle - w351.throw_angle[0]), 360)),
        np.sort(np.mod(phi, 360)),
        atol=1e-9,
    )
    # explicit maps: GM's numbers written as crankbalance's by hand
    explicit = v8([1, 8, 4, 3, 6, 5, 7, 2], None)
    explicit["crank_train"]["maker_numbers"] = [5, 1, 6, 2, 7, 3, 8, 4]
    same_engine(model_of(explicit), gm)


# --------------------------------------------------------------------------- the check
def test_wrong_order_on_a_crossplane_v8_is_refused() -> None:
    base = model_of(preset("v8-crossplane"))
    data = preset("v8-crossplane")
    data["crank_train"]["throw_angles"] = degrees(base.throw_angle)
    model_of(data)  # its own order on its own crank
    data["crank_train"]["firing_order"] = [1, 2, 3, 4, 5, 6, 7, 8]
    with pytest.raises(InputError) as caught:
        model_of(data)
    error = caught.value
    assert error.field == "crank_train.firing_order"
    assert error.value == [1, 2, 3, 4, 5, 6, 7, 8]
    text = str(error)
    # the crank's top dead centres, by hand: theta_c = beta_c - phi_c after cylinder 1's
    beta = base.cylinder_bank
    theta = np.mod(np.degrees(beta - base.throw_angle[base.cylinder_throw]), 360)
    after = np.mod(np.round(theta - theta[0], 6), 360)
    for c in range(8):
        assert re.search(rf"\b{c + 1}: {after[c]:.4g}\b", text), (c, text)
    # the order it offers fires every 90 deg and is accepted when given back
    offered = re.search(r"allows is ([\d-]+) \(intervals ([\d.-]+) deg\)", text)
    assert offered, text
    assert offered.group(2) == "-".join(["90"] * 8)
    data["crank_train"]["firing_order"] = [int(c) for c in offered.group(1).split("-")]
    model_of(data)
    # in a maker's numbering, the message gives the offer in the maker's numbers too
    data["crank_train"]["numbering"] = "gm-vee"
    data["crank_train"]["firing_order"] = [1, 2, 3, 4, 5, 6, 7, 8]
    with pytest.raises(InputError, match="in the maker's numbers"):
        model_of(data)


def test_uneven_consistent_orders_pass() -> None:
    # odd-fire 90 deg V6 on three common pins at 120 deg: intervals 90/150
    v6 = preset("v6-90")
    v6["crank_train"]["firing_order"] = [1, 4, 2, 5, 3, 6]
    m = model_of(v6)
    theta = np.mod(m.cylinder_bank - m.throw_angle[m.cylinder_throw], 2 * math.pi)
    steps = np.degrees(order_intervals(theta, [1, 4, 2, 5, 3, 6], 4))
    np.testing.assert_allclose(steps, [90, 150, 90, 150, 90, 150], atol=1e-9)
    # crossplane inline-4 (pins at 0, 90, 270, 180 deg): uneven 90/180/270/180
    i4 = preset("inline4")
    i4["crank_train"]["throw_angles"] = ["0 deg", "90 deg", "270 deg", "180 deg"]
    i4["crank_train"]["firing_order"] = [1, 3, 2, 4]
    m = model_of(i4)
    theta = np.mod(-m.throw_angle, 2 * math.pi)
    steps = np.degrees(order_intervals(theta, [1, 3, 2, 4], 4))
    np.testing.assert_allclose(steps, [90, 180, 270, 180], atol=1e-9)
    # 1-2-3-4 fits too (270-180-90-180: the same intervals from another cylinder); 1-2-4-3
    # would need four turns of 270 deg
    i4["crank_train"]["firing_order"] = [1, 2, 3, 4]
    model_of(i4)
    i4["crank_train"]["firing_order"] = [1, 2, 4, 3]
    with pytest.raises(InputError, match="add up to 1080 deg"):
        model_of(i4)
    # the 180 deg twin fires both in one revolution and none in the next
    assert model_of(preset("inline2-180")).firing_order == (1, 2)


def test_single_throw_and_two_stroke() -> None:
    radial = preset("radial5")
    radial["crank_train"]["firing_order"] = [1, 2, 3, 4, 5]  # uneven: one turn, then none
    model_of(radial)
    radial["crank_train"]["firing_order"] = [1, 5, 4, 3, 2]  # backwards: 4 x 288 deg
    with pytest.raises(InputError, match="1440 deg"):
        model_of(radial)
    # a two-stroke fires at every top dead centre: the order is the crank's
    two = preset("inline2-2stroke")
    m = model_of(two)
    theta = np.mod(-m.throw_angle, 2 * math.pi)
    assert math.isclose(float(order_intervals(theta, [1, 2], 2).sum()), 2 * math.pi)
    inline3 = preset("inline3")
    inline3["crank_train"]["strokes"] = 2
    inline3["crank_train"]["throw_angles"] = ["0 deg", "120 deg", "240 deg"]
    inline3["crank_train"]["firing_order"] = [1, 3, 2]
    model_of(inline3)
    inline3["crank_train"]["firing_order"] = [1, 2, 3]
    with pytest.raises(InputError, match=r"\(360 deg\)"):
        model_of(inline3)


def test_every_preset_loads() -> None:
    for name in list_presets():
        model_of(preset(name))


@pytest.mark.parametrize(
    ("patch", "field", "words"),
    [
        ({"numbering": "gm"}, "crank_train.numbering", "porsche-boxer, gm-vee, ford-vee"),
        ({"numbering": "porsche-boxer"}, "crank_train.numbering", "maker_numbers"),
        ({"maker_numbers": [1, 2, 3, 4, 5, 6, 7, 7]}, "crank_train.maker_numbers", "1..8"),
        ({"maker_numbers": [1, 2, 3]}, "crank_train.maker_numbers", "1..8"),
        (
            {"numbering": "gm-vee", "maker_numbers": list(range(1, 9))},
            "crank_train.maker_numbers",
            "either",
        ),
    ],
)
def test_bad_numbering(patch: dict[str, Any], field: str, words: str) -> None:
    data = preset("v8-crossplane")
    data["crank_train"].update(patch)
    with pytest.raises(InputError) as caught:
        spec_from_dict(data)
    assert caught.value.field == field and words in str(caught.value)


# --------------------------------------------------------------------------- properties
#: base presets of the property test: (preset, cylinders per throw count)
BASES = {"inline": ("inline4", 1), "vee": ("v8-crossplane", 2), "vr": ("vr6", 1), "w-vr": ("w8", 2)}


@PROPERTY
@given(
    layout=st.sampled_from(sorted(BASES)),
    throws=st.integers(2, 6),
    strokes=st.sampled_from([2, 4]),
    vee=st.sampled_from([60, 72, 90, 120, 180]),
    seed=st.integers(0, 2**31),
)
def test_the_crank_of_an_even_order_accepts_it(
    layout: str, throws: int, strokes: int, vee: int, seed: int
) -> None:
    """For an even-firing inline, vee, VR or W-from-VR engine built from a random order
    (VR rows with their bore offset, so each row's top dead centre is shifted), the crank
    given as throw_angles accepts that order at its even intervals, and the order the
    crank offers passes too."""
    name, per_throw = BASES[layout]
    n = throws * per_throw
    rng = np.random.default_rng(seed)
    order = [1, *(int(c) + 2 for c in rng.permutation(n - 1))]
    data = preset(name)
    ct = data["crank_train"]
    ct.update(cylinders=n, strokes=strokes, firing_order=order)
    ct.pop("pin_split", None)  # the crank from the order
    if layout == "vee":
        ct["bank_angle"] = f"{vee} deg"
    try:
        m = model_of(data)
    except InputError as error:  # no even crank for this order on shared pins
        assert "throw_angles" in str(error) and layout in ("vee", "w-vr")
        return
    ct["throw_angles"] = degrees(m.throw_angle)
    assert model_of(data).firing_order == tuple(order)
    psi = np.arcsin(m.cylinder_offset / (m.crank_radius + m.rod_length))
    theta = np.mod(m.cylinder_bank + psi - m.throw_angle[m.cylinder_throw], 2 * math.pi)
    steps = order_intervals(theta, order, strokes)
    np.testing.assert_allclose(steps, 2 * math.pi * strokes / 2 / n, atol=1e-9)
    offered, gaps = crank_order(theta, 1, strokes)
    assert math.isclose(float(gaps.sum()), math.pi * strokes)
    ct["firing_order"] = offered
    model_of(data)
    # the second and third swapped: intervals 2, a turn less 1, 2, then 1 each (in even
    # intervals, each at most half a turn: a two-stroke, or a four-stroke of 4 or more):
    # a turn more than the cycle, unless both reach top dead centre together
    if (
        n > 2
        and (strokes == 2 or n >= 4)
        and abs(math.remainder(theta[order[1] - 1] - theta[order[2] - 1], 2 * math.pi)) > 1e-6
    ):
        ct["firing_order"] = [order[0], order[2], order[1], *order[3:]]
        with pytest.raises(InputError, match="crank_train.firing_order"):
            model_of(data)


def test_explorer_candidate_keeps_the_makers_numbering() -> None:
    """The web explorer's candidate (an order in crankbalance's numbering) written into an
    engine in Porsche's numbering is written in Porsche's numbers: the same engine."""
    pytest.importorskip("nicegui")
    from types import SimpleNamespace

    from crankbalance.web.tab_explore import candidate_file

    data = preset("boxer6")
    base = model_of(data)
    problem = SimpleNamespace(layout="boxer", strokes=4)
    row = {"firing_order": [1, 6, 3, 2, 5, 4], "throw_angle_rad": list(base.throw_angle)}
    out = candidate_file(data, problem, None, row)
    assert out["crank_train"]["numbering"] == "porsche-boxer"
    assert out["crank_train"]["firing_order"] == [1, 6, 2, 4, 3, 5]
    same_engine(model_of(out), base)
    # another cylinder count: the numbering is dropped with the crank's other counts
    row = {"firing_order": [1, 4, 3, 2], "throw_angle_rad": [0.0, math.pi, math.pi, 0.0]}
    out = candidate_file(data, problem, None, row)
    assert "numbering" not in out["crank_train"]
    assert out["crank_train"]["firing_order"] == [1, 4, 3, 2]


@pytest.mark.parametrize(
    ("throws_deg", "banks_deg", "strokes"),
    [
        ([0, 120, 240, 0, 120, 240], [-45, -45, -45, 45, 45, 45], 4),  # odd-fire V6
        ([0, 90, 270, 180], [0, 0, 0, 0], 4),  # crossplane inline-4
        ([0, 180, 180, 0], [0, 0, 0, 0], 4),  # flat inline-4
        ([0, 180, 180, 0], [0, 0, 0, 0], 2),
        ([0, 0, 90, 210, 300], [-30, 30, -30, 30, 0], 4),
        ([0, 120, 240], [0, 0, 0], 2),
    ],
)
def test_engine_cycle_fires_what_the_check_accepts(
    throws_deg: list[float], banks_deg: list[float], strokes: int
) -> None:
    """Every order from cylinder 1 (brute force): the engine cycle's firing angles exist
    exactly for the orders the build accepts, increase along the order within one cycle,
    and have the check's intervals."""
    import itertools

    from crankbalance.physics.firing import check_firing_order, firing_angles

    phi, beta = np.radians(throws_deg), np.radians(banks_deg)
    theta = np.mod(beta - phi, 2 * math.pi)
    n, cycle = phi.size, math.pi * strokes
    accepted = 0
    for rest in itertools.permutations(range(2, n + 1)):
        order = [1, *rest]
        try:
            check_firing_order(theta, order, strokes, "crank_train.firing_order", order)
        except InputError:
            with pytest.raises(InputError, match="crank_train.firing_order"):
                firing_angles(phi, beta, order, strokes)
            continue
        accepted += 1
        fire = firing_angles(phi, beta, order, strokes)
        times = np.mod(fire[np.array(order) - 1] - fire[0], cycle)
        assert np.all(np.diff(times) >= -1e-9), (order, times)
        steps = np.diff(np.append(times, cycle))
        shortest = order_intervals(theta, order, strokes)
        if math.isclose(float(shortest.sum()), cycle):
            np.testing.assert_allclose(steps, shortest, atol=1e-9)
        np.testing.assert_allclose(np.mod(fire + phi - beta + 1e-9, 2 * math.pi), 1e-9, atol=1e-8)
    assert accepted > 0
