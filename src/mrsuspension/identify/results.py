"""Result types of a periodic identification and their outputs.

:class:`IdentificationResult` is what :func:`~mrsuspension.identify.campaign.identify`
returns (per-test outcomes, band fits, the whole); :func:`write_outputs` and
:func:`summary_text` render it (what :meth:`IdentificationResult.save` and
:meth:`IdentificationResult.summary_text` call). The types and their writers share this
module, so nothing imports in a circle; :mod:`mrsuspension.identify.report` names the
writers for callers that import them from there.

:func:`write_outputs` writes into one folder:

``parameters.toml`` (or ``parameters-<band>.toml`` per band)
    the fitted set, in the format the simulator loads
    (``make_damper("wang-symmetric", "out/parameters.toml")``);
``compare-<model>.toml``
    the sets of the models fitted for comparison;
``tests.csv``
    one row per test: status, message, current, frequency, amplitude, v_m, NRMSE,
    peak-force and energy errors, the compared models' NRMSE;
``summary.json``
    the object ``mrsus identify --json`` prints;
``plots/*.png``
    measured and model F-v and F-x loops of every fitted test (matplotlib, imported
    here only, with the Agg backend);
``index.html``
    a summary page linking all of the above.

Examples
--------
>>> t = TestOutcome("run01.csv", current=0.2, status="ok", nrmse=0.012)
>>> t.fitted, t.to_dict()["nrmse"]
(True, 0.012)
"""

from __future__ import annotations

import csv
import html
import importlib.util
import json
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from mrsuspension import parameters as _parameters
from mrsuspension.errors import ValidationError
from mrsuspension.identify.fit import FitResult
from mrsuspension.identify.preprocess import Loop

__all__ = [
    "BandFit",
    "IdentificationResult",
    "TestOutcome",
    "evidence_text",
    "plot_test",
    "summary_text",
    "write_outputs",
]

FloatArray = npt.NDArray[np.float64]


@dataclass
class TestOutcome:
    """What happened to one test (one row of the per-test table).

    ``nrmse`` is the RMS force error over the loop divided by the measured force range;
    ``peak_force_error`` the relative error of the larger of the compression and rebound
    peak forces (the one with the larger error, signed: + means the model is higher);
    ``energy_error`` the relative error of the energy dissipated per cycle.
    """

    file: str
    current: float | None = None
    frequency: float | None = None
    amplitude: float | None = None
    peak_velocity: float | None = None
    status: str = "error"
    message: str = ""
    notes: list[str] = field(default_factory=list)
    band: str | None = None
    nrmse: float | None = None
    peak_force_error: float | None = None
    energy_error: float | None = None
    compare: dict[str, float | None] = field(default_factory=dict)
    loop: Loop | None = None
    model_force: FloatArray | None = None
    compare_forces: dict[str, FloatArray] = field(default_factory=dict)

    __test__ = False

    @property
    def fitted(self) -> bool:
        """Whether the test took part in a fit and has errors to show."""
        return self.nrmse is not None

    def to_dict(self) -> dict[str, Any]:
        """Plain data for JSON (no arrays)."""
        return {
            "file": self.file,
            "current": self.current,
            "frequency": self.frequency,
            "amplitude": self.amplitude,
            "peak_velocity": self.peak_velocity,
            "band": self.band,
            "status": self.status,
            "message": self.message,
            "nrmse": self.nrmse,
            "peak_force_error": self.peak_force_error,
            "energy_error": self.energy_error,
            "compare": dict(self.compare),
            "cycles_used": None if self.loop is None else self.loop.cycles_used,
            "notes": list(self.notes),
        }


@dataclass
class BandFit:
    """The fits of one frequency band (or of the whole campaign): primary and compared."""

    label: str
    low: float
    high: float
    result: FitResult | None = None
    error: str | None = None
    compare: dict[str, FitResult | str] = field(default_factory=dict)


