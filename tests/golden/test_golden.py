"""Golden tier: the JSON of every preset's analysis and balance, and of one run of each
other study, compared value by value with the files in ``tests/golden/data``.

The files were written before the restructuring of the package; a change of layout must
not change a number. Where the output vocabulary renamed a key or changed its unit, the
map below names the old key (and the factor from the new unit to the old one); where a
value changed on purpose, ``DELIBERATE`` names the key and says why. Regenerate with
``python tests/golden/regenerate.py`` only for a deliberate change of results.
"""

from __future__ import annotations

import json
import math
import re
from typing import Any

import pytest

from .cases import DATA, cases, run

RPM = 30.0 / math.pi  # rad/s -> rpm
DEG = math.pi / 180.0  # degrees -> radians

#: (pattern on the new dotted key, the old key it replaces, factor new -> old unit[, pattern
#: on the case names it is limited to])
RENAMED: list[tuple[str, str, float] | tuple[str, str, float, str]] = [
    # analysis/2, balance/2: speeds in rad/s, conrod splits with their units
    (r"^engine\.cylinder_offset_m\.\d+$", "engine.offset_m", 1.0),  # one offset per cylinder
    (r"^engine\.speed_rad_s$", "engine.speed_rpm", RPM),
    (r"^(masses\.conrods\.\d+)\.mass_kg$", r"\1.mass", 1.0),
    (r"^(masses\.conrods\.\d+)\.(rotating|reciprocating)_kg$", r"\1.\2", 1.0),
    (r"^(masses\.conrods\.\d+)\.cg_from_big_end_m$", r"\1.cg_from_big_end", 1.0),
    (r"^(masses\.conrods\.\d+)\.(inertia_\w+)_kg_m2$", r"\1.\2", 1.0),
    # shaft/2: the placement studies' curves, and every key of shaft check
    (r"^((studies\.\w+\.)?curves)\.first_frequency_hz", r"\1.first_frequency_Hz", 1.0),
    (r"^((studies\.\w+\.)?curves)\.unbalances_kg_m", r"\1.unbalances_kgm", 1.0),
    (r"^(shaft|response)\.(\w+)_deg(\.\d+)?$", r"\1.\2\3", DEG),
    (r"^(shaft|response)\.(\w+?)_rad_s$", r"\1.\2", 1.0),
    # bench/2, cycle/2, sensitivity/2: speeds in rad/s, rotor and cylinder with units
    (r"^(runs\.\d+\.(final_)?speed)_rad_s$", r"\1_rpm", RPM),
    (r"^speed_rad_s$", "speed_rpm", RPM, r"cycle-.*|sensitivity-.*"),
    (r"^curves\.speed_rad_s", "curves.speed_rpm", RPM),
    (r"^curves\.pressure_Pa", "curves.pressure_bar", 1e-5),
    (r"^curves\.cycle_angle_rad", "curves.angle_deg", 180.0 / math.pi, r"cycle-.*"),
    (r"^(rotor|cylinder)\.(\w+?)_(m|kg|kg_m|kg_m2|m_s2|N|Pa)(\.\d+)?$", r"\1.\2\4", 1.0),
    # counterweight/2: angles in degrees
    (r"^((least_mass|least_radius|pareto\.\d+|design)\.\w+?)_deg$", r"\1_rad", DEG),
    (r"^(bounds\.\w+?)_deg(\.\d+)?$", r"\1_rad\2", DEG),
    (r"^(gamma|lambda)_deg$", r"\1_rad", DEG),
    (
        r"^(shaft\.section|shaft|response|checks)\.(\w+?)_(m|m2|kg_m|N|Nm|Pa|hz|kg_m3|N_per_m)(\.\d+)?$",
        r"\1.\2\4",
        1.0,
    ),
    # balance-factor/2, rebalance/2, tolerance/2: every key with a unit ends in its SI unit
    (
        r"^mass_properties\.counterweight_moment_kg_m$",
        "mass_properties.counterweight_moment_kgm",
        1.0,
    ),
    (r"^tolerance\.unbalance_kg_m$", "tolerance.unbalance_kgm", 1.0),
    (r"^(old|new)\.(rotating|reciprocating)_parts_kg\.", r"\1.parts.\2.", 1.0),
    (r"^(old|new)\.(rotating|reciprocating)_mass_kg$", r"\1.\2_mass", 1.0),
    (r"^(cases\.\d+\.correction\.)(radius|depth_resolution|diameter)_m$", r"\1\2", 1.0),
    (r"^(cases\.\d+\.correction\.)area_m2$", r"\1area", 1.0),
    (r"^(cases\.\d+\.correction\.)density_kg_m3$", r"\1density", 1.0),
    (
        r"^(cases\.\d+\.iterations\.\d+\.)"
        r"(unbalance_to_correct|removed_unbalance|residual)_kg_m$",
        r"\1\2",
        1.0,
    ),
    (r"^(cases\.\d+\.iterations\.\d+\.)(correction_mass|removed_mass)_kg$", r"\1\2", 1.0),
    (r"^(cases\.\d+\.iterations\.\d+\.)(correction_radius|depth)_m$", r"\1\2", 1.0),
    (
        r"^(cases\.\d+\.)(original_moment|required_moment|unbalance|residual|tolerance)_kg_m$",
        r"\1\2",
        1.0,
    ),
    (r"^(cases\.\d+\.)bob_weight_kg$", r"\1bob_weight", 1.0),
    (r"^grade\.value_m_s$", "grade.value", 1.0),
    (r"^permissible_unbalance_kg_m$", "permissible_unbalance_kgm", 1.0),
    (r"^planes\.(total|bearing_a|bearing_b|plane_1|plane_2)_kg_m$", r"planes.\1", 1.0),
]

