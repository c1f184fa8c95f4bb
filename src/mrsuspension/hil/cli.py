"""``mrsus hil run``: run a scenario in the loop with a simulated (or ideal) rig.

A plain typer command function; :mod:`mrsuspension.cli` registers it. The loop runs in
its own process; the recording goes to ``--out`` (see docs/hil.md for the format).
"""

from __future__ import annotations

import json
import math
import shutil
import tempfile
from pathlib import Path
from typing import Annotated, Any

import typer

from mrsuspension._cli_errors import _user_errors
from mrsuspension.errors import ValidationError
from mrsuspension.hil.loop import run_hil
from mrsuspension.hil.rig import Rig, SimulatedRig, ideal_rig

__all__ = ["RIGS", "hil_run_command", "make_rig"]

#: rig names accepted by ``--rig``
RIGS = ("simulated", "ideal")


def make_rig(spec: str, damper: Any) -> Rig:
    """A rig from its ``--rig`` spec (``simulated`` or ``ideal``) carrying ``damper``."""
    spec = spec.strip().lower()
    if spec == "simulated":
        return SimulatedRig(damper=damper)
    if spec == "ideal":
        return ideal_rig(damper)
    if spec.startswith("udp://"):
        raise ValidationError(
            f"--rig {spec}: the UDP network rig is not available in this version; "
            f"use one of: {', '.join(RIGS)}"
        )
    raise ValidationError(f"unknown --rig {spec!r}; valid: {', '.join(RIGS)}")


def _clean(value: Any) -> Any:
    if isinstance(value, dict):
        return {str(k): _clean(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_clean(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def hil_run_command(
    scenario: Annotated[
        Path, typer.Argument(help="scenario TOML file (see docs/scenarios.md)", show_default=False)
    ],
    rig: Annotated[str, typer.Option(help="rig: simulated | ideal")] = "simulated",
    duration: Annotated[float, typer.Option(help="run time [s]")] = 10.0,
    rate: Annotated[float, typer.Option(help="loop rate [Hz]")] = 1000.0,
    out: Annotated[
        Path | None, typer.Option(help="recording directory (default: not kept)")
    ] = None,
    as_json: Annotated[
        bool, typer.Option("--json", help="print the outcome and tick statistics as JSON")
    ] = False,
) -> None:
    """Run SCENARIO hardware-in-the-loop for DURATION seconds at RATE Hz.

    The loop runs in its own process; on exit the stop reason and the deadline
    statistics are printed. A safety trip exits with code 1.
    """
    from mrsuspension.hil.loop import _simulation_of

    with _user_errors():
        if not scenario.exists():
            raise ValidationError(f"scenario file {scenario} does not exist")
        sim = _simulation_of(scenario)
        the_rig = make_rig(rig, sim.damper)
        tmp = None
        target = out
        if target is None:
            tmp = Path(tempfile.mkdtemp(prefix="mrsus-hil-"))
            target = tmp / "recording"
        try:
            result = run_hil(sim, the_rig, duration=duration, rate=rate, out=target, process=True)
        finally:
            if tmp is not None:
                shutil.rmtree(tmp, ignore_errors=True)
    info = result.describe()
    if tmp is not None:
        info["out"] = None
    if as_json:
        typer.echo(json.dumps(_clean(info), indent=2))
    else:
        typer.echo(f"stopped: {result.reason}")
        typer.echo(result.stats.summary())
        typer.echo(f"rms body acceleration: {info['rms_body_acceleration']:.4g} m/s^2")
        if info["out"]:
            typer.echo(f"recording: {info['out']}")
    if result.tripped:
        raise typer.Exit(1)
