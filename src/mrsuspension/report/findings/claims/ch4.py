"""The dissertation's testable claims of Chapter 4 (skyhook hi-lo: nonlinearities, policies, SCM / ACM, mass, speed, excitation, gain, order, summary), as data.

:data:`CLAIMS` in the dissertation's order; :data:`KNOWN`: those known not to hold in our
model, with the suspected cause (assembled in :mod:`mrsuspension.report.findings.claims`).
"""

from __future__ import annotations

from mrsuspension.control.hilo import POLICY_LAWS
from mrsuspension.report.findings.checks import (
    CONSIDERABLY,
    GAMMA,
    INSENSITIVE,
    MEAN_CURRENT,
    ROAD,
    ROAD_DLC,
    SHOCK,
    SLIGHT,
    Check,
    Claim,
    Run,
    about,
    all_of,
    amplitude,
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
    retabled,
    road_current_std,
    spread,
    within,
)
from mrsuspension.report.findings.claims.common import (
    _RULE_GAINS,
    _SWEPT_IN_FULL,
    A4_F,
    A4_P,
    A4_T,
    K4_F,
    K4_P,
    K4_R,
    K4_T,
    M4_F,
    M4_P,
    M4_R,
    M4_T,
    N4_F,
    N4_R,
    N4_T,
    P4_F,
    P4_P,
    P4_R,
    P4_T,
    PASSIVE_F,
    POL_F,
    POL_T,
    R4,
    SKY_F15,
    SKY_H,
    SKY_T,
    T41,
    T42,
    T43,
    T44,
    T45,
    V4_P,
    V4_R,
    _adfg_sensitivity,
    _approaches,
    _band_ratio,
    _decay,
    _drift,
    _dtr_at_most,
    _dtr_readings,
    _identified_sensitivity,
    _insensitive_shock,
    _monotone_all,
    _one,
    _peaks_lower,
    _phase_ratio,
    _road_levels,
    _road_sensitivity,
    _sub,
    _swept,
)

__all__ = ["CLAIMS", "KNOWN"]


#: The CM smoothing of section 4.3.1 (xi_c = 10) read on the condition function z_c in
#: centimetre units (z_s', v_d in cm/s, x_d in cm): xi_c z_c 1e4 times the SI value, which
#: is xi_c = 1e5 on the SI z_c of the code (M_c depends on the product only). The model
#: reference's SI reading (the default) leaves policies III and IV at M_c = 0.47-0.53 (they
#: never switch) and every peak i_d at 0.22-0.37 A; in centimetres the CM switches as the
#: text describes and each policy's peak i_d is its peak i_z, 0.45-0.5 A at the stated
#: gains (docs/errata.md, "The hi-lo policies checked against the equations")
XI_C_CM_UNITS = 10.0 * 1e4
_CM_UNITS = "z_c in cm units (section 3.3's CM switches: xi_c = 10 on z_c x 1e4)"


def _cm_units(check: Check) -> Check:
    """``check`` with every hi-lo policy's CM read on z_c in centimetre units."""
    for law in POLICY_LAWS.values():
        check = retabled(check, "z_c cm", law, controller={"xi_c": XI_C_CM_UNITS})
    return check


#: Fig 4.4: each policy's peak drive current is 0.4-0.5 A
_PEAK_CURRENT = within(peak("i_d"), POL_T, 0.4, 0.5 + 1e-9, 0.5)


def _policy_readings(check: Check) -> Check:
    """A Figs 4.4/4.5 policy check at the stated gains (kept), at the gains by the stated
    rule (:data:`_RULE_GAINS`) and with the CM on z_c in centimetre units
    (:data:`XI_C_CM_UNITS`) at the stated gains."""
    rule = check
    for law, gain in _RULE_GAINS.items():
        rule = retabled(rule, f"k_c {gain:g}", law, controller={"gain": gain})
    name = "gains by the stated rule (peak i_d 0.49 A: k_c = " + ", ".join(
        f"{g:g}" for g in _RULE_GAINS.values()
    )
    return readings(
        ("stated gains k_c = 3, 10, 10, 300", check),
        (name + ")", rule),
        (_CM_UNITS, _cm_units(check)),
    )


def _hysteresis_transients(hysteretic: Run, mean: Run, scheme: str = "") -> Check:
    """The hysteretic damper's run has a larger max |dF_d/dt| and larger shares of a_s and
    a_u above 5 Hz than the mean damper's (history runs of one ``scheme``, a label prefix)."""
    return all_of(
        *(
            compare(m, {f"{scheme}hysteretic": hysteretic}, {f"{scheme}mean": mean}, ">")
            for m in (max_rate("F_d"), hf_fraction("a_s"), hf_fraction("a_u"))
        )
    )


