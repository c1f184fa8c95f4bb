"""HiL command functions: ``mrsus hil run``, ``hil validate``, ``hil latency``, ``rig-emulator``.

Plain typer command functions; :mod:`mrsuspension.cli` registers them. The loop, the
rigs (:mod:`mrsuspension.hil.rigs`) and the monitor load inside the commands. ``hil run`` runs
the loop in its own process with a simulated, ideal or network (``udp://HOST:PORT``)
rig; the recording goes to ``--out`` (see docs/hil.md for the format). ``hil validate``
runs a scenario in HiL and offline and compares them. ``hil latency`` measures the
machine's latency floor (the loop's pacing and scheduling alone). ``rig-emulator``
serves a simulated rig over UDP.
"""

from __future__ import annotations

import json
import math
import shutil
import signal
import tempfile
import threading
from pathlib import Path
from typing import Annotated, Any

import typer

from mrsuspension._docs import doc
from mrsuspension._jsonsafe import to_jsonable
from mrsuspension._output import (
    check_output_folder,
    prepare_output,
    relocate_files,
    relocated,
)
from mrsuspension.cli.errors import keep_on_interrupt, user_errors
from mrsuspension.errors import (
    ValidationError,
    check_host,
    check_input_file,
    check_port,
    check_range,
    require_extra,
)
from mrsuspension.hil.rigs import rig_syntax

__all__ = [
    "app",
    "hil_latency_command",
    "hil_run_command",
    "hil_validate_command",
    "rig_emulator_command",
]

#: ``hil run``'s run time when neither ``--duration`` nor the scenario's ``[simulation]``
#: says, and its loop rate (the dissertation's HiL rig, Chapter 7)
DEFAULT_DURATION = 10.0  # [s]
DEFAULT_RATE = 1000.0  # [Hz]
#: fastest loop ``hil run`` starts (the range :func:`~mrsuspension.hil.loop.run_hil` checks),
#: and with ``--monitor`` (the monitor's live stream and settings)
MAX_RATE = 100000.0  # [Hz]
MONITOR_MAX_RATE = 5000.0  # [Hz]

#: ``mrsus hil ...`` (``rig-emulator`` is a top-level command)
app = typer.Typer(
    help="Hardware in the loop: run a scenario around a (simulated) rig.",
    no_args_is_help=True,
    rich_markup_mode=None,  # as the root app: units in brackets stay
)


