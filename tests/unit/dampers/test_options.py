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


def test_bingham_checks_its_coefficients_over_the_given_current_range() -> None:
    from mrsuspension import parameters

    weak = parameters.get("bingham-wang-low").replace(fc_b=-200.0)  # fc drops to 0 at ~0.55 A
    make_damper("bingham", weak)  # fine up to the default 0.5 A
    with pytest.raises(ValidationError, match="yield force"):
        make_damper("bingham", weak, max_current=1.0)


def test_numpy_path_is_overflow_free_for_extreme_currents() -> None:
    import warnings

    from mrsuspension import parameters

    steep = parameters.get("wang-symmetric-low").replace(a2=2000.0, I0=-0.3)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        f = make_damper("wang-symmetric", steep).force(0.0, 0.1, 0.0, [0.0, 0.5])
    assert bool((f > 0).all())
