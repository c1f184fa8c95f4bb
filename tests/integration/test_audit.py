"""Issue 17's audit, category by category, as tests: nothing lost, nothing stale, never a
traceback.

Every case runs the real command line (in-process with typer's ``CliRunner``; a
subprocess where a process boundary matters) and checks what the audit asked: the exit
code, one ``error:`` line naming the option or file, no ``Traceback``, and nothing lost
(the previous output folder intact). Checks that live in other test files are listed
here by reference (:func:`_reference`: the case passes when the named test exists, and
the named test does the checking), so this file is the one list of every category.

``python tests/integration/audit_summary.py`` runs this file and prints the table
``category | cases | clean``.
"""

from __future__ import annotations

import contextlib
import importlib.util
import json
import os
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pytest
from typer.testing import CliRunner

from mrsuspension._output import prepare_output
from mrsuspension.cli import app

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "examples" / "scenarios" / "passive-harmonic.toml"
PROBLEM = ROOT / "examples" / "optimize" / "skyhook-gain.toml"
STUDY = ROOT / "examples" / "studies" / "passive-current.toml"
TESTS = Path(__file__).resolve().parent


@dataclass(frozen=True)
class Case:
    """One audited case: its category (a row of the summary), name and check."""

    category: str
    name: str
    check: Callable[[Path], None]

    @property
    def id(self) -> str:
        return f"{self.category}/{self.name}"


CASES: list[Case] = []


def case(category: str, name: str) -> Callable[[Callable[[Path], None]], Callable[[Path], None]]:
    def register(check: Callable[[Path], None]) -> Callable[[Path], None]:
        CASES.append(Case(category, name, check))
        return check

    return register


# -- helpers -------------------------------------------------------------------------------
def _run(args: list[str], env: dict[str, str] | None = None) -> tuple[int, str, str]:
    """``mrsus ARGS`` in-process: exit code, stdout, stderr (a traceback fails the case)."""
    result = CliRunner(env=env).invoke(app, [str(a) for a in args])
    exc = result.exception
    assert exc is None or isinstance(exc, SystemExit), f"traceback: {exc!r}"
    return result.exit_code, result.stdout, result.stderr


def _one_error(args: list[str], *names: str, env: dict[str, str] | None = None) -> str:
    """Run a bad invocation: exit 2, exactly one ``error:`` line naming one of ``names``."""
    code, _out, err = _run(args, env)
    lines = [ln for ln in err.splitlines() if ln.strip() and not ln.startswith("compiling")]
    assert "Traceback" not in err
    assert code == 2, (code, err)
    assert len(lines) == 1, err
    assert lines[0].startswith("error:"), err
    assert any(n in lines[0] for n in names), (names, lines[0])
    return lines[0]


def _reference(path: str, test: str) -> Callable[[Path], None]:
    """A case checked elsewhere: passes when ``path`` defines ``test``."""

    def check(_tmp: Path) -> None:
        source = (ROOT / path).read_text()
        assert f"def {test}(" in source, f"{path} has no {test}"

    return check


def _blocker(tmp: Path) -> Path:
    blocker = tmp / "blocker"
    blocker.write_text("a regular file\n")
    return blocker


def _kept(tmp: Path) -> Path:
    """A previous sweep output folder (to check it is left intact)."""
    out = tmp / "kept"
    with prepare_output(out, "sweep") as folder:
        assert folder is not None
        (folder / "sweep.csv").write_text("frequency [Hz]\n1.0\n")
    return out


def _intact(out: Path) -> None:
    assert (out / "sweep.csv").read_text() == "frequency [Hz]\n1.0\n"
    assert sorted(p.name for p in out.parent.iterdir() if p.name.startswith(f".{out.name}")) == []


