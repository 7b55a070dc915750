"""The 2021 crankshaft-balancing paper: Tables 2 and 5, through the general solver.

Reference values and readings: docs/references.md, Appl. Sci. 2021.
"""

from __future__ import annotations

import math

import pytest

from crankbalance.studies.engine import balance_engine

from ..conftest import EXAMPLES

# Table 5 (V4-90) prints m_c1 = 0.3948 kg on a co- and a counter-rotating shaft; the checked
# reading a m_alt r / (sqrt(2) r_c1 l_sh1) with a = 90 mm, m_alt = 0.94 kg, r = 40 mm,
# r_c1 = 30 mm, l_sh1 = 200 mm gives 0.3988 kg, 1 % off (docs/references.md). Data, not a
# test: that pair is not what the solver builds (test_v4_primary_shafts_erratum).
V4_TABLE5_PRIMARY_PRINTED_KG = 0.3948
V4_TABLE5_PRIMARY_READING_KG = 0.09 * 0.94 * 0.04 / (math.sqrt(2) * 0.03 * 0.2)
# That pair would leave, of the rotating couple C = a m_alt r w^2, a forward part
# C (1 - 1/sqrt 2) (the co-rotating shaft is short) and a new backward part C / sqrt 2
# (the counter-rotating shaft has nothing to cancel): together about C, i.e. no balancing.
V4_TABLE5_PAIR_LEAVES = (1 - 1 / math.sqrt(2)) + 1 / math.sqrt(2)


def test_inline3_table2() -> None:
    data = balance_engine(EXAMPLES / "paper_inline3.toml").to_dict()
    assert round(data["counterweight"]["mass_kg"], 4) == 1.2413, (
        "Appl. Sci. 2021, Table 2: m_c = 1.2413 kg"
    )
    assert round(data["primary_shafts"]["mass_kg"], 4) == 0.4884, (
        "Appl. Sci. 2021, Table 2: m_c1 = 0.4884 kg"
    )
    assert round(data["secondary_shafts"]["mass_kg"], 4) == 0.0362, (
        "Appl. Sci. 2021, Table 2: m_c2 = 0.0362 kg"
    )
    # every shaft mass is the same (pairs in opposite phase at +-l_sh/2, Eq. 13)
    for key in ("primary_shafts", "secondary_shafts"):
        for shaft in data[key]["shafts"]:
            assert [m["position_m"] for m in shaft["masses"]] == [-0.1, 0.1]
    for value in data["residual"].values():
        assert value == 0.0, "every targeted component is cancelled (time-domain check)"


def test_inline3_closed_forms() -> None:
    """Closed forms of docs/references.md for this inline-3:
    m_c = sqrt(3) m_rot r/(4 r_c cos(a-30)), m_c1 = sqrt(3) m_alt r a/(2 r_c1 l_sh1),
    m_c2 = sqrt(3) m_alt L r a/(8 r_c2 l_sh2)."""
    m_rot, m_alt, r, a, rc, l_sh, lam = 2.15, 0.94, 0.04, 0.09, 0.03, 0.2, 0.04 / 0.135
    # the JSON keeps 12 significant digits (format.py): compare to 1e-11
    data = balance_engine(EXAMPLES / "paper_inline3.toml").to_dict()
    assert data["counterweight"]["mass_kg"] == pytest.approx(
        math.sqrt(3) * m_rot * r / (4 * rc), rel=1e-11
    )
    assert data["primary_shafts"]["mass_kg"] == pytest.approx(
        math.sqrt(3) * m_alt * r * a / (2 * rc * l_sh), rel=1e-11
    )
    assert data["secondary_shafts"]["mass_kg"] == pytest.approx(
        math.sqrt(3) * m_alt * lam * r * a / (8 * rc * l_sh), rel=1e-11
    )


def test_inline3_optimal_angle_is_30_degrees() -> None:
    """docs/references.md: the alpha that gives Table 2 is 30 deg, the optimum for 120-deg
    cranks."""
    data = balance_engine(EXAMPLES / "paper_inline3.toml", angle="optimal").to_dict()
    assert data["counterweight"]["angle_deg"] == pytest.approx(30.0, abs=1e-9)
    assert round(data["counterweight"]["mass_kg"], 4) == 1.2413


def test_inline3_other_angle_leaves_a_force() -> None:
    """Erratum: Eq. 11 solves one equation only. At alpha = 0 the paper's formula gives
    m_c = sqrt(3) m_rot r/(4 r_c cos 30) = 1.4333 kg, which cancels the couple's x-part but
    leaves a force: equal counterweights at alpha != 30 deg cannot cancel both. The solver
    reports the residual instead of hiding it."""
    study = balance_engine(EXAMPLES / "paper_inline3.toml", angle=0.0)
    rotating = study.result.residual("rotating")
    assert rotating.force_after > 100.0
    assert any("cannot balance" in note for note in study.result.notes)


def test_v4_table5() -> None:
    data = balance_engine(EXAMPLES / "paper_v4.toml").to_dict()
    assert round(data["counterweight"]["mass_kg"], 3) == 1.700, (
        "Appl. Sci. 2021, Table 5: m_c = 1.700 kg"
    )
    secondary = data["secondary_shafts"]
    assert secondary["mass_kg"] == pytest.approx(0.1299, rel=0.015), (
        "Appl. Sci. 2021, Table 5: m_c2 = 0.1299 kg within 1.5 %: "
        "we get sqrt(2) lam m_alt r/(4 r_c2) = 0.1313 (each shaft one mass mid-shaft, "
        "the force case); docs/references.md finds no reading that gives the printed "
        "digits, so 1 % is what the print supports"
    )
    assert secondary["mass_kg"] == pytest.approx(
        math.sqrt(2) * (0.04 / 0.135) * 0.94 * 0.04 / (4 * 0.03), rel=1e-12
    )


def test_v4_primary_shafts_erratum() -> None:
    """Table 5 prints m_c1 = 0.3948 kg on both a co- and a counter-rotating shaft; the
    checked reading gives 0.3988 = a m_alt r / (sqrt(2) r_c1 l_sh1). But the primary of a
    90-degree V pair is a purely forward (co-rotating) phasor of one cylinder's force
    (textbook), so the couple of this V4 is a rotating couple of a m_alt r w^2: it needs a
    co-rotating shaft of 0.564 kg per mass and no counter-rotating shaft at all. The pair
    of Table 5 would leave a residual couple (V4_TABLE5_PAIR_LEAVES above), so we do not
    reproduce it."""
    study = balance_engine(EXAMPLES / "paper_v4.toml")
    data = study.to_dict()
    co, counter = data["primary_shafts"]["shafts"]
    a, m_alt, r, rc, l_sh = 0.09, 0.94, 0.04, 0.03, 0.2
    assert co["mass_kg"] == pytest.approx(a * m_alt * r / (rc * l_sh), rel=1e-12)
    assert counter["masses"] == [], "nothing counter-rotating to cancel"
    assert data["residual"]["order1_moment_Nm"] == 0.0
