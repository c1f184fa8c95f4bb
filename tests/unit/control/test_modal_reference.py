"""Modal skyhook against an independent linear reference (issue 29, part 4).

The reference is the full car linearised with a passive damper ``c_0`` at every corner
plus the *ideal* (active, unclipped) modal skyhook: the wrench ``w* = -G (v_z, q, p)``
with ``G = diag(c_z, c_theta, c_phi)`` put on the corners as ``F = D w*`` with ``D`` the
minimum-norm right inverse of ``J`` (rows ``1, -x_i, y_i``), here ``numpy.linalg.pinv``,
not the package's :func:`~mrsuspension.control.modal.distribution_matrix`. The matrices
are written from the equations of motion (docs/vehicles.md, "Model"): ``M q'' + C q' + K
q = K_r z_r + C_r z_r'`` with the sky forces up on the body and down on the wheels.

Checked against it:

* the law's distribution, gains (``for_vehicle``) and corner forces for given body rates;
* the compiled engine's plant closed through the law's force kernel
  (:func:`~mrsuspension.control.modal.modal_forces`) as a force source at every corner
  (the engine has no ideal-force path for vehicle laws, so the force ``c_0 v_d + F_i`` is
  given each tick as the HiL path's external force, held over the tick): sinusoidal
  steady state of heave, pitch and roll within 1 % of the reference's closed-form
  response, for in-phase wheels and left/right and front/rear anti-phase wheels;
* the engine's own modal-skyhook block: the recorded target forces are the reference's
  for the recorded body rates, and the current is high exactly when the target force has
  the sign the stroke rate allows (``F_i v_d > 0``);
* hi-lo uses only the signs of the target forces: scaling every gain changes nothing.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mrsuspension.control.kernel import F_EXTERNAL
from mrsuspension.control.modal import ModalSkyhook, distribution_matrix, modal_forces
from mrsuspension.engine import kernel as EK
from mrsuspension.engine import vehicle_kernel as VX
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.engine.vehicle_result import VehicleResult
from mrsuspension.excitation import Harmonic
from mrsuspension.excitation.wheels import WheelRoads
from mrsuspension.vehicle import FullCar

C0 = 1500.0  # N s/m: the passive damper of the reference at every corner
C_S = 6750.0  # N s/m: the skyhook reference's damping (model reference, section 5)
AMPLITUDE = 1e-3  # m: the tyres stay in contact
DT = 2e-4  # s: the force held over a tick lags by dt/2, 0.4 % of phase at 6 Hz


@pytest.fixture(scope="module")
def car() -> FullCar:
    return FullCar()


def jacobian(car: FullCar) -> np.ndarray:
    """``J`` with ``w = J F``: rows ``1``, ``-x_i``, ``y_i`` (pitch nose down, roll left up)."""
    x, y = car.corner_positions()
    return np.vstack([np.ones_like(x), -x, y])


def reference_matrices(
    car: FullCar, c0: float, gains: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``M, C, K, K_r, C_r`` of the full car with ``c0`` and ideal modal skyhook ``gains``.

    ``q = (z, theta, phi, z_u,1..4)``; the body moves at corner ``i`` by
    ``z_s,i = z - x_i theta + y_i phi = (J^T q_b)_i``, the stroke is ``x_d,i = z_u,i -
    z_s,i``; the suspension force ``k_s x_d + c0 v_d`` and the sky force ``F_i`` push the
    body up and the wheel down.
    """
    j = jacobian(car)
    n, nb = j.shape[1], 3
    ks, kt, ct = car.suspension_stiffnesses, car.tire_stiffnesses, car.tire_dampings
    masses = [car.sprung_mass, car.pitch_inertia, car.roll_inertia, *car.unsprung_masses]
    m = np.diag(masses)
    k = np.zeros((nb + n, nb + n))
    c = np.zeros_like(k)
    for i in range(n):
        d = np.zeros(nb + n)  # x_d,i = d . q
        d[:nb], d[nb + i] = -j[:, i], 1.0
        k += ks[i] * np.outer(d, d)
        c += c0 * np.outer(d, d)
    k[nb:, nb:] += np.diag(kt)
    c[nb:, nb:] += np.diag(ct)
    # sky: F = D w*, w* = -G q_b'. On the body J F = -G q_b' (J D = I): C_bb += G; on
    # wheel i the force -F_i = (D G q_b')_i: C_wb -= D G.
    dg = np.linalg.pinv(j) @ np.diag(gains)
    c[:nb, :nb] += j @ dg
    c[nb:, :nb] -= dg
    kr, cr = np.zeros((nb + n, n)), np.zeros((nb + n, n))
    kr[nb:], cr[nb:] = np.diag(kt), np.diag(ct)
    return m, c, k, kr, cr