# -- tracebacks: unwritable or wrong-kind --out and caches ---------------------------------
OUT_COMMANDS: dict[str, list[str]] = {
    "simulate": ["simulate", str(SCENARIO)],
    "sweep": ["sweep", str(SCENARIO), "-f", "5"],
    "optimize": ["optimize", str(PROBLEM)],
    "identify": ["identify", "{manifest}"],
    "damper loops": ["damper", "loops"],
    "damper matrix": ["damper", "matrix"],
    "damper figures": ["damper", "figures"],
    "reproduce": ["reproduce", "--chapters", "3"],
    "hil run": ["hil", "run", str(SCENARIO)],
    "hil validate": ["hil", "validate", str(SCENARIO)],
}


def _out_case(command: str, where: str) -> None:
    def check(tmp: Path) -> None:
        from mrsuspension.identify import example_campaign

        blocker = _blocker(tmp)
        out = blocker if where == "a file" else blocker / "out"
        manifest = str(example_campaign())
        args = [a.format(manifest=manifest) for a in OUT_COMMANDS[command]]
        _one_error([*args, "--out", str(out)], f"--out '{out}'")
        assert blocker.read_text() == "a regular file\n"

    case("tracebacks", f"{command} --out {where}")(check)


for _command in OUT_COMMANDS:
    _out_case(_command, "a file")
_out_case("study", "a file")
OUT_COMMANDS["study"] = ["study", str(STUDY), "--no-cache"]
_out_case("study", "under a file")
_out_case("reproduce", "under a file")


@case("tracebacks", "study cache folder is a file")
def _(tmp: Path) -> None:
    blocker = _blocker(tmp)
    _one_error(
        ["study", str(STUDY)], "the study cache folder", env={"MRSUSPENSION_CACHE": str(blocker)}
    )


@case("tracebacks", "corrupted study-cache file named")
def _(tmp: Path) -> None:
    _reference(
        "tests/integration/test_cache.py", "test_a_corrupted_cache_file_is_named_and_recomputed"
    )(tmp)


# -- unchecked rates, durations, ports, scheduler, memory ----------------------------------
@case("unchecked input", "hil run --rate 1e9 before the child")
def _(tmp: Path) -> None:
    _one_error(["hil", "run", str(SCENARIO), "--rate", "1e9"], "--rate")


@case("unchecked input", "hil run --duration -1 before the child")
def _(tmp: Path) -> None:
    _one_error(["hil", "run", str(SCENARIO), "--duration", "-1"], "--duration")


@case("unchecked input", "hil run recording memory")
def _(tmp: Path) -> None:
    line = _one_error(
        ["hil", "run", str(SCENARIO), "--duration", "1e5", "--rate", "20000"], "--duration"
    )
    assert "GiB of memory" in line
    assert "loop rate" in line


@case("unchecked input", "simulate duration memory")
def _(tmp: Path) -> None:
    from unittest import mock

    with mock.patch("mrsuspension.engine.settings.memory_limit", return_value=2.0**20):
        line = _one_error(["simulate", str(SCENARIO), "--duration", "1000"], "duration")
    assert "GiB of memory" in line  # a 1 MiB machine: 1000 s do not fit


@case("unchecked input", "rig-emulator --port 70000")
def _(tmp: Path) -> None:
    _one_error(["rig-emulator", "--port", "70000"], "--port")


@case("unchecked input", "monitor --port -1")
def _(tmp: Path) -> None:
    _one_error(["monitor", "--port", "-1"], "--port")


@case("unchecked input", "rig-emulator --host unknown")
def _(tmp: Path) -> None:
    _one_error(["rig-emulator", "--host", "no such host"], "--host")


@case("unchecked input", "study --scheduler malformed")
def _(tmp: Path) -> None:
    _one_error(["study", str(STUDY), "--no-cache", "--scheduler", "tcp://:x:y"], "--scheduler")


@case("unchecked input", "study --workers 0")
def _(tmp: Path) -> None:
    _one_error(["study", str(STUDY), "--no-cache", "--workers", "0"], "--workers")


# -- hangs and slow interrupts -------------------------------------------------------------
@case("hangs", "interrupt inside an output leaves the previous folder")
def _(tmp: Path) -> None:
    kept = _kept(tmp)

    def interrupted() -> None:
        with prepare_output(kept, "sweep") as folder:
            assert folder is not None
            (folder / "sweep.csv").write_text("half")
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        interrupted()
    _intact(kept)


