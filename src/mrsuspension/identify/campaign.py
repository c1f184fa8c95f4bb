"""A whole identification: manifest -> loops -> fits -> per-test results.

:func:`identify` is what ``mrsus identify`` runs. Every test listed in the manifest ends
up in :attr:`IdentificationResult.tests` with a status:

``ok``
    fitted; its NRMSE, peak-force and energy errors are given;
``warning``
    fitted, but something deserves a look (frequency or current disagreeing with the
    manifest, a fit that did not converge...): see ``message`` and ``notes``;
``poor-fit``
    fitted, but its NRMSE exceeds ``poor_fit`` (15 %): check its current, units and sign;
``error``
    not fitted: the file could not give a loop (missing columns, NaN, time not
    increasing, no whole cycle, no current...); ``message`` says why;
``fit-failed``
    the fit of its group failed, or the model force was not finite for it.

A problem with one test never stops the others; only a campaign with no usable test
raises :class:`~mrsuspension.errors.ValidationError`.
"""

from __future__ import annotations

import datetime as _dt
import math
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from mrsuspension import parameters as _parameters
from mrsuspension.errors import MRSuspensionError, ValidationError, check_count, unknown_name
from mrsuspension.identify.fit import BoundsSpec, FitResult, FixedSpec, fit_loops
from mrsuspension.identify.manifest import Manifest, TestEntry, read_manifest
from mrsuspension.identify.models import FIT_MODELS, fit_model
from mrsuspension.identify.preprocess import Loop, PreprocessOptions, preprocess
from mrsuspension.identify.readers import TestDataError, read_test
from mrsuspension.identify.results import BandFit, IdentificationResult, TestOutcome

__all__ = [
    "BandFit",
    "IdentificationResult",
    "TestOutcome",
    "identify",
    "load_campaign",
    "loop_metrics",
    "parse_bands",
]

FloatArray = npt.NDArray[np.float64]

#: NRMSE above which a fitted test is flagged ``poor-fit``.
POOR_FIT = 0.15


def loop_metrics(loop: Loop, model_force: npt.ArrayLike) -> dict[str, float]:
    """NRMSE, peak-force error and energy-per-cycle error of a model loop.

    Examples
    --------
    >>> import numpy as np
    >>> th = 2 * np.pi * np.arange(360) / 360
    >>> x, v = 0.01 * np.sin(th), 0.01 * np.cos(th)
    >>> loop = Loop("c", th, x, v, -x, 1e5 * v, np.zeros(360), 1.0, 0.01, 0.01)
    >>> m = loop_metrics(loop, 1.1e5 * v)
    >>> {k: round(q, 4) for k, q in m.items()}
    {'nrmse': 0.0354, 'peak_force_error': 0.1, 'energy_error': 0.1}
    """
    fm = np.asarray(model_force, dtype=float)
    f = loop.force
    err = fm - f
    nrmse = math.sqrt(float(np.mean(err * err))) / loop.force_range
    candidates = []
    if f.max() > 0:
        candidates.append((fm.max() - f.max()) / f.max())
    if f.min() < 0:
        candidates.append((f.min() - fm.min()) / f.min() * -1.0)
    peak = float(max(candidates, key=abs)) if candidates else math.nan
    e_meas = loop.energy_per_cycle()
    e_model = loop.energy_per_cycle(fm)
    energy = (e_model - e_meas) / abs(e_meas) if abs(e_meas) > 0 else math.nan
    return {"nrmse": nrmse, "peak_force_error": peak, "energy_error": float(energy)}


def parse_bands(
    text: str | Sequence[tuple[float, float]] | None,
) -> list[tuple[float, float]] | None:
    """Frequency bands from ``"0.5-5,5-15"`` or a list of pairs [Hz].

    Examples
    --------
    >>> parse_bands("0.5-5,5-15")
    [(0.5, 5.0), (5.0, 15.0)]
    """
    if text is None:
        return None
    pairs: list[tuple[float, float]] = []
    if isinstance(text, str):
        for tok in (t.strip() for t in text.split(",") if t.strip()):
            low, sep, high = tok.partition("-")
            try:
                pairs.append((float(low), float(high)))
            except ValueError:
                raise ValidationError(
                    f"--bands: {tok!r} is not a frequency range LOW-HIGH in Hz (e.g. 0.5-5,5-15)"
                ) from None
            if not sep:  # pragma: no cover - float('') fails above
                raise ValidationError(f"--bands: {tok!r} needs LOW-HIGH")
    else:
        pairs = [(float(a), float(b)) for a, b in text]
    if not pairs:
        raise ValidationError("--bands is empty; e.g. 0.5-5,5-15")
    for lo, hi in pairs:
        if not 0 <= lo < hi:
            raise ValidationError(f"frequency band {lo:g}-{hi:g} Hz must have 0 <= low < high")
    return pairs


