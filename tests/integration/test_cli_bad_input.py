"""Every ``mrsus`` command and option, fed bad values: one ``error:`` line, exit code 2.

Like python-control's package-wide keyword test, this walks the typer app itself
(every command and subcommand, with click's ``commands`` and ``params``), so a new
command or option is covered without editing the test. Each numeric option gets
``nan``, ``-1``, ``1e300`` and ``0``; each path gets a missing path and the wrong kind
of entry (a folder where a file is expected, a file where a folder is expected). A case
passes when the command exits with code 2 before doing its work, prints exactly one
error line naming the option, and no traceback. Values that are legitimately valid are
listed in :data:`VALID` with the reason and not run (they would start the real work).
"""

from __future__ import annotations

import signal
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
import typer

from mrsuspension.cli import app

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "examples" / "scenarios" / "passive-harmonic.toml"
PROBLEM = ROOT / "examples" / "optimize" / "skyhook-gain.toml"
STUDY = ROOT / "examples" / "studies" / "passive-current.toml"
#: seconds one invocation may take: every bad value must be refused before the work starts
TIMEOUT = 15.0
BAD_NUMBERS = ("nan", "-1", "1e300", "0")
#: bad values for a text option (a name, a choice, a spec): label -> the value
BAD_TEXTS: dict[str, str] = {
    "empty": "",
    "blank": "   ",
    "unknown": "no-such-choice",
    "long": "x" * 5000,
}

#: arguments a command needs besides the option under test (``{name}`` is a fixture path)
BASE: dict[str, list[str]] = {
    "examples copy": ["scenarios/passive-harmonic.toml"],
    "simulate": ["{scenario}"],
    "sweep": ["{scenario}"],
    "optimize": ["{problem}"],
    "study": ["{study}"],
    "hil run": ["{scenario}"],
    "hil validate": ["{scenario}"],
    "identify": ["{manifest}"],
    "damper force": ["-v", "0.1"],
    "damper inverse": ["-f", "500", "-v", "0.1"],
    "monitor": ["--port", "{port}"],  # a free port: 8765 may be busy on a shared machine
}

#: text options that carry numbers (comma-separated lists): fed the bad numbers too
NUMERIC_TEXT = {
    ("damper force", "--velocity"),
    ("damper force", "--stroke"),
    ("damper force", "--acceleration"),
    ("damper force", "--current"),
    ("damper inverse", "--force"),
    ("damper inverse", "--velocity"),
    ("damper inverse", "--acceleration"),
    ("damper loops", "--currents"),
    ("sweep", "--frequencies"),
    ("hil validate", "--frequencies"),
    ("hil validate", "--masses"),
}

#: what a path parameter names: an input file, an input folder, an output folder or an
#: output file. A new path parameter must be added here (the test says so).
PATH_KIND: dict[tuple[str, str], str] = {
    ("simulate", "scenario"): "in-file",
    ("sweep", "scenario"): "in-file",
    ("optimize", "problem"): "in-file",
    ("study", "path"): "in-file",
    ("benchmark", "spec"): "in-file",
    ("hil run", "scenario"): "in-file",
    ("hil validate", "scenario"): "in-file",
    ("identify", "manifest"): "in-file-or-folder",
    ("monitor", "--road-dir"): "in-folder",
    ("study", "--out"): "out-file",
    ("reproduce", "--out"): "out-folder",
    ("simulate", "--out"): "out-folder",
    ("sweep", "--out"): "out-folder",
    ("optimize", "--out"): "out-folder",
    ("benchmark", "--out"): "out-folder",
    ("hil run", "--out"): "out-folder",
    ("hil validate", "--out"): "out-folder",
    ("identify", "--out"): "out-folder",
    ("damper loops", "--out"): "out-folder",
    ("damper matrix", "--out"): "out-folder",
    ("damper figures", "--out"): "out-folder",
    ("monitor", "--workdir"): "out-folder",
    ("examples copy", "--to"): "out-folder",
    ("monitor", "--token-file"): "in-file",
    ("hil run", "--token-file"): "in-file",
}

