"""VR engines and Ws built from VR banks (issue 17, item 1; docs/engine_file.md, "VR and W
from VR banks"): the layout and numbering, the crank from the firing order with the top
dead centre of an offset cylinder, the published VR6 pin split, and the free forces and
couples against hand calculations:

- every cylinder written out by hand (bank, offset, axial place, and the pin angle
  beta + asin(e/(l+r)) - t of even firing), its inertia force taken from a Fourier
  analysis of the closed-form piston position s = r cos psi + sqrt(l^2 - (e - r sin psi)^2)
  done here (the acceleration harmonics are -(n w)^2 times the position harmonics), summed;
- the VR6 at even firing: orders 1 and 2 vanish because each row's three cylinders fire
  120 deg apart (their pins are 120 deg apart), order 3 in closed form;
- the same VR6 entered the old way, as six custom throws with hand-computed angles;
- the exact time-domain residual (shaking.exact_time_domain).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from crankbalance.errors import InputError
from crankbalance.io.engine_file import list_presets, load_engine
from crankbalance.physics.model import EngineModel, standard_layout, vr_rows
from crankbalance.physics.shaking import exact_time_domain, free_forces
from crankbalance.schema.engine import spec_from_dict
from crankbalance.studies.build import build_model

DEG = math.pi / 180
ORDERS = 8
#: samples of the hand Fourier analysis over one revolution
SAMPLES = 256

VR6 = {
    "name": "VR6 by hand",
    "speed": "6000 rpm",
    "crank_train": {
        "layout": "vr",
        "cylinders": 6,
        "firing_order": [1, 5, 3, 6, 2, 4],
        "crank_radius": "45.15 mm",
        "rod_length": "164 mm",
        "crank_pitch": "45 mm",
        "bank_angle": "15 deg",
        "bore_offset": "12.5 mm",
    },
    "masses": {"reciprocating": "0.8 kg", "rotating": "1.1 kg"},
}


def spec(data: dict[str, Any], **train: Any) -> Any:
    out = {**data, "crank_train": {**data["crank_train"], **train}}
    for key in [k for k, v in train.items() if v is None]:
        del out["crank_train"][key]
    return spec_from_dict(out)


# --------------------------------------------------------------------------- hand reference
def position_harmonics(r: float, l: float, e: float) -> np.ndarray:
    """S_n, n = -ORDERS..ORDERS, of s(psi) = sum S_n exp(i n psi), by the FFT of samples of
    the closed form (written here, not taken from crankbalance.physics.kinematics)."""
    psi = 2 * np.pi * np.arange(SAMPLES) / SAMPLES
    s = r * np.cos(psi) + np.sqrt(l**2 - (e - r * np.sin(psi)) ** 2)
    c = np.fft.fft(s) / SAMPLES
    return np.array([c[n % SAMPLES] for n in range(-ORDERS, ORDERS + 1)])


def hand_phasors(
    table: list[tuple[float, float, float, float, float]], r: float, l: float, w: float
) -> tuple[np.ndarray, ...]:
    """Forward and backward phasors of force and couple, orders 1..ORDERS, of cylinders
    given as rows (mass [kg], pin angle [rad], bank [rad], offset [m], axial place [m]).

    The inertia force of a cylinder on the block is -m a e^{i beta} with
    a(theta) = w^2 s''(psi), psi = theta + phi - beta; its e^{i n theta} part is
    m (n w)^2 S_n e^{i[n(phi - beta) + beta]} and its e^{-i n theta} part
    m (n w)^2 S_-n e^{i[-n(phi - beta) + beta]}."""
    out = [np.zeros(ORDERS, complex) for _ in range(4)]
    for m, phi, beta, e, y in table:
        s = position_harmonics(r, l, e)
        for n in range(1, ORDERS + 1):
            k = m * (n * w) ** 2
            fwd = k * s[ORDERS + n] * np.exp(1j * (n * (phi - beta) + beta))
            bwd = k * s[ORDERS - n] * np.exp(1j * (-n * (phi - beta) + beta))
            out[0][n - 1] += fwd
            out[1][n - 1] += bwd
            out[2][n - 1] += y * fwd
            out[3][n - 1] += y * bwd
    return tuple(out)


def vr6_by_hand(e: float, split: float | None = None) -> list[tuple[float, ...]]:
    """The VR6 of :data:`VR6` written out cylinder by cylinder: odd cylinders in row A
    (-7.5 deg, offset -e), even in row B (+7.5 deg, +e), 45 mm apart from the crank's
    mid-point; firing order 1-5-3-6-2-4 every 120 deg after cylinder 1, which is at top dead
    centre at crank angle d1 = asin(-e/(l+r)); each pin at beta + asin(e/(l+r)) - d1 - t
    (or, given a split, at -t -+ split/2, turned so that cylinder 1's pin is at -7.5 deg,
    where even firing puts it)."""
    r, l, p = 0.04515, 0.164, 0.045
    fire = {1: 0, 5: 120, 3: 240, 6: 360, 2: 480, 4: 600}
    first = math.asin(-e / (l + r))
    rows = []
    for c in range(1, 7):
        sign = -1 if c % 2 else 1
        beta = sign * 7.5 * DEG
        ec = sign * e
        if split is None:
            phi = beta + math.asin(ec / (l + r)) - first - fire[c] * DEG
        else:
            phi = sign * split / 2 - fire[c] * DEG + (split / 2 - 7.5 * DEG)
        rows.append((0.8, phi, beta, ec, (c - 3.5) * p))
    return rows


def assert_phasors(model: EngineModel, hand: tuple[np.ndarray, ...], what: str) -> None:
    got = free_forces(model, ORDERS)
    scale = float(model.reciprocating_mass.max() * model.crank_radius * model.speed**2)
    names = ("force forward", "force backward", "couple forward", "couple backward")
    ours = (got.force_forward, got.force_backward, got.couple_forward, got.couple_backward)
    for name, a, b in zip(names, ours, hand, strict=True):
        unit = scale if name.startswith("force") else scale * 0.1
        worst = float(np.abs(a - b).max()) / unit
        assert worst < 1e-9, f"{what}: {name} differs from the hand sum by {worst:.2e} of m r w^2"


# --------------------------------------------------------------------------- layout
def test_vr_numbering() -> None:
    """docs/engine_file.md numbering: VR cylinder k on throw k, odd in row A (-v/2)."""
    pos, throw_of, banks = standard_layout("vr", 6, 15 * DEG, 0.045)
    assert throw_of.tolist() == list(range(6))
    assert np.allclose(np.degrees(banks), [-7.5, 7.5] * 3)
    assert np.allclose(pos, (np.arange(6) - 2.5) * 0.045)
    assert vr_rows(6).tolist() == [-1, 1, -1, 1, -1, 1]


def test_w_from_vr_numbering() -> None:
    """W from VR banks: bank 1 (-V/2) holds 1..n/2, bank 2 (+V/2) n/2+1..n, rows at -+v/2
    about each bank's centre, cylinders k and k + n/2 at one axial place."""
    pos, throw_of, banks = standard_layout("w", 12, 72 * DEG, 0.046, vr_angle=15 * DEG)
    assert throw_of.tolist() == list(range(12))
    assert np.allclose(np.degrees(banks), [-43.5, -28.5] * 3 + [28.5, 43.5] * 3)
    assert np.allclose(pos[:6], pos[6:]) and np.allclose(pos[:6], (np.arange(6) - 2.5) * 0.046)
    assert vr_rows(12, 2).tolist() == [-1, 1] * 6
    # a broad-arrow W is unchanged: three banks on n/3 pins
    _, throw_of, banks = standard_layout("w", 12, 60 * DEG, 0.1)
    assert throw_of.tolist() == [0, 1, 2, 3] * 3