def _warning(note: str) -> bool:
    return note.startswith("warning:")


def load_campaign(
    manifest: Manifest,
    options: PreprocessOptions | None = None,
    *,
    current_gain: float | None = None,
) -> list[TestOutcome]:
    """Read and pre-process every test of a manifest; problems stay with their test.

    ``current_gain`` [A/V] converts current columns recorded as a voltage
    (:func:`~mrsuspension.identify.readers.read_test`).
    """
    outcomes = []
    for entry in manifest.entries:
        outcomes.append(_load_one(entry, manifest, options or PreprocessOptions(), current_gain))
    return outcomes


def _load_one(
    entry: TestEntry,
    manifest: Manifest,
    options: PreprocessOptions,
    current_gain: float | None = None,
) -> TestOutcome:
    out = TestOutcome(
        file=entry.label,
        current=entry.current,
        frequency=entry.frequency,
        amplitude=entry.amplitude,
        notes=list(entry.notes),
    )
    if entry.error:
        out.message = entry.error
        return out
    try:
        raw = read_test(entry.file, entry.columns, entry.units, current_gain=current_gain)
        if entry.current is None and raw.current is None:
            why = (
                f"the file name does not match --current-pattern {manifest.current_pattern.pattern!r}"
                if manifest.current_pattern is not None
                else "no --current-pattern is given"
            )
            raise TestDataError(
                f"no drive current: the manifest gives none, the file has no current column, "
                f"and {why}"
            )
        loop = preprocess(
            raw,
            options,
            current=entry.current,
            frequency=entry.frequency,
            amplitude=entry.amplitude,
            label=entry.label,
        )
    except TestDataError as exc:
        out.message = str(exc)
        return out
    out.loop = loop
    out.notes = list(entry.notes) + list(loop.notes)
    out.current = loop.mean_current
    out.frequency = loop.nominal_frequency or loop.frequency
    out.amplitude = loop.nominal_amplitude or loop.amplitude
    out.peak_velocity = loop.peak_velocity
    out.status = "ok"
    warnings = [n for n in loop.notes if _warning(n)]
    if warnings:
        out.status = "warning"
        out.message = warnings[0]
    return out


