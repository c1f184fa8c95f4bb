"""The dissertation's testable claims of Chapter 8 (the conclusions), as data.

:data:`CLAIMS` in the dissertation's order; :data:`KNOWN`: those known not to hold in our
model, with the suspected cause (assembled in :mod:`mrsuspension.report.findings.claims`).
"""

from __future__ import annotations

from mrsuspension.report.findings.checks import (
    SLIGHT,
    Claim,
    all_of,
    compare,
    fmean,
    fpeak,
    spread,
)
from mrsuspension.report.findings.claims.common import (
    _SWEPT_IN_FULL,
    CTRL_F,
    INV_KD_F,
    M5_F,
    M6_F,
    SM_ACM1_F,
    SM_G_F,
    _sub,
)

__all__ = ["CLAIMS", "KNOWN"]

CLAIMS: tuple[Claim, ...] = (
    # ---------------------------------------------------------------- 8.2 conclusions
    Claim(
        "8.2-skyhook-vs-inverse",
        "8.2",
        "offers superior vibration attenuation, tire force and rattle space performance, "
        "when compared to those of other control syntheses formulated in the study",
        "ACM controllers (Figs 4.9 / 5.9 / 6.8): skyhook hi-lo has the lowest mean T_as, DLC "
        "and T_dr over 0.5-15 Hz of the three.",
        all_of(
            *(
                compare(
                    fmean(k, 0.5, 15.0),
                    _sub(CTRL_F, "skyhook hi-lo"),
                    _sub(CTRL_F, "inverse hi-lo", "sliding mode"),
                    "<",
                )
                for k in ("T_as", "DLC", "T_dr")
            )
        ),
        inconsistent="section 6.5, which this conclusion restates, says the skyhook-based "
        "controller 'yields slight higher rattle space response in the vicinity of unsprung "
        "mass natural frequency than the two inverse-model-based controllers' "
        "(6.5-skyhook-wheel-hop); the conclusion's superior rattle space is tested.",
        also=("6.5",),
    ),
    Claim(
        "8.2-inverse-robust",
        "8.2",
        'The "inverse model"-based hi-lo and sliding-mode ACM controllers exhibit desirable '
        "robust control performance with respect to variations in some of the operating "
        "parameters, namely, operating load and speed.",
        "Figs 5.13 / 6.12: peak T_as (0.5-4 Hz) varies by at most 25 % over m_s with both "
        "inverse-model laws.",
        all_of(
            spread(fpeak("T_as"), {f"inverse {k}": v for k, v in M5_F.items()}, SLIGHT),
            spread(fpeak("T_as"), {f"sliding {k}": v for k, v in M6_F.items()}, SLIGHT),
        ),
        also=("5.6",),
    ),
    Claim(
        "8.2-high-preyield-degrades",
        "8.2",
        "High pre-yield damping required for improving the force-tracking performance, "
        "however, causes degradation of the vibration transmission performance of both "
        '"inverse model"-based controllers.',
        "ACM frequency responses: mean T_as over 3-7 Hz higher at k_d = 2.5 than at k_d = 1, "
        "for inverse hi-lo (Fig 5.7) and sliding mode.",
        all_of(
            compare(
                fmean("T_as", 3.0, 7.0),
                {"inverse k_d = 2.5": INV_KD_F["k_d = 2.5"]},
                {"inverse k_d = 1": INV_KD_F["k_d = 1"]},
                ">",
            ),
            compare(
                fmean("T_as", 3.0, 7.0),
                {"sliding k_d = 2.5": SM_G_F["ACM k_d = 2.5"]},
                {"sliding k_d = 1": SM_ACM1_F},
                ">",
            ),
        ),
        also=("5.6",),
    ),
)

#: Claims of this chapter known not to hold in our model: id -> suspected cause
KNOWN: dict[str, str] = {
    "8.2-skyhook-vs-inverse": "model: skyhook hi-lo ACM has the lowest mean DLC, but sliding "
    "mode a marginally lower mean T_as (0.798 against 0.804) and both inverse-model laws a "
    "lower mean T_dr (0.62-0.64 against 0.96: skyhook's wheel-hop stroke, which section 6.5 "
    "itself reports, 6.5-skyhook-wheel-hop holds)" + _SWEPT_IN_FULL,
}