def hil_run_command(
    scenario: Annotated[
        Path,
        typer.Argument(
            metavar="SCENARIO",
            help=f"scenario TOML file (see {doc('scenarios')})",
            show_default=False,
        ),
    ],
    rig: Annotated[str, typer.Option(help=f"rig: {rig_syntax()}")] = "simulated",
    duration: Annotated[
        float | None,
        typer.Option(
            help=f"run time [s] (default: the scenario's [simulation] duration, else "
            f"{DEFAULT_DURATION:g})",
            show_default=False,
        ),
    ] = None,
    rate: Annotated[
        float,
        typer.Option(
            help="loop rate [Hz] (the scenario's [simulation] dt is the engine step within "
            "each tick)"
        ),
    ] = DEFAULT_RATE,
    out: Annotated[
        Path | None, typer.Option(help="recording directory (default: not kept)")
    ] = None,
    force: Annotated[
        bool, typer.Option("--force", help="replace an --out folder holding other output")
    ] = False,
    as_json: Annotated[
        bool, typer.Option("--json", help="print the outcome and tick statistics as JSON")
    ] = False,
    realtime: Annotated[
        str, typer.Option(help=f"scheduling: auto | fifo | spin | off ({doc('hil')})")
    ] = "auto",
    isolate: Annotated[
        bool,
        typer.Option(
            "--isolate",
            help="move every other movable task off the loop's core meanwhile, and back "
            f"afterwards (needs --realtime auto, fifo or spin; {doc('hil')})",
        ),
    ] = False,
    monitor: Annotated[
        bool,
        typer.Option(
            "--monitor", help="serve the browser monitor with the run attached (until Ctrl-C)"
        ),
    ] = False,
    port: Annotated[int, typer.Option(help="monitor TCP port (with --monitor)")] = 8765,
    host: Annotated[
        str, typer.Option(help="monitor address (with --monitor; loopback unless --token)")
    ] = "127.0.0.1",
    token: Annotated[
        str | None,
        typer.Option(
            help="monitor access token (with --monitor; shows in ps: prefer --token-file)"
        ),
    ] = None,
    token_file: Annotated[
        Path | None,
        typer.Option(
            help="file holding the monitor access token (with --monitor; else the "
            "environment variable MRSUS_MONITOR_TOKEN)"
        ),
    ] = None,
    corner: Annotated[
        str | None,
        typer.Option(
            help="a half or full car's corner whose damper is on the rig; the rest of the "
            "car is simulated in the loop (default: the first corner)",
            show_default=False,
        ),
    ] = None,
) -> None:
    """Run SCENARIO hardware-in-the-loop for DURATION seconds at RATE Hz.

    The loop runs in its own process; on exit the stop reason and the deadline
    statistics are printed. A safety trip exits with code 1. With --monitor the browser
    monitor is served instead, with this run started and attached (live plots, live
    changes, STOP, recording download), until Ctrl-C, and the exit code is 1 if that
    run tripped (not when STOP was pressed); with --monitor --json the run's outcome is printed as JSON when it ends
    (the monitor's address goes to stderr). A half or full car scenario runs with the
    damper of one corner (--corner) on the rig and the rest of the car simulated; the
    recording adds the body's heave, pitch and roll.
    """
    from mrsuspension.engine.settings import DEFAULT_DT
    from mrsuspension.hil.loop import (
        _rig_damper,
        _simulation_of,
        check_recording_memory,
    )
    from mrsuspension.hil.realtime import normalise_mode
    from mrsuspension.hil.rigs import make_rig, rig_kind
    from mrsuspension.scenario import Scenario

    with user_errors():
        check_input_file("scenario file", scenario)
        check_port("--port", port)
        check_host("--host", host)
        if monitor:
            require_extra("web", "hil run --monitor", "run without --monitor")
        if monitor or token is not None or token_file is not None:
            from mrsuspension.cli.monitor import monitor_token

            token = monitor_token(token, token_file)
        if out is not None and not monitor:
            check_output_folder("--out", out, "hil run", force=force)
        elif out is not None:
            check_output_folder("--out", out)
        if normalise_mode(realtime) == "unpaced":
            raise ValidationError(
                f"--realtime {realtime!r}: `hil run` runs in real time; valid: auto, fifo, spin, off"
            )
        if isolate and normalise_mode(realtime) == "off":
            raise ValidationError(
                "--isolate needs a pinned loop: use --realtime auto, fifo or spin (got 'off')"
            )
        rig_kind(rig)  # the spec's form; a network rig is pinged when it is built
        scn = Scenario.load(scenario)
        duration, model_dt = _run_settings(scn, duration)
        check_range("--duration", duration, 0.0, 1e5, unit="s", low_inclusive=False)
        check_range("--rate", rate, 50.0, MONITOR_MAX_RATE if monitor else MAX_RATE, unit="Hz")
        check_recording_memory(duration, rate, name="--duration")
        sim = _simulation_of(scn)
        corner = _rig_corner(sim, corner)
        from mrsuspension.cli.compiling import notify_if_compiling

        notify_if_compiling(None, "step")
        if monitor:
            from mrsuspension.monitor.app import AttachedRun
            from mrsuspension.monitor.server import serve

            ended: dict[str, Any] = {}

            def on_end(info: dict[str, Any]) -> None:
                ended.update(info)
                if info.get("out"):  # named in the `interrupted:` line of a Ctrl-C
                    keep_on_interrupt(
                        f"the run's recording in {str(info['out'])!r} (loop stopped: "
                        f"{info.get('reason')}; rig commanded to mid-stroke, current 0)"
                    )
                if as_json:  # the object `hil run --json` prints (the recording: the run's folder)
                    if out is None and "out" in info:
                        info["out"] = None
                    typer.echo(json.dumps(to_jsonable(info), indent=2))

            end = serve(
                host, port, token, rig=rig, workdir=out, url_to_stderr=as_json, realtime=realtime,
                isolate=isolate, attach=AttachedRun(
                    sim, rate=rate, duration=duration, model_dt=model_dt, on_end=on_end,
                    corner=corner,
                ),
            )  # fmt: skip
            # as `hil run`: a signal that stopped the attached run (the loop's own, or the
            # server's shutdown while it ran) exits 128 + the signal with one line naming
            # the recording (on_end); a safety trip (or a failed loop) exits 1; the
            # operator's STOP (which takes the same safe path) and a server closed after
            # the run had ended do not
            signum = ended.get("signal") or (end.signum if end.stopped_run else None)
            if signum:
                from mrsuspension._pool import Interrupted

                raise Interrupted(int(signum))
            stopped = ended.get("ending") == "stopped"  # the operator's STOP
            if (ended.get("tripped") and not stopped) or ended.get("state") == "error":
                raise typer.Exit(1)
            return
        the_rig = make_rig(rig, _rig_damper(sim, corner))
        # SIGHUP stops it as Ctrl-C does (the command's `interrupts`, _pool.handle_signals)
        result, kept, interrupted = _run_recorded(
            sim, the_rig, out, force=force, duration=duration, rate=rate, realtime=realtime,
            isolate=isolate, model_dt=DEFAULT_DT if model_dt is None else model_dt,
            corner=corner,
        )  # fmt: skip
    _report_ending(result, kept, out, interrupted, as_json)


