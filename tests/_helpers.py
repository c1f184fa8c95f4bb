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
