"""The vectorised (numpy) and compiled (kernel) paths of every model agree to round-off."""

from __future__ import annotations

import numpy as np
import pytest

from mrsuspension.dampers import DAMPERS, make_damper

WANG_OPTIONS = [
    {},
    {"hysteresis": False},
    {"vh_variant": "2.13"},
    {"estimator": "instantaneous"},
    {"force_gain": 2.5},
]
CASES = [(name, opts) for name in DAMPERS for opts in (WANG_OPTIONS if "wang" in name else [{}])]


@pytest.fixture(scope="module")
def inputs() -> tuple[np.ndarray, ...]:
    rng = np.random.default_rng(1)
    n = 5000
    return (
        rng.uniform(-0.05, 0.05, n),
        rng.uniform(-1.0, 1.0, n),
        rng.uniform(-50.0, 50.0, n),
        rng.uniform(0.0, 0.5, n),
        rng.uniform(0.01, 1.0, n),
    )


@pytest.mark.parametrize(("name", "options"), CASES, ids=[f"{n}-{o}" for n, o in CASES])
def test_vectorised_equals_compiled(
    name: str, options: dict, inputs: tuple[np.ndarray, ...]
) -> None:
    x, v, a, i, vm = inputs
    model = make_damper(name, **options)
    f_vec = model.force(x, v, a, i)
    f_cmp = model.kernel_force(x, v, a, i)
    np.testing.assert_allclose(f_vec, f_cmp, rtol=1e-12, atol=1e-9)
    if "wang" in name:
        np.testing.assert_allclose(
            model.force(x, v, a, i, peak_velocity=vm),
            model.kernel_force(x, v, a, i, peak_velocity=vm),
            rtol=1e-12,
            atol=1e-9,
        )


def test_broadcasting_factorised_inputs_match_full_arrays() -> None:
    """Scalar current and v_m (computed once) give the same as full arrays."""
    model = make_damper("wang-symmetric")
    v = np.linspace(-0.5, 0.5, 101)
    a = -np.sign(v)
    full = model.force(np.zeros(101), v, a, np.full(101, 0.3), peak_velocity=np.full(101, 0.5))
    scalar = model.force(0.0, v, a, 0.3, peak_velocity=0.5)
    np.testing.assert_array_equal(full, scalar)
    assert scalar.shape == (101,)
