"""The dissertation's testable claims of Chapter 5 (inverse-model hi-lo), as data.

:data:`CLAIMS` in the dissertation's order; :data:`KNOWN`: those known not to hold in our
model, with the suspected cause (assembled in :mod:`mrsuspension.report.findings.claims`).
"""

from __future__ import annotations

from mrsuspension.report.findings.checks import (
    CONSIDERABLY,
    GAMMA,
    INSENSITIVE,
    MEAN_CURRENT,
    ROAD,
    ROAD_DLC,
    SHOCK,
    SLIGHT,
    TRACKING,
    Check,
    Claim,
    about,
    all_of,
    band_amplitude,
    change,
    compare,
    dtr_values,
    fig,
    fmean,
    fpeak,
    fraction,
    hf_fraction,
    max_rate,
    monotone,
    peak,
    phase_peak,
    psd_mean,
    ratio,
    readings,
    spread,
    time_above,
    within,
)
from mrsuspension.report.findings.claims.common import (
    _SM_GAIN,
    _SWEPT_IN_FULL,
    A5_F,
    A5_P,
    A5_T,
    A6_P,
    INV_H1,
    INV_KD,
    INV_KD_F,
    INV_KD_SCM,
    INV_MIX,
    INV_MODES,
    INV_SCM1,
    M5_F,
    M5_R,
    M5_T,
    M6_R,
    P4_P,
    P5_F,
    P5_P,
    P5_R,
    P5_T,
    P6_P,
    P6_R,
    R5,
    R6,
    T51,
    T52,
    T53,
    V5_P,
    V5_R,
    V6_P,
    V6_R,
    _beta_sensitivity,
    _decay,
    _dtr_readings,
    _identified_sensitivity,
    _insensitive_shock,
    _monotone_all,
    _one,
    _peaks_lower,
    _road_levels,
    _road_sensitivity,
    _sub,
    _swept,
    _tracking_by_speed,
)

__all__ = ["CLAIMS", "KNOWN"]


def _relative_velocity_levels() -> Check:
    """Figs 5.1/5.3: peak |v_r| within 25 % of 0.6 m/s (mean models) and 0.75 m/s
    (hysteretic)."""
    return all_of(
        about(peak("v_r"), _sub(INV_SCM1, "mean damper + mean inverse"), 0.6),
        about(peak("v_r"), _sub(INV_SCM1, "hysteretic damper + hysteretic inverse"), 0.75),
    )