def test_bore_offset_sign_from_the_geometry() -> None:
    """The sign of each row's offset from the drawing: both rows' bore axes pass through a
    point D below the crank axis (away from the heads), D = bore_offset / sin(v/2). The
    wrist pin, found on that line at the rod length from the crankpin, is where
    kinematics.piston_position puts it with the model's cylinder_offset."""
    from crankbalance.physics.kinematics import piston_position

    model = build_model(load_engine("vr6"))
    r, l = model.crank_radius, model.rod_length
    depth = 0.0125 / math.sin(7.5 * DEG)
    meet = np.array([0.0, -depth])  # (x, z)
    for c in (0, 1):  # row A, row B
        beta = float(model.cylinder_bank[c])
        axis = np.array([math.sin(beta), math.cos(beta)])
        foot = meet - (meet @ axis) * axis  # foot of the perpendicular from the crank axis
        for crank in np.linspace(0, 2 * np.pi, 13):
            pin = r * np.array([math.sin(crank), math.cos(crank)])
            # |foot + s axis - pin| = l, the root away from the crank
            b = (foot - pin) @ axis
            q = (foot - pin) @ (foot - pin) - l**2
            s_geo = -b + math.sqrt(b * b - q)
            s_model = piston_position(crank - beta, r, l, model.cylinder_offset[c])
            assert s_geo == pytest.approx(float(s_model), abs=1e-12), (c, crank)


