"""Vehicles on random roads against closed forms derived here, not by the simulator (issue 27).

A road whose displacement PSD is ``Gd(n) = Gd(n0) (n/n0)^-2`` (every ISO 8608 class) has a
white velocity seen by the wheel: ``G_v = 4 pi^2 Gd(n0) n0^2 V`` [m^2/s^2 per Hz] over the
temporal band ``V n`` of the road's spatial band. A linear vehicle on it has exact rms
responses, computed here from equations of motion written out by hand in this file (not
the package's ``linear_matrices`` or ``frequency_response``):

- ``var(y) = integral over the band of Y(f)^H S(f) Y(f) df``: ``Y`` the response of ``y``
  to each wheel's road, ``S`` the road's cross-spectral matrix (the rear wheels see the
  front wheels' road ``wheelbase/V`` later; the right track has the isotropic coherence
  ``gamma(n) = x K_1(x)``, ``x = 2 pi n b``, with the left, Kamash and Robson 1978);
- ``scipy.linalg.solve_continuous_lyapunov`` for a white velocity over all frequencies,
  which the band integral must reproduce on a wide band (a check of the integral itself),
  and which the simulator must reproduce on a road whose band reaches far above the
  vehicle's modes.

The simulator runs from scenario tables at default settings (``mrsus simulate``'s path):
``dt``, output rate, the ISO road's point spacing and its spline.

The quarter car of the issue (m_s 320 kg, m_u 40 kg, k 22 kN/m, k_t 190 kN/m, c 1500 N s/m,
no tire damping) on ISO class C at 50 km/h: rms body acceleration 1.1713 m/s^2, rms stroke
9.176 mm, DLC 0.1776 over ISO's band 0.011-2.83 cycle/m. At the former default spacing of
0.3 m the road stopped at 1.67 cycle/m and the simulated DLC came out 7.5 % low.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np
import pytest
from scipy.linalg import solve_continuous_lyapunov
from scipy.special import k1

from mrsuspension.dampers import LinearViscous
from mrsuspension.engine.simulate import Simulation
from mrsuspension.excitation import RoadSpectrum, synthesise_road
from mrsuspension.scenario import Scenario
from mrsuspension.vehicle import QuarterCar

G = 9.81
N0 = 0.1  # ISO 8608 reference spatial frequency [cycle/m]
CLASS_C = 256e-6  # Gd(n0) of class C [m^3]
ISO_BAND = (0.011, 2.83)  # cycle/m
TOLERANCE = 0.015  # the issue's 1.5 %

#: the issue's quarter car
ISSUE_CAR = {"sprung_mass": 320.0, "unsprung_mass": 40.0, "suspension_stiffness": 22_000.0,
             "tire_stiffness": 190_000.0, "tire_damping": 0.0}  # fmt: skip
ISSUE_DAMPING = 1500.0
#: the issue's closed-form values (ISO class C, 50 km/h, ISO's band)
ISSUE_VALUES = {"rms_body_acceleration": 1.1713, "rms_stroke": 9.176e-3, "DLC": 0.1776}


def velocity_psd(level: float, speed: float) -> float:
    """One-sided PSD [m^2/s^2 per Hz] of the road velocity of an ``n^-2`` road at ``speed``."""
    return 4.0 * math.pi**2 * level * N0**2 * speed


@dataclass(frozen=True)
class Linear:
    """``M q'' + C q' + K q = Kr z_r + Cr z_r'`` (``z_r`` one road per wheel) and outputs
    ``y = Oq q + Ov q' + Oa q'' + Rq z_r + Rv z_r'`` (one row per output)."""

    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    Kr: np.ndarray
    Cr: np.ndarray
    names: tuple[str, ...]
    Oq: np.ndarray
    Ov: np.ndarray
    Oa: np.ndarray
    Rq: np.ndarray
    Rv: np.ndarray

    def response(self, f: np.ndarray) -> np.ndarray:
        """``Y[k, i, j]``: output ``i`` per unit road displacement at wheel ``j``, at ``f[k]``."""
        w = 2.0 * math.pi * f[:, None, None]
        dyn = self.K - w**2 * self.M + 1j * w * self.C
        q = np.linalg.solve(dyn, self.Kr + 1j * w * self.Cr)
        return (self.Oq - w**2 * self.Oa + 1j * w * self.Ov) @ q + self.Rq + 1j * w * self.Rv

    def state_space(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``x' = A x + B u``, ``y = Cy x`` with the road velocities ``u = z_r'`` (``Cr = 0``).

        States ``x = [e, q']`` with ``e = q - G z_r``, ``G = K^-1 Kr`` (the static
        deflection under the road): ``e' = q' - G u``, ``M q'' = -C q' - K e``. The outputs
        must not see a constant road: ``Oq G + Rq = 0``.
        """
        assert not np.any(self.Cr)
        assert not np.any(self.Rv)
        n = self.M.shape[0]
        minv = np.linalg.inv(self.M)
        static = np.linalg.solve(self.K, self.Kr)
        assert np.allclose(self.Oq @ static + self.Rq, 0.0, atol=1e-9)
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-minv @ self.K, -minv @ self.C]])
        B = np.vstack([-static, np.zeros_like(static)])
        Cy = np.hstack([self.Oq, self.Ov]) + self.Oa @ A[n:]
        return A, B, Cy


