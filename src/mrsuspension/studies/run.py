"""Running a study: a local process pool or a Dask cluster, cached by content and code.

The cache key (:func:`cache_key`) hashes the study's content and a fingerprint of the
package code that computes it (:func:`code_fingerprint`), so editing a measure or the
engine in an editable install misses the cache instead of returning stale numbers.

Every run is reduced to its measures in the worker (``result.measures(road_peak=...)``),
so only a few numbers travel back. Results are a :class:`StudyResult` wrapping an
:class:`xarray.Dataset` (dimensions = the study's grid fields, cases and ``frequency``;
variables = measures), saved as NetCDF (``.nc``) or CSV.
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import json
import os
import time
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from mrsuspension._batch import Job
from mrsuspension._progress import progress_bar as _bar
from mrsuspension.engine.batch import run_batch
from mrsuspension.engine.result import SimulationResult
from mrsuspension.engine.simulate import MeasuresOf, run_quietly
from mrsuspension.engine.vehicle_result import SEAT_MEASURES, WithSeatMeasures
from mrsuspension.errors import ValidationError
from mrsuspension.measures.shock import DEFAULT_ROAD_PEAK, RoadPeak
from mrsuspension.studies.study import PROGRESS_POINTS, SCHEDULER_TIMEOUT, Study

if TYPE_CHECKING:
    import pandas as pd
    import xarray as xr

__all__ = [
    "StudyCacheWarning",
    "StudyResult",
    "cache_key",
    "code_fingerprint",
    "default_cache_dir",
    "reducer_of",
    "run_study",
]

Progress = Callable[[int, int], None]

#: seconds an interrupted or finished study waits for its own Dask client to close
DASK_CLOSE_TIMEOUT = 2.0
#: subpackages a study's computation never reaches: left out of :func:`code_fingerprint`
_NOT_COMPUTING = frozenset({"cli", "monitor", "report", "hil", "identify"})
#: the files that make up the code (and the parameter sets shipped as data)
_CODE_SUFFIXES = frozenset({".py", ".toml"})
_fingerprint: str | None = None  # a pure function of the installed files: once per process


class StudyCacheWarning(UserWarning):
    """A cached study result could not be read; it is recomputed and replaced."""


def code_fingerprint() -> str:
    """sha256 of the package code a study's computation can reach.

    Hashes the relative path and bytes of every ``.py`` and ``.toml`` file of the
    ``mrsuspension`` package except ``cli/``, ``monitor/``, ``report/``, ``hil/`` and
    ``identify/``. Computed once per process (about 550 kB to read).

    Returns
    -------
    str
        64 hexadecimal digits.

    Examples
    --------
    >>> len(code_fingerprint())
    64
    """
    global _fingerprint
    if _fingerprint is None:
        root = Path(__file__).resolve().parents[1]
        digest = hashlib.sha256()
        files = sorted(
            (p.relative_to(root).as_posix(), p)
            for p in root.rglob("*")
            if p.suffix in _CODE_SUFFIXES
            and p.is_file()
            and p.relative_to(root).parts[0] not in _NOT_COMPUTING
            and "__pycache__" not in p.parts
        )
        for rel, p in files:
            digest.update(rel.encode() + b"\0" + p.read_bytes() + b"\0")
        _fingerprint = digest.hexdigest()
    return _fingerprint


def cache_key(study: Study) -> str:
    """The study's cache key: its :meth:`~Study.content_hash` and :func:`code_fingerprint`.

    Parameters
    ----------
    study : Study
        The study.

    Returns
    -------
    str
        64 hexadecimal digits; the cache file is ``{key}.nc``.

    Examples
    --------
    >>> from mrsuspension.studies import Study
    >>> study = Study.from_dict({
    ...     "excitation": {"kind": "harmonic", "frequency": 5.0, "amplitude": 0.01},
    ...     "grid": {"controller.current": [0.0, 0.2]},
    ... })
    >>> cache_key(study) != study.content_hash()
    True
    """
    text = f"{study.content_hash()}:{code_fingerprint()}"
    return hashlib.sha256(text.encode()).hexdigest()


def default_cache_dir() -> Path:
    """``$MRSUSPENSION_CACHE/studies``, else ``~/.cache/mrsuspension/studies``."""
    root = os.environ.get("MRSUSPENSION_CACHE")
    base = Path(root) if root else Path.home() / ".cache" / "mrsuspension"
    return base / "studies"


@dataclass
class StudyResult:
    """The measures of every run of a study, as labelled arrays.

    Parameters
    ----------
    study : Study
        The study that produced them.
    dataset : xarray.Dataset
        One variable per measure over the study's dimensions.
    content_hash : str
        The study's :meth:`~mrsuspension.studies.Study.content_hash`.
    from_cache : bool
        True when read back from the cache instead of computed.
    run_time : float
        Wall time of the computation [s] (of the original run when cached).
    cache_file : Path, optional
        The cache file it was read from or written to (None without a cache).
    """

    study: Study
    dataset: xr.Dataset
    content_hash: str
    from_cache: bool = False
    run_time: float = 0.0
    cache_file: Path | None = None

    def __getitem__(self, measure: str) -> xr.DataArray:
        """One measure over the study's dimensions; ``"<measure>.<corner>"`` selects one
        corner of a vehicle's per-corner measure (``result["DLC.front_left"]``)."""
        ds = self.dataset
        if measure not in ds.data_vars:
            base, dot, corner = measure.rpartition(".")
            per_corner = dot and base in ds.data_vars and "corner" in ds[base].dims
            if per_corner and corner in set(map(str, ds["corner"].values)):
                return ds[base].sel(corner=corner)
            from mrsuspension.errors import unknown_name

            names = [*map(str, ds.data_vars)]
            if "corner" in ds.dims:
                corners = [str(c) for c in ds["corner"].values]
                names += [
                    f"{n}.{c}" for n in ds.data_vars if "corner" in ds[n].dims for c in corners
                ]
            raise unknown_name("measure", measure, names)
        return ds[measure]

    def __repr__(self) -> str:
        dims = " x ".join(f"{d} ({n})" for d, n in self.dataset.sizes.items()) or "one point"
        cached = ", from cache" if self.from_cache else ""
        return (
            f"StudyResult({self.study.name!r}: {len(self.study)} runs over {dims}; "
            f"{len(self.dataset.data_vars)} measures{cached})"
        )

    def _repr_html_(self) -> str:
        """A notebook's view: the study, its dimensions and measures with units, then
        the data set itself (folded)."""
        from mrsuspension._notebook import html_table

        ds = self.dataset
        rows: list[tuple[str, str]] = [("study", self.study.name)]
        if self.study.description:
            rows.append(("description", self.study.description))
        rows.append(("runs", f"{len(self.study)}"))
        for d, n in ds.sizes.items():
            field = ds[d].attrs.get("field") if d in ds.coords else None
            rows.append((f"dimension {d}", f"{n}" + (f" ({field})" if field else "")))
        rows.append(
            ("run time", f"{self.run_time:.3g} s" + (" (from cache)" if self.from_cache else ""))
        )
        head = html_table(rows, caption="StudyResult")
        measures = html_table(
            (
                (str(n), ds[n].attrs.get("units", ""), " x ".join(map(str, ds[n].dims)),
                 ds[n].attrs.get("long_name", ""))
                for n in ds.data_vars
            ),
            header=("measure", "unit", "dimensions", "description"),
        )  # fmt: skip
        return (
            f"<div>{head}{measures}<details><summary>data set</summary>"
            f"{ds._repr_html_()}</details></div>"
        )

    def to_xarray(self) -> xr.Dataset:
        """The results as an :class:`xarray.Dataset` (CF-style ``units`` and ``long_name``).

        Dimensions: the ``[grid]`` fields named without dots (``controller_gain``; the
        dotted field is the coordinate's ``field`` attribute), the ``[cases]`` tables,
        ``frequency`` for a sweep, and ``corner`` for a vehicle's per-corner measures
        (``ds["DLC"].sel(corner="front_left")``).
        """
        return self.dataset

    def to_pandas(self) -> pd.DataFrame:
        """Long table: one row per run, a column per dimension and per measure.

        A vehicle's per-corner measure is one column per corner (``"DLC.front_left"``);
        the units are in ``df.attrs["units"]`` (column -> unit) and the dotted field of
        each grid column in ``df.attrs["fields"]``.
        """
        ds = self.dataset
        flat = ds.drop_dims("corner") if "corner" in ds.dims else ds
        units = {str(n): str(ds[n].attrs["units"]) for n in ds.variables if "units" in ds[n].attrs}
        kept = set(self.study.measures)
        if "corner" in ds.dims:
            columns = {
                f"{name}.{c}": ds[name].sel(corner=c, drop=True)
                for name in ds.data_vars
                if "corner" in ds[name].dims
                for c in map(str, ds["corner"].values)
            }
            if kept & set(columns):  # the corners' measures the study kept, not the NaN rest
                columns = {k: v for k, v in columns.items() if k in kept}
            for key in columns:
                base = key.rpartition(".")[0]
                if base in units:
                    units[key] = units[base]
            flat = flat.assign(columns)
        df = flat.to_dataframe().reset_index()
        dims = [c for c in df.columns if c not in flat.data_vars]
        order = [m for m in self.study.measures if m in df.columns]
        df = df[[*dims, *order, *(c for c in df.columns if c not in dims and c not in order)]]
        df.attrs["units"] = {c: units[c] for c in map(str, df.columns) if c in units}
        df.attrs["fields"] = {
            str(n): str(ds[n].attrs["field"]) for n in ds.coords if "field" in ds[n].attrs
        }
        return df

    def save(self, path: str | Path) -> Path:
        """Write ``.nc`` (NetCDF, with the study in the attributes and ``units`` on every
        measure and numeric field) or ``.csv`` (+ ``.json``; headers ``name [unit]``)."""
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        suffix = path.suffix.lower()
        if suffix == ".nc":
            self.dataset.to_netcdf(path)
        elif suffix == ".csv":
            from mrsuspension._notebook import with_unit_headers

            with_unit_headers(self.to_pandas()).to_csv(path, index=False)
            path.with_suffix(".json").write_text(
                json.dumps(
                    {"study": self.study.describe(), "content_hash": self.content_hash},
                    indent=2,
                    default=str,
                )
            )
        else:
            raise ValidationError(
                f"cannot save study results as {suffix!r}; use .nc (NetCDF) or .csv"
            )
        return path


