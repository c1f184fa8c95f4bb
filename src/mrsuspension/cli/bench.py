"""``mrsus bench``: time the engine against its baselines."""

from __future__ import annotations

import json
from typing import Annotated

import typer

from mrsuspension.cli.errors import user_errors
from mrsuspension.errors import check_count

__all__ = ["bench"]

JsonOpt = Annotated[bool, typer.Option("--json", help="print the result as one JSON object")]


def bench(
    as_json: JsonOpt = False,
    quick: Annotated[
        bool, typer.Option("--quick", help="1 s runs and a 6-frequency sweep")
    ] = False,
    workers: Annotated[
        int | None, typer.Option(help="processes for the sweep (default: all cores)")
    ] = None,
) -> None:
    """Time the engine against scipy, LSODA and plain-Python RK4 baselines, and a sweep."""
    from rich.console import Console

    from mrsuspension.bench import run_benchmarks

    with user_errors():
        if workers is not None:
            check_count("--workers", workers)
    console = Console(stderr=True)
    with user_errors(), console.status("benchmarking") as status:
        res = run_benchmarks(quick=quick, workers=workers, say=lambda m: status.update(m))
    if as_json:
        typer.echo(json.dumps(res))
        return
    typer.echo(
        f"single run ({res['duration_s']:g} s simulated, dt = 1e-4 s): {res['single_run_s']:.3f} s "
        f"({res['single_run_ns_per_step']:.0f} ns per step, of which road sampling "
        f"{res['single_run_road_sampling_s'] * 1e3:.1f} ms)"
    )
    typer.echo(
        f"  vs scipy RK45: {res['speedup_vs_scipy']:.1f}x ({res['scipy_baseline_s']:.2f} s, "
        f"relative rms difference {res['scipy_relative_rms_difference']:.1e})"
    )
    typer.echo(f"  vs scipy LSODA: {res['speedup_vs_lsoda']:.1f}x ({res['lsoda_s']:.2f} s)")
    typer.echo(
        f"  vs plain-Python RK4: {res['speedup_vs_python_rk4']:.1f}x ({res['python_rk4_s']:.2f} s, "
        f"max difference {res['python_rk4_max_difference_m']:.1e} m)"
    )
    typer.echo(
        f"sweep: {res['sweep_runs']} runs, {res['sweep_steps'] / 1e6:.1f} M steps in {res['sweep_s']:.2f} s "
        f"on {res['sweep_workers']} processes ({res['sweep_ns_per_run_step']:.0f} ns per run and step "
        f"per core; {res['sweep_at_single_run_speed_s']:.2f} s at the single run's speed)"
    )
    typer.echo(
        f"  vs run by run with post-processed measures: {res['sweep_speedup']:.2f}x "
        f"({res['sweep_run_by_run_s']:.2f} s; measures within "
        f"{res['sweep_measures_max_relative_difference']:.1e} relative)"
    )
    compiled = "skipped" if res["compile_s"] is None else f"{res['compile_s']:.1f} s"
    typer.echo(f"compile (fresh, no cache): {compiled}; first call: {res['first_call_s']:.2f} s")
    load = ", ".join("n/a" if x is None else f"{x:.2f}" for x in res["load_average"])
    typer.echo(f"load average (1 min) before, after: {load}")