def reference_response(
    car: FullCar, c0: float, gains: np.ndarray, f: float, road: np.ndarray
) -> np.ndarray:
    """Complex amplitudes of ``q`` for the road phasors ``road`` at ``f`` [Hz] (closed form)."""
    m, c, k, kr, cr = reference_matrices(car, c0, gains)
    w = 2.0 * math.pi * f
    return np.linalg.solve(-(w**2) * m + 1j * w * c + k, (kr + 1j * w * cr) @ road)


def corner_gains(car: FullCar) -> np.ndarray:
    x, y = car.corner_positions()
    return np.array([4.0 * C_S, C_S * float(x @ x), C_S * float(y @ y)])


# --- the law against the reference -------------------------------------------------------


def test_reference_without_sky_is_the_passive_car(car: FullCar) -> None:
    # the passive part is the package's linear model, checked against the engine to 1e-6
    # (tests/unit/engine/test_vehicle_frf.py)
    m, c, k, kr, cr = reference_matrices(car, C0, np.zeros(3))
    lin = car.linear_matrices(C0)
    for ours, theirs in ((m, lin.M), (c, lin.C), (k, lin.K), (kr, lin.K_road), (cr, lin.C_road)):
        assert np.allclose(ours, theirs, rtol=1e-12, atol=1e-9)


@pytest.mark.parametrize(
    "geometry",
    [None, ([1.2, 1.2, -1.6, -1.6], [0.75, -0.75, 0.78, -0.78])],
    ids=["published car", "asymmetric car"],
)
def test_distribution_is_the_minimum_norm_inverse(
    car: FullCar, geometry: tuple[list[float], list[float]] | None
) -> None:
    if geometry is None:
        x, y = car.corner_positions()
    else:
        x, y = (np.asarray(g, dtype=float) for g in geometry)
    j = np.vstack([np.ones_like(x), -x, y])
    dist = distribution_matrix(x, y)
    assert np.allclose(dist, np.linalg.pinv(j), rtol=1e-12, atol=1e-15)
    assert np.allclose(j @ dist, np.eye(3), atol=1e-12)


def test_for_vehicle_gains_are_the_corner_equivalent(car: FullCar) -> None:
    gains = ModalSkyhook().for_vehicle(car).params()[:3]  # (c_z, c_theta, c_phi)
    assert gains == pytest.approx(corner_gains(car), rel=1e-12)
    # published car: c_z = 27000 N s/m, c_theta = 37304 N m s/rad, c_phi = 10412 N m s/rad
    assert np.round(gains).tolist() == [27000.0, 37304.0, 10412.0]