# -- executors ----------------------------------------------------------------------------
def _measures(result: SimulationResult, road_peak: RoadPeak) -> dict[str, Any]:
    """``result.measures(road_peak=...)``, the reducer (module level, so it pickles)."""
    return result.measures(road_peak=road_peak)


def reducer_of(study: Study) -> MeasuresOf | WithSeatMeasures:
    """What each run of ``study`` is reduced to: its measures, in the kernel where the
    model can (:class:`~mrsuspension.engine.simulate.MeasuresOf`), or with the seat's
    ISO 2631-1 measures when the study asks for one
    (:class:`~mrsuspension.engine.vehicle_result.WithSeatMeasures`: from the time history).

    Examples
    --------
    >>> from mrsuspension.studies import Study
    >>> base = {"vehicle": {"model": "half-car"},
    ...         "excitation": {"kind": "road", "iso_class": "C", "length": 20.0},
    ...         "grid": {"controller.current": [0.0, 0.2]}}
    >>> type(reducer_of(Study.from_dict(base))).__name__
    'MeasuresOf'
    >>> type(reducer_of(Study.from_dict({**base, "study": {"measures": ["seat_z"]}}))).__name__
    'WithSeatMeasures'
    """
    if set(study.measures) & set(SEAT_MEASURES):
        return WithSeatMeasures(study.road_peak)
    return MeasuresOf(study.road_peak)