@dataclass
class IdentificationResult:
    """Everything :func:`identify` found: fits, per-test outcomes, comparison.

    Use :attr:`parameters` (single fit) or :attr:`parameter_sets` (per band), and
    :meth:`save` for the files (parameter set, per-test CSV, JSON, plots, HTML).
    """

    manifest: str
    model: str
    tests: list[TestOutcome]
    fits: list[BandFit]
    compare_models: tuple[str, ...] = ()
    notes: list[str] = field(default_factory=list)
    created: str = ""
    settings: dict[str, Any] = field(default_factory=dict)

    @property
    def parameter_sets(self) -> dict[str, _parameters.ParameterSet]:
        """Fitted parameter set of each band that fitted (label -> set)."""
        return {b.label: b.result.parameters for b in self.fits if b.result is not None}

    @property
    def parameters(self) -> _parameters.ParameterSet:
        """The fitted parameter set (the first band's when fitting per band)."""
        sets = self.parameter_sets
        if not sets:
            raise ValidationError("no fit succeeded; see the per-test messages")
        return next(iter(sets.values()))

    def fitted_tests(self) -> list[TestOutcome]:
        """Tests with a fit result."""
        return [t for t in self.tests if t.fitted]

    @property
    def mean_nrmse(self) -> float | None:
        """Mean NRMSE over the fitted tests."""
        vals = [t.nrmse for t in self.fitted_tests() if t.nrmse is not None]
        return float(np.mean(vals)) if vals else None

    @property
    def max_nrmse(self) -> float | None:
        """Largest NRMSE over the fitted tests."""
        vals = [t.nrmse for t in self.fitted_tests() if t.nrmse is not None]
        return float(np.max(vals)) if vals else None

    def comparison(self) -> list[dict[str, Any]]:
        """Mean and largest NRMSE of each model over the tests every model fitted."""
        models = (self.model, *self.compare_models)
        common = [
            t for t in self.fitted_tests()
            if all(t.compare.get(m) is not None for m in self.compare_models)
        ]  # fmt: skip
        rows = []
        for m in models:
            vals = [t.nrmse if m == self.model else t.compare[m] for t in common]
            clean = [float(v) for v in vals if v is not None]
            rows.append({
                "model": m,
                "tests": len(clean),
                "mean_nrmse": float(np.mean(clean)) if clean else None,
                "max_nrmse": float(np.max(clean)) if clean else None,
            })  # fmt: skip
        return rows

    def verdict(self) -> str:
        """One sentence saying which model fits better (by mean NRMSE)."""
        rows = [r for r in self.comparison() if r["mean_nrmse"] is not None]
        if len(rows) < 2:
            return ""
        ranked = sorted(rows, key=lambda r: r["mean_nrmse"])
        best, others = ranked[0], ranked[1:]
        parts = ", ".join(
            f"{r['model']} {100 * r['mean_nrmse']:.2f} % (worst {100 * r['max_nrmse']:.2f} %)"
            for r in others
        )
        return (
            f"{best['model']} fits better: mean NRMSE {100 * best['mean_nrmse']:.2f} % "
            f"(worst test {100 * best['max_nrmse']:.2f} %) against {parts}, over "
            f"{best['tests']} tests"
        )

    @property
    def best_model(self) -> str | None:
        """The model with the lowest mean NRMSE (``None`` without a comparison)."""
        rows = [r for r in self.comparison() if r["mean_nrmse"] is not None]
        return min(rows, key=lambda r: r["mean_nrmse"])["model"] if len(rows) > 1 else None

    def to_dict(self) -> dict[str, Any]:
        """The JSON object of ``mrsus identify --json``."""
        sets = self.parameter_sets
        if len(self.fits) == 1:
            params: Any = dict(sets[self.fits[0].label].values) if sets else None
        else:
            params = {label: dict(s.values) for label, s in sets.items()}
        fits = []
        for b in self.fits:
            entry: dict[str, Any] = {"band": b.label, "error": b.error}
            if b.result is not None:
                r = b.result
                entry.update(
                    parameter_set=r.parameters.name,
                    converged=r.converged,
                    status=r.status,
                    message=r.message,
                    nfev=r.nfev,
                    starts=len(r.starts),
                    seconds=r.seconds,
                    rms_nrmse=r.rms_nrmse,
                    free=list(r.free),
                    at_bounds=list(r.at_bounds),
                    evidence=r.evidence,
                )
            entry["compare"] = {
                m: (c if isinstance(c, str) else {"parameters": dict(c.parameters.values),
                                                  "rms_nrmse": c.rms_nrmse})
                for m, c in b.compare.items()
            }  # fmt: skip
            fits.append(entry)
        # the campaign module owns the JSON cleaner (imported when called: no cycle at
        # import time; it moves to a shared module later)
        from mrsuspension._jsonsafe import to_jsonable

        return to_jsonable({
            "manifest": self.manifest,
            "model": self.model,
            "created": self.created,
            "parameters": params,
            "tests": [t.to_dict() for t in self.tests],
            "mean_nrmse": self.mean_nrmse,
            "max_nrmse": self.max_nrmse,
            "fitted": len(self.fitted_tests()),
            "failed": sum(1 for t in self.tests if not t.fitted),
            "fits": fits,
            "comparison": self.comparison() if self.compare_models else [],
            "best_model": self.best_model,
            "verdict": self.verdict(),
            "notes": list(self.notes),
            "settings": dict(self.settings),
        })  # fmt: skip

    def save(self, folder: str | Path, *, plots: bool = True) -> list[Path]:
        """Write the parameter set(s), ``tests.csv``, ``summary.json``, plots and
        ``index.html`` into ``folder`` (see :mod:`mrsuspension.identify.report`)."""
        return write_outputs(self, Path(folder), plots=plots)

    def summary_text(self) -> str:
        """Human-readable summary (what the CLI prints without ``--json``)."""
        return summary_text(self)