def quarter_car(ms: float, mu: float, k: float, kt: float, ct: float, c: float) -> Linear:
    """``q = [z_s, z_u]``; outputs body acceleration, stroke, dynamic tire force."""
    M = np.diag([ms, mu])
    K = np.array([[k, -k], [-k, k + kt]])
    C = np.array([[c, -c], [-c, c + ct]])
    Kr, Cr = np.array([[0.0], [kt]]), np.array([[0.0], [ct]])
    zero = np.zeros((3, 2))
    Oq, Ov, Oa = zero.copy(), zero.copy(), zero.copy()
    Oa[0, 0] = 1.0  # z_s''
    Oq[1] = [1.0, -1.0]  # stroke z_s - z_u
    Oq[2, 1], Ov[2, 1] = -kt, -ct  # F_T - static = k_t (z_r - z_u) + c_t (z_r' - z_u')
    Rq, Rv = np.array([[0.0], [0.0], [kt]]), np.array([[0.0], [0.0], [ct]])
    return Linear(M, C, K, Kr, Cr, ("acc", "stroke", "tire"), Oq, Ov, Oa, Rq, Rv)


def body_car(p: dict[str, float], corners: tuple[str, ...], damping: dict[str, float]) -> Linear:
    """A half or full car written out: body heave, pitch (and roll), one wheel per corner.

    A corner at ``(x, y)`` (``x`` forward of the centre of gravity, ``y`` to the left) moves
    the body by ``z + x theta + y phi`` there (nose up and left side up positive: the
    signs are this file's; rms values do not depend on them). An anti-roll bar of roll
    stiffness ``K`` [N m/rad] on an axle of track ``t`` is a spring ``K / t^2`` between the
    left and right strokes. Outputs per corner: body acceleration at the corner, stroke,
    dynamic tire force; then heave, pitch and roll accelerations.
    """
    full = len(corners) == 4
    nb = 3 if full else 2
    n = nb + len(corners)
    a, b = p["cg_to_front"], p["cg_to_rear"]
    inertia = [p["sprung_mass"], p["pitch_inertia"]] + ([p["roll_inertia"]] if full else [])
    M = np.diag(inertia + [p[f"{c.split('_')[0]}_unsprung_mass"] for c in corners])
    K, C = np.zeros((n, n)), np.zeros((n, n))
    Kr, Cr = np.zeros((n, len(corners))), np.zeros((n, len(corners)))
    strokes = []
    for j, corner in enumerate(corners):
        axle = corner.split("_")[0]
        x = a if axle == "front" else -b
        y = 0.0 if not full else (0.5 if corner.endswith("left") else -0.5) * p[f"{axle}_track"]
        d = np.zeros(n)  # stroke = body at the corner - wheel
        d[:nb] = [1.0, x, y][:nb]
        d[nb + j] = -1.0
        strokes.append(d)
        K += p[f"{axle}_suspension_stiffness"] * np.outer(d, d)
        C += damping[corner] * np.outer(d, d)
        kt, ct = p[f"{axle}_tire_stiffness"], p[f"{axle}_tire_damping"]
        K[nb + j, nb + j] += kt
        C[nb + j, nb + j] += ct
        Kr[nb + j, j], Cr[nb + j, j] = kt, ct
    if full:
        for axle, (left, right) in (("front", (0, 1)), ("rear", (2, 3))):
            rate = p[f"{axle}_anti_roll_stiffness"] / p[f"{axle}_track"] ** 2
            r = strokes[left] - strokes[right]
            K += rate * np.outer(r, r)
    rows = 3 * len(corners) + nb
    Oq, Ov, Oa = np.zeros((rows, n)), np.zeros((rows, n)), np.zeros((rows, n))
    Rq, Rv = np.zeros((rows, len(corners))), np.zeros((rows, len(corners)))
    names: list[str] = []
    for j, corner in enumerate(corners):
        axle = corner.split("_")[0]
        body = strokes[j].copy()
        body[nb + j] = 0.0
        Oa[3 * j] = body
        Oq[3 * j + 1] = strokes[j]
        kt, ct = p[f"{axle}_tire_stiffness"], p[f"{axle}_tire_damping"]
        Oq[3 * j + 2, nb + j], Ov[3 * j + 2, nb + j] = -kt, -ct
        Rq[3 * j + 2, j], Rv[3 * j + 2, j] = kt, ct
        names += [f"acc.{corner}", f"stroke.{corner}", f"tire.{corner}"]
    for i, dof in enumerate(("heave", "pitch", "roll")[:nb]):
        Oa[3 * len(corners) + i, i] = 1.0
        names.append(dof)
    return Linear(M, C, K, Kr, Cr, tuple(names), Oq, Ov, Oa, Rq, Rv)


