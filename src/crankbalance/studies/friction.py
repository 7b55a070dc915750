"""Bearing friction and the rotor test bench as studies of the registry (Hoem and Røsholm
2016, Sec. 4.2.1 and 5.2.5): the friction torque of a bearing under a constant plus a
rotating load, Coulomb (given a friction coefficient, or back-computed from a measured
torque) and hydrodynamic (``friction``), and the simulated spin-up, hold and required
torque of a rotor on the bench (``bench``)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import field
from typing import Any

from ..errors import InputError
from ..output.format import keyed
from ..physics import friction as fr
from ..physics.rotor_bench import BenchResult, BenchRotor
from ..records import record
from ..results import ResultMixin, require_finite, to_jsonable
from ..schema.settings import BenchOptions, FrictionOptions, given

FRICTION_SCHEMA = "crankbalance.friction/1"
BENCH_SCHEMA = "crankbalance.bench/2"
#: the mean-load methods of the Coulomb friction, in the order of the output
METHODS: tuple[fr.MeanLoadMethod, ...] = ("approximate", "cubic", "arithmetic")
#: JSON keys of the bench rotor (unit in a suffix)
ROTOR_KEYS: dict[str, str | tuple[str, float]] = {
    "mass": "mass_kg",
    "inertia": "inertia_kg_m2",
    "journal_diameter": "journal_diameter_m",
    "unbalance": "unbalance_kg_m",
    "bearing_positions": "bearing_positions_m",
    "mass_position": "mass_position_m",
    "unbalance_position": "unbalance_position_m",
    "gravity": "gravity_m_s2",
}
#: the settings of the hydrodynamic bearing
HYDRODYNAMIC = ("bearing_length", "clearance", "eccentricity", "attitude_angle")


def _checked(payload: dict[str, Any]) -> dict[str, Any]:
    out = to_jsonable(payload)
    assert isinstance(out, dict)
    return out


@record(repr=False)
class FrictionResult(ResultMixin):
    """The friction of one bearing.

    Attributes
    ----------
    constant_load, rotating_load : float
        [N].
    journal_diameter : float
        [m].
    eccentricity : float
        Of the hydrodynamic bearing [-].
    coulomb : list of dict
        Per mean-load method: the mean load [N] and the torque [N m] (with a friction
        coefficient) or the friction coefficient (with a measured torque).
    hydrodynamic : dict, optional
        Petroff and journal-bearing torques [N m].
    """

    constant_load: float
    rotating_load: float
    journal_diameter: float
    eccentricity: float
    coulomb: list[dict[str, float | str]]
    hydrodynamic: dict[str, float] | None

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.friction/1``."""
        return _checked(
            {
                "schema": FRICTION_SCHEMA,
                "inputs": {
                    "constant_load_N": self.constant_load,
                    "rotating_load_N": self.rotating_load,
                    "journal_diameter_m": self.journal_diameter,
                },
                "coulomb": self.coulomb,
                "hydrodynamic": self.hydrodynamic,
            }
        )


