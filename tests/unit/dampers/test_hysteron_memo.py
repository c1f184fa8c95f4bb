"""The passive hysteron's memo of its v_m terms gives :func:`passive_hysteron` bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

from mrsuspension.dampers import WangAsymmetric, WangSymmetric
from mrsuspension.dampers import kernels as DK


@pytest.mark.parametrize("model", [WangSymmetric(), WangAsymmetric()], ids=["sym", "asym"])
def test_memo_is_bit_identical_along_a_sequence(model) -> None:  # type: ignore[no-untyped-def]
    dp = model.kernel(1e-4).params
    rng = np.random.default_rng(7)
    memo = np.zeros(DK.PH_SIZE)
    vms = np.repeat(rng.uniform(0.0, 1.5, 40), rng.integers(1, 30, 40))  # held, then new
    recomputed = 0
    for vm in vms:
        v, sgn_a = rng.normal(0.0, 0.4), float(rng.choice([-1.0, 0.0, 1.0]))
        before = memo.copy()
        got = DK.passive_hysteron_memo(dp, memo, v, sgn_a, float(vm))
        assert got == DK.passive_hysteron(dp, v, sgn_a, float(vm))
        assert memo[DK.PH_VM] == vm
        recomputed += int(not np.array_equal(before, memo))
    assert recomputed == len(np.unique(vms))  # once per new v_m, not per call


def test_empty_memo_is_recomputed_even_at_its_stored_v_m() -> None:
    dp = WangSymmetric().kernel(1e-4).params
    memo = np.zeros(DK.PH_SIZE)  # zero-filled: empty, although its v_m reads 0
    assert DK.passive_hysteron_memo(dp, memo, 0.2, 1.0, 0.0) == DK.passive_hysteron(
        dp, 0.2, 1.0, 0.0
    )
    assert memo[DK.PH_FT] == DK.transition_force(dp, 0.0) != 0.0


def test_memo_terms_are_the_damper_latch_terms() -> None:
    # one definition: the damper's own latch and the memo hold the same values
    dp = WangAsymmetric().kernel(1e-4).params
    s = np.zeros(DK.STATE_SIZE)
    DK.wang_latch_motion(dp, s, 0.37, -1.0)
    memo = np.zeros(DK.PH_SIZE)
    DK.passive_hysteron_memo(dp, memo, 0.1, -1.0, 0.37)
    assert (memo[DK.PH_FT], memo[DK.PH_HALF_ALPHA], memo[DK.PH_DECAY]) == (
        s[DK.WS_FT],
        s[DK.WS_HALF_ALPHA],
        s[DK.WS_DECAY],
    )


def test_inverse_from_the_hysteron_is_the_inverse() -> None:
    dp = WangSymmetric().kernel(1e-4).params
    rng = np.random.default_rng(3)
    for _ in range(500):
        target, v = rng.normal(0.0, 1500.0), rng.normal(0.0, 0.4)
        sgn_a, vm = float(rng.choice([-1.0, 1.0])), rng.uniform(0.0, 1.0)
        fh = DK.passive_hysteron(dp, v, sgn_a, vm)
        assert DK.wang_inverse_from(dp, target, fh, 0.5) == DK.wang_inverse(
            dp, target, v, sgn_a, vm, 0.5
        )