def isotropic_gamma(n: np.ndarray, track: float) -> np.ndarray:
    """Coherence of two parallel tracks ``track`` apart on an ``n^-2`` road: ``x K_1(x)``."""
    x = 2.0 * math.pi * n * track
    return np.asarray(x * k1(x))


def band_rms(
    car: Linear,
    level: float,
    speed: float,
    band: tuple[float, float],
    *,
    delays: np.ndarray | None = None,
    tracks: np.ndarray | None = None,
    track_width: float = 0.0,
    points: int = 40_000,
) -> dict[str, float]:
    """RMS of every output of ``car`` on an ``n^-2`` road over ``band`` [cycle/m] at ``speed``.

    ``delays[j]`` [s]: wheel ``j`` sees the road of its track that much later;
    ``tracks[j]``: 0 left, 1 right (coherence :func:`isotropic_gamma` over ``track_width``).
    """
    f = np.geomspace(band[0] * speed, band[1] * speed, points)
    wheels = car.Kr.shape[1]
    delays = np.zeros(wheels) if delays is None else delays
    tracks = np.zeros(wheels, dtype=int) if tracks is None else tracks
    y = car.response(f) * np.exp(-2j * math.pi * f[:, None, None] * delays[None, None, :])
    per_track = np.stack([y[:, :, tracks == k].sum(axis=2) for k in (0, 1)], axis=2)
    gamma = isotropic_gamma(f / speed, track_width) if track_width > 0 else np.ones_like(f)
    power = np.abs(per_track[:, :, 0]) ** 2 + np.abs(per_track[:, :, 1]) ** 2
    power += 2.0 * gamma[:, None] * np.real(per_track[:, :, 0] * np.conj(per_track[:, :, 1]))
    g_disp = velocity_psd(level, speed) / (2.0 * math.pi * f) ** 2  # G_zr(f) [m^2/Hz]
    var = np.trapezoid(power * (g_disp * f)[:, None], np.log(f), axis=0)
    return dict(zip(car.names, np.sqrt(var), strict=True))


def lyapunov_rms(car: Linear, level: float, speed: float) -> dict[str, float]:
    """RMS of every output on a white road velocity over all frequencies (one wheel)."""
    A, B, Cy = car.state_space()
    # one-sided G_v per Hz is a two-sided intensity G_v / 2 per Hz on x' = A x + B w
    P = solve_continuous_lyapunov(A, -0.5 * velocity_psd(level, speed) * (B @ B.T))
    return dict(zip(car.names, np.sqrt(np.maximum(np.diag(Cy @ P @ Cy.T), 0.0)), strict=True))


