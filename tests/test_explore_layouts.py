"""The explorer on VR layouts, Ws from VR banks, side-by-side rods and articulated radials
(issue 27 item 3c): each candidate's free forces and moments agree with ``analyze`` of the
engine file written with the candidate's firing order (the one-engine path, an independent
reference: the crank is derived there by ``studies/build.py`` from the order), to 1e-9
relative; and a fixed crank bounds the enumeration of a 16-cylinder W."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.io.engine_file import dumps_toml, parse_engine_text, preset_text
from crankbalance.physics.balance_types import ShaftOptions
from crankbalance.physics.explore import merit
from crankbalance.physics.explore import orders as enumeration
from crankbalance.physics.model import model_fire_angles
from crankbalance.schema.settings import ExploreOptions
from crankbalance.studies.build import build_model
from crankbalance.studies.engine import analyze, balance_engine, firing
from crankbalance.studies.explorer import _problem

ORDERS = 4


#: rods side by side on the crossplane V8's shared pins, 20 mm apart (cylinder k of bank
#: A toward -y, its partner k + 4 toward +y)
SIDE_BY_SIDE = {"rod_positions": ["-10 mm"] * 4 + ["10 mm"] * 4}


def _engine(
    preset: str, firing_order: list[int] | None = None, extra: dict[str, object] | None = None
) -> object:
    """The preset's engine file (with ``extra`` crank-train keys), its crank derived from
    ``firing_order`` (pin split and given throw angles removed), parsed as a user's file
    would be."""
    data = tomllib.loads(preset_text(preset))
    data["crank_train"].update(extra or {})
    if firing_order is not None:
        data["crank_train"]["firing_order"] = firing_order
        for key in ("pin_split", "throw_angles"):
            data["crank_train"].pop(key, None)
    return parse_engine_text(dumps_toml(data), preset)


def _same_engine(a: np.ndarray, b: np.ndarray) -> bool:
    """Two cranks equal up to a rigid rotation [rad]."""
    gap = np.remainder((a - a[0]) - (b - b[0]) + np.pi, 2 * np.pi) - np.pi
    return bool(np.all(np.abs(gap) < 1e-9))


def _check(
    preset: str,
    settings: dict[str, object],
    rows: int = 12,
    extra: dict[str, object] | None = None,
) -> int:
    """``rows`` candidates spread over the enumeration, each against ``analyze`` of its
    engine file; the number of candidates."""
    spec = _engine(preset, extra=extra)
    options = ExploreOptions.parse(settings)
    problem = _problem(spec, options)
    batch = enumeration.chunk(problem, 0, enumeration.count(problem))
    assert batch.size > 0
    columns = merit.merit(batch, target="none", orders=ORDERS)
    pick = np.unique(np.linspace(0, batch.size - 1, min(rows, batch.size)).astype(int))
    for i in pick:
        order = [int(c) for c in batch.firing_order[i]]
        reference = analyze(_engine(preset, order, extra), ORDERS)
        # the engine file's crank is the candidate's (up to a rigid rotation)
        assert _same_engine(reference.model.throw_angle, batch.throw_angle[i])
        f = reference.forces
        scale = float(np.max(np.abs(f.force_forward) + np.abs(f.force_backward)))
        for n in range(ORDERS):
            for name, fwd, bwd in (
                (f"F{n + 1}", f.force_forward, f.force_backward),
                (f"M{n + 1}", f.couple_forward, f.couple_backward),
            ):
                unit = "_N" if name[0] == "F" else "_Nm"
                for suffix, want in (("f", abs(fwd[n])), ("b", abs(bwd[n]))):
                    got = columns[name + suffix + unit][i]
                    assert got == pytest.approx(want, rel=1e-9, abs=1e-12 * scale), (
                        preset,
                        order,
                        name + suffix,
                    )
        assert columns["Frot_N"][i] == pytest.approx(
            abs(f.rotating_force), rel=1e-9, abs=1e-12 * scale
        )
        assert columns["Mrot_Nm"][i] == pytest.approx(
            abs(f.rotating_couple), rel=1e-9, abs=1e-12 * scale
        )
    return batch.size


def test_vr6_candidates_agree_with_analyze() -> None:
    size = _check("vr6", {"layout": "vr", "cylinders": 6, "bank_angle": "15 deg"})
    assert size == 120  # one pin per cylinder: 5!, no symmetry with offset rows


def test_vr6_order_of_the_preset_fires_evenly_with_its_offsets() -> None:
    """The preset's order is among the candidates, on the crank ``studies/build.py``
    derives from it with the rows' offsets (top dead centres turned by asin(e/(l+r)))."""
    spec = _engine("vr6")
    problem = _problem(
        spec, ExploreOptions.parse({"layout": "vr", "bank_angle": "15 deg", "cylinders": 6})
    )
    batch = enumeration.chunk(problem, 0, enumeration.count(problem))
    model = build_model(_engine("vr6", [1, 5, 3, 6, 2, 4]))
    found = [i for i in range(batch.size) if _same_engine(batch.throw_angle[i], model.throw_angle)]
    assert found
    assert np.any(np.abs(model.cylinder_offset) > 0)  # the offsets are in play