@case("hangs", "Ctrl-C during sweep/study/optimize/reproduce (interrupt tests)")
def _(tmp: Path) -> None:
    found = [p for p in TESTS.glob("test_*interrupt*.py")]
    if not found:
        pytest.skip("the interrupt tests (Ctrl-C within 2 s, no orphans) are another branch's")
    assert any("def test_" in p.read_text() for p in found)


# -- silent garbage or loss ----------------------------------------------------------------
@case("silent garbage", "stale cache after a code change")
def _(tmp: Path) -> None:
    _reference("tests/integration/test_cache.py", "test_a_code_change_misses_the_cache")(tmp)


@case("silent garbage", "harmonic above the output Nyquist rate")
def _(tmp: Path) -> None:
    line = _one_error(["sweep", str(SCENARIO), "-f", "600", "-j", "1"], "output_rate")
    assert "aliased" in line


@case("silent garbage", "--out holding another command's output")
def _(tmp: Path) -> None:
    kept = _kept(tmp)
    _one_error(["optimize", str(PROBLEM), "--out", str(kept)], "holds the output of 'mrsus sweep'")
    _intact(kept)


@case("silent garbage", "--out holding files not written by mrsus")
def _(tmp: Path) -> None:
    mine = tmp / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("mine")
    _one_error(["sweep", str(SCENARIO), "-f", "5", "--out", str(mine)], "not written by mrsus")
    assert [p.name for p in mine.iterdir()] == ["notes.txt"]


@case("silent garbage", "two runs on one --out at once")
def _(tmp: Path) -> None:
    kept = _kept(tmp)
    with contextlib.suppress(RuntimeError), prepare_output(kept, "sweep"):  # a first run
        _one_error(
            ["sweep", str(SCENARIO), "-f", "5", "--out", str(kept)], "being written by another"
        )
        raise RuntimeError("the first run fails: it commits nothing")
    _intact(kept)


@case("silent garbage", "sweep killed (SIGKILL) mid-run: previous --out intact")
def _(tmp: Path) -> None:
    kept = _kept(tmp)
    before = sorted(p.name for p in kept.iterdir())
    child = subprocess.Popen(
        [sys.executable, "-m", "mrsuspension", "sweep", str(SCENARIO), "-f", "log:400:0.5:15",
         "-j", "1", "--out", str(kept)],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True,
    )  # fmt: skip
    deadline = time.monotonic() + 120
    while not [p for p in tmp.iterdir() if p.name.endswith(".tmp")]:  # its staging folder
        assert child.poll() is None, "the sweep ended before it was killed"
        assert time.monotonic() < deadline, "the sweep did not start"
        time.sleep(0.05)
    os.killpg(child.pid, signal.SIGKILL)
    child.wait()
    assert sorted(p.name for p in kept.iterdir()) == before  # the previous output, untouched
    assert (kept / "sweep.csv").read_text() == "frequency [Hz]\n1.0\n"
    code, _out, err = _run(["sweep", str(SCENARIO), "-f", "5", "-j", "1", "--out", str(kept)])
    assert code == 0, err
    assert sorted(p.name for p in tmp.iterdir()) == ["kept"]  # the killed run's temp: gone
    assert "frequency [Hz]" in (kept / "sweep.csv").read_text()


