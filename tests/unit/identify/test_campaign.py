"""The whole pipeline on messy campaigns: every test is accounted for, none silently."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from mrsuspension import parameters
from mrsuspension.dampers import make_damper
from mrsuspension.errors import ValidationError
from mrsuspension.identify import identify, synthetic_campaign
from mrsuspension.identify.campaign import parse_bands

GOOD = [(f, a, i) for f, a in [(1.5, 0.0125), (2.5, 0.0125)] for i in (0.0, 0.2, 0.4)]


def add_bad_tests(folder: Path, manifest: Path) -> list[str]:
    """Append one test per kind of bad data; return their file names."""
    t = np.arange(0.0, 2.0, 1e-3)
    x = 0.0125 * np.sin(2 * np.pi * 1.5 * t)
    f = 1000.0 * np.tanh(x / 0.002)

    def save(name: str, header: str, cols) -> str:
        np.savetxt(folder / name, np.column_stack(cols), delimiter=",", header=header, comments="")
        return name

    names = [
        save("no_force.csv", "time,displacement", [t, x]),
        save("nans.csv", "time,displacement,force", [t, x, np.where(t > 1.2, np.nan, f)]),
        save("time_back.csv", "time,displacement,force", [np.r_[t[:900], t[899:-1]], x, f]),
        save("short.csv", "time,displacement,force", [t[:400], x[:400], f[:400]]),
        save("no_current.csv", "time,displacement,force", [t, x, f]),
        "missing.csv",
    ]
    rows = [f"{n},0.2,1.5,0.0125,," for n in names[:4]] + [
        "no_current.csv,,1.5,0.0125,,",
        "missing.csv,0.2,1.5,0.0125,,",
    ]
    with manifest.open("a") as fh:
        fh.write("\n".join(rows) + "\n")
    return names


def test_bad_tests_are_reported_and_the_rest_fit(tmp_path: Path) -> None:
    manifest = synthetic_campaign(tmp_path, "wang-symmetric", GOOD, noise=0.01, layout="mixed")
    bad = add_bad_tests(tmp_path, manifest)
    result = identify(manifest, multistart=1)
    by_file = {t.file: t for t in result.tests}
    assert len(result.tests) == len(GOOD) + len(bad)  # nothing dropped
    expected = {
        "no_force.csv": "no force column (found: time, displacement)",
        "nans.csv": "799 of 2000 rows (40.0 %) hold NaN or infinite values in force (first at "
        "data row 1202, t = 1.201 s)",
        "time_back.csv": "time is not increasing at data row 901",
        "short.csv": "no whole cycle",
        "no_current.csv": "no drive current: the manifest gives none",
        "missing.csv": "file not found",
    }
    for name, text in expected.items():
        assert by_file[name].status == "error"
        assert text in by_file[name].message, by_file[name].message
        assert by_file[name].nrmse is None
    good = [t for t in result.tests if t.file not in expected]
    assert all(t.status == "ok" and t.nrmse is not None and t.nrmse < 0.01 for t in good)
    data = result.to_dict()
    assert data["fitted"] == len(GOOD)
    assert data["failed"] == len(bad)
    json.dumps(data, allow_nan=False)  # strict JSON


def test_non_converged_fit_is_said_on_every_test(tmp_path: Path) -> None:
    manifest = synthetic_campaign(tmp_path, "wang-symmetric", GOOD[:3])
    start = parameters.get("wang-symmetric-low").replace(a0=500.0, k2=5.0)
    result = identify(manifest, start=start, multistart=1, max_nfev=2)
    assert not result.fits[0].result.converged  # type: ignore[union-attr]
    for t in result.tests:
        assert t.status in ("warning", "poor-fit")
        assert t.nrmse is not None
    assert any("did not converge" in t.message for t in result.tests)
    assert any("did not converge" in n for n in result.notes)


def test_poor_fit_is_flagged(tmp_path: Path) -> None:
    manifest = synthetic_campaign(tmp_path, "wang-symmetric", GOOD[:3])
    text = manifest.read_text().replace("_0.4A_1.5Hz.csv,0.4,", "_0.4A_1.5Hz.csv,0.0,")
    manifest.write_text(text)  # the 0.4 A test is listed as 0 A
    result = identify(manifest, multistart=1)
    flagged = [t for t in result.tests if t.status == "poor-fit"]
    assert [t.file for t in flagged] == ["test03_0.4A_1.5Hz.csv"]
    assert "check this test's current, units and sign" in flagged[0].message


def test_bands_fit_separately_and_a_failing_band_does_not_stop_the_other(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    conds = [(f, 0.005, i) for f in (1.5, 5.0, 10.0, 20.0) for i in (0.0, 0.3)]
    manifest = synthetic_campaign(tmp_path, "bingham", conds)
    result = identify(manifest, "bingham", bands="0.5-5,5-15")
    labels = [t.band for t in result.tests if t.fitted]
    assert labels.count("0.5-5 Hz") == 4
    assert labels.count("5-15 Hz") == 4
    outside = [t for t in result.tests if t.status == "error"]
    assert len(outside) == 2
    assert "outside every band" in outside[0].message
    assert set(result.parameter_sets) == {"0.5-5 Hz", "5-15 Hz"}
    assert isinstance(result.to_dict()["parameters"]["5-15 Hz"], dict)

    from mrsuspension.identify import campaign

    real = campaign.fit_loops

    def flaky(loops, model, **kw):
        if min(lp.frequency for lp in loops) > 4.9:
            raise campaign.MRSuspensionError("solver exploded")
        return real(loops, model, **kw)

    monkeypatch.setattr(campaign, "fit_loops", flaky)
    result = identify(manifest, "bingham", bands="0.5-5,5-15")
    failed = [t for t in result.tests if t.status == "fit-failed"]
    assert {t.band for t in failed} == {"5-15 Hz"}
    assert "solver exploded" in failed[0].message
    assert all(t.nrmse is not None for t in result.tests if t.band == "0.5-5 Hz")


def test_a_campaign_without_usable_tests_is_a_user_error(tmp_path: Path) -> None:
    m = tmp_path / "m.csv"
    m.write_text("file,current\na.csv,0.1\nb.csv,0.2\n")
    with pytest.raises(
        ValidationError, match=r"none of the 2 tests in m.csv could be used \(a.csv: "
    ):
        identify(m)
    with pytest.raises(ValidationError, match="unknown damper model"):
        identify(m, "wang")
    with pytest.raises(ValidationError, match="--bands"):
        parse_bands("0.5..5")


def test_outputs_load_into_the_simulator(tmp_path: Path) -> None:
    manifest = synthetic_campaign(tmp_path / "data", "wang-symmetric", GOOD[:4], noise=0.01)
    result = identify(manifest, compare="bingham", multistart=1)
    files = result.save(tmp_path / "out")
    names = {p.relative_to(tmp_path / "out").as_posix() for p in files}
    assert {
        "parameters.toml",
        "compare-bingham.toml",
        "tests.csv",
        "summary.json",
        "index.html",
    } <= names
    assert sum(n.startswith("plots/") for n in names) == 4
    pset = parameters.load(tmp_path / "out" / "parameters.toml")
    assert pset.source.startswith(f"fitted by mrsuspension identify from {manifest} on ")
    damper = make_damper("wang-symmetric", tmp_path / "out" / "parameters.toml")
    t = np.arange(0.0, 1.0, 1e-3)
    r = damper.response(t, 0.01 * np.sin(2 * math.pi * 2 * t), current=0.2)
    assert np.all(np.isfinite(r.force))
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["best_model"] == "wang-symmetric"
    assert summary["parameters"] == pytest.approx(dict(pset.values))
    page = (tmp_path / "out" / "index.html").read_text()
    assert "wang-symmetric fits better" in page
    assert all(t.file in page for t in result.tests)
    rows = (tmp_path / "out" / "tests.csv").read_text().splitlines()
    assert len(rows) == 1 + len(result.tests)
    assert "nrmse_bingham" in rows[0]


def test_plots_are_skipped_with_a_note_without_matplotlib(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import importlib.util

    manifest = synthetic_campaign(tmp_path / "d", "linear", [(1.0, 0.01, 0.0)])
    result = identify(manifest, "linear")
    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util,
        "find_spec",
        lambda name, *a: None if name == "matplotlib" else real(name, *a),
    )
    files = result.save(tmp_path / "out")
    assert not any("plots/" in p.as_posix() for p in files)
    assert any("matplotlib is not installed" in n for n in result.notes)
