"""Chapter 2 figures: model loops (Figs 2.3-2.5, 2.8, 2.9, 2.11), ADFG (2.6-2.7), inverse (2.10).

The dissertation's Figs 2.3-2.5 and 2.8 show *measured* loops; the measurements are not
available, so these figures show the identified models under the same test conditions.
Every function returns a :class:`~mrsuspension.report.toolkit.FigureRecord` holding the
figure, its caption and the numbers a test can check.
"""

from __future__ import annotations

import html
import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from mrsuspension.characterisation import HarmonicLoop, harmonic_loop
from mrsuspension.dampers import (
    DAMPERS,
    KnownPeak,
    WangAsymmetric,
    WangSymmetric,
    make_damper,
)
from mrsuspension.dampers.wang import CHARACTERISATION_VH
from mrsuspension.report.toolkit import (
    Chapter,
    Context,
    FigureRecord,
    Jobs,
    figure_legend,
    figure_sections,
    side_legend,
    subplots,
    table,
    write_csv,
)
from mrsuspension.shaping import adfg_multiplier, onoff_adfg_current

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = ["CHAPTER", "CHAPTER_2_FIGURES", "band_model", "table_2_1_rows"]

_CURRENTS = (0.0, 0.1, 0.2, 0.3, 0.4)


def band_model(frequency: float, **options: Any) -> WangSymmetric:
    """The symmetric model with the Table 2.2 set of the frequency band (<= 5 Hz: low)."""
    name = "wang-symmetric-low" if frequency <= 5.0 else "wang-symmetric-high"
    return WangSymmetric(name, **{"vh_variant": CHARACTERISATION_VH, **options})


def _loop_axes(ax: Axes, kind: str = "F-v") -> None:
    from matplotlib.ticker import MaxNLocator

    # at most 5 labelled ticks: labels like "-0.075" collide in a 4.2 in panel
    ax.xaxis.set_major_locator(MaxNLocator(nbins=5))
    if kind == "F-v":
        ax.set_xlabel("velocity $v_d$ [m/s]")
    else:
        ax.set_xlabel("stroke $x_d$ [mm]")
    ax.set_ylabel("force $F_d$ [N]")
    ax.grid(True, alpha=0.3)
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.axvline(0.0, color="0.6", lw=0.6)


def _plot_loops(ax: Axes, loops: Sequence[HarmonicLoop], labels: Sequence[str], kind: str) -> None:
    for loop, label in zip(loops, labels, strict=True):
        x = loop.velocity if kind == "F-v" else loop.stroke * 1e3
        ax.plot(np.append(x, x[0]), np.append(loop.force, loop.force[0]), label=label, lw=1.3)
    _loop_axes(ax, kind)


def _peaks(loops: Sequence[HarmonicLoop]) -> list[float]:
    return [float(np.max(np.abs(loop.force))) for loop in loops]


def fig_2_3() -> FigureRecord:
    """Model F-v and F-x loops under different drive currents and excitations."""
    conditions = [(0.5, 0.025), (1.5, 0.0125), (2.5, 0.0125)]
    fig, axes = subplots(2, len(conditions), layout="fixed", title_rows=1)
    data: dict[str, Any] = {}
    for col, (f, a) in enumerate(conditions):
        model = band_model(f)
        loops = [harmonic_loop(model, f, a, i) for i in _CURRENTS]
        labels = [f"{i:g} A" for i in _CURRENTS]
        _plot_loops(axes[0, col], loops, labels, "F-v")
        _plot_loops(axes[1, col], loops, labels, "F-x")
        axes[0, col].set_title(f"({'abc'[col]}) f = {f:g} Hz, $a_m$ = {a * 1e3:g} mm")
        data[f"{f:g} Hz, {a * 1e3:g} mm peak |F| [N]"] = _peaks(loops)
    axes[0, 0].legend(title="current", fontsize=8)
    return FigureRecord(
        number="2.3",
        title="F-v and F-x characteristics under different drive currents and excitations",
        caption=(
            "Symmetric hysteretic model (2.15), Table 2.2 0.5-5 Hz set, v_h of (2.12), known "
            "peak velocity 2 pi f a_m; drive currents 0-0.4 A (Table 2.1). Loops run "
            "counter-clockwise in F-v. The dissertation's figure shows measured loops."
        ),
        figure=fig,
        data=data,
    )