def test_w12_from_vr_banks_candidates_agree_with_analyze() -> None:
    settings = {"layout": "w", "cylinders": 12, "bank_angle": "72 deg"}
    _check("w12-vw", settings | {"fixed_crank": _fixed("w12-vw")})


def test_w16_fixed_crank_candidates_agree_with_analyze() -> None:
    settings = {
        "layout": "w",
        "cylinders": 16,
        "bank_angle": "90 deg",
        "fixed_crank": _fixed("w16"),
    }
    size = _check("w16", settings)
    assert size >= 1


def test_side_by_side_v_candidates_agree_with_analyze() -> None:
    size = _check(
        "v8-crossplane",
        {"layout": "vee", "cylinders": 8, "bank_angle": "90 deg"},
        extra=SIDE_BY_SIDE,
    )
    assert size > 1


def test_articulated_radial_candidates_agree_with_analyze() -> None:
    _check("radial5-kinner", {"layout": "radial", "cylinders": 5})


def _w16_crank() -> list[str]:
    """The W16's crank as a user would type it, to four decimals of a degree."""
    return _fixed("w16", 4)


def test_fixed_crank_prunes_the_enumeration() -> None:
    """A fixed crank is known at the root of the enumeration: the W16 from VR banks (one
    throw per cylinder, 15! = 1.3e12 orders) builds a few thousand prefixes, counted
    exactly, instead of every order (the crank typed to four decimals of a degree)."""
    options = ExploreOptions.parse(
        {"layout": "w", "cylinders": 16, "bank_angle": "90 deg", "fixed_crank": _w16_crank()}
    )
    problem = _problem(_engine("w16"), options)
    total = enumeration.count(problem)
    assert total == math.factorial(15)
    size = enumeration.size(problem, 0, total)
    assert size.exact and size.orders >= 128 and size.prefixes < 10**6
    batch = enumeration.chunk(problem, 0, total)
    assert batch.size == 128
    # the preset's own order (Bugatti's) is one of them, as the engine it describes
    preset = build_model(_engine("w16"))
    assert any(_same_engine(preset.throw_angle, row) for row in batch.throw_angle)
    orders = {tuple(int(c) for c in row) for row in batch.firing_order}
    listed = {
        order
        for row in batch.firing_order
        for order in enumeration.equivalent_orders(problem, row.tolist())
    }
    assert tuple(preset.firing_order) in orders | listed


def test_shared_pin_v16_with_a_fixed_crank_is_small() -> None:
    """A reduced case of the shared-pin V16 search: the 90 deg V16 on a fixed crank
    enumerates exactly, every candidate on that crank."""
    crank = [0, 315, 270, 225, 180, 135, 90, 45]  # a spiral crank of 45 deg steps
    problem = enumeration.problem(
        "vee", 16, 4, bank_angle=math.pi / 2, fixed_throw_angles=np.radians(crank).tolist()
    )
    size = enumeration.size(problem, 0, enumeration.count(problem))
    assert size.exact and size.prefixes < 10**6
    batch = enumeration.chunk(problem, 0, enumeration.count(problem))
    assert batch.size > 0
    for row in batch.throw_angle:
        assert _same_engine(row, np.radians(crank))