#: case -> {pattern on an old key no longer printed: why}
DROPPED: dict[str, dict[str, str]] = {
    "tolerance-crf250r": {
        r"^permissible_unbalance_gmm$": "non-SI duplicate of permissible_unbalance_kg_m"
    },
}

#: keys new on purpose: {pattern: why}; the value must be zero (what the engines of the
#: golden files had before the key existed)
ADDED: dict[str, str] = {
    r"^engine\.cylinder_axial_m\.\d+$": "rods' axial places on a shared pin, issue 17",
    r"^engine\.moment_reference_m$": "moment reference point from the crank mid-point, issue 17",
}

#: keys new on purpose that label the engine rather than compute on it (any value):
#: {pattern: why}
LABELS: dict[str, str] = {
    r"^engine\.(firing_order|firing_order_maker|maker_number)\.\d+$": "the firing order as "
    "given, and in a maker's numbering with each cylinder's maker's number, issue 17",
    r"^remaining(\.\d+\.|$)": "what is left in words with the next step (issue 27), the "
    "forward and backward parts of the residuals the components pin",
    r"(^|\.)combustion\.(heat_release_J|fuel_mass_kg|heating_value_J_kg|combustion_efficiency"
    r"|gamma|exhaust_pressure_Pa|burn_end)$": "the combustion's settings stated, at the "
    "defaults the model always took, issue 27",
}

#: keys whose value depends on the run, not on the engine
VOLATILE = re.compile(r"(^|\.)elapsed_s$")

#: case (a pattern on its whole name) -> {dotted key pattern: why its value changed on purpose}
DELIBERATE: dict[str, dict[str, str]] = {
    r"balance-(?!factor).*": {
        r"^unbalanced\.\d+$": "text in the one vocabulary (format.py): N·m, no 2.155e+04"
    },
    "rebalance-crf250r": {r"^name$": "the example's name cites the thesis by author and year"},
    "cycle-engine": {
        r"^curves\.cycle_angle_rad\.": "cycle/3: the angle over the 720 deg cycle, which "
        "cycle/2 folded into [0, 360) as angle_deg"
    },
    "shaft-inline3-engine": {r"^paper\.(source|note)$": "cites Kim (2018) by author and year"},
    "shaft-inline4-engine": {r"^paper\.source$": "cites Kim (2018) by author and year"},
    "tolerance-crf250r": {r"^grade\.examples$": "cites the thesis by author and year"},
}

REL, ABS = 1e-9, 1e-12


def flatten(value: Any, prefix: str = "") -> dict[str, Any]:
    """{"a": {"b": [1, 2]}} -> {"a.b.0": 1, "a.b.1": 2}."""
    if isinstance(value, dict):
        out: dict[str, Any] = {}
        for key, item in value.items():
            out.update(flatten(item, f"{prefix}{key}."))
        return out
    if isinstance(value, list):
        out = {}
        for k, item in enumerate(value):
            out.update(flatten(item, f"{prefix}{k}."))
        return out if value else {prefix[:-1]: []}
    return {prefix[:-1]: value}


def old_key(key: str, case: str) -> tuple[str, float]:
    """The key this value had in the golden file, and the factor to its old unit."""
    for pattern, old, factor, *only in RENAMED:
        if only and not re.fullmatch(only[0], case):
            continue
        if re.search(pattern, key):
            return re.sub(pattern, old, key), factor
    return key, 1.0


def same(key: str, new: Any, old: Any) -> bool:
    if isinstance(new, bool) or isinstance(old, bool) or not isinstance(new, int | float):
        return bool(new == old)
    if not isinstance(old, int | float):
        return False
    if re.search(r"_deg(\.\d+)*$", key):  # one angle range, [0, 360): compare modulo a turn
        turn = (new - old) / 360.0
        return abs(turn - round(turn)) * 360.0 <= 1e-9 * max(1.0, abs(old))
    return math.isclose(new, old, rel_tol=REL, abs_tol=ABS)


@pytest.mark.parametrize("name", sorted(cases()))
def test_golden(name: str) -> None:
    path = DATA / f"{name}.json"
    assert path.exists(), f"no golden file for {name}: run python tests/golden/regenerate.py"
    golden = flatten(json.loads(path.read_text()))
    now = flatten(run(cases()[name]))
    deliberate = {
        key: why
        for case, keys in DELIBERATE.items()
        if re.fullmatch(case, name)
        for key, why in keys.items()
    }
    seen: set[str] = set()
    problems = []
    for key, value in now.items():
        if VOLATILE.search(key) or key.endswith("schema"):
            continue
        old, factor = old_key(key, name)
        if old not in golden and key in golden:  # a file written after the rename
            old, factor = key, 1.0
        if old not in golden and any(re.search(p, key) for p in ADDED) and value == 0:
            continue
        if old not in golden and any(re.search(p, key) for p in LABELS):
            continue
        if old not in golden:
            problems.append(f"{key}: new key (not in the golden file as {old})")
            continue
        seen.add(old)
        if any(re.search(p, key) for p in deliberate):
            continue
        expected = golden[old]
        if isinstance(value, int | float) and not isinstance(value, bool) and factor != 1.0:
            value = value * factor
        if not same(key, value, expected):
            problems.append(f"{key}: {value!r} != golden {old} = {expected!r}")
    dropped = DROPPED.get(name, {})
    missing = [
        k
        for k in golden
        if k not in seen
        and not VOLATILE.search(k)
        and not k.endswith("schema")
        and not any(re.search(p, k) for p in dropped)
    ]
    problems += [f"{k}: in the golden file, no longer printed" for k in missing]
    assert not problems, f"{name} differs from its golden file:\n" + "\n".join(problems[:40])
