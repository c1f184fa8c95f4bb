"""Chapter 7: the figures and page of ``mrsus hil validate`` (HiL against offline).

The comparisons run in :mod:`mrsuspension.hil.chapter7`
(:func:`~mrsuspension.hil.chapter7.validate_chapter7`: the HiL and offline runs, frequency
responses, shock ratios, PSDs, ``validation.json``); this module draws them and writes the
``index.html`` page (Figs 7.9-7.11 and 7.14-7.21; the time histories and F-v loops of Figs
7.7, 7.8, 7.12-7.14 are drawn by :mod:`mrsuspension.hil.validate`).
:func:`validate_chapter7` here is the same call with the figures and the page: ``hil``
never imports the report, the report hands ``hil`` its :func:`render`.

Chapter 7 is not a chapter of ``mrsus reproduce`` (it needs a rig), so it has no
``CHAPTER`` entry in :mod:`mrsuspension.report.chapters`.
"""

from __future__ import annotations

import html
import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

from mrsuspension.hil.chapter7 import FREQUENCY_MEASURES, PSD_CHANNELS, mass_tag
from mrsuspension.hil.chapter7 import validate_chapter7 as _validate
from mrsuspension.report.toolkit import format_number, save_figure, table

if TYPE_CHECKING:
    from mrsuspension.engine.simulate import Simulation
    from mrsuspension.hil.rig import Rig

__all__ = ["draw_figures", "index_page", "render", "validate_chapter7"]


def validate_chapter7(
    sim: Simulation, rig: Rig, out: str | Path | None = None, **options: Any
) -> dict[str, Any]:
    """The Chapter 7 comparisons, with their figures and ``index.html`` in ``out``.

    :func:`mrsuspension.hil.chapter7.validate_chapter7` with :func:`render`: the same
    keywords (``what``, ``cases``, ``frequencies``, ``amplitude``, ``duration``,
    ``road_duration``, ``rate``, ``model_dt``, ``limits``, ``realtime``, ``masses``) and
    the same numbers. ``mrsus hil validate`` calls this one.

    Parameters
    ----------
    sim : Simulation
        The scenario.
    rig : Rig
        The rig (reset before every run).
    out : path, optional
        Output folder (figures, ``validation.json``, ``index.html``, the ``time``
        recording); nothing is written without it.
    **options
        The keywords of :func:`mrsuspension.hil.chapter7.validate_chapter7`.

    Returns
    -------
    dict
        Every number (as written to ``validation.json``), with the figures' file names
        under ``figures`` when ``out`` is given.

    Examples
    --------
    >>> import tempfile
    >>> from mrsuspension.engine.simulate import Simulation
    >>> from mrsuspension.excitation import Harmonic
    >>> from mrsuspension.hil import ideal_rig
    >>> sim = Simulation(Harmonic(1.5, 0.02))
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     data = validate_chapter7(sim, ideal_rig(sim.damper), tmp, what=["pulse"], rate=500.0)
    ...     sorted(p.name for p in Path(tmp).iterdir())
    ['index.html', 'pulse_scenario.png', 'validation.json']
    >>> data["figures"]
    {'pulse': ['pulse_scenario.png']}
    """
    return _validate(sim, rig, out, render=render, **options)


def render(data: dict[str, Any], pulses: dict[str, Any], out: Path) -> dict[str, list[str]]:
    """Draw the comparison figures into ``out`` and write its ``index.html``.

    The renderer :func:`validate_chapter7` hands to
    :func:`mrsuspension.hil.chapter7.validate_chapter7`
    (:data:`mrsuspension.hil.chapter7.Renderer`).

    Parameters
    ----------
    data : dict
        The validation's numbers; ``data["figures"]`` holds the figures made so far (the
        ``time`` ones).
    pulses : dict
        The pulse entries with their aligned runs (``_pair``).
    out : Path
        Output folder.

    Returns
    -------
    dict
        The new figures' file names by comparison.

    Examples
    --------
    >>> import tempfile
    >>> data = {"pacing": "UNPACED", "realtime": "unpaced", "rig": {"rig": "simulated"},
    ...         "masses": [563.0], "figures": {}}
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     render(data, {}, Path(tmp)), sorted(p.name for p in Path(tmp).iterdir())
    ({}, ['index.html'])
    """
    made = draw_figures(data, pulses, out)
    (out / "index.html").write_text(index_page(data, {**data.get("figures", {}), **made}))
    return made


#: panels of the pulse figures: (channel, label)
_PULSE_PANELS = (
    ("z_s", "x_s [m]"), ("z_s_ddot", "a_s [m/s^2]"), ("z_u_ddot", "a_u [m/s^2]"),
    ("x_d", "x_r [m]"), ("F_d", "F_d [N]"), ("F_T", "F_T [N]"),
)  # fmt: skip


