"""``mrsus damper ...``: evaluate, characterise and plot damper models."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated, Any

import typer

from mrsuspension._output import check_output_folder, prepare_output, save_listed
from mrsuspension.cli.errors import user_errors
from mrsuspension.errors import ValidationError, check_range

__all__ = ["app"]

#: bounds of the kinematic inputs ``damper force``/``inverse`` accept: an automotive
#: damper's stroke is well within 1 m (the characterisation's amplitude limit), its
#: velocity within 10 m/s (the identified sets reach 0.4-1.5 m/s; the peak-velocity
#: estimators clamp at 5 m/s) and its acceleration within 1000 m/s^2 (100 g); a target
#: force beyond 100 kN is far past any MR damper (the dissertation's peaks at ~3 kN)
MAX_STROKE = 1.0  # [m]
MAX_VELOCITY = 10.0  # [m/s]
MAX_ACCELERATION = 1000.0  # [m/s^2]
MAX_FORCE = 1e5  # [N]
#: library fields named differently on the command line
_ALIASES = {"target_force": "--force", "drive current": "--current"}

#: ``mrsus damper ...``
app = typer.Typer(
    help="Evaluate, characterise and plot damper models.",
    no_args_is_help=True,
    rich_markup_mode=None,  # as the root app: units in brackets stay
)

_WANG = ("wang-symmetric", "wang-asymmetric")


def _floats(name: str, text: str) -> list[float]:
    try:
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise ValidationError(
            f"--{name} must be a number or comma-separated numbers; got {text!r}"
        ) from None
    if not values:
        raise ValidationError(f"--{name} needs at least one number")
    limit = {"stroke": (MAX_STROKE, "m"), "velocity": (MAX_VELOCITY, "m/s"),
             "acceleration": (MAX_ACCELERATION, "m/s^2"), "force": (MAX_FORCE, "N")}.get(name)  # fmt: skip
    if limit is not None:
        check_range(f"--{name}", values, -limit[0], limit[0], unit=limit[1])
    return values


def _peak(peak_velocity: float | None) -> None:
    """``--peak-velocity`` must be > 0 (its upper bound is the model's)."""
    if peak_velocity is not None:
        check_range("--peak-velocity", peak_velocity, 0.0, None, unit="m/s", low_inclusive=False)


ModelOpt = Annotated[
    str,
    typer.Option(
        "--model", "-m", help="wang-symmetric | wang-asymmetric | bingham | spencer | linear"
    ),
]
ParamsOpt = Annotated[
    str | None, typer.Option("--parameters", "-p", help="registered set name or a .toml/.json file")
]
HystOpt = Annotated[
    bool | None,
    typer.Option("--hysteresis/--mean", help="hysteretic (default) or mean model (k4 = 0)"),
]
VhOpt = Annotated[
    str | None,
    typer.Option("--vh-variant", help="v_h from (2.13) (default, as in simulations) or (2.12)"),
]
GainOpt = Annotated[float | None, typer.Option("--force-gain", help="force gain k_d (default 1)")]
EstOpt = Annotated[
    str | None,
    typer.Option(
        "--estimator",
        help="peak-velocity estimator: cycle-rms (default) | window | instantaneous | known",
    ),
]


def _model(
    model: str,
    parameters: str | None,
    hysteresis: bool | None,
    vh_variant: str | None,
    force_gain: float | None,
    estimator: str | None,
    peak_velocity: float | None = None,
) -> Any:
    from mrsuspension.dampers import make_damper

    options: dict[str, Any] = {}
    wang_only = {
        "--hysteresis/--mean": ("hysteresis", hysteresis),
        "--vh-variant": ("vh_variant", vh_variant),
        "--force-gain": ("force_gain", force_gain),
        "--estimator": ("estimator", estimator),
    }
    for flag, (key, value) in wang_only.items():
        if value is not None:
            if model not in _WANG:
                raise ValidationError(
                    f"{flag} applies to the dissertation's models ({', '.join(_WANG)}), not {model!r}"
                )
            options[key] = value
    if options.get("estimator") == "known":
        if peak_velocity is None:
            raise ValidationError("--estimator known needs --peak-velocity")
        options["value"] = peak_velocity
    return make_damper(model, parameters, **options)


JsonOpt = Annotated[bool, typer.Option("--json", help="print the result as one JSON object")]
ForceOpt = Annotated[
    bool, typer.Option("--force", help="replace an --out folder holding other output")
]


@app.command("force")
def damper_force(
    velocity: Annotated[
        str, typer.Option("--velocity", "-v", help="v_d [m/s], comma-separated for several")
    ],
    model: ModelOpt = "wang-symmetric",
    parameters: ParamsOpt = None,
    stroke: Annotated[str, typer.Option("--stroke", "-x", help="x_d [m]")] = "0",
    acceleration: Annotated[str, typer.Option("--acceleration", "-a", help="a_d [m/s^2]")] = "0",
    current: Annotated[str, typer.Option("--current", "-i", help="drive current [A]")] = "0",
    peak_velocity: Annotated[
        float | None, typer.Option(help="v_m [m/s] (dissertation's models)")
    ] = None,
    hysteresis: HystOpt = None,
    vh_variant: VhOpt = None,
    force_gain: GainOpt = None,
    estimator: EstOpt = None,
    as_json: JsonOpt = False,
) -> None:
    """Print a model's force for given stroke, velocity, acceleration and current.

    Comma-separated values broadcast against each other (one value or equal lengths).
    """
    import numpy as np

    with user_errors(_ALIASES):
        _peak(peak_velocity)
        m = _model(model, parameters, hysteresis, vh_variant, force_gain, estimator, peak_velocity)
        arrays = [np.asarray(_floats(n, t)) for n, t in
                  (("stroke", stroke), ("velocity", velocity), ("acceleration", acceleration), ("current", current))]  # fmt: skip
        vm = peak_velocity if m.name in _WANG and estimator != "known" else None
        try:
            x, v, a, i = (np.array(q) for q in np.broadcast_arrays(*arrays))
        except ValueError:
            raise ValidationError(
                "comma-separated inputs must have one value or equal lengths"
            ) from None
        f = m.force(x, v, a, i, peak_velocity=vm)
    if as_json:
        typer.echo(json.dumps({
            "model": m.describe(), "stroke": x.tolist(), "velocity": v.tolist(),
            "acceleration": a.tolist(), "current": i.tolist(), "peak_velocity": vm,
            "force": f.tolist(),
        }))  # fmt: skip
        return
    typer.echo(f"{m!r}")
    typer.echo(f"{'x_d [m]':>10} {'v_d [m/s]':>10} {'a_d [m/s2]':>11} {'i [A]':>7} {'F_d [N]':>12}")
    for row in zip(x, v, a, i, f, strict=True):
        typer.echo(f"{row[0]:10.4g} {row[1]:10.4g} {row[2]:11.4g} {row[3]:7.3g} {row[4]:12.6g}")


@app.command("inverse")
def damper_inverse(
    force: Annotated[str, typer.Option("--force", "-f", help="target force F* [N]")],
    velocity: Annotated[str, typer.Option("--velocity", "-v", help="v_d [m/s]")],
    acceleration: Annotated[str, typer.Option("--acceleration", "-a", help="a_d [m/s^2]")] = "0",
    peak_velocity: Annotated[
        float | None, typer.Option(help="v_m [m/s]; default: model estimator")
    ] = None,
    parameters: ParamsOpt = None,
    hysteresis: HystOpt = None,
    force_gain: GainOpt = None,
    as_json: JsonOpt = False,
) -> None:
    """Current that makes the symmetric model produce F* (model reference, section 2.3).

    Only |F*| is used: the damper's force takes the sign of its passive hysteron, so a
    negative target gives the current of its magnitude (said on stderr). A target beyond
    the force at i_max gives i_max (saturated, said on stderr); one below the passive
    force gives 0 A.
    """
    import numpy as np

    with user_errors(_ALIASES):
        _peak(peak_velocity)
        m = _model("wang-symmetric", parameters, hysteresis, "2.13", force_gain, None)
        arrays = [np.asarray(_floats(n, t)) for n, t in
                  (("force", force), ("velocity", velocity), ("acceleration", acceleration))]  # fmt: skip
        try:
            f, v, a = (np.array(q) for q in np.broadcast_arrays(*arrays))
        except ValueError:
            raise ValidationError(
                "comma-separated inputs must have one value or equal lengths"
            ) from None
        i = m.inverse_current(f, v, a, peak_velocity=peak_velocity)
    saturated = (i >= m.max_current) & (np.abs(f) > 0)
    if np.any(f < 0):
        typer.echo(
            "note: only |F*| is used: the damper's force takes the sign of its passive "
            "hysteron (model reference, section 2.3)",
            err=True,
        )
    if np.any(saturated):
        which = ", ".join(f"{x:g}" for x in f[saturated])
        typer.echo(
            f"note: F* = {which} N is out of reach: the current saturates at i_max = "
            f"{m.max_current:g} A (the damper's largest force there is smaller)",
            err=True,
        )
    if as_json:
        typer.echo(json.dumps({"target_force": f.tolist(), "velocity": v.tolist(),
                               "acceleration": a.tolist(), "current": i.tolist(),
                               "saturated": saturated.tolist()}))  # fmt: skip
        return
    for row in zip(f, v, a, i, strict=True):
        typer.echo(f"F*={row[0]:g} N  v={row[1]:g} m/s  a={row[2]:g} m/s2  ->  i={row[3]:.6g} A")


@app.command("loops")
def damper_loops(
    frequency: Annotated[float, typer.Option("--frequency", help="f [Hz]")] = 1.5,
    amplitude: Annotated[float, typer.Option("--amplitude", help="a_m [m]")] = 0.0125,
    currents: Annotated[
        str, typer.Option("--currents", help="comma-separated currents [A]")
    ] = "0,0.1,0.2,0.3,0.4",
    model: ModelOpt = "wang-symmetric",
    parameters: ParamsOpt = None,
    hysteresis: HystOpt = None,
    vh_variant: VhOpt = None,
    force_gain: GainOpt = None,
    out: Annotated[
        Path | None, typer.Option("--out", "-o", help="folder for loops.csv and a plot")
    ] = None,
    as_json: JsonOpt = False,
    force: ForceOpt = False,
) -> None:
    """Steady-state F-v and F-x loops of one harmonic test at several currents."""
    from mrsuspension.characterisation import TestCondition, characterise

    with user_errors({"drive current": "--currents"}):
        if out is not None:
            check_output_folder("--out", out, "damper loops", force=force)
        m = _model(model, parameters, hysteresis, vh_variant, force_gain, None)
        conds = [TestCondition(frequency, amplitude, i) for i in _floats("currents", currents)]
        result = characterise(m, conds)
        files = []
        with prepare_output(out, "damper loops", force=force) as folder:
            if out is not None and folder is not None:
                files = save_listed(
                    out, folder, lambda f: [*result.save(f), _plot_result(result, f / "loops.png")]
                )
    _echo_characterisation(result, files, as_json)


def _plot_result(result: Any, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
    for loop in result.loops:
        label = loop.condition.label()
        ax1.plot(loop.velocity, loop.force, label=label)
        ax2.plot(loop.stroke * 1e3, loop.force, label=label)
    ax1.set_xlabel("velocity $v_d$ [m/s]")
    ax2.set_xlabel("stroke $x_d$ [mm]")
    for ax in (ax1, ax2):
        ax.set_ylabel("force $F_d$ [N]")
        ax.grid(True, alpha=0.3)
    ax1.legend(fontsize=7)
    fig.suptitle(f"{result.model['model']} ({result.model['parameter_set']})")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _echo_characterisation(result: Any, files: list[str], as_json: bool) -> None:
    """Print a characterisation's summary rows (or JSON) and the files written."""
    rows = result.summary_rows()
    if as_json:
        typer.echo(json.dumps({"model": result.model, "tests": rows, "files": files}))
        return
    _print_rows(rows)
    for f in files:
        typer.echo(f"wrote {f}")


def _print_rows(rows: list[dict[str, float]]) -> None:
    """A table with two header lines, names and ``[unit]``, each column as wide as needed."""
    keys = list(rows[0])
    heads = [_split_unit(k) for k in keys]
    widths = [max(10, len(name), len(unit)) for name, unit in heads]
    for line in zip(*heads, strict=True):
        typer.echo("  ".join(f"{h:>{w}}" for h, w in zip(line, widths, strict=True)).rstrip())
    for r in rows:
        typer.echo("  ".join(f"{r[k]:{w}.5g}" for k, w in zip(keys, widths, strict=True)))


def _split_unit(label: str) -> tuple[str, str]:
    """``("max rebound force", "[N]")`` from ``"max rebound force [N]"``."""
    name, bracket, unit = label.rpartition(" [")
    return (name, f"[{unit}") if bracket and unit.endswith("]") else (label, "")


@app.command("matrix")
def damper_matrix(
    model: ModelOpt = "wang-symmetric",
    parameters: ParamsOpt = None,
    hysteresis: HystOpt = None,
    vh_variant: VhOpt = None,
    force_gain: GainOpt = None,
    out: Annotated[
        Path | None, typer.Option("--out", "-o", help="folder for summary.csv and loops.csv")
    ] = None,
    as_json: JsonOpt = False,
    force: ForceOpt = False,
) -> None:
    """Run the 165 tests of Table 2.1 on a model (summary per test; loops with --out)."""
    from mrsuspension.characterisation import characterise

    with user_errors():
        if out is not None:
            check_output_folder("--out", out, "damper matrix", force=force)
        m = _model(model, parameters, hysteresis, vh_variant, force_gain, None)
        files = []
        with prepare_output(out, "damper matrix", force=force) as folder:  # before the tests
            result = characterise(m, progress=not as_json)
            if out is not None and folder is not None:
                files = save_listed(out, folder, result.save)
    _echo_characterisation(result, files, as_json)


@app.command("figures")
def damper_figures(
    out: Annotated[Path, typer.Option("--out", "-o", help="output folder")] = Path("results"),
    force: ForceOpt = False,
) -> None:
    """Regenerate the Chapter 2 figures (2.3-2.11) and their index page (merged into a
    report already in OUT, as ``mrsus reproduce --chapters 2``)."""
    from mrsuspension.cli.report import reproduce

    reproduce(out=out, chapters="2", quick=False, force=force)


@app.command("sets")
def damper_sets(
    name: Annotated[str | None, typer.Argument(help="a set name or file to show")] = None,
    as_json: JsonOpt = False,
) -> None:
    """List the registered parameter sets, or show one with units and provenance."""
    from mrsuspension import parameters

    with user_errors():
        if name is None:
            sets = [parameters.get(n) for n in parameters.available()]
            if as_json:
                typer.echo(
                    json.dumps(
                        [{"name": s.name, "model": s.model, "source": s.source} for s in sets]
                    )
                )
                return
            import textwrap

            for s in sets:
                lines = textwrap.wrap(s.source, width=60) or [""]
                typer.echo(f"{s.name:22} {s.model:16} {lines[0]}")
                for more in lines[1:]:
                    typer.echo(f"{'':22} {'':16} {more}")
            return
        s = parameters.resolve(name, model="")
    if as_json:
        typer.echo(json.dumps(s.to_dict()))
        return
    typer.echo(f"{s.name} (model {s.model}, table {s.table})\nsource: {s.source}")
    for k, v in s.items():
        typer.echo(f"  {k:14} {v:14.6g} {s.units.get(k, ''):12} {s.descriptions.get(k, '')}")