@case("silent garbage", "reproduce --chapters merges into a report")
def _(tmp: Path) -> None:
    from mrsuspension.report.merge import wrap_part

    out = tmp / "report"
    with prepare_output(out, "reproduce") as folder:  # a previous report with chapters 2, 3
        assert folder is not None
        for n in (2, 3):
            (folder / f"chapter{n}").mkdir()
            (folder / f"chapter{n}" / f"old_{n}.png").write_bytes(b"png")
        parts = {"ch2": {"quick": False, "version": "0.0.1", "built": "then"}}
        parts["ch3"] = dict(parts["ch2"])
        manifest = {"version": "0.0.1", "chapters": {"2": {"n": 2}, "3": {"n": 3}}, "parts": parts}
        (folder / "manifest.json").write_text(json.dumps(manifest))
        body = "".join(wrap_part(f"ch{n}", f"<h2 id='ch{n}'>old {n}</h2>") for n in (2, 3))
        (folder / "index.html").write_text(f"<html><body>{body}</body></html>")
    code, _stdout, err = _run(["reproduce", "--chapters", "3", "--quick", "--out", str(out)])
    assert code == 0, err
    page = (out / "index.html").read_text()
    assert "<h2 id='ch2'>old 2</h2>" in page
    assert "old 3" not in page
    assert "href='#ch2'" in page
    assert "href='#ch3'" in page
    assert "different modes and versions" in page  # full 0.0.1 merged with quick now
    assert (out / "chapter2" / "old_2.png").exists()
    assert not (out / "chapter3" / "old_3.png").exists()
    merged = json.loads((out / "manifest.json").read_text())
    assert merged["chapters"]["2"] == {"n": 2}
    assert "3" in merged["chapters"]
    assert merged["parts"]["ch2"]["quick"] is False
    assert merged["parts"]["ch3"]["quick"] is True


@case("silent garbage", "a folder without a marker is no report (nothing guessed)")
def _(tmp: Path) -> None:
    from mrsuspension._output import marked_command

    site = tmp / "site"  # a static site or an e-book: index.html and chapters in manifest
    site.mkdir()
    (site / "index.html").write_text("<html></html>")
    (site / "manifest.json").write_text('{"chapters": {"2": {}}}')
    assert marked_command(site) is None  # issue 26: no guessing from file names
    for args in ([], ["--chapters", "2"], ["--force"]):
        _one_error(["reproduce", "--quick", "--out", str(site), *args], "not written by mrsus")
    assert sorted(p.name for p in site.iterdir()) == ["index.html", "manifest.json"]


@case("silent garbage", "a parameter of 1e308")
def _(tmp: Path) -> None:
    file = tmp / "huge.toml"
    file.write_text('model = "linear"\n[parameters]\nc = { value = 1e308, unit = "N s/m" }\n')
    line = _one_error(["damper", "force", "-v", "0.1", "-m", "linear", "-p", str(file)], "'c'")
    assert "1e+308 N s/m" in line
    assert "huge.toml" in line


@case("silent garbage", "damper force -v 1e300")
def _(tmp: Path) -> None:
    _one_error(["damper", "force", "-v", "1e300"], "--velocity", "-v")


@case("silent garbage", "damper force --peak-velocity 0")
def _(tmp: Path) -> None:
    _one_error(["damper", "force", "-v", "0.1", "--peak-velocity", "0"], "--peak-velocity")


# -- unclear messages ----------------------------------------------------------------------
@case("unclear messages", "a folder where a file is expected")
def _(tmp: Path) -> None:
    line = _one_error(["simulate", str(tmp)], str(tmp))
    assert "folder" in line


@case("unclear messages", "sweep -f log:0:1:2 names the option")
def _(tmp: Path) -> None:
    _one_error(["sweep", str(SCENARIO), "-f", "log:0:1:2"], "--frequencies")


@case("unclear messages", "damper inverse says it saturates and uses |F*|")
def _(tmp: Path) -> None:
    code, out, err = _run(["damper", "inverse", "-f", "-50000", "-v", "0.1"])
    assert code == 0, err
    text = (out + err).lower()
    assert "saturat" in text
    assert "|f*|" in text


@case("unclear messages", "monitor on a port in use")
def _(tmp: Path) -> None:
    with socket.socket() as busy:
        busy.bind(("127.0.0.1", 0))
        busy.listen()
        port = busy.getsockname()[1]
        _one_error(["monitor", "--port", str(port)], "--port")


