"""Issue 26 section 5: bounded work and clean refusals, on the real command line.

Each case runs ``mrsus`` in-process (typer's ``CliRunner``) and checks that the command
is refused before its work starts (within a few seconds), with exit code 2 and one
``error:`` line naming the input and the limit; or, for a big but allowed job, that it
shows progress with an estimate. Inputs: files nested hundreds of levels deep (every
reader), counts with no upper bound, runs and fits whose memory cannot fit, a Dask
scheduler that accepts TCP and never answers, unreadable files, and edge inputs that
must not leak a ``RuntimeWarning``.
"""

from __future__ import annotations

import io
import socket
import threading
import time
import warnings
from collections.abc import Callable, Iterator
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from mrsuspension.cli import app

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "examples" / "scenarios" / "passive-harmonic.toml"
SWEPT = ROOT / "examples" / "scenarios" / "linear-swept.toml"
PROBLEM = ROOT / "examples" / "optimize" / "skyhook-gain.toml"
STUDY = ROOT / "examples" / "studies" / "passive-current.toml"
#: seconds a refusal may take: it must come before any work (generous for a loaded machine)
QUICK = 10.0
DEEP = 400


def _run(args: list[object]) -> tuple[int, str, str, float]:
    """``mrsus ARGS`` in-process: exit code, stdout, stderr, seconds (no traceback)."""
    start = time.monotonic()
    result = CliRunner().invoke(app, [str(a) for a in args])
    elapsed = time.monotonic() - start
    exc = result.exception
    assert exc is None or isinstance(exc, SystemExit), f"traceback: {exc!r}"
    return result.exit_code, result.stdout, result.stderr, elapsed


def _refused(args: list[object], *names: str) -> str:
    """Exit 2 within :data:`QUICK` s, one ``error:`` line holding every one of ``names``."""
    code, _out, err, elapsed = _run(args)
    lines = [ln for ln in err.splitlines() if ln.strip() and not ln.startswith("compiling")]
    assert "Traceback" not in err
    assert code == 2, (code, err)
    assert len(lines) == 1, err
    assert lines[0].startswith("error:"), err
    for name in names:
        assert name in lines[0], (name, lines[0])
    assert elapsed < QUICK, f"refused only after {elapsed:.1f} s: {lines[0]}"
    return lines[0]


# -- input files nested hundreds of levels deep, in every reader ---------------------------
def _deep_array(key: str = "a") -> str:
    return f"{key} = " + "[" * DEEP + "1" + "]" * DEEP + "\n"


def _deep_tables(prefix: str) -> str:
    return f"[{prefix}" + ".a" * DEEP + "]\nx = 1\n"


DEEP_FILES: dict[str, tuple[str, str, Callable[[Path], list[object]]]] = {
    "scenario (TOML)": ("s.toml", _deep_array(), lambda p: ["simulate", p]),
    "study (TOML tables)": ("st.toml", _deep_tables("grid"), lambda p: ["study", p, "--no-cache"]),
    "optimisation problem (TOML)": ("o.toml", _deep_array(), lambda p: ["optimize", p]),
    "parameter file (JSON)": (
        "p.json",
        '{"model": "linear", "parameters": ' + "[" * DEEP + "]" * DEEP + "}",
        lambda p: ["damper", "force", "-m", "linear", "-v", "0.1", "-p", p],
    ),
    "parameter file (TOML)": (
        "p.toml",
        'model = "linear"\n' + _deep_tables("parameters"),
        lambda p: ["damper", "force", "-m", "linear", "-v", "0.1", "-p", p],
    ),
    "identification manifest (TOML)": (
        "manifest.toml",
        _deep_array("test"),
        lambda p: ["identify", p],
    ),
    "hil scenario (TOML)": ("h.toml", _deep_array(), lambda p: ["hil", "validate", p]),
}


@pytest.mark.audit("bounded work")
@pytest.mark.parametrize("reader", list(DEEP_FILES))
def test_deeply_nested_input_is_refused(reader: str, tmp_path: Path) -> None:
    name, text, args = DEEP_FILES[reader]
    path = tmp_path / name
    path.write_text(text)
    _refused(args(path), name, "more than 32 levels deep")


# -- counts with no upper bound --------------------------------------------------------------
@pytest.mark.audit("bounded work")
@pytest.mark.parametrize("n", ["1000000000", "100000000000000000000"])
def test_sweep_frequency_count_is_bounded(n: str) -> None:
    _refused(
        ["sweep", SCENARIO, "-f", f"log:{n}:0.5:15", "--workers", "1"], "--frequencies", "10000"
    )


@pytest.mark.audit("bounded work")
@pytest.mark.parametrize("n", ["1000000000", "1" + "0" * 5000])
def test_study_frequency_spec_is_bounded(n: str, tmp_path: Path) -> None:
    study = tmp_path / "s.toml"
    study.write_text(STUDY.read_text().replace('"log:6:0.8:3"', f'"log:{n}:0.8:3"'))
    _refused(["study", study, "--no-cache"], "[excitation] frequencies", "10000")


