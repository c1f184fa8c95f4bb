"""Issue 31 item 1: a control law defined here, in the test file (no edit under src/), runs
on the quarter car and the full car, in a sweep and in the HiL loop with a simulated rig,
on the numba path and on the Python path; its per-step cost beside a built-in law's."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg

from mrsuspension.control import Passive, law
from mrsuspension.engine import Simulation
from mrsuspension.engine.simulate import run_many
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.errors import MRSuspensionError, ValidationError
from mrsuspension.excitation import Harmonic
from mrsuspension.excitation.wheels import WheelRoads
from mrsuspension.hil import SimulatedRig, StartUp, run_hil
from mrsuspension.scenario import Scenario
from mrsuspension.vehicle import FullCar

DT = 1e-4


# -- the laws: plain Python in this file -------------------------------------------------
@law
def constant(current=0.2):  # type: ignore[no-untyped-def]
    """A constant current: the same physics as the built-in passive law."""
    return current


@law(numba=False)
def constant_py(current=0.2):  # type: ignore[no-untyped-def]
    return current


def _onoff(z_s_dot, v_d, high=0.5, low=0.0):  # type: ignore[no-untyped-def]
    """On-off skyhook: high current when the damper can push against the body's velocity."""
    return high if z_s_dot * v_d < 0.0 else low


skyhook = law(_onoff)
skyhook_py = law(numba=False)(_onoff)


@law(numba=False)
def slow(v_d, seconds=2e-4):  # type: ignore[no-untyped-def]
    """A Python law that spends ``seconds`` per call."""
    end = time.perf_counter() + seconds
    while time.perf_counter() < end:
        pass
    return 0.0


@law
def broken(v_d):  # type: ignore[no-untyped-def]
    return 1.0 / 0.0 if v_d > 1.0 else 0.0  # numba: inf (error_model numpy): clipped


@law(numba=False)
def raises(time):  # type: ignore[no-untyped-def]
    if time > 0.05:
        raise ZeroDivisionError("the law's own bug")
    return 0.0


def _lq_gains(plant, K):  # type: ignore[no-untyped-def]
    """Clipped-optimal LQ on the linearised quarter car: K from a Riccati solve.

    States x = (z_s - z_u, z_s', z_u - z_r, z_u'), input the damper force u (up on the
    body); cost: body acceleration, suspension and tire deflection, and the force. Given
    gains (not all zero) are kept."""
    if np.any(np.asarray(K) != 0.0):
        return {}
    ms, mu = plant.sprung_mass, plant.unsprung_mass
    ks, kt = plant.suspension_stiffness, plant.tire_stiffness
    a = np.array(
        [[0, 1, 0, -1], [-ks / ms, 0, 0, 0], [0, 0, 0, 1], [ks / mu, 0, -kt / mu, 0]], float
    )
    b = np.array([[0.0], [1 / ms], [0.0], [-1 / mu]])
    c = np.array([[-ks / ms, 0, 0, 0]])  # body acceleration (without u)
    q = c.T @ c + np.diag([1e2, 0.0, 1e3, 0.0])
    r = np.array([[1.0 / ms**2 + 1e-6]])
    p = scipy.linalg.solve_continuous_are(a, b, q, r)
    return {"K": np.linalg.solve(r, b.T @ p)}


@law(output="force", for_plant=_lq_gains)
def lq(z_s, z_s_dot, z_u, z_u_dot, K=((0.0, 0.0, 0.0, 0.0),)):  # type: ignore[no-untyped-def]
    """f_c = -K x with the wheel's road unknown (x_3 = 0: its static deflection)."""
    return -(K[0, 0] * (z_s - z_u) + K[0, 1] * z_s_dot + K[0, 3] * z_u_dot)


# -- the tests ----------------------------------------------------------------------------
def _quarter(controller, f: float = 1.5):  # type: ignore[no-untyped-def]
    return Simulation(Harmonic(f, 0.02), controller=controller)


def _same(a, b, keys) -> None:  # type: ignore[no-untyped-def]
    for k in keys:
        np.testing.assert_array_equal(a[k], b[k], err_msg=k)


def test_paths() -> None:
    assert constant.path() == "numba"
    assert skyhook.path() == "numba"
    assert lq.path() == "numba"
    assert constant_py.path() == "python"
    assert constant_py.entry().reason == "numba=False"
    print(f"compile of a first law {constant.entry().compile_seconds:.2f} s, "
          f"a second {skyhook.entry().compile_seconds:.2f} s")  # fmt: skip