@pytest.mark.parametrize("preset", ["radial5-kinner", "radial9-r985"])
@pytest.mark.parametrize("target", ["counterweights", "primary", "secondary"])
def test_articulated_balancing_agrees_with_balance_engine(preset: str, target: str) -> None:
    """Master-and-link rods: every balancing target of the explorer (formerly refused) is
    the one-engine balancing of its crank, ``balance_engine`` of the engine file with the
    candidate's order and the explorer's default shafts (balance factor 0.5)."""
    cylinders = int(preset[6])
    problem = _problem(
        _engine(preset), ExploreOptions.parse({"layout": "radial", "cylinders": cylinders})
    )
    batch = enumeration.chunk(problem, 0, enumeration.count(problem))
    columns = merit.merit(batch, target=target, balance_factor=0.5, orders=ORDERS)
    topo = problem.topology
    shaft = ShaftOptions(cg_radius=topo.crank_radius, length=2 * topo.crank_radius)
    level = merit.TARGETS.index(target)
    for i in range(batch.size):  # a radial: one crank, one engine
        order = [int(c) for c in batch.firing_order[i]]
        result = balance_engine(
            _engine(preset, order),
            ORDERS,
            balance_factor=0.5,
            primary=shaft if level >= 2 else None,
            secondary=shaft if level >= 3 else None,
        ).result
        assert result.counterweights is not None
        shafts = [s for g in (result.primary, result.secondary) if g for s in g.shafts]
        want = {
            "cw_mass_kg": result.counterweights.mass.sum(),
            "shafts": sum(1 for s in shafts if s.masses),
            "shaft_mass_kg": sum(m.mass for s in shafts for m in s.masses),
            "residual_F_N": max(c.force_after for c in result.residuals),
            "residual_M_Nm": max(c.moment_after for c in result.residuals),
        }
        scale = max(c.force_before for c in result.residuals)
        assert want["cw_mass_kg"] > 0 and want["shafts"] == 2 * (level - 1)
        for name, value in want.items():
            assert columns[name][i] == pytest.approx(value, rel=1e-9, abs=1e-12 * scale), name


def test_articulated_explore_command_balances(capsys: pytest.CaptureFixture[str]) -> None:
    """`crankbalance explore --engine radial5-kinner` with the default target
    (counterweights): the counterweight mass of `crankbalance balance` of the file."""
    import json

    from crankbalance.cli import main

    main(
        ["explore", "--engine", "radial5-kinner", "--layout", "radial", "--cylinders", "5"]
        + ["--balance-factor", "0.5", "--format", "json"]
    )
    row = json.loads(capsys.readouterr().out)["top"][0]
    result = balance_engine(_engine("radial5-kinner"), balance_factor=0.5).result
    assert result.counterweights is not None
    assert row["cw_mass_kg"] == pytest.approx(result.counterweights.mass.sum(), rel=1e-9)