def identify(
    manifest: str | Path,
    model: str = "wang-symmetric",
    *,
    columns: str | None = None,
    units: str | None = None,
    current_pattern: str | None = None,
    points_per_cycle: int = 360,
    remove_offset: bool = False,
    max_cycles: int | None = None,
    peak_velocity: str = "auto",
    force_delay: float = 0.0,
    stroke_tolerance: float = 0.01,
    start: Any = None,
    bounds: BoundsSpec | None = None,
    fixed: FixedSpec | None = None,
    model_options: Mapping[str, Any] | None = None,
    bands: str | Sequence[tuple[float, float]] | None = None,
    compare: str | Sequence[str] = (),
    multistart: int | None = None,
    seed: int = 0,
    max_nfev: int | None = None,
    poor_fit: float = POOR_FIT,
    name: str | None = None,
    progress: Callable[[str], None] | None = None,
    current_gain: float | None = None,
) -> IdentificationResult:
    """Identify a damper model from a campaign of harmonic tests (model reference, section 10).

    Parameters
    ----------
    manifest : str or Path
        CSV or TOML manifest, or a folder of test files
        (:func:`~mrsuspension.identify.manifest.read_manifest`).
    model : str
        Model to fit: ``"wang-symmetric"`` (default), ``"wang-asymmetric"``,
        ``"bingham"``, ``"spencer"`` or ``"linear"``.
    columns, units, current_pattern : str, optional
        Column mapping, units and file-name current pattern for every test (override
        the manifest).
    points_per_cycle, remove_offset, max_cycles, peak_velocity, force_delay, stroke_tolerance
        Pre-processing (:class:`~mrsuspension.identify.preprocess.PreprocessOptions`).
    start, bounds, fixed, model_options, multistart, seed, max_nfev
        Fit settings (:func:`~mrsuspension.identify.fit.fit_loops`).
    bands : str or list of (low, high), optional
        Fit each frequency band separately (``"0.5-5,5-15"``, as the dissertation's two
        sets); a test belongs to every band containing its frequency.
    compare : str or sequence of str
        Other models fitted to the same loops, for comparison (``"bingham,spencer"``).
    poor_fit : float
        NRMSE above which a fitted test is flagged ``poor-fit``.
    name : str, optional
        Name of the fitted parameter set (default ``<model>-fitted``).
    progress : callable, optional
        Called with a short message at each stage.
    current_gain : float, optional
        Gain of the coil driver [A/V] for current columns recorded in V or mV.

    Returns
    -------
    IdentificationResult

    Raises
    ------
    ValidationError
        For a bad manifest or option, or when no test could be used at all.

    Examples
    --------
    >>> import tempfile
    >>> from mrsuspension.identify import synthetic_campaign
    >>> folder = tempfile.mkdtemp()
    >>> manifest = synthetic_campaign(folder, "bingham", [(1.5, 0.0125, i) for i in (0, 0.2, 0.4)])
    >>> result = identify(manifest, "bingham")
    >>> len(result.tests), result.max_nrmse < 0.02
    (3, True)
    """
    say = progress or (lambda _msg: None)
    # user errors in the fit settings fail before any file is read (exit code 2 in the CLI)
    _check_settings(model, model_options, start, bounds, fixed, multistart, max_nfev)
    compare_list = (
        [c.strip() for c in compare.split(",")] if isinstance(compare, str) else list(compare)
    )
    compare_list = [c for c in compare_list if c and c != model]
    for c in compare_list:
        fit_model(c)
    band_list = parse_bands(bands)
    if not poor_fit > 0:
        raise ValidationError(f"poor_fit must be > 0; got {poor_fit!r}")
    options = PreprocessOptions(
        points_per_cycle=points_per_cycle,
        remove_offset=remove_offset,
        max_cycles=max_cycles,
        peak_velocity=peak_velocity,
        force_delay=force_delay,
        stroke_tolerance=stroke_tolerance,
    )
    say("reading the manifest")
    man = read_manifest(manifest, columns=columns, units=units, current_pattern=current_pattern)
    say(f"reading and pre-processing {len(man)} tests")
    if current_gain is not None and not (
        isinstance(current_gain, int | float) and math.isfinite(current_gain) and current_gain > 0
    ):
        raise ValidationError(f"--gain must be a number > 0 [A/V]; got {current_gain!r}")
    tests = load_campaign(man, options, current_gain=current_gain)
    usable = [t for t in tests if t.loop is not None]
    if not usable:
        first = "; ".join(f"{t.file}: {t.message}" for t in tests[:3])
        raise ValidationError(
            f"none of the {len(tests)} tests in {Path(manifest).name} could be used ({first}"
            + (" ..." if len(tests) > 3 else "")
            + ")"
        )
    today = _dt.date.today().isoformat()
    source = f"fitted by mrsuspension identify from {manifest} on {today}"
    groups: list[tuple[BandFit, list[TestOutcome]]] = []
    rows: list[TestOutcome] = []
    if band_list is None:
        groups.append((BandFit("all", 0.0, math.inf), usable))
        rows = list(tests)
    else:
        groups = [(BandFit(f"{lo:g}-{hi:g} Hz", lo, hi), []) for lo, hi in band_list]
        for t in tests:
            if t.loop is None:
                rows.append(t)
                continue
            assert t.frequency is not None
            inside = [(b, m) for b, m in groups if b.low <= t.frequency <= b.high]
            if not inside:
                t.status = "error"
                t.message = (
                    f"frequency {t.frequency:g} Hz is outside every band "
                    f"({', '.join(b.label for b, _ in groups)})"
                )
                rows.append(t)
            for b, members in inside:
                copy = TestOutcome(**{**t.__dict__, "notes": list(t.notes), "compare": {},
                                      "compare_forces": {}})  # fmt: skip
                copy.band = b.label
                members.append(copy)
                rows.append(copy)
    for band, members in groups:
        if not members:
            band.error = "no test in this band"
            continue
        loops = [t.loop for t in members if t.loop is not None]
        tag = "" if band.label == "all" else f" ({band.label})"
        set_name = (name or f"{model}-fitted") + (
            "" if band.label == "all" else f"-{band.label.replace(' ', '')}"
        )
        say(f"fitting {model}{tag} to {len(loops)} tests")
        try:
            band.result = fit_loops(
                loops, model, start=start, bounds=bounds, fixed=fixed,
                model_options=model_options, multistart=multistart, seed=seed,
                max_nfev=max_nfev, name=set_name, source=source,
            )  # fmt: skip
        except MRSuspensionError as exc:
            band.error = str(exc)
            for t in members:
                t.status = "fit-failed"
                t.message = f"the {model} fit{tag} failed: {exc}"
            continue
        _apply_fit(band, members, model, poor_fit)
        for other in compare_list:
            say(f"fitting {other}{tag} for comparison")
            try:
                res = fit_loops(loops, other, seed=seed, source=source,
                                name=f"{other}-fitted")  # fmt: skip
            except MRSuspensionError as exc:
                band.compare[other] = str(exc)
                for t in members:
                    t.compare[other] = None
                continue
            band.compare[other] = res
            for t in members:
                t.compare[other] = None
            for k, idx in enumerate(res.loop_index):
                members[idx].compare[other] = float(res.nrmse[k])
                members[idx].compare_forces[other] = res.model_forces[k]
    man_notes = list(man.notes)
    result = IdentificationResult(
        manifest=str(manifest),
        model=model,
        tests=rows,
        fits=[b for b, _ in groups],
        compare_models=tuple(compare_list),
        notes=man_notes,
        created=_dt.datetime.now().isoformat(timespec="seconds"),
        settings={
            "columns": columns,
            "units": units,
            "current_pattern": current_pattern,
            "points_per_cycle": points_per_cycle,
            "remove_offset": remove_offset,
            "max_cycles": max_cycles,
            "peak_velocity": peak_velocity,
            "force_delay": force_delay,
            "stroke_tolerance": stroke_tolerance,
            "start": None if start is None else str(getattr(start, "name", start)),
            "bands": band_list,
            "multistart": multistart,
            "seed": seed,
            "model_options": dict(model_options or {}),
            "current_gain": current_gain,
        },
    )
    for band, _ in groups:
        if band.result is not None:
            result.notes.extend(f"{band.label}: {n}" for n in _fit_notes(band.result))
    say("done")
    return result