CLAIMS: tuple[Claim, ...] = (
    # ---------------------------------------------------------------- 5.2 inverse hi-lo
    Claim(
        "5.2-mixed-inverse-transients",
        "5.2",
        "The presence of high magnitude transients in damping force are mostly caused by the "
        "mean inverse model. Such transients can be partly suppressed when the hysteretic "
        "inverse model is considered",
        "Figs 5.1-5.3 (SCM, k_d = 1): max |dF_d/dt| is largest with the hysteretic damper and "
        "mean inverse, smaller with the hysteretic inverse, smallest with mean damper and "
        "mean inverse.",
        monotone(
            max_rate("F_d"),
            {
                "mean damper + mean inverse": INV_SCM1["mean damper + mean inverse"],
                "hysteretic damper + hysteretic inverse": INV_SCM1[
                    "hysteretic damper + hysteretic inverse"
                ],
                "hysteretic damper + mean inverse": INV_SCM1["hysteretic damper + mean inverse"],
            },
        ),
        also=("5.6",),
    ),
    Claim(
        "5.2-relative-velocity",
        "5.2",
        "The consideration of mean damping and inverse models yields peak steady-state "
        "relative velocity in the order of 0.6 m/s, which is considerably smaller than 0.75 "
        "m/s attained with hysteretic models.",
        "Figs 5.1/5.3: peak |v_r| 0.6 m/s (mean models) and 0.75 m/s (hysteretic), each "
        "within 25 %, the mean one at most 0.85 times the hysteretic one.",
        readings(
            (
                "'considerably' as at most 0.85 times (every value given: no unknown involved)",
                all_of(
                    _relative_velocity_levels(),
                    compare(
                        peak("v_r"),
                        _sub(INV_SCM1, "mean damper + mean inverse"),
                        _sub(INV_SCM1, "hysteretic damper + hysteretic inverse"),
                        "<",
                        CONSIDERABLY,
                    ),
                ),
            ),
            (
                "the sentence's own numbers: 'considerably smaller' is what 0.6 against 0.75 m/s "
                "(0.80 times) denotes, tested as each peak within 25 % of its printed value "
                "with the mean models' below the hysteretic ones'",
                all_of(
                    _relative_velocity_levels(),
                    compare(
                        peak("v_r"),
                        _sub(INV_SCM1, "mean damper + mean inverse"),
                        _sub(INV_SCM1, "hysteretic damper + hysteretic inverse"),
                        "<",
                    ),
                ),
            ),
        ),
    ),
    Claim(
        "5.2-tracking-speed",
        "5.2",
        "the proposed controller can yield satisfactory forcing-tracking ability only at "
        "higher velocities, while the forcing-tracking ability at low velocities is severely "
        "limited",
        "Fig 5.3 (hysteretic, SCM, k_d = 1): the relative tracking error while z_c < 0 at "
        "|v_r| < 0.1 m/s is over twice that at |v_r| >= 0.3 m/s.",
        readings(
            (
                "Fig 5.3, the hysteretic damper and inverse (every value given: no unknown "
                "involved)",
                _tracking_by_speed(("inverse hi-lo SCM k_d = 1", INV_H1)),
            ),
            (
                "Fig 5.1, the run the text's example of poor low-speed tracking names ('e.g. "
                "t = 3.4 s in Figure 5.1')",
                _tracking_by_speed(
                    ("mean models SCM k_d = 1", fig("5.1", "mean damper + mean inverse", "history"))
                ),
            ),
        ),
        also=("5.6", "8.2"),
    ),
    Claim(
        "5.2-acm-gamma",
        "5.2",
        "the chosen control parameters could yield asymmetric damping force ratio in the "
        "order of 2.5 in the ACM",
        "Fig 5.4 (inverse hi-lo, k_d = 1): gamma in ACM 2.5 within 25 %.",
        about(GAMMA, _sub(INV_MODES, "ACM"), 2.5),
    ),
    Claim(
        "5.2-acm-current",
        "5.2",
        "The corresponding power consumption is reduced by nearly 50% as observed from "
        "variations in i_d in Figure 5.4",
        "Fig 5.4: the mean drive current in ACM is 0.35-0.65 times that in SCM.",
        ratio(MEAN_CURRENT, _one(INV_MODES, "ACM"), _one(INV_MODES, "SCM"), 0.35, 0.65, 0.5),
    ),
    Claim(
        "5.2-acm-compression-current",
        "5.2",
        "The results show nonzero current of small peak value ($i_d < 0.1$ A; $F_d > 0$)",
        "Fig 5.4: in ACM the peak drive current in compression is below 0.1 A.",
        _identified_sensitivity(
            within(phase_peak("i_d", "compression"), _sub(INV_MODES, "ACM"), 0.0, 0.1)
        ),
    ),
    Claim(
        "5.2-acm-unsprung",
        "5.2",
        "The peak magnitudes of the unsprung mass oscillations, however, are considerably "
        "lower with asymmetric damping.",
        "Fig 5.4: ACM's peak |a_u| is at most 0.85 times SCM's; its peak |a_s| is higher.",
        readings(
            (
                "the peak |a_u|, over the ADFG centre's range",
                _swept(
                    all_of(
                        compare(
                            peak("a_u"),
                            _sub(INV_MODES, "ACM"),
                            _sub(INV_MODES, "SCM"),
                            "<",
                            CONSIDERABLY,
                        ),
                        compare(peak("a_s"), _sub(INV_MODES, "ACM"), _sub(INV_MODES, "SCM"), ">"),
                    )
                ),
            ),
            (
                "the oscillations the sentence before names ('both SCM and ACM controls tend to "
                "excite resonant oscillations of the unsprung mass'): a_u's largest spectral "
                "amplitude at the wheel hop, 7-15 Hz",
                all_of(
                    compare(
                        band_amplitude("a_u", 7.0, 15.0),
                        {"ACM (whole run)": fig("5.4", "ACM", "history")},
                        {"SCM (whole run)": fig("5.4", "SCM", "history")},
                        "<",
                        CONSIDERABLY,
                    ),
                    compare(peak("a_s"), _sub(INV_MODES, "ACM"), _sub(INV_MODES, "SCM"), ">"),
                ),
            ),
        ),
    ),
    Claim(
        "5.2-hysteretic-current",
        "5.2",
        "Although the hysteretic models yield significantly higher peak current in rebound, "
        "the corresponding sprung mass acceleration responses for mean as well as hysteretic "
        "models are comparable.",
        "Fig 5.5 (ACM, k_d = 1): peak rebound current of the hysteretic pair over 1/0.85 "
        "times the mean pair's; peak |a_s| within 10 %.",
        _swept(
            all_of(
                compare(
                    phase_peak("i_d", "rebound"),
                    _sub(INV_MIX, "mean damper + mean inverse"),
                    _sub(INV_MIX, "hysteretic damper + hysteretic inverse"),
                    "<",
                    CONSIDERABLY,
                ),
                spread(
                    peak("a_s"),
                    _sub(
                        INV_MIX,
                        "mean damper + mean inverse",
                        "hysteretic damper + hysteretic inverse",
                    ),
                ),
            )
        ),
    ),
    Claim(
        "5.2-mean-models-smooth",
        "5.6",
        'The "inverse model"-based upon mean damping force characteristics coupled with the '
        "mean force MR-damper model would yield smooth responses, but these deviate "
        "significantly from the practically realizable responses.",
        "Fig 5.5 (ACM, k_d = 1): the mean pair's share of i_d above 5 Hz is at most 0.85 times the hysteretic "
        "pair's, and its peak |v_r| differs from theirs by more than 15 %.",
        _swept(
            all_of(
                compare(
                    hf_fraction("i_d"),
                    _sub(INV_MIX, "mean damper + mean inverse"),
                    _sub(INV_MIX, "hysteretic damper + hysteretic inverse"),
                    "<",
                    CONSIDERABLY,
                ),
                compare(
                    peak("v_r"),
                    _sub(INV_MIX, "mean damper + mean inverse"),
                    _sub(INV_MIX, "hysteretic damper + hysteretic inverse"),
                    "<",
                    CONSIDERABLY,
                ),
            )
        ),
        also=("8.2",),
    ),
    # ---------------------------------------------------------------- 5.3 force gain
    Claim(
        "5.3-tracking-kd",
        "5.3",
        "The higher damping force permits reducing the force error between the target spring "
        "force and damping force.",
        "Fig 5.6 (inverse hi-lo, 2.5 cm / 1.5 Hz): rms(|F_d| - |F*|) while z_c < 0 falls as "
        "k_d rises (1, 2, 2.5), in ACM and SCM, by at least 15 % over the range.",
        all_of(
            monotone(TRACKING, INV_KD, "decreasing"),
            monotone(TRACKING, {f"SCM {k}": v for k, v in INV_KD_SCM.items()}, "decreasing"),
            compare(
                TRACKING, _sub(INV_KD, "k_d = 2.5"), _sub(INV_KD, "k_d = 1"), "<", CONSIDERABLY
            ),
        ),
        also=("5.6", "8.2"),
    ),
    Claim(
        "5.3-current-kd",
        "5.3",
        "the magnitude of drive current (i_d) in compression and rebound decreases with "
        "increasing value of k_d",
        "Fig 5.6 (ACM): the mean and the peak drive current fall as k_d rises.",
        all_of(
            monotone(MEAN_CURRENT, INV_KD, "decreasing"),
            monotone(peak("i_d"), INV_KD, "decreasing"),
        ),
    ),
    Claim(
        "5.3-peaks-kd",
        "5.3",
        "The results suggest a higher force gain yields improved suspension performance in "
        "view of a_s, a_u, x_s, x_r and F_T",
        "Fig 5.6 (ACM): peak |a_s|, |a_u|, |x_s|, |x_r| and |F_T| are lower at k_d = 2.5 than "
        "at k_d = 1.",
        _peaks_lower(
            ("a_s", "a_u", "x_s", "x_r", "F_T"), _one(INV_KD, "k_d = 2.5"), _sub(INV_KD, "k_d = 1")
        ),
    ),
    Claim(
        "5.3-frequency-kd",
        "5.3",
        "The peak acceleration and relative displacement transmissibility decrease "
        "significantly with higher force gain",
        "Fig 5.7 (ACM): peak T_as, T_au (0.5-15 Hz) and T_dr at k_d = 2.5 at most 0.85 times "
        "those at k_d = 1.",
        all_of(
            *(
                compare(
                    m, _sub(INV_KD_F, "k_d = 2.5"), _sub(INV_KD_F, "k_d = 1"), "<", CONSIDERABLY
                )
                for m in (fpeak("T_as"), fpeak("T_au", 0.5, 15.0), fpeak("T_dr"))
            )
        ),
    ),
    Claim(
        "5.3-mid-ride-kd",
        "5.3",
        "while the sprung mass acceleration response increases in the mid-ride frequencies region",
        "Fig 5.7 (ACM): mean T_as over 3-7 Hz is higher at k_d = 2.5 than at k_d = 1.",
        compare(
            fmean("T_as", 3.0, 7.0), _sub(INV_KD_F, "k_d = 2.5"), _sub(INV_KD_F, "k_d = 1"), ">"
        ),
        also=("5.6",),
    ),
    Claim(
        "5.3-dlc-kd",
        "5.3",
        "DLC due to tire force increases slightly in the 1.5 to 7.5 frequency range",
        "Fig 5.7 (ACM): DLC at k_d = 2.5 above k_d = 1 at more than half of the grid "
        "frequencies in 1.5-7.5 Hz.",
        fraction("DLC", _one(INV_KD_F, "k_d = 2.5"), _sub(INV_KD_F, "k_d = 1"), ">", (1.5, 7.5)),
    ),
    # ---------------------------------------------------------------- 5.4 response
    Claim(
        "5.4-harmonic-peaks",
        "5.4",
        "The results show that the semi-active ACM damping mode effectively reduces the peak "
        "magnitudes of x_s , a_s , x_r , and F_T , when compared to those attained under "
        "light and higher passive damping modes",
        "Fig 5.8: inverse hi-lo ACM (k_d = 2.5) has lower peak |x_s|, |a_s|, |x_r| and |F_T| "
        "than passive 0 A and 0.1 A.",
        _peaks_lower(
            ("x_s", "a_s", "x_r", "F_T"),
            _one(P5_T, "inverse-model hi-lo ACM"),
            _sub(P5_T, "passive 0 A", "passive 0.1 A"),
        ),
    ),
    Claim(
        "5.4-current-levels",
        "5.4",
        "current modulation is well below 0.1 A in the compression cycle, while the current "
        "approaches 0.35 A in the rebound mode",
        "Fig 5.8: peak drive current below 0.1 A in compression and 0.35 A within 25 % in rebound.",
        _identified_sensitivity(
            all_of(
                within(
                    phase_peak("i_d", "compression"),
                    _sub(P5_T, "inverse-model hi-lo ACM"),
                    0.0,
                    0.1,
                ),
                about(phase_peak("i_d", "rebound"), _sub(P5_T, "inverse-model hi-lo ACM"), 0.35),
            )
        ),
    ),
    Claim(
        "5.4-passive-resonance",
        "5.4",
        "both the passive damping modes yield higher resonant magnitudes of T_{as} , T_{dr} "
        "and DLC",
        "Fig 5.9: peak T_as, T_dr and DLC (0.5-4 Hz) of both passive modes exceed inverse "
        "hi-lo ACM's.",
        all_of(
            *(
                compare(
                    fpeak(k),
                    _sub(P5_F, "passive 0 A", "passive 0.1 A"),
                    _sub(P5_F, "inverse-model hi-lo ACM"),
                    ">",
                )
                for k in ("T_as", "T_dr", "DLC")
            )
        ),
    ),
    Claim(
        "5.4-light-passive-unsprung",
        "5.4",
        "Light passive mode damping yields significantly higher unsprung mass acceleration "
        "near the unsprung mass resonance but slightly lower response near the sprung mass "
        "resonance.",
        "Fig 5.9: mean T_au over 7-15 Hz at passive 0 A over 1/0.85 times inverse hi-lo "
        "ACM's; over 1-2.5 Hz lower than ACM's.",
        all_of(
            compare(
                fmean("T_au", 7.0, 15.0),
                _sub(P5_F, "inverse-model hi-lo ACM"),
                _sub(P5_F, "passive 0 A"),
                "<",
                CONSIDERABLY,
            ),
            compare(
                fmean("T_au", 1.0, 2.5),
                _sub(P5_F, "passive 0 A"),
                _sub(P5_F, "inverse-model hi-lo ACM"),
                "<",
            ),
        ),
    ),
    Claim(
        "5.4-ride-transmission",
        "5.4",
        "yields improved resonance control but slightly higher transmission in the important "
        "ride frequencies",
        "Fig 5.9: mean T_as over 3-7 Hz with inverse hi-lo ACM above passive 0 A's.",
        compare(
            fmean("T_as", 3.0, 7.0),
            _sub(P5_F, "inverse-model hi-lo ACM"),
            _sub(P5_F, "passive 0 A"),
            ">",
        ),
    ),
    Claim(
        "5.4-pulse",
        "5.4",
        "and higher passive damping ($i_d=0.1$ A) yield rapid rate of decay and effectively "
        "reduce the peak amplitudes of x_s and x_r",
        "Fig 5.10 (5 cm pulse): inverse hi-lo ACM and passive 0.1 A have lower peak |x_s|, "
        "|x_r| and rms x_s after the pulse (from its end) than passive 0 A.",
        all_of(
            *(
                compare(
                    m,
                    _sub(P5_P, "inverse-model hi-lo ACM", "passive 0.1 A"),
                    _sub(P5_P, "passive 0 A"),
                    "<",
                )
                for m in (peak("x_s"), peak("x_r"))
            ),
            _decay(
                _sub(P5_P, "inverse-model hi-lo ACM", "passive 0.1 A"), _sub(P5_P, "passive 0 A")
            ),
        ),
    ),
    Claim(
        "5.4-pulse-vs-skyhook",
        "5.4",
        'yields larger peak magnitude of a_s in compression than the "skyhook"-based hi-lo '
        "semi-active controller",
        "Figs 5.10 / 4.10 (5 cm pulse): peak |a_s| in compression is larger with inverse "
        "hi-lo ACM than with skyhook hi-lo ACM.",
        compare(
            phase_peak("a_s", "compression"),
            _sub(P5_P, "inverse-model hi-lo ACM"),
            _sub(P4_P, "skyhook hi-lo ACM"),
            ">",
        ),
    ),
    Claim(
        "5.4-pulse-current",
        "5.4",
        "The drive current exceeds 0.1 A only for short durations in rebound",
        "Figs 5.10 and 6.9 (5 cm pulse): inverse hi-lo and sliding mode ACM spend at most "
        "0.2 s of the 4 s record above 0.1 A.",
        _beta_sensitivity(
            within(
                time_above("i_d", 0.1),
                {
                    "inverse hi-lo": P5_P["inverse-model hi-lo ACM"],
                    "sliding mode": P6_P["sliding mode ACM"],
                },
                0.0,
                0.2,
            )
        ),
        also=("6.3",),
    ),
    Claim(
        "5.4-road-force",
        "5.4",
        "yields significantly higher damping force than the low passive mode damping "
        "($i_d=0$) in the entire frequency range",
        "Figs 5.11 / 6.10 (rough road): the PSD of F_d with inverse hi-lo and sliding mode "
        "ACM is above passive 0 A's at 90 % or more of the 0.5-20 Hz bins.",
        all_of(
            fraction(
                "PSD F_d",
                _one(P5_R, "inverse-model hi-lo ACM"),
                _sub(P5_R, "passive 0 A"),
                ">",
                (0.5, 20.0),
                0.9,
                strictly_more=False,
            ),
            fraction(
                "PSD F_d",
                _one(P6_R, "sliding mode ACM"),
                _sub(P6_R, "passive 0 A"),
                ">",
                (0.5, 20.0),
                0.9,
                strictly_more=False,
            ),
        ),
        depends_on=(ROAD,),
        also=("6.3",),
    ),
    Claim(
        "5.4-road-ride",
        "5.4",
        "The resulting high damping force tends to suppress the sprung mass acceleration near "
        "the resonant frequency but causes considerably higher acceleration responses in the "
        "ride frequency range.",
        "Figs 5.11 / 6.10: mean PSD of a_s over 2-7 Hz with inverse hi-lo and sliding mode "
        "ACM over 1/0.85 times passive 0 A's; over 1-2 Hz lower than passive 0 A's.",
        all_of(
            compare(
                psd_mean("a_s", 2.0, 7.0),
                _sub(P5_R, "passive 0 A"),
                {
                    "inverse hi-lo": P5_R["inverse-model hi-lo ACM"],
                    "sliding mode": P6_R["sliding mode ACM"],
                },
                "<",
                CONSIDERABLY,
            ),
            compare(
                psd_mean("a_s", 1.0, 2.0),
                {
                    "inverse hi-lo": P5_R["inverse-model hi-lo ACM"],
                    "sliding mode": P6_R["sliding mode ACM"],
                },
                _sub(P5_R, "passive 0 A"),
                "<",
            ),
        ),
        depends_on=(ROAD,),
        also=("6.3", "5.6", "8.2"),
    ),
    Claim(
        "5.4-road-dlc",
        "5.4",
        "The DLC value due to dynamic tire force of the semi-active ACM damping mode is in "
        "the order of 0.113, which is slightly lower than 0.139 due to that with the fixed "
        "low passive damping mode.",
        "Fig 5.11 (rough road): inverse hi-lo ACM's DLC is 0.7-0.95 times passive 0 A's "
        "(dissertation 0.81).",
        ratio(
            ROAD_DLC,
            _one(P5_R, "inverse-model hi-lo ACM"),
            _one(P5_R, "passive 0 A"),
            0.7,
            0.95,
            0.113 / 0.139,
        ),
        depends_on=(ROAD,),
    ),
    # ---------------------------------------------------------------- 5.5.1 mass
    Claim(
        "5.5.1-harmonic-mass",
        "5.5.1",
        "The magnitude of the damping force tends to increase with increasing sprung mass.",
        "Fig 5.12 (inverse hi-lo ACM): peak |F_d|, |x_r| and |F_T| rise with m_s.",
        _monotone_all(("F_d", "x_r", "F_T"), M5_T, "increasing"),
    ),
    Claim(
        "5.5.1-frequency-mass",
        "5.5.1",
        "the peak resonant magnitudes of T_{as} and T_{dr} remain insensitive to the sprung "
        "mass variations, while the peak magnitudes of T_{au} and DLC around the sprung mass "
        "natural frequency increase slightly with increasing m_s",
        "Fig 5.13: peak T_as and T_dr spread at most 10 % over m_s; peak T_au and DLC "
        "(0.5-4 Hz) rise with m_s.",
        all_of(
            spread(fpeak("T_as"), M5_F),
            spread(fpeak("T_dr"), M5_F),
            monotone(fpeak("T_au"), M5_F),
            monotone(fpeak("DLC"), M5_F),
        ),
    ),
    Claim(
        "5.5.1-table",
        "5.5.1",
        "The sprung mass shock displacement ratio (SDR_s) and acceleration ratio (SAR_s) "
        "increase with decreasing sprung mass.",
        "Table 5.1: SDR_s and SAR_s fall as m_s rises; SDR_u, SAR_u and RDR spread at most 10 %.",
        all_of(
            monotone(SHOCK["SDR_s"], T51, "decreasing"),
            monotone(SHOCK["SAR_s"], T51, "decreasing"),
            _insensitive_shock(T51, ("SDR_u", "SAR_u", "RDR"), INSENSITIVE),
        ),
    ),
    Claim(
        "5.5.1-table-dtr",
        "5.5.1",
        "The peak force deviations (DTR) decreases and increases by 18% and 14%, when the "
        "sprung mass is decreased and increased by 25%, respectively.",
        "Table 5.1: DTR 0.18 at 422 kg and 0.14 at 703 kg, within 30 %.",
        _dtr_readings(
            _one(T51, "m_s = 563"),
            {"m_s = 422": (T51["m_s = 422"], 0.18), "m_s = 703": (T51["m_s = 703"], 0.14)},
        ),
    ),
    Claim(
        "5.5.1-road-light-ride",
        "5.5.1",
        "The sprung mass acceleration response, however, increases with decreasing mass at "
        "higher frequencies.",
        "Figs 5.15 / 6.14 (rough road): mean PSD of a_s over 4-20 Hz is higher for 422 kg "
        "than for 703 kg, with inverse hi-lo and with sliding mode.",
        all_of(
            compare(
                psd_mean("a_s", 4.0, 20.0),
                {"inverse 422 kg": M5_R["m_s = 422 kg"]},
                {"inverse 703 kg": M5_R["m_s = 703 kg"]},
                ">",
            ),
            compare(
                psd_mean("a_s", 4.0, 20.0),
                {"sliding 422 kg": M6_R["m_s = 422 kg"]},
                {"sliding 703 kg": M6_R["m_s = 703 kg"]},
                ">",
            ),
        ),
        depends_on=(ROAD,),
        also=("6.4.1",),
    ),
    # ---------------------------------------------------------------- 5.5.2 speed
    Claim(
        "5.5.2-pulse-speed",
        "5.5.2",
        "Operation at a higher speed ($V=100$ km/h) results in higher demand on the damping "
        "force, and yields higher peak acceleration but lower sprung mass displacement.",
        "Figs 5.16 / 6.15 (3.5 cm pulse): at 100 km/h peak |F_d| and |a_s| are higher and "
        "peak |x_s| lower than at 50 km/h, with inverse hi-lo and with sliding mode.",
        all_of(
            *(
                all_of(
                    compare(
                        peak("F_d"),
                        {f"{n} 100 km/h": r["V = 100 km/h"]},
                        {f"{n} 50 km/h": r["V = 50 km/h"]},
                        ">",
                    ),
                    compare(
                        peak("a_s"),
                        {f"{n} 100 km/h": r["V = 100 km/h"]},
                        {f"{n} 50 km/h": r["V = 50 km/h"]},
                        ">",
                    ),
                    compare(
                        peak("x_s"),
                        {f"{n} 100 km/h": r["V = 100 km/h"]},
                        {f"{n} 50 km/h": r["V = 50 km/h"]},
                        "<",
                    ),
                )
                for n, r in (("inverse", V5_P), ("sliding", V6_P))
            )
        ),
        also=("6.4.2",),
    ),
    Claim(
        "5.5.2-table-changes",
        "5.5.2",
        "The sprung mass displacement and acceleration ratios (SDR_s and SAR_s) and the "
        "unsprung mass acceleration ratio (SAR_u) decrease by 42%, 76% and 54%, respectively",
        "Table 5.2's rows: at 100 km/h SDR_s changes by -37 %, SAR_s by -76 %, SAR_u by -61 %.",
        all_of(
            *(
                change(SHOCK[k], _one(T52, "V = 50"), {"V = 100": (T52["V = 100"], c)})
                for k, c in (
                    ("SDR_s", 0.57 / 0.91 - 1),
                    ("SAR_s", -0.76),
                    ("SAR_u", 0.48 / 1.24 - 1),
                )
            )
        ),
        inconsistent="the text's 42 % and 54 % do not match Table 5.2's rows (SDR_s 0.91 -> "
        "0.57 is -37 %, SAR_u 1.24 -> 0.48 is -61 %); 42 % is Table 4.2's SDR_s change. The "
        "table is tested.",
    ),
    Claim(
        "5.5.2-table-rest",
        "5.5.2",
        "The results also show that the unsprung mass and relative displacement ratios "
        "(SDR_u and RDR) remain insensitive to variations in speed.",
        "Table 5.2: SDR_u and RDR within 10 % between 50 and 100 km/h; DTR 0.37 within 30 %.",
        all_of(
            _insensitive_shock(T52, ("SDR_u", "RDR"), INSENSITIVE),
            dtr_values(_one(T52, "V = 50"), {"V = 100": (T52["V = 100"], 0.37)}),
        ),
    ),
    Claim(
        "5.5.2-road-dlc",
        "5.5.2",
        "The DLC due to tire force at 100 km/h increases slightly to 0.114, compared to 0.113 "
        "at 50 km/h.",
        "Figs 5.17 / 6.16 (rough road): DLC at 100 km/h is 0.97-1.1 times that at 50 km/h, "
        "with inverse hi-lo and with sliding mode.",
        _road_sensitivity(
            all_of(
                ratio(
                    ROAD_DLC,
                    ("inverse 100 km/h", V5_R["V = 100 km/h"]),
                    ("inverse 50 km/h", V5_R["V = 50 km/h"]),
                    0.97,
                    1.1,
                    0.114 / 0.113,
                ),
                ratio(
                    ROAD_DLC,
                    ("sliding 100 km/h", V6_R["V = 100 km/h"]),
                    ("sliding 50 km/h", V6_R["V = 50 km/h"]),
                    0.97,
                    1.1,
                    0.114 / 0.112,
                ),
            ),
        ),
        depends_on=(ROAD,),
        also=("6.4.2",),
    ),
    # ---------------------------------------------------------------- 5.5.3 excitation
    Claim(
        "5.5.3-harmonic-amplitude",
        "5.5.3",
        "Despite the higher damping force, the amplitudes of sprung mass (x_s and a_s) and "
        "tire force (F_T) responses increase considerably with increasing excitation "
        "amplitude.",
        "Fig 5.18 (1.5 Hz): peak |F_d|, |x_s|, |a_s| and |F_T| rise with the amplitude; the "
        "peak drive current varies by at most 25 %.",
        all_of(
            _monotone_all(("F_d", "x_s", "a_s", "F_T"), A5_T, "increasing"),
            spread(peak("i_d"), A5_T, SLIGHT),
        ),
    ),
    Claim(
        "5.5.3-frequency-amplitude",
        "5.5.3",
        "An increase in the excitation magnitude, however, does not alter the peak unsprung "
        "mass acceleration transmissibility (T_{au}).",
        "Fig 5.19: peak T_au (0.5-15 Hz) spread at most 10 %; peak T_as rises with the "
        "amplitude; peak DLC rises with it.",
        all_of(
            spread(fpeak("T_au", 0.5, 15.0), A5_F),
            monotone(fpeak("T_as"), A5_F),
            monotone(fpeak("DLC", 0.5, 15.0), A5_F),
        ),
    ),
    Claim(
        "5.5.3-pulse-height",
        "5.5.3",
        "An increase in peak excitation displacement yields higher peak damping force in "
        "response to increased target force and thus higher sprung mass acceleration.",
        "Figs 5.20 / 6.19 (pulse 2, 3.5, 5 cm): peak |F_d| and |a_s| rise with the height, "
        "with inverse hi-lo and with sliding mode.",
        all_of(
            *(
                _monotone_all(("F_d", "a_s"), {f"{n} {k}": v for k, v in r.items()}, "increasing")
                for n, r in (("inverse", A5_P), ("sliding", A6_P))
            )
        ),
        also=("6.4.3",),
    ),
    Claim(
        "5.5.3-table",
        "5.5.3",
        "The corresponding unsprung mass shock displacement and acceleration ratios (SDR_u "
        "and SAR_u) and relative displacement ratio (RDR) reveal increases and decreases by "
        "0.9% and 0.9%, 0.8% and 0.8%, and 2.3% and 2.3%.",
        "Table 5.3: SDR_s rises with the pulse height (0.88, 0.91, 0.96); SDR_u, SAR_u and "
        "RDR spread at most 10 %; DTR 0.29 at 2 and 5 cm within 30 %.",
        _swept(
            all_of(
                monotone(SHOCK["SDR_s"], T53),
                _insensitive_shock(T53, ("SDR_u", "SAR_u", "RDR"), INSENSITIVE),
                dtr_values(
                    _one(T53, "a_m = 3.5"),
                    {"a_m = 2": (T53["a_m = 2"], 0.29), "a_m = 5": (T53["a_m = 5"], 0.29)},
                ),
            )
        ),
    ),
    Claim(
        "5.5.3-road-roughness",
        "5.5.3",
        "The DLC due to tire force for the rough random road excitation is in the order of "
        "0.113, which is considerably higher than 0.056 obtained for the medium-rough road "
        "excitation.",
        "Figs 5.21 / 6.20: rough/medium-rough DLC ratio 2.0 (inverse hi-lo) and 2.1 (sliding "
        "mode), within 25 %.",
        all_of(
            ratio(
                ROAD_DLC,
                ("inverse rough", R5["rough"]),
                ("inverse medium", R5["medium-rough"]),
                0.75 * 0.113 / 0.056,
                1.25 * 0.113 / 0.056,
                0.113 / 0.056,
            ),
            ratio(
                ROAD_DLC,
                ("sliding rough", R6["rough"]),
                ("sliding medium", R6["medium-rough"]),
                0.75 * 0.112 / 0.054,
                1.25 * 0.112 / 0.054,
                0.112 / 0.054,
            ),
        ),
        depends_on=(ROAD,),
        also=("6.4.3",),
    ),
    Claim(
        "5.4-road-dlc-levels",
        "5.4",
        "The DLC value due to dynamic tire force of the semi-active ACM damping mode is in "
        "the order of 0.113",
        "Road DLC levels (50 km/h) within 25 %: rough, passive 0 A 0.139, inverse hi-lo 0.113, "
        "sliding mode 0.112; medium-rough, inverse hi-lo 0.056, sliding mode 0.054.",
        _road_levels(
            {
                "rough passive 0 A": (P5_R["passive 0 A"], 0.139),
                "rough inverse hi-lo": (P5_R["inverse-model hi-lo ACM"], 0.113),
                "rough sliding mode": (P6_R["sliding mode ACM"], 0.112),
                "medium-rough inverse hi-lo": (R5["medium-rough"], 0.056),
                "medium-rough sliding mode": (R6["medium-rough"], 0.054),
            }
        ),
        depends_on=(ROAD,),
        also=("5.5.3", "6.3", "6.4.3"),
    ),
)

