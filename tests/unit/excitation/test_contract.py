"""The contract every registered excitation kind passes (one test, every kind).

A new kind is covered by being registered in ``mrsuspension.excitation``: its declared
options, example and measures kind drive these tests.
"""

from __future__ import annotations

import inspect
import json
from typing import Any

import numpy as np
import pytest

from _helpers import raises_validation
from mrsuspension.engine.result import MEASURES_BY_KIND
from mrsuspension.excitation import (
    EXCITATION_OPTIONS,
    EXCITATIONS,
    Excitation,
    Option,
    SteppedSweep,
    make_excitation,
)
from mrsuspension.scenario import SCENARIO_KEYS, Scenario

KINDS = sorted(EXCITATIONS)


def _runs(kind: str) -> list[Excitation]:
    """The single-run excitations of the kind's example (one per frequency of a sweep)."""
    exc = make_excitation(kind, **EXCITATIONS[kind].example_options)
    return list(exc) if isinstance(exc, SteppedSweep) else [exc]


@pytest.mark.parametrize("kind", KINDS)
def test_declarations(kind: str) -> None:
    cls = EXCITATIONS[kind]
    assert cls.name == kind
    assert cls.measures_kind in MEASURES_BY_KIND
    assert cls.options, "a kind declares its options"
    assert cls.example_options, "a kind declares a valid example"
    for opt in cls.options:
        assert isinstance(opt, Option)
        assert opt.doc.strip()
        assert opt.kind in ("number", "integer", "string", "numbers")
        if opt.kind in ("number", "numbers") and opt.low is not None and opt.high is not None:
            assert opt.low < opt.high
    assert EXCITATION_OPTIONS[kind] == {o.name: o.doc for o in cls.options}
    for opt in cls.options:  # the scenario file's table is derived from them
        assert SCENARIO_KEYS["excitation"][opt.name] == opt.kind


@pytest.mark.parametrize("kind", KINDS)
def test_options_cover_the_constructor(kind: str) -> None:
    cls = EXCITATIONS[kind]
    params = [
        n
        for n, p in inspect.signature(cls).parameters.items()
        if p.kind not in (p.VAR_KEYWORD, p.VAR_POSITIONAL)
    ]
    covered = {o.argument for o in cls.options} | set(cls.internal_parameters)
    assert set(params) <= covered, set(params) - covered
    assert set(cls.internal_parameters) <= set(params)
    for opt in cls.options:  # an option names a constructor keyword (or a builder's)
        if not cls.internal_parameters:
            assert opt.argument in params, opt


@pytest.mark.parametrize("kind", KINDS)
def test_derivatives_are_finite_differences(kind: str) -> None:
    for exc in _runs(kind)[:3]:
        t = np.linspace(0.05, min(exc.duration, 4.0), 4001)
        h = 1e-6
        z = exc.displacement
        v_fd = (z(t + h) - z(t - h)) / (2 * h)
        a_fd = (exc.velocity(t + h) - exc.velocity(t - h)) / (2 * h)
        v, a = exc.velocity(t), exc.acceleration(t)
        # away from a kink (the pulse's onset, a profile's ends) the derivatives agree
        smooth = np.abs(a_fd - a) <= 1e-4 * (np.max(np.abs(a)) + 1e-12) + 1e-6
        assert smooth.mean() > 0.99, kind
        np.testing.assert_allclose(v, v_fd, rtol=0, atol=1e-6 * (np.max(np.abs(v)) + 1e-9))
        np.testing.assert_allclose(
            a[smooth], a_fd[smooth], rtol=0, atol=1e-4 * (np.max(np.abs(a)) + 1e-9)
        )


@pytest.mark.parametrize("kind", KINDS)
def test_sample_grid_is_pointwise_evaluation(kind: str) -> None:
    for exc in _runs(kind)[:3]:
        for start in (0.0, 0.37):
            n, step = 2049, 5e-4
            zr, vr = exc.sample_grid(n, step, start=start)
            t = start + np.arange(n) * step
            z, v = exc.displacement(t), exc.velocity(t)
            assert zr.shape == vr.shape == (n,)
            np.testing.assert_allclose(zr, z, rtol=0, atol=1e-12 * (np.max(np.abs(z)) + 1e-3))
            np.testing.assert_allclose(vr, v, rtol=0, atol=1e-12 * (np.max(np.abs(v)) + 1e-3))


@pytest.mark.parametrize("kind", KINDS)
def test_describe_and_round_trip(kind: str) -> None:
    example = EXCITATIONS[kind].example_options
    exc = make_excitation(kind, **example)
    described = exc.describe()
    assert described["kind"] == kind
    json.dumps(described)  # plain data
    # the scenario file builds the same excitation
    scenario = Scenario.from_dict({"excitation": {"kind": kind, **example}})
    assert scenario.excitation.describe() == described
    # an excitation built from options gives them back, and they rebuild it
    options = exc.to_options()
    if options is not None:
        assert set(options) <= set(EXCITATION_OPTIONS[kind])
        again = make_excitation(kind, **options)
        assert again.describe() == described
        assert Scenario.from_dict({"excitation": {"kind": kind, **options}}).excitation == again


def _bad_values(opt: Option) -> list[Any]:
    """Values outside an option's declared range or choices."""
    bad: list[Any] = []
    if opt.kind in ("number", "integer", "numbers"):
        if opt.low is not None:
            below = opt.low if not opt.low_inclusive else opt.low - 1.0
            bad.append(int(below) if opt.kind == "integer" else below)
        if opt.high is not None:
            bad.append(opt.high * 2.0 + 1.0)
        bad = [[v] for v in bad] if opt.kind == "numbers" else bad
    elif opt.choices is not None:
        bad.append("not-a-choice")
    return bad


CASES = [
    (kind, opt, value)
    for kind in KINDS
    for opt in EXCITATIONS[kind].options
    for value in _bad_values(opt)
]


@pytest.mark.parametrize(
    ("kind", "opt", "value"), CASES, ids=[f"{k}-{o.name}-{v}" for k, o, v in CASES]
)
def test_bad_option_value_names_the_option(kind: str, opt: Option, value: Any) -> None:
    options = dict(EXCITATIONS[kind].example_options)
    if kind == "road" and opt.name in ("length", "spacing", "iso_class"):
        options = {"iso_class": "C"}  # options of a synthesised road
    if kind == "road" and opt.name in ("distance_unit", "elevation_unit"):
        pytest.skip("needs a CSV file: covered by test_road.py")
    options[opt.name] = value
    msg = raises_validation(lambda: make_excitation(kind, **options))
    assert opt.name in msg or opt.argument in msg, msg


@pytest.mark.parametrize("kind", KINDS)
def test_missing_required_option(kind: str) -> None:
    for opt in EXCITATIONS[kind].options:
        if not opt.required:
            continue
        options = {k: v for k, v in EXCITATIONS[kind].example_options.items() if k != opt.name}
        raises_validation(lambda o=options: make_excitation(kind, **o), repr(opt.name))