@pytest.mark.audit("bounded work")
def test_study_of_a_million_runs_is_refused_with_an_estimate(tmp_path: Path) -> None:
    values = ", ".join(f"{v:.6f}" for v in np.linspace(0.0, 0.5, 1000))
    masses = ", ".join(f"{v:.3f}" for v in np.linspace(300.0, 700.0, 1000))
    study = tmp_path / "big.toml"
    study.write_text(
        '[excitation]\nkind = "harmonic"\nfrequency = 2.0\namplitude = 0.01\n'
        f'[grid]\n"controller.current" = [{values}]\n"vehicle.sprung_mass" = [{masses}]\n'
    )
    line = _refused(["study", study, "--no-cache"], "1000000 runs", "1000 x 1000", "100000")
    assert " min " in line  # the estimate of what checking it alone would take


@pytest.mark.audit("bounded work")
def test_optimiser_budgets_are_bounded(tmp_path: Path) -> None:
    _refused(["optimize", PROBLEM, "--max-evaluations", 10**12], "--max-evaluations", "100000")
    problem = tmp_path / "p.toml"
    problem.write_text(PROBLEM.read_text().replace("population = 10", f"population = {10**20}"))
    _refused(["optimize", problem], "[problem] population", "100000")


@pytest.mark.audit("bounded work")
def test_big_study_shows_progress_with_an_estimate(monkeypatch: pytest.MonkeyPatch) -> None:
    """A grid being checked reports ``(done, total)``; plain progress lines say the time left."""
    from mrsuspension import _progress
    from mrsuspension.studies import Study

    calls: list[tuple[int, int]] = []
    study = Study.from_dict(
        {
            "excitation": {"kind": "harmonic", "frequency": 2.0, "amplitude": 0.01},
            "grid": {"controller.current": [0.01 * k for k in range(12)]},
        },
        progress=lambda done, total: calls.append((done, total)),
    )
    assert len(study) == 12
    assert calls[-1] == (12, 12)
    assert len(calls) == 12

    clock = iter([0.0, 0.0, 10.0, 10.0, 40.0])  # start, then two updates and the final line
    monkeypatch.setattr(_progress.time, "monotonic", lambda: next(clock))
    log = io.StringIO()
    with _progress.progress_bar(True, "study big: checking 400 grid points", stream=log) as tick:
        assert tick is not None
        tick(100, 400)
        tick(400, 400)
    first = log.getvalue().splitlines()[0]
    assert first == "study big: checking 400 grid points: 100/400 (25 %), 10 s, about 30 s left"


@pytest.mark.audit("bounded work")
def test_identification_budgets_are_bounded(tmp_path: Path) -> None:
    from mrsuspension.identify import synthetic_campaign

    manifest = synthetic_campaign(tmp_path, "linear", [(1.0, 0.01, 0.0)])
    _refused(["identify", manifest, "--multistart", 10**9], "--multistart", "<= 1000")
    _refused(["identify", manifest, "--max-nfev", 10**12], "--max-nfev", "<= 100000")