#: ``hil run``'s exit status per ending of the run (docs/hil.md, "Endings"); a signal
#: that stopped the run exits 128 + its number (130 SIGINT, 143 SIGTERM, 129 SIGHUP)
EXIT_CODES = {
    "completed": 0,
    "stopped": 0,
    "tripped": 1,
    "failed": 1,
    "recording failed": 1,
    "orphaned": 1,
}


class _NotCommitted(Exception):
    """Raised inside :func:`prepare_output` to leave ``--out`` as it was."""


def _run_recorded(
    sim: Any,
    the_rig: Any,
    out: Path | None,
    *,
    force: bool,
    duration: float,
    rate: float,
    realtime: str,
    isolate: bool,
    model_dt: float,
    corner: str | None = None,
) -> tuple[Any, Path | None, KeyboardInterrupt | None]:
    """Run the loop in its own process; keep its recording whatever the ending.

    Returns the result (None when the loop left none), where the recording is when it is
    not ``out`` (the temporary folder of a run without ``--out`` that ended badly, or
    ``NAME.recovered`` when it could not be committed), and the interrupt to re-raise.
    A run that ended through the loop is committed to ``out`` (the recording up to a
    Ctrl-C included); a failed recording (a full disk) is moved aside, not committed.
    """
    from mrsuspension._output import keep_recovered
    from mrsuspension.errors import MRSuspensionError
    from mrsuspension.hil.loop import load_result, run_hil
    from mrsuspension.hil.recorder import META_FILE

    tmp = None
    result = None
    kept: Path | None = None
    interrupted: KeyboardInterrupt | None = None
    try:
        with prepare_output(out, "hil run", force=force) as staged:
            target = staged
            if target is None:
                tmp = Path(tempfile.mkdtemp(prefix="mrsus-hil-"))
                target = tmp / "recording"
            failure: MRSuspensionError | None = None
            try:
                result = run_hil(
                    sim, the_rig, duration=duration, rate=rate, out=target, process=True,
                    realtime=realtime, isolate=isolate, model_dt=model_dt, recover=out,
                    corner=corner,
                )  # fmt: skip
            except KeyboardInterrupt as exc:  # the loop stopped the safe way: keep the data
                interrupted = exc
                _ignore_signals()  # the cleanup is bounded: later signals change nothing
            except MRSuspensionError as exc:  # the loop process died
                failure = exc
            if result is None:
                try:
                    result = load_result(target)
                except (MRSuspensionError, ValueError, OSError):
                    result = None
            started = (target / META_FILE).exists()
            bad = result is None or result.ending not in ("completed", "stopped")
            if tmp is not None:
                if bad and started:
                    kept = target  # the run ended badly: the temporary recording stays
                else:
                    shutil.rmtree(tmp, ignore_errors=True)
            elif staged is not None and out is not None:
                if started and (
                    failure is not None
                    or (result is not None and result.ending == "recording failed")
                ):
                    kept = keep_recovered(staged, out)  # the disk may be full: not committed
                    raise _NotCommitted
                relocate_files(staged, out)  # the recording names its final folder
                if result is not None:
                    result.out = out
            if failure is not None and not started:
                raise failure
            if failure is not None and result is None and interrupted is None:
                raise failure
    except _NotCommitted:
        pass
    if result is not None and tmp is not None and kept is None:
        result.out = None
    if result is not None and kept is not None:
        result.out = kept
    if interrupted is None and result is not None and result.signal is not None:
        from mrsuspension._pool import Interrupted

        interrupted = Interrupted(result.signal)  # the loop got it alone: exit the same way
    return result, kept, interrupted