@pytest.mark.parametrize("cls", [constant, constant_py])
def test_quarter_car_equals_the_built_in_law(cls) -> None:  # type: ignore[no-untyped-def]
    """A constant-current law is the passive law: bit for bit, numba and Python path."""
    a = _quarter(cls(current=0.2)).run(1.0, dt=DT)
    b = _quarter(Passive(0.2)).run(1.0, dt=DT)
    _same(a, b, ("z_s", "z_s_ddot", "z_u", "F_d", "F_T", "i_d"))


def test_quarter_car_skyhook_both_paths_and_better_than_passive() -> None:
    a = _quarter(skyhook()).run(3.0, dt=DT)
    b = _quarter(skyhook_py()).run(3.0, dt=DT)
    _same(a, b, ("z_s", "z_s_ddot", "i_d"))
    soft = _quarter(Passive(0.0)).run(3.0, dt=DT)
    rms = {k: float(np.sqrt(np.mean(r["z_s_ddot"][r.time >= 1.5] ** 2))) for k, r in
           (("skyhook", a), ("passive 0 A", soft))}  # fmt: skip
    print(f"rms z_s'' at 1.5 Hz: {rms}")
    assert rms["skyhook"] < rms["passive 0 A"]
    assert set(np.unique(a["i_d"])) <= {0.0, 0.5}


def test_full_car_every_corner() -> None:
    car = FullCar()
    road = WheelRoads.two_track(
        "C", (car.wheelbase, car.front_track), speed_kmh=54.0, length=30.0, seed=5
    )
    a = VehicleSimulation(car, road, controllers=constant(current=0.1)).run(0.5, dt=DT)
    b = VehicleSimulation(car, road, controllers=Passive(0.1)).run(0.5, dt=DT)
    _same(a, b, [f"{s}.{c}" for s in ("z_s", "F_d", "i_d") for c in car.corners])
    sky = VehicleSimulation(car, road, controllers=skyhook()).run(0.5, dt=DT)
    py = VehicleSimulation(car, road, controllers={"rear_left": skyhook_py()}).run(0.5, dt=DT)
    assert set(np.unique(sky["i_d.front_left"])) == {0.0, 0.5}
    np.testing.assert_array_equal(py["i_d.front_left"], 0.0)  # passive there
    assert set(np.unique(py["i_d.rear_left"])) == {0.0, 0.5}
    # the Riccati law's gains differ by corner (each corner's own quarter car)
    sim = VehicleSimulation(car, road, controllers=lq())
    gains = {c: sim.corner_simulation(c).controller.K for c in car.corners}
    assert gains["front_left"] != gains["rear_left"]
    assert sim.run(0.3, dt=DT)["i_d.front_left"].max() > 0.0


def test_riccati_law_derives_its_gains_from_the_plant() -> None:
    sim = _quarter(lq())
    k = np.asarray(sim.controller.K)
    assert k.shape == (1, 4)
    assert np.all(np.isfinite(k))
    assert abs(k[0, 1]) > 100.0
    again = _quarter(lq())
    assert again.controller == sim.controller  # same plant, same gains
    res = sim.run(2.0, dt=DT)
    assert np.isfinite(res["F_target"][1:]).all()
    assert res["i_d"].max() > 0.0


def rms_body_acceleration(result) -> float:  # type: ignore[no-untyped-def]
    """A sweep's reducer (module level: the workers import it)."""
    return float(np.sqrt(np.mean(result["z_s_ddot"] ** 2)))


def test_sweep_in_a_process_pool() -> None:
    """run_many in two worker processes: numba and Python path, as in one process; a
    user law never joins the lanes (it reads the signals the lanes do not fill)."""
    freqs = (1.0, 1.5, 2.0, 3.0, 4.0, 5.0)
    sims = [_quarter(skyhook(), f) for f in freqs]
    py = [_quarter(skyhook_py(), f) for f in freqs]
    kw = {"dt": DT, "duration": 1.0, "reduce": rms_body_acceleration}
    many = run_many(sims + py, workers=2, **kw)
    one = run_many(sims, workers=1, **kw)
    assert many[:6] == one == many[6:]
    assert len(set(one)) == len(freqs)


@pytest.mark.parametrize("cls", [skyhook, skyhook_py])
def test_hil_loop_with_a_simulated_rig(cls) -> None:  # type: ignore[no-untyped-def]
    sim = Simulation(Harmonic(1.5, 0.02), controller=cls(high=0.3), max_current=0.3)
    result = run_hil(
        sim, SimulatedRig(sim.damper), duration=0.5, rate=1000.0, startup=StartUp.none(),
        realtime="unpaced",
    )  # fmt: skip
    assert result.reason == "completed"
    assert not result.tripped
    assert set(np.unique(result.recording["i_d"][result.running()])) >= {0.0}
    assert result.recording["i_d"].max() > 0.1