# --------------------------------------------------------------------------- crank
def test_vr6_pin_split_is_the_published_22_deg() -> None:
    """At even firing the two rows' pins are split by v + 2 asin(e/(l+r)): 15 deg +
    2 asin(12.5/209.15) = 21.85 deg with the preset's (assumed) rod and bore offset, the
    published 22 deg (Wikipedia 2012, Engine Labs 2021) to 0.15 deg."""
    model = build_model(spec(VR6))
    angles = np.degrees(model.throw_angle)
    split = (angles[3] - angles[2] + 180) % 360 - 180  # cylinders 3 (row A) and 4 (row B)
    expected = 15 + 2 * math.degrees(math.asin(12.5 / (164 + 45.15)))
    assert split == pytest.approx(expected, abs=1e-9)
    assert abs(split - 22.0) < 0.2, f"VR6 split {split:.3f} deg vs the published 22 deg"
    # the preset gives the maker's 22 deg itself
    preset = build_model(load_engine("vr6"))
    a = np.degrees(preset.throw_angle)
    assert (a[3] - a[2]) % 360 == pytest.approx(22.0, abs=1e-9)


def test_pin_split_places_the_pins_as_given() -> None:
    """With pin_split the pins sit split/2 either side of the angle a cylinder on the
    centre line needs: -t -+ split/2, the rows' offsets notwithstanding."""
    model = build_model(spec(VR6, pin_split="22 deg"))
    hand = [row[1] for row in vr6_by_hand(0.0125, 22 * DEG)]
    gap = np.remainder(model.throw_angle - np.array(hand) + np.pi, 2 * np.pi) - np.pi
    assert np.abs(gap).max() < 1e-12


@pytest.mark.parametrize(
    ("preset", "half", "split"),
    [("w12-vw", 6, 72 - 60), ("w8", 4, 72 - 90), ("w16", 8, 0)],
)
def test_w_pairs_split_by_bank_angle_minus_firing_delay(preset: str, half: int, split: int) -> None:
    """Cylinders k and k + n/2 sit in the same row of their banks, so at even firing their
    pins differ by V minus the delay between their firings (mod 360): 72 - 60 = 12 deg for
    the W12 (the split Audi 2011 publishes), 72 - 90 = -18 deg for the W8, and for the
    W16, whose published order fires cylinder k + 8 90 or 450 deg after k, 90 - 90 = 0:
    one shared pin (hand values)."""
    model = build_model(load_engine(preset))
    a = np.degrees(model.throw_angle)
    gap = (a[half:] - a[:half] + 180) % 360 - 180
    assert np.allclose(gap, split, atol=1e-9), gap


def test_w12_firing_is_even() -> None:
    """Every cylinder of the W12 preset reaches its top dead centre (crank angle
    asin(e/(l+r)) past its axis) 60 deg after the one before it in the firing order."""
    model = build_model(load_engine("w12-vw"))
    e = np.array([-0.0125, 0.0125] * 6)  # rows A and B of both banks
    assert np.allclose(model.cylinder_offset, e)
    tdc = np.arcsin(e / (model.rod_length + model.crank_radius))
    fire = np.mod(model.cylinder_bank + tdc - model.cylinder_angle, 4 * np.pi)
    order = np.array(model.firing_order) - 1
    steps = np.diff(np.degrees(fire[order])) % 360
    assert np.allclose(steps, 60.0, atol=1e-9), steps