def _ignore_signals() -> None:
    if threading.current_thread() is threading.main_thread():
        for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            signal.signal(s, signal.SIG_IGN)


def _report_ending(
    result: Any,
    kept: Path | None,
    out: Path | None,
    interrupted: KeyboardInterrupt | None,
    as_json: bool,
) -> None:
    """One line saying how the run ended, and ``hil run``'s exit status (:data:`EXIT_CODES`)."""
    where = kept if kept is not None else out
    if result is None:  # the loop left no result (it died before its stop record)
        if interrupted is not None:
            if where is not None and where.exists():
                keep_on_interrupt(f"the recording so far in {str(where)!r}")
            raise interrupted
        raise typer.Exit(1)
    info = result.describe()
    if as_json:
        typer.echo(json.dumps(to_jsonable(info), indent=2))
    if interrupted is not None:  # one line, exit 128 + the signal (SIGHUP included)
        from mrsuspension.cli.errors import _exit_interrupted

        home = "rig commanded to mid-stroke, current 0"
        what = f"the recording in {str(where)!r}" if where is not None else "no recording"
        signum = int(getattr(interrupted, "signum", signal.SIGINT))
        _exit_interrupted(signum, [], [f"{what} (loop stopped: {result.reason}; {home})"])
    if not as_json:
        typer.echo(f"stopped: {result.reason}")
        typer.echo(result.stats.summary())
        at = f" at {info['corner']}" if info.get("corner") else ""
        typer.echo(f"rms body acceleration{at}: {info['rms_body_acceleration']:.4g} m/s^2")
        if "rms_heave_acceleration" in info:
            typer.echo(f"rms heave acceleration: {info['rms_heave_acceleration']:.4g} m/s^2")
        if info["out"]:
            note = " (not committed to --out)" if kept is not None and out is not None else ""
            typer.echo(f"recording: {info['out']}{note}")
    code = EXIT_CODES.get(result.ending, 1)
    if code:
        raise typer.Exit(code)


def _rig_corner(sim: Any, corner: str | None) -> str | None:
    """``--corner``, checked: a half or full car's rig corner (default: its first); an
    error for a quarter car.

    Examples
    --------
    >>> from mrsuspension.hil.loop import _simulation_of
    >>> _rig_corner(_simulation_of("examples/vehicles/half_car.toml"), None)
    'front'
    """
    from mrsuspension.hil.vehicle import check_corner, has_corners

    if has_corners(sim):
        return check_corner(sim, corner, "--corner")
    if corner is not None:
        raise ValidationError(
            f"--corner {corner!r}: this is a quarter-car scenario, it has no corners "
            "(--corner is for half and full car scenarios)"
        )
    return None


