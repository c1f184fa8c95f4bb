"""The compiled step (RK4 stages written out in scalars) against the textbook array form.

The reference below is classical RK4 over the state vector, written with numpy arrays
and the engine's own building blocks called one by one from Python (damper latch,
controller (:func:`mrsuspension.control.kernel.control`), ``rates`` into an array,
damper advance), in the order of the module
docstring of :mod:`mrsuspension.engine.kernel`. Both do the same arithmetic, so they
must agree to round-off for every controller, including the sliding-mode controller's
reference model (state entries 4-5), and for the ideal-damper and external-force paths.
"""

from __future__ import annotations

import numpy as np
import pytest

from mrsuspension.control import CONTROLLERS, UserLaw, controller_class, make_controller
from mrsuspension.control import kernel as CK
from mrsuspension.dampers import WangSymmetric
from mrsuspension.dampers import kernels as DK
from mrsuspension.engine import KernelArrays, Simulation
from mrsuspension.engine import kernel as EK
from mrsuspension.excitation import Harmonic
from mrsuspension.vehicle import kernel as VK

DT = 1e-4
N_STEPS = 400
ROAD = Harmonic(3.0, 0.03)


def reference_step(y: np.ndarray, road: list[tuple[float, float]], a: KernelArrays) -> None:
    mem, ds = a.memory, a.damper_state
    xd, vd, ad = y[2] - y[0], y[3] - y[1], mem[EK.M_AD]
    DK.damper_sample(
        a.damper_kind, a.damper_params, ds, a.damper_estimator_kind, a.damper_estimator_params,
        a.damper_estimator_state, xd, vd, ad, mem[EK.M_ID],
    )  # fmt: skip
    if a.controller_estimator_kind == CK.EST_SHARED:
        vm = ds[DK.WS_VM]
    else:
        vm = DK.estimator_update(
            a.controller_estimator_kind, a.controller_estimator_params,
            a.controller_estimator_state, xd, vd, ad,
        )  # fmt: skip
    mem[EK.M_VM] = vm
    # the step count; the signals (control/signals.py) are filled for the laws from
    # C_SIGNALS on only (user laws: tests/unit/control/test_signals.py)
    count = mem[EK.M_STEP]
    mem[EK.M_STEP] = count + 1.0
    assert a.controller_kind < CK.C_SIGNALS
    i_d, i_z, z_c, target = CK.control(
        a.controller_kind, a.controller_params, a.vehicle, a.damper_params, y, ad, vm,
        mem[EK.M_PH : EK.M_PH + DK.PH_SIZE],
    )  # fmt: skip
    mem[EK.M_ID], mem[EK.M_IZ], mem[EK.M_ZC], mem[EK.M_TARGET] = i_d, i_z, z_c, target
    # the current's chatter count (tests/unit/engine/test_aliasing.py), in Python
    change = i_d - mem[EK.M_IPREV]
    if abs(change) > EK.CHATTER_CURRENT:
        mem[EK.M_NREV] += 1.0 if change * mem[EK.M_DI] < 0.0 else 0.0
        mem[EK.M_DI] = change
    else:
        mem[EK.M_DI] = 0.0
    mem[EK.M_IPREV] = i_d
    reference = a.controller_kind == CK.C_SLIDING

    def f(state: np.ndarray, zr: float, zrd: float) -> tuple[np.ndarray, float, float]:
        dy = np.zeros(VK.NY)
        fd, ft = EK.rates(
            state, zr, zrd, a.vehicle, a.force_source, a.damper_kind, a.damper_params, ds,
            a.controller_params, mem, reference, dy,
        )  # fmt: skip
        return dy, fd, ft

    k1, _, _ = f(y, *road[0])
    k2, _, _ = f(y + (0.5 * DT) * k1, *road[1])
    k3, _, _ = f(y + (0.5 * DT) * k2, *road[1])
    k4, _, _ = f(y + DT * k3, *road[2])
    y += (DT / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    k5, fd, ft = f(y, *road[2])
    mem[EK.M_AS], mem[EK.M_AU], mem[EK.M_A0] = k5[1], k5[3], k5[5]
    mem[EK.M_FD], mem[EK.M_FT], mem[EK.M_AD] = fd, ft, k5[3] - k5[1]
    DK.damper_advance(a.damper_kind, a.damper_params, ds, xd, vd, mem[EK.M_ID], DT)


def simulation(law: str) -> Simulation:
    ctl = make_controller(law)
    return Simulation(
        ROAD, controller=ctl, damper=WangSymmetric(force_gain=2.5 if ctl.needs_inverse else 1.0)
    )


def road_at(k: int) -> list[tuple[float, float]]:
    t = np.array([k * DT, (k + 0.5) * DT, (k + 1) * DT])
    return list(zip(ROAD.displacement(t).tolist(), ROAD.velocity(t).tolist(), strict=True))


def run_both(sim: Simulation, external: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """States and mem after every step: compiled step, array reference."""
    a_eng, a_ref = sim.kernel_arrays(DT), sim.kernel_arrays(DT)
    if external is not None:
        a_eng = a_eng.replace(force_source=CK.F_EXTERNAL)
        a_ref = a_ref.replace(force_source=CK.F_EXTERNAL)
        for a in (a_eng, a_ref):
            a.memory[EK.M_FEXT] = external
    y_eng = np.zeros(VK.NY)
    y_ref = np.zeros(VK.NY)
    scratch = np.zeros(EK.SCRATCH_SIZE)
    for a, y in ((a_eng, y_eng), (a_ref, y_ref)):
        EK.start(y, 0.0, float(ROAD.velocity(0.0)), *a.args(), scratch)
    out_eng, out_ref = [], []
    for k in range(N_STEPS):
        road = road_at(k)
        EK.step(y_eng, DT, *road[0], *road[1], *road[2], *a_eng.args(), scratch)
        reference_step(y_ref, road, a_ref)
        out_eng.append(np.concatenate([y_eng, a_eng.memory]))
        out_ref.append(np.concatenate([y_ref, a_ref.memory]))
    return np.array(out_eng), np.array(out_ref)


def assert_same(eng: np.ndarray, ref: np.ndarray) -> None:
    # NaN (no target force) in the same places, equal to round-off elsewhere
    assert np.array_equal(np.isnan(eng), np.isnan(ref))
    ok = ~np.isnan(ref)
    scale = np.maximum(np.abs(ref), 1e-9)
    assert np.max(np.abs(eng[ok] - ref[ok]) / scale[ok]) <= 1e-12


#: the compiled kernel's laws (the reference calls ``control`` below C_SIGNALS; user laws,
#: e.g. control/literature.py's, read the signals: tests/unit/control/test_signals.py)
COMPILED = sorted(law for law in CONTROLLERS if not issubclass(controller_class(law), UserLaw))


@pytest.mark.parametrize("law", COMPILED)
def test_scalar_stages_equal_the_array_rk4(law: str) -> None:
    eng, ref = run_both(simulation(law))
    assert np.ptp(eng[:, 0]) > 1e-4  # the body moved: the comparison is not vacuous
    assert_same(eng, ref)


def test_sliding_mode_reference_model_is_integrated() -> None:
    eng, ref = run_both(simulation("sliding-mode"))
    assert np.ptp(eng[:, 4]) > 1e-5  # z_s0 moves with the wheel
    assert_same(eng[:, 4:6], ref[:, 4:6])


def test_external_force_path() -> None:
    eng, ref = run_both(simulation("passive"), external=150.0)
    assert np.all(eng[:, VK.NY + EK.M_FD] == 150.0)
    assert_same(eng, ref)