def _check_settings(
    model: str,
    model_options: Mapping[str, Any] | None,
    start: Any,
    bounds: BoundsSpec | None,
    fixed: FixedSpec | None,
    multistart: int | None,
    max_nfev: int | None,
) -> None:
    """Raise ValidationError for fit settings that no data could make right."""
    spec = fit_model(model, model_options)
    damper = spec.damper
    if start is not None:
        pset = _parameters.resolve(start, model=damper.name)
        if pset.model not in damper.accepts:
            raise ValidationError(
                f"start set {pset.name!r} is for model {pset.model!r}; model {model!r} "
                f"starts from sets of: {', '.join(damper.accepts)}"
            )
    names = list(damper.parameter_rules)
    fixed_names = list(fixed.keys()) if isinstance(fixed, Mapping) else list(fixed or [])
    for key in [*fixed_names, *(bounds or {})]:
        if key not in names:
            raise unknown_name(f"parameter of model {model!r}", key, names)
    for what, value, most in (("multistart", multistart, 1000), ("max_nfev", max_nfev, 100_000)):
        if value is not None:  # bounded: each start or evaluation fits every test once
            check_count(what, value, 1, most, why=" (each refits every test)")


def _fit_notes(res: FitResult) -> list[str]:
    notes = []
    if res.at_bounds:
        notes.append(
            f"parameters at a bound: {', '.join(res.at_bounds)} (widen with bounds= or check "
            "the data)"
        )
    if not res.converged:
        notes.append(f"the fit did not converge: {res.message}")
    return notes


def _apply_fit(band: BandFit, members: list[TestOutcome], model: str, poor_fit: float) -> None:
    res = band.result
    assert res is not None
    for k, why in res.excluded.items():
        members[k].status = "fit-failed"
        members[k].message = f"left out of the {model} fit: {why}"
    nrmse_all = [float(q) for q in res.nrmse]
    median = float(np.median(nrmse_all)) if nrmse_all else math.nan
    for k, idx in enumerate(res.loop_index):
        t = members[idx]
        assert t.loop is not None
        fm = res.model_forces[k]
        if not np.all(np.isfinite(fm)):
            t.status = "fit-failed"
            t.message = f"the fitted {model} model gives no finite force for this test"
            continue
        metrics = loop_metrics(t.loop, fm)
        t.nrmse = metrics["nrmse"]
        t.peak_force_error = metrics["peak_force_error"]
        t.energy_error = metrics["energy_error"]
        t.model_force = fm
        if not res.converged:
            t.status = "warning"
            t.message = (
                f"the fit did not converge ({res.message}); the parameters are the best found"
            )
        if t.nrmse > poor_fit:
            t.status = "poor-fit"
            t.message = (
                f"poor fit: NRMSE {100 * t.nrmse:.1f} % (campaign median {100 * median:.1f} %); "
                "check this test's current, units and sign"
            )


#: models that can be fitted (for the CLI help)
MODEL_NAMES = tuple(FIT_MODELS)