def _by_case(entries: dict[str, Any]) -> dict[str, list[dict[str, Any]]]:
    """Entries grouped by controller case, in mass order."""
    out: dict[str, list[dict[str, Any]]] = {}
    for res in entries.values():
        out.setdefault(res["case"], []).append(res)
    return out


def draw_figures(data: dict[str, Any], pulses: dict[str, Any], out: Path) -> dict[str, list[str]]:
    """Draw the comparison figures of a validation into ``out`` (PNG).

    Parameters
    ----------
    data : dict
        The numbers of :func:`~mrsuspension.hil.chapter7.validate_chapter7`.
    pulses : dict
        Its pulse entries with their aligned runs (``_pair``).
    out : Path
        Output folder.

    Returns
    -------
    dict
        File names by comparison (``frequency``, ``pulse``, ``pulse_masses``, ``road``,
        ``road_masses``).

    Examples
    --------
    >>> data = {"realtime": "unpaced", "masses": [563.0]}
    >>> draw_figures(data, {}, Path("unused"))
    {}
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    tag = " [UNPACED]" if data["realtime"] == "unpaced" else ""
    masses = data["masses"]
    several = len(masses) > 1

    def suffix(mass: float) -> str:
        return f"_{mass_tag(mass)}" if several else ""

    made: dict[str, list[str]] = {}
    if "frequency" in data:
        made["frequency"] = []
        for mass in masses:
            fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharex=True)
            here = [fr for fr in data["frequency"].values() if fr["sprung_mass"] == mass]
            for i, fr in enumerate(here):
                color, case = f"C{i}", fr["case"]
                for ax, k in zip(axes.flat, FREQUENCY_MEASURES, strict=True):
                    ax.plot(
                        fr["frequency"], fr["offline"][k], "-", color=color, label=f"{case} offline"
                    )
                    ax.plot(fr["frequency"], fr["hil"][k], "o", mfc="none", color=color,
                            label=f"{case} HiL")  # fmt: skip
            for ax, k in zip(axes.flat, FREQUENCY_MEASURES, strict=True):
                ax.set_xscale("log")
                ax.set_ylabel(k)
                ax.grid(True, which="both", alpha=0.3)
            for ax in axes[1]:
                ax.set_xlabel("frequency [Hz]")
            axes[0, 0].legend(fontsize=7)
            fig.suptitle(
                f"Frequency responses, m_s = {mass:g} kg: HiL (markers) vs offline (lines){tag}"
            )
            made["frequency"].append(save_figure(fig, out, f"frequency_response{suffix(mass)}.png"))
    if pulses:
        made["pulse"] = []
        for res in pulses.values():
            case, mass, pair = res["case"], res["sprung_mass"], res["_pair"]
            fig, axes = plt.subplots(3, 2, figsize=(10, 8), sharex=True)
            for ax, (ch, ylabel) in zip(axes.flat, _PULSE_PANELS, strict=True):
                ax.plot(pair["time"], pair["offline"][ch], label="offline", lw=1.2)
                ax.plot(pair["time"], pair["hil"][ch], "--", label="HiL", lw=1.0)
                ax.set_ylabel(ylabel)
                ax.grid(True, alpha=0.3)
            axes[0, 0].legend()
            for ax in axes[2]:
                ax.set_xlabel("time [s]")
            fig.suptitle(f"Rounded pulse, {case}, m_s = {mass:g} kg: HiL vs offline{tag}")
            made["pulse"].append(save_figure(fig, out, f"pulse_{case}{suffix(mass)}.png"))
        if several:  # Fig 7.18: the masses overlaid, one figure per case
            made["pulse_masses"] = []
            for case, group in _by_case(pulses).items():
                fig, axes = plt.subplots(3, 2, figsize=(10, 8), sharex=True)
                for i, res in enumerate(group):
                    pair, m = res["_pair"], res["sprung_mass"]
                    for ax, (ch, ylabel) in zip(axes.flat, _PULSE_PANELS, strict=True):
                        ax.plot(pair["time"], pair["offline"][ch], "-", color=f"C{i}", lw=1.2,
                                label=f"{m:g} kg offline")  # fmt: skip
                        ax.plot(pair["time"], pair["hil"][ch], "--", color=f"C{i}", lw=1.0,
                                label=f"{m:g} kg HiL")  # fmt: skip
                        ax.set_ylabel(ylabel)
                for ax in axes.flat:
                    ax.grid(True, alpha=0.3)
                axes[0, 0].legend(fontsize=7)
                for ax in axes[2]:
                    ax.set_xlabel("time [s]")
                fig.suptitle(f"Rounded pulse, {case}, sprung masses overlaid (Fig 7.18){tag}")
                made["pulse_masses"].append(save_figure(fig, out, f"pulse_masses_{case}.png"))
    if "road" in data:
        made["road"] = []
        for res in data["road"].values():
            case, mass = res["case"], res["sprung_mass"]
            fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharex=True)
            for ax, (_, label, unit) in zip(axes.flat, PSD_CHANNELS, strict=True):
                s = res["psd"][label]
                ax.loglog(s["frequency"], s["offline"], label="offline", lw=1.2)
                ax.loglog(s["frequency"], s["hil"], "--", label="HiL", lw=1.0)
                ax.set_ylabel(f"PSD {label} [({unit})^2/Hz]")
                ax.grid(True, which="both", alpha=0.3)
            axes[0, 0].legend()
            for ax in axes[1]:
                ax.set_xlabel("frequency [Hz]")
            fig.suptitle(
                f"Random road (rough, 50 km/h, x0.5), {case}, m_s = {mass:g} kg: "
                f"HiL vs offline{tag}"
            )
            made["road"].append(save_figure(fig, out, f"road_psd_{case}{suffix(mass)}.png"))
        if several:  # Fig 7.21: the masses overlaid, one figure per case
            made["road_masses"] = []
            for case, group in _by_case(data["road"]).items():
                fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharex=True)
                for i, res in enumerate(group):
                    m = res["sprung_mass"]
                    for ax, (_, label, unit) in zip(axes.flat, PSD_CHANNELS, strict=True):
                        s = res["psd"][label]
                        ax.loglog(s["frequency"], s["offline"], "-", color=f"C{i}", lw=1.2,
                                  label=f"{m:g} kg offline")  # fmt: skip
                        ax.loglog(s["frequency"], s["hil"], "--", color=f"C{i}", lw=1.0,
                                  label=f"{m:g} kg HiL")  # fmt: skip
                        ax.set_ylabel(f"PSD {label} [({unit})^2/Hz]")
                for ax in axes.flat:
                    ax.grid(True, which="both", alpha=0.3)
                axes[0, 0].legend(fontsize=7)
                for ax in axes[1]:
                    ax.set_xlabel("frequency [Hz]")
                fig.suptitle(
                    f"Random road (rough, 50 km/h, x0.5), {case}, sprung masses overlaid "
                    f"(Fig 7.21){tag}"
                )
                made["road_masses"].append(save_figure(fig, out, f"road_psd_masses_{case}.png"))
    return made


def index_page(data: dict[str, Any], figures: dict[str, list[str]]) -> str:
    """The HTML page of a validation: pacing, rig, tables of every comparison, figures.

    Parameters
    ----------
    data : dict
        The numbers of :func:`~mrsuspension.hil.chapter7.validate_chapter7`.
    figures : dict
        File names by comparison (the ``time`` ones and those of :func:`draw_figures`).

    Returns
    -------
    str
        The page (``index.html``).

    Examples
    --------
    >>> data = {"pacing": "UNPACED", "rig": {"rig": "simulated"}, "masses": [563.0]}
    >>> page = index_page(data, {"pulse": ["pulse_scenario.png"]})
    >>> "<h2>Other figures</h2>" in page, "src='pulse_scenario.png'" in page
    (True, True)
    """
    several = len(data["masses"]) > 1
    made = {name for group in figures.values() for name in group}
    placed: list[str] = []

    def img(name: str) -> str:
        if name not in made:
            return ""
        placed.append(name)
        return f"<p><img src='{html.escape(name)}' style='max-width:100%'></p>"

    def title(res: dict[str, Any]) -> str:
        mass = f", m_s = {res['sprung_mass']:g} kg" if several else ""
        return f"<h3>{html.escape(res['case'])}{mass}</h3>"

    def suffix(mass: float) -> str:
        return f"_{mass_tag(mass)}" if several else ""

    parts = [
        "<!doctype html><html><head><meta charset='utf-8'><title>HiL validation</title>",
        "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse;"
        "margin:1em 0}td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}"
        ".pacing{font-weight:bold;padding:.5em;background:#ffe}</style></head><body>",
        "<h1>HiL against offline (dissertation Chapter 7)</h1>",
        f"<p class='pacing'>{html.escape(data['pacing'])}</p>",
        f"<p>rig: {html.escape(json.dumps(data['rig']))}</p>",
        "<p>sprung mass m_s: " + ", ".join(f"{m:g} kg" for m in data["masses"]) + "</p>"
        if data["masses"]
        else "",
    ]
    if data.get("corner"):  # a half or full car: one corner's damper on the rig
        model = data.get("scenario", {}).get("vehicle", {}).get("model", "vehicle")
        parts.append(
            f"<p>{html.escape(str(model))}, the damper of corner "
            f"<b>{html.escape(str(data['corner']))}</b> on the rig, the rest of the car "
            "simulated in the loop; RMS of that corner's signals and of the body's</p>"
        )
    if "time" in data:
        parts.append(
            "<h2>Time histories and F-v loop, scenario excitation "
            "(Figs 7.7, 7.8, 7.12, 7.13; Fig 7.14 at m_s = 703 kg)</h2>"
        )
        reports = data["time"] if several else {"": data["time"]}
        for t in reports.values():
            if several:
                parts.append(f"<h3>m_s = {t['sprung_mass']:g} kg</h3>")
            parts.append(f"<p>{html.escape(str(t['reason']))}</p>")
            rows = [
                [m["label"], format_number(m["hil"]), format_number(m["offline"]),
                 format_number(m["relative_difference"], percent=True)]
                for m in t["rms"].values()
            ]  # fmt: skip
            parts.append(table(rows, header=["RMS", "HiL", "offline", "difference"]))
            prefix = f"{mass_tag(t['sprung_mass'])}/" if several else ""
            parts += [img(n) for n in figures.get("time", []) if n.startswith(prefix)]
    if "frequency" in data:
        parts.append("<h2>Frequency responses (Figs 7.9, 7.15; Fig 7.16 at m_s = 703 kg)</h2>")
        for fr in data["frequency"].values():
            parts.append(title(fr))
            head = ["f [Hz]", "a [mm]"]
            for k in FREQUENCY_MEASURES:
                head += [f"{k} HiL", f"{k} offline", "diff"]
            rows = []
            for i, f in enumerate(fr["frequency"]):
                row = [f"{f:g}", f"{1e3 * fr['amplitude'][i]:.3g}"]
                for k in FREQUENCY_MEASURES:
                    row += [
                        format_number(fr["hil"][k][i]),
                        format_number(fr["offline"][k][i]),
                        format_number(fr["relative_difference"][k][i], percent=True),
                    ]
                rows.append(row)
            parts.append(table(rows, header=head))
        for mass in data["masses"]:
            if several:
                parts.append(f"<h3>Frequency responses, m_s = {mass:g} kg</h3>")
            parts.append(img(f"frequency_response{suffix(mass)}.png"))
    if "pulse" in data:
        parts.append("<h2>Rounded pulse (Figs 7.10, 7.17)</h2>")
        for res in data["pulse"].values():
            parts.append(title(res))
            rows = [
                [k, format_number(res["hil"][k]), format_number(res["offline"][k]),
                 format_number(res["relative_difference"][k], percent=True)]
                for k in res["hil"]
            ]  # fmt: skip
            parts.append(table(rows, header=["measure", "HiL", "offline", "difference"]))
            parts.append(img(f"pulse_{res['case']}{suffix(res['sprung_mass'])}.png"))
        if several:
            parts.append("<h2>Rounded pulse, sprung masses overlaid (Fig 7.18)</h2>")
            for case in _by_case(data["pulse"]):
                parts.append(f"<h3>{html.escape(case)}</h3>")
                parts.append(img(f"pulse_masses_{case}.png"))
    if "road" in data:
        parts.append("<h2>Random road PSDs (Figs 7.11, 7.19, 7.20)</h2>")
        for res in data["road"].values():
            parts.append(title(res))
            lo, hi = res["band"]
            rows = [
                [f"{label} [{b['unit']}]", format_number(b["hil"]), format_number(b["offline"]),
                 format_number(b["relative_difference"], percent=True),
                 format_number(b["max_pointwise_relative_difference"], percent=True)]
                for label, b in res["band_rms"].items()
            ]  # fmt: skip
            head = [f"RMS {lo:g}-{hi:g} Hz", "HiL", "offline", "difference", "max PSD diff"]
            parts.append(table(rows, header=head))
            parts.append(img(f"road_psd_{res['case']}{suffix(res['sprung_mass'])}.png"))
        if several:
            parts.append("<h2>Random road PSDs, sprung masses overlaid (Fig 7.21)</h2>")
            for case in _by_case(data["road"]):
                parts.append(f"<h3>{html.escape(case)}</h3>")
                parts.append(img(f"road_psd_masses_{case}.png"))
    rest = [n for group in figures.values() for n in group if n not in placed]
    if rest:
        parts.append("<h2>Other figures</h2>")
        parts += [img(n) for n in rest]
    parts.append("</body></html>\n")
    return "\n".join(p for p in parts if p)