def test_law_forces_are_the_reference_forces(car: FullCar) -> None:
    sky = ModalSkyhook().for_vehicle(car)
    dist = distribution_matrix(*car.corner_positions())
    d_ref = np.linalg.pinv(jacobian(car))
    gains = corner_gains(car)
    rng = np.random.default_rng(29)
    for vz, q, p in rng.normal(scale=[0.2, 0.1, 0.1], size=(20, 3)):
        ours = sky.forces(dist, heave_velocity=vz, pitch_rate=q, roll_rate=p)
        assert np.allclose(ours, -d_ref @ (gains * [vz, q, p]), rtol=1e-12, atol=1e-9)
    # signs: a body rising at the front-left (heave up) is pulled down there; a nose-down
    # pitch rate (front sinking) is pushed up at the front; left side rising: pulled down
    f = sky.forces(dist, heave_velocity=0.1, pitch_rate=0.0)
    assert np.all(f < 0.0)
    f = sky.forces(dist, heave_velocity=0.0, pitch_rate=0.1)
    assert f[0] > 0.0
    assert f[2] < 0.0
    f = sky.forces(dist, heave_velocity=0.0, pitch_rate=0.0, roll_rate=0.1)
    assert f[0] < 0.0
    assert f[1] > 0.0


def test_ideal_modal_skyhook_damps_the_body_modes(car: FullCar) -> None:
    # the closed form: sky damping takes the body resonances down (heave in phase, roll
    # left/right anti-phase, as transmissibilities: roll times the half track)
    gains = corner_gains(car)
    freqs = np.linspace(0.5, 4.0, 36)
    half_track = car.front_track / 2.0
    for road, dof, scale in (
        (np.ones(4), 0, 1.0),
        (np.array([1.0, -1.0, 1.0, -1.0]), 2, half_track),
    ):
        passive = [
            scale * abs(reference_response(car, C0, np.zeros(3), f, road)[dof]) for f in freqs
        ]
        sky = [scale * abs(reference_response(car, C0, gains, f, road)[dof]) for f in freqs]
        assert max(sky) < 0.6 * max(passive)
        assert max(sky) < 1.0 + 1e-9  # no amplification of the road at any body frequency


# --- the engine against the reference ---------------------------------------------------


def engine_ideal_modal_phasors(car: FullCar, f: float, road: np.ndarray) -> np.ndarray:
    """Heave, pitch and roll phasors of the compiled step with ``c0 v_d + F_i`` at every
    corner (``F_i`` from the law's kernel at the tick's start), started at the reference's
    steady state and fitted over one period."""
    sky = ModalSkyhook().for_vehicle(car)
    gains = corner_gains(car)
    x, y = car.corner_positions()
    dist = np.ascontiguousarray(distribution_matrix(x, y))
    mp = sky.params()
    sim = VehicleSimulation(car, WheelRoads.in_phase(Harmonic(f, AMPLITUDE), car.corners))
    arrays = sim.arrays(DT)
    arrays.force_source[:] = F_EXTERNAL
    args = arrays.args()
    mem = arrays.memory
    w = 2.0 * math.pi * f
    # start on the steady state (no transient to wait for: any mismatch shows as one)
    q = AMPLITUDE * reference_response(car, C0, gains, f, road)
    state = np.zeros(6 + 4 * 4)
    state[:3], state[3:6] = q[:3].imag, (1j * w * q[:3]).imag
    for i in range(4):
        state[6 + 4 * i], state[7 + 4 * i] = q[3 + i].imag, (1j * w * q[3 + i]).imag
    scratch, work = np.zeros((5, state.size)), np.zeros((5, 8))
    n = round(1.0 / (f * DT))  # one period
    rot = AMPLITUDE * road[:, None] * np.exp(1j * w * np.arange(2 * n + 1) * DT / 2.0)
    zr, zrd = np.ascontiguousarray(rot.imag), np.ascontiguousarray((1j * w * rot).imag)
    forces = np.zeros(4)
    out = np.zeros((n, 3))
    t_out = (np.arange(n) + 1) * DT
    for s in range(n):
        modal_forces(forces, dist, mp, state[3], state[4], state[5])
        v_d = state[7::4] - (state[3] - x * state[4] + y * state[5])
        mem[:, EK.M_FEXT] = C0 * v_d + forces
        VX.step(state, DT, zr, zrd, 2 * s, *args, scratch, work)
        out[s] = state[:3]
    basis = np.column_stack([np.sin(w * t_out), np.cos(w * t_out)])
    coef, *_ = np.linalg.lstsq(basis, out, rcond=None)
    return coef[0] + 1j * coef[1]