#: Claims of this chapter known not to hold in our model: id -> suspected cause
KNOWN: dict[str, str] = {
    "5.2-hysteretic-current": "model: the hysteretic models' peak rebound current is only 4 % "
    "above the mean models' (0.448 against 0.429 A; both near i_max)",
    "5.2-mean-models-smooth": "model: with the mean damper and inverse the current is hardly "
    "smoother (share above 5 Hz 0.64 against 0.66) and v_r only 11 % lower",
    "5.4-pulse-current": _SM_GAIN + " (sliding mode spends 0.61 s above 0.1 A)",
    "5.5.1-frequency-mass": "model: the body-resonance DLC falls with m_s (0.52, 0.44, 0.37; "
    "DLC divides by the weight) where the dissertation sees a slight rise; T_au rises as "
    "stated" + _SWEPT_IN_FULL,
    "5.5.3-frequency-amplitude": "model: peak T_au grows 23 % with the amplitude (not "
    "unaltered) and peak T_as is flat (1.90, 2.00, 1.98) rather than rising" + _SWEPT_IN_FULL,
    "5.5.3-table": "model: SDR_s falls with the pulse height (0.86, 0.80, 0.69) where Table "
    "5.3 has it rising, and SAR_u / RDR vary by 28 % / 16 %, not under 3 %",
}