def fig_2_4() -> FigureRecord:
    """Model loops at 2.5 mm under different frequencies and currents."""
    freqs = (0.5, 1.5, 2.5, 5.0, 7.5, 10.0, 12.5, 15.0)
    currents = (0.0, 0.2, 0.4)
    fig, axes = subplots(1, len(currents), layout="fixed", title_rows=1)
    data: dict[str, Any] = {}
    for col, i in enumerate(currents):
        loops = [harmonic_loop(band_model(f), f, 0.0025, i) for f in freqs]
        _plot_loops(axes[0, col], loops, [f"{f:g} Hz" for f in freqs], "F-v")
        axes[0, col].set_title(f"({'abc'[col]}) $i_d$ = {i:g} A, $a_m$ = 2.5 mm")
        data[f"{i:g} A peak |F| [N]"] = _peaks(loops)
    axes[0, 0].legend(fontsize=7, ncols=2)
    return FigureRecord(
        number="2.4",
        title="F-v characteristics under different excitation frequencies and drive currents (a_m = 2.5 mm)",
        caption=(
            "Symmetric model (2.15) with the Table 2.2 set of each frequency band "
            "(0.5-5 Hz set up to 5 Hz, 5-15 Hz set above), known peak velocity."
        ),
        figure=fig,
        data=data,
    )


def fig_2_5() -> FigureRecord:
    """Model loops at 0.5 Hz under different amplitudes and currents."""
    amps = (0.0025, 0.0125, 0.025, 0.05, 0.075)
    currents = (0.0, 0.2, 0.4)
    fig, axes = subplots(1, len(currents), layout="fixed", title_rows=1)
    model = band_model(0.5)
    data: dict[str, Any] = {}
    for col, i in enumerate(currents):
        loops = [harmonic_loop(model, 0.5, a, i) for a in amps]
        _plot_loops(axes[0, col], loops, [f"{a * 1e3:g} mm" for a in amps], "F-v")
        axes[0, col].set_title(f"({'abc'[col]}) $i_d$ = {i:g} A, f = 0.5 Hz")
        data[f"{i:g} A peak |F| [N]"] = _peaks(loops)
    axes[0, 0].legend(fontsize=8)
    return FigureRecord(
        number="2.5",
        title="F-v characteristics under different excitation amplitudes and drive currents (f = 0.5 Hz)",
        caption="Symmetric model (2.15), Table 2.2 0.5-5 Hz set, known peak velocity.",
        figure=fig,
        data=data,
    )


def fig_2_6() -> FigureRecord:
    """ADFG multiplier M_p against v_d/v_m."""
    ratio = np.linspace(-2.0, 2.0, 801)
    fig, axes = subplots(1, 2, layout="fixed", title_rows=1)
    data: dict[str, Any] = {}
    for p in (0.0, 0.25, 0.5, 1.0):
        m = adfg_multiplier(ratio, 1.0, p=p, xi=2.0)
        axes[0, 0].plot(ratio, m, label=f"p = {p:g}")
        data[f"M_p range p={p:g}"] = [float(m.min()), float(m.max())]
    axes[0, 0].plot(
        ratio, onoff_adfg_current(1.0, ratio, p=0.0), "k--", lw=1, label="on-off (2.1), p = 0"
    )
    axes[0, 0].set_title(r"(a) $\xi$ = 2")
    for xi in (0.5, 2.0, 5.0, 20.0):
        axes[0, 1].plot(ratio, adfg_multiplier(ratio, 1.0, p=0.0, xi=xi), label=f"ξ = {xi:g}")
    axes[0, 1].set_title("(b) p = 0")
    for ax in axes[0]:
        ax.set_xlabel("$v_d / v_m$ (compression > 0)")
        ax.set_ylabel("multiplier $M_p$")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    return FigureRecord(
        number="2.6",
        title="Modulation of command current with velocity to achieve asymmetric damping",
        caption=(
            "ADFG multiplier (2.3): i_d = M_p i_c moves smoothly from i_c in rebound to p i_c "
            "in compression; the dashed line is the on-off law (2.1)."
        ),
        figure=fig,
        data=data,
    )


