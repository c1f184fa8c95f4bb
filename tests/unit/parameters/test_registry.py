"""The parameter-set registry: every published set loads, with units and provenance."""

from __future__ import annotations

import math

import pytest

from mrsuspension import parameters
from mrsuspension.dampers import DAMPERS, make_damper

NAMES = parameters.available()


def test_registry_is_not_empty() -> None:
    assert len(NAMES) >= 6


@pytest.mark.parametrize("name", NAMES)
def test_every_published_set_loads(name: str) -> None:
    pset = parameters.get(name)
    assert pset.name == name
    assert pset.model in {a for cls in DAMPERS.values() for a in cls.accepts}
    assert pset.source.strip()
    assert pset.values
    for key, value in pset.values.items():
        assert math.isfinite(value), key
        assert key in pset.units, f"{name}: no unit for {key}"
        assert pset.units[key].strip(), f"{name}: empty unit for {key}"


@pytest.mark.parametrize("name", NAMES)
def test_velocity_range_valid(name: str) -> None:
    vrange = parameters.get(name).velocity_range
    if vrange is None:
        return
    low, high = vrange
    assert math.isfinite(low)
    assert math.isfinite(high)
    assert 0.0 <= low < high


@pytest.mark.parametrize("name", NAMES)
def test_every_set_builds_its_model(name: str) -> None:
    pset = parameters.get(name)
    model = next(m for m, cls in DAMPERS.items() if pset.model in cls.accepts)
    damper = make_damper(model, name)
    assert damper.parameters.name == name
