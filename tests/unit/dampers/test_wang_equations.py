"""The dissertation's damper model against hand values (model reference, sections 2.1-2.2).

Every expected value is computed here with plain ``math`` from the model reference's
equations and
tables (``wang_reference`` in ``tests/conftest.py``), never from the package's output.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mrsuspension import parameters
from mrsuspension.characterisation import harmonic_loop
from mrsuspension.dampers import WangAsymmetric, WangSymmetric
from mrsuspension.dampers import kernels as K
from mrsuspension.parameters import ParameterSet

WANG_SETS = ["wang-symmetric-low", "wang-symmetric-high", "wang-asymmetric"]
SYMMETRIC_SETS = ["wang-symmetric-low", "wang-symmetric-high"]

# the state of the worked example: v_d = 0.1 m/s, a_d < 0, i = 0.2 A, v_m = 0.25 m/s
V, A, CURRENT, VM = 0.1, -1.0, 0.2, 0.25


def make_model(set_name: str, **options) -> WangSymmetric:
    cls = WangAsymmetric if set_name == "wang-asymmetric" else WangSymmetric
    return cls(set_name, **options)


def params_of(model: WangSymmetric):
    """The compiled parameter vector, through the public kernel view."""
    return model.kernel(1e-3).params


# ----------------------------------------------------------------------------------
# the registered sets are the model reference's tables
@pytest.mark.parametrize("set_name", WANG_SETS)
def test_registered_set_values_are_the_spec_tables(set_name, spec_sets):
    pset = parameters.get(set_name)
    assert dict(pset.values) == spec_sets[set_name]


# ----------------------------------------------------------------------------------
# C_i, eq. (2.9)
@pytest.mark.parametrize("set_name", WANG_SETS)
def test_current_gain_is_exactly_one_at_zero_current(set_name):
    model = make_model(set_name)
    assert float(model.current_gain(0.0)) == 1.0
    assert K.current_gain(params_of(model), 0.0) == 1.0


@pytest.mark.parametrize("set_name", WANG_SETS)
@pytest.mark.parametrize("current", [0.05, 0.2, 0.3, 0.5])
def test_current_gain_matches_eq_2_9(set_name, current, wang_reference):
    ref = wang_reference(set_name)
    got = float(make_model(set_name).current_gain(current))
    assert got == pytest.approx(ref.current_gain(current), rel=1e-13)


def test_current_gain_hand_value():
    # (2.9) with the 0.5-5 Hz set at i = 0.2 A, written out term by term:
    # 1 + 9.244/(1+exp(-7.258*(0.2+0.079))) - 9.244/(1+exp(-7.258*0.079))
    expected = 1.0 + 9.244 / (1.0 + math.exp(-7.258 * 0.279)) - 9.244 / (1.0 + math.exp(-0.573382))
    assert expected == pytest.approx(3.2541677910, rel=1e-10)
    got = WangSymmetric("wang-symmetric-low").current_gain([0.0, 0.2])
    assert got.shape == (2,)
    assert got[1] == pytest.approx(expected, rel=1e-13)


# ----------------------------------------------------------------------------------
# F_t (2.7), alpha (2.11), k_v (2.10)
@pytest.mark.parametrize("set_name", WANG_SETS)
@pytest.mark.parametrize("vm", [0.0, 0.05, 0.25, 0.75, 1.0])
def test_kernel_building_blocks(set_name, vm, wang_reference):
    ref = wang_reference(set_name)
    p = params_of(make_model(set_name))
    assert K.transition_force(p, vm) == pytest.approx(ref.transition_force(vm), rel=1e-14)
    assert K.hysteresis_slope(p, vm) == pytest.approx(ref.alpha(vm), rel=1e-14)
    for v in (0.3, -0.3):
        expected = 1.0 + ref.k_v(vm, v) * abs(v)
        assert K.linear_rise(p, v, vm) == pytest.approx(expected, rel=1e-14)


def test_transition_force_hand_value():
    # F_t = F0 (1 + exp(a1 v_m)) = 68.506 * (1 + exp(5.197 * 0.25))
    assert 68.506 * (1.0 + math.exp(5.197 * 0.25)) == pytest.approx(319.686381564, rel=1e-10)


def _bare_model(set_name: str, **changes: float) -> WangSymmetric:
    """Mean model with k1 = 0: F = F_t tanh(alpha v / 2) at zero current."""
    pset = parameters.get(set_name).replace(k1=0.0, **changes)
    return WangSymmetric(pset, hysteresis=False)


@pytest.mark.parametrize("set_name", SYMMETRIC_SETS)
@pytest.mark.parametrize("vm", [0.05, 0.25, 0.6])
def test_transition_force_through_the_force(set_name, vm, wang_reference):
    # with k1 = 0 and a saturated tanh, the force is F_t itself (eq. 2.7)
    ref = wang_reference(set_name)
    model = _bare_model(set_name)
    f = float(model.force(0.0, 5.0, 0.0, 0.0, peak_velocity=vm))
    assert f == pytest.approx(ref.transition_force(vm), rel=1e-13)
    f_neg = float(model.force(0.0, -5.0, 0.0, 0.0, peak_velocity=vm))
    assert f_neg == pytest.approx(-ref.transition_force(vm), rel=1e-13)


@pytest.mark.parametrize("set_name", SYMMETRIC_SETS)
@pytest.mark.parametrize("vm", [0.05, 0.25, 0.6])
def test_alpha_through_the_force(set_name, vm, wang_reference):
    # F = F_t tanh(alpha v/2)  =>  alpha = 2 atanh(F / F_t) / v   (eq. 2.11)
    ref = wang_reference(set_name)
    model = _bare_model(set_name)
    v = 1.0 / ref.alpha(vm)  # tanh argument 0.5: well conditioned
    f = float(model.force(0.0, v, 0.0, 0.0, peak_velocity=vm))
    alpha = 2.0 * math.atanh(f / ref.transition_force(vm)) / v
    assert alpha == pytest.approx(ref.p["a0"] / (1.0 + ref.p["k0"] * vm), rel=1e-11)


@pytest.mark.parametrize("set_name", SYMMETRIC_SETS)
@pytest.mark.parametrize("v", [0.2, -0.2, 0.6])
def test_k_v_through_the_force(set_name, v, wang_reference):
    # mean model at zero current: F / (F_t tanh(alpha v / 2)) - 1 = k_v |v|   (eq. 2.10)
    ref = wang_reference(set_name)
    vm = 0.25
    model = WangSymmetric(set_name, hysteresis=False)
    f = float(model.force(0.0, v, 0.0, 0.0, peak_velocity=vm))
    k_v = (f / (ref.transition_force(vm) * math.tanh(ref.alpha(vm) * v / 2.0)) - 1.0) / abs(v)
    assert k_v == pytest.approx(ref.p["k1"] * math.exp(-ref.p["a4"] * vm), rel=1e-10)


# ----------------------------------------------------------------------------------
# v_h, eqs. (2.12) and (2.13): the force vanishes at v_d = -v_h
@pytest.mark.parametrize("set_name", SYMMETRIC_SETS)
@pytest.mark.parametrize("variant", ["2.12", "2.13"])
@pytest.mark.parametrize("accel", [-3.0, 3.0])
@pytest.mark.parametrize("current", [0.0, 0.2, 0.45])
def test_zero_force_velocity_is_minus_v_h(set_name, variant, accel, current, wang_reference):
    ref = wang_reference(set_name)
    p = ref.p
    factor = 1.0
    if variant == "2.12":
        factor = (
            1.0
            + p["k3"] / (1.0 + math.exp(-p["a3"] * (current + p["I1"])))
            - p["k3"] / (1.0 + math.exp(-p["a3"] * p["I1"]))
        )
    v_h = math.copysign(1.0, accel) * p["k4"] * VM * factor
    model = WangSymmetric(set_name, vh_variant=variant, estimator="known", value=VM)
    f = model.force(0.0, [-v_h - 1e-6, -v_h, -v_h + 1e-6], accel, current)
    assert abs(f[1]) < 1e-7
    assert f[0] < -1e-4
    assert f[2] > 1e-4
    # H(i) itself, through the kernel
    kp = params_of(model)
    assert K.hysteresis_current_factor(kp, current) == pytest.approx(factor, rel=1e-14)


def test_h_factor_hand_value():
    # H(0.2) of the 0.5-5 Hz set: 1 + 9.186 (sigma(6.635 * 0.467) - sigma(6.635 * 0.267))
    h = 1.0 + 9.186 / (1.0 + math.exp(-6.635 * 0.467)) - 9.186 / (1.0 + math.exp(-6.635 * 0.267))
    assert h == pytest.approx(1.93865291, rel=1e-8)
    kp = params_of(WangSymmetric("wang-symmetric-low", vh_variant="2.12"))
    assert K.hysteresis_current_factor(kp, 0.2) == pytest.approx(h, rel=1e-14)
    kp13 = params_of(WangSymmetric("wang-symmetric-low", vh_variant="2.13"))
    assert K.hysteresis_current_factor(kp13, 0.2) == 1.0


def test_one_name_one_model_the_default_is_the_simulations():
    """Issue 31: ``WangSymmetric()`` is the model every simulation runs ((2.13))."""
    from mrsuspension.dampers.wang import VEHICLE_VH_VARIANT
    from mrsuspension.engine import Simulation
    from mrsuspension.excitation import Harmonic

    assert WangSymmetric().vh_variant == VEHICLE_VH_VARIANT == "2.13"
    assert WangAsymmetric().vh_variant == "2.13"
    assert Simulation(Harmonic(1.0, 0.01)).damper.describe() == WangSymmetric().describe()


def test_v_h_variants_differ_by_h():
    # with a nonzero current the two variants have different zero-force velocities
    m12 = WangSymmetric(vh_variant="2.12")
    m13 = WangSymmetric(vh_variant="2.13")
    v_h_213 = 0.119 * VM  # -sgn(a) k4 v_m with a < 0
    assert abs(float(m13.force(0.0, -v_h_213, A, CURRENT, peak_velocity=VM))) < 1e-7
    assert abs(float(m12.force(0.0, -v_h_213, A, CURRENT, peak_velocity=VM))) > 100.0


# ----------------------------------------------------------------------------------
# the full force, eq. (2.15)
def test_full_force_eq_2_15_hand_values(wang_reference):
    ref = wang_reference("wang-symmetric-low")
    cases = [
        # (options, reference keyword arguments, value from the plain-math reference)
        ({"vh_variant": "2.12"}, {"variant": "2.12"}, 1199.2706329554765),
        ({"vh_variant": "2.13"}, {"variant": "2.13"}, 1173.4263372066903),
        ({"hysteresis": False}, {"hysteresis": False}, 1109.1850566841504),
        ({"hysteresis": False, "vh_variant": "2.13"}, {"hysteresis": False}, 1109.1850566841504),
        ({"force_gain": 2.5, "vh_variant": "2.12"}, {"kd": 2.5}, 2998.1765823886913),
        ({"force_gain": 2.5, "vh_variant": "2.13"}, {"kd": 2.5, "variant": "2.13"}, 2933.565843017),
    ]  # fmt: skip
    for options, kwargs, pinned in cases:
        expected = ref.force(V, A, CURRENT, VM, **kwargs)
        assert expected == pytest.approx(pinned, rel=1e-12)
        model = WangSymmetric("wang-symmetric-low", **options)
        got = float(model.force(0.0, V, A, CURRENT, peak_velocity=VM))
        assert got == pytest.approx(expected, rel=1e-12), options


def test_force_gain_scales_linearly():
    base = WangSymmetric()
    scaled = WangSymmetric(force_gain=2.5)
    rng = np.random.default_rng(1)
    v = rng.uniform(-1, 1, 200)
    a = rng.choice([-5.0, 0.0, 5.0], 200)
    i = rng.uniform(0, 0.5, 200)
    vm = rng.uniform(0.01, 1, 200)
    f1 = base.force(0.0, v, a, i, peak_velocity=vm)
    f2 = scaled.force(0.0, v, a, i, peak_velocity=vm)
    np.testing.assert_allclose(f2, 2.5 * f1, rtol=1e-13, atol=1e-12)


@pytest.mark.parametrize("set_name", SYMMETRIC_SETS)
def test_full_force_random_points(set_name, wang_reference):
    ref = wang_reference(set_name)
    rng = np.random.default_rng(7)
    for variant in ("2.12", "2.13"):
        model = WangSymmetric(set_name, vh_variant=variant, force_gain=1.7)
        for _ in range(40):
            v, a = rng.uniform(-1, 1), rng.choice([-2.0, 0.0, 2.0])
            i, vm = rng.uniform(0, 0.5), rng.uniform(0.0, 1.0)
            got = float(model.force(0.3, v, a, i, peak_velocity=vm))
            expected = ref.force(v, a, i, vm, variant=variant, kd=1.7)
            assert got == pytest.approx(expected, rel=1e-11, abs=1e-9)


# ----------------------------------------------------------------------------------
# the asymmetric model, eqs. (2.19)-(2.21)
@pytest.mark.parametrize("velocity", [0.1, -0.1, 0.4, -0.4])
@pytest.mark.parametrize("accel", [-1.0, 1.0])
@pytest.mark.parametrize("variant", ["2.12", "2.13"])
def test_asymmetric_force_hand_values(velocity, accel, variant, wang_reference):
    ref = wang_reference("wang-asymmetric")
    model = WangAsymmetric(vh_variant=variant)
    got = float(model.force(0.0, velocity, accel, CURRENT, peak_velocity=VM))
    assert got == pytest.approx(ref.force(velocity, accel, CURRENT, VM, variant=variant), rel=1e-12)


def test_asymmetric_force_written_out():
    # (2.19)-(2.21) at v = -0.1 m/s (rebound), a > 0, i = 0.2 A, v_m = 0.25 m/s, term by term
    p = {
        "a0": 995.499, "a1": 1.417, "a2": 5.225, "a3": 2.441, "a4": 2.383, "I0": 0.268,
        "I1": 1.131, "k0": 177.51, "k1e": 4.673, "k2": 10.61, "k3": 10.666, "k4": -0.125,
        "k5": 0.269, "k6": 0.453, "F0": 79.92,
    }  # fmt: skip
    ci = 1 + p["k2"] / (1 + math.exp(-p["a2"] * 0.468)) - p["k2"] / (1 + math.exp(-p["a2"] * 0.268))
    ft = p["F0"] * (1 + math.exp(p["a1"] * 0.25))
    alpha = p["a0"] / (1 + p["k0"] * 0.25)
    h = 1 + p["k3"] / (1 + math.exp(-p["a3"] * 1.331)) - p["k3"] / (1 + math.exp(-p["a3"] * 1.131))
    vh = 1.0 * p["k4"] * 0.25 * h
    vb = p["k6"] * 0.25
    fb = p["k5"] * ci * ft
    kve = p["k1e"] * math.exp(-p["a4"] * 0.25)
    expected = ci * (ft * math.tanh(alpha * (-0.1 + vh + vb) / 2) - fb) * (1 + kve * 0.1)
    assert expected == pytest.approx(-481.37881033, rel=1e-9)
    got = float(WangAsymmetric(vh_variant="2.12").force(0.0, -0.1, 1.0, 0.2, peak_velocity=0.25))
    assert got == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("velocity", [0.2, -0.2])
def test_asymmetric_linear_rise_coefficient_by_direction(velocity, wang_reference):
    # with k4 = k5 = k6 = 0 and i = 0: F / (F_t tanh(alpha v/2)) - 1 = k_v |v| with
    # k_vc = k1c exp(-a4 v_m) in compression and k_ve = k1e exp(-a4 v_m) in rebound (2.21)
    ref = wang_reference("wang-asymmetric")
    vm = 0.25
    pset = parameters.get("wang-asymmetric").replace(k4=0.0, k5=0.0, k6=0.0)
    f = float(WangAsymmetric(pset).force(0.0, velocity, 0.0, 0.0, peak_velocity=vm))
    k_v = (f / (ref.transition_force(vm) * math.tanh(ref.alpha(vm) * velocity / 2)) - 1) / 0.2
    k1 = 16.877 if velocity > 0 else 4.673
    assert k_v == pytest.approx(k1 * math.exp(-2.383 * vm), rel=1e-10)


def test_asymmetric_rebound_force_exceeds_compression_force():
    # the point of the asymmetric model: |F(-v)| > F(v) for the mean model
    m = WangAsymmetric(hysteresis=False)
    f = m.force(0.0, [0.2, -0.2], 0.0, 0.2, peak_velocity=0.3)
    assert -f[1] > f[0] > 0


# ----------------------------------------------------------------------------------
# reductions (model reference, section 2.2)
def _random_inputs(seed: int, n: int = 500):
    rng = np.random.default_rng(seed)
    x = rng.uniform(-0.05, 0.05, n)
    v = rng.uniform(-1.2, 1.2, n)
    a = rng.uniform(-50, 50, n)
    a[::7] = 0.0
    i = rng.uniform(0.0, 0.5, n)
    vm = rng.uniform(0.0, 1.2, n)
    return x, v, a, i, vm


@pytest.mark.parametrize("set_name", SYMMETRIC_SETS)
@pytest.mark.parametrize("variant", ["2.12", "2.13"])
def test_asymmetric_model_with_a_symmetric_set_is_the_symmetric_model(set_name, variant):
    sym = WangSymmetric(set_name, vh_variant=variant)
    asym = WangAsymmetric(set_name, vh_variant=variant)
    x, v, a, i, vm = _random_inputs(3)
    np.testing.assert_allclose(
        asym.force(x, v, a, i, peak_velocity=vm), sym.force(x, v, a, i, peak_velocity=vm),
        rtol=1e-12, atol=1e-9,
    )  # fmt: skip
    # with the estimators too (pointwise and causal)
    np.testing.assert_allclose(asym.force(x, v, a, i), sym.force(x, v, a, i), rtol=1e-12, atol=1e-9)
    t = np.arange(x.size) * 1e-3
    r_a, r_s = asym.response(t, x, v, a, i), sym.response(t, x, v, a, i)
    np.testing.assert_allclose(r_a.force, r_s.force, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(r_a.peak_velocity, r_s.peak_velocity, rtol=1e-12)


def test_asymmetric_set_with_k5_k6_zero_and_equal_k1_is_the_symmetric_model():
    asym_set = parameters.get("wang-asymmetric").replace(k5=0.0, k6=0.0, k1e=16.877)
    sym_values = {k: v for k, v in asym_set.items() if k not in ("k1c", "k1e", "k5", "k6")}
    sym_values["k1"] = 16.877
    sym_set = ParameterSet(name="sym-from-asym", model="wang-symmetric", values=sym_values)
    x, v, a, i, vm = _random_inputs(4)
    for variant in ("2.12", "2.13"):
        asym = WangAsymmetric(asym_set, vh_variant=variant)
        sym = WangSymmetric(sym_set, vh_variant=variant)
        np.testing.assert_allclose(
            asym.force(x, v, a, i, peak_velocity=vm), sym.force(x, v, a, i, peak_velocity=vm),
            rtol=1e-12, atol=1e-9,
        )  # fmt: skip
        # and the result is odd in (v, a): the asymmetry is gone
        np.testing.assert_allclose(
            asym.force(x, -v, -a, i, peak_velocity=vm), -asym.force(x, v, a, i, peak_velocity=vm),
            rtol=1e-12, atol=1e-9,
        )  # fmt: skip
    # whereas the published asymmetric set is not odd
    full = WangAsymmetric()
    f_pos = full.force(0.0, 0.3, 0.0, 0.2, peak_velocity=0.3)
    f_neg = full.force(0.0, -0.3, 0.0, 0.2, peak_velocity=0.3)
    assert abs(f_pos + f_neg) > 50.0


@pytest.mark.parametrize("set_name", WANG_SETS)
@pytest.mark.parametrize("variant", ["2.12", "2.13"])
def test_hysteresis_false_is_k4_zero(set_name, variant, wang_reference):
    cls = WangAsymmetric if set_name == "wang-asymmetric" else WangSymmetric
    mean = cls(set_name, hysteresis=False, vh_variant=variant)
    k4_zero = cls(parameters.get(set_name).replace(k4=0.0), vh_variant=variant)
    x, v, a, i, vm = _random_inputs(5)
    f_mean = mean.force(x, v, a, i, peak_velocity=vm)
    np.testing.assert_allclose(
        f_mean, k4_zero.force(x, v, a, i, peak_velocity=vm), rtol=1e-12, atol=1e-9
    )
    # the mean model does not depend on the sign of the acceleration
    np.testing.assert_allclose(
        f_mean, mean.force(x, v, -a, i, peak_velocity=vm), rtol=1e-12, atol=1e-9
    )
    ref = wang_reference(set_name)
    for k in range(0, 500, 50):
        expected = ref.force(v[k], a[k], i[k], vm[k], hysteresis=False)
        assert f_mean[k] == pytest.approx(expected, rel=1e-11, abs=1e-9)


# ----------------------------------------------------------------------------------
# k4 < 0: the decreasing-velocity branch is the upper branch of the F-v loop
def _branches(model: WangSymmetric, current: float):
    """Forces of a harmonic loop paired at equal velocity: (decreasing, increasing)."""
    loop = harmonic_loop(model, frequency=1.5, amplitude=0.0125, current=current)
    n = loop.force.size
    k = np.arange(1, n // 2)  # skip the two turning points of the velocity
    mirror = n - k  # same velocity (cos is even), opposite acceleration
    np.testing.assert_allclose(loop.velocity[k], loop.velocity[mirror], atol=1e-12)
    # x > 0 <=> a = -omega^2 x < 0 <=> decreasing velocity
    assert np.all(loop.stroke[k] > 0)
    assert np.all(loop.stroke[mirror] < 0)
    return loop.force[k], loop.force[mirror]


@pytest.mark.parametrize("set_name", SYMMETRIC_SETS)
@pytest.mark.parametrize("current", [0.0, 0.2])
def test_negative_k4_puts_decreasing_velocity_branch_on_top(set_name, current):
    assert parameters.get(set_name)["k4"] < 0
    decreasing, increasing = _branches(WangSymmetric(set_name), current)
    assert np.all(decreasing > increasing)
    # the mean model has no loop ...
    d0, i0 = _branches(WangSymmetric(set_name, hysteresis=False), current)
    np.testing.assert_allclose(d0, i0, rtol=1e-12, atol=1e-9)
    # ... and a positive k4 would put the increasing branch on top
    flipped = WangSymmetric(parameters.get(set_name).replace(k4=-parameters.get(set_name)["k4"]))
    d1, i1 = _branches(flipped, current)
    assert np.all(d1 < i1)


@pytest.mark.parametrize("set_name", SYMMETRIC_SETS)
def test_negative_k4_branch_order_through_force(set_name):
    model = WangSymmetric(set_name)
    v = np.linspace(-0.2, 0.2, 81)
    upper = model.force(0.0, v, -1.0, 0.2, peak_velocity=0.25)  # decreasing velocity
    lower = model.force(0.0, v, +1.0, 0.2, peak_velocity=0.25)  # increasing velocity
    assert np.all(upper > lower)


# ----------------------------------------------------------------------------------
# the compiled kernel (the path of response(), the engine and the HiL loop) obeys the
# same equations as force()
@pytest.mark.parametrize("set_name", WANG_SETS)
@pytest.mark.parametrize("variant", ["2.12", "2.13"])
@pytest.mark.parametrize("vm", [0.05, 0.3, 0.9])
def test_compiled_path_matches_the_equations(set_name, variant, vm, wang_reference):
    ref = wang_reference(set_name)
    cls = WangAsymmetric if set_name == "wang-asymmetric" else WangSymmetric
    model = cls(set_name, vh_variant=variant, force_gain=1.3, estimator="known", value=vm)
    x, v, a, i, _ = _random_inputs(11, n=200)
    t = np.arange(v.size) * 1e-3
    r = model.response(t, x, v, a, i)
    np.testing.assert_array_equal(r.peak_velocity, vm)
    expected = [ref.force(v[k], a[k], i[k], vm, variant=variant, kd=1.3) for k in range(v.size)]
    np.testing.assert_allclose(r.force, expected, rtol=1e-11, atol=1e-9)
