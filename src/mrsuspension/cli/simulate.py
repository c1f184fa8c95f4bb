"""``mrsus simulate`` and ``mrsus sweep``: run scenario files from the command line.

Plain typer command functions; :mod:`mrsuspension.cli` registers them. The engine,
scenarios and plots load inside the commands, so ``mrsus --help`` stays fast. Input
errors and diverging runs are reported in one line on stderr with exit code 2.
"""

from __future__ import annotations

import csv
import gc
import importlib.util
import json
import math
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer

from mrsuspension._docs import doc
from mrsuspension._jsonsafe import to_jsonable
from mrsuspension._output import (
    check_output_folder,
    prepare_output,
    relocate_files,
    relocated,
)
from mrsuspension.cli.errors import user_errors
from mrsuspension.errors import ValidationError, check_count, check_range

if TYPE_CHECKING:
    from mrsuspension.engine.result import SimulationResult
    from mrsuspension.excitation import Harmonic, SteppedSweep
    from mrsuspension.scenario import Scenario

__all__ = [
    "measure_unit",
    "parse_formats",
    "parse_frequencies",
    "simulate_command",
    "sweep_command",
]

#: measures shown in the transmissibility plot of a sweep
SWEEP_PLOT = ("T_as", "T_au", "T_dr", "DLC")
#: the defaults the help texts name (the library's own, kept here so that ``--help`` does
#: not import the engine; ``tests/integration/test_cli_startup.py`` checks they agree)
DEFAULT_ROAD_PEAK = "after-onset"  # measures.shock.DEFAULT_ROAD_PEAK
DEFAULT_SWEEP_POINTS = 30  # excitation.DEFAULT_SWEEP_POINTS
#: ``--format`` of ``mrsus simulate``: result file suffix by format name
RESULT_FORMATS = {"csv": ".csv", "nc": ".nc", "parquet": ".parquet"}
DEFAULT_RESULT_FORMATS = "csv,nc"

ScenarioArg = Annotated[
    Path,
    typer.Argument(
        metavar="SCENARIO", help=f"scenario TOML file (see {doc('scenarios')})", show_default=False
    ),
]
JsonOpt = Annotated[bool, typer.Option("--json", help="print the measures as JSON on stdout")]


# -- helpers ------------------------------------------------------------------------------
def _run_row(excitation: Harmonic, measures: Mapping[str, Any]) -> dict[str, Any]:
    """``frequency``, ``amplitude`` and the harmonic measures of one sweep run."""
    return {
        "frequency": float(excitation.frequency),
        "amplitude": float(excitation.amplitude),
        **measures,
    }


def parse_frequencies(text: str) -> list[float]:
    """Parse ``--frequencies``: a comma list (``"1,1.5,4"``) or ``"log:N:fmin:fmax"``.

    Examples
    --------
    >>> parse_frequencies("1, 2.5")
    [1.0, 2.5]
    >>> [round(f, 3) for f in parse_frequencies("log:3:1:100")]
    [1.0, 10.0, 100.0]
    """
    text = text.strip()
    if text.lower().startswith("log:"):
        parts = text.split(":")
        if len(parts) != 4:
            raise ValidationError(
                f"--frequencies log form is 'log:N:fmin:fmax' (e.g. log:30:0.5:15); got {text!r}"
            )
        try:
            n = int(parts[1])
            lo, hi = float(parts[2]), float(parts[3])
        except ValueError:
            raise ValidationError(
                f"--frequencies 'log:N:fmin:fmax' needs an integer N and numbers; got {text!r}"
            ) from None
        from mrsuspension.excitation import log_frequencies

        try:
            return [float(f) for f in log_frequencies(n, lo, hi)]
        except ValidationError as exc:
            raise ValidationError(f"--frequencies/-f {text!r}: {exc}") from None
    try:
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise ValidationError(
            f"--frequencies must be comma-separated numbers [Hz] or 'log:N:fmin:fmax'; got {text!r}"
        ) from None
    if not values:
        raise ValidationError("--frequencies needs at least one frequency [Hz]")
    check_range("--frequencies", values, 0.0, None, unit="Hz", low_inclusive=False)
    return values


def _write(out: Path, write: Callable[[Path], Any]) -> None:
    """Create ``out`` and write into it, reporting file-system errors as user errors."""
    try:
        out.mkdir(parents=True, exist_ok=True)
        write(out)
    except OSError as exc:
        raise ValidationError(f"cannot write to {str(out)!r}: {exc}") from None


