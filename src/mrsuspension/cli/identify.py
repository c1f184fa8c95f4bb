"""The ``mrsus identify`` command (registered by :mod:`mrsuspension.cli`).

``identify_command`` is a plain typer command function; ``app`` runs it on its own
(``python -m mrsuspension.cli.identify MANIFEST ...``). User errors print one line on
stderr and exit with code 2; problems with single tests are reported per test and do
not change the exit code; when no fit succeeded at all (every band failed) the output
says why and the exit code is 1.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated, Any

import typer

from mrsuspension._output import (
    check_output_folder,
    prepare_output,
    relocate_files,
    relocated,
)
from mrsuspension.cli.errors import option_named, user_errors
from mrsuspension.errors import (
    MRSuspensionError,
    ValidationError,
    check_count,
    check_range,
)

__all__ = ["app", "identify_command"]


def _fixed(text: str | None) -> dict[str, float | None] | None:
    if text is None:
        return None
    out: dict[str, float | None] = {}
    for tok in (t.strip() for t in text.split(",") if t.strip()):
        key, sep, value = tok.partition("=")
        if sep:
            try:
                out[key.strip()] = float(value)
            except ValueError:
                raise ValidationError(
                    f"--fix: {tok!r} is not NAME or NAME=VALUE (e.g. k4 or k4=-0.119)"
                ) from None
        else:
            out[key.strip()] = None
    if not out:
        raise ValidationError("--fix is empty; e.g. k4 or k3,a3,I1")
    return out


def identify_command(
    manifest: Annotated[
        Path,
        typer.Argument(
            metavar="MANIFEST",
            help="manifest (.csv or .toml) or a folder of test files; with --time-domain, "
            "one record file",
        ),
    ],
    model: Annotated[
        str,
        typer.Option(
            "--model",
            "-m",
            help="model to fit: wang-symmetric | wang-asymmetric | bingham | spencer | linear "
            "(--time-domain: spencer | bingham | wang)",
        ),
    ] = "wang-symmetric",
    out: Annotated[
        Path | None,
        typer.Option(
            "--out", "-o", help="folder for parameters.toml, tests.csv, plots, index.html"
        ),
    ] = None,
    force: Annotated[
        bool, typer.Option("--force", help="replace an --out folder holding other output")
    ] = False,
    as_json: Annotated[
        bool, typer.Option("--json", help="print the result as one JSON object")
    ] = False,
    columns: Annotated[
        str | None,
        typer.Option(
            "--columns",
            help="which column is which: t,x,v,F (positional, _ skips) "
            "or t=Time,x=Disp,F=Load; -F flips a sign",
        ),
    ] = None,
    units: Annotated[
        str | None, typer.Option("--units", help="units, e.g. s,mm,mm/s,kN or x=mm,F=kN")
    ] = None,
    current_pattern: Annotated[
        str | None,
        typer.Option(
            "--current-pattern",
            help=r"regex for the current in file names, e.g. '_(?P<current>[0-9.]+)A'",
        ),
    ] = None,
    gain: Annotated[
        float | None,
        typer.Option(
            "--gain",
            help="coil driver gain [A/V] for a coil input in V or mV (periodic tests and "
            "--time-domain records)",
        ),
    ] = None,
    start: Annotated[
        str | None,
        typer.Option("--start", "-p", help="start parameter set: registered name or .toml/.json"),
    ] = None,
    compare: Annotated[
        str | None,
        typer.Option("--compare", help="other models fitted for comparison, e.g. bingham,spencer"),
    ] = None,
    bands: Annotated[
        str | None,
        typer.Option("--bands", help="fit frequency bands separately, e.g. 0.5-5,5-15 [Hz]"),
    ] = None,
    points: Annotated[int, typer.Option("--points", help="points per resampled loop")] = 360,
    remove_offset: Annotated[
        bool, typer.Option("--remove-offset", help="subtract each loop's mean force")
    ] = False,
    max_cycles: Annotated[
        int | None,
        typer.Option("--max-cycles", help="use at most the last N cycles of the plateau"),
    ] = None,
    peak_velocity: Annotated[
        str, typer.Option("--peak-velocity", help="v_m source: auto | nominal | measured")
    ] = "auto",
    force_delay: Annotated[
        float,
        typer.Option(
            "--force-delay", help="delay of the force channel behind the motion [s], compensated"
        ),
    ] = 0.0,
    stroke_tolerance: Annotated[
        float,
        typer.Option(
            "--stroke-tolerance",
            help="how far the stroke amplitudes of a plateau's cycles may differ (fraction)",
        ),
    ] = 0.01,
    fix: Annotated[
        str | None,
        typer.Option("--fix", help="parameters held fixed: NAME or NAME=VALUE, comma-separated"),
    ] = None,
    vh_variant: Annotated[
        str | None, typer.Option("--vh-variant", help="dissertation's models: 2.12 or 2.13")
    ] = None,
    hysteresis: Annotated[
        bool | None,
        typer.Option("--hysteresis/--mean", help="dissertation's models: hysteretic or mean"),
    ] = None,
    multistart: Annotated[
        int | None, typer.Option("--multistart", help="number of starts (default 4 / 1)")
    ] = None,
    seed: Annotated[int, typer.Option("--seed", help="seed of the random starts")] = 0,
    max_nfev: Annotated[
        int | None, typer.Option("--max-nfev", help="evaluation budget per start")
    ] = None,
    name: Annotated[
        str | None, typer.Option("--name", help="name of the fitted parameter set")
    ] = None,
    plots: Annotated[
        bool, typer.Option("--plots/--no-plots", help="loop plots in --out (needs matplotlib)")
    ] = True,
    time_domain: Annotated[
        bool,
        typer.Option(
            "--time-domain",
            help="MANIFEST is one record of any motion (random, switched coil): integrate "
            "the model over it (--model spencer | bingham | wang)",
        ),
    ] = False,
    validation_fraction: Annotated[
        float,
        typer.Option(
            "--validation-fraction", help="--time-domain: share of the record (its end) kept out"
        ),
    ] = 0.3,
    free: Annotated[
        str | None,
        typer.Option("--free", help="--time-domain: parameters fixed by default to fit, e.g. n"),
    ] = None,
) -> None:
    """Fit a damper model to harmonic tests (MANIFEST) or to one record (--time-domain).

    Prints a per-test table (NRMSE, peak-force and energy errors) and the parameters.

    With --out it writes the parameter set the simulator loads, tests.csv, summary.json,
    loop plots and index.html (docs/identification.md).

    With --time-domain, MANIFEST is one record (random displacement, switched coil
    current or voltage): the model is integrated over it, fitted on its start and
    validated on its end (docs/identification.md, "Time-domain records").
    """
    from mrsuspension.identify.campaign import identify

    periodic_only = {
        "--current-pattern": current_pattern is not None, "--compare": compare is not None,
        "--bands": bands is not None, "--points": points != 360,
        "--remove-offset": remove_offset, "--max-cycles": max_cycles is not None,
        "--peak-velocity": peak_velocity != "auto", "--fix": fix is not None,
        "--force-delay": force_delay != 0.0, "--stroke-tolerance": stroke_tolerance != 0.01,
        "--vh-variant": vh_variant is not None, "--hysteresis/--mean": hysteresis is not None,
    }  # fmt: skip
    time_domain_only = {
        "--free": free is not None,
        "--validation-fraction": validation_fraction != 0.3,
    }  # fmt: skip
    clash = [
        k for k, given in (periodic_only if time_domain else time_domain_only).items() if given
    ]
    if clash:
        typer.echo(
            f"error: {', '.join(clash)} appl{'ies' if len(clash) == 1 else 'y'} "
            + ("to periodic campaigns, not with --time-domain" if time_domain
               else "to time-domain records only (add --time-domain)"),
            err=True,
        )  # fmt: skip
        raise typer.Exit(2)
    with user_errors({"points per cycle": "--points"}):
        check_count("--seed", seed, 0)
        if gain is not None:
            # a coil driver's transconductance is of order 0.1-2 A/V
            check_range("--gain", gain, 0.0, 1e3, unit="A/V", low_inclusive=False)
        if vh_variant is not None and vh_variant not in ("2.12", "2.13"):
            raise ValidationError(f"--vh-variant must be '2.12' or '2.13'; got {vh_variant!r}")
        if out is not None:
            check_output_folder("--out", out, "identify", force=force)
    if time_domain:
        _time_domain(
            manifest, model, out=out, force=force, as_json=as_json, columns=columns, units=units,
            gain=gain, validation_fraction=validation_fraction, start=start, free=free,
            starts=multistart, seed=seed, max_nfev=max_nfev, name=name, plots=plots,
        )  # fmt: skip
        return
    try:
        options: dict[str, Any] = {}
        if vh_variant is not None:
            options["vh_variant"] = vh_variant
        if hysteresis is not None:
            options["hysteresis"] = hysteresis
        if options and model not in ("wang-symmetric", "wang-asymmetric"):
            raise ValidationError(
                "--vh-variant and --hysteresis/--mean apply to the dissertation's models "
                f"(wang-symmetric, wang-asymmetric), not {model!r}"
            )
        kwargs: dict[str, Any] = {
            "columns": columns, "units": units, "current_pattern": current_pattern,
            "points_per_cycle": points, "remove_offset": remove_offset,
            "max_cycles": max_cycles, "peak_velocity": peak_velocity, "start": start,
            "force_delay": force_delay, "stroke_tolerance": stroke_tolerance,
            "fixed": _fixed(fix), "model_options": options or None, "bands": bands,
            "compare": compare or (), "multistart": multistart, "seed": seed,
            "max_nfev": max_nfev, "name": name, "current_gain": gain,
        }  # fmt: skip
        if as_json:
            result = identify(manifest, model, **kwargs)
        else:
            from rich.console import Console

            with Console(stderr=True).status("identify") as status:
                result = identify(manifest, model, progress=lambda m: status.update(m), **kwargs)
        files = _save(result, out, plots=plots, force=force)
    except MRSuspensionError as exc:
        aliases = {"points per cycle": "--points"}
        typer.echo(f"error: {option_named(' '.join(str(exc).split()), aliases)}", err=True)
        raise typer.Exit(2) from None
    failed = not result.parameter_sets  # every fit failed: the output says why
    if as_json:
        data = result.to_dict()
        data["files"] = files
        typer.echo(json.dumps(data))
        if failed:
            raise typer.Exit(1)
        return
    typer.echo(result.summary_text())
    if out is None:
        typer.echo("no files written; --out DIR saves the parameter set, tables, plots and HTML")
    for f in files:
        if not f.endswith(".png"):
            typer.echo(f"wrote {f}")
    if any(f.endswith(".png") for f in files):
        typer.echo(
            f"wrote {sum(f.endswith('.png') for f in files)} loop plots in {Path(out or '.') / 'plots'}"
        )
    if failed:
        raise typer.Exit(1)


def _save(result: Any, out: Path | None, *, plots: bool, force: bool) -> list[str]:
    """Save a fit's files into ``out`` whole (:func:`mrsuspension._output.prepare_output`);
    the paths written, as the user will find them."""
    with prepare_output(out, "identify", force=force) as staged:
        if out is None or staged is None:
            return []
        written = [str(p) for p in result.save(staged, plots=plots)]
        relocate_files(staged, out)
        return list(relocated(written, staged, out))


_TIME_DOMAIN_MODELS_BY_PERIODIC = {"wang-symmetric": "wang"}


def _time_domain(
    record_path: Path,
    model: str,
    *,
    out: Path | None,
    force: bool,
    as_json: bool,
    columns: str | None,
    units: str | None,
    gain: float | None,
    validation_fraction: float,
    start: str | None,
    free: str | None,
    starts: int | None,
    seed: int,
    max_nfev: int | None,
    name: str | None,
    plots: bool,
) -> None:
    """``mrsus identify RECORD --time-domain``: one line on a user error, exit code 2."""
    from mrsuspension.identify.record import read_record
    from mrsuspension.identify.timedomain import TIME_DOMAIN_MODELS, fit_time_domain

    try:
        # the periodic default model name maps onto its time-domain counterpart
        model = _TIME_DOMAIN_MODELS_BY_PERIODIC.get(model, model)
        if model not in TIME_DOMAIN_MODELS:
            from mrsuspension.errors import unknown_name

            raise unknown_name("--model for --time-domain", model, TIME_DOMAIN_MODELS)
        if record_path.is_dir():
            raise ValidationError(
                f"--time-domain takes one record file, not a folder ({record_path})"
            )
        record = read_record(record_path, columns, units, gain=gain)
        frees = [k.strip() for k in free.split(",") if k.strip()] if free else None
        kwargs: dict[str, Any] = {
            "validation_fraction": validation_fraction, "start": start, "free": frees,
            "starts": 3 if starts is None else starts, "seed": seed, "max_nfev": max_nfev,
            "name": name,
        }  # fmt: skip
        if as_json:
            result = fit_time_domain(record, model, **kwargs)
        else:
            from rich.console import Console

            with Console(stderr=True).status("identify --time-domain") as status:
                result = fit_time_domain(
                    record, model, progress=lambda m: status.update(m), **kwargs
                )
        files = _save(result, out, plots=plots, force=force)
    except MRSuspensionError as exc:
        aliases = {"points per cycle": "--points"}
        typer.echo(f"error: {option_named(' '.join(str(exc).split()), aliases)}", err=True)
        raise typer.Exit(2) from None
    if as_json:
        data = result.to_dict()
        data["files"] = files
        typer.echo(json.dumps(data))
        return
    typer.echo(result.summary_text())
    if out is None:
        typer.echo("no files written; --out DIR saves the parameter set, result.json and plots")
    for f in files:
        typer.echo(f"wrote {f}")


app = typer.Typer(add_completion=False, pretty_exceptions_enable=False)
app.command()(identify_command)

if __name__ == "__main__":  # pragma: no cover
    app()