def _run_settings(scn: Any, duration: float | None) -> tuple[float, float | None]:
    """``hil run``'s duration and engine step: the option, else the scenario's, else the
    defaults.

    The scenario's ``[simulation] duration`` is the run time unless ``--duration`` is
    given; its ``dt`` is the engine step of the loop (``run_hil``'s ``model_dt``: each
    tick of ``--rate`` runs ``ceil(1/(rate dt))`` steps), as offline. What was taken from
    the scenario is said on stderr.
    """
    table = scn.data.get("simulation", {})
    said = []
    if duration is None:
        if "duration" in table:
            duration = float(table["duration"])
            said.append(f"duration {duration:g} s")
        else:
            duration = DEFAULT_DURATION
    model_dt = None
    if "dt" in table:
        model_dt = float(table["dt"])
        said.append(f"engine step dt = {model_dt:g} s")
    if said:
        typer.echo(f"hil run: {' and '.join(said)} from the scenario's [simulation]", err=True)
    return duration, model_dt


def hil_latency_command(
    rate: Annotated[float, typer.Option(help="tick rate [Hz]")] = 1000.0,
    duration: Annotated[float, typer.Option(help="length of the measurement [s]")] = 10.0,
    realtime: Annotated[
        str, typer.Option(help="scheduling: auto | fifo | spin | off (as 'hil run')")
    ] = "auto",
    isolate: Annotated[
        bool,
        typer.Option(
            "--isolate",
            help="move every other movable task off the measuring core meanwhile, as "
            "'hil run --isolate' (needs --realtime auto, fifo or spin)",
        ),
    ] = False,
    work_us: Annotated[
        float,
        typer.Option(
            "--work-us", help="busy work per tick [us] (e.g. a run's compute p50; 0: empty)"
        ),
    ] = 0.0,
    as_json: Annotated[
        bool, typer.Option("--json", help="print the statistics as one JSON object")
    ] = False,
) -> None:
    """Measure the machine's latency floor for the HiL loop (like cyclictest).

    Paces ticks at RATE Hz for DURATION seconds exactly as `hil run` does (same
    scheduling modes) with no model and no rig, only WORK-US of busy work per tick, in
    its own process, and prints the share of ticks in deadline, the release lateness,
    the stalls longer than one period and the CPU time stolen by the hypervisor or used
    by other processes meanwhile. Misses here come from the machine, not the loop
    (docs/hil.md, "Checking a machine").
    """
    import sys

    from mrsuspension._progress import progress_bar
    from mrsuspension.hil.latency import LATENCY_MODES, measure_latency
    from mrsuspension.hil.realtime import normalise_mode

    with user_errors():
        rate = float(check_range("--rate", rate, 0.0, 100000.0, unit="Hz", low_inclusive=False))
        check_range("--duration", duration, 0.0, 1e6, unit="s", low_inclusive=False)
        check_range("--work-us", work_us, 0.0, 1e6 / rate, unit="us", high_inclusive=False)
        if normalise_mode(realtime) not in LATENCY_MODES:
            raise ValidationError(
                f"--realtime {realtime!r} has no deadlines to measure; "
                f"valid: {', '.join(LATENCY_MODES)}"
            )
        if isolate and normalise_mode(realtime) == "off":
            raise ValidationError(
                "--isolate needs a pinned loop: use --realtime auto, fifo or spin (got 'off')"
            )
        with progress_bar(not as_json and sys.stderr.isatty(), "latency") as progress:
            result = measure_latency(
                rate, duration, realtime, work=work_us / 1e6, progress=progress, process=True,
                isolate=isolate,
            )  # fmt: skip
    if as_json:
        typer.echo(json.dumps(to_jsonable(result.describe())))
    else:
        typer.echo(result.summary())