@case("unclear messages", "Simulation(None) and controller='skyhook'")
def _(tmp: Path) -> None:
    from mrsuspension.engine.simulate import Simulation
    from mrsuspension.errors import ValidationError
    from mrsuspension.excitation import Harmonic

    with pytest.raises(ValidationError, match="excitation"):
        Simulation(None)  # type: ignore[arg-type]
    with pytest.raises(ValidationError, match="skyhook"):
        Simulation(Harmonic(1.5, 0.01), controller="skyhook")  # type: ignore[arg-type]


# -- expectations --------------------------------------------------------------------------
@case("expectations", "hil run --help shows [s]")
def _(tmp: Path) -> None:
    code, out, _err = _run(["hil", "run", "--help"])
    assert code == 0
    assert "[s]" in out


@case("expectations", "mrsus --version and python -m mrsuspension")
def _(tmp: Path) -> None:
    _reference("tests/integration/test_cli_startup.py", "test_version_and_python_dash_m")(tmp)


@case("expectations", "py.typed ships")
def _(tmp: Path) -> None:
    spec = importlib.util.find_spec("mrsuspension")
    assert spec is not None
    assert spec.origin is not None
    assert (Path(spec.origin).parent / "py.typed").is_file()


@case("expectations", "compile notice")
def _(tmp: Path) -> None:
    _reference(
        "tests/integration/test_cli_sim.py",
        "test_compile_notice_only_when_the_engine_cache_is_cold",
    )(tmp)


@case("expectations", "plain progress off-terminal")
def _(tmp: Path) -> None:
    _reference(
        "tests/integration/test_cli.py", "test_reproduce_prints_plain_progress_lines_in_a_log"
    )(tmp)


@case("expectations", "units in sweep.csv headers")
def _(tmp: Path) -> None:
    out = tmp / "out"
    code, _o, err = _run(["sweep", str(SCENARIO), "-f", "5", "-j", "1", "--out", str(out)])
    assert code == 0, err
    header = (out / "sweep.csv").read_text().splitlines()[0].split(",")
    assert all(h.endswith("]") for h in header), header


@case("expectations", "units in study CSV headers and NetCDF attributes")
def _(tmp: Path) -> None:
    import numpy as np
    import xarray as xr

    from mrsuspension.studies.units import add_units, csv_headers

    study = tmp / "study.toml"
    study.write_text(
        '[excitation]\nkind = "harmonic"\nfrequency = 5.0\namplitude = 0.01\n'
        '[grid]\n"controller.current" = [0.0, 0.2]\n'
    )
    for name in ("s.csv", "s.nc"):
        code, _o, err = _run(
            ["study", str(study), "--no-cache", "--workers", "1", "--out", str(tmp / name)]
        )
        assert code == 0, err
    header = (tmp / "s.csv").read_text().splitlines()[0].split(",")
    assert header, "no header"
    assert all(h.endswith("]") for h in header), header  # every column is numeric
    ds = xr.open_dataset(tmp / "s.nc")
    numeric = [n for n in [*ds.data_vars, *ds.coords] if np.asarray(ds[n]).dtype.kind in "fiu"]
    assert numeric, "no numeric variables"
    assert all("units" in ds[n].attrs for n in numeric), numeric
    assert csv_headers(add_units(ds.load())) == {
        n: f"{n} [{ds[n].attrs['units']}]" for n in numeric
    }
    ds.close()


@case("expectations", "units in Parquet metadata")
def _(tmp: Path) -> None:
    _reference("tests/unit/engine/test_units.py", "test_parquet_keeps_scenario_and_units")(tmp)


@case("expectations", "sample rig campaign for mrsus identify")
def _(tmp: Path) -> None:
    from mrsuspension.identify import example_campaign

    manifest = example_campaign()
    assert manifest.name == "manifest.csv"
    assert manifest.is_file()
    assert "mrsus identify manifest.csv" in (ROOT / "README.md").read_text()


@pytest.mark.parametrize("audit", CASES, ids=[c.id for c in CASES])
def test_audit(audit: Case, tmp_path: Path) -> None:
    audit.check(tmp_path)
