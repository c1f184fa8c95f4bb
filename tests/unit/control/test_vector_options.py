"""Vector and matrix options of a control law: declared like numbers, packed after the fixed
slots, checked with errors naming the shape, shown by describe_options, from TOML."""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pytest

from mrsuspension.control import Controller, law
from mrsuspension.control import kernel as CK
from mrsuspension.control.base import option
from mrsuspension.errors import ValidationError


@dataclass(frozen=True)
class Gains(Controller):
    """A throwaway law with a 1 x n gain row and a 2 x 2 weight (never run)."""

    K: tuple[tuple[float, ...], ...] = option(((1.0, 2.0, 3.0),), unit="N/m", shape=(1, None))
    W: tuple[tuple[float, ...], ...] = option(((1.0, 0.0), (0.0, 1.0)), low=0.0, shape=(2, 2))
    gain: float = option(2.0, low=0.0, high=10.0)
    law: ClassVar[str] = "gains"
    code: ClassVar[int] = CK.C_PASSIVE


def test_vector_options_pack_after_the_fixed_slots() -> None:
    ctl = Gains(K=[[4.0, 5.0, 6.0, 7.0]])
    assert ctl.K == ((4.0, 5.0, 6.0, 7.0),)
    p = ctl.params(0.5)
    slots = ctl.option_slots()
    assert slots == {
        "K": slice(CK.CP_SIZE, CK.CP_SIZE + 4),
        "W": slice(CK.CP_SIZE + 4, CK.CP_SIZE + 8),
    }
    assert p[slots["K"]].tolist() == [4.0, 5.0, 6.0, 7.0]
    assert p[slots["W"]].tolist() == [1.0, 0.0, 0.0, 1.0]
    assert p.size == CK.CP_SIZE + 8
    shapes = {o.name: o.shape for o in Gains.describe_options()}
    assert shapes == {"K": (1, None), "W": (2, 2), "gain": None}
    assert Gains.describe_options()[0].describe()["shape"] == (1, None)


@pytest.mark.parametrize(
    ("value", "message"),
    [
        ([1.0, 2.0], r"K must be an array of shape \(1, n\) \[N/m\]; got shape \(2,\)"),
        ([[1.0, "x"]], r"K must be an array of shape \(1, n\) \[N/m\] of numbers"),
        ([[1.0, float("nan")]], "K must hold finite numbers"),
    ],
)
def test_bad_vector_values_name_the_shape(value: object, message: str) -> None:
    with pytest.raises(ValidationError, match=message):
        Gains(K=value)  # type: ignore[arg-type]
    with pytest.raises(ValidationError, match=r"W elements must be in \[0, inf\]"):
        Gains(W=[[1.0, -1.0], [0.0, 1.0]])  # type: ignore[arg-type]


@law(output="force")
def row(x_d, v_d, K=(100.0, 10.0)):  # type: ignore[no-untyped-def]
    return -(K[0] * x_d + K[1] * v_d)


def test_a_user_laws_vector_option_from_toml() -> None:
    table = tomllib.loads('[controller]\nlaw = "x:row"\nK = [2000.0, 300.0]\n')["controller"]
    ctl = row(K=table["K"])
    assert ctl.K == (2000.0, 300.0)
    assert ctl.describe() == {"law": row.law, "K": [2000.0, 300.0]}
    assert ctl.params(0.5)[ctl.option_slots()["K"]].tolist() == [2000.0, 300.0]
    with pytest.raises(
        ValidationError, match=r"K must be an array of shape \(2,\); got shape \(3,\)"
    ):
        row(K=[1.0, 2.0, 3.0])
    assert np.asarray(row().K).shape == (2,)
