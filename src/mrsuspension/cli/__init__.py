"""The ``mrsus`` command: a leaf package, one module per command group.

``mrsus reproduce`` regenerates the dissertation's analyses into an HTML report (the
main job); ``mrsus damper ...`` evaluates, characterises and plots damper models;
``simulate``, ``sweep``, ``study``, ``optimize``, ``benchmark``, ``identify``, ``hil ...``,
``rig-emulator``, ``monitor`` and ``bench`` run the rest. Every command imports its
implementation inside the command function (``identify`` is loaded when it is called),
so ``mrsus --help`` imports neither numpy nor numba, scipy or matplotlib. Every error in
the input is reported in one line on stderr with exit code 2. Nothing outside this
package imports it.
"""

from __future__ import annotations

import importlib
import inspect
import re
import sys
from typing import Annotated, Any

import typer
from typer.core import TyperGroup

from mrsuspension.cli import bench as _bench
from mrsuspension.cli import benchmark as _benchmark
from mrsuspension.cli import cache as _cache
from mrsuspension.cli import damper as _damper
from mrsuspension.cli import examples as _examples
from mrsuspension.cli import hil as _hil
from mrsuspension.cli import monitor as _monitor
from mrsuspension.cli import optimize as _optimize
from mrsuspension.cli import report as _report
from mrsuspension.cli import simulate as _simulate
from mrsuspension.cli import study as _study
from mrsuspension.cli.report import _chapters, reproduce
from mrsuspension.errors import MRSuspensionError

__all__ = ["app", "main", "plain_help"]

_ROLE = re.compile(r":[a-z]+(?::[a-z]+)?:`(~?)([^`]+)`")
_LITERAL = re.compile(r"``([^`]+)``|`([^`]+)`")


def plain_help(text: str | None) -> str | None:
    """A docstring as terminal help: RST roles and backticks dropped, text kept.

    Examples
    --------
    >>> plain_help("Run ``SCENARIO`` with :func:`~mrsuspension.hil.loop.run_hil`; see `hil run`.")
    'Run SCENARIO with run_hil; see hil run.'
    """
    if text is None:
        return None

    def role(m: re.Match[str]) -> str:
        return m.group(2).rsplit(".", 1)[-1] if m.group(1) else m.group(2)

    text = _ROLE.sub(role, inspect.cleandoc(text))
    return _LITERAL.sub(lambda m: m.group(1) or m.group(2), text)


#: commands whose implementation module is imported only when the command runs:
#: name -> (module, function, one-line help for ``mrsus --help``)
_LAZY: dict[str, tuple[str, str, str]] = {
    "identify": (
        "mrsuspension.cli.identify",
        "identify_command",
        "Fit a damper model to harmonic tests (MANIFEST) or to one record (--time-domain).",
    ),
}


class _LazyGroup(TyperGroup):
    """A command group that imports the modules of :data:`_LAZY` commands on demand.

    (Contexts and formatters are typed ``Any``: typer 0.29 vendors its own click.)
    """

    def list_commands(self, ctx: Any) -> list[str]:
        names = super().list_commands(ctx)
        return names + [n for n in _LAZY if n not in names]

    def get_command(self, ctx: Any, cmd_name: str) -> Any:
        if cmd_name in _LAZY and cmd_name not in self.commands:
            module, function, _ = _LAZY[cmd_name]
            callback = getattr(importlib.import_module(module), function)
            single = typer.Typer(rich_markup_mode=None)
            single.command(cmd_name, help=plain_help(callback.__doc__))(callback)
            command = typer.main.get_command(single)
            command.name = cmd_name
            self.commands[cmd_name] = command
        return super().get_command(ctx, cmd_name)

    def format_commands(self, ctx: Any, formatter: Any) -> None:
        """The command list, without importing the lazy commands for their help."""
        names = self.list_commands(ctx)
        if not names:
            return
        limit = formatter.width - 6 - max(len(n) for n in names)
        rows = []
        for name in names:
            if name in _LAZY and name not in self.commands:
                rows.append((name, _LAZY[name][2]))
                continue
            command = self.get_command(ctx, name)
            if command is not None and not command.hidden:
                rows.append((name, command.get_short_help_str(limit)))
        with formatter.section("Commands"):
            formatter.write_dl(rows)


def _show_version(value: bool) -> None:
    if value:
        from mrsuspension import __version__

        typer.echo(__version__)
        raise typer.Exit()


# rich_markup_mode=None: plain click help. Rich markup would eat the units in brackets
# ("run time [s]" printed as "run time"), and rich itself costs ~40 ms at start-up.
app = typer.Typer(
    cls=_LazyGroup,
    help="mrsuspension: MR-damper models, semi-active suspension studies and reports.",
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    add_completion=False,
    rich_markup_mode=None,
)


@app.callback()
def _root(
    version: Annotated[
        bool,
        typer.Option(
            "--version", callback=_show_version, is_eager=True, help="print the version and exit"
        ),
    ] = False,
) -> None:
    pass


def _register(target: typer.Typer, name: str, function: Any) -> None:
    target.command(name, help=plain_help(function.__doc__))(function)


def _plain_commands(group: typer.Typer) -> None:
    """Give a sub-app's decorated commands plain help (no RST markup)."""
    for info in group.registered_commands:
        info.help = plain_help(info.help or (info.callback.__doc__ if info.callback else None))


_register(app, "reproduce", reproduce)
_plain_commands(_damper.app)
app.add_typer(_damper.app, name="damper")
_register(app, "simulate", _simulate.simulate_command)
_register(app, "sweep", _simulate.sweep_command)
_register(app, "optimize", _optimize.optimize_command)
_register(app, "study", _study.study)
_register(app, "benchmark", _benchmark.benchmark_command)
_plain_commands(_cache.app)
app.add_typer(_cache.app, name="cache")
_plain_commands(_examples.app)
app.add_typer(_examples.app, name="examples")
_register(_hil.app, "run", _hil.hil_run_command)
_register(_hil.app, "validate", _hil.hil_validate_command)
_register(_hil.app, "latency", _hil.hil_latency_command)
app.add_typer(_hil.app, name="hil")
_register(app, "rig-emulator", _hil.rig_emulator_command)
_register(app, "monitor", _monitor.monitor_command)
_register(app, "bench", _bench.bench)


@app.command()
def version() -> None:
    """Print the package version."""
    from mrsuspension import __version__

    typer.echo(__version__)


def main() -> None:
    """Entry point of the ``mrsus`` command (and ``python -m mrsuspension``)."""
    from mrsuspension.cli.errors import interrupts, plain_warnings

    plain_warnings()
    try:
        with interrupts():  # Ctrl-C / SIGTERM: one line, exit 130 / 143, no orphans
            app(prog_name="mrsus")
    except MRSuspensionError as exc:  # pragma: no cover - commands catch their own
        print(f"error: {exc}", file=sys.stderr)
        sys.exit(2)
    except PermissionError as exc:  # outside a command's user_errors: the same one line
        from mrsuspension.cli.errors import permission_message

        print(f"error: {permission_message(exc)}", file=sys.stderr)
        sys.exit(2)


# kept importable here for callers of the former module (tests/unit/report)
_ = (_chapters, _report)