# -- outputs: parameter sets, tables, plots, html -----------------------------------------


def _pct(value: float | None, signed: bool = False) -> str:
    if value is None or not np.isfinite(value):
        return "-"
    return f"{100 * value:+.2f} %" if signed else f"{100 * value:.2f} %"


def _slug(text: str) -> str:
    return re.sub(r"[^0-9A-Za-z.+-]+", "_", text).strip("_") or "test"


def _set_file(label: str) -> str:
    return (
        "parameters.toml" if label == "all" else f"parameters-{_slug(label.replace(' ', ''))}.toml"
    )


def evidence_text(r: FitResult) -> str:
    """One line on how trustworthy a fit's optimum is (:attr:`FitResult.evidence`)."""
    parts = [
        f"best of {len(r.starts)} starts, {r.starts_within} within 1 % of the best cost"
        + ("" if len(r.starts) < 2 or r.starts_within > 1 else " (a single start found it:"
           " try --multistart higher)")
    ]  # fmt: skip
    if r.at_bounds:
        parts.append(f"at a bound: {', '.join(r.at_bounds)}")
    if r.correlated:
        shown = ", ".join(f"{a}/{b} {c:+.3f}" for a, b, c in r.correlated[:4])
        more = f" (+{len(r.correlated) - 4} more)" if len(r.correlated) > 4 else ""
        parts.append(f"strongly correlated (|corr| > 0.98): {shown}{more}")
    if r.condition > 1e10:
        parts.append(
            f"J^T J near singular (condition {r.condition:.2g}): some parameters are not "
            "identifiable from these tests (fix them with --fix)"
        )
    return "; ".join(parts)