#: (command, option, value) -> why the value is valid (the case is not run)
VALID: dict[tuple[str, str, str], str] = {
    ("rig-emulator", "--port", "0"): "0 binds any free port (said in the help)",
    ("rig-emulator", "--drop", "0"): "no dropped replies (the default)",
    ("rig-emulator", "--delay", "0"): "no extra delay (the default)",
    ("rig-emulator", "--heartbeat", "0"): "no heartbeats (said in the help)",
    ("rig-emulator", "--watchdog", "0"): "no watchdog (said in the help)",
    ("hil latency", "--work-us", "0"): "an empty tick (the default)",
    ("identify", "--seed", "0"): "a seed (the default)",
    ("identify", "--force-delay", "0"): "no force delay (the default)",
    ("damper force", "--velocity", "-1"): "a velocity of either sign",
    ("damper force", "--velocity", "0"): "a velocity of either sign",
    ("damper force", "--stroke", "-1"): "a stroke of either sign [m] (not range-checked)",
    ("damper force", "--stroke", "0"): "the default",
    ("damper force", "--acceleration", "-1"): "an acceleration of either sign",
    ("damper force", "--acceleration", "0"): "the default",
    ("damper force", "--current", "0"): "the default (no current)",
    ("damper inverse", "--force", "-1"): "a force of either sign (only |F*| is used, said)",
    ("damper inverse", "--force", "0"): "no force: current 0",
    ("damper inverse", "--velocity", "-1"): "a velocity of either sign",
    ("damper inverse", "--velocity", "0"): "zero velocity: the current saturates, said",
    ("damper inverse", "--acceleration", "-1"): "an acceleration of either sign",
    ("damper inverse", "--acceleration", "0"): "the default",
    ("damper loops", "--currents", "0"): "one loop at no current",
    # a token of 16 or more URL-safe characters is valid (shorter ones are refused)
    ("monitor", "--token", "long"): "a token of 5000 characters",
    ("hil run", "--token", "long"): "a token of 5000 characters",
    ("identify", "--name", "*"): "the fitted set's name is any text",
    ("identify", "--compare", "empty"): "no comparison models (the default)",
    ("identify", "--compare", "blank"): "no comparison models (the default)",
}
for _kind_cmd, _opt in [(c, o) for (c, o), k in PATH_KIND.items() if k == "out-folder"]:
    VALID[(_kind_cmd, _opt, "missing")] = "an output folder is created"
VALID[("identify", "manifest", "folder")] = "a folder of test files is a valid campaign"


@dataclass(frozen=True)
class Case:
    """One invocation: the command, the parameter under test and the bad value."""

    command: str
    param: str  # the long option ("--port") or the argument's name ("scenario")
    value: str  # "nan", "-1", ..., or "missing" / "folder" / "file" for paths
    names: tuple[str, ...]  # what the error line must mention (any of them)
    args: tuple[str, ...]

    @property
    def id(self) -> str:
        return f"{self.command}:{self.param}={self.value}"


def _leaves(group: Any, prefix: str = "") -> Iterator[tuple[str, Any]]:
    from typer._click.core import Context

    ctx = Context(group)
    for name in group.list_commands(ctx):
        command = group.get_command(ctx, name)
        full = f"{prefix} {name}".strip()
        if hasattr(command, "list_commands"):
            yield from _leaves(command, full)
        else:
            yield full, command


def _kind(param: Any) -> str:
    annotation = param.type_descriptor.annotation
    text = str(annotation)
    if annotation is bool or text.startswith("bool"):
        return "flag"
    if "Path" in text:
        return "path"
    if annotation in (int, float) or text in ("int | None", "float | None"):
        return "number"
    return "text"


def _long(param: Any) -> str:
    if param.param_type_name == "argument":
        return str(param.name)
    return max((o for o in param.opts if o.startswith("--")), key=len)


def _cases(paths: dict[str, str]) -> Iterator[Case]:
    for command, click_command in _leaves(typer.main.get_command(app)):
        base = [a.format(**paths) for a in BASE.get(command, [])]
        for param in click_command.params:
            if param.name == "help":
                continue
            key = _long(param)
            kind = _kind(param)
            if kind == "number" or (command, key) in NUMERIC_TEXT:
                values: tuple[str, ...] = BAD_NUMBERS
            elif kind == "path":
                where = PATH_KIND.get((command, key))
                assert where is not None, f"classify the path {command} {key} in PATH_KIND"
                values = ("missing", "file") if where.endswith("folder") else ("missing", "folder")
            elif kind == "text" and not key.endswith("-completion"):
                values = tuple(BAD_TEXTS)
            else:
                continue
            for value in values:
                if (command, key, value) in VALID or (command, key, "*") in VALID:
                    continue
                text = {"missing": paths["missing"], "folder": paths["folder"],
                        "file": paths["file"], **BAD_TEXTS}.get(value, value)  # fmt: skip
                if param.param_type_name == "argument":
                    args = [text if a == base[0] else a for a in base] if base else [text]
                    names: tuple[str, ...] = (text, Path(text).name)
                else:
                    args = [*base, key, text]
                    names = tuple(param.opts)
                yield Case(command, key, value, names, tuple(command.split()) + tuple(args))


