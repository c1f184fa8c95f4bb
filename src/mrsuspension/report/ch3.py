"""Chapter 3 figures: CM current modulation (Fig 3.2), reference model (3.4), rounded
pulses (3.9) and road spectra (3.10).

Every function takes ``quick`` (coarser grids) and returns a
:class:`~mrsuspension.report.toolkit.FigureRecord` holding the figure, its caption and the
numbers a test can check. Matplotlib is imported inside the functions (Agg backend).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from mrsuspension.excitation import (
    PRESET_ROADS,
    RoundedPulse,
    iso8608_psd,
    preset_road,
    two_stage_amplitude,
)
from mrsuspension.report.toolkit import (
    Chapter,
    Context,
    FigureRecord,
    Jobs,
    figure_sections,
    subplots,
)
from mrsuspension.shaping import cm_multiplier
from mrsuspension.vehicle import QuarterCar, linear_frequency_response

__all__ = ["CHAPTER", "CHAPTER_3_FIGURES", "fig_3_2", "fig_3_4", "fig_3_9", "fig_3_10"]

#: viscous damping c_0 [N s/m] of the reference-model curves of Fig. 3.4
REFERENCE_DAMPING = (1000.0, 2500.0, 4000.0, 6000.0)
#: low-frequency amplitude of the two-stage sweep used for the DLC of Fig. 3.4 [m]
SWEEP_AMPLITUDE = 0.025


def fig_3_2(quick: bool = False) -> FigureRecord:
    """CM multiplier: controller current for a harmonic condition function (Fig. 3.2)."""
    t = np.linspace(0.0, 2.0, 401 if quick else 2001)
    z_c = np.sin(2.0 * math.pi * t)  # condition function varied harmonically
    i_z = 0.5  # on-off upper limit [A]
    fig, axes = subplots(1, 2)
    data: dict[str, Any] = {}
    for xi_c in (1.0, 10.0, 100.0):
        i_c = i_z * cm_multiplier(z_c, p_c=0.0, xi_c=xi_c)
        axes[0, 0].plot(t, i_c, label=rf"$\xi_c$ = {xi_c:g}")
        data[f"on-off xi_c={xi_c:g} range [A]"] = [float(i_c.min()), float(i_c.max())]
    axes[0, 0].set_title(r"(a) on-off: $p_c$ = 0")
    for p_c in (0.0, 0.25, 0.5):
        i_c = i_z * cm_multiplier(z_c, p_c=p_c, xi_c=10.0)
        axes[0, 1].plot(t, i_c, label=f"$p_c$ = {p_c:g}")
        data[f"hi-lo p_c={p_c:g} range [A]"] = [float(i_c.min()), float(i_c.max())]
    axes[0, 1].set_title(r"(b) hi-lo: $\xi_c$ = 10")
    for ax in axes[0]:
        ax.plot(t, 0.25 * z_c + 0.25, color="0.6", lw=0.8, ls=":", label="$z_c$ (scaled)")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("controller current $i_c$ [A]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncols=2)
    return FigureRecord(
        number="3.2",
        title="Continuous variations in the controller current of on-off or hi-lo control",
        caption=(
            "i_c = M_c(p_c, xi_c, z_c) i_z with the CM multiplier (3.8), i_z = 0.5 A and a "
            "harmonic condition function z_c = sin(2 pi t). A low xi_c smooths the switching; "
            "p_c > 0 keeps a lower current p_c i_z (hi-lo) instead of 0 (on-off)."
        ),
        figure=fig,
        data=data,
    )


def fig_3_4(quick: bool = False) -> FigureRecord:
    """Reference (modified skyhook) model frequency response vs viscous damping c_0."""
    f = np.geomspace(0.5, 15.0, 80 if quick else 400)
    car = QuarterCar.reference()
    amp = np.asarray(two_stage_amplitude(f, SWEEP_AMPLITUDE))
    fig, axes = subplots(2, 2, layout="fixed")
    panels = (("T_as", "$T_{as}$"), ("T_au", "$T_{au}$"), ("T_dr", "$T_{dr}$"), ("DLC", "DLC"))
    data: dict[str, Any] = {"frequency [Hz]": [float(v) for v in f[:: max(1, f.size // 40)]]}
    for c0 in REFERENCE_DAMPING:
        r = linear_frequency_response(car, c0, f)
        r = {**r, "DLC": r["DLC"] * amp}  # per metre of road -> two-stage sweep amplitude
        for ax, (key, label) in zip(axes.ravel(), panels, strict=True):
            ax.plot(f, r[key], label=f"$c_0$ = {c0:g} N s/m")
            ax.set_ylabel(label)
        data[f"c0={c0:g} peak T_as"] = float(r["T_as"].max())
        data[f"c0={c0:g} peak T_as frequency [Hz]"] = float(f[np.argmax(r["T_as"])])
        data[f"c0={c0:g} peak DLC"] = float(r["DLC"].max())
    for ax in axes.ravel():
        ax.set_xscale("log")
        ax.set_xlabel("frequency [Hz]")
        ax.grid(True, which="both", alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    return FigureRecord(
        number="3.4",
        title="Frequency response of the modified skyhook reference model vs viscous damping",
        caption=(
            "Exact linear response of the reference vehicle (c_sky = 6750 N s/m, section 3.3) "
            f"with a viscous damper c_0 = {', '.join(f'{c:g}' for c in REFERENCE_DAMPING)} "
            "N s/m; DLC under the two-stage sweep (a = 2.5 cm, f_T = 2.1 Hz)."
        ),
        figure=fig,
        data=data,
    )


def fig_3_9(quick: bool = False) -> FigureRecord:
    """Rounded pulse displacement: severity, peak displacement, fundamental frequency."""
    n = 300 if quick else 1500
    fig, axes = subplots(1, 3, layout="fixed", title_rows=1)
    data: dict[str, Any] = {}
    groups: list[tuple[str, list[tuple[str, RoundedPulse]]]] = [
        (
            r"(a) $a_m$ = 5 cm, $\omega_0$ = 10.4 rad/s",
            [(f"μ = {mu:g}", RoundedPulse(0.05, mu, delay=0.0)) for mu in (1.0, 2.0, 3.0)],
        ),
        (
            r"(b) μ = 3, $\omega_0$ = 10.4 rad/s",
            [
                (f"$a_m$ = {a * 100:g} cm", RoundedPulse(a, 3.0, delay=0.0))
                for a in (0.025, 0.05, 0.075)
            ],
        ),
        (
            "(c) μ = 3, $a_m$ = 5 cm",
            [
                (rf"$\omega_0$ = {w:g} rad/s", RoundedPulse(0.05, 3.0, omega0=w, delay=0.0))
                for w in (5.2, 10.4, 20.8)
            ],
        ),
    ]
    for ax, (title, pulses) in zip(axes[0], groups, strict=True):
        t = np.linspace(0.0, 2.0, n)
        for label, pulse in pulses:
            z = pulse.displacement(t)
            ax.plot(t, z * 100, label=label)
            data[f"{title[:3]} {label} peak [cm]"] = float(z.max() * 100)
            data[f"{title[:3]} {label} peak time [s]"] = float(pulse.peak_time)
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("time [s]")
        ax.set_ylabel("$z_r$ [cm]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    return FigureRecord(
        number="3.9",
        title="Rounded pulse displacement excitation",
        caption=(
            "Eq. (3.38): (a) severity mu; (b) peak displacement a_m; (c) fundamental frequency "
            "w0 (10.4 rad/s at 50 km/h, scaled with speed: erratum 9)."
        ),
        figure=fig,
        data=data,
    )


def fig_3_10(quick: bool = False) -> FigureRecord:
    """Road spectra: spatial PSDs of the presets and temporal PSDs at 50 and 100 km/h."""
    fig, axes = subplots(1, 3, layout="fixed", title_rows=1)
    data: dict[str, Any] = {}
    nn = np.geomspace(0.011, 2.83, 50)
    for name, preset in PRESET_ROADS.items():
        road = preset_road(name, 50.0)
        n, gd = road.spatial_psd(nperseg=256 if quick else 512)
        keep = n > 0
        (line,) = axes[0, 0].loglog(n[keep], gd[keep], label=name)
        band = nn[(nn >= preset.band[0]) & (nn <= preset.band[1])]
        axes[0, 0].loglog(band, preset.spectrum.density(band), "--", color=line.get_color(), lw=0.8)
        data[f"{name} Gd(n0) [m^3]"] = preset.level
        data[f"{name} rms elevation [mm]"] = road.rms_elevation * 1e3
        data[f"{name} peak elevation [mm]"] = road.peak_elevation * 1e3
        for col, speed in ((1, 50.0), (2, 100.0)):
            v = speed / 3.6
            f, g = n[keep] * v, gd[keep] / v  # G(f) = Gd(n) / V at f = n V
            axes[0, col].loglog(f, g, label=name)
            data[f"{name} {speed:g} km/h PSD max frequency [Hz]"] = float(f.max())
            data[f"{name} {speed:g} km/h variance [mm^2]"] = float(np.sum(g[1:] * np.diff(f)) * 1e6)
    for cls in ("A", "B"):
        axes[0, 0].loglog(nn, iso8608_psd(cls, nn), "k--" if cls == "A" else "k:", lw=0.8,
                          label=f"ISO 8608 class {cls}")  # fmt: skip
    axes[0, 0].set_xlabel("spatial frequency n [cycle/m]")
    axes[0, 0].set_ylabel("$G_d(n)$ [m$^3$]")
    axes[0, 0].set_title("(a) spatial PSD of the road profiles", fontsize=9)
    for col, speed in ((1, 50.0), (2, 100.0)):
        axes[0, col].set_xlabel("frequency [Hz]")
        axes[0, col].set_ylabel("$G(f)$ [m$^2$/Hz]")
        axes[0, col].set_title(f"({'bc'[col - 1]}) PSD at {speed:g} km/h", fontsize=9)
    for ax in axes[0]:
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    return FigureRecord(
        number="3.10",
        title="Road profile spectra and the influence of vehicle speed",
        caption=(
            "Preset roads: stand-ins for the dissertation's measured roads (not available), "
            "each defined by its PSD G_d(n) = G_d(n0) (n/0.1)^-1 over 0.011-2 cycle/m "
            "(dashed; model reference, section 8(c)), G_d(n0) tuned against the dissertation's "
            "DLCs, "
            "synthesised with random phases (500 m at 0.3 m: content up to 1.67 cycle/m). "
            "Temporal PSD G(f) = G_d(n)/V at f = nV: with the n^-1 slope, doubling the "
            "speed spreads the spectrum over twice the frequencies at the same level."
        ),
        figure=fig,
        data=data,
    )


#: The chapter's figure builders, in report order (each takes ``quick``).
CHAPTER_3_FIGURES: tuple[Callable[[bool], FigureRecord], ...] = (
    fig_3_2,
    fig_3_4,
    fig_3_9,
    fig_3_10,
)


def _jobs(quick: bool) -> Jobs:
    return Jobs(specials=[("chapter3", b, quick) for b in CHAPTER_3_FIGURES])


def _build(context: Context) -> tuple[str, dict[str, Any]]:
    sections, records = figure_sections(3, context.built.figures, context.folder)
    body = (
        "<h2 id='ch3'>Chapter 3: semi-active control synthesis, reference model and "
        "excitations</h2>" + "".join(sections)
    )
    return body, {"figures": records, "tables": []}


#: The chapter's entry in the report (:data:`mrsuspension.report.chapters.CHAPTERS`)
CHAPTER = Chapter(3, _jobs, _build)