@pytest.mark.parametrize("preset", ["radial5-kinner", "radial7-scarab", "radial9-r985"])
def test_articulated_firing_intervals_agree_with_analyze(preset: str) -> None:
    """The explorer's firing-interval figures of an articulated radial are those of the
    firing intervals `crankbalance analyze` prints for the engine file with the
    candidate's order (``studies.engine.firing``: the model's own firing angles)."""
    cylinders = int(preset[6])
    problem = _problem(
        _engine(preset), ExploreOptions.parse({"layout": "radial", "cylinders": cylinders})
    )
    batch = enumeration.chunk(problem, 0, enumeration.count(problem))
    columns = merit.merit(batch, target="none", orders=ORDERS)
    cycle = 4 * math.pi
    for i in range(batch.size):
        model = build_model(_engine(preset, [int(c) for c in batch.firing_order[i]]))
        order, intervals = firing(model)
        assert order == [int(c) for c in batch.firing_order[i]]
        want = float(np.max(np.abs(intervals - cycle / cylinders)))
        got = float(columns["interval_dev_rad"][i])
        assert got == pytest.approx(want, abs=1e-9)
        # one bank angle per cylinder: a bank's one interval is the whole cycle
        assert columns["bank_interval_dev_rad"][i] == pytest.approx(0.0, abs=1e-9)
        # the candidate's fire angles are the model's own (cylinder 1 at the same start)
        fire, mine = model_fire_angles(model), batch.fire_angle[i]
        assert np.allclose(np.mod(mine - mine[0], cycle), np.mod(fire - fire[0], cycle))


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (
            ["--layout", "w", "--cylinders", "16", "--bank-angle", "90 deg"],
            "--cylinders = '16': a multiple of 3 for layout w (a W from two VR banks: give "
            "its engine file)",
        ),
        (
            ["--layout", "w", "--cylinders", "12", "--bank-angle", "72 deg"]
            + ["--engine", "w12-vw", "--crank", "split"],
            "--crank = 'split': split crankpins need layout vee or a broad-arrow w",
        ),
        (
            ["--layout", "vr", "--cylinders", "6"],
            "--bank-angle: required for layout vr",
        ),
    ],
)
def test_what_is_refused_names_the_key(
    arguments: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    from crankbalance.cli import main

    with pytest.raises(SystemExit) as stop:
        main(["explore", *arguments])
    err = capsys.readouterr().err
    assert stop.value.code == 2 and err.count("\n") == 1 and message in err


def test_explore_command_runs_vr6_and_w16(capsys: pytest.CaptureFixture[str]) -> None:
    """`crankbalance explore --engine vr6 --layout vr` and the W16 on its own crank."""
    from crankbalance.cli import main

    main(
        ["explore", "--layout", "vr", "--cylinders", "6", "--bank-angle", "15 deg"]
        + ["--engine", "vr6", "--format", "json"]
    )
    import json

    data = json.loads(capsys.readouterr().out)
    assert data["counts"]["distinct_engines"] == 120
    main(
        ["explore", "--layout", "w", "--cylinders", "16", "--bank-angle", "90 deg"]
        + ["--engine", "w16", "--fixed-crank", ",".join(_w16_crank()), "--format", "json"]
    )
    data = json.loads(capsys.readouterr().out)
    assert data["counts"]["distinct_engines"] == 128


def _fixed(preset: str, decimals: int | None = None) -> list[str]:
    """The preset's crank as ``--fixed-crank`` values, exact or to ``decimals``."""
    angles = [math.degrees(a) for a in build_model(_engine(preset)).throw_angle]
    return [f"{a if decimals is None else round(a, decimals)} deg" for a in angles]


@pytest.mark.parametrize(
    ("preset", "settings", "extra"),
    [
        ("vr6", {"layout": "vr", "cylinders": 6, "bank_angle": "15 deg"}, None),
        ("w12-vw", {"layout": "w", "cylinders": 12, "bank_angle": "72 deg"}, None),
        ("w16", {"layout": "w", "cylinders": 16, "bank_angle": "90 deg"}, None),
        ("v8-crossplane", {"layout": "vee", "cylinders": 8, "bank_angle": "90 deg"}, SIDE_BY_SIDE),
    ],
)
def test_counterweights_agree_with_balance_engine(
    preset: str, settings: dict[str, object], extra: dict[str, object] | None
) -> None:
    """The explorer's counterweight mass and what its counterweights leave (balance factor
    0.5) equal ``balance_engine`` of the engine file written with the candidate's order."""
    if preset.startswith("w"):
        settings = settings | {"fixed_crank": _fixed(preset)}
    spec = _engine(preset, extra=extra)
    problem = _problem(spec, ExploreOptions.parse(settings))
    batch = enumeration.chunk(problem, 0, enumeration.count(problem))
    columns = merit.merit(batch, target="counterweights", balance_factor=0.5, orders=ORDERS)
    for i in sorted({0, batch.size // 2, batch.size - 1}):
        order = [int(c) for c in batch.firing_order[i]]
        study = balance_engine(_engine(preset, order, extra), ORDERS, balance_factor=0.5)
        result = study.result
        assert result.counterweights is not None
        mass = result.counterweights.mass.sum()
        if result.extra_counterweights is not None:
            mass += result.extra_counterweights.mass.sum()
        force = max(c.force_after for c in result.residuals)
        moment = max(c.moment_after for c in result.residuals)
        scale = max(c.force_before for c in result.residuals)
        assert columns["cw_mass_kg"][i] == pytest.approx(mass, rel=1e-9, abs=1e-12)
        assert columns["residual_F_N"][i] == pytest.approx(force, rel=1e-9, abs=1e-12 * scale)
        assert columns["residual_M_Nm"][i] == pytest.approx(moment, rel=1e-9, abs=1e-12 * scale)


def test_broad_arrow_w12_candidates_agree_with_analyze() -> None:
    """The broad-arrow W12 of the presets (three banks on four shared pins): every one of
    its 256 engines' forces as analyze gives them."""
    size = _check("w12", {"layout": "w", "cylinders": 12, "bank_angle": "60 deg"}, rows=256)
    assert size == 256


def test_articulated_balancing_refuses_as_the_batch_does() -> None:
    """Options a radial cannot have are refused on the one-engine path with the batch
    solver's line: the field, the value and what is allowed (the plain radial of the same
    layout, without master-and-link rods, takes the batch path)."""
    from crankbalance.physics.balance_types import CounterweightOptions

    options = ExploreOptions.parse({"layout": "radial", "cylinders": 5})
    articulated = _problem(_engine("radial5-kinner"), options)
    plain = enumeration.problem("radial", 5, 4)
    assert articulated.topology.articulation is not None
    assert plain.topology.articulation is None
    cw = CounterweightOptions(cg_radius=0.05, scope="halves")
    messages = []
    for problem in (articulated, plain):
        batch = enumeration.chunk(problem, 0, enumeration.count(problem))
        with pytest.raises(InputError) as info:
            merit.merit(batch, counterweights=cw)
        messages.append(str(info.value))
    assert messages[0] == messages[1]
    assert messages[0].startswith("counterweights.scope = 'halves': ")