# -- runs or fits whose memory cannot fit ------------------------------------------------------
@pytest.mark.audit("bounded work")
def test_records_that_cannot_fit_are_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A swept scenario keeps every run's record: together they are checked before the
    first run (each one alone fits: the limit is set between the two)."""
    from mrsuspension.engine import settings

    freqs = ", ".join(f"{f:.6g}" for f in np.geomspace(0.5, 15.0, 200))
    scenario = tmp_path / "many.toml"
    scenario.write_text(SWEPT.read_text().replace("[1.0, 1.5, 4.0, 10.0, 15.0]", f"[{freqs}]"))
    monkeypatch.setattr(settings, "memory_limit", lambda: 64.0 * 2**20)  # 64 MiB
    line = _refused(["simulate", scenario], "keeping the records of 200 runs", "GiB allowed")
    assert "fewer" in line


@pytest.mark.audit("bounded work")
def test_time_domain_fit_that_cannot_fit_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    from mrsuspension.engine import settings
    from mrsuspension.errors import ValidationError
    from mrsuspension.identify import fit_time_domain, synthetic_record

    record = synthetic_record(duration=1.0, noise=0.0, seed=1)
    monkeypatch.setattr(settings, "memory_limit", lambda: 64.0 * 2**10)  # 64 kB
    with pytest.raises(ValidationError, match="time-domain fit of 2100 training samples") as info:
        fit_time_domain(record, "bingham", starts=1, max_nfev=2)
    assert "resample" in str(info.value)


# -- a Dask scheduler that accepts TCP and never answers ------------------------------------
@pytest.fixture
def mute_server() -> Iterator[int]:
    """A TCP server that accepts connections and never sends a byte."""
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen(8)
    held: list[socket.socket] = []
    stop = threading.Event()

    def accept() -> None:
        srv.settimeout(0.1)
        while not stop.is_set():
            try:
                held.append(srv.accept()[0])
            except OSError:
                continue

    thread = threading.Thread(target=accept, daemon=True)
    thread.start()
    yield srv.getsockname()[1]
    stop.set()
    thread.join(5.0)
    for conn in held:
        conn.close()
    srv.close()


@pytest.mark.audit("bounded work")
def test_mute_dask_scheduler_is_refused_in_bounded_time(mute_server: int) -> None:
    address = f"tcp://127.0.0.1:{mute_server}"
    args = ["study", STUDY, "--no-cache", "--scheduler", address, "--scheduler-timeout", "0.5"]
    _refused(args, address, "no Dask handshake within 0.5 s", "--scheduler-timeout")


@pytest.mark.audit("bounded work")
def test_run_study_on_a_mute_scheduler_is_refused(mute_server: int) -> None:
    from mrsuspension.errors import ValidationError
    from mrsuspension.studies import Study, run_study

    study = Study.load(STUDY)
    start = time.monotonic()
    with pytest.raises(ValidationError, match="no Dask handshake"):
        run_study(
            study,
            executor=f"127.0.0.1:{mute_server}",
            progress=False,
            cache_dir=False,
            scheduler_timeout=0.5,
        )
    assert time.monotonic() - start < QUICK


# -- unreadable files (PermissionError) -------------------------------------------------------
@pytest.mark.audit("bounded work")
def test_unreadable_input_file_is_one_line(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Tests run as root (chmod 000 does not stop a read): the read itself is made to fail."""
    scenario = tmp_path / "locked.toml"
    scenario.write_text(SCENARIO.read_text())
    real = Path.read_bytes

    def read_bytes(self: Path) -> bytes:
        if self.name == "locked.toml":
            raise PermissionError(13, "Permission denied", str(self))
        return real(self)

    monkeypatch.setattr(Path, "read_bytes", read_bytes)
    _refused(
        ["simulate", scenario], "cannot read scenario file", "locked.toml", "Permission denied"
    )
    _refused(["study", scenario, "--no-cache"], "locked.toml", "Permission denied")


@pytest.mark.audit("bounded work")
def test_permission_error_anywhere_is_one_line(monkeypatch: pytest.MonkeyPatch) -> None:
    """Any PermissionError a command meets (here: the study's loader) is one line, exit 2."""
    from mrsuspension.studies import Study

    def denied(*_args: object, **_kwargs: object) -> None:
        raise PermissionError(13, "Permission denied", "/srv/shared/base.toml")

    monkeypatch.setattr(Study, "load", denied)
    _refused(["study", STUDY, "--no-cache"], "permission denied: '/srv/shared/base.toml'")


# -- no RuntimeWarning on edge inputs ---------------------------------------------------------
def _edge_inputs(tmp: Path) -> list[list[object]]:
    t = np.arange(0.0, 2.0, 1e-3)
    x = 0.01 * np.sin(2 * np.pi * t)
    v = np.gradient(x, t)

    def record(name: str, force: np.ndarray, disp: np.ndarray = x, vel: np.ndarray = v) -> Path:
        rows = "\n".join(
            f"{a:g},{b:g},{c:g},{d:g},0.2" for a, b, c, d in zip(t, disp, vel, force, strict=True)
        )
        (tmp / name).write_text("t,x,v,F,i\n" + rows + "\n")
        return tmp / name

    flat = tmp / "flat.csv"
    flat.write_text("distance,elevation\n" + "".join(f"{k},0\n" for k in range(40)))
    road = tmp / "flat.toml"
    road.write_text('[excitation]\nkind = "road"\nprofile = "flat.csv"\n')
    const = record("const.csv", np.full(t.size, 100.0))
    still = record("still.csv", 500.0 * np.sin(t), np.zeros(t.size), np.zeros(t.size))
    (tmp / "empty.csv").write_text("t,x,v,F,i\n")
    return [
        ["simulate", road, "--duration", "0.5"],  # a flat road: every measure 0
        ["simulate", road, "--duration", "0.001"],  # a record of two samples
        ["damper", "force", "-m", "spencer", "-v", "0"],
        ["damper", "inverse", "-m", "linear", "-f", "0", "-v", "0"],
        ["identify", "--time-domain", const],  # constant force
        ["identify", "--time-domain", still],  # constant displacement
        ["identify", "--time-domain", tmp / "empty.csv"],  # zero-length record
    ]


@pytest.mark.audit("bounded work")
def test_edge_inputs_leak_no_runtime_warning(tmp_path: Path) -> None:
    for args in _edge_inputs(tmp_path):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            code, out, err, _ = _run(args)
        leaked = [str(w.message) for w in caught if issubclass(w.category, RuntimeWarning)]
        assert not leaked, (args, leaked)
        assert "RuntimeWarning" not in out + err, (args, err)
        assert code in (0, 2), (args, code, err)