def fig_2_7() -> FigureRecord:
    """Symmetric, on-off and ADFG drive currents for a sinusoidal control current."""
    t = np.linspace(0.0, 2.0, 2001)
    w = 3.0 * math.pi
    i_c = 0.25 + 0.2 * np.sin(w * t)
    v = 0.025 * w * np.cos(w * t)  # x_d = 2.5 sin(3 pi t) cm, as in Fig. 2.10
    vm = 0.025 * w
    i_s = onoff_adfg_current(i_c, v, p=0.0)
    i_d = adfg_multiplier(v, vm, p=0.0, xi=2.0) * i_c
    fig, axes = subplots(1, 1, width=8.0, height=3.6)
    ax = axes[0, 0]
    ax.plot(t, i_c, label="symmetric $i_c$")
    ax.plot(t, i_s, "--", label="on-off $i_s$ (2.1)")
    ax.plot(t, i_d, label=r"ADFG $i_d$ (2.2)-(2.3), p = 0, $\xi$ = 2")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("current [A]")
    ax.grid(True, alpha=0.3)
    ax2 = ax.twinx()
    ax2.plot(t, v, color="0.5", lw=0.8, label="$v_d$")
    ax2.set_ylabel("velocity $v_d$ [m/s]")
    figure_legend(fig, ax, fontsize=8)
    return FigureRecord(
        number="2.7",
        title="Modulation of command current: symmetric, on-off and ADFG",
        caption=(
            "i_c = 0.25 + 0.2 sin(3 pi t) A, p = 0, xi = 2. The velocity signal is not given "
            "in the dissertation; we use x_d = 2.5 sin(3 pi t) cm (as in Fig. 2.10). The ADFG "
            "current has no jump at v_d = 0 and no phase lag."
        ),
        figure=fig,
        data={
            "max |di_s| per sample [A]": float(np.max(np.abs(np.diff(i_s)))),
            "max |di_d| per sample [A]": float(np.max(np.abs(np.diff(i_d)))),
        },
    )


def fig_2_8() -> FigureRecord:
    """Asymmetric loops: the asymmetric model, and the symmetric model through ADFG."""
    conditions = [(0.5, 0.025), (1.5, 0.0125)]
    currents = (0.0, 0.1, 0.2, 0.3)
    fig, axes = subplots(2, len(conditions), layout="fixed", title_rows=1)
    asym = WangAsymmetric(vh_variant=CHARACTERISATION_VH)
    sym = WangSymmetric(vh_variant=CHARACTERISATION_VH)

    def adfg(v: np.ndarray, vm: np.ndarray, i_c: float) -> np.ndarray:
        return adfg_multiplier(v, vm, p=0.0, xi=2.0) * i_c

    data: dict[str, Any] = {}
    for col, (f, a) in enumerate(conditions):
        loops_a = [harmonic_loop(asym, f, a, i) for i in currents]
        loops_s = [harmonic_loop(sym, f, a, i, current_shaping=adfg) for i in currents]
        labels = [f"{i:g} A" for i in currents]
        _plot_loops(axes[0, col], loops_a, labels, "F-v")
        _plot_loops(axes[1, col], loops_s, labels, "F-v")
        axes[0, col].set_title(
            f"({'ab'[col]}) asymmetric model; {f:g} Hz, {a * 1e3:g} mm", fontsize=10
        )
        axes[1, col].set_title(
            f"({'cd'[col]}) symmetric + ADFG (p = 0, ξ = 2)\n{f:g} Hz, {a * 1e3:g} mm", fontsize=10
        )
        data[f"gamma asymmetric model {f:g} Hz"] = [
            lp.max_rebound_force / lp.max_compression_force for lp in loops_a
        ]
        data[f"gamma symmetric+ADFG {f:g} Hz"] = [
            lp.max_rebound_force / lp.max_compression_force for lp in loops_s
        ]
    axes[0, 0].legend(title="current", fontsize=8)
    return FigureRecord(
        number="2.8",
        title="Asymmetric F-v characteristics under different control conditions",
        caption=(
            "Top: the asymmetric model (2.19)-(2.21) with Table 2.3. Bottom: the symmetric "
            "model driven through the ADFG algorithm (p = 0, xi = 2), the way the asymmetric "
            "data were measured. The dissertation's figure shows measured loops; it reports "
            "a rebound/compression ratio gamma of about 4 at low velocity and about 2 at 0.3 A."
        ),
        figure=fig,
        data=data,
    )