CLAIMS: tuple[Claim, ...] = (
    # ---------------------------------------------------------------- 4.2 nonlinearities
    Claim(
        "4.2-hysteresis-passive",
        "4.2",
        "The presence of hysteresis, however, yields slightly larger magnitudes of relative "
        "velocity and acceleration responses.",
        "Passive damper at 0.2 A (Fig 4.1): the hysteretic model gives larger peak |v_r| and "
        "|a_s| than the mean model, by at most 25 %.",
        all_of(
            ratio(
                peak("v_r"),
                ("hysteretic", fig("4.1", "hysteretic model")),
                ("mean", fig("4.1", "mean model")),
                1.0,
                1 + SLIGHT,
            ),
            ratio(
                peak("a_s"),
                ("hysteretic", fig("4.1", "hysteretic model")),
                ("mean", fig("4.1", "mean model")),
                1.0,
                1 + SLIGHT,
            ),
        ),
    ),
    Claim(
        "4.2-light-damping-oscillation",
        "4.2",
        "The magnitude of such oscillations is further amplified under light damping "
        "($i_d=0$), as shown in Figure 4.2.",
        "Passive damper (Fig 4.2): the share of a_u above 5 Hz (the force-limiting "
        "oscillations) is larger at 0 A than at 0.2 A.",
        compare(
            hf_fraction("a_u"),
            {"0 A": fig("4.2", "passive 0 A")},
            {"0.2 A": fig("4.2", "passive 0.2 A")},
            ">",
        ),
        also=("4.6", "8.2"),
    ),
    Claim(
        "4.2-higher-current",
        "4.2",
        "the magnitudes of sprung and unsprung mass accelerations and the oscillations in "
        "a_u due to force-limiting property of the MR-damper can be reduced by selecting "
        "higher drive current",
        "Passive damper (Fig 4.2): peak |a_s| and |a_u| are lower at 0.2 A than at 0 A.",
        all_of(
            *(
                compare(
                    peak(s),
                    {"0.2 A": fig("4.2", "passive 0.2 A")},
                    {"0 A": fig("4.2", "passive 0 A")},
                    "<",
                )
                for s in ("a_s", "a_u")
            )
        ),
    ),
    Claim(
        "4.2-onoff-hysteresis",
        "4.2",
        "The presence of hysteresis causes larger magnitude transient peaks in damping force "
        "and acceleration responses, which occur in the vicinity of current switching",
        "On-off ADFG control (0-0.2 A, Fig 4.3): the hysteretic model gives a larger max "
        "|dF_d/dt| and larger peak |a_s| and |a_u| than the mean model.",
        all_of(
            *(
                compare(
                    m,
                    {"hysteretic": fig("4.3", "hysteretic model")},
                    {"mean": fig("4.3", "mean model")},
                    ">",
                )
                for m in (max_rate("F_d"), peak("a_s"), peak("a_u"))
            )
        ),
    ),
    Claim(
        "4.2-semi-active-hysteresis",
        "4.6",
        "The hysteresis property of the MR-damper would invariably yield transient "
        "oscillations in the damping force, and sprung and unsprung mass acceleration "
        "responses, when the semi-active control scheme is utilized.",
        "Skyhook hi-lo SCM (k_c = 3): the hysteretic damper gives a larger max |dF_d/dt| and "
        "a larger share of a_s and a_u above 5 Hz than the mean damper.",
        readings(
            (
                "skyhook hi-lo SCM, Fig 4.6's scheme (every value given: no unknown involved)",
                _hysteresis_transients(
                    SKY_H["SCM"], fig("4.6", "SCM", "history", damper={"hysteresis": False})
                ),
            ),
            (
                "the semi-active scheme whose hysteresis effect section 4.2 evaluates and this "
                "summary restates (on-off ADFG control, Fig 4.3)",
                _hysteresis_transients(
                    fig("4.3", "hysteretic model", "history"),
                    fig("4.3", "mean model", "history"),
                    "on-off ",
                ),
            ),
        ),
        also=("8.2",),
    ),
    Claim(
        "4.2-saturation-oscillation",
        "4.6",
        "The force saturation in the post-yield at higher velocities could cause strong "
        "oscillations in the unsprung mass acceleration response, irrespective of the open- "
        "or closed-loop operation of the MR-suspension.",
        "At 2.5 cm / 1.5 Hz, more than 20 % of the rms of a_u lies above 5 Hz with the MR "
        "damper both passive (0 A) and under skyhook hi-lo SCM; a linear damper "
        "(1500 N s/m) has almost none.",
        all_of(
            within(
                hf_fraction("a_u"),
                {"passive 0 A": fig("4.2", "passive 0 A", "history"), "skyhook SCM": SKY_H["SCM"]},
                0.2,
                1.0,
            ),
            within(
                hf_fraction("a_u"),
                {
                    "linear 1500 N s/m": fig(
                        "4.2",
                        "passive 0 A",
                        "history",
                        damper={"model": "linear", "damping": 1500.0},
                    )
                },
                0.0,
                0.05,
            ),
        ),
        also=("8.2",),
    ),
    # ---------------------------------------------------------------- 4.3.1 policies
    Claim(
        "4.3.1-policy-i-resonance",
        "4.3.1",
        'the scheme I based upon "skyhook" modulation of the current yields significantly '
        "lower resonant acceleration responses",
        "Fig 4.5 (SCM): peak T_as of policy I is at most 0.85 times that of II, III and IV.",
        _policy_readings(
            compare(
                fpeak("T_as"), _sub(POL_F, "I"), _sub(POL_F, "II", "III", "IV"), "<", CONSIDERABLY
            )
        ),
    ),
    Claim(
        "4.3.1-policy-i-high-frequency",
        "4.3.1",
        "and better attenuation of sprung mass acceleration in the higher frequency range",
        "Fig 4.5: above 3 Hz, T_as of policy I is below that of II and III at more than 75 % "
        "of the grid frequencies.",
        fraction("T_as", _one(POL_F, "I"), _sub(POL_F, "II", "III"), "<", (3.0, 15.0), 0.75),
    ),
    Claim(
        "4.3.1-policy-iv-highest",
        "4.3.1",
        "The lower damping due to policy IV related to relative displacement response yields "
        "highest resonant response",
        "Fig 4.5: policy IV has the highest peak T_as (0.5-4 Hz) of the four policies.",
        compare(fpeak("T_as"), _sub(POL_F, "IV"), _sub(POL_F, "I", "II", "III"), ">"),
    ),
    Claim(
        "4.3.1-dlc-i-iv",
        "4.3.1",
        "Both the schemes also yield relative small variations in the dynamic tire forces "
        "suggesting better road-holding potential as evident from lower DLC response in "
        "majority of the frequency range.",
        "Fig 4.5: the DLC of policies I and IV is below that of II and III at more than half "
        "of the grid frequencies.",
        _policy_readings(
            all_of(
                fraction("DLC", _one(POL_F, "I"), _sub(POL_F, "II", "III"), "<"),
                fraction("DLC", _one(POL_F, "IV"), _sub(POL_F, "II", "III"), "<"),
            )
        ),
    ),
    Claim(
        "4.3.1-tdr-i-iv-wheel-hop",
        "4.3.1",
        "Both the schemes also yield higher relative displacement response near the unsprung "
        "mass resonant frequency.",
        "Fig 4.5: mean T_dr over 7-15 Hz of policies I and IV is above that of II and III.",
        compare(fmean("T_dr", 7.0, 15.0), _sub(POL_F, "I", "IV"), _sub(POL_F, "II", "III"), ">"),
    ),
    Claim(
        "4.3.1-policy-i-smooth",
        "4.3.1",
        'the modulation scheme I based upon the "skyhook" damping concept [87] yields '
        "relative smooth variations in the drive current and damping force",
        "Fig 4.4 (2.5 cm, 1.5 Hz): policy I has the smallest share of i_d and of F_d above 5 Hz "
        "of the four policies.",
        _policy_readings(
            all_of(
                *(
                    compare(hf_fraction(s), _sub(POL_T, "I"), _sub(POL_T, "II", "III", "IV"), "<")
                    for s in ("i_d", "F_d")
                )
            )
        ),
    ),
    Claim(
        "4.3.1-policy-iv-switching",
        "4.3.1",
        "The control scheme IV based upon modulation of current in proportion to relative "
        "deflection response causes large variations in F_d and i_d near the switching "
        "instants.",
        "Fig 4.4: policy IV has the largest max |di_d/dt| and max |dF_d/dt| of the four policies.",
        _policy_readings(
            all_of(
                *(
                    compare(max_rate(s), _sub(POL_T, "IV"), _sub(POL_T, "I", "II", "III"), ">")
                    for s in ("i_d", "F_d")
                )
            )
        ),
    ),
    Claim(
        "4.3.1-ii-iii-oscillation",
        "4.3.1",
        "but cause high frequency oscillations around the switching, which are more evident "
        "in the unsprung mass acceleration response",
        "Fig 4.4: the share of a_u above 5 Hz is larger with policies II and III than with I.",
        _policy_readings(
            compare(hf_fraction("a_u"), _sub(POL_T, "II", "III"), _sub(POL_T, "I"), ">")
        ),
    ),
    Claim(
        "4.3.1-peak-current",
        "4.3.1",
        "to ensure identical peak value of the drive current about ($i_d=i_H=0.5$ A) under "
        "selected excitation magnitude",
        "Fig 4.4 (2.5 cm, 1.5 Hz): each policy's peak drive current is 0.4-0.5 A.",
        readings(
            ("stated gains k_c = 3, 10, 10, 300", _swept(_PEAK_CURRENT)),
            (_CM_UNITS, _cm_units(_PEAK_CURRENT)),
        ),
    ),
    # ---------------------------------------------------------------- 4.3.2 SCM / ACM
    Claim(
        "4.3.2-gamma",
        "4.3.2",
        "the chosen control parameters could yield asymmetric damping force ratio in the "
        "order of 2.4 in the ACM",
        "Fig 4.6: skyhook hi-lo ACM gives gamma (rebound/compression peak force) of "
        "2.4 +- 25 %, SCM about 1.",
        _adfg_sensitivity(
            all_of(
                about(GAMMA, _sub(SKY_T, "ACM"), 2.4),
                within(GAMMA, _sub(SKY_T, "SCM"), 0.9, 1.1, 1.0),
            )
        ),
        also=("4.6",),
    ),
    Claim(
        "4.3.2-current",
        "4.3.2",
        "The corresponding power consumption is reduced by nearly 50% as observed from "
        "variations in i_d in Figure 4.6",
        "Fig 4.6: the mean drive current in ACM is 0.35-0.65 times that in SCM.",
        _identified_sensitivity(
            ratio(MEAN_CURRENT, _one(SKY_T, "ACM"), _one(SKY_T, "SCM"), 0.35, 0.65, 0.5)
        ),
    ),
    Claim(
        "4.3.2-compression-peaks",
        "4.3.2",
        "the asymmetric damping modulation causes slightly higher magnitudes of the tire force "
        "(F_T), sprung mass deflection and acceleration (x_s and a_s), relative displacement "
        "(x_r) responses during the compression cycle",
        "Fig 4.6: over the compression samples (v_r > 0), ACM's peaks of |F_T|, |x_s|, |a_s| "
        "and |x_r| exceed SCM's by at most 25 %.",
        _swept(
            all_of(
                *(
                    ratio(
                        phase_peak(s, "compression"),
                        _one(SKY_T, "ACM"),
                        _one(SKY_T, "SCM"),
                        1.0,
                        1 + SLIGHT,
                    )
                    for s in ("F_T", "x_s", "a_s", "x_r")
                )
            )
        ),
    ),
    Claim(
        "4.3.2-drift",
        "4.3.2",
        "The light damping in the compression mode also yields asymmetric variations in the "
        "sprung mass displacement and relative displacement responses about their static "
        "equilibria.",
        "Fig 4.6: the mean stroke x_r over whole cycles moves further from equilibrium in ACM "
        "than in SCM (by more than 1 mm).",
        _drift(SKY_H, "ACM", "SCM", 1.0),
    ),
    Claim(
        "4.3.2-wheel-hop-excited",
        "4.3.2",
        "The damping force modulation in both SCM and ACM tend to excite resonant oscillations "
        "of the unsprung mass, even though the excitation frequency is close to the sprung "
        "mass resonance.",
        "Fig 4.6: the a_u spectrum has a component at 8-12 Hz of at least 10 % of its 1.5 Hz "
        "component, in SCM and in ACM.",
        _band_ratio(SKY_H, "a_u", (8.0, 12.0), (1.4, 1.6), 0.1),
    ),
    Claim(
        "4.3.2-acm-resonance-1.5cm",
        "4.3.2",
        "the ACM damping variations cause slightly larger resonant responses in a_s and x_r , "
        "when compared to the SCM",
        "Fig 4.7 (constant 1.5 cm, 0.5-15 Hz): peak T_as and T_dr (0.5-4 Hz) in ACM exceed "
        "SCM's by at most 25 %.",
        all_of(
            *(
                ratio(fpeak(k), _one(SKY_F15, "ACM"), _one(SKY_F15, "SCM"), 1.0, 1 + SLIGHT)
                for k in ("T_as", "T_dr")
            )
        ),
    ),
    Claim(
        "4.3.2-acm-above-resonance",
        "4.3.2",
        "The ACM variations, however, yield lower magnitudes of variations in the dynamic "
        "tire force (DLC) and transmitted accelerations at frequencies above the sprung mass "
        "resonant frequency.",
        "Fig 4.7 (constant 1.5 cm): above 2 Hz, ACM's DLC and T_as are below SCM's at more "
        "than half of the grid frequencies.",
        all_of(
            *(
                fraction(k, _one(SKY_F15, "ACM"), _sub(SKY_F15, "SCM"), "<", (2.0, 15.0))
                for k in ("DLC", "T_as")
            )
        ),
        also=("8.1",),
    ),
    Claim(
        "4.3.2-passive-light",
        "4.3.2",
        "Light constant damping corresponding to $i_d=0$ yields larger magnitudes of a_s , "
        "a_u , x_s , x_r and F_T .",
        "Fig 4.8: peak |a_s|, |a_u|, |x_s|, |x_r| and |F_T| are larger with the passive "
        "damper at 0 A than at 0.1 A.",
        all_of(
            *(
                compare(peak(s), _sub(P4_T, "passive 0 A"), _sub(P4_T, "passive 0.1 A"), ">")
                for s in ("a_s", "a_u", "x_s", "x_r", "F_T")
            )
        ),
    ),
    Claim(
        "4.3.2-passive-current-peak",
        "4.3.2",
        "An increase in the passive mode damping by selecting $i_d=0.1$ A tends to reduce the "
        "peak magnitudes considerably.",
        "Fig 4.9: the peak T_as (0.5-4 Hz) of the passive damper at 0.1 A is at most 0.85 "
        "times that at 0 A.",
        compare(
            fpeak("T_as"), _sub(P4_F, "passive 0.1 A"), _sub(P4_F, "passive 0 A"), "<", CONSIDERABLY
        ),
    ),
    Claim(
        "4.3.2-acm-xs-ft",
        "4.3.2",
        "ACM damping causes lower magnitudes of sprung mass displacement and tire force",
        "Fig 4.8: skyhook hi-lo ACM's peak |x_s| and |F_T| are below both passive modes'.",
        readings(
            (
                "peak |x_s| and |F_T| over the ADFG centre's range",
                _swept(
                    _peaks_lower(
                        ("x_s", "F_T"),
                        _one(P4_T, "skyhook hi-lo ACM"),
                        _sub(P4_T, "passive 0 A", "passive 0.1 A"),
                    )
                ),
            ),
            (
                "magnitude read as the amplitude of the oscillation (half peak-to-peak): the "
                "peak of ACM's x_s includes the drift about the static equilibrium that the "
                "same paragraph reports apart (4.3.2-drift)",
                all_of(
                    *(
                        compare(
                            amplitude(s),
                            _sub(P4_T, "skyhook hi-lo ACM"),
                            _sub(P4_T, "passive 0 A", "passive 0.1 A"),
                            "<",
                        )
                        for s in ("x_s", "F_T")
                    )
                ),
            ),
        ),
    ),
    Claim(
        "4.3.2-au-lowest-passive",
        "4.3.2",
        "The peak unsprung mass acceleration response, however, is lowest under higher value "
        "of passive damping ($i_d=0.1$ A).",
        "Fig 4.8: peak |a_u| at passive 0.1 A is below ACM's and passive 0 A's.",
        compare(
            peak("a_u"),
            _sub(P4_T, "passive 0.1 A"),
            _sub(P4_T, "passive 0 A", "skyhook hi-lo ACM"),
            "<",
        ),
    ),
    Claim(
        "4.3.2-acm-rebound-force",
        "4.3.2",
        "which yields considerably higher damping force in rebound. The compression mode "
        "damping force tends to be lower than that observed for the passive mode.",
        "Fig 4.8: ACM's peak |F_d| in rebound is over 1/0.85 times its compression peak, and "
        "its compression peak is below passive 0.1 A's.",
        all_of(
            _phase_ratio(("ACM", P4_T["skyhook hi-lo ACM"]), "F_d", CONSIDERABLY),
            compare(
                phase_peak("F_d", "compression"),
                {"ACM": P4_T["skyhook hi-lo ACM"]},
                _sub(P4_T, "passive 0.1 A"),
                "<",
            ),
        ),
    ),
    Claim(
        "4.3.2-acm-majority",
        "4.3.2",
        "ACM damping yields superior sprung mass acceleration transmissibility (T_{as}) and "
        "variations in the tire force in vast majority of the frequency range",
        "Fig 4.9: skyhook hi-lo ACM's T_as and DLC are below both passive modes' at more than "
        "half of the grid frequencies.",
        _swept(
            all_of(
                *(
                    fraction(k, _one(P4_F, "skyhook hi-lo ACM"), PASSIVE_F, "<")
                    for k in ("T_as", "DLC")
                )
            )
        ),
    ),
    Claim(
        "4.3.2-passive-resonance",
        "4.3.2",
        "Both the passive modes of damping yield higher resonant values of T_{as} and DLC",
        "Fig 4.9: peak T_as and peak DLC (0.5-4 Hz) of both passive modes exceed ACM's.",
        _adfg_sensitivity(
            all_of(
                *(
                    compare(fpeak(k), PASSIVE_F, _sub(P4_F, "skyhook hi-lo ACM"), ">")
                    for k in ("T_as", "DLC")
                )
            )
        ),
    ),
    Claim(
        "4.3.2-passive-0a-approaches",
        "4.3.2",
        "the responses corresponding to $i_d=0$ approach those of the semi-active damping at "
        "frequencies above 2.5 Hz",
        "Fig 4.9: above 2.5 Hz, T_as at passive 0 A is within 25 % of ACM's at every grid "
        "frequency.",
        _approaches(
            _one(P4_F, "passive 0 A"), _one(P4_F, "skyhook hi-lo ACM"), "T_as", 2.5, SLIGHT
        ),
    ),
    Claim(
        "4.3.2-passive-au-high",
        "4.3.2",
        "A higher value of passive damping, however, is desirable to limit the unsprung mass "
        "acceleration",
        "Fig 4.9: mean T_au over 5-15 Hz is lower at passive 0.1 A than with ACM.",
        compare(
            fmean("T_au", 5.0, 15.0),
            _sub(P4_F, "passive 0.1 A"),
            _sub(P4_F, "skyhook hi-lo ACM"),
            "<",
        ),
    ),
    Claim(
        "4.3.2-pulse-passive",
        "4.3.2",
        "Light passive damping ($i_d=0$), on the other hand, yields lower peak value of a_s , "
        "but higher peak values of x_s and considerably lower rate of decay.",
        "Fig 4.10 (5 cm pulse): passive 0 A has lower peak |a_s|, higher peak |x_s| and an "
        "rms x_s after the pulse (from its end, 0.80 s) over 1/0.85 times that of passive 0.1 A.",
        all_of(
            compare(peak("a_s"), _sub(P4_P, "passive 0 A"), _sub(P4_P, "passive 0.1 A"), "<"),
            compare(peak("x_s"), _sub(P4_P, "passive 0 A"), _sub(P4_P, "passive 0.1 A"), ">"),
            _decay(_sub(P4_P, "passive 0.1 A"), _sub(P4_P, "passive 0 A"), CONSIDERABLY),
        ),
    ),
    Claim(
        "4.3.2-pulse-acm-both",
        "4.3.2",
        "ACM damping variations can help realize the benefits of both the lower and higher "
        "passive mode damping, in limiting the peak responses and rate of decay",
        "Fig 4.10 (5 cm pulse): ACM's peak |a_s| is below passive 0.1 A's, its peak |x_s| and "
        "rms x_s after the pulse below passive 0 A's.",
        all_of(
            compare(peak("a_s"), _sub(P4_P, "skyhook hi-lo ACM"), _sub(P4_P, "passive 0.1 A"), "<"),
            compare(peak("x_s"), _sub(P4_P, "skyhook hi-lo ACM"), _sub(P4_P, "passive 0 A"), "<"),
            _decay(_sub(P4_P, "skyhook hi-lo ACM"), _sub(P4_P, "passive 0 A")),
        ),
    ),
    Claim(
        "4.3.2-road-force",
        "4.3.2",
        "the passive mode damping force is generally considerably higher than the semi-active "
        "damping force in majority of the frequency range",
        "Fig 4.11 (rough road, 50 km/h): the PSD of F_d at passive 0.1 A is above ACM's at "
        "more than half of the 0.5-20 Hz bins.",
        fraction(
            "PSD F_d",
            _one(P4_R, "passive 0.1 A"),
            _sub(P4_R, "skyhook hi-lo ACM"),
            ">",
            (0.5, 20.0),
        ),
        depends_on=(ROAD,),
    ),
    Claim(
        "4.3.2-road-ride",
        "4.3.2",
        "The PSD of sprung mass acceleration in the vicinity of the sprung mass resonance thus "
        "tends to be lower for the passive mode damping, while the response in the ride "
        "frequency range (2-8 Hz) is considerably larger than that of the semi-active",
        "Fig 4.11: mean PSD of a_s over 1-2 Hz is lower at passive 0.1 A than with ACM, and "
        "over 2-8 Hz ACM's is at most 0.85 times passive 0.1 A's.",
        all_of(
            compare(
                psd_mean("a_s", 1.0, 2.0),
                _sub(P4_R, "passive 0.1 A"),
                _sub(P4_R, "skyhook hi-lo ACM"),
                "<",
            ),
            compare(
                psd_mean("a_s", 2.0, 8.0),
                _sub(P4_R, "skyhook hi-lo ACM"),
                _sub(P4_R, "passive 0.1 A"),
                "<",
                CONSIDERABLY,
            ),
        ),
        depends_on=(ROAD,),
    ),
    Claim(
        "4.3.2-road-dlc",
        "4.3.2",
        "the semi-active ACM damping variations yield lower unsprung mass acceleration and "
        "dynamic tire force variations",
        "Fig 4.11 (rough road): skyhook hi-lo ACM gives a lower road DLC than passive 0.1 A.",
        compare(ROAD_DLC, _sub(P4_R, "skyhook hi-lo ACM"), _sub(P4_R, "passive 0.1 A"), "<"),
        depends_on=(ROAD,),
        inconsistent="the same paragraph gives DLC 0.138 for the semi-active ACM damping and "
        "0.111 for the fixed 0.1 A damping, a higher value for ACM; the text's reading "
        "(lower with ACM) is tested.",
    ),
    # ---------------------------------------------------------------- 4.4.1 sprung mass
    Claim(
        "4.4.1-harmonic-insensitive",
        "4.4.1",
        "The peak magnitudes of sprung mass responses (a_s and x_s), however, remain almost "
        "insensitive to variations in m_s .",
        "Fig 4.12 (m_s 422-703 kg): the spread of peak |a_s| and |x_s| is at most 10 %.",
        _swept(all_of(spread(peak("a_s"), M4_T), spread(peak("x_s"), M4_T))),
    ),
    Claim(
        "4.4.1-light-rebound-force",
        "4.4.1",
        "For a lighter sprung mass, the current modulation to higher value occurs earlier than "
        "that for the nominal mass, and the magnitude of the corresponding damping force is "
        "relatively smaller, particularly in the rebound mode.",
        "Fig 4.12: peak |F_d| in rebound is lower for 422 kg than for 563 kg.",
        compare(
            phase_peak("F_d", "rebound"),
            _sub(M4_T, "m_s = 422 kg"),
            _sub(M4_T, "m_s = 563 kg"),
            "<",
        ),
    ),
    Claim(
        "4.4.1-tire-force-mass",
        "4.4.1",
        "The mean and amplitude of the tire force increase with increasing sprung mass.",
        "Fig 4.12: peak |F_T| and the amplitude of F_T rise with m_s.",
        all_of(monotone(peak("F_T"), M4_T), monotone(amplitude("F_T"), M4_T)),
    ),
    Claim(
        "4.4.1-tas-tdr-mass",
        "4.4.1",
        "An increase in m_s causes slightly higher magnitudes of T_{as} and T_{dr}",
        "Fig 4.13: peak T_as and T_dr rise with m_s, spread at most 25 %.",
        all_of(
            *(
                all_of(monotone(fpeak(k), M4_F), spread(fpeak(k), M4_F, SLIGHT))
                for k in ("T_as", "T_dr")
            )
        ),
    ),
    Claim(
        "4.4.1-dlc-lighter-peak",
        "4.4.1",
        "Owing to its definition, the DLC increases with decreasing vehicle weight.",
        "Fig 4.13: the peak DLC over 0.5-15 Hz falls as m_s rises.",
        monotone(fpeak("DLC", 0.5, 15.0), M4_F, "decreasing"),
        also=("5.5.1",),
    ),
    Claim(
        "4.4.1-dlc-lighter-everywhere",
        "4.4.1",
        "The lower mass thus yields higher DLC response in the entire frequency range.",
        "Fig 4.13: the 422 kg car's DLC is above the 563 and 703 kg cars' at every grid frequency.",
        fraction(
            "DLC",
            _one(M4_F, "m_s = 422 kg"),
            _sub(M4_F, "m_s = 563 kg", "m_s = 703 kg"),
            ">",
            at_least=1.0,
            strictly_more=False,
        ),
    ),
    Claim(
        "4.4.1-pulse-current",
        "4.4.1",
        "A lower sprung mass causes higher drive current in rebound due to higher sprung mass "
        "velocity, as evident from the sprung mass acceleration response shown in Figure 4.14. "
        "The peak damping force, however, varies only slightly",
        "Fig 4.14 (3.5 cm pulse): the peak drive current falls as m_s rises; the peak |F_d| "
        "varies by at most 25 % ('only slightly').",
        all_of(monotone(peak("i_d"), M4_P, "decreasing"), spread(peak("F_d"), M4_P, SLIGHT)),
    ),
    Claim(
        "4.4.1-table-sar-s",
        "4.4.1",
        "The sprung mass shock acceleration ratio (SAR_s), however, increases by 32% when m_s "
        "is reduced by 25%, and it decreases by 21% when m_s is increased by 25%.",
        "Table 4.1: SAR_s changes by +32 % at 422 kg and -21 % at 703 kg.",
        change(
            SHOCK["SAR_s"],
            _one(T41, "m_s = 563"),
            {"m_s = 422": (T41["m_s = 422"], 0.32), "m_s = 703": (T41["m_s = 703"], -0.21)},
        ),
    ),
    Claim(
        "4.4.1-table-insensitive",
        "4.4.1",
        "the peak suspension travel (RDR), sprung mass displacement ratio (SDR_s) and "
        "unsprung mass acceleration and displacement ratios (SAR_u and SDR_u) remain "
        "insensitive to variations in m_s",
        "Table 4.1: the spread of RDR, SDR_s, SAR_u and SDR_u over m_s is at most 10 %.",
        _insensitive_shock(T41, ("RDR", "SDR_s", "SAR_u", "SDR_u"), INSENSITIVE),
    ),
    Claim(
        "4.4.1-table-dtr",
        "4.4.1",
        "The normalized peak force increases is in the order of 26%, when sprung mass is "
        "decreased by 25%. The peak tire force deviation, however, decreases by 29%",
        "Table 4.1: DTR 0.26 at 422 kg and 0.29 at 703 kg, within 30 %.",
        _dtr_readings(
            _one(T41, "m_s = 563"),
            {"m_s = 422": (T41["m_s = 422"], 0.26), "m_s = 703": (T41["m_s = 703"], 0.29)},
        ),
    ),
    Claim(
        "4.4.1-road-current",
        "4.4.1",
        "The results show higher drive current for the lower mass ($m_s=422$ kg) due to high "
        "sprung mass motion and thus damping force demand",
        "Fig 4.15 (rough road): the mean drive current falls as m_s rises.",
        monotone(MEAN_CURRENT, M4_R, "decreasing"),
        depends_on=(ROAD,),
    ),
    Claim(
        "4.4.1-road-dlc-heavier",
        "4.4.1",
        "The DLC due to tire force tends to be lower for heavier operating mass, which is "
        "attributed to its definition.",
        "Fig 4.15 (rough road): the road DLC falls as m_s rises.",
        monotone(ROAD_DLC, M4_R, "decreasing"),
        depends_on=(ROAD,),
        inconsistent="the next sentence says the DLC 'increases from 0.114 to 0.176, when the "
        "sprung mass is increased by 67%', and section 6.5 repeats the rise (+54 %); the "
        "'lower for heavier' reading is tested here, the rise in 6.5-road-dlc-mass.",
    ),
    # ---------------------------------------------------------------- 4.4.2 speed
    Claim(
        "4.4.2-pulse-speed",
        "4.4.2",
        "The peak sprung mass acceleration response at a speed of 100 km/h is relatively "
        "larger than that at 50 km/h.",
        "Fig 4.16 (3.5 cm pulse): at 100 km/h peak |a_s| is higher, peak |x_s| and the peak "
        "drive current lower than at 50 km/h.",
        all_of(
            compare(peak("a_s"), _sub(V4_P, "V = 100 km/h"), _sub(V4_P, "V = 50 km/h"), ">"),
            compare(peak("x_s"), _sub(V4_P, "V = 100 km/h"), _sub(V4_P, "V = 50 km/h"), "<"),
            compare(peak("i_d"), _sub(V4_P, "V = 100 km/h"), _sub(V4_P, "V = 50 km/h"), "<"),
        ),
    ),
    Claim(
        "4.4.2-table-changes",
        "4.4.2",
        "the sprung mass shock displacement and acceleration ratios (SDR_s and SAR_s) "
        "decrease and increase by 42% and 74%, respectively, and the unsprung mass "
        "acceleration ratio (SAR_u) decreases by 69%",
        "Table 4.2: at 100 km/h SDR_s changes by -42 %, SAR_s by -74 % and SAR_u by -69 %.",
        all_of(
            *(
                change(SHOCK[k], _one(T42, "V = 50"), {"V = 100": (T42["V = 100"], c)})
                for k, c in (("SDR_s", -0.42), ("SAR_s", -0.74), ("SAR_u", -0.69))
            )
        ),
        inconsistent="the text pairs SAR_s with an increase of 74 %, Table 4.2 lists SAR_s "
        "0.19 at 50 km/h and 0.05 at 100 km/h, a decrease of 74 %; the table is tested.",
    ),
    Claim(
        "4.4.2-table-insensitive",
        "4.4.2",
        "the unsprung mass and relative displacement ratios (SDR_u and RDR) remain relatively "
        "insensitive to variations in speed",
        "Table 4.2: SDR_u and RDR differ by at most 10 % between 50 and 100 km/h.",
        _insensitive_shock(T42, ("SDR_u", "RDR"), INSENSITIVE),
    ),
    Claim(
        "4.4.2-table-dtr",
        "4.4.2",
        "The peak force deviation (DTR) is in the order of 42%, when vehicle speed is "
        "increased by 100%",
        "Table 4.2: DTR at 100 km/h 0.42 within 30 %.",
        dtr_values(_one(T42, "V = 50"), {"V = 100": (T42["V = 100"], 0.42)}),
    ),
    Claim(
        "4.4.2-road-dlc",
        "4.4.2",
        "The DLC due to tire force at 100 km/h increases slightly to 0.142 compared to 0.138 "
        "at 50 km/h.",
        "Fig 4.17 (rough road): DLC at 100 km/h is 1.0-1.15 times that at 50 km/h.",
        ratio(
            ROAD_DLC,
            _one(V4_R, "V = 100 km/h"),
            _one(V4_R, "V = 50 km/h"),
            1.0,
            1.15,
            0.142 / 0.138,
        ),
        depends_on=(ROAD,),
    ),
    Claim(
        "4.4.2-road-current",
        "4.4.2",
        "The variation in drive current magnitude thus tends to be higher for the 50 km/h "
        "operation, when compared to that for 100 km/h.",
        "Fig 4.17: the standard deviation of the drive current is higher at 50 km/h.",
        _road_sensitivity(
            compare(road_current_std(), _sub(V4_R, "V = 50 km/h"), _sub(V4_R, "V = 100 km/h"), ">"),
        ),
        depends_on=(ROAD,),
    ),
    # ---------------------------------------------------------------- 4.4.3 excitation
    Claim(
        "4.4.3-harmonic-amplitude",
        "4.4.3",
        "An increase in excitation magnitude causes higher sprung mass displacement and "
        "acceleration response, and thus poses increased demand on the damping force. The "
        "drive current increases considerably",
        "Fig 4.18 (1.5 Hz): peak |x_s| and |a_s| rise with the amplitude (1.5, 2.5, 3.5 cm); "
        "the mean current at 2.5 cm is over 1/0.85 times that at 1.5 cm.",
        all_of(
            _monotone_all(("x_s", "a_s"), A4_T, "increasing"),
            compare(
                MEAN_CURRENT, _sub(A4_T, "a = 1.5 cm"), _sub(A4_T, "a = 2.5 cm"), "<", CONSIDERABLY
            ),
        ),
    ),
    Claim(
        "4.4.3-tas-slight",
        "4.4.3",
        "The peak resonant transmissibility increases only slightly with increasing "
        "excitation magnitude",
        "Fig 4.19: peak T_as rises with the amplitude, spread at most 25 %.",
        _swept(all_of(monotone(fpeak("T_as"), A4_F), spread(fpeak("T_as"), A4_F, SLIGHT))),
    ),
    Claim(
        "4.4.3-tau-dlc-tdr",
        "4.4.3",
        "Higher excitation magnitudes, however, cause significantly higher unsprung mass "
        "acceleration and thus the tire force responses",
        "Fig 4.19: peak T_au and DLC (0.5-15 Hz) rise with the amplitude, at 3.5 cm over "
        "1/0.85 times their value at 1.5 cm.",
        all_of(
            *(monotone(fpeak(k, 0.5, 15.0), A4_F) for k in ("T_au", "DLC")),
            *(
                compare(
                    fpeak(k, 0.5, 15.0),
                    _sub(A4_F, "a = 3.5 cm"),
                    _sub(A4_F, "a = 1.5 cm"),
                    ">",
                    1 / CONSIDERABLY,
                )
                for k in ("T_au", "DLC")
            ),
        ),
    ),
    Claim(
        "4.4.3-pulse-height",
        "4.4.3",
        "the drive current increases significantly with increasing pulse displacement",
        "Fig 4.20 (pulse 2, 3.5, 5 cm): peak drive current, peak |x_s|, |a_s| and |F_T| rise "
        "with the pulse height.",
        _swept(_monotone_all(("i_d", "x_s", "a_s", "F_T"), A4_P, "increasing")),
    ),
    Claim(
        "4.4.3-table",
        "4.4.3",
        "the sprung mass acceleration ratio (SAR_s) remains insensitive to variation in the "
        "peak excitation magnitude",
        "Table 4.3: SAR_s spread at most 10 % over the pulse heights; SDR_s falls as the "
        "height rises (0.75, 0.71, 0.64).",
        all_of(spread(SHOCK["SAR_s"], T43), monotone(SHOCK["SDR_s"], T43, "decreasing")),
    ),
    Claim(
        "4.4.3-table-dtr",
        "4.4.3",
        "The peak force deviation (DTR) increases and decreases in the order of 29%",
        "Table 4.3: DTR 0.29 at 2 cm and at 5 cm, within 30 %.",
        dtr_values(
            _one(T43, "a_m = 3.5"),
            {"a_m = 2": (T43["a_m = 2"], 0.29), "a_m = 5": (T43["a_m = 5"], 0.29)},
        ),
    ),
    Claim(
        "4.4.3-road-roughness",
        "4.4.3",
        "The DLC due to tire force for the rough road excitation increases significantly to "
        "0.138, compared to 0.045 for medium-rough road excitation.",
        "Fig 4.21: rough/medium-rough road DLC ratio 0.138/0.045 = 3.07, within 25 %.",
        ratio(
            ROAD_DLC,
            _one(R4, "rough"),
            _one(R4, "medium-rough"),
            0.75 * 0.138 / 0.045,
            1.25 * 0.138 / 0.045,
            0.138 / 0.045,
        ),
        depends_on=(ROAD,),
    ),
    Claim(
        "4.4.3-road-ride-comparable",
        "4.4.3",
        "The responses of a_s , a_u and F_T for the rough road excitation are comparable to "
        "those attained under the medium rough road excitation in the ride frequency range "
        "(2-5 Hz).",
        "Fig 4.21: mean PSDs of a_s, a_u and F_T over 2-5 Hz on the rough road are within a "
        "factor 1.5 of the medium-rough road's.",
        _road_sensitivity(
            all_of(
                *(
                    ratio(
                        psd_mean(s, 2.0, 5.0),
                        _one(R4, "rough"),
                        _one(R4, "medium-rough"),
                        1 / 1.5,
                        1.5,
                    )
                    for s in ("a_s", "a_u", "F_T")
                )
            ),
            white_rough=True,
        ),
        depends_on=(ROAD,),
    ),
    Claim(
        "4.4-road-dlc-levels",
        "4.3.2",
        "The results revealed comparable values of DLC of 0.111 for the fixed higher damping "
        "and 0.138 for the semi-active ACM damping.",
        "Road DLC levels (50 km/h) within 25 %: rough, passive 0.1 A 0.111 and skyhook ACM "
        "0.138; medium-rough, skyhook ACM 0.045.",
        _road_levels(
            {
                "rough passive 0.1 A": (P4_R["passive 0.1 A"], 0.111),
                "rough skyhook ACM": (P4_R["skyhook hi-lo ACM"], 0.138),
                "medium-rough skyhook ACM": (R4["medium-rough"], 0.045),
            }
        ),
        depends_on=(ROAD,),
        also=("4.4.3",),
    ),
    # ---------------------------------------------------------------- 4.5.1 gain
    Claim(
        "4.5.1-gain-current",
        "4.5.1",
        "a lower controller gain yield considerably lower current in accordance with the "
        "formulation in EQ (3.15). The corresponding relative velocity response, however, "
        "increases, which is evident from slightly higher relative displacement response.",
        "Fig 4.22: the mean current rises with k_c (0.5, 1.5, 3); peak |x_r| at k_c = 0.5 "
        "exceeds that at k_c = 3.",
        all_of(
            monotone(MEAN_CURRENT, K4_T),
            compare(peak("x_r"), _sub(K4_T, "k_c = 0.5"), _sub(K4_T, "k_c = 3"), ">"),
        ),
    ),
    Claim(
        "4.5.1-gain-comparable",
        "4.5.1",
        "the different values of controller gain yielded only slight variations in the "
        "resonant response magnitude. This is evident from comparable magnitudes of x_s , a_s "
        ", x_r and F_T .",
        "Fig 4.22: the spread of peak |x_s|, |a_s|, |x_r| and |F_T| over k_c is at most 25 % ('only slight').",
        all_of(*(spread(peak(s), K4_T, SLIGHT) for s in ("x_s", "a_s", "x_r", "F_T"))),
        also=("4.6", "8.2"),
    ),
    Claim(
        "4.5.1-gain-frequency",
        "4.5.1",
        "The results show variations in the control gain variation affect the frequency "
        "characteristics only slightly.",
        "Fig 4.23: the spread of peak T_as, T_au, T_dr and DLC (0.5-15 Hz) over k_c is at "
        "most 25 %.",
        all_of(
            *(spread(fpeak(k, 0.5, 15.0), K4_F, SLIGHT) for k in ("T_as", "T_au", "T_dr", "DLC"))
        ),
    ),
    Claim(
        "4.5.1-table-sdr",
        "4.5.1",
        "The lower compression damping corresponding to lower controller gain ($k_c=0.5$) "
        "causes slightly magnitudes of sprung mass displacement and accelerations",
        "Table 4.4: SDR_s falls as k_c rises (0.88, 0.74, 0.71).",
        monotone(SHOCK["SDR_s"], T44, "decreasing"),
    ),
    Claim(
        "4.5.1-table-insensitive",
        "4.5.1",
        "The relatively high insensitivity of the controller synthesis to variations in the "
        "gain are further evident from the measures of the shock response predicted in Table "
        "4.4.",
        "Table 4.4: the spread of SAR_s, SDR_u, SAR_u and RDR over k_c is at most 10 %.",
        _insensitive_shock(T44, ("SAR_s", "SDR_u", "SAR_u", "RDR"), INSENSITIVE),
        inconsistent="Table 4.4 lists SDR_u 1.71 for k_c = 0.5 and 1.5 but 1.17 for k_c = 3 "
        "(a 46 % change, against 'high insensitivity'); every other chapter-4 table has 1.17 "
        "at the nominal case, so 1.71 looks like a transposed 1.17. The text's reading is "
        "tested.",
    ),
    Claim(
        "4.5.1-pulse-rebound",
        "4.5.1",
        "while the rebound damping force remains insensitive to k_c and i_d",
        "Fig 4.24 (3.5 cm pulse): the peak |F_d| in rebound varies by at most 10 % over k_c.",
        # (not read with section 4.2's swapped phase names: the sentence's other half,
        # compression force "only slightly smaller" with the lower gain, would then read our
        # rebound peak, which falls 34 % from k_c = 3 to 0.5; a reading must not hold one
        # half of a sentence by breaking the other)
        _swept(spread(phase_peak("F_d", "rebound"), K4_P)),
    ),
    Claim(
        "4.5.1-road-gain",
        "4.5.1",
        "The DLC values due to tire force also remain identical (0.138) for both controller "
        "gains. The lower controller gain, however, yields considerably lower drive current",
        "Fig 4.25 (rough road): DLC at k_c = 1.5 and 3 within 5 %; mean current at k_c = 1.5 "
        "at most 0.85 times that at 3.",
        all_of(
            spread(ROAD_DLC, K4_R, 0.05),
            compare(
                MEAN_CURRENT, _sub(K4_R, "k_c = 1.5"), _sub(K4_R, "k_c = 3"), "<", CONSIDERABLY
            ),
        ),
        depends_on=(ROAD,),
    ),
    # ---------------------------------------------------------------- 4.5.2 order
    Claim(
        "4.5.2-order-current",
        "4.5.2",
        "a low order ($n=1$) controller yields rapid variations and considerable "
        "discontinuities in the drive current",
        "Fig 4.26: max |di_d/dt| falls as the order n rises (1, 2, 3).",
        monotone(max_rate("i_d"), N4_T, "decreasing"),
        also=("4.6", "8.2"),
    ),
    Claim(
        "4.5.2-order-peaks",
        "4.5.2",
        "The peak responses, however, do not show a significant influence of the controller order.",
        "Fig 4.26: the spread of peak |x_s|, |a_s|, |x_r| and |F_T| over n is at most 25 % (no 'significant influence'); "
        "n = 3 gives peaks of |x_s|, |a_s| and |x_r| at least those of n = 2.",
        _identified_sensitivity(
            all_of(
                *(spread(peak(s), N4_T, SLIGHT) for s in ("x_s", "a_s", "x_r", "F_T")),
                *(
                    compare(peak(s), _sub(N4_T, "n = 3"), _sub(N4_T, "n = 2"), ">=")
                    for s in ("x_s", "a_s", "x_r")
                ),
            )
        ),
    ),
    Claim(
        "4.5.2-order-frequency",
        "4.5.2",
        "The associated discontinuity in damping force, however, yields significantly higher "
        "unsprung mass acceleration transmissibility.",
        "Fig 4.27: n = 1 gives a peak T_au (0.5-15 Hz) over 1/0.85 times n = 2's, and lower "
        "peak T_as and T_dr than n = 2.",
        all_of(
            compare(
                fpeak("T_au", 0.5, 15.0),
                _sub(N4_F, "n = 2"),
                _sub(N4_F, "n = 1"),
                "<",
                CONSIDERABLY,
            ),
            *(
                compare(fpeak(k), _sub(N4_F, "n = 1"), _sub(N4_F, "n = 2"), "<")
                for k in ("T_as", "T_dr")
            ),
        ),
    ),
    Claim(
        "4.5.2-order-3-comparable",
        "4.5.2",
        "The frequency response characteristics of the highest order controller ($n=3$) are "
        "generally comparable with those of the second order ($n=2$) controller.",
        "Fig 4.27: peak T_as, T_au, T_dr and DLC (0.5-15 Hz) of n = 3 within 10 % of n = 2.",
        _identified_sensitivity(
            all_of(
                *(
                    spread(fpeak(k, 0.5, 15.0), _sub(N4_F, "n = 2", "n = 3"))
                    for k in ("T_as", "T_au", "T_dr", "DLC")
                )
            )
        ),
    ),
    Claim(
        "4.5.2-table-sdr",
        "4.5.2",
        "The sprung mass displacement ratio (SDR_s), however, decreases and increases by 35% "
        "and 20%, when the order is decreased to 1 or increased to 3, respectively.",
        "Table 4.5 text: SDR_s changes by -35 % at n = 1 and +20 % at n = 3.",
        change(
            SHOCK["SDR_s"],
            _one(T45, "n = 2"),
            {"n = 1": (T45["n = 1"], -0.35), "n = 3": (T45["n = 3"], 0.20)},
        ),
        inconsistent="Table 4.5 lists SDR_s 0.85, 0.71, 0.46 for n = 1, 2, 3: +20 % at n = 1 "
        "and -35 % at n = 3, the reverse of its text (the text agrees with Fig 4.28's: 'The "
        "higher damping [n = 1] yields lower peak displacement'); the text is tested.",
    ),
    Claim(
        "4.5.2-table-insensitive",
        "4.5.2",
        "The peak tire force deviation (DTR), sprung mass acceleration (SAR_s), unsprung "
        "displacement and acceleration (SDR_u and SAR_u) and relative displacement (RDR) "
        "ratios remain insensitive to variations in the controller order.",
        "Table 4.5: the spread of SAR_s, SDR_u, SAR_u and RDR over n at most 10 %; DTR at "
        "most 0.05.",
        all_of(
            _insensitive_shock(T45, ("SAR_s", "SDR_u", "SAR_u", "RDR"), INSENSITIVE),
            _dtr_at_most(T45, "n = 2", 0.05),
        ),
    ),
    Claim(
        "4.5.2-road-order",
        "4.5.2",
        "The responses at frequencies above 2 Hz show negligible effects of the controller "
        "order. The results show that the low order controller ($n=1$) yields considerably "
        "higher variation in i_d",
        "Fig 4.29 (rough road): mean PSD of a_s over 2-20 Hz within 10 % for n = 1 and 2; "
        "the standard deviation of i_d at n = 1 over 1/0.85 times that at n = 2.",
        _identified_sensitivity(
            all_of(
                spread(psd_mean("a_s", 2.0, 20.0), N4_R),
                compare(
                    road_current_std(), _sub(N4_R, "n = 2"), _sub(N4_R, "n = 1"), "<", CONSIDERABLY
                ),
            )
        ),
        depends_on=(ROAD,),
    ),
    # ---------------------------------------------------------------- 4.6 summary
    Claim(
        "4.6-skyhook-best-policy",
        "4.6",
        "offers superior vibration attenuation, tire force and rattle space performance, "
        "when compared to those of other control synthesis formulated in the study",
        "Fig 4.5: policy I has the lowest mean T_as, DLC and T_dr over the grid of the four "
        "policies.",
        _policy_readings(
            all_of(
                *(
                    compare(
                        fmean(k, 0.5, 15.0), _sub(POL_F, "I"), _sub(POL_F, "II", "III", "IV"), "<"
                    )
                    for k in ("T_as", "DLC", "T_dr")
                )
            )
        ),
        also=("4.3.1", "8.2"),
    ),
    Claim(
        "4.6-cm-smooths",
        "4.6",
        "can be effectively reduced by employing the proposed continuous modulation (CM) and "
        "asymmetric damping force generation (ADFG) functions",
        "Skyhook hi-lo at 2.5 cm / 1.5 Hz: CM (xi_c = 10, SCM) against a near switch "
        "(xi_c = 1000), and ADFG (xi = 4.5, ACM) against a near switch (xi = 1000): max "
        "|di_d/dt| and the share of a_u above 5 Hz are lower with the smooth functions.",
        _identified_sensitivity(
            all_of(
                *(
                    compare(
                        m,
                        {"SCM xi_c = 10": SKY_H["SCM"]},
                        {
                            "SCM xi_c = 1000": fig(
                                "4.6", "SCM", "history", controller={"xi_c": 1000.0}
                            )
                        },
                        "<",
                    )
                    for m in (max_rate("i_d"), hf_fraction("a_u"))
                ),
                *(
                    compare(
                        m,
                        {"ACM xi = 4.5": SKY_H["ACM"]},
                        {"ACM xi = 1000": fig("4.6", "ACM", "history", controller={"xi": 1000.0})},
                        "<",
                    )
                    for m in (max_rate("i_d"), hf_fraction("a_u"))
                ),
            )
        ),
        also=("8.2",),
    ),
    Claim(
        "8.2-adfg-tunable",
        "8.2",
        "The ADFG function can be easily tuned to attain desired asymmetry factor for the "
        "MR-damper force.",
        "Skyhook hi-lo (k_c = 3) at 2.5 cm / 1.5 Hz: gamma rises as p falls from 1 to 0.5 to 0.",
        monotone(
            GAMMA,
            {
                "p = 1": SKY_T["SCM"],
                "p = 0.5": fig(
                    "4.6", "SCM", controller={"law": "skyhook-hilo", "gain": 3.0, "p": 0.5}
                ),
                "p = 0": SKY_T["ACM"],
            },
        ),
        also=("4.6",),
    ),
    Claim(
        "4.6-skyhook-robust",
        "4.6",
        "has desirable robust control performance with respect to variations in the "
        "operating parameters, such as load, speed and road roughness",
        "Skyhook hi-lo ACM: peak T_as (0.5-4 Hz) varies by at most 25 % over m_s (422-703 "
        "kg), k_c (0.5-3) and n (1-3).",
        all_of(
            spread(fpeak("T_as"), M4_F, SLIGHT),
            spread(fpeak("T_as"), K4_F, SLIGHT),
            spread(fpeak("T_as"), N4_F, SLIGHT),
        ),
        also=("8.2",),
    ),
)

