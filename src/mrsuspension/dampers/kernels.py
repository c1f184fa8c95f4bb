"""Compiled (numba) scalar kernels of every damper model and peak-velocity estimator.

This module is the single source of the damper physics: the vectorised array API of
:mod:`mrsuspension.dampers` loops over these functions, and the simulation engine and the
hardware-in-the-loop loop call them sample by sample. Short symbols follow the model
reference (``docs/model.md``), sections 2-3; the mapping to domain names is given at each
constant.
The kernels are compiled once each and inlined into their callers by LLVM
(:data:`~mrsuspension._numba_cache.INLINED`); the few that the lane kernel's vectorised
stages use (:func:`wang_combine`, :func:`lane_tanh` and what they call) are inlined by numba
instead (``inline="always"``), so that they take the stages' fused multiply-adds. The array
loops are compiled without reference counting (see :mod:`mrsuspension.engine.kernel`).

A damper is described by four flat arrays so that one compiled step can serve every
model:

``kind``
    model code (:data:`LINEAR`, :data:`BINGHAM`, :data:`WANG`, :data:`SPENCER`);
``p``
    parameter vector (layout: the ``*_`` index constants below);
``s``
    internal state held over a time step (zero-order hold): ``v_m``, ``sgn(a_d)`` and the
    terms derived from them (``WS_*`` layout) for the dissertation's model,
    ``[y, z, u, initialised]`` for Spencer's;
``ek, ep, es``
    the peak-velocity estimator's code, parameters and buffer.

A time step is ``damper_sample`` (latch the held internals from the state at the start of
the step), any number of ``damper_force`` calls (e.g. the four RK4 stages) and
``damper_advance`` (integrate internal dynamics over the step).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit

from mrsuspension._numba_cache import INLINED, invalidate_if_changed

# no other module's kernels are called here; registered so that a change of INLINED drops
# the cache
invalidate_if_changed(__file__)

#: numba option compiling a function without reference counting (no allocation inside):
#: the loops over kernels run ~30x faster without the per-call reference counts.
NO_REFCOUNT: dict[str, Any] = {"_nrt": False}

# ----------------------------------------------------------------------------------
# model codes
LINEAR = 0
BINGHAM = 1
WANG = 2
SPENCER = 3
#: the model codes the kernels compute, by name (:class:`~.base.DamperKernel` refuses others)
MODEL_CODES: dict[str, int] = {
    "LINEAR": LINEAR,
    "BINGHAM": BINGHAM,
    "WANG": WANG,
    "SPENCER": SPENCER,
}

STATE_SIZE = 10

# Dissertation (Wang) model, eqs. (2.7)-(2.21); symmetric sets use K1C = K1E = k1, K5 = K6 = 0.
W_A0 = 0  # a0, hysteresis slope alpha at v_m = 0 [s/m]
W_A1 = 1  # a1, transition-force growth [s/m]
W_A2 = 2  # a2, current-gain sigmoid slope [1/A]
W_A3 = 3  # a3, slope of H(i) in v_h [1/A]
W_A4 = 4  # a4, decay of the linear-rise coefficient [s/m]
W_I0 = 5  # I0, current-gain bias [A]
W_I1 = 6  # I1, H(i) bias [A]
W_K0 = 7  # k0, decay of alpha with v_m [s/m]
W_K1C = 8  # k1c (compression, v_d >= 0) linear rise [s/m]
W_K1E = 9  # k1e (rebound, v_d < 0) linear rise [s/m]
W_K2 = 10  # k2, current-gain amplitude
W_K3 = 11  # k3, H(i) amplitude
W_K4 = 12  # k4, v_h / v_m (negative: upper branch = decreasing velocity)
W_K5 = 13  # k5, force offset F_b / (C_i F_t)
W_K6 = 14  # k6, velocity offset v_b / v_m
W_F0 = 15  # F0, seal friction [N]
W_KD = 16  # k_d, force gain (sections 5.3 / 6.2)
W_VHI = 17  # 1.0: v_h from (2.12) (current dependent); 0.0: (2.13)
W_SA2 = 18  # derived: sigma(a2 I0), filled by wang_derive
W_SA3 = 19  # derived: sigma(a3 I1), filled by wang_derive
W_SIZE = 20

# Held state of the dissertation's model over a step. The motion terms are latched by
# damper_sample; the current terms are recomputed whenever the current differs from the
# latched one (so a held current costs nothing in the RK4 stages).
WS_VM, WS_SGN, WS_I, WS_CI, WS_SHIFT, WS_FT, WS_HALF_ALPHA, WS_DECAY, WS_FB = range(9)

# The inverse-model control laws' memo of the passive hysteron's v_m terms, held by the
# caller between steps (see passive_hysteron_memo): the v_m they belong to, F_t (2.7),
# alpha/2 (2.11) and exp(-a4 v_m). Zero-filled (PH_FT = 0): empty.
PH_VM, PH_FT, PH_HALF_ALPHA, PH_DECAY = range(4)
PH_SIZE = 4

# Spencer et al. (1997) modified Bouc-Wen (model reference, section 2.5).
S_C0A, S_C0B, S_K0, S_C1A, S_C1B, S_K1, S_X0 = 0, 1, 2, 3, 4, 5, 6
S_ALA, S_ALB, S_GAM, S_BET, S_A, S_N, S_ETA, S_VPA = 7, 8, 9, 10, 11, 12, 13, 14
S_SIZE = 15

# Bingham with current-linear coefficients: F = (fc_a + fc_b i) sgn(v) + (c0_a + c0_b i) v + f0.
B_FCA, B_FCB, B_C0A, B_C0B, B_F0 = 0, 1, 2, 3, 4
B_SIZE = 5

# Peak-velocity estimators (model reference, section 2.4).
EST_KNOWN = 0  # ep = [v_m]
EST_INSTANT = 1  # ep = [v_min, v_max]; eq. (2.14), clamped
EST_WINDOW = 2  # ep = [v_min, v_max, n_window]; peak |v_d| over the last n samples, clamped
# window buffer layout: es = [head, count, step, values(n+1)..., step indices(n+1)...]
EST_CYCLE_RMS = 3  # ep = [v_min, v_max, n_window]; sqrt(2 mean(v_d^2)) over the last n samples
# cycle-rms buffer layout: es = [next slot, samples seen (<= n), running sum, v_d^2 ring(n)...]
CR_HEAD, CR_COUNT, CR_SUM, CR_RING = 0, 1, 2, 3


@njit(cache=True, **INLINED)
def sigmoid(u: float) -> float:
    """Logistic function 1/(1+exp(-u)), evaluated without overflow."""
    return sigmoid_from(u, math.exp(-abs(u)))


@njit(cache=True, inline="always")  # in the lane latch: see the module docstring
def sigmoid_from(u: float, t: float) -> float:
    """The logistic function from ``t = exp(-|u|)`` (so it never overflows).

    ``1/(1 + t)`` for ``u >= 0``, ``t/(1 + t)`` below: one formula for :func:`sigmoid`
    (libm's exp) and :func:`lane_sigmoid`.
    """
    return (1.0 if u >= 0.0 else t) / (1.0 + t)


#: |u| below which :func:`fast_tanh` uses its rational form (else its exp form)
TANH_RATIONAL_BELOW = 0.55


@njit(cache=True, **INLINED)
def fast_tanh(u: float) -> float:
    """tanh(u) to round-off, with at most one exp and one division.

    libm's tanh goes through expm1 and was the slowest operation of the simulation step
    (five per step, one per RK4 stage, on the chain from one stage to the next). Here,
    for ``|u| >= 0.55``, ``tanh|u| = (1 - t)/(1 + t)`` with ``t = exp(-2|u|) <= 0.33``
    (no cancellation; ``t`` underflows to 0 for large ``|u|``, giving exactly 1); below,
    the convergent ``u P(u^2)/Q(u^2)`` of Lambert's continued fraction
    ``u/(1 + u^2/(3 + u^2/(5 + ...)))`` truncated after the term 15 (truncation error
    below 1e-17 there). Relative error below 3.5e-16 on the tested points (against
    40-digit decimal arithmetic; libm's tanh: 3e-16), i.e. round-off.

    Examples
    --------
    >>> import math
    >>> all(abs(fast_tanh(u) - math.tanh(u)) <= 4e-16 * abs(math.tanh(u))
    ...     for u in (-30.0, -1.0, -0.3, 1e-9, 0.54, 0.56, 3.0))
    True
    """
    a = abs(u)
    if a < TANH_RATIONAL_BELOW:
        return _tanh_rational(u)
    # exp(-2|u|) <= exp(-1.1); 0 for large |u|, which gives exactly 1
    return _tanh_from_exp(u, math.exp(-2.0 * a))


@njit(cache=True, inline="always")  # in the lane stages: see the module docstring
def _tanh_rational_parts(u: float) -> tuple[float, float]:
    """Numerator and denominator of Lambert's continued fraction for tanh, truncated
    after the term 15 (for |u| < 0.55)."""
    z = u * u
    num = u * (2027025.0 + z * (270270.0 + z * (6930.0 + z * 36.0)))
    return num, 2027025.0 + z * (945945.0 + z * (51975.0 + z * (630.0 + z)))


@njit(cache=True, **INLINED)
def _tanh_rational(u: float) -> float:
    num, den = _tanh_rational_parts(u)
    return num / den


@njit(cache=True, **INLINED)
def _tanh_from_exp(u: float, t: float) -> float:
    """tanh(u) from ``t = exp(-2|u|)``: ``sgn(u) (1 - t)/(1 + t)``."""
    r = (1.0 - t) / (1.0 + t)
    return r if u > 0.0 else (-r if u < 0.0 else u)


# exp by range reduction to |r| <= ln(2)/2 and a degree-12 Taylor polynomial, in plain
# arithmetic so that a loop over independent values compiles to vector instructions
# (numba has no vector exp without Intel's SVML)
_LOG2E = 1.4426950408889634
_LN2_HI = 6.93147180369123816490e-01  # ln 2 split: m * _LN2_HI is exact for m < 2^11
_LN2_LO = 1.90821492927058770002e-10
_TWO_M63 = 2.0**-63
#: :func:`exp_neg` clamps its argument here (tanh is exactly 1 beyond |u| = 20)
EXP_NEG_FLOOR = -40.0


@njit(cache=True, inline="always")  # in the lane stages: see the module docstring
def exp_neg(x: float) -> float:
    """exp(x) for ``EXP_NEG_FLOOR <= x <= 0`` (clamped below) in vectorisable arithmetic.

    ``exp(x) = 2^-m p(r)`` with ``m = round(-x / ln 2)``, ``r = x + m ln 2`` and ``p`` the
    degree-12 Taylor polynomial; ``2^-m`` is an integer shift converted to float. Relative
    error below 1.5 ulp on [-40, 0] (libm's: 0.5 ulp), so results computed with it
    differ from libm's at round-off only. Used by the lane kernel
    (:mod:`mrsuspension.engine.lanes`); the scalar step keeps libm's exp.

    Examples
    --------
    >>> import math
    >>> all(abs(exp_neg(x) - math.exp(x)) <= 4e-16 * math.exp(x)
    ...     for x in (0.0, -1e-9, -0.3466, -0.35, -1.0, -7.3, -39.9))
    True
    >>> exp_neg(-1000.0) == exp_neg(EXP_NEG_FLOOR)
    True
    """
    x = max(x, EXP_NEG_FLOOR)
    m = np.uint64(-x * _LOG2E + 0.5)
    fm = float(m)
    r = x + fm * _LN2_HI + fm * _LN2_LO
    p = 1.0 / 479001600.0  # Horner, from the degree-12 coefficient 1/12! down
    p = p * r + 1.0 / 39916800.0
    p = p * r + 1.0 / 3628800.0
    p = p * r + 1.0 / 362880.0
    p = p * r + 1.0 / 40320.0
    p = p * r + 1.0 / 5040.0
    p = p * r + 1.0 / 720.0
    p = p * r + 1.0 / 120.0
    p = p * r + 1.0 / 24.0
    p = p * r + 1.0 / 6.0
    p = p * r + 0.5
    p = p * r + 1.0
    p = p * r + 1.0
    return p * (float(np.uint64(1) << (np.uint64(63) - m)) * _TWO_M63)


@njit(cache=True, inline="always")  # in the lane stages: see the module docstring
def lane_tanh(u: float) -> float:
    """:func:`fast_tanh` without branches or calls (vectorisable): both forms, selected.

    Uses :func:`exp_neg` instead of libm's exp, so it agrees with :func:`fast_tanh` to
    round-off, not bit for bit.

    Examples
    --------
    >>> all(abs(lane_tanh(u) - fast_tanh(u)) <= 8e-16 * abs(fast_tanh(u))
    ...     for u in (-30.0, -1.0, -0.3, 1e-9, 0.54, 0.56, 3.0))
    True
    """
    a = abs(u)
    t = exp_neg(-2.0 * a)
    small = a < TANH_RATIONAL_BELOW
    # one division for both forms: select numerator and denominator first
    rn, rd = _tanh_rational_parts(u)
    r = (rn if small else 1.0 - t) / (rd if small else 1.0 + t)
    return r if small or u > 0.0 else (-r if u < 0.0 else u)


@njit(cache=True, **INLINED)
def sign(u: float) -> float:
    """sgn(u) with sgn(0) = 0."""
    if u > 0.0:
        return 1.0
    if u < 0.0:
        return -1.0
    return 0.0


# ----------------------------------------------------------------------------------
# the dissertation's model
@njit(cache=True, **INLINED)
def wang_derive(p: np.ndarray) -> None:
    """Fill the derived slots of a parameter vector (constants of C_i and H)."""
    p[W_SA2] = sigmoid(p[W_A2] * p[W_I0])
    p[W_SA3] = sigmoid(p[W_A3] * p[W_I1])


@njit(cache=True, **INLINED)
def current_gain(p: np.ndarray, i: float) -> float:
    """C_i(i) = 1 + k2 sigma(a2 (i + I0)) - k2 sigma(a2 I0), eq. (2.9); C_i(0) = 1."""
    return current_gain_from(p, sigmoid(p[W_A2] * (i + p[W_I0])))


# The formulas below take their exponentials as arguments (``*_from``): the scalar
# kernels pass libm's, the lane latch (lane_wang_latch) vectorisable ones; one copy of
# each equation.
@njit(cache=True, inline="always")
def current_gain_from(p: np.ndarray, sig: float) -> float:
    """C_i of eq. (2.9) from ``sig = sigma(a2 (i + I0))``."""
    return 1.0 + p[W_K2] * (sig - p[W_SA2])


@njit(cache=True, **INLINED)
def hysteresis_current_factor(p: np.ndarray, i: float) -> float:
    """H(i) of eq. (2.12); 1 for the simplified (2.13) variant."""
    if p[W_VHI] == 0.0:
        return 1.0
    return hysteresis_factor_from(p, sigmoid(p[W_A3] * (i + p[W_I1])))


@njit(cache=True, inline="always")
def hysteresis_factor_from(p: np.ndarray, sig: float) -> float:
    """H of eq. (2.12) from ``sig = sigma(a3 (i + I1))`` (1 for the (2.13) variant)."""
    return 1.0 + p[W_K3] * (sig - p[W_SA3]) if p[W_VHI] != 0.0 else 1.0


@njit(cache=True, **INLINED)
def transition_force(p: np.ndarray, vm: float) -> float:
    """F_t = F0 (1 + exp(a1 v_m)), eq. (2.7)."""
    return transition_force_from(p, math.exp(p[W_A1] * vm))


@njit(cache=True, inline="always")
def transition_force_from(p: np.ndarray, growth: float) -> float:
    """F_t of eq. (2.7) from ``growth = exp(a1 v_m)``."""
    return p[W_F0] * (1.0 + growth)


@njit(cache=True, inline="always")  # in the lane latch: no call, no division check
def hysteresis_slope(p: np.ndarray, vm: float) -> float:
    """alpha = a0 / (1 + k0 v_m), eq. (2.11)."""
    return p[W_A0] / (1.0 + p[W_K0] * vm)


@njit(cache=True, **INLINED)
def linear_rise(p: np.ndarray, v: float, vm: float) -> float:
    """1 + k_v |v_d| with k_v = k1 exp(-a4 v_m), eqs. (2.5), (2.10), (2.18), (2.21)."""
    return linear_rise_from(p, v, math.exp(-p[W_A4] * vm))


@njit(cache=True, **INLINED)
def linear_rise_from(p: np.ndarray, v: float, decay: float) -> float:
    """1 + k_v |v_d| of :func:`linear_rise` from ``decay = exp(-a4 v_m)``."""
    k1 = p[W_K1C] if v >= 0.0 else p[W_K1E]
    return 1.0 + k1 * decay * abs(v)


@njit(cache=True, **INLINED)
def motion_terms(p: np.ndarray, vm: float) -> tuple[float, float, float]:
    """The terms of v_m only: ``(F_t, alpha/2, exp(-a4 v_m))``, eqs. (2.7), (2.11), (2.10).

    What :func:`wang_latch_motion` and :func:`passive_hysteron_memo` latch.

    Examples
    --------
    >>> p = np.zeros(W_SIZE)
    >>> p[W_F0], p[W_A0], p[W_K0] = 100.0, 40.0, 1.0
    >>> motion_terms(p, 0.5)
    (200.0, 13.333333333333334, 1.0)
    """
    return transition_force(p, vm), 0.5 * hysteresis_slope(p, vm), math.exp(-p[W_A4] * vm)


@njit(cache=True, **INLINED)
def passive_hysteron(p: np.ndarray, v: float, sgn_a: float, vm: float) -> float:
    """Passive hysteron F_h of eq. (2.8) with v_h of (2.13), as used by the inverse model."""
    ft, half_alpha, decay = motion_terms(p, vm)
    return passive_hysteron_latched(p, v, sgn_a, vm, ft, half_alpha, decay)


@njit(cache=True, **INLINED)
def passive_hysteron_latched(
    p: np.ndarray, v: float, sgn_a: float, vm: float, ft: float, half_alpha: float, decay: float
) -> float:
    """:func:`passive_hysteron` from its v_m terms (as :func:`motion_terms` gives them)."""
    vh = sgn_a * p[W_K4] * vm
    return ft * fast_tanh(half_alpha * (v + vh)) * linear_rise_from(p, v, decay)


@njit(cache=True, **INLINED)
def passive_hysteron_memo(p: np.ndarray, m: np.ndarray, v: float, sgn_a: float, vm: float) -> float:
    """:func:`passive_hysteron`, its v_m terms kept in the memo ``m`` (``PH_*`` layout).

    The terms are recomputed only when ``vm`` differs from the memo's (exact equality:
    the windowed v_m changes rarely) or the memo is empty (``m[PH_FT] == 0``, e.g.
    zero-filled); the result is bit for bit :func:`passive_hysteron`'s. ``m`` belongs
    to one damper parameter vector ``p``: empty it (``m[PH_FT] = 0``) when ``p``
    changes or a run starts.

    Examples
    --------
    >>> p = np.zeros(W_SIZE)
    >>> p[W_F0], p[W_A0], p[W_A1], p[W_K1C], p[W_K4] = 100.0, 40.0, 1.5, 0.3, -0.2
    >>> m = np.zeros(PH_SIZE)
    >>> passive_hysteron_memo(p, m, 0.1, 1.0, 0.4) == passive_hysteron(p, 0.1, 1.0, 0.4)
    True
    >>> float(m[PH_VM]), passive_hysteron_memo(p, m, -0.2, -1.0, 0.4) == passive_hysteron(
    ...     p, -0.2, -1.0, 0.4)
    (0.4, True)
    """
    if vm != m[PH_VM] or m[PH_FT] == 0.0:
        m[PH_VM] = vm
        m[PH_FT], m[PH_HALF_ALPHA], m[PH_DECAY] = motion_terms(p, vm)
    return passive_hysteron_latched(p, v, sgn_a, vm, m[PH_FT], m[PH_HALF_ALPHA], m[PH_DECAY])


@njit(cache=True, **INLINED)
def wang_latch_motion(p: np.ndarray, s: np.ndarray, vm: float, sgn_a: float) -> None:
    """Latch v_m, sgn(a_d) and the terms that depend on them only (eqs. 2.7, 2.10, 2.11).

    Nothing is recomputed when both are unchanged (the windowed v_m and the sign of the
    acceleration change rarely), so the current terms stay valid too.
    """
    if vm == s[WS_VM] and sgn_a == s[WS_SGN] and s[WS_FT] != 0.0:
        return
    s[WS_VM] = vm
    s[WS_SGN] = sgn_a
    s[WS_I] = math.nan  # current terms must be recomputed
    s[WS_FT], s[WS_HALF_ALPHA], s[WS_DECAY] = motion_terms(p, vm)


@njit(cache=True, **INLINED)
def wang_latch_current(p: np.ndarray, s: np.ndarray, i: float) -> None:
    """Latch the current-dependent terms: C_i (2.9), v_h + v_b (2.12)/(2.13)/(2.20), F_b."""
    ci = current_gain(p, i)
    vm = s[WS_VM]
    s[WS_I] = i
    s[WS_CI] = ci
    s[WS_SHIFT] = wang_shift(p, s[WS_SGN], vm, hysteresis_current_factor(p, i))
    s[WS_FB] = wang_offset_force(p, ci, s[WS_FT])


@njit(cache=True, inline="always")
def wang_shift(p: np.ndarray, sgn_a: float, vm: float, h: float) -> float:
    """Velocity shift ``v_h + v_b``: ``sgn(a_d) k4 v_m H + k6 v_m`` (2.12)/(2.13)/(2.20)."""
    return sgn_a * p[W_K4] * vm * h + p[W_K6] * vm


@njit(cache=True, inline="always")
def wang_offset_force(p: np.ndarray, ci: float, ft: float) -> float:
    """Force offset ``F_b = k5 C_i F_t`` of eq. (2.19)."""
    return p[W_K5] * ci * ft


@njit(cache=True, inline="always")  # in the lane latch: see the module docstring
def lane_exp(x: float) -> float:
    """exp(x) for ``|x| <= -EXP_NEG_FLOOR`` in vectorisable arithmetic (clamped beyond).

    :func:`exp_neg` of ``-|x|``, inverted for positive ``x`` (within 2.5 ulp of libm's).

    Examples
    --------
    >>> import math
    >>> all(abs(lane_exp(x) - math.exp(x)) <= 6e-16 * math.exp(x)
    ...     for x in (-39.0, -1.0, 0.0, 0.3, 3.9, 39.0))
    True
    """
    t = exp_neg(-abs(x))
    return 1.0 / t if x > 0.0 else t


@njit(cache=True, inline="always")  # in the lane latch: see the module docstring
def lane_sigmoid(u: float) -> float:
    """:func:`sigmoid` with :func:`exp_neg` (vectorisable; exact to round-off for |u| <= 40).

    Examples
    --------
    >>> all(abs(lane_sigmoid(u) - sigmoid(u)) <= 4e-16 * sigmoid(u)
    ...     for u in (-30.0, -1.0, 0.0, 0.5, 12.0))
    True
    """
    return sigmoid_from(u, exp_neg(-abs(u)))


#: largest exp argument of :func:`lane_wang_latch` that is exact to round-off (beyond,
#: :func:`exp_neg` clamps; the lane kernel then latches with the scalar kernels instead)
LANE_EXP_LIMIT = -EXP_NEG_FLOOR


@njit(cache=True, inline="always")  # in the lane loops: see the module docstring
def lane_motion_terms(p: np.ndarray, vm: float) -> tuple[float, float, float, float]:
    """:func:`motion_terms` with :func:`lane_exp`, and the largest |exp argument|.

    ``(F_t, alpha/2, exp(-a4 v_m), largest)``: branch-free, so a loop over lanes
    vectorises; within round-off of :func:`motion_terms` while ``largest`` stays within
    :data:`LANE_EXP_LIMIT`.

    Examples
    --------
    >>> p = np.zeros(W_SIZE)
    >>> p[W_F0], p[W_A0], p[W_A1], p[W_K0], p[W_A4] = 100.0, 40.0, 5.0, 1.0, 7.5
    >>> lane, exact = lane_motion_terms(p, 0.3), motion_terms(p, 0.3)
    >>> all(abs(a - b) <= 1e-15 * abs(b) for a, b in zip(lane, exact)), lane[3]
    (True, 2.25)
    """
    x1 = p[W_A1] * vm
    x4 = -p[W_A4] * vm
    ft = transition_force_from(p, lane_exp(x1))
    return ft, 0.5 * hysteresis_slope(p, vm), lane_exp(x4), max(abs(x1), abs(x4))


@njit(cache=True, inline="always")  # in the lane latch: see the module docstring
def lane_wang_latch(
    p: np.ndarray, vm: float, sgn_a: float, i: float
) -> tuple[float, float, float, float, float, float, float]:
    """Every latched term of :func:`wang_latch_motion` and :func:`wang_latch_current`.

    Returns ``(alpha/2, v_h + v_b, F_t, F_b, k_d C_i, exp(-a4 v_m), largest |exp
    argument|)``, with the exponentials from :func:`lane_exp` and :func:`lane_sigmoid`
    (branch-free: a loop over lanes vectorises). The formulas are the scalar kernels' own (``*_from``, :func:`hysteresis_slope`,
    :func:`wang_shift`, :func:`wang_offset_force`); the results agree with theirs to
    round-off while the largest argument stays within :data:`LANE_EXP_LIMIT`.

    Examples
    --------
    >>> p = np.zeros(W_SIZE)
    >>> p[W_A0], p[W_A1], p[W_F0], p[W_K2], p[W_A2], p[W_A4], p[W_KD] = 900.0, 5.0, 60.0, 9.0, 7.0, 7.5, 1.0
    >>> wang_derive(p)
    >>> s = np.zeros(STATE_SIZE)
    >>> wang_latch_motion(p, s, 0.2, 1.0)
    >>> wang_latch_current(p, s, 0.3)
    >>> lane = lane_wang_latch(p, 0.2, 1.0, 0.3)
    >>> exact = (s[WS_HALF_ALPHA], s[WS_SHIFT], s[WS_FT], s[WS_FB], s[WS_CI], s[WS_DECAY])
    >>> all(abs(a - b) <= 1e-15 * abs(b) for a, b in zip(lane[:6], exact))
    True
    """
    ft, half_alpha, decay, motion = lane_motion_terms(p, vm)
    u2 = p[W_A2] * (i + p[W_I0])
    u3 = p[W_A3] * (i + p[W_I1])
    s2, s3 = lane_sigmoid(u2), lane_sigmoid(u3)
    ci = current_gain_from(p, s2)
    shift = wang_shift(p, sgn_a, vm, hysteresis_factor_from(p, s3))
    largest = max(motion, max(abs(u2), abs(u3)))
    return half_alpha, shift, ft, wang_offset_force(p, ci, ft), p[W_KD] * ci, decay, largest


@njit(cache=True, **INLINED)
def wang_eval(p: np.ndarray, s: np.ndarray, v: float, i: float) -> float:
    """Damper force of eqs. (2.15) and (2.19) from the latched state, with the gain k_d.

    ``F_d = k_d C_i (F_t tanh(alpha (v_d + v_h + v_b)/2) - F_b)(1 + k_v |v_d|)``,
    ``F_b = k5 C_i F_t``, ``v_b = k6 v_m``; k5 = k6 = 0 and k1c = k1e give the symmetric
    model (2.15); k4 = 0 the mean model.
    """
    if i != s[WS_I]:  # also true for the NaN set by wang_latch_motion
        wang_latch_current(p, s, i)
    k1 = p[W_K1C] if v >= 0.0 else p[W_K1E]
    tanh = fast_tanh(s[WS_HALF_ALPHA] * (v + s[WS_SHIFT]))
    return wang_combine(p[W_KD] * s[WS_CI], s[WS_FT], s[WS_FB], tanh, k1, s[WS_DECAY], v)


@njit(cache=True, inline="always")  # in the lane stages: see the module docstring
def wang_combine(
    kd_ci: float, ft: float, fb: float, tanh: float, k1: float, decay: float, v: float
) -> float:
    """``k_d C_i (F_t tanh - F_b)(1 + k1 exp(-a4 v_m) |v_d|)`` from the latched terms.

    The one place the force of eqs. (2.15)/(2.19) is assembled, for the scalar step and
    the lane kernel alike.
    """
    return kd_ci * (ft * tanh - fb) * (1.0 + k1 * decay * abs(v))


@njit(cache=True, inline="always")  # allocates: needs reference counting
def wang_force(p: np.ndarray, v: float, sgn_a: float, i: float, vm: float) -> float:
    """Force of the dissertation's model at one point (convenience; allocates a state)."""
    s = np.empty(STATE_SIZE)
    wang_latch_motion(p, s, vm, sgn_a)
    return wang_eval(p, s, v, i)


@njit(cache=True, **INLINED)
def wang_inverse(
    p: np.ndarray, target: float, v: float, sgn_a: float, vm: float, i_max: float
) -> float:
    """Inverse model (model reference, section 2.3): the current whose force magnitude is |target|.

    The passive hysteron uses the (2.13) form of v_h (current independent), as in the
    dissertation, so the inverse is exact for the (2.13) variant. (2.9) is inverted
    directly (the printed closed form (2.17) is garbled, erratum 6).
    """
    return wang_inverse_from(p, target, passive_hysteron(p, v, sgn_a, vm), i_max)


@njit(cache=True, **INLINED)
def wang_inverse_from(p: np.ndarray, target: float, fh: float, i_max: float) -> float:
    """:func:`wang_inverse` from the passive hysteron ``fh`` (:func:`passive_hysteron`).

    Examples
    --------
    >>> p = np.zeros(W_SIZE)
    >>> p[W_KD], p[W_K2], p[W_A2], p[W_I0] = 1.0, 2.0, 5.0, 0.1
    >>> wang_derive(p)
    >>> wang_inverse_from(p, 50.0, 100.0, 0.5), wang_inverse_from(p, 1e4, -100.0, 0.5)
    (0.0, 0.5)
    """
    denom = p[W_KD] * abs(fh)
    if denom == 0.0:
        # the damper produces no force at this state whatever the current
        return 0.0 if target == 0.0 else i_max
    c = abs(target) / denom
    if c <= 1.0:
        return 0.0
    y = (c - 1.0) / p[W_K2] + p[W_SA2]
    if y >= 1.0:
        return i_max
    i = -p[W_I0] - math.log(1.0 / y - 1.0) / p[W_A2]
    if i < 0.0:
        return 0.0
    if i > i_max:
        return i_max
    return i


# ----------------------------------------------------------------------------------
# peers
@njit(cache=True, **INLINED)
def bingham_force(p: np.ndarray, v: float, i: float) -> float:
    """Bingham plastic model with current-linear yield force and viscosity."""
    return (p[B_FCA] + p[B_FCB] * i) * sign(v) + (p[B_C0A] + p[B_C0B] * i) * v + p[B_F0]


@njit(cache=True, **INLINED)
def spencer_ydot(p: np.ndarray, x: float, xd: float, y: float, z: float, u: float) -> float:
    """Internal velocity y' of the modified Bouc-Wen model."""
    alpha = p[S_ALA] + p[S_ALB] * u
    c0 = p[S_C0A] + p[S_C0B] * u
    c1 = p[S_C1A] + p[S_C1B] * u
    return (alpha * z + c0 * xd + p[S_K0] * (x - y)) / (c0 + c1)


@njit(cache=True, **INLINED)
def spencer_force(p: np.ndarray, x: float, xd: float, y: float, z: float, u: float) -> float:
    """F = c1 y' + k1 (x - x0)."""
    c1 = p[S_C1A] + p[S_C1B] * u
    return c1 * spencer_ydot(p, x, xd, y, z, u) + p[S_K1] * (x - p[S_X0])


@njit(cache=True, **INLINED)
def _spencer_rates(
    p: np.ndarray, x: float, xd: float, y: float, z: float, u: float, command: float
) -> tuple[float, float, float]:
    yd = spencer_ydot(p, x, xd, y, z, u)
    w = xd - yd
    az = abs(z)
    n = p[S_N]
    zd = -p[S_GAM] * abs(w) * z * az ** (n - 1.0) - p[S_BET] * w * az**n + p[S_A] * w
    ud = -p[S_ETA] * (u - command)
    return yd, zd, ud


# not inlined (explicitly: numba would inherit its caller's forceinline): large, and
# dominated by its own sub-steps
@njit(cache=True, forceinline=False)
def spencer_advance(p: np.ndarray, s: np.ndarray, x: float, xd: float, i: float, dt: float) -> None:
    """Integrate (y, z, u) over ``dt`` with x' held, by RK4 sub-steps sized for stability."""
    command = p[S_VPA] * i
    y, z, u = s[0], s[1], s[2]
    c0 = p[S_C0A] + p[S_C0B] * u
    c1 = p[S_C1A] + p[S_C1B] * u
    alpha = p[S_ALA] + p[S_ALB] * u
    n = p[S_N]
    az = abs(z)
    # largest eigenvalue estimate of the (y, z, u) dynamics
    rate = (p[S_GAM] + p[S_BET]) * n * az ** max(n - 1.0, 0.0) * (abs(xd) + 1e-3)
    rate += (p[S_A] + (p[S_GAM] + p[S_BET]) * az**n) * alpha / (c0 + c1)
    rate += p[S_K0] / (c0 + c1) + p[S_ETA]
    nsub = int(min(max(math.ceil(dt * rate / 1.5), 1.0), 10000.0))
    h = dt / nsub
    for k in range(nsub):
        xs = x + xd * k * h
        y1, z1, u1 = _spencer_rates(p, xs, xd, y, z, u, command)
        y2, z2, u2 = _spencer_rates(
            p, xs + 0.5 * h * xd, xd, y + 0.5 * h * y1, z + 0.5 * h * z1, u + 0.5 * h * u1, command
        )
        y3, z3, u3 = _spencer_rates(
            p, xs + 0.5 * h * xd, xd, y + 0.5 * h * y2, z + 0.5 * h * z2, u + 0.5 * h * u2, command
        )
        y4, z4, u4 = _spencer_rates(p, xs + h * xd, xd, y + h * y3, z + h * z3, u + h * u3, command)
        y += h * (y1 + 2.0 * y2 + 2.0 * y3 + y4) / 6.0
        z += h * (z1 + 2.0 * z2 + 2.0 * z3 + z4) / 6.0
        u += h * (u1 + 2.0 * u2 + 2.0 * u3 + u4) / 6.0
    s[0], s[1], s[2] = y, z, u


# ----------------------------------------------------------------------------------
# peak-velocity estimators
@njit(cache=True, **INLINED)
def _clamp(u: float, lo: float, hi: float) -> float:
    return lo if u < lo else (hi if u > hi else u)


@njit(cache=True, **INLINED)
def estimator_pointwise(ek: int, ep: np.ndarray, x: float, v: float, a: float) -> float:
    """v_m of a freshly reset estimator that has seen one sample."""
    if ek == EST_KNOWN:
        return ep[0]
    if ek == EST_WINDOW:
        return _clamp(abs(v), ep[0], ep[1])
    # instantaneous: (2.14); cycle-rms: one sample of the radicand whose cycle mean it takes
    return _clamp(math.sqrt(max(v * v - a * x, 0.0)), ep[0], ep[1])


@njit(cache=True, **INLINED)
def _cycle_rms_update(ep: np.ndarray, es: np.ndarray, v: float) -> float:
    """sqrt(2 mean(v_d^2)) over the last n samples (fewer at the start), clamped.

    The cycle mean of (2.14)'s radicand ``v^2 - a x`` equals ``2 mean(v^2)`` for any
    periodic motion (integrate ``a x`` by parts over a cycle), so this is the cycle average
    of (2.14): exact for a sinusoid whatever its phase when the window is a whole number of
    half periods, free of ``a_d`` (no loop through the damper force) and insensitive to
    spikes. O(1) per sample: a running sum over a ring of the last n squares, summed afresh
    each time the ring wraps (so round-off cannot accumulate).
    """
    n = int(ep[2])
    head = int(es[CR_HEAD])
    count = es[CR_COUNT]
    w = v * v
    total = es[CR_SUM] + w
    if count >= n:
        total -= es[CR_RING + head]
    else:
        count += 1.0
    es[CR_RING + head] = w
    head += 1
    if head == n:
        head = 0
        total = 0.0
        for m in range(n):
            total += es[CR_RING + m]
    es[CR_HEAD] = head
    es[CR_COUNT] = count
    es[CR_SUM] = total
    return _clamp(math.sqrt(2.0 * max(total, 0.0) / count), ep[0], ep[1])


@njit(cache=True, **INLINED)
def estimator_update(
    ek: int, ep: np.ndarray, es: np.ndarray, x: float, v: float, a: float
) -> float:
    """Feed one sample to the estimator and return the new v_m."""
    if ek == EST_CYCLE_RMS:
        return _cycle_rms_update(ep, es, v)
    if ek != EST_WINDOW:
        return estimator_pointwise(ek, ep, x, v, a)
    # exact sliding maximum of |v| over the last n samples (monotonic deque in a ring
    # buffer of n + 1 slots; wrap-around by comparison, cheaper than integer modulo)
    n = int(ep[2])
    cap = n + 1
    head = int(es[0])
    count = int(es[1])
    step = es[2]
    w = abs(v)
    while count > 0:
        last = head + count - 1
        if last >= cap:
            last -= cap
        if es[3 + last] > w:
            break
        count -= 1
    pos = head + count
    if pos >= cap:
        pos -= cap
    es[3 + pos] = w
    es[3 + cap + pos] = step
    count += 1
    while es[3 + cap + head] <= step - n:
        head += 1
        if head == cap:
            head = 0
        count -= 1
    es[0] = head
    es[1] = count
    es[2] = step + 1.0
    return _clamp(es[3 + head], ep[0], ep[1])


# ----------------------------------------------------------------------------------
# one interface for every model
@njit(cache=True, **INLINED)
def damper_sample(
    kind: int,
    p: np.ndarray,
    s: np.ndarray,
    ek: int,
    ep: np.ndarray,
    es: np.ndarray,
    x: float,
    v: float,
    a: float,
    i: float,
) -> None:
    """Latch the internals held over the coming step from the sampled state.

    ``a`` is the acceleration available to a sampled controller: in closed loop, the
    previous step's (model reference, sections 2.4 and 7).
    """
    if kind == WANG:
        wang_latch_motion(p, s, estimator_update(ek, ep, es, x, v, a), sign(a))
    elif kind == SPENCER and s[3] == 0.0:
        s[0] = x  # no preload in the k0 spring at start
        s[1] = 0.0
        s[2] = p[S_VPA] * i  # coil filter settled on the first command
        s[3] = 1.0


@njit(cache=True, **INLINED)
def damper_force(kind: int, p: np.ndarray, s: np.ndarray, x: float, v: float, i: float) -> float:
    """Damper force [N] (positive resists compression) with the held internals ``s``."""
    if kind == WANG:
        return wang_eval(p, s, v, i)
    if kind == LINEAR:
        return p[0] * v
    if kind == BINGHAM:
        return bingham_force(p, v, i)
    if kind == SPENCER:
        return spencer_force(p, x, v, s[0], s[1], s[2])
    return math.nan  # an unknown code: the engine stops on the non-finite force


@njit(cache=True, **INLINED)
def damper_advance(
    kind: int, p: np.ndarray, s: np.ndarray, x: float, v: float, i: float, dt: float
) -> None:
    """Integrate the damper's internal dynamics over one step of length ``dt``."""
    if kind == SPENCER:
        spencer_advance(p, s, x, v, i, dt)


@njit(cache=True, **NO_REFCOUNT)
def damper_series(
    kind: int,
    p: np.ndarray,
    s: np.ndarray,
    ek: int,
    ep: np.ndarray,
    es: np.ndarray,
    x: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    i: np.ndarray,
    dt: float,
    force: np.ndarray,
    peak_velocity: np.ndarray,
) -> None:
    """Causal response to sampled motion and current (fills ``force``, ``peak_velocity``)."""
    for k in range(x.shape[0]):
        damper_sample(kind, p, s, ek, ep, es, x[k], v[k], a[k], i[k])
        force[k] = damper_force(kind, p, s, x[k], v[k], i[k])
        peak_velocity[k] = s[0] if kind == WANG else math.nan
        damper_advance(kind, p, s, x[k], v[k], i[k], dt)


@njit(cache=True, **NO_REFCOUNT)
def damper_pointwise(
    kind: int,
    p: np.ndarray,
    ek: int,
    ep: np.ndarray,
    x: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    i: np.ndarray,
    vm: np.ndarray,
    force: np.ndarray,
    s: np.ndarray,
) -> None:
    """Force of a freshly reset damper at each point (vm NaN: from the estimator).

    ``s`` is work space of ``STATE_SIZE``.
    """
    for k in range(x.shape[0]):
        if kind == WANG:
            m = vm[k] if not math.isnan(vm[k]) else estimator_pointwise(ek, ep, x[k], v[k], a[k])
            wang_latch_motion(p, s, m, sign(a[k]))
        elif kind == SPENCER:
            s[3] = 0.0
            damper_sample(kind, p, s, ek, ep, ep, x[k], v[k], a[k], i[k])
        force[k] = damper_force(kind, p, s, x[k], v[k], i[k])


@njit(cache=True, **NO_REFCOUNT)
def wang_inverse_array(
    p: np.ndarray,
    ek: int,
    ep: np.ndarray,
    target: np.ndarray,
    x: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    vm: np.ndarray,
    i_max: float,
    current: np.ndarray,
    hysteron: np.ndarray,
) -> None:
    """:func:`wang_inverse` and :func:`passive_hysteron` over arrays (vm NaN: estimator)."""
    for k in range(target.shape[0]):
        m = vm[k] if not math.isnan(vm[k]) else estimator_pointwise(ek, ep, x[k], v[k], a[k])
        sa = sign(a[k])
        fh = passive_hysteron(p, v[k], sa, m)
        current[k] = wang_inverse_from(p, target[k], fh, i_max)
        hysteron[k] = fh
