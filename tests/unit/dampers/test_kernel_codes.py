"""An unknown damper model code is refused, never computed as another model (issue 28)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from _helpers import raises_validation
from mrsuspension.dampers import LinearViscous
from mrsuspension.dampers import kernels as K


def test_damper_kernel_refuses_an_unknown_model_code() -> None:
    kern = LinearViscous(damping=1000.0).kernel(1e-4)
    assert kern.kind == K.LINEAR
    raises_validation(
        lambda: dataclasses.replace(kern, kind=7),
        "unknown damper model code 7",
        "SPENCER = 3",
        "dampers/kernels.py",
    )


def test_the_compiled_force_of_an_unknown_code_is_nan_not_spencer() -> None:
    p = np.zeros(32)
    s = np.zeros(K.STATE_SIZE)
    assert math.isnan(K.damper_force(7, p, s, 0.01, 0.1, 0.2))
    linear = LinearViscous(damping=1000.0).kernel(1e-4)
    assert K.damper_force(K.LINEAR, linear.params, s, 0.01, 0.1, 0.2) == 100.0