def hil_validate_command(
    scenario: Annotated[
        Path,
        typer.Argument(
            metavar="SCENARIO",
            help=f"scenario TOML file (see {doc('scenarios')})",
            show_default=False,
        ),
    ],
    rig: Annotated[str, typer.Option(help=f"rig: {rig_syntax()}")] = "ideal",
    duration: Annotated[float, typer.Option(help="run time of the 'time' comparison [s]")] = 10.0,
    rate: Annotated[float, typer.Option(help="loop rate [Hz]")] = 1000.0,
    out: Annotated[
        Path | None,
        typer.Option(help="folder for the figures, validation.json, index.html, recording"),
    ] = None,
    force: Annotated[
        bool, typer.Option("--force", help="replace an --out folder holding other output")
    ] = False,
    as_json: Annotated[bool, typer.Option("--json", help="print the numbers as JSON")] = False,
    what: Annotated[
        str, typer.Option(help="comparisons: all or a list of time,frequency,pulse,road")
    ] = "all",
    frequencies: Annotated[
        str | None,
        typer.Option(help="frequency list [Hz], e.g. 1,1.5,4 (default: the 14 of the HiL rig)"),
    ] = None,
    cases: Annotated[
        str,
        typer.Option(
            help="controller cases: scenario, passive-0, passive-0.1, skyhook-scm, "
            "skyhook-acm (comma-separated) or all"
        ),
    ] = "scenario",
    amplitude: Annotated[float, typer.Option(help="sweep amplitude up to 2 Hz [m]")] = 0.015,
    masses: Annotated[
        str | None,
        typer.Option(
            help="sprung masses [kg], e.g. 563,703: every comparison for each "
            "(default: the scenario's own)"
        ),
    ] = None,
    road_duration: Annotated[
        float | None, typer.Option(help="length of the random road [s] (default: all 36 s)")
    ] = None,
    realtime: Annotated[
        str | None,
        typer.Option(
            help="auto | fifo | spin | off | unpaced (default: unpaced for simulated and ideal "
            "rigs, auto for a UDP rig, which always runs paced)"
        ),
    ] = None,
    corner: Annotated[
        str | None,
        typer.Option(
            help="a half or full car's corner whose damper is on the rig (default: the "
            "first corner); a vehicle is compared on 'time' only",
            show_default=False,
        ),
    ] = None,
) -> None:
    """Run SCENARIO in HiL and offline and compare them (Chapter 7 validation).

    Comparisons (--what): time histories and F-v loops under the scenario's excitation
    (time), frequency responses T_as, T_au, T_dr and DLC over a frequency list
    (frequency), transient responses under the rounded pulse (pulse) and PSDs under the
    random road (road), for each controller case (--cases) and sprung mass (--masses,
    e.g. 563,703 for Figs 7.14, 7.16, 7.18, 7.21). Prints the differences; with
    --out writes the figures, validation.json (every number), index.html, and for
    'time' summary.json and the HiL recording. A simulated or ideal rig runs unpaced by
    default (as fast as possible; the outputs say so). A safety trip exits with code 1.
    A half or full car scenario runs with one corner's damper on the rig (--corner) and
    is compared on 'time' with the offline vehicle run: that corner's RMS and the body's.
    """
    from mrsuspension.hil.chapter7 import (
        parse_cases,
        parse_frequencies,
        parse_masses,
        parse_what,
    )
    from mrsuspension.hil.loop import _rig_damper, _simulation_of
    from mrsuspension.hil.realtime import normalise_mode
    from mrsuspension.hil.rigs import make_rig
    from mrsuspension.report.ch7 import validate_chapter7

    with user_errors({"sprung_mass": "--masses", "frequency": "--frequencies"}):
        check_input_file("scenario file", scenario)
        if out is not None:
            check_output_folder("--out", out, "hil validate", force=force)
        chosen = parse_what(what)
        case_list = parse_cases(cases)
        freq_list = parse_frequencies(frequencies)
        mass_list = parse_masses(masses) or None
        if realtime is not None:
            normalise_mode(realtime)
        if road_duration is not None:
            check_range("--road-duration", road_duration, 0.0, 1e5, unit="s", low_inclusive=False)
        sim = _simulation_of(scenario)
        corner = _rig_corner(sim, corner)
        from mrsuspension.cli.compiling import notify_if_compiling

        notify_if_compiling(None, "run", "step")
        the_rig = make_rig(rig, _rig_damper(sim, corner))
        with prepare_output(out, "hil validate", force=force) as staged:
            data = validate_chapter7(
                sim, the_rig, staged, what=chosen, cases=case_list, frequencies=freq_list,
                amplitude=amplitude, duration=duration, road_duration=road_duration, rate=rate,
                realtime=realtime, masses=mass_list, corner=corner,
            )  # fmt: skip
            if staged is not None and out is not None:
                relocate_files(staged, out)
                data = relocated(data, staged, out)
    tripped = _tripped(data)
    # one time report is printed flat (as before masses); several stay under "time"
    flat = _flat_time(data)
    info: dict[str, Any] = dict(data["time"]) if flat else {}
    info.update({k: v for k, v in data.items() if not (flat and k == "time")})
    info["scenario"] = str(scenario)
    info["rig"] = rig
    if as_json:
        typer.echo(json.dumps(to_jsonable(info), indent=2))
    else:
        _print_validation(data, out)
    if tripped:
        raise typer.Exit(1)


