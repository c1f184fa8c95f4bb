"""Helpers shared by the test modules (importable: ``pythonpath = ["tests"]`` in pyproject)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest

from mrsuspension.errors import ValidationError


def raises_validation(call: Callable[[], Any], *fragments: str) -> str:
    """Call, expect a ValidationError whose message contains every fragment; return it."""
    with pytest.raises(ValidationError) as info:
        call()
    message = str(info.value)
    for fragment in fragments:
        assert fragment in message, (fragment, message)
    return message


def noise_floor(true_model: Any, loop: Any) -> float:
    """NRMSE of the true damper against a pre-processed loop (noise and resampling).

    What a fit of an identification test can reach at best; the campaign tests hold each
    fit within a factor of it.
    """
    import math

    import numpy as np

    f_true = true_model.force(loop.stroke, loop.velocity, loop.acceleration, loop.current,
                              peak_velocity=loop.peak_velocity)  # fmt: skip
    return math.sqrt(float(np.mean((f_true - loop.force) ** 2))) / loop.force_range