#: Claims of this chapter known not to hold in our model: id -> suspected cause
KNOWN: dict[str, str] = {
    "4.3.1-policy-i-resonance": "model: policies II and III damp the body mode as well as I "
    "(peak T_as about 1.7-1.8 for I, II, III); the k_c = 10 relative-velocity laws reach "
    "0.29-0.36 A, close to policy I's 0.37 A; with z_c in cm units I 1.68 against II 1.63",
    "4.3.1-dlc-i-iv": "model: policy IV's DLC is below II's and III's at only about a third "
    "of the frequencies (I's holds); IV's current stays low (0.22 A peak); with z_c in cm "
    "units (IV's peak 0.45 A) at 42 %",
    "4.3.1-policy-i-smooth": "model: policy I's current has the largest high-frequency share "
    "(0.22 against 0.10-0.17): with k_c |z_s'|^2 the current follows the body velocity, "
    "which carries the wheel-hop ripple; with z_c in cm units I's F_d is the smoothest "
    "(0.095) but its i_d (0.375) not, II's is 0.352",
    "4.3.2-compression-peaks": "reading: ACM's compression peaks exceed SCM's as stated, but "
    "by 10-44 % (x_r 44 %), more than 'slightly' (25 %)",
    "4.3.2-acm-majority": "reading: ACM's DLC is below passive 0.1 A's at exactly half of the "
    "grid, short of a majority",
    "4.3.2-road-dlc": "road presets: they are tuned to the DLCs of this very paragraph (ACM "
    "0.138, passive 0.1 A 0.111) and ours follow them (0.136 against 0.114), so the text's "
    "'lower with ACM' fails as the dissertation's own numbers do",
    "4.3.2-pulse-passive": "model: not held for any admissible decay window: the light passive "
    "damper's rms x_s after the pulse is 1.06 times the 0.1 A damper's from the pulse's end "
    "(0.80 s; 'considerably' needs 1/0.85 = 1.18) and 0.84 times it from 1 s (the 0.1 A "
    "damper's yield force leaves a slow creep); its peak |x_s| is only 3 % higher",
    "4.4.1-harmonic-insensitive": "reading: peak |a_s| varies by 12 % over m_s, just above "
    "'almost insensitive' (10 %); peak |x_s| by 9 %",
    "4.4.1-dlc-lighter-everywhere": "model: below the body resonance the heavier car has the "
    "larger DLC (the lighter car's is higher at about two thirds of the grid, from about 2 "
    "Hz up)" + _SWEPT_IN_FULL,
    "4.4.3-tas-slight": "model: the peak T_as falls with the amplitude (2.41, 2.13, 1.99 for "
    "1.5, 2.5, 3.5 cm; the MR damper's friction-like force is relatively larger at small "
    "amplitude), where the dissertation sees a slight rise",
    "4.4.3-pulse-height": "model: the peak body displacement saturates (21.4 mm at 3.5 cm, "
    "21.2 mm at 5 cm); current, a_s and F_T rise as stated",
    "4.5.1-pulse-rebound": "model: the rebound peak force over the pulse rises with k_c "
    "(1.5, 1.9, 2.3 kN for k_c = 0.5, 1.5, 3): the damper is not saturated in rebound at "
    "the 3.5 cm pulse",
    "4.6-skyhook-best-policy": "model: policy I has the lowest mean T_as and DLC but the "
    "policies II and III the lowest mean T_dr (0.77 against I's 0.90; with z_c in cm units "
    "II 0.80 against I's 0.89): I's wheel-hop stroke is larger (4.3.1-tdr-i-iv-wheel-hop)",
}