def simulate(tables: dict[str, dict[str, object]]) -> dict[str, float]:
    (result,) = Scenario.from_dict(tables).run()
    return dict(result.measures())


# -- the references agree with each other -----------------------------------------------------
def test_band_integral_reproduces_lyapunov_on_a_wide_band() -> None:
    car = quarter_car(320.0, 40.0, 22e3, 190e3, 0.0, 1500.0)
    speed = 50.0 / 3.6
    exact = lyapunov_rms(car, CLASS_C, speed)
    wide = band_rms(car, CLASS_C, speed, (1e-5, 1e5), points=200_000)
    for name in exact:
        assert wide[name] == pytest.approx(exact[name], rel=2e-4), name
    # the issue's numbers: ISO's band (0.011-2.83 cycle/m) holds all but 4 % of the tire force
    iso = band_rms(car, CLASS_C, speed, ISO_BAND)
    assert iso["acc"] == pytest.approx(1.1713, abs=1e-4)
    assert iso["stroke"] == pytest.approx(9.176e-3, abs=1e-6)
    assert iso["tire"] / ((320.0 + 40.0) * G) == pytest.approx(0.1776, abs=1e-4)
    assert exact["tire"] / ((320.0 + 40.0) * G) == pytest.approx(0.1852, abs=1e-4)


def test_band_integral_of_a_full_car_reproduces_its_lyapunov_solution() -> None:
    """The multi-input integral (delays, coherence) against Lyapunov where both apply.

    Every wheel on one road at once (no delay, coherence 1) is a one-input system that
    Lyapunov solves exactly; a rear delay, which Lyapunov cannot take, must change it.
    """
    from mrsuspension.vehicle import FullCar

    body = FullCar(front_anti_roll_stiffness=15_000.0)
    params = {f.name: getattr(body, f.name) for f in fields(body)}
    corners = ("front_left", "front_right", "rear_left", "rear_right")
    car = body_car(params, corners, dict.fromkeys(corners, 1500.0))
    one = Linear(car.M, car.C, car.K, car.Kr.sum(axis=1, keepdims=True),
                 car.Cr.sum(axis=1, keepdims=True), car.names, car.Oq, car.Ov, car.Oa,
                 car.Rq.sum(axis=1, keepdims=True), car.Rv.sum(axis=1, keepdims=True))  # fmt: skip
    speed = 50.0 / 3.6
    exact = lyapunov_rms(one, CLASS_C, speed)
    wide = band_rms(car, CLASS_C, speed, (1e-5, 1e5), points=40_000)
    for name in exact:
        if exact[name] > 1e-9 * max(exact.values()):  # pitch and roll are zero here
            assert wide[name] == pytest.approx(exact[name], rel=2e-4), name
    delayed = band_rms(car, CLASS_C, speed, ISO_BAND, delays=np.array([0.0, 0.0, 0.17, 0.17]))
    assert delayed["pitch"] > 0.1 * delayed["heave"]


def test_hand_written_vehicles_match_the_textbook_quarter_car() -> None:
    """A half car whose pitch inertia is m a b splits into two quarter cars (no coupling)."""
    p = {"sprung_mass": 600.0, "pitch_inertia": 600.0 * 1.2 * 1.4, "cg_to_front": 1.2,
         "cg_to_rear": 1.4, "front_unsprung_mass": 40.0, "rear_unsprung_mass": 45.0,
         "front_suspension_stiffness": 20e3, "rear_suspension_stiffness": 22e3,
         "front_tire_stiffness": 190e3, "rear_tire_stiffness": 190e3,
         "front_tire_damping": 0.0, "rear_tire_damping": 0.0}  # fmt: skip
    half = body_car(p, ("front", "rear"), {"front": 1400.0, "rear": 1600.0})
    f = np.geomspace(0.2, 40.0, 50)
    y = half.response(f)
    ms_front = 600.0 * 1.4 / 2.6  # the body mass over the front axle
    quarter = quarter_car(ms_front, 40.0, 20e3, 190e3, 0.0, 1400.0).response(f)
    names = list(half.names)
    np.testing.assert_allclose(y[:, names.index("stroke.front"), 0], quarter[:, 1, 0], rtol=1e-9)
    np.testing.assert_allclose(y[:, names.index("tire.front"), 0], quarter[:, 2, 0], rtol=1e-9)
    np.testing.assert_allclose(y[:, names.index("acc.front"), 0], quarter[:, 0, 0], rtol=1e-9)
    assert np.max(np.abs(y[:, names.index("stroke.front"), 1])) < 1e-12  # no coupling