def test_hil_refuses_a_python_law_too_slow_for_the_rate() -> None:
    sim = Simulation(Harmonic(1.5, 0.02), controller=slow(), max_current=0.3)
    with pytest.raises(ValidationError, match=r"runs in Python .* us per call: 1 corner\(s\) x 10"):
        run_hil(sim, SimulatedRig(sim.damper), duration=0.1, realtime="unpaced")


def test_a_python_law_that_raises_stops_the_run_with_its_error() -> None:
    with pytest.raises(MRSuspensionError, match="raised ZeroDivisionError: the law's own bug"):
        _quarter(raises()).run(0.5, dt=DT)
    stepper = _quarter(raises()).stepper(DT)

    def steps() -> None:
        for _ in range(1000):
            stepper.step(0.0, 0.0)

    with pytest.raises(MRSuspensionError, match="the law's own bug"):
        steps()
    assert _quarter(broken()).run(0.2, dt=DT)["i_d"].max() == 0.0  # inf only above 1 m/s


def test_scenario_names_the_law_with_vector_options(tmp_path: Path) -> None:
    toml = tmp_path / "lq.toml"
    law_file = Path(__file__)
    toml.write_text(
        f'[controller]\nlaw = "{law_file}:lq"\nK = [[1000.0, 500.0, 0.0, 20.0]]\n'
        '[excitation]\nkind = "harmonic"\nfrequency = 1.5\namplitude = 0.02\n'
        "[simulation]\nduration = 0.5\ndt = 1e-4\n"
    )
    s = Scenario.load(toml)
    assert s.controller.law == f"{law_file}:lq"
    assert s.to_dict()["controller"]["K"] == [[1000.0, 500.0, 0.0, 20.0]]
    assert np.isfinite(s.run()[0]["z_s"]).all()
    again = Scenario.from_dict(s.to_dict(), s.base_dir)
    assert again.controller == s.controller  # the for_plant hook gives the same gains
    bad = toml.read_text().replace("[[1000.0, 500.0, 0.0, 20.0]]", "[1000.0, 500.0]")
    toml.write_text(bad)
    with pytest.raises(
        ValidationError, match=r"K must be an array of shape \(1, 4\); got shape \(2,\)"
    ):
        Scenario.load(toml)
    for spec, message in (
        ("no_such_module_x:lq", "cannot import module 'no_such_module_x'"),
        (f"{law_file}:lqq", "has no 'lqq'. Did you mean 'lq'?"),
        ("mrsuspension.control:law", "option 'fn' must default to a number"),
    ):
        with pytest.raises(ValidationError, match=message):
            Scenario.from_dict({"controller": {"law": spec}})
    with pytest.raises(ValidationError, match="has no option 'gain'"):
        Scenario.from_dict({"controller": {"law": f"{law_file}:constant", "gain": 1.0}})


def _per_step(controller, n: int = 20000) -> float:  # type: ignore[no-untyped-def]
    sim = _quarter(controller)
    sim.run(DT * 100, dt=DT)  # warm
    best = np.inf
    for _ in range(3):
        t0 = time.perf_counter()
        sim.run(DT * n, dt=DT, output_rate=100.0)
        best = min(best, (time.perf_counter() - t0) / n)
    return best


def test_per_step_cost_beside_a_built_in_law() -> None:
    from mrsuspension.control import HiLo

    costs = {
        "passive (built-in)": _per_step(Passive(0.2)),
        "skyhook-hilo (built-in)": _per_step(HiLo(1)),
        "constant, numba path": _per_step(constant()),
        "on-off skyhook, numba path": _per_step(skyhook()),
        "constant, Python path": _per_step(constant_py()),
        "on-off skyhook, Python path": _per_step(skyhook_py()),
    }
    for k, v in costs.items():
        print(f"per step {k:28s} {v * 1e9:8.0f} ns")
    print(
        f"law call alone: numba {skyhook.cost() * 1e9:.0f} ns, Python {skyhook_py.cost() * 1e9:.0f} ns"
    )
    # the numba path costs about a built-in law; the Python path a callback per step
    assert costs["on-off skyhook, numba path"] < 3.0 * costs["skyhook-hilo (built-in)"]
    assert costs["on-off skyhook, Python path"] > costs["on-off skyhook, numba path"]
