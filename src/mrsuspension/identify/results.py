"""Result types of a periodic identification: per-test outcomes, band fits, the whole.

:class:`IdentificationResult` is what :func:`~mrsuspension.identify.campaign.identify`
returns; :mod:`~mrsuspension.identify.report` renders it. The types live here so that
the campaign (which builds them) and the report (which writes them) both import
downwards, with no cycle between them.

Examples
--------
>>> t = TestOutcome("run01.csv", current=0.2, status="ok", nrmse=0.012)
>>> t.fitted, t.to_dict()["nrmse"]
(True, 0.012)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from mrsuspension import parameters as _parameters
from mrsuspension.errors import ValidationError
from mrsuspension.identify.fit import FitResult
from mrsuspension.identify.preprocess import Loop
from mrsuspension.identify.report import summary_text, write_outputs

__all__ = ["BandFit", "IdentificationResult", "TestOutcome"]

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