# --------------------------------------------------------------------------- forces
@pytest.mark.parametrize("e", [0.0, 0.0125])
def test_vr6_equals_six_custom_throws(e: float) -> None:
    """The VR6 is the custom engine of six throws at the hand angles of vr6_by_hand (the
    old way of entering it; its offsets as cylinder_offsets, -+e): the same phasors,
    rotating masses and crank to round-off."""
    vr = build_model(spec(VR6, bore_offset=f"{e * 1e3:g} mm"))
    rows = vr6_by_hand(e)
    throws = [
        {"position": f"{(c - 3.5) * 45:g} mm", "angle": f"{row[1] / DEG:.12f} deg"}
        | {"banks": [f"{row[2] / DEG:g} deg"]}
        for c, row in enumerate(rows, start=1)
    ]
    train = {k: v for k, v in VR6["crank_train"].items() if k in ("crank_radius", "rod_length")}
    train |= {"cylinder_offsets": [f"{row[3] * 1e3:g} mm" for row in rows]}
    custom = build_model(
        spec_from_dict(
            {
                **VR6,
                "crank_train": {"layout": "custom", "firing_order": [1, 5, 3, 6, 2, 4], **train}
                | {"throw": throws},
            }
        )
    )
    a, b = free_forces(vr, ORDERS), free_forces(custom, ORDERS)
    for name in ("force_forward", "force_backward", "couple_forward", "couple_backward"):
        assert np.allclose(getattr(a, name), getattr(b, name), rtol=1e-9, atol=1e-6), name
    assert a.rotating_couple == pytest.approx(b.rotating_couple, abs=1e-6)
    gap = np.remainder(vr.throw_angle - custom.throw_angle + np.pi, 2 * np.pi)
    assert np.abs(gap - np.pi).max() < 1e-12
    assert np.allclose(vr.cylinder_offset, custom.cylinder_offset, atol=1e-15)


def test_vr6_even_firing_orders_1_and_2_vanish() -> None:
    """Each row's three cylinders fire 0, 120, 240 deg apart (mod 360), so their pins are
    120 deg apart and the forces of orders 1 and 2 sum to zero; the couples do not (the
    two rows' pins of one inline-six throw pair are split and stand at -+y)."""
    model = build_model(spec(VR6))
    f = free_forces(model, ORDERS)
    scale = 0.8 * model.crank_radius * model.speed**2
    assert f.force_amplitude[:2].max() < 1e-9 * scale
    assert f.moment_amplitude[0] > 0.01 * scale * 0.045


@pytest.mark.parametrize("e", [0.0, 0.0125])
def test_vr6_matches_hand_sum(e: float) -> None:
    """Every order's phasors of the VR6, with and without its bore offset, are the
    cylinder-by-cylinder hand sum."""
    model = build_model(spec(VR6, bore_offset=f"{e * 1e3:g} mm"))
    assert np.allclose(model.cylinder_offset, [-e, e] * 3)
    hand = hand_phasors(vr6_by_hand(e), model.crank_radius, model.rod_length, model.speed)
    assert_phasors(model, hand, f"VR6 with bore offset {e * 1e3:g} mm")


def test_vr6_equals_six_hand_throws_with_offsets() -> None:
    """The VR6 with its offset rows is the model of six throws written by hand (angles,
    banks, offsets and places of vr6_by_hand): the same phasors and the same curves."""
    vr = build_model(spec(VR6))
    rows = vr6_by_hand(0.0125)
    by_hand = EngineModel(
        name="six throws by hand",
        speed=vr.speed,
        kinematics="exact",
        crank_radius=0.04515,
        rod_length=0.164,
        strokes=4,
        throw_angle=np.array([row[1] for row in rows]),
        throw_position=np.array([row[4] for row in rows]),
        throw_rotating_mass=np.full(6, 1.1),
        cylinder_throw=np.arange(6),
        cylinder_bank=np.array([row[2] for row in rows]),
        reciprocating_mass=np.full(6, 0.8),
        cylinder_offset=np.array([row[3] for row in rows]),
        cylinder_axial=np.zeros(6),
        cylinder_rotating_mass=np.zeros(6),
        firing_order=(1, 5, 3, 6, 2, 4),
    )
    a, b = free_forces(vr, ORDERS), free_forces(by_hand, ORDERS)
    for name in ("force_forward", "force_backward", "couple_forward", "couple_backward"):
        assert np.allclose(getattr(a, name), getattr(b, name), rtol=1e-12, atol=1e-9), name
    assert a.rotating_force == pytest.approx(b.rotating_force, abs=1e-9)
    assert a.rotating_couple == pytest.approx(b.rotating_couple, abs=1e-9)


