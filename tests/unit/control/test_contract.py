"""The contract every registered control law passes.

Parametrised over :data:`mrsuspension.control.CONTROLLERS`: a new law is covered by
registering it. Each law, built with its defaults, keeps the drive current within
``[0, i_max]`` on a run, describes itself in a form :func:`make_controller` takes back,
refuses bad options naming them, fills a parameter vector of the kernel's layout and
declares options whose defaults are the constructor's.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from _helpers import raises_validation
from mrsuspension.control import CONTROLLERS, ControlOption, law_options, make_controller
from mrsuspension.control import kernel as CK
from mrsuspension.engine import Simulation
from mrsuspension.excitation import Harmonic

LAWS = sorted(CONTROLLERS)
MAX_CURRENT = 0.3


def _bad_value(option: ControlOption) -> Any:
    """A value outside the option's valid set (a vector or matrix option: its default
    with one element out of range)."""
    if option.choices is not None:
        return "no-such-choice"
    if option.high is not None:
        bad = option.high * 10.0 + 1.0
    else:
        assert option.low is not None
        bad = option.low - 1.0
    if option.shape is not None:
        arr = np.array(option.default, dtype=float)
        arr.flat[0] = bad
        return arr.tolist()
    return bad


@pytest.mark.parametrize("law", LAWS)
def test_drive_current_stays_within_its_limit(law: str) -> None:
    sim = Simulation(Harmonic(2.0, 0.03), controller=make_controller(law), max_current=MAX_CURRENT)
    result = sim.run(duration=1.0, dt=2e-4, output_rate=1000.0)
    i_d = np.asarray(result.i_d)
    assert np.all(np.isfinite(i_d))
    assert i_d.min() >= 0.0
    assert i_d.max() <= MAX_CURRENT
    if sim.controller.drives_damper and law != "passive":  # the law does act
        assert i_d.max() > 0.0


@pytest.mark.parametrize("law", LAWS)
def test_describe_round_trips_through_make_controller(law: str) -> None:
    ctl = make_controller(law)
    again = make_controller(**ctl.describe())
    assert again == ctl
    assert again.describe() == ctl.describe()
    assert again.law == law


@pytest.mark.parametrize("law", LAWS)
def test_params_have_the_kernel_layout(law: str) -> None:
    ctl = make_controller(law)
    p = ctl.params(MAX_CURRENT)
    assert p.ndim == 1
    assert p.shape[0] >= CK.CP_SIZE  # a user law's entry and options follow the fixed slots
    assert np.all(np.isfinite(p))
    assert p[CK.P_IMAX] == MAX_CURRENT
    assert ctl.code in {
        CK.C_PASSIVE, CK.C_ONOFF_ADFG, CK.C_POLICY, CK.C_INVERSE_HILO, CK.C_SLIDING,
        CK.C_IDEAL_SKYHOOK, CK.C_IDEAL_ONOFF, CK.C_USER_CURRENT, CK.C_USER_FORCE,
        CK.C_USER_ACTIVE,
    }  # fmt: skip


@pytest.mark.parametrize("law", LAWS)
def test_declared_defaults_are_the_constructor_defaults(law: str) -> None:
    options = law_options(law)
    assert options, f"{law} declares no options"
    given = {o.name: o.default for o in options if o.default is not None}
    assert make_controller(law, **given) == make_controller(law)
    for o in options:
        assert o.choices is not None or o.low is not None, o.name  # a valid set is declared


@pytest.mark.parametrize(
    ("law", "option"),
    [(law, o) for law in LAWS for o in law_options(law)],
    ids=lambda v: v if isinstance(v, str) else v.name,
)
def test_a_bad_option_value_is_refused_naming_it(law: str, option: ControlOption) -> None:
    bad = _bad_value(option)
    message = raises_validation(lambda: make_controller(law, **{option.name: bad}))
    label = option.label or option.name
    assert label in message or option.name in message, message
    shown = bad if isinstance(bad, str) else str(bad) if isinstance(bad, list) else f"{bad:g}"
    assert shown in message, message


@pytest.mark.parametrize("law", LAWS)
def test_an_unknown_option_is_refused_naming_it(law: str) -> None:
    raises_validation(lambda: make_controller(law, no_such_option=1.0), "no_such_option")


@pytest.mark.parametrize("law", LAWS)
def test_non_finite_numbers_are_refused(law: str) -> None:
    numbers = [o for o in law_options(law) if o.choices is None]
    for o in numbers:
        raises_validation(lambda o=o: make_controller(law, **{o.name: math.nan}), o.name)