CASES = [  # (frequency [Hz], road phasors FL FR RL RR, outputs excited)
    (1.3, [1.0, 1.0, 1.0, 1.0], (0, 1)),  # in phase: heave (and pitch: CG not midway)
    (6.0, [1.0, 1.0, 1.0, 1.0], (0, 1)),
    (1.8, [1.0, -1.0, 1.0, -1.0], (2,)),  # left/right anti-phase: roll
    (1.6, [1.0, 1.0, -1.0, -1.0], (0, 1)),  # front/rear anti-phase: pitch
]


@pytest.mark.parametrize(("f", "road", "excited"), CASES)
def test_engine_with_ideal_modal_forces_matches_the_reference(
    car: FullCar, f: float, road: list[float], excited: tuple[int, ...]
) -> None:
    phasors = np.asarray(road, dtype=complex)
    ref = AMPLITUDE * reference_response(car, C0, corner_gains(car), f, phasors)[:3]
    sim = engine_ideal_modal_phasors(car, f, phasors)
    for k in range(3):
        if k in excited:
            assert abs(sim[k] - ref[k]) <= 0.01 * abs(ref[k]), (k, sim[k], ref[k])
        else:  # not excited by this road: stays (nearly) at rest
            assert abs(sim[k]) <= 1e-3 * max(abs(ref[j]) for j in excited)


@pytest.fixture(scope="module")
def modal_run(car: FullCar) -> tuple[VehicleSimulation, VehicleResult]:
    road = WheelRoads.two_track("C", (car.wheelbase, car.front_track), 50.0, length=20.0, seed=3)
    sim = VehicleSimulation(car, road, body_control=ModalSkyhook())
    return sim, sim.run(1.0, dt=2e-4, output_rate=5000.0)


def test_engine_targets_and_switching_follow_the_reference(
    car: FullCar, modal_run: tuple[VehicleSimulation, VehicleResult]
) -> None:
    _, res = modal_run
    d_ref = np.linalg.pinv(jacobian(car))
    gains = corner_gains(car)
    # the law acts at the step's start: row r's target is from row r - 1's state
    rates = np.column_stack([res["heave_dot"], res["pitch_dot"], res["roll_dot"]])[:-1]
    expected = -(rates * gains) @ d_ref.T
    switched = 0
    for i, c in enumerate(car.corners):
        target = np.asarray(res[f"F_target.{c}"])[1:]
        scale = np.abs(expected[:, i]).max()
        assert np.allclose(target, expected[:, i], rtol=0.0, atol=1e-9 * scale)
        achievable = target * np.asarray(res[f"v_d.{c}"])[:-1] > 0.0
        high = np.asarray(res[f"i_d.{c}"])[1:] == 0.5
        assert np.array_equal(high, achievable)
        assert np.all(np.asarray(res[f"i_d.{c}"])[1:][~high] == 0.0)
        switched += int(high.sum())
    assert 0.2 < switched / expected.size < 0.8  # both states are visited


def test_hilo_uses_only_the_signs_of_the_targets(
    car: FullCar, modal_run: tuple[VehicleSimulation, VehicleResult]
) -> None:
    sim, res = modal_run
    cz, ctheta, cphi = ModalSkyhook().for_vehicle(car).params()[:3]
    scaled = ModalSkyhook(10.0 * cz, 10.0 * ctheta, 10.0 * cphi)
    other = VehicleSimulation(car, sim.excitation, body_control=scaled).run(
        1.0, dt=2e-4, output_rate=5000.0
    )
    for name in ("heave_ddot", "i_d.front_left", "i_d.rear_right", "F_d.rear_left"):
        assert np.array_equal(np.asarray(other[name]), np.asarray(res[name]))
    assert np.allclose(other["F_target.front_left"], 10.0 * np.asarray(res["F_target.front_left"]))