def test_vr6_order_3_closed_form() -> None:
    """Order 3 of the VR6 at even firing: each row's cylinders fire at multiples of 120 deg
    after cylinder 1 (at top dead centre at crank angle d1 = -d, d = asin(e/(l+r))), so
    F3+ = 3 m (3w)^2 [S3(-e) e^{i(3(-d - d1) - v/2)} + S3(e) e^{i(3(d - d1) + v/2)}] and
    F3- = 3 m (3w)^2 [S-3(-e) e^{i(-3(-d - d1) - v/2)} + S-3(e) e^{i(-3(d - d1) + v/2)}],
    S_n the piston position's harmonics (hand FFT); zero without offset (no odd harmonics)."""
    r, l, e, v = 0.04515, 0.164, 0.0125, 15 * DEG
    model = build_model(spec(VR6))
    w = model.speed
    d = math.asin(e / (l + r))
    d1 = -d
    sa, sb = position_harmonics(r, l, -e), position_harmonics(r, l, e)
    k = 3 * 0.8 * (3 * w) ** 2
    row_a, row_b = np.exp(1j * (3 * (-d - d1) - v / 2)), np.exp(1j * (3 * (d - d1) + v / 2))
    fwd = k * (sa[ORDERS + 3] * row_a + sb[ORDERS + 3] * row_b)
    row_a, row_b = np.exp(1j * (-3 * (-d - d1) - v / 2)), np.exp(1j * (-3 * (d - d1) + v / 2))
    bwd = k * (sa[ORDERS - 3] * row_a + sb[ORDERS - 3] * row_b)
    f = free_forces(model, ORDERS)
    scale = 0.8 * r * w**2
    assert abs(f.force_forward[2] - fwd) < 1e-9 * scale
    assert abs(f.force_backward[2] - bwd) < 1e-9 * scale
    assert abs(fwd) > 1e-4 * scale  # the offset's odd harmonic is there
    plain = free_forces(build_model(spec(VR6, bore_offset=None)), ORDERS)
    assert plain.force_amplitude[2] < 1e-9 * scale


def w_by_hand(preset: str) -> tuple[EngineModel, list[tuple[float, ...]]]:
    """A W preset cylinder by cylinder: rows -V/2 -+ v/2 (bank 1, cylinders 1..n/2) and
    +V/2 -+ v/2 (bank 2), odd cylinders of a bank in row A (offset -e), pairs at one place,
    fired every 720/n deg in the preset's order after the first, which is at top dead
    centre at crank angle d1 = asin(e1/(l+r)); pins at beta + asin(e/(l+r)) - d1 - t."""
    data = load_engine(preset)
    ct = data.crank_train
    model = build_model(data)
    n, half = ct.cylinder_count, ct.cylinder_count // 2
    assert ct.bank_angle is not None and ct.vr_angle is not None and ct.crank_pitch
    fire = {c: k * 4 * math.pi / n for k, c in enumerate(ct.firing_order or [])}
    one = (ct.firing_order or [1])[0]  # row A or B of the first to fire, by its place k
    e1 = (-1 if ((one - 1) % half) % 2 == 0 else 1) * ct.bore_offset
    first = math.asin(e1 / (ct.rod_length + ct.crank_radius))
    rows = []
    for c in range(1, n + 1):
        k = (c - 1) % half  # place along the crank
        sign = -1 if k % 2 == 0 else 1
        centre = (-1 if c <= half else 1) * ct.bank_angle / 2
        beta = centre + sign * ct.vr_angle / 2
        e = sign * ct.bore_offset
        phi = beta + math.asin(e / (ct.rod_length + ct.crank_radius)) - first - fire[c]
        m = float(model.reciprocating_mass[c - 1])
        rows.append((m, phi, beta, e, (k - (half - 1) / 2) * ct.crank_pitch))
    return model, rows


