"""Misspelled model options are named as such, with a did-you-mean."""

from __future__ import annotations

import pytest

from mrsuspension import ValidationError, make_damper


@pytest.mark.parametrize(
    ("options", "hint"),
    [
        ({"hysterisis": False}, "Did you mean 'hysteresis'?"),
        ({"force_gian": 2.0}, "Did you mean 'force_gain'?"),
        ({"windw": 0.5}, "Did you mean 'window'?"),
        ({"estimator": "known", "valu": 0.3}, "Did you mean 'value'?"),
    ],
)
def test_misspelled_option(options: dict, hint: str) -> None:
    with pytest.raises(ValidationError, match="unknown option of WangSymmetric") as err:
        make_damper("wang-symmetric", **options)
    assert hint in str(err.value)


def test_estimator_options_reach_the_estimator() -> None:
    m = make_damper("wang-symmetric", window=0.5, v_max=0.8)
    assert m.estimator.window == 0.5
    assert m.estimator.v_max == 0.8