def summary_text(result: IdentificationResult) -> str:
    """Plain-text summary: fit status, per-test table, comparison, parameters."""
    lines = [f"identify: {result.model} on {len(result.tests)} test rows from {result.manifest}"]
    for band in result.fits:
        tag = "" if band.label == "all" else f" [{band.label}]"
        if band.result is None:
            lines.append(f"fit{tag}: FAILED: {band.error}")
            continue
        r = band.result
        state = "converged" if r.converged else "NOT converged"
        lines.append(
            f"fit{tag}: {state} ({r.message}); {len(r.starts)} start(s), {r.nfev} evaluations, "
            f"{r.seconds:.2f} s; RMS of the per-test NRMSE {_pct(r.rms_nrmse)}"
        )
        lines.append(f"  evidence{tag}: {evidence_text(r)}")
    header = (
        f"{'#':>3} {'file':28} {'band':10} {'i [A]':>6} {'f [Hz]':>7} {'a [mm]':>7} "
        f"{'v_m':>6} {'NRMSE':>8} {'peak err':>9} {'energy':>9}  status"
    )
    lines.append(header)
    for k, t in enumerate(result.tests, start=1):
        cur = "-" if t.current is None else f"{t.current:.3g}"
        freq = "-" if t.frequency is None else f"{t.frequency:.3g}"
        amp = "-" if t.amplitude is None else f"{t.amplitude * 1e3:.3g}"
        vm = "-" if t.peak_velocity is None else f"{t.peak_velocity:.3g}"
        lines.append(
            f"{k:>3} {t.file[:28]:28} {(t.band or '')[:10]:10} {cur:>6} {freq:>7} {amp:>7} "
            f"{vm:>6} {_pct(t.nrmse):>8} {_pct(t.peak_force_error, True):>9} "
            f"{_pct(t.energy_error, True):>9}  {t.status}" + (f": {t.message}" if t.message else "")
        )
    if result.mean_nrmse is not None and result.max_nrmse is not None:
        worst = max(result.fitted_tests(), key=lambda t: t.nrmse or 0.0)
        lines.append(
            f"mean NRMSE {_pct(result.mean_nrmse)}, max {_pct(result.max_nrmse)} ({worst.file}); "
            f"{len(result.fitted_tests())} fitted, "
            f"{sum(1 for t in result.tests if not t.fitted)} not fitted"
        )
    verdict = result.verdict()
    if verdict:
        lines.append(f"comparison: {verdict}")
    for label, pset in result.parameter_sets.items():
        tag = "" if label == "all" else f" [{label}]"
        values = "  ".join(f"{k}={v:.6g}" for k, v in pset.items())
        lines.append(f"parameters{tag}: {values}")
    for note in result.notes:
        lines.append(f"note: {note}")
    return "\n".join(lines)