@pytest.mark.parametrize("preset", ["w8", "w12-vw", "w16"])
def test_w_presets_match_hand_sum(preset: str) -> None:
    model, rows = w_by_hand(preset)
    hand = hand_phasors(rows, model.crank_radius, model.rod_length, model.speed)
    assert_phasors(model, hand, preset)


def test_vr6_preset_matches_hand_sum_with_its_pin_split() -> None:
    """The preset gives the maker's 22 deg split: pins at -t -+ 11 deg, offsets -+12.5 mm."""
    model = build_model(load_engine("vr6"))
    rows = [
        (float(model.reciprocating_mass[0]), *row[1:4], (c - 3.5) * 0.045)
        for c, row in enumerate(vr6_by_hand(0.0125, 22 * DEG), start=1)
    ]
    hand = hand_phasors(rows, model.crank_radius, model.rod_length, model.speed)
    assert_phasors(model, hand, "vr6 preset")


@pytest.mark.parametrize("preset", ["VR6 at even firing", "vr6", "w8", "w12-vw", "w16"])
def test_phasors_against_exact_time_domain(preset: str) -> None:
    """The phasors of 40 orders, summed into curves, are the force and couple of the
    exact slider-crank acceleration of every cylinder (shaking.exact_time_domain)."""
    model = build_model(spec(VR6) if preset.startswith("VR6") else load_engine(preset))
    orders = 40
    f = free_forces(model, orders)
    theta = np.linspace(0, 2 * np.pi, 97)
    turn = np.exp(1j * np.outer(theta, f.orders))
    force = turn @ f.force_forward + turn.conj() @ f.force_backward
    couple = turn @ f.couple_forward + turn.conj() @ f.couple_backward
    exact_force, exact_couple = exact_time_domain(model, theta)
    scale = float(model.reciprocating_mass.max() * model.crank_radius * model.speed**2)
    assert np.abs(force - exact_force).max() < 1e-9 * scale
    assert np.abs(couple - exact_couple).max() < 1e-9 * scale


# --------------------------------------------------------------------------- errors
@pytest.mark.parametrize(
    ("train", "field", "words"),
    [
        ({"w_type": "vr"}, "crank_train.w_type", "only used with layout 'w'"),
        ({"vr_angle": "15 deg"}, "crank_train.vr_angle", "w_type = 'vr'"),
        (
            {"pin_split": "22 deg", "throw_angles": ["0 deg"] * 6},
            "crank_train.pin_split",
            "not both",
        ),
        ({"pin_split": "200 deg"}, "crank_train.pin_split", "[0, 180)"),
        ({"bank_angle": None}, "crank_train.bank_angle", "required for layout 'vr'"),
        ({"cylinders": 1}, "crank_train.cylinders", "at least 2"),
        ({"bore_offset": "130 mm"}, "crank_train.bore_offset", "leaves no rod"),
        ({"bank_offsets": ["1 mm", "2 mm"]}, "crank_train.bank_offsets", "bore_offset"),
    ],
)
def test_vr_refusals(train: dict[str, Any], field: str, words: str) -> None:
    with pytest.raises(InputError) as info:
        spec(VR6, **train)
    assert info.value.field == field and words in info.value.allowed, info.value


def test_vr_keys_refused_elsewhere() -> None:
    inline = {**VR6, "crank_train": {**VR6["crank_train"], "layout": "inline"}}
    del inline["crank_train"]["bank_angle"]
    with pytest.raises(InputError) as info:
        spec_from_dict(inline)
    assert info.value.field == "crank_train.bore_offset"
    w = {**VR6, "crank_train": {**VR6["crank_train"], "layout": "w", "cylinders": 12}}
    w["crank_train"] |= {"w_type": "vr", "bank_angle": "72 deg"}
    with pytest.raises(InputError) as info:
        spec_from_dict(w)
    assert info.value.field == "crank_train.vr_angle" and "required" in info.value.allowed
    w["crank_train"] |= {"vr_angle": "15 deg", "cylinders": 9}
    with pytest.raises(InputError) as info:
        spec_from_dict(w)
    assert info.value.field == "crank_train.cylinders" and "even" in info.value.allowed


def test_presets_listed() -> None:
    names = list_presets()
    for name in ("vr6", "w8", "w12-vw", "w16", "w12"):
        assert name in names