def _run_point(
    job: Job,
    road_peak: RoadPeak = DEFAULT_ROAD_PEAK,
    reduce: Callable[[SimulationResult], dict[str, Any]] | None = None,
) -> dict[str, Any]:
    """One run reduced to its measures (module level, so workers can unpickle it)."""
    result = run_quietly(job.simulation, job.settings)
    return _measures(result, road_peak) if reduce is None else reduce(result)


def _run_local(
    jobs: Sequence[Job],
    workers: int | None,
    progress: Progress | None,
    road_peak: RoadPeak = DEFAULT_ROAD_PEAK,
    reduce: Callable[[SimulationResult], dict[str, Any]] | None = None,
) -> list[dict[str, Any]]:
    """The engine's batch front door (:func:`~mrsuspension.engine.batch.run_batch`), any
    model: runs reduced to their measures inside the kernels where the model can
    (``reduce``: another reducer, e.g. :class:`WithSeatMeasures`)."""
    return run_batch(
        [job.simulation for job in jobs],
        settings=[job.settings for job in jobs],
        workers=workers,
        progress=progress,
        reduce=MeasuresOf(road_peak) if reduce is None else reduce,
    )


def _run_dask(
    jobs: Sequence[Job],
    executor: Any,
    progress: Progress | None,
    road_peak: RoadPeak = DEFAULT_ROAD_PEAK,
    scheduler_timeout: float = SCHEDULER_TIMEOUT,
    reduce: Callable[[SimulationResult], dict[str, Any]] | None = None,
) -> list[dict[str, Any]]:
    """The same reducer on a Dask cluster (an address or a ``distributed.Client``)."""
    from mrsuspension.errors import require_extra

    require_extra("distributed", "running a study on a Dask scheduler")
    from dask.distributed import Client, as_completed

    own = not isinstance(executor, Client)
    if own:  # a bounded connect and handshake: Dask's own can wait minutes on a mute server
        from mrsuspension.studies.study import check_scheduler

        executor = check_scheduler(str(executor), scheduler_timeout)
    client = Client(executor, timeout=scheduler_timeout) if own else executor
    futures: list[Any] = []
    try:
        futures = client.map(
            functools.partial(_run_point, road_peak=road_peak, reduce=reduce),
            list(jobs),
            pure=False,
        )
        index = {f.key: k for k, f in enumerate(futures)}
        out: list[dict[str, Any]] = [{} for _ in jobs]
        for n, fut in enumerate(as_completed(futures), start=1):
            out[index[fut.key]] = fut.result()
            if progress:
                progress(n, len(jobs))
        return out
    except BaseException:  # Ctrl-C, SIGTERM or a failed run: the cluster stops computing
        with contextlib.suppress(Exception):
            client.cancel(futures)
        raise
    finally:
        if own:  # bounded: an interrupted study does not wait for a slow scheduler
            with contextlib.suppress(Exception):
                client.close(timeout=DASK_CLOSE_TIMEOUT)