def parse_formats(text: str) -> list[str]:
    """Parse ``--format``: a comma list of ``csv``, ``nc`` and ``parquet``.

    Examples
    --------
    >>> parse_formats("csv, parquet")
    ['csv', 'parquet']
    """
    names = [n.strip().lower() for n in text.split(",") if n.strip()]
    bad = [n for n in names if n not in RESULT_FORMATS]
    if bad or not names:
        raise ValidationError(
            f"--format must be a comma list of {', '.join(RESULT_FORMATS)}; got {text!r}"
        )
    if "parquet" in names:
        from mrsuspension.engine.result import require_pyarrow

        require_pyarrow()
    return list(dict.fromkeys(names))


def _title(source: Path, scenario: Mapping[str, Any], what: str | None = None) -> str:
    """A plot title: the scenario file, then the controller and the excitation (or ``what``).

    Examples
    --------
    >>> _title(Path("runs/a.toml"), {"controller": {"law": "passive", "current": 0.1},
    ...        "excitation": {"kind": "harmonic", "frequency": 1.5}}, "frequency response")
    'a.toml: passive (current 0.1), frequency response'
    """
    from mrsuspension.engine.result import describe_run

    if what is not None:
        scenario = {k: v for k, v in scenario.items() if k != "excitation"}
    text = describe_run(scenario)
    text = what if text == "simulation" and what else ", ".join(filter(None, [text, what]))
    return f"{source.name}: {text}"


