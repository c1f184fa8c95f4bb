"""Start-up stays cheap: importing the package and the CLI loads no numerical stack.

``import mrsuspension`` and ``import mrsuspension.cli`` (everything ``mrsus --help``
needs) must not import numba, scipy or matplotlib (nor numpy): they load inside the
functions that use them. Checked in a fresh interpreter.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from typer.testing import CliRunner

HEAVY = ("numba", "scipy", "matplotlib", "numpy", "xarray", "pandas", "rich")


def _loaded(code: str) -> list[str]:
    probe = f"{code}\nimport sys, json\nprint(json.dumps(sorted(sys.modules)))"
    out = subprocess.run(
        [sys.executable, "-c", probe], capture_output=True, text=True, check=True, timeout=120
    ).stdout
    modules = json.loads(out.strip().splitlines()[-1])
    return sorted({m.split(".")[0] for m in modules} & set(HEAVY))


@pytest.mark.parametrize(
    "code",
    [
        "import mrsuspension",
        "import mrsuspension.cli",
        "from mrsuspension.cli import app\n"
        "from typer.main import get_command\n"
        "import contextlib\n"
        "with contextlib.suppress(SystemExit):\n"
        "    get_command(app)(['--help'], prog_name='mrsus')\n"
        "with contextlib.suppress(SystemExit):\n"
        "    get_command(app)(['hil', 'run', '--help'], prog_name='mrsus')",
    ],
    ids=["package", "cli", "help"],
)
def test_no_numerical_stack_at_import(code: str) -> None:
    assert _loaded(code) == []


def test_public_names_still_import() -> None:
    import mrsuspension

    assert set(mrsuspension.__all__) <= set(dir(mrsuspension))
    from mrsuspension import WangSymmetric, make_damper, parameters

    assert isinstance(make_damper("wang-symmetric"), WangSymmetric)
    assert "wang-symmetric-low" in parameters.available()


def test_help_defaults_match_the_library() -> None:
    from mrsuspension import excitation
    from mrsuspension.cli import simulate
    from mrsuspension.cli.identify import identify_command
    from mrsuspension.measures import shock

    assert simulate.DEFAULT_ROAD_PEAK == shock.DEFAULT_ROAD_PEAK
    assert simulate.DEFAULT_SWEEP_POINTS == excitation.DEFAULT_SWEEP_POINTS
    from mrsuspension.cli import _LAZY, plain_help

    doc = plain_help(identify_command.__doc__) or ""
    assert _LAZY["identify"][2] == doc.splitlines()[0]


def test_help_shows_units_and_no_rst() -> None:
    from mrsuspension.cli import app

    runner = CliRunner()
    text = runner.invoke(app, ["hil", "run", "--help"]).stdout
    assert "[s]" in text
    assert "[Hz]" in text
    assert "``" not in text
    assert "identify" in runner.invoke(app, ["--help"]).stdout
    assert "`" not in runner.invoke(app, ["hil", "latency", "--help"]).stdout


def test_version_and_python_dash_m() -> None:
    import mrsuspension

    for args in (["-m", "mrsuspension", "--version"], ["-m", "mrsuspension.cli", "version"]):
        out = subprocess.run(
            [sys.executable, *args], capture_output=True, text=True, check=True, timeout=120
        ).stdout
        assert out.strip() == mrsuspension.__version__


SIMULATE_PROBE = """
import contextlib, gc, json, sys
from typer.main import get_command
from mrsuspension.cli import app
with contextlib.suppress(SystemExit):
    get_command(app)(["simulate", sys.argv[1], "--json"], prog_name="mrsus")
print(json.dumps({"modules": sorted(sys.modules), "gc": gc.isenabled()}))
"""

#: what a plain ``mrsus simulate`` (no --out) has no use for
NOT_FOR_SIMULATE = (
    "matplotlib", "pandas", "xarray", "mrsuspension.identify", "mrsuspension.studies",
    "mrsuspension.optimize", "mrsuspension.report", "mrsuspension.monitor",
)  # fmt: skip


def test_simulate_loads_only_what_it_runs(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """``mrsus simulate`` of a harmonic run imports no plotting, tables or other commands,
    and leaves the garbage collector enabled after pausing it while the engine loads."""
    scenario = tmp_path / "harm.toml"
    scenario.write_text(
        '[excitation]\nkind = "harmonic"\nfrequency = 2.0\namplitude = 0.02\n'
        "[simulation]\nduration = 10.0\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", SIMULATE_PROBE, str(scenario)],
        capture_output=True, text=True, check=True, timeout=300,
    ).stdout  # fmt: skip
    lines = out.strip().splitlines()
    assert "T_as" in json.loads(lines[-2])
    probe = json.loads(lines[-1])
    assert probe["gc"] is True
    loaded = [m for m in probe["modules"] if m.startswith(NOT_FOR_SIMULATE)]
    assert loaded == []