def _generalised(model: WangSymmetric, number: str, title: str) -> FigureRecord:
    f, a, i = 1.5, 0.0125, 0.2
    hyst = harmonic_loop(model, f, a, i)
    mean = harmonic_loop(model.with_options(hysteresis=False), f, a, i)
    fig, axes = subplots(1, 1, width=6.0, height=4.2)
    ax = axes[0, 0]
    ax.plot(
        np.append(hyst.velocity, hyst.velocity[0]),
        np.append(hyst.force, hyst.force[0]),
        label="hysteretic",
    )
    order = np.argsort(mean.velocity)
    ax.plot(mean.velocity[order], mean.force[order], "k", lw=2.2, label="mean ($k_4$ = 0)")
    vm = hyst.peak_velocity
    fh = float(model.force(0.0, 0.0, -1.0, i, peak_velocity=vm))  # zero-velocity force intercept
    ax.plot([0.0], [fh], "o", color="C3")
    ax.annotate("$F_h$ (v = 0, decreasing v)", (0.0, fh), textcoords="offset points", xytext=(8, 8))
    _loop_axes(ax)
    side_legend(ax)
    return FigureRecord(
        number=number,
        title=title,
        caption=(
            f"{type(model).__name__} ({model.parameters.name}) at {f:g} Hz, {a * 1e3:g} mm, "
            f"{i:g} A. The upper branch belongs to decreasing velocity (k4 < 0); the mean "
            "curve is the model with k4 = 0."
        ),
        figure=fig,
        data={
            "zero-velocity force intercept [N]": fh,
            "hysteretic peak |F| [N]": float(np.max(np.abs(hyst.force))),
            "mean peak |F| [N]": float(np.max(np.abs(mean.force))),
        },
    )


def fig_2_9() -> FigureRecord:
    """Generalised hysteretic F-v curve with its mean curve (symmetric model)."""
    return _generalised(
        WangSymmetric(vh_variant=CHARACTERISATION_VH),
        "2.9",
        "Generalized hysteretic F-v curve (hysteretic and mean)",
    )


def fig_2_11() -> FigureRecord:
    """Generalised asymmetric F-v curve with its mean curve."""
    return _generalised(
        WangAsymmetric(vh_variant=CHARACTERISATION_VH),
        "2.11",
        "Generalized asymmetric F-v characteristics (hysteretic and mean)",
    )


def fig_2_10() -> FigureRecord:
    """Inverse-model check: i_d recovered from F_d."""
    t = np.linspace(0.0, 2.0, 2001)
    w = 3.0 * math.pi
    i_d = 0.25 + 0.2 * np.sin(w * t)
    x = 0.025 * np.sin(w * t)
    v = 0.025 * w * np.cos(w * t)
    a = -0.025 * w * w * np.sin(w * t)
    vm = 0.025 * w
    model = WangSymmetric(hysteresis=False, vh_variant="2.13", estimator=KnownPeak(vm))
    f_d = model.force(x, v, a, i_d)
    i_z = model.inverse_current(f_d, v, a, stroke=x)
    f_h = model.passive_hysteron(v, a, stroke=x)
    err = np.abs(i_d - i_z)
    fig, axes = subplots(3, 1, width=8.0, height=2.4)
    axes[0, 0].plot(t, i_d, label="$i_d$")
    axes[0, 0].plot(t, i_z, "--", label="$i_z$ (inverse)")
    axes[0, 0].set_ylabel("current [A]")
    side_legend(axes[0, 0], fontsize=8)
    axes[1, 0].semilogy(t, np.maximum(err, 1e-18))
    axes[1, 0].set_ylabel("$e_i = |i_d - i_z|$ [A]")
    axes[2, 0].plot(t, f_h, label="$F_h$ (passive hysteron)")
    axes[2, 0].plot(t, f_d, label="$F_d$")
    axes[2, 0].set_ylabel("force [N]")
    side_legend(axes[2, 0], fontsize=8)
    for ax in axes[:, 0]:
        ax.grid(True, alpha=0.3)
    axes[2, 0].set_xlabel("time [s]")
    return FigureRecord(
        number="2.10",
        title="Validity of inverse model, and variations in the hysteron and the damping force",
        caption=(
            "i_d = 0.25 + 0.2 sin(3 pi t) A, x_d = 2.5 sin(3 pi t) cm, mean model with v_h of "
            f"(2.13). The inverse (model reference, section 2.3) recovers the current to max e_i = "
            f"{err.max():.1e} A; F_d stays in phase with F_h."
        ),
        figure=fig,
        data={"max inverse error [A]": float(err.max())},
    )