# -- the simulator against them -----------------------------------------------------------------
def _quarter_tables(length: float, seed: int, **vehicle: float) -> dict[str, dict[str, object]]:
    return {
        "vehicle": dict(ISSUE_CAR, **vehicle),
        "damper": {"model": "linear", "damping": ISSUE_DAMPING},
        "controller": {"law": "passive"},
        "excitation": {"kind": "road", "iso_class": "C", "speed": 50.0, "length": length,
                       "seed": seed},
    }  # fmt: skip


@pytest.mark.audit("closed form")
def test_quarter_car_on_iso_class_c_at_default_settings_matches_the_closed_form() -> None:
    """The issue's acceptance: 5 km, three seeds, default settings, each within 1.5 %."""
    car = quarter_car(320.0, 40.0, 22e3, 190e3, 0.0, ISSUE_DAMPING)
    exact = band_rms(car, CLASS_C, 50.0 / 3.6, ISO_BAND)
    static = (320.0 + 40.0) * G
    reference = {"rms_body_acceleration": exact["acc"], "rms_stroke": exact["stroke"],
                 "DLC": exact["tire"] / static}  # fmt: skip
    for name, value in ISSUE_VALUES.items():  # the issue's values, to their last digit
        assert reference[name] == pytest.approx(
            value, abs=0.5 * 10 ** math.floor(math.log10(value) - 3)
        )
    sims = [simulate(_quarter_tables(5000.0, seed)) for seed in (0, 1, 2)]
    for name, value in reference.items():
        mean = float(np.mean([m[name] for m in sims]))
        print(f"{name}: simulated {mean:.5g}, closed form {value:.5g} ({mean / value - 1:+.2%})")
        assert mean == pytest.approx(value, rel=TOLERANCE), name
        for m in sims:
            assert m[name] == pytest.approx(value, rel=TOLERANCE), name


@pytest.mark.audit("closed form")
@pytest.mark.parametrize(
    "vehicle",
    [
        # the dissertation's quarter car (model reference, section 4) without tire damping
        {"sprung_mass": 563.0, "unsprung_mass": 90.0, "suspension_stiffness": 57_000.0,
         "tire_stiffness": 285_000.0, "tire_damping": 0.0},
        # a light, stiff car
        {"sprung_mass": 250.0, "unsprung_mass": 35.0, "suspension_stiffness": 35_000.0,
         "tire_stiffness": 250_000.0, "tire_damping": 0.0},
    ],
    ids=["dissertation", "light"],
)  # fmt: skip
def test_quarter_car_matches_lyapunov_on_a_wide_band_road(vehicle: dict[str, float]) -> None:
    """Other parameter sets, against the Lyapunov solution of a white road velocity.

    The road's band, 0.011-30 cycle/m (0.15-417 Hz at 50 km/h), reaches far above the
    wheel hop: what the band leaves out of the Lyapunov variance is under 1 % of it
    (0.3 % of the rms tire force). The spacing is the default one for that band.
    """
    speed = 50.0 / 3.6
    car = quarter_car(vehicle["sprung_mass"], vehicle["unsprung_mass"],
                      vehicle["suspension_stiffness"], vehicle["tire_stiffness"], 0.0,
                      ISSUE_DAMPING)  # fmt: skip
    exact = lyapunov_rms(car, CLASS_C, speed)
    banded = band_rms(car, CLASS_C, speed, (0.011, 30.0))
    assert banded["tire"] == pytest.approx(exact["tire"], rel=0.005)  # the band holds it
    road = synthesise_road(RoadSpectrum(CLASS_C, 2.0, (0.011, 30.0)), 1000.0, seed=4)
    assert road.spacing == 0.005  # the default for the band: its top at 0.3 of Nyquist
    sim = Simulation(road, QuarterCar(**vehicle), LinearViscous(damping=ISSUE_DAMPING))
    m = sim.run().measures()
    static = (vehicle["sprung_mass"] + vehicle["unsprung_mass"]) * G
    assert m["rms_body_acceleration"] == pytest.approx(exact["acc"], rel=TOLERANCE)
    assert m["rms_stroke"] == pytest.approx(exact["stroke"], rel=TOLERANCE)
    assert m["DLC"] == pytest.approx(exact["tire"] / static, rel=TOLERANCE)