def _write_sweep(out: Path, rows: Sequence[Mapping[str, Any]], title: str) -> list[Path]:
    """``sweep.csv`` (headers ``name [unit]``) and ``sweep.png`` (T_as, T_au, T_dr, DLC)
    titled ``title`` (the scenario)."""
    from mrsuspension.engine.result import measure_label

    files = [out / "sweep.csv", out / "sweep.png"]
    keys = list(rows[0])
    with files[0].open("w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow([_label(k) for k in keys])
        for row in rows:
            writer.writerow([row[k] for k in keys])
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    freqs = [r["frequency"] for r in rows]
    panels = _sweep_panels(rows[0])  # T_as, T_au, T_dr, DLC; a vehicle: body, per corner
    fig, axes = plt.subplots(len(panels), 1, sharex=True, figsize=(7, 2.0 * len(panels)))
    for ax, group in zip(axes, panels, strict=True):
        for key in group:
            values = [r[key] if r[key] is not None else math.nan for r in rows]
            ax.plot(freqs, values, "o-", ms=3, lw=1, label=key.partition(".")[2] or None)
        name = group[0].partition(".")[0] if len(group) > 1 else group[0]
        ax.set_ylabel(measure_label(name) if name in SWEEP_PLOT else _label(name))
        if len(group) > 1:
            ax.legend(fontsize=7, ncol=len(group))
        ax.set_xscale("log")
        ax.grid(True, which="both", alpha=0.3)
    axes[-1].set_xlabel("frequency [Hz]")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(files[1], dpi=120)
    plt.close(fig)
    return files


def _write_single(
    out: Path,
    result: SimulationResult,
    measures: Mapping[str, Any],
    formats: Sequence[str] = ("csv", "nc"),
    title: str | None = None,
) -> list[Path]:
    """``result.<format>`` per format (csv + ``result.json``; nc if xarray), plot (titled
    ``title``, default the run's controller and excitation), measures."""
    files: list[Path] = []
    for name in formats:
        if name == "nc" and importlib.util.find_spec("xarray") is None:
            continue
        files.append(result.save(out / f"result{RESULT_FORMATS[name]}"))
        if name == "csv":
            files.append(out / "result.json")
    import matplotlib.pyplot as plt

    fig = result.plot(title=title)
    fig.savefig(out / "result.png", dpi=120)
    plt.close(fig)
    files.append(out / "result.png")
    (out / "measures.json").write_text(json.dumps(to_jsonable(measures), indent=2))
    files.append(out / "measures.json")
    return files


@contextmanager
def _collector_paused() -> Iterator[None]:
    """Pause the cyclic garbage collector while the engine loads, then freeze what loaded.

    Importing numba, scipy and the package and loading the cached kernels creates some
    130 000 tracked objects; the collector walked them ~300 times while they were created
    (70 ms of a 0.8 s ``mrsus simulate``, whole process, warm cache) and once more at
    interpreter exit. Nothing loaded here is garbage, so the collector waits until it is
    all loaded and then :func:`gc.freeze` moves it out of every later collection (the
    run's own objects are still collected).
    """
    was_enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        gc.freeze()
        if was_enabled:
            gc.enable()


def _spare_teardown() -> None:
    """Keep the interpreter's exit from walking the objects the run created (freeze them)."""
    gc.freeze()


def _echo_measures(measures: Mapping[str, Any]) -> None:
    """One ``name = value [unit]`` line per measure (a note such as ``road_peak``: no unit)."""
    width = max(26, *(len(k) for k in measures)) if measures else 26  # vehicle: long names
    for key, value in measures.items():
        text = "n/a" if value is None else f"{value:.6g}" if isinstance(value, float) else value
        unit = measure_unit(key)
        typer.echo(f"{key:>{width}} = {text!s:<12} {'' if unit is None else f'[{unit}]'}".rstrip())


def _clamp_note(fractions: Sequence[float | None]) -> None:
    """Say on stderr when runs sat at the peak-velocity clamp (model reference, section 2.4)."""
    from mrsuspension.engine.result import CLAMP_WARN_FRACTION

    shares = [f for f in fractions if f is not None]
    hit = [f for f in shares if f > CLAMP_WARN_FRACTION]
    if not hit:
        return
    runs = "the run" if len(shares) == 1 else f"{len(hit)} of {len(shares)} runs"
    typer.echo(
        f"note: in {runs} the peak-velocity estimate v_m sat at its upper clamp for "
        f"{100 * max(hit):.0f} % of the time{'' if len(shares) == 1 else ' at most'} "
        "(vm_clamp_fraction): the damper model ran beyond its identified velocity range and "
        f"its forces there are an extrapolation ({doc('damper-models')})",
        err=True,
    )


def _current_note(scn: Scenario, rows: Sequence[Mapping[str, Any]]) -> None:
    """Say on stderr when the law left the current near zero (:meth:`Scenario.current_note`)."""
    note = scn.current_note(rows)
    if note is not None:
        typer.echo(f"note: {note}", err=True)


def _echo_rows(rows: Sequence[Mapping[str, Any]]) -> None:
    """A table, one row per run, headers ``name [unit]`` (columns as wide as needed)."""
    keys = [k for k in rows[0] if k != "amplitude"]
    labels = [_label(k) for k in keys]
    widths = [max(12, len(label)) for label in labels]
    typer.echo(" ".join(f"{label:>{w}}" for label, w in zip(labels, widths, strict=True)))
    for row in rows:
        typer.echo(
            " ".join(
                f"{'n/a':>{w}}" if row[k] is None else f"{row[k]:{w}.5g}"
                for k, w in zip(keys, widths, strict=True)
            )
        )


# -- commands -----------------------------------------------------------------------------
def simulate_command(
    scenario: ScenarioArg,
    out: Annotated[
        Path | None,
        typer.Option(
            "--out", "-o", help="folder for the result (see --format), a plot and measures.json"
        ),
    ] = None,
    formats: Annotated[
        str | None,
        typer.Option(
            "--format",
            help="with --out, a single run's result files: a comma list of csv (+ JSON "
            "scenario), nc (NetCDF) and parquet (needs the 'data' extra; scenario and units "
            f"in its metadata) [default: {DEFAULT_RESULT_FORMATS}]",
            show_default=False,
        ),
    ] = None,
    as_json: JsonOpt = False,
    duration: Annotated[
        float | None,
        typer.Option("--duration", help="simulated time of each run [s] (overrides the file)"),
    ] = None,
    road_peak: Annotated[
        str,
        typer.Option(
            "--road-peak",
            help="pulse runs: the road acceleration peak that divides SAR_s and SAR_u: "
            "'after-onset' (after the pulse's onset jump; matches the dissertation's SAR_s) "
            "or 'onset' (the largest over the record: the onset jump, 4.854x larger)",
        ),
    ] = DEFAULT_ROAD_PEAK,
    force: Annotated[
        bool, typer.Option("--force", help="replace an --out folder holding other output")
    ] = False,
) -> None:
    """Run a scenario file and print its measures (model reference, section 9).

    A harmonic, pulse or road scenario prints one set of measures (``--json``: one
    object); a swept scenario prints one row per frequency (``--json``: a list of
    objects with ``frequency`` and ``amplitude`` added). A pulse run's measures include
    ``road_peak``, the definition ``--road-peak`` chose for the SAR denominators.
    """
    with user_errors():
        with _collector_paused():
            from mrsuspension._progress import progress_bar
            from mrsuspension.cli.compiling import notify_if_compiling
            from mrsuspension.excitation import Harmonic
            from mrsuspension.measures.shock import check_road_peak
            from mrsuspension.scenario import Scenario

            how = check_road_peak(road_peak)
            kinds = parse_formats(DEFAULT_RESULT_FORMATS if formats is None else formats)
            if formats is not None and out is None:
                raise ValidationError(f"--format {formats!r} needs --out DIR (the folder to write)")
            if out is not None:
                check_output_folder("--out", out, "simulate", force=force)
            notify_if_compiling()  # before the first kernel loads (the scenario's damper)
            scn = Scenario.load(scenario)
            if formats is not None and scn.is_sweep:
                raise ValidationError(
                    f"--format {formats!r} applies to single runs; a swept scenario writes "
                    "sweep.csv, sweep.png and measures.json"
                )
        files: list[Path] = []
        payload: Any
        with prepare_output(out, "simulate", force=force) as folder:  # before the run
            with progress_bar(scn.is_sweep and not as_json, "simulating") as progress:
                results = scn.run(duration=duration, workers=None, progress=progress)
            if scn.is_sweep:
                rows = [
                    to_jsonable(_run_row(exc, res.measures()))
                    for exc, res in zip(scn.excitations, results, strict=True)
                    if isinstance(exc, Harmonic)
                ]
                payload = rows
                if folder is not None:
                    title = _title(scenario, results[0].scenario, "frequency response")
                    _write(folder, lambda d: files.extend(_write_sweep(d, rows, title)))
                    measures = folder / "measures.json"
                    _write(folder, lambda _d: measures.write_text(json.dumps(rows, indent=2)))
                    files.append(measures)
            else:
                payload = to_jsonable(results[0].measures(road_peak=how))
                if folder is not None:
                    title = _title(scenario, results[0].scenario)
                    _write(
                        folder,
                        lambda d: files.extend(_write_single(d, results[0], payload, kinds, title)),
                    )
            if folder is not None and out is not None:
                relocate_files(folder, out)
                files = [Path(f) for f in relocated([str(f) for f in files], folder, out)]
    _clamp_note([getattr(r, "velocity_clamp_fraction", None) for r in results])
    _current_note(scn, payload if scn.is_sweep else [payload])
    _spare_teardown()
    if as_json:
        typer.echo(json.dumps(payload))
        return
    if scn.is_sweep:
        _echo_rows(payload)
    else:
        _echo_measures(payload)
    for f in files:
        typer.echo(f"wrote {f}")


def sweep_command(
    scenario: ScenarioArg,
    frequencies: Annotated[
        str | None,
        typer.Option(
            "--frequencies",
            "-f",
            help=f"comma-separated [Hz] or 'log:N:fmin:fmax' (default: the scenario's sweep, "
            f"else log:{DEFAULT_SWEEP_POINTS}:0.5:15)",
        ),
    ] = None,
    amplitude: Annotated[
        float | None,
        typer.Option(
            "--amplitude", "-a", help="low-frequency amplitude a [m] (default: the scenario's)"
        ),
    ] = None,
    out: Annotated[
        Path | None, typer.Option("--out", "-o", help="folder for sweep.csv and sweep.png")
    ] = None,
    as_json: JsonOpt = False,
    workers: Annotated[
        int | None, typer.Option("--workers", "-j", help="processes (default: one per core)")
    ] = None,
    force: Annotated[
        bool, typer.Option("--force", help="replace an --out folder holding other output")
    ] = False,
) -> None:
    """Frequency response of a scenario's vehicle, damper and controller.

    Runs a two-stage stepped sweep (one steady-state harmonic run per frequency at
    ``a`` up to f_T and ``a (f_T/f)^2`` above) across processes, with a progress bar on
    stderr (none with ``--json``), and prints T_as, T_au, T_dr, T_ds, T_du, DLC, gamma
    and the current per frequency (``--json``: a list of objects).
    """
    from mrsuspension._progress import progress_bar
    from mrsuspension.cli.compiling import notify_if_compiling
    from mrsuspension.engine.batch import run_batch
    from mrsuspension.engine.simulate import measures_of
    from mrsuspension.scenario import Scenario

    with user_errors({"frequency": "--frequencies"}):
        if workers is not None:
            check_count("--workers", workers)
        if out is not None:
            check_output_folder("--out", out, "sweep", force=force)
        scn = Scenario.load(scenario)
        sweep = _sweep_for(scn, frequencies, amplitude)
        excitations = list(sweep.excitations())
        sims = scn.runs(excitations)  # any model: quarter, half or full car
        files: list[Path] = []
        with prepare_output(out, "sweep", force=force) as folder:  # checked before the runs
            notify_if_compiling()
            with progress_bar(not as_json, "sweep") as progress:
                results = run_batch(
                    sims,
                    dt=scn.dt,
                    output_rate=scn.output_rate,
                    workers=workers,
                    progress=progress,
                    reduce=measures_of,  # measures computed in the workers: little traffic
                )
            rows = [to_jsonable(_run_row(e, m)) for e, m in zip(excitations, results, strict=True)]
            if out is not None and folder is not None:
                try:
                    title = _title(scenario, sims[0].describe(), "frequency response")
                    files = [out / f.name for f in _write_sweep(folder, rows, title)]
                except OSError as exc:
                    raise ValidationError(f"cannot write --out {str(out)!r}: {exc}") from None
    _clamp_note([m.get("vm_clamp_fraction") for m in results])
    _current_note(scn, rows)
    if as_json:
        typer.echo(json.dumps(rows))
        return
    _echo_rows(rows)
    for f in files:
        typer.echo(f"wrote {f}")


def _sweep_for(scn: Scenario, frequencies: str | None, amplitude: float | None) -> SteppedSweep:
    """The stepped sweep of ``mrsus sweep``: options first, then the scenario's excitation."""
    from mrsuspension import excitation as E
    from mrsuspension.excitation import Harmonic, SteppedSweep, log_frequencies

    exc = scn.excitation
    if frequencies is not None:
        freqs: Sequence[float] = parse_frequencies(frequencies)
    elif isinstance(exc, SteppedSweep):
        freqs = exc.frequencies
    else:
        freqs = [float(f) for f in log_frequencies(E.DEFAULT_SWEEP_POINTS)]
    if amplitude is None:
        if isinstance(exc, SteppedSweep | Harmonic):
            amplitude = exc.amplitude
        else:
            raise ValidationError(
                f"the scenario's excitation is {scn.data['excitation']['kind']!r}: give the "
                "sweep amplitude with "
                "--amplitude (metres, e.g. 0.025)"
            )
    if isinstance(exc, SteppedSweep):
        return SteppedSweep(tuple(freqs), amplitude, exc.transition_frequency)
    return SteppedSweep(tuple(freqs), amplitude)


# -- half and full cars (issue 19) ------------------------------------------------------------
def measure_unit(key: str) -> str | None:
    """Unit of a measure: the quarter car's, a vehicle's body measure, or ``"<m>.<corner>"``.

    Examples
    --------
    >>> measure_unit("T_as"), measure_unit("DLC.front_left"), measure_unit("roll_ddot_rms")
    ('-', '-', 'rad/s^2')
    """
    from mrsuspension.engine.result import MEASURE_UNITS
    from mrsuspension.engine.vehicle_result import BODY_MEASURES

    if key in BODY_MEASURES:
        return BODY_MEASURES[key][1]
    unit = MEASURE_UNITS.get(key, MEASURE_UNITS.get(key.split(".", 1)[0]))
    if unit is None:  # a registered model's own measure
        from mrsuspension.engine.plants import PLANTS

        unit = next((p.units[key] for p in PLANTS.values() if key in p.units), None)
    return unit


def _label(key: str) -> str:
    """``"name [unit]"`` (see :func:`measure_unit`), else ``name``."""
    unit = measure_unit(key)
    return key if unit is None else f"{key} [{unit}]"


def _sweep_panels(row: Mapping[str, Any]) -> list[list[str]]:
    """The sweep plot's panels: T_as, T_au, T_dr, DLC; a vehicle's body RMS accelerations,
    then T_as and DLC of every corner (one panel each)."""
    if all(k in row for k in SWEEP_PLOT):
        return [[k] for k in SWEEP_PLOT]
    body = [[k] for k in ("heave_ddot_rms", "pitch_ddot_rms", "roll_ddot_rms") if k in row]
    corners = [[k for k in row if k.startswith(f"{m}.")] for m in ("T_as", "DLC")]
    return body + [keys for keys in corners if keys]