def _flat_time(data: dict[str, Any]) -> bool:
    """One ``time`` report (one mass), not one per mass."""
    return "reason" in data.get("time", {})


def _time_reports(data: dict[str, Any]) -> list[dict[str, Any]]:
    if "time" not in data:
        return []
    return [data["time"]] if _flat_time(data) else list(data["time"].values())


def _tripped(data: dict[str, Any]) -> bool:
    if any(t.get("tripped") for t in _time_reports(data)):
        return True
    reasons = [r for fr in data.get("frequency", {}).values() for r in fr["reasons"]]
    reasons += [r["reason"] for key in ("pulse", "road") for r in data.get(key, {}).values()]
    return any(r != "completed" for r in reasons)


def _pct(v: Any) -> str:
    return "-" if v is None or not math.isfinite(v) else f"{100 * v:+.2f}%"


def _print_validation(data: dict[str, Any], out: Path | None) -> None:
    typer.echo(data["pacing"])
    for t in _time_reports(data):
        mass = "" if _flat_time(data) else f", m_s = {t['sprung_mass']:g} kg"
        corner = f", {t['corner']} damper on the rig" if t.get("corner") else ""
        typer.echo(f"time histories{mass}{corner}: HiL stopped: {t['reason']}")
        labels = [f"{m['label']} [{m['unit']}]" for m in t["rms"].values()]
        w = max([34, *(len(label) + 2 for label in labels)])
        typer.echo(f"{'RMS':<{w}}{'HiL':>12}{'offline':>12}{'diff':>10}")
        for label, m in zip(labels, t["rms"].values(), strict=True):
            typer.echo(
                f"{label:<{w}}{m['hil']:>12.5g}"
                f"{m['offline']:>12.5g}{_pct(m['relative_difference']):>10}"
            )
    for case, fr in data.get("frequency", {}).items():
        typer.echo(f"frequency responses, {case} (HiL vs offline):")
        typer.echo(f"{'f [Hz]':>7}" + "".join(f"{k + ' diff':>11}" for k in fr["hil"]))
        for i, f in enumerate(fr["frequency"]):
            diffs = "".join(f"{_pct(fr['relative_difference'][k][i]):>11}" for k in fr["hil"])
            typer.echo(f"{f:>7g}{diffs}")
    for case, res in data.get("pulse", {}).items():
        diffs = ", ".join(f"{k} {_pct(v)}" for k, v in res["relative_difference"].items())
        typer.echo(f"rounded pulse, {case}: {diffs}")
    for case, res in data.get("road", {}).items():
        lo, hi = res["band"]
        diffs = ", ".join(
            f"{label} {_pct(b['relative_difference'])}" for label, b in res["band_rms"].items()
        )
        typer.echo(f"random road, {case}: RMS {lo:g}-{hi:g} Hz {diffs}")
    if out is not None:
        for group in data.get("figures", {}).values():
            for name in group:
                typer.echo(f"figure: {out / name}")
        typer.echo(f"index: {out / 'index.html'}")