# -- assembling ---------------------------------------------------------------------------
def _dataset(study: Study, rows: Sequence[dict[str, Any]], run_time: float) -> xr.Dataset:
    import xarray as xr

    shape = study.shape
    data_vars = {}
    for m in study.measures:
        values = np.array([float(r.get(m, np.nan)) for r in rows], dtype=float).reshape(shape)
        data_vars[m] = (study.dims, values)
    coords: dict[str, Any] = {}
    for name, labels in study.coords.items():
        coords[name] = (name, np.asarray(labels))
    if study.frequencies is not None:
        sweep = study.scenarios[0].excitation
        coords["amplitude"] = ("frequency", np.asarray(sweep.amplitudes))  # type: ignore[union-attr]
        coords["frequency"] = ("frequency", np.asarray(study.frequencies), {"units": "Hz"})
    from mrsuspension.studies.units import add_units, conventional

    ds = conventional(add_units(xr.Dataset(data_vars, coords=coords)))
    ds.attrs["study"] = json.dumps(study.describe(), default=str)
    ds.attrs["content_hash"] = study.content_hash()
    ds.attrs["code_fingerprint"] = code_fingerprint()
    ds.attrs["run_time_s"] = float(run_time)
    if study.has_pulses:
        ds.attrs["road_peak"] = study.road_peak  # the SAR_s / SAR_u denominators
    from mrsuspension import __version__

    ds.attrs["mrsuspension_version"] = __version__
    return ds


