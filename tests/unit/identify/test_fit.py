"""The fit: analytic Jacobians, bounds and fixing, scaling, recovery of known parameters."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from mrsuspension import parameters
from mrsuspension.characterisation import harmonic_loop
from mrsuspension.dampers import make_damper
from mrsuspension.errors import ValidationError
from mrsuspension.identify.fit import FitProblem, fit_loops
from mrsuspension.identify.preprocess import Loop

PAIRS = [(0.5, 0.025), (1.5, 0.0125), (2.5, 0.0125), (5.0, 0.0025)]


def as_loop(h, label: str = "t") -> Loop:
    w = 2 * math.pi * h.condition.frequency
    return Loop(
        label, h.time, h.stroke, h.velocity, -h.stroke * w * w, h.force, h.current,
        h.condition.frequency, h.condition.amplitude, h.peak_velocity,
    )  # fmt: skip


def campaign(model: str, pset=None, options=None, currents=(0.0, 0.2, 0.4), pairs=PAIRS):
    own = {"vh_variant": "2.12"} if model.startswith("wang-") else {}  # what the fit uses
    damper = make_damper(model, pset, **{**own, **(options or {})})
    return [as_loop(harmonic_loop(damper, f, a, i)) for f, a in pairs for i in currents]


def numeric_jacobian(problem: FitProblem, x: np.ndarray) -> np.ndarray:
    out = np.empty((problem.data.force.size, x.size))
    for j in range(x.size):
        h = 1e-6 * max(abs(x[j]), 1e-2)
        xp, xm = x.copy(), x.copy()
        xp[j] += h
        xm[j] -= h
        out[:, j] = (problem.residuals(xp) - problem.residuals(xm)) / (2 * h)
    return out


@pytest.mark.parametrize(
    ("model", "pset", "options"),
    [
        ("wang-symmetric", "wang-symmetric-low", {}),
        ("wang-symmetric", "wang-symmetric-high", {"vh_variant": "2.13", "force_gain": 2.5}),
        ("wang-symmetric", "wang-symmetric-low", {"hysteresis": False}),
        ("wang-asymmetric", "wang-asymmetric", {}),
        ("wang-asymmetric", "wang-symmetric-low", {}),  # k5 = k6 = 0 start
        ("bingham", None, {}),
        ("linear", None, {}),
    ],
)
def test_analytic_jacobian_matches_finite_differences(model, pset, options) -> None:
    loops = campaign(model, pset, options)
    problem = FitProblem(loops, model, start=pset, model_options=options)
    rng = np.random.default_rng(0)
    x = problem.x_start * (1 + 0.1 * rng.uniform(-1, 1, problem.x_start.size)) + 1e-3
    analytic = problem.jacobian(x)
    numeric = numeric_jacobian(problem, x)
    scale = np.abs(numeric).max(axis=0) + 1e-12
    assert np.max(np.abs(analytic - numeric) / scale) < 1e-5


def test_options_fix_parameters_that_have_no_effect() -> None:
    loops = campaign("wang-symmetric", currents=(0.0, 0.3), pairs=PAIRS[:2])
    assert "k4" not in FitProblem(loops, model_options={"hysteresis": False}).free
    free = FitProblem(loops, model_options={"vh_variant": "2.13"}).free
    assert not {"a3", "k3", "I1"} & set(free)
    assert "n" not in FitProblem(loops, "spencer").free


def test_fixed_bounds_and_names_are_checked() -> None:
    loops = campaign("wang-symmetric", currents=(0.0, 0.3), pairs=PAIRS[:2])
    p = FitProblem(loops, fixed={"k4": -0.2, "F0": None}, bounds={"a1": (0.0, 8.0)})
    assert "k4" not in p.free
    assert "F0" not in p.free
    assert p.values(p.x_start)["k4"] == -0.2
    assert p.bounds["a1"] == (0.0, 8.0)
    with pytest.raises(
        ValidationError, match="unknown parameter of model 'wang-symmetric' to fix 'k44'"
    ):
        FitProblem(loops, fixed=["k44"])
    with pytest.raises(ValidationError, match="must have low < high"):
        FitProblem(loops, bounds={"a1": (2.0, 1.0)})
    with pytest.raises(ValidationError, match="unknown option of model 'bingham'"):
        FitProblem(loops, "bingham", model_options={"hysteresis": False})
    # a start value outside the default bounds widens them, with a note
    p = FitProblem(loops, start=parameters.get("wang-symmetric-low").replace(k4=-3.0))
    assert p.bounds["k4"][0] < -3.0
    assert any("k4" in n for n in p.notes)


def test_scaling_brings_another_damper_size_to_the_data() -> None:
    big = parameters.get("wang-symmetric-low").replace(F0=68.506 * 3.0)
    loops = campaign("wang-symmetric", big, currents=(0.0, 0.4), pairs=PAIRS[:2])
    p = FitProblem(loops)  # starts from Table 2.2: forces 3 times too small
    scaled = p.scaled(p.x_start)
    assert scaled[p.free.index("F0")] == pytest.approx(3 * 68.506, rel=1e-9)
    assert np.max(np.abs(p.residuals(scaled))) < 1e-12


def test_wang_recovers_its_parameters_from_a_perturbed_start() -> None:
    truth = parameters.get("wang-symmetric-low")
    loops = campaign("wang-symmetric", truth, currents=(0.0, 0.1, 0.2, 0.3, 0.4))
    rng = np.random.default_rng(7)
    start = truth.replace(**{k: v * (1 + rng.uniform(-0.2, 0.2)) for k, v in truth.items()})
    result = fit_loops(loops, start=start, source="unit test")
    assert result.converged
    assert result.nrmse.max() < 1e-5
    for key in ("F0", "a0", "k2", "a2", "I0"):
        assert result.parameters[key] == pytest.approx(truth[key], rel=1e-3)
    # the fitted set has provenance, units and drops straight into the simulator
    pset = result.parameters
    assert pset.source == "unit test"
    assert pset.units["F0"] == "N"
    assert pset.frequency_range == (0.5, 5.0)
    damper = make_damper("wang-symmetric", pset, vh_variant="2.12")  # the form it was fitted in
    lp = loops[3]
    f = damper.force(
        lp.stroke, lp.velocity, lp.acceleration, lp.current, peak_velocity=lp.peak_velocity
    )
    np.testing.assert_allclose(f, result.model_forces[3], rtol=1e-12)


def test_finite_difference_jacobian_reaches_the_same_fit() -> None:
    loops = campaign("bingham", currents=(0.0, 0.2, 0.4), pairs=PAIRS[:2])
    a = fit_loops(
        loops, "bingham", start={"fc_a": 50, "fc_b": 500, "c0_a": 1000, "c0_b": 9000, "f0": 1}
    )
    b = fit_loops(loops, "bingham", start={"fc_a": 50, "fc_b": 500, "c0_a": 1000, "c0_b": 9000, "f0": 1},
                  jacobian="2-point")  # fmt: skip
    assert a.jacobian == "analytic"
    assert b.jacobian == "2-point"
    for k in ("fc_a", "fc_b", "c0_a", "c0_b"):
        assert a.parameters[k] == pytest.approx(b.parameters[k], rel=1e-5)


def test_spencer_fit_runs_over_repeated_cycles_and_improves() -> None:
    """Stateful model: its slow k0/(c0+c1) mode (seconds) leaves a force offset that
    depends on the run length, so the loops are compared without their means."""
    truth = parameters.get("spencer-1997")
    loops = [
        replace(lp, force=lp.force - lp.force.mean(), offset_removed=True)
        for lp in campaign("spencer", truth, currents=(0.0, 0.3), pairs=[(2.5, 0.01)])
    ]
    start = truth.replace(c0a=2100 * 1.3, alpha_a=14000 * 0.7, alpha_b=69500 * 1.2)
    free = ["c0a", "alpha_a", "alpha_b"]
    fixed = [k for k in truth if k not in free and k != "max_voltage"]
    p = FitProblem(loops, "spencer", start=start, fixed=fixed, model_options={"substeps": 4})
    before = float(np.sqrt(np.sum(p.residuals(p.x_start) ** 2) / len(loops)))
    result = p.solve(max_nfev=30)
    assert result.rms_nrmse < 0.02 * before
    assert result.parameters["alpha_b"] == pytest.approx(69500, rel=0.05)


def test_loops_with_non_finite_model_force_are_left_out(monkeypatch) -> None:
    loops = campaign("linear", currents=(0.0,), pairs=PAIRS[:3])
    from mrsuspension.identify import models

    original = models.LinearFit.forces

    def broken(self, model, data):
        f = original(self, model, data)
        for lp, sl in zip(data.loops, data.slices, strict=True):
            if lp is loops[1]:
                f[sl] = np.nan
        return f

    monkeypatch.setattr(models.LinearFit, "forces", broken)
    result = fit_loops(loops, "linear")
    assert dict(result.excluded) == {1: "model force not finite at the start parameters"}
    assert result.loop_index == (0, 2)
    assert result.parameters["c"] == pytest.approx(2500.0, rel=1e-6)


def test_unknown_model_and_bad_settings() -> None:
    loops = campaign("linear", currents=(0.0,), pairs=PAIRS[:1])
    with pytest.raises(
        ValidationError, match=r"unknown damper model 'bingam'\. Did you mean 'bingham'"
    ):
        fit_loops(loops, "bingam")
    with pytest.raises(ValidationError, match="jacobian must be one of"):
        fit_loops(loops, "linear", jacobian="exact")
    with pytest.raises(ValidationError, match="every parameter of model 'linear' is fixed"):
        fit_loops(loops, "linear", fixed=["c"])