def rig_emulator_command(
    port: Annotated[int, typer.Option(help="UDP port (0: any free port)")] = 9870,
    host: Annotated[str, typer.Option(help="address to bind (loopback by default)")] = "127.0.0.1",
    rig: Annotated[str, typer.Option(help=f"served rig: {rig_syntax(local_only=True)}")] = (
        "simulated"
    ),
    damper: Annotated[str, typer.Option(help="damper model carried by the rig")] = (
        "wang-symmetric"
    ),
    rate: Annotated[float, typer.Option(help="tick rate [Hz] until a client resets")] = 1000.0,
    drop: Annotated[
        float, typer.Option(help="probability of dropping a reply (fault injection)")
    ] = 0.0,
    delay: Annotated[float, typer.Option(help="extra reply delay [s] (fault injection)")] = 0.0,
    heartbeat: Annotated[
        float, typer.Option(help="period of the server's heartbeats [s] (0: none)")
    ] = 0.02,
    watchdog: Annotated[
        float,
        typer.Option(help="client silence [s] after which the rig goes safe (0: never)"),
    ] = 0.25,
    realtime: Annotated[
        str, typer.Option(help=f"scheduling: auto | fifo | spin | off ({doc('hil')})")
    ] = "auto",
) -> None:
    """Serve a simulated rig over UDP (the network rig protocol, docs/hil.md).

    Runs until Ctrl-C (or SIGTERM, e.g. `kill`), then ramps a driven rig home and prints
    its packet counts; refused resets, commands from strangers and watchdog trips are
    printed as they happen. Connect a loop with `mrsus hil run SCENARIO --rig
    udp://HOST:PORT`.
    """
    import signal

    from mrsuspension.dampers import make_damper
    from mrsuspension.dampers.wang import VEHICLE_VH_VARIANT
    from mrsuspension.hil.network import serve_rig
    from mrsuspension.hil.rigs import RIGS, make_rig, rig_kind

    def interrupt(_signum: int, _frame: Any) -> None:
        raise KeyboardInterrupt

    with user_errors():
        check_port("--port", port, any_free=True)
        check_host("--host", host)
        spec = rig_kind(rig, kinds=[k for k in RIGS.values() if k.local]).name
        model = make_damper(
            damper, **({"vh_variant": VEHICLE_VH_VARIANT} if damper.startswith("wang-") else {})
        )
        served = make_rig(spec, model)

        def ready(bound: int) -> None:
            typer.echo(f"rig emulator ({spec}, {damper}) listening on udp://{host}:{bound}")

        # stop cleanly on Ctrl-C even when started with SIGINT ignored (a background job of
        # a script), and on SIGTERM; the handlers the caller had come back at the end (a
        # call in a longer-lived process, e.g. a test, keeps its own)
        previous = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
        signal.signal(signal.SIGINT, signal.default_int_handler)
        signal.signal(signal.SIGTERM, interrupt)
        try:
            counts = serve_rig(
                served, host=host, port=port, rate=rate, drop=drop, delay=delay, ready=ready,
                heartbeat=heartbeat, watchdog=watchdog, realtime=realtime, log=typer.echo,
            )  # fmt: skip
        finally:
            for s, handler in previous.items():
                signal.signal(s, handler if handler is not None else signal.SIG_DFL)
    typer.echo("stopped: " + ", ".join(f"{k} {v}" for k, v in counts.items()))