def fig_models() -> FigureRecord:
    """Every damper model of the toolkit under the same test (beyond the dissertation)."""
    f, a = 1.5, 0.0125
    fig, axes = subplots(1, 2, layout="fixed", title_rows=1)
    data: dict[str, Any] = {}
    for col, i in enumerate((0.0, 0.4)):
        loops, labels = [], []
        for name in DAMPERS:
            loops.append(harmonic_loop(make_damper(name), f, a, i))
            labels.append(name)
        _plot_loops(axes[0, col], loops, labels, "F-v")
        axes[0, col].set_title(f"{f:g} Hz, {a * 1e3:g} mm, {i:g} A")
        data[f"peak |F| at {i:g} A [N]"] = dict(zip(labels, _peaks(loops), strict=True))
    axes[0, 0].legend(fontsize=8)
    return FigureRecord(
        number="2.M",
        title="Peer damper models under the same harmonic test",
        caption=(
            "Dissertation's symmetric and asymmetric models, Bingham (fitted to the symmetric "
            "model), Spencer et al. (1997) modified Bouc-Wen (current mapped to voltage at "
            "4.5 V/A) and a 2500 N s/m linear damper. Not in the dissertation."
        ),
        figure=fig,
        data=data,
    )


#: The chapter's figure builders, in report order.
CHAPTER_2_FIGURES: tuple[Callable[[], FigureRecord], ...] = (
    fig_2_3,
    fig_2_4,
    fig_2_5,
    fig_2_6,
    fig_2_7,
    fig_2_8,
    fig_2_9,
    fig_2_10,
    fig_2_11,
    fig_models,
)


def table_2_1_rows(quick: bool) -> list[dict[str, Any]]:
    """Table 2.1's test matrix on the symmetric model (both frequency bands), sorted."""
    from mrsuspension.characterisation import characterise, table_2_1

    conds = table_2_1() if not quick else table_2_1(frequencies=[0.5, 1.5, 5.0, 15.0])
    result = characterise(band_model(0.5), [c for c in conds if c.frequency <= 5.0])
    result_hi = characterise(band_model(7.5), [c for c in conds if c.frequency > 5.0])
    rows: list[dict[str, Any]] = result.summary_rows() + result_hi.summary_rows()
    rows.sort(key=lambda r: (r["amplitude [m]"], r["frequency [Hz]"], r["current [A]"]))
    return rows


def _jobs(quick: bool) -> Jobs:
    return Jobs(
        specials=[("chapter2", b, None) for b in CHAPTER_2_FIGURES],
        calls={"table 2.1": (table_2_1_rows, (quick,))},
    )


def _build(context: Context) -> tuple[str, dict[str, Any]]:
    """The chapter's section: figures, the Table 2.1 matrix, parameter sets, errata."""
    from mrsuspension import parameters
    from mrsuspension.errata import ERRATA

    folder, quick = context.folder, context.quick
    sections, records = figure_sections(2, context.built.figures, folder)
    manifest: dict[str, Any] = {"figures": records, "tables": []}
    rows = context.built.calls["table 2.1"]
    folder.mkdir(parents=True, exist_ok=True)
    write_csv(folder / "table_2_1_model.csv", rows)
    manifest["tables"].append(
        {"number": "2.1", "file": "chapter2/table_2_1_model.csv", "rows": len(rows)}
    )
    ptables = []
    for name in ("wang-symmetric-low", "wang-symmetric-high", "wang-asymmetric"):
        p = parameters.get(name)
        ptables.append(
            f"<h3>{html.escape(name)} (Table {p.table})</h3><p class='meta'>"
            f"{html.escape(p.source)}</p>"
            + table(
                [{"parameter": k, "value": v, "unit": p.units.get(k, "")} for k, v in p.items()]
            )
        )
    errata = table(
        [
            {
                "#": e.number,
                "where": e.location,
                "dissertation": e.printed,
                "mrsuspension": e.correction,
            }
            for e in ERRATA
        ]
    )
    body = (
        "<h2 id='ch2'>Chapter 2: characterisation and modelling of the MR damper</h2>"
        + "".join(sections)
        + f"<h3>Table 2.1 test matrix on the model ({len(rows)} tests)</h3>"
        "<p>Peak forces, energy per cycle and equivalent damping of every test, with the "
        "Table 2.2 set of each frequency band: "
        "<a href='chapter2/table_2_1_model.csv'>table_2_1_model.csv</a>. Tests far outside "
        "the identified velocity range (about 0.05-0.75 m/s) extrapolate the exponential "
        "transition force (2.7) and give unphysically large forces.</p>"
        + table(
            [r for r in rows if r["current [A]"] in (0.0, 0.4)][:: 1 if quick else 2], fmt="{:.4g}"
        )
        + "<h3>Parameter sets</h3>"
        + "".join(ptables)
        + "<h3>Errata applied (model reference, section 12)</h3>"
        + errata
    )
    return body, manifest


#: The chapter's entry in the report (:data:`mrsuspension.report.chapters.CHAPTERS`)
CHAPTER = Chapter(2, _jobs, _build)