class _Timeout(BaseException):
    """Raised by the alarm (a BaseException: CliRunner does not swallow it)."""


@contextmanager
def _deadline(seconds: float) -> Iterator[None]:
    def ring(_signum: int, _frame: Any) -> None:
        raise _Timeout

    old = signal.signal(signal.SIGALRM, ring)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


def _problem(case: Case, code: int, stderr: str, exception: BaseException | None) -> str | None:
    """What is wrong with one outcome, or None."""
    if "Traceback" in stderr or (exception is not None and not isinstance(exception, SystemExit)):
        return f"traceback: {exception!r}"
    if code != 2:
        return f"exit code {code}; stderr {stderr.strip()[-200:]!r}"
    lines = [ln for ln in stderr.splitlines() if ln.strip()]
    ours = [ln for ln in lines if ln.startswith("error:")]
    # a value click itself cannot parse (nan for an integer): its usage block ends in one
    # "Error: Invalid value for '--x'" line
    clicks = [ln for ln in lines if ln.startswith("Error:")]
    if len(ours) == 1 and len(lines) == 1:
        line = ours[0]
    elif len(clicks) == 1 and not ours and lines[0].startswith("Usage:"):
        line = clicks[0]
    else:
        return f"not one error line: {stderr!r}"
    if not any(" ".join(n.split()) in line for n in case.names):  # messages fold blanks
        return f"the error does not name {' / '.join(case.names)}: {line!r}"
    return None


@pytest.fixture(scope="module")
def paths(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    from mrsuspension.identify import synthetic_campaign

    root = tmp_path_factory.mktemp("bad-input")
    (root / "a-folder").mkdir()
    (root / "a-file.txt").write_text("not a folder\n")
    manifest = synthetic_campaign(root / "campaign", "wang-symmetric", [(1.5, 0.0125, 0.1)])
    import socket

    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    return {
        "port": str(port),
        "scenario": str(SCENARIO),
        "problem": str(PROBLEM),
        "study": str(STUDY),
        "manifest": str(manifest),
        "missing": str(root / "no-such-thing"),
        "folder": str(root / "a-folder"),
        "file": str(root / "a-file.txt"),
    }


def test_every_option_refuses_bad_values(paths: dict[str, str]) -> None:
    # the click command built once: typer's runner rebuilds it from the app on every
    # invoke (50 ms; 0.3 ms here), which made this walk of 400 cases take 20-27 s
    from click.testing import CliRunner as ClickRunner

    runner = ClickRunner()
    command = typer.main.get_command(app)
    cases = list(_cases(paths))
    failures = []
    for case in cases:
        try:
            with _deadline(TIMEOUT):
                result = runner.invoke(command, list(case.args))
        except _Timeout:
            failures.append(f"{case.id}: still running after {TIMEOUT:g} s")
            continue
        problem = _problem(case, result.exit_code, result.stderr, result.exception)
        if problem is not None:
            failures.append(f"{case.id}: {problem}")
    commands = {c.command for c in cases}
    options = {(c.command, c.param) for c in cases}
    print(
        f"\n{len(commands)} commands, {len(options)} options, {len(cases)} bad-value cases; "
        f"{len(VALID)} valid values listed"
    )
    assert not failures, f"{len(failures)} of {len(cases)} cases:\n" + "\n".join(failures)


def test_the_valid_list_names_real_options(paths: dict[str, str]) -> None:
    """An entry of :data:`VALID` or :data:`PATH_KIND` that no longer exists is removed."""
    real = {
        (command, _long(p))
        for command, c in _leaves(typer.main.get_command(app))
        for p in c.params
        if p.name != "help"
    }
    stale = {(c, o) for c, o, _ in VALID} - real
    stale |= set(PATH_KIND) - real
    stale |= NUMERIC_TEXT - real
    assert not stale