def plot_test(
    test: TestOutcome, path: Path, model: str, compare_models: tuple[str, ...] = ()
) -> Path:
    """Measured and model F-v and F-x loops of one test, as a PNG."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    loop = test.loop
    assert loop is not None
    close = np.r_[np.arange(loop.force.size), 0]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.4))
    fig.subplots_adjust(left=0.095, right=0.985, bottom=0.15, top=0.88, wspace=0.3)
    curves = [("measured", loop.force, {"color": "k", "lw": 0, "marker": ".", "ms": 2.5})]
    if test.model_force is not None:
        curves.append(
            (f"{model} ({_pct(test.nrmse)})", test.model_force, {"color": "C3", "lw": 1.4})
        )
    for k, other in enumerate(compare_models):
        if other in test.compare_forces:
            label = f"{other} ({_pct(test.compare.get(other))})"
            curves.append(
                (label, test.compare_forces[other], {"color": f"C{k}", "lw": 1.0, "ls": "--"})
            )
    for label, force, style in curves:
        ax1.plot(loop.velocity[close], force[close], label=label, **style)
        ax2.plot(loop.stroke[close] * 1e3, force[close], label=label, **style)
    ax1.set_xlabel("velocity $v_d$ [m/s]")
    ax2.set_xlabel("stroke $x_d$ [mm]")
    for ax in (ax1, ax2):
        ax.set_ylabel("force $F_d$ [N]")
        ax.grid(True, alpha=0.3)
    ax1.legend(fontsize=7)
    band = f", {test.band}" if test.band else ""
    fig.suptitle(
        f"{test.file}: {loop.mean_current:.3g} A, {loop.frequency:.3g} Hz, "
        f"{loop.amplitude * 1e3:.3g} mm{band}",
        fontsize=9,
    )
    fig.savefig(path, dpi=80)
    plt.close(fig)
    return path


_STYLE = """
body{font-family:system-ui,sans-serif;max-width:1200px;margin:2em auto;padding:0 1em;color:#222}
h1{font-size:1.5em} h2{border-bottom:1px solid #ccc;margin-top:1.8em}
table{border-collapse:collapse;font-size:.85em;margin:.5em 0}
td,th{border:1px solid #ccc;padding:.2em .5em;text-align:right} th{background:#f4f4f4}
td.l,th.l{text-align:left} .ok{color:#176117} .warning{color:#8a6100}
.error,.fit-failed,.poor-fit{color:#a40000;font-weight:bold} .meta{color:#666;font-size:.85em}
img{max-width:100%;border:1px solid #eee;margin:.3em 0} details{margin:.2em 0}
"""


def _tests_csv(result: IdentificationResult, path: Path) -> Path:
    keys = ["file", "band", "status", "message", "current", "frequency", "amplitude",
            "peak_velocity", "nrmse", "peak_force_error", "energy_error", "cycles_used"]  # fmt: skip
    keys += [f"nrmse_{m}" for m in result.compare_models]
    keys.append("notes")
    with path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(keys)
        for t in result.tests:
            d = t.to_dict()
            row = [d.get(k, None) for k in keys[:12]]
            row += [t.compare.get(m) for m in result.compare_models]
            row.append(" | ".join(t.notes))
            w.writerow(["" if v is None else v for v in row])
    return path


def _html(result: IdentificationResult, plots: dict[int, str], files: list[str]) -> str:
    e = html.escape
    parts = [
        "<!doctype html><html><head><meta charset='utf-8'>",
        f"<title>identification: {e(result.model)}</title><style>{_STYLE}</style></head><body>",
        f"<h1>Identification of <code>{e(result.model)}</code></h1>",
        f"<p class='meta'>manifest {e(result.manifest)} &middot; {e(result.created)} &middot; "
        "mrsuspension identify (model reference, section 10, eq. 2.22: least squares over all "
        "tests, each normalised by its force range)</p>",
    ]
    mean, worst = result.mean_nrmse, result.max_nrmse
    parts.append(
        f"<p>{len(result.fitted_tests())} of {len(result.tests)} test rows fitted; mean NRMSE "
        f"<b>{_pct(mean)}</b>, max <b>{_pct(worst)}</b>.</p>"
    )
    verdict = result.verdict()
    if verdict:
        parts.append(f"<h2>Model comparison</h2><p><b>{e(verdict)}</b></p>")
        rows = "".join(
            f"<tr><td class='l'>{e(r['model'])}</td><td>{r['tests']}</td>"
            f"<td>{_pct(r['mean_nrmse'])}</td><td>{_pct(r['max_nrmse'])}</td></tr>"
            for r in result.comparison()
        )
        parts.append(
            "<table><tr><th class='l'>model</th><th>tests</th><th>mean NRMSE</th>"
            f"<th>max NRMSE</th></tr>{rows}</table>"
        )
    parts.append("<h2>Fits</h2>")
    for band in result.fits:
        title = "all tests" if band.label == "all" else band.label
        if band.result is None:
            parts.append(f"<p class='error'>{e(title)}: fit failed: {e(str(band.error))}</p>")
            continue
        r = band.result
        state = "converged" if r.converged else "did NOT converge"
        parts.append(
            f"<h3>{e(title)}: <code>{e(_set_file(band.label))}</code></h3><p>{state} "
            f"({e(r.message)}); {len(r.starts)} start(s), {r.nfev} evaluations, {r.seconds:.2f} s, "
            f"Jacobian {e(r.jacobian)}; started from <code>{e(r.start.name)}</code>.</p>"
            f"<p>Evidence: {e(evidence_text(r))}.</p>"
        )
        prows = []
        for key, v in r.parameters.items():
            start = r.start.values.get(key)
            lo_hi = r.bounds.get(key)
            bound = "fixed" if lo_hi is None else f"[{lo_hi[0]:.4g}, {lo_hi[1]:.4g}]"
            flag = " (at bound)" if key in r.at_bounds else ""
            prows.append(
                f"<tr><td class='l'>{e(key)}</td><td>{v:.6g}</td>"
                f"<td class='l'>{e(r.parameters.units.get(key, ''))}</td>"
                f"<td>{'' if start is None else f'{start:.6g}'}</td><td class='l'>{bound}{flag}</td>"
                f"<td class='l'>{e(r.parameters.descriptions.get(key, ''))}</td></tr>"
            )
        parts.append(
            "<table><tr><th class='l'>parameter</th><th>fitted</th><th class='l'>unit</th>"
            "<th>start</th><th class='l'>bounds</th><th class='l'>meaning</th></tr>"
            + "".join(prows)
            + "</table>"
        )
    parts.append("<h2>Tests</h2>")
    head = ("<tr><th>#</th><th class='l'>file</th><th class='l'>band</th><th>i [A]</th>"
            "<th>f [Hz]</th><th>a [mm]</th><th>v_m [m/s]</th><th>NRMSE</th><th>peak force</th>"
            "<th>energy</th>")  # fmt: skip
    head += "".join(f"<th>NRMSE {e(m)}</th>" for m in result.compare_models)
    head += "<th class='l'>status</th></tr>"
    body = []
    for k, t in enumerate(result.tests, start=1):

        def num(q: float | None, scale: float = 1.0) -> str:
            return "-" if q is None else f"{q * scale:.4g}"

        cells = (
            f"<td>{k}</td><td class='l'>{e(t.file)}</td><td class='l'>{e(t.band or '')}</td>"
            f"<td>{num(t.current)}</td><td>{num(t.frequency)}</td><td>{num(t.amplitude, 1e3)}</td>"
            f"<td>{num(t.peak_velocity)}</td><td>{_pct(t.nrmse)}</td>"
            f"<td>{_pct(t.peak_force_error, True)}</td><td>{_pct(t.energy_error, True)}</td>"
        )
        cells += "".join(f"<td>{_pct(t.compare.get(m))}</td>" for m in result.compare_models)
        status = f"<span class='{e(t.status)}'>{e(t.status)}</span>"
        if t.message:
            status += f": {e(t.message)}"
        body.append(f"<tr>{cells}<td class='l'>{status}</td></tr>")
    parts.append(f"<table>{head}{''.join(body)}</table>")
    parts.append("<h2>Loops and pre-processing</h2>")
    for k, t in enumerate(result.tests, start=1):
        notes = "".join(f"<li>{e(n)}</li>" for n in t.notes)
        img = f"<br><img src='{e(plots[k])}' alt='loops of {e(t.file)}'>" if k in plots else ""
        parts.append(
            f"<details{' open' if k in plots else ''}><summary>{k}. {e(t.file)} "
            f"{e(t.band or '')} &middot; <span class='{e(t.status)}'>{e(t.status)}</span>"
            f"</summary><ul>{notes}</ul>{img}</details>"
        )
    if result.notes:
        parts.append(
            "<h2>Notes</h2><ul>" + "".join(f"<li>{e(n)}</li>" for n in result.notes) + "</ul>"
        )
    parts.append(
        "<h2>Files</h2><ul>"
        + "".join(f"<li><a href='{e(f)}'>{e(f)}</a></li>" for f in files)
        + "</ul>"
    )
    parts.append("</body></html>")
    return "\n".join(parts)


def write_outputs(result: IdentificationResult, folder: Path, *, plots: bool = True) -> list[Path]:
    """Write every output of ``result`` into ``folder`` (see the module docstring)."""
    folder.mkdir(parents=True, exist_ok=True)
    written: list[Path] = []
    for band in result.fits:
        if band.result is not None:
            written.append(band.result.parameters.save(folder / _set_file(band.label)))
        for other, res in band.compare.items():
            if not isinstance(res, str):
                suffix = "" if band.label == "all" else "-" + _slug(band.label.replace(" ", ""))
                written.append(res.parameters.save(folder / f"compare-{other}{suffix}.toml"))
    if plots and importlib.util.find_spec("matplotlib") is None:
        plots = False
        result.notes.append(
            "loop plots skipped: matplotlib is not installed (pip install 'mrsuspension[plot]')"
        )
    written.append(_tests_csv(result, folder / "tests.csv"))
    summary = folder / "summary.json"
    data: dict[str, Any] = result.to_dict()
    plot_files: dict[int, str] = {}
    if plots:
        plot_dir = folder / "plots"
        plot_dir.mkdir(exist_ok=True)
        for k, t in enumerate(result.tests, start=1):
            if t.loop is None or t.model_force is None:
                continue
            stem = _slug(Path(t.file).stem) + (f"_{_slug(t.band)}" if t.band else "")
            path = plot_test(
                t, plot_dir / f"{k:03d}-{stem}.png", result.model, result.compare_models
            )
            plot_files[k] = f"plots/{path.name}"
            written.append(path)
    data["files"] = [p.relative_to(folder).as_posix() for p in written] + [
        "summary.json",
        "index.html",
    ]
    summary.write_text(json.dumps(data, indent=2) + "\n")
    written.append(summary)
    index = folder / "index.html"
    index.write_text(_html(result, plot_files, data["files"]))
    written.append(index)
    return written