def friction(settings: FrictionOptions) -> FrictionResult:
    """Bearing friction torque under a constant plus a rotating load (Hoem and Røsholm
    2016, Sec. 4.2.1): the rotating load given, or an unbalance at a speed; Coulomb friction
    by the three mean-load methods with a friction coefficient (or the coefficient of a
    measured torque), and the hydrodynamic bearing's torques with a viscosity."""
    o = settings
    typed = given(o)
    if o.journal_diameter is None:
        raise InputError("journal_diameter", None, "is required, e.g. '20 mm'")
    if "rotating_load" in typed and "unbalance" in typed:
        raise InputError("unbalance", o.unbalance, "give either --rotating-load or --unbalance")
    if o.unbalance is not None:
        if o.speed is None:
            raise InputError("speed", None, "is needed with --unbalance")
        rotating = o.unbalance * o.speed**2
    else:
        rotating = o.rotating_load or 0.0
    constant = o.load
    if o.torque is None and o.friction_coefficient is None and o.viscosity is None:
        raise InputError(
            "friction_coefficient",
            None,
            "give --friction-coefficient, --torque or the hydrodynamic options",
        )
    acts = {name: o.viscosity is not None for name in HYDRODYNAMIC}
    acts["speed"] = o.viscosity is not None or o.unbalance is not None
    for name, used in acts.items():
        if name in typed and not used:
            raise InputError(
                name,
                getattr(o, name),
                "only acts on the hydrodynamic bearing (with --viscosity), or for --speed "
                "with --unbalance",
            )
    if (o.torque is not None or o.friction_coefficient is not None) and not (
        constant > 0 or rotating > 0
    ):
        raise InputError(
            "load",
            o.load,
            "the bearing carries no load: give --load (e.g. "
            "the rotor weight) and/or --rotating-load or --unbalance",
        )
    rows: list[dict[str, float | str]] = []
    for method in METHODS:
        mean = (
            float(fr.mean_equivalent_load(constant, rotating, method))
            if constant + rotating > 0
            else 0.0
        )
        row: dict[str, float | str] = {"method": method, "mean_load_N": mean}
        if o.friction_coefficient is not None:
            row["torque_Nm"] = float(
                fr.friction_torque(o.friction_coefficient, mean, o.journal_diameter)
            )
        if o.torque is not None:
            mu = fr.friction_coefficient_from_torque(
                o.torque, constant, rotating, o.journal_diameter, method
            )
            row["friction_coefficient"] = float(mu)
        rows.append(row)
    hydro: dict[str, float] | None = None
    if o.viscosity is not None:
        if o.speed is None or o.bearing_length is None or o.clearance is None:
            raise InputError(
                "viscosity",
                o.viscosity,
                "the hydrodynamic bearing needs --speed, --bearing-length, --clearance",
            )
        args = (o.viscosity, o.journal_diameter, o.bearing_length, o.clearance, o.speed)
        hydro = {
            "petroff_torque_Nm": float(fr.petroff_torque(*args)),
            "journal_bearing_torque_Nm": float(
                fr.journal_bearing_torque(
                    *args, o.eccentricity, constant + rotating, o.attitude_angle
                )
            ),
        }
    result = FrictionResult(constant, rotating, o.journal_diameter, o.eccentricity, rows, hydro)
    result.to_dict()  # checked finite
    return result


@record(repr=False)
class BenchStudy(ResultMixin):
    """Runs of the simulated rotor test bench, one per set speed.

    Attributes
    ----------
    rotor : BenchRotor
    runs : list of BenchResult
        In the order of the speeds (the time histories of each run included).
    """

    rotor: BenchRotor
    runs: list[BenchResult] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract ``crankbalance.bench/2``."""
        return _checked(
            {
                "schema": BENCH_SCHEMA,
                "rotor": keyed(self.rotor.to_dict(), ROTOR_KEYS),
                "runs": [
                    {
                        "speed_rad_s": r.settings.speed,
                        "required_torque_Nm": r.required_torque,
                        "mean_friction_torque_Nm": r.mean_friction_torque,
                        "friction_power_W": r.friction_power,
                        "final_speed_rad_s": r.final_speed,
                    }
                    for r in self.runs
                ],
            }
        )


def bench(
    settings: BenchOptions, *, progress: Callable[[int, int], Any] | None = None
) -> BenchStudy:
    """The simulated rotor test bench (Hoem and Røsholm 2016, Sec. 5.2.5): a PI-controlled
    spin-up to each set speed, a hold, the required torque and the bearing friction; the
    defaults are the thesis' test rotor (Appendix E, balanced case 1). Every run is checked
    before the first starts; ``progress(done, total)`` is called after each."""
    from ..physics.rotor_bench import BenchSettings, run_bench

    o = settings
    if o.friction_coefficient is None:
        raise InputError(
            "friction_coefficient", None, "is required: the Coulomb friction of each bearing"
        )
    rotor = BenchRotor(
        mass=o.mass,
        inertia=o.inertia,
        journal_diameter=o.journal_diameter,
        friction_coefficient=o.friction_coefficient,
        unbalance=o.unbalance,
    )
    runs = [
        BenchSettings(
            speed=speed,
            ramp_time=o.ramp_time,
            hold_time=o.hold_time,
            proportional_gain=o.kp,
            integral_gain=o.ki,
        )
        for speed in o.speed
    ]
    results: list[BenchResult] = []
    for k, run in enumerate(runs):
        results.append(run_bench(rotor, run))
        require_finite(results[-1], f"runs[{k}]")
        if progress is not None:
            progress(k + 1, len(runs))
    return BenchStudy(rotor, results)
