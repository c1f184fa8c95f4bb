"""The compiled half and full car: symmetry, decoupled corners, controllers, bad input, order."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mrsuspension.control import HiLo, Passive, SlidingMode, make_controller
from mrsuspension.control.registry import CONTROLLERS
from mrsuspension.dampers import LinearViscous
from mrsuspension.engine import Simulation, SimulationDiverged
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.errors import ValidationError
from mrsuspension.excitation import Harmonic, RoundedPulse, WheelRoads
from mrsuspension.vehicle import FullCar, HalfCar, QuarterCar

SPEED_KMH = 72.0  # 20 m/s


def _road(car: HalfCar | FullCar, excitation: Harmonic | RoundedPulse) -> WheelRoads:
    return WheelRoads.from_excitation(excitation, car, speed_kmh=SPEED_KMH)


# -- symmetry ---------------------------------------------------------------------------
@pytest.mark.parametrize(
    "controller",
    [Passive(0.1), HiLo(1, mode="ACM"), SlidingMode()],
    ids=["passive", "skyhook", "sliding"],
)
@pytest.mark.parametrize(
    "car", [FullCar(), FullCar(front_anti_roll_stiffness=20_000.0)], ids=["plain", "arb"]
)
def test_identical_left_right_input_gives_no_roll(controller, car) -> None:
    for exc in (Harmonic(1.5, 0.02), RoundedPulse(0.035, 3.0)):
        res = VehicleSimulation(car, _road(car, exc), controllers=controller).run(3.0)
        roll, rate = np.abs(res.roll).max(), np.abs(res.roll_dot).max()
        print(f"\n{type(controller).__name__} {type(exc).__name__}: max |roll| {roll:.1e} rad, "
              f"max |roll rate| {rate:.1e} rad/s, max |pitch| {np.abs(res.pitch).max():.2e} rad")  # fmt: skip
        assert roll < 1e-12
        assert rate < 1e-12
        assert np.abs(res.pitch).max() > 1e-4  # the delayed rear wheels pitch the body


def test_one_sided_input_rolls_the_body() -> None:
    car = FullCar()
    # the left wheel track only; the right one flat
    road = WheelRoads(Harmonic(1.5, 0.01), None, car.wheelbase, SPEED_KMH, car.track)
    res = VehicleSimulation(car, road).run(2.0)
    assert np.abs(res.roll).max() > 1e-3


# -- decoupled corners are quarter cars ---------------------------------------------------
@pytest.mark.parametrize(
    "controller", [Passive(0.2), HiLo(1, mode="ACM")], ids=["passive", "skyhook"]
)
@pytest.mark.parametrize("exc", [Harmonic(1.5, 0.025), Harmonic(8.0, 0.005)], ids=["1.5Hz", "8Hz"])
@pytest.mark.parametrize("cls", [HalfCar, FullCar])
def test_decoupled_corners_reproduce_the_quarter_car(cls, exc, controller) -> None:
    qc = QuarterCar()
    car = cls.from_quarter_car(qc)
    road = _road(car, exc)
    res = VehicleSimulation(car, road, controllers=controller).run(road.duration)
    ref = Simulation(exc, vehicle=qc, controller=controller).run().measures()
    for c in car.corners:
        m = res.corner(c).measures()
        for key in ("T_as", "DLC"):
            rel = abs(m[key] / ref[key] - 1.0)
            print(f"\n{cls.__name__} {c} {exc.frequency} Hz {type(controller).__name__}: "
                  f"{key} {m[key]:.5f} vs quarter car {ref[key]:.5f} ({rel:.1e})")  # fmt: skip
            assert rel < 5e-3, (c, key)


def test_decoupled_published_car_corners_are_their_quarter_cars() -> None:
    """The published car with I_y = m a b (a != b): front and rear corners differ, each
    moves as its own quarter car (static share of the body, its wheel, spring and tire)."""
    car = FullCar().decoupled()
    exc = Harmonic(1.5, 0.02)
    road = _road(car, exc)
    res = VehicleSimulation(car, road, controllers=HiLo(1, mode="ACM")).run(road.duration)
    for c in ("front_left", "rear_right"):
        qc = car.corner_quarter_car(c)
        ref = Simulation(exc, vehicle=qc, controller=HiLo(1, mode="ACM")).run().measures()
        m = res.corner(c).measures()
        for key in ("T_as", "DLC"):
            rel = abs(m[key] / ref[key] - 1.0)
            print(
                f"\npublished car, decoupled, {c}: {key} {m[key]:.5f} vs {ref[key]:.5f} ({rel:.1e})"
            )
            assert rel < 5e-3, (c, key)


def test_runaway_says_when_and_which_signal() -> None:
    class Ramp:  # the front wheel's road climbs 30 m/s: its wheel leaves the 10 m range
        corners = ("front", "rear")
        duration = None

        def displacement(self, t: np.ndarray) -> np.ndarray:
            return np.outer([30.0, 0.0], np.atleast_1d(t))

        def velocity(self, t: np.ndarray) -> np.ndarray:
            return np.outer([30.0, 0.0], np.ones(np.size(t)))

    with pytest.raises(SimulationDiverged, match=r"diverged at t = 0\.3.* z_u\.front = 10"):
        VehicleSimulation(HalfCar(), Ramp()).run(1.0)
    with pytest.raises(ValidationError, match="duration is required"):
        VehicleSimulation(HalfCar(), Ramp()).run()


# -- every controller family per corner ------------------------------------------------
@pytest.mark.parametrize("law", sorted(CONTROLLERS))
def test_every_controller_runs_per_corner(law: str) -> None:
    car = FullCar()
    controllers = {"front_left": make_controller(law), "rear_right": make_controller(law)}
    res = VehicleSimulation(car, _road(car, Harmonic(2.0, 0.01)), controllers=controllers).run(0.5)
    for c in car.corners:
        assert np.all(np.isfinite(res[f"F_d.{c}"]))
        assert res[f"i_d.{c}"].max() <= 0.5 + 1e-12
    assert res["i_d.front_right"].max() == 0.0  # passive at 0 A where none was given


# -- bad input ---------------------------------------------------------------------------
def _sim(**kw: object) -> VehicleSimulation:
    car = kw.pop("vehicle", FullCar())
    road = kw.pop("excitation", WheelRoads.in_phase(Harmonic(1.0, 0.01), car))
    return VehicleSimulation(car, road, **kw)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: _sim(controllers={"front_lef": HiLo(1)}),
         "unknown corner 'front_lef'. Did you mean 'front_left'? Valid: front_left, front_right, rear_left, rear_right."),
        (lambda: _sim(dampers={"rear": LinearViscous()}),
         "unknown corner 'rear'. Did you mean 'rear_left'? Valid: front_left, front_right, rear_left, rear_right."),
        (lambda: _sim(excitation=WheelRoads.in_phase(Harmonic(1.0, 0.01), "half-car")),
         "unknown corner 'front'. Did you mean 'front_left'? Valid: front_left, front_right, rear_left, rear_right."),
        (lambda: FullCar(pitch_inertia=-100.0),
         "pitch_inertia must be in (0, 1e+07] kg m^2; got -100 kg m^2"),
        (lambda: HalfCar(cg_to_front=1.0, cg_to_rear=-1.0),
         "wheelbase cg_to_front + cg_to_rear must be > 0 m; got 1 + -1 = 0 m"),
        (lambda: _sim(controllers="skyhook"),
         "controller for corner 'front_left' must be a Controller object; got 'skyhook'"),
        (lambda: _sim(excitation=Harmonic(1.0, 0.01)), "excitation must be a wheel input"),
        (lambda: _sim(max_current=3.0), "max_current must be in [0, 0.5] A; got 3 A"),
        (lambda: _sim().run(1.0, dt=0.005), "dt = 0.005 s is too large for stability"),
    ],
)  # fmt: skip
def test_bad_input_gives_one_clear_line(make, message: str) -> None:
    with pytest.raises(ValidationError) as info:
        make()
    text = str(info.value)
    print(f"\n{text}")
    assert text.startswith(message)
    assert "\n" not in text


# -- order of accuracy --------------------------------------------------------------------
def test_dt_convergence_is_fourth_order() -> None:
    car = FullCar()
    # a smooth input at every wheel: driven along the road, the rear wheels would meet
    # the harmonic at L/V with a jump in road velocity (held before), and no fixed-step
    # scheme keeps its order across a kink that falls inside a step
    road = WheelRoads.in_phase(Harmonic(3.0, 0.005), car)
    sim = VehicleSimulation(car, road, dampers=LinearViscous(damping=1500.0))

    def final(dt: float) -> np.ndarray:
        res = sim.run(0.5, dt=dt)
        names = ["heave", "pitch", "roll", *(f"z_u.{c}" for c in car.corners)]
        return np.array([res[n][-1] for n in names])

    ref = final(2.5e-5)
    errors = [float(np.abs(final(dt) - ref).max()) for dt in (8e-4, 4e-4, 2e-4)]
    ratios = [errors[i] / errors[i + 1] for i in range(2)]
    print(f"\nerrors {errors}, ratios {ratios} (4th order: 16)")
    orders = [math.log2(r) for r in ratios]
    assert all(3.5 < p < 4.5 for p in orders), orders


# -- the step a HiL loop calls ------------------------------------------------------------
def test_stepper_reproduces_run_bit_for_bit() -> None:
    car = FullCar()
    road = _road(car, Harmonic(2.0, 0.01))
    sim = VehicleSimulation(car, road, controllers=HiLo(1, mode="ACM"))
    dt, n = 1e-4, 2000
    res = sim.run(n * dt, dt=dt, output_rate=1.0 / dt)
    zr, zrd = road.sample_grid(2 * n + 1, 0.5 * dt)  # the road run() samples
    st = sim.stepper(dt)
    st.reset(zr[:, 0], zrd[:, 0])
    for k in range(n):
        j = 2 * k
        out = st.step(zr[:, j], zrd[:, j], road_mid=(zr[:, j + 1], zrd[:, j + 1]),
                      road_end=(zr[:, j + 2], zrd[:, j + 2]))  # fmt: skip
    for name in ("heave", "pitch", "roll", "z_u.rear_left", "F_d.front_right", "i_d.front_left"):
        assert out[name] == res[name][-1], name


def test_stepper_takes_a_measured_force_at_one_corner() -> None:
    car = HalfCar()
    sim = VehicleSimulation(car, WheelRoads.in_phase(Harmonic(2.0, 0.01), car))
    st = sim.stepper(1e-4, external="rear")
    out = st.step([0.0, 0.0], [0.1, 0.1], damper_force=250.0)
    assert out["F_d.rear"] == 250.0
    assert out["F_d.front"] != 250.0
    with pytest.raises(ValidationError, match="needs a finite damper_force"):
        st.step([0.0, 0.0], [0.1, 0.1])
    with pytest.raises(ValidationError, match="Did you mean 'rear'"):
        sim.stepper(1e-4, external="reer")
    with pytest.raises(ValidationError, match=r"road must have one value per wheel \(2\)"):
        st.step([0.0], [0.0], damper_force=0.0)


def test_docs_page_example_runs() -> None:
    import re
    from pathlib import Path

    page = Path(__file__).resolve().parents[3] / "docs" / "vehicles.md"
    blocks = re.findall(r"```python\n(.*?)```", page.read_text(), flags=re.DOTALL)
    assert blocks
    exec(compile("\n".join(blocks), str(page), "exec"), {})


def test_batches_run_across_processes_in_order() -> None:
    from mrsuspension.engine.vehicle import run_vehicles

    car = HalfCar()
    sims = [VehicleSimulation(car, _road(car, Harmonic(f, 0.01))) for f in (1.0, 3.0, 5.0)]
    alone = [s.run(0.3) for s in sims]
    batch = run_vehicles(sims, duration=0.3, workers=2)
    for a, b in zip(alone, batch, strict=True):
        assert np.array_equal(a["F_T.rear"], b["F_T.rear"])
    with pytest.raises(ValidationError, match="takes VehicleSimulation objects"):
        run_vehicles([Simulation(Harmonic(1.0, 0.01))])