def run_study(
    study: Study | str | Path,
    *,
    executor: Any = "local",
    workers: int | None = None,
    progress: bool | Progress = True,
    cache_dir: str | Path | bool | None = None,
    scheduler_timeout: float = SCHEDULER_TIMEOUT,
) -> StudyResult:
    """Run every grid point of a study; measures as labelled arrays.

    Parameters
    ----------
    study : Study or path
        A study, or a study TOML file to load.
    executor : "local", str or dask.distributed.Client
        ``"local"`` (default): the engine's process pool
        (:func:`~mrsuspension.engine.batch.run_batch`); a scheduler address such as
        ``"tcp://10.0.0.5:8786"`` or a ``Client``: the same reducer on a Dask cluster.
    workers : int, optional
        Local processes (None: one per core; 1: this process). Ignored for Dask.
    progress : bool or callable
        A rich progress bar on stderr (True, default), none (False), or a
        ``progress(done, total)`` callback.
    cache_dir : path, None or False
        Folder of cached results, keyed by :func:`cache_key` (the study and the code);
        None: the :func:`default_cache_dir`; False: no cache. The folder is checked
        before any computing; an unreadable cache file is recomputed and replaced, with
        a :class:`StudyCacheWarning` naming it.
    scheduler_timeout : float
        Seconds [s] a scheduler address is given to accept the connection, and again to
        answer it (:func:`~mrsuspension.studies.study.check_scheduler`; 10 s by default).

    Returns
    -------
    StudyResult
        ``from_cache`` tells whether it was read back rather than computed, and
        ``cache_file`` from (or to) which file.

    Raises
    ------
    ValidationError
        The cache folder is not a folder or cannot be written (before any computing).

    Examples
    --------
    >>> from mrsuspension.studies import Study
    >>> study = Study.from_dict({
    ...     "excitation": {"kind": "harmonic", "frequency": 5.0, "amplitude": 0.01},
    ...     "simulation": {"dt": 5e-4},
    ...     "grid": {"controller.current": [0.0, 0.2]},
    ...     "study": {"measures": ["mean_current"]},
    ... })
    >>> res = run_study(study, workers=1, progress=False, cache_dir=False)
    >>> [round(float(v), 3) for v in res["mean_current"]]
    [0.0, 0.2]
    """
    if not isinstance(study, Study):
        study = Study.load(study)
    digest = study.content_hash()
    cache_file: Path | None = None
    if cache_dir is not False:
        folder = default_cache_dir() if cache_dir is None or cache_dir is True else Path(cache_dir)
        cache_file = folder / f"{cache_key(study)}.nc"
        cached = _read_cache(cache_file)
        if cached is not None:
            return StudyResult(
                study,
                cached,
                digest,
                from_cache=True,
                run_time=float(cached.attrs.get("run_time_s", 0)),
                cache_file=cache_file,
            )
        _check_cache_folder(folder)
    total = len(study)
    with _bar(progress, f"study {study.name} ({total} runs)") as tick:
        if progress is True and tick is not None and total > PROGRESS_POINTS:
            tick(0, total, "preparing the runs")  # a big study: about 0.2 ms a run
        jobs = [
            Job(sim, settings)
            for sim, settings in zip(study.simulations(), study.run_settings(), strict=True)
        ]
        start = time.perf_counter()
        reduce = reducer_of(study)
        if (isinstance(executor, str) and executor == "local") or executor is None:
            rows = _run_local(jobs, workers, tick, study.road_peak, reduce)
        else:
            rows = _run_dask(jobs, executor, tick, study.road_peak, scheduler_timeout, reduce)
    elapsed = time.perf_counter() - start
    ds = _dataset(study, rows, elapsed)
    if cache_file is not None:
        _write_cache(ds, cache_file)
    return StudyResult(study, ds, digest, from_cache=False, run_time=elapsed, cache_file=cache_file)


# -- the cache ----------------------------------------------------------------------------
def _read_cache(path: Path) -> xr.Dataset | None:
    """The cached dataset, or None (missing; unreadable: warned, to be replaced)."""
    if not path.is_file():
        return None
    import xarray as xr

    try:
        with xr.open_dataset(path) as cached:
            from mrsuspension.studies.units import conventional

            return conventional(cached.load())  # a file of an earlier layout: today's
    except Exception as exc:  # any unreadable file is recomputed
        warnings.warn(
            f"the study cache file {path} is unreadable ({type(exc).__name__}); recomputing "
            "and replacing it (mrsus cache clear empties the cache)",
            StudyCacheWarning,
            stacklevel=3,
        )
        return None


def _check_cache_folder(folder: Path) -> None:
    """Raise before any computing if the cache folder cannot hold a new file."""
    from mrsuspension._output import check_writable_folder

    check_writable_folder(
        folder, "the study cache folder", hint="set MRSUSPENSION_CACHE or use --no-cache"
    )


def _write_cache(ds: xr.Dataset, path: Path) -> None:
    """Write through a temporary sibling and rename: readers never see half a file."""
    tmp = path.with_suffix(f".{os.getpid()}.tmp")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        ds.to_netcdf(tmp)
        tmp.replace(path)
    except OSError as exc:  # the result is computed: keep it, say the cache missed it
        warnings.warn(
            f"could not write the study cache file {path} ({exc})", StudyCacheWarning, stacklevel=3
        )
    finally:
        tmp.unlink(missing_ok=True)
