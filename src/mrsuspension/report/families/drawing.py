"""Rendering: :func:`render` draws a figure family from its units' payloads (one renderer
per kind), notes a velocity clamp in the caption (:func:`clamp_note`), saves the files and
returns the figure's manifest record; ``_build_special`` does the same for a figure
function that simulates and draws itself.

Both run in the report's worker processes
(:func:`~mrsuspension.report.families.pool.build_all` sends them there by module path).
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from mrsuspension.report.families.run import CLAMP_KEY, _finite
from mrsuspension.report.families.spec import FREQ_PANELS, PSD_SIGNALS, SIGNALS, FigureSpec
from mrsuspension.report.toolkit import (
    SHOCK,
    FigureRecord,
    figure_legend,
    label_outer_x,
    legend_columns,
    reused_subplots,
    share_x,
)


def _subplots(rows: int, cols: int, labels: Sequence[str], key: Any) -> tuple[Any, Any]:
    """The family figures' panel grid: 3.3 x 2.5 in panels with fixed margins, and a strip
    for the legend of ``labels`` between the title and the panels (off the data); one
    figure per ``key`` (the family and its panels) and shape, reused
    (:func:`~mrsuspension.report.toolkit.reused_subplots`)."""
    per_row = legend_columns(labels, 3.3 * cols)
    legend_rows = -(-len(labels) // per_row)
    return reused_subplots(
        (key, rows, cols, legend_rows), rows, cols, 3.3, 2.5, legend_rows=legend_rows
    )


def _grid(n: int) -> tuple[int, int]:
    if n <= 3:
        return 1, n
    if n == 4:
        return 2, 2
    return 2, (n + 1) // 2


def _style(label: str) -> str:
    return "--" if label.startswith("passive") else "-"


def _render_histories(
    spec: FigureSpec, payloads: Mapping[str, dict[str, Any]]
) -> tuple[Any, dict[str, Any]]:
    rows, cols = _grid(len(spec.signals))
    fig, axes = _subplots(rows, cols, list(payloads), ("histories", len(spec.signals)))
    flat = axes.ravel()
    share_x(flat[: len(spec.signals)])
    data: dict[str, Any] = {}
    every = 10
    for label, p in payloads.items():
        t = p["time"]
        data[f"time {label} [s]"] = [round(float(v), 4) for v in t[::every]]
        for ax, name in zip(flat, spec.signals, strict=False):
            ax.set_ylabel(SIGNALS[name][1])
            if name not in p:
                continue
            ax.plot(t, p[name], _style(label), lw=1, label=label)
            data[f"peak |{name}| {label}"] = p[f"peak {name}"]
            data[f"{name} {label}"] = _finite(p[name][::every])
        if spec.kind == "time":
            data[f"mean current {label} [A]"] = p["mean current [A]"]
            data[f"gamma (rebound/compression peak force) {label}"] = p["gamma"]
            data[f"max |di_d| per ms {label} [A]"] = p["max |di_d| per ms [A]"]
            if "force-tracking error [N]" in p:
                data[f"force-tracking error {label} [N]"] = p["force-tracking error [N]"]
        else:
            for k in (*SHOCK, "peak_tire_force"):
                data[f"{k} {label}"] = p[k]
            data["road_peak (SAR_s, SAR_u denominator)"] = p.get("road_peak", "after-onset")
    for ax in flat[len(spec.signals) :]:
        ax.set_visible(False)
    for ax in flat[: len(spec.signals)]:
        ax.set_xlabel("time [s]")
        ax.grid(True, alpha=0.3)
    label_outer_x(axes)
    figure_legend(fig, flat[0])
    return fig, data


def _render_freq(
    spec: FigureSpec, payloads: Mapping[str, dict[str, Any]]
) -> tuple[Any, dict[str, Any]]:
    fig, axes = _subplots(2, 2, list(payloads), "freq")
    share_x(axes.ravel())
    data: dict[str, Any] = {}
    for label, p in payloads.items():
        f = p["frequency"]
        data.setdefault("frequency [Hz]", _finite(f))
        for ax, (key, ylabel) in zip(axes.ravel(), FREQ_PANELS, strict=True):
            ax.plot(f, p[key], _style(label), marker="o", ms=3, label=label)
            ax.set_ylabel(ylabel)
            data[f"{key} {label}"] = _finite(p[key])
        body = (f >= 0.5) & (f <= 4.0)
        k = int(np.argmax(np.where(body, p["T_as"], -np.inf)))
        data[f"peak T_as {label}"] = float(p["T_as"][k])
        data[f"peak T_as frequency {label} [Hz]"] = float(f[k])
    from matplotlib.ticker import FixedLocator, FormatStrFormatter, NullLocator

    for ax in axes.ravel():
        ax.set_xscale("log")
        # labelled ticks at 0.5-10 Hz, no minor ticks (cheaper to draw, easier to read)
        ax.xaxis.set_major_locator(FixedLocator([0.5, 1, 2, 5, 10]))
        ax.xaxis.set_major_formatter(FormatStrFormatter("%g"))
        ax.xaxis.set_minor_locator(NullLocator())
        ax.set_xlabel("frequency [Hz]")
        ax.grid(True, alpha=0.3)
    label_outer_x(axes)
    figure_legend(fig, axes[0, 0])
    return fig, data


def _render_psd(
    spec: FigureSpec, payloads: Mapping[str, dict[str, Any]]
) -> tuple[Any, dict[str, Any]]:
    fig, axes = _subplots(2, 3, list(payloads), "psd")
    flat = axes.ravel()
    share_x(flat[:5])
    data: dict[str, Any] = {}
    for label, p in payloads.items():
        f = p["frequency"]
        keep = f <= 20.0
        data.setdefault("PSD frequency [Hz]", _finite(f[keep][::4]))
        for ax, name in zip(flat, PSD_SIGNALS, strict=False):
            ax.loglog(f, p[f"PSD {name}"], _style(label), lw=1, label=label)
            symbol, unit = SIGNALS[name][1].rstrip("]").split(" [")
            ax.set_ylabel(f"PSD {symbol} [({unit})$^2$/Hz]")
            data[f"PSD {name} {label}"] = _finite(p[f"PSD {name}"][keep][::4])
        flat[5].plot(p["time"], p["i_d"], lw=0.6, label=label)
        data[f"road DLC model {label}"] = p["DLC"]
        data[f"road DLC dissertation {label}"] = spec.given.get(label, "not given")
        data[f"rms a_s {label} [m/s^2]"] = p["rms a_s [m/s^2]"]
        data[f"mean current {label} [A]"] = p["mean current [A]"]
        ride = (f >= 2.0) & (f <= 8.0)
        data[f"mean PSD a_s 2-8 Hz {label} [(m/s^2)^2/Hz]"] = float(np.mean(p["PSD a_s"][ride]))
    from matplotlib.ticker import LogLocator, NullLocator

    for ax in flat[:5]:
        ax.set_xlabel("frequency [Hz]")
        # PSDs span many decades: hundreds of minor ticks would cost seconds to draw
        ax.yaxis.set_major_locator(LogLocator(numticks=5))
        ax.yaxis.set_minor_locator(NullLocator())
        ax.xaxis.set_minor_locator(NullLocator())
        ax.grid(True, alpha=0.3)
    flat[5].set_xlabel("time [s]")
    flat[5].set_ylabel("$i_d$ [A]")
    label_outer_x(axes)
    figure_legend(fig, flat[0])
    return fig, data


_RENDERERS = {"time": _render_histories, "pulse": _render_histories, "freq": _render_freq}


def clamp_note(payloads: Mapping[str, Mapping[str, Any]], data: dict[str, Any]) -> str:
    """Record each variant's time at the v_m clamp in ``data``; a caption note when large.

    Model reference, section 2.4: beyond its identified velocity range the damper model is an
    extrapolation, and a figure that goes there says so.
    """
    from mrsuspension.engine.result import CLAMP_WARN_FRACTION

    hit = {}
    for label, payload in payloads.items():
        share = float(payload.get(CLAMP_KEY, 0.0))
        data[f"{CLAMP_KEY} {label}"] = round(share, 2)
        if share > 100.0 * CLAMP_WARN_FRACTION:
            hit[label] = share
    if not hit:
        return ""
    where = ", ".join(f"{k} {v:.0f} %" for k, v in hit.items())
    return (
        f" Note: the peak-velocity estimate v_m sat at its upper clamp (the identified range, "
        f"0.75 m/s) for part of a run ({where}; largest share per run): there the damper "
        "model is an extrapolation."
    )


def render(
    spec: FigureSpec,
    payloads: Mapping[str, dict[str, Any]],
    folder: Path,
    formats: Sequence[str],
    check: bool = False,
) -> dict[str, Any]:
    """Draw ``spec`` from its units' payloads, save it and return its manifest record.

    Parameters
    ----------
    spec : FigureSpec
        A non-special figure.
    payloads : mapping
        Variant label -> :func:`run_unit` output.
    folder : Path
        Where the files go.
    formats : sequence of str
        ``("png",)`` or ``("png", "svg")``.
    check : bool
        Also record the figure's ``layout issues``
        (:func:`~mrsuspension.report.legibility.layout_issues`).

    Returns
    -------
    dict
        ``number``, ``title``, ``caption``, ``files``, ``data`` (with the scenario of each
        variant under ``scenario <label>``) and ``render time [s]``.
    """
    start, cpu = time.perf_counter(), time.process_time()
    draw = _RENDERERS.get(spec.kind, _render_psd)
    fig, data = draw(spec, payloads)
    for label in spec.variants:
        data[f"scenario {label}"] = json.dumps(spec.scenario(label), sort_keys=True)
    rec = FigureRecord(
        spec.number, spec.title, spec.caption + clamp_note(payloads, data), fig, data
    )
    simulated = sum(p["run time [s]"] for p in payloads.values())
    return _saved(rec, folder, formats, start, cpu, round(simulated, 3), check)


def _build_special(
    builder: Callable[..., Any],
    quick: bool | None,
    folder: Path,
    formats: Sequence[str],
    check: bool = False,
) -> dict[str, Any]:
    """Run a figure function (``builder(quick)``, or ``builder()`` if quick is None) and save."""
    start, cpu = time.perf_counter(), time.process_time()
    rec = builder() if quick is None else builder(quick)
    return _saved(rec, folder, formats, start, cpu, 0.0, check)


def _saved(
    rec: FigureRecord,
    folder: Path,
    formats: Sequence[str],
    start: float,
    cpu: float,
    simulated: float,
    check: bool = False,
) -> dict[str, Any]:
    """Save ``rec`` and return its manifest entry, timed from ``start`` (wall) and ``cpu``."""
    rec.save(folder, formats, check=check)
    extra = {} if rec.issues is None else {"layout issues": rec.issues}
    return {
        "number": rec.number,
        "title": rec.title,
        "caption": rec.caption,
        "files": rec.files,
        "data": rec.data,
        "render time [s]": round(time.perf_counter() - start, 3),
        "render cpu time [s]": round(time.process_time() - cpu, 3),
        "simulation time [s]": simulated,
        **extra,
    }