# -- half and full cars ---------------------------------------------------------------------------
def _vehicle_check(tables: dict[str, dict[str, object]], corners: tuple[str, ...]) -> None:
    """Simulate ``tables`` and compare every corner and body DOF with :func:`band_rms`."""
    (sim,) = Scenario.from_dict(tables).vehicle_simulations()
    body = sim.vehicle
    params = {f.name: getattr(body, f.name) for f in fields(body)}
    speed = float(tables["excitation"]["speed"]) / 3.6  # type: ignore[arg-type]
    wheelbase = body.cg_to_front + body.cg_to_rear
    full = len(corners) == 4
    two_track = tables["excitation"]["kind"] == "two-track"
    car = body_car(params, corners, dict.fromkeys(corners, 1500.0))
    delays = np.array([0.0 if c.startswith("front") else wheelbase / speed for c in corners])
    tracks = np.array([int(c.endswith("right")) for c in corners])
    exact = band_rms(car, CLASS_C, speed, ISO_BAND, delays=delays, tracks=tracks,
                     track_width=getattr(body, "front_track", 0.0) if two_track else 0.0)  # fmt: skip
    result = sim.run()
    m = result.measures()
    got = {"heave": m["heave_ddot_rms"], "pitch": m["pitch_ddot_rms"]}
    if full:
        got["roll"] = m["roll_ddot_rms"]
    for c in corners:
        got[f"acc.{c}"] = m[f"rms_body_acceleration.{c}"]
        got[f"stroke.{c}"] = m[f"rms_stroke.{c}"]
        got[f"tire.{c}"] = float(np.std(result[f"F_T.{c}"]))
    errors = {name: got[name] / exact[name] - 1.0 for name in got}
    print(f"\n{type(body).__name__} ({tables['excitation']['kind']}): worst "
          f"{max(errors.items(), key=lambda kv: abs(kv[1]))}")  # fmt: skip
    bad = {k: f"{v:+.2%}" for k, v in errors.items() if abs(v) > TOLERANCE}
    assert not bad, bad


@pytest.mark.audit("closed form")
def test_half_car_on_an_iso_road_matches_its_spectral_solution() -> None:
    """Both wheels on one track, the rear wheelbase/V later (``kind = "road"``)."""
    _vehicle_check(
        {
            "vehicle": {"model": "half-car"},
            "damper": {"model": "linear", "damping": 1500.0},
            "controller": {"law": "passive"},
            "excitation": {"kind": "road", "iso_class": "C", "speed": 50.0, "length": 2000.0,
                           "seed": 2},
        },
        ("front", "rear"),
    )  # fmt: skip


@pytest.mark.audit("closed form")
def test_full_car_on_a_two_track_iso_road_matches_its_spectral_solution() -> None:
    """Two coherent tracks (isotropic), rear wheels later, an anti-roll bar at the front."""
    _vehicle_check(
        {
            "vehicle": {"model": "full-car", "front_anti_roll_stiffness": 15_000.0},
            "damper": {"model": "linear", "damping": 1500.0},
            "controller": {"law": "passive"},
            "excitation": {"kind": "two-track", "iso_class": "C", "speed": 72.0,
                           "length": 2000.0, "seed": 3},
        },
        ("front_left", "front_right", "rear_left", "rear_right"),
    )  # fmt: skip
