"""``hil validate``: the Chapter 7 comparisons (frequency responses, pulse, road PSDs)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import typer
from typer.testing import CliRunner

from _helpers import raises_validation
from mrsuspension.cli.hil import hil_validate_command
from mrsuspension.hil import ideal_rig
from mrsuspension.hil.chapter7 import FREQUENCY_MEASURES
from mrsuspension.hil.network import UdpRig
from mrsuspension.report.ch7 import validate_chapter7
from mrsuspension.scenario import Scenario

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "examples" / "scenarios" / "skyhook-hilo-acm-harmonic.toml"
#: one engine step (1e-4 s) per tick: the ideal rig then reproduces the offline run
RATE = 10000.0


def _sim():  # type: ignore[no-untyped-def]
    return Scenario.load(SCENARIO).simulations()[0]


def test_frequency_responses_agree_with_the_ideal_rig(tmp_path: Path) -> None:
    sim = _sim()
    data = validate_chapter7(
        sim, ideal_rig(sim.damper), tmp_path, what=["frequency"],
        cases=["skyhook-scm", "passive-0.1"], frequencies=[1.5, 4.0, 10.0], rate=RATE,
    )  # fmt: skip
    for case in ("skyhook-scm", "passive-0.1"):
        fr = data["frequency"][case]
        assert fr["reasons"] == ["completed"] * 3
        assert fr["amplitude"] == pytest.approx([0.015, 0.015 * (2 / 4) ** 2, 0.015 * 0.04])
        for k in FREQUENCY_MEASURES:
            print(case, k, fr["hil"][k], fr["relative_difference"][k])
            assert all(v > 0 for v in fr["offline"][k])
            assert all(abs(r) < 0.01 for r in fr["relative_difference"][k]), (case, k)
    # the transmissibility peaks near the body resonance and falls off above it
    t_as = data["frequency"]["passive-0.1"]["offline"]["T_as"]
    assert t_as[0] > 1.0 > t_as[2]
    assert data["pacing"].startswith("UNPACED")
    saved = json.loads((tmp_path / "validation.json").read_text())
    assert saved["frequency"]["passive-0.1"]["frequency"] == [1.5, 4.0, 10.0]
    assert (tmp_path / "frequency_response.png").stat().st_size > 5000
    page = (tmp_path / "index.html").read_text()
    assert "UNPACED" in page
    assert "frequency_response.png" in page
    assert "T_dr HiL" in page


def test_pulse_and_road_psds_agree_with_the_ideal_rig(tmp_path: Path) -> None:
    sim = _sim()
    data = validate_chapter7(
        sim, ideal_rig(sim.damper), tmp_path, what=["pulse", "road"], road_duration=16.0,
        rate=RATE,
    )  # fmt: skip
    pulse = data["pulse"]["scenario"]
    assert pulse["reason"] == "completed"
    assert pulse["excitation"]["kind"] == "pulse"
    for k in ("SDR_s", "SAR_s", "RDR", "peak_F_d", "peak_F_T"):
        assert abs(pulse["relative_difference"][k]) < 0.01, k
    road = data["road"]["scenario"]
    assert road["reason"] == "completed"
    for label, b in road["band_rms"].items():
        print(label, b)
        assert b["offline"] > 0
        assert abs(b["relative_difference"]) < 0.02, label
    for label in ("x_s", "x_u"):  # displacement spectra agree bin by bin
        assert road["band_rms"][label]["max_pointwise_relative_difference"] < 0.05
    spectrum = road["psd"]["a_s"]
    assert len(spectrum["frequency"]) == len(spectrum["hil"]) > 10
    for name in ("pulse_scenario.png", "road_psd_scenario.png", "index.html"):
        assert (tmp_path / name).stat().st_size > 1000


def test_validate_cli_options(tmp_path: Path) -> None:
    app = typer.Typer(pretty_exceptions_enable=False)
    app.command("validate")(hil_validate_command)
    app.command("other")(lambda: None)
    runner = CliRunner()
    out = tmp_path / "v"
    res = runner.invoke(
        app,
        ["validate", str(SCENARIO), "--what", "frequency", "--frequencies", "2,6",
         "--rate", "10000", "--out", str(out), "--json"],
    )  # fmt: skip
    assert res.exit_code == 0, res.output
    info = json.loads(res.stdout)
    assert info["frequency"]["scenario"]["frequency"] == [2.0, 6.0]
    assert info["realtime"] == "unpaced"
    assert (out / "index.html").exists()
    text = runner.invoke(
        app, ["validate", str(SCENARIO), "--what", "frequency", "--frequencies", "3"]
    )
    assert text.exit_code == 0, text.output
    assert "UNPACED" in text.stdout
    assert "T_au diff" in text.stdout
    for args, fragment in (
        (["--what", "time,bogus"], "unknown 'bogus'"),
        (["--what", ","], "at least one"),
        (["--frequencies", "1,x"], "'x' is not a number"),
        (["--frequencies", "0"], "(0, 50] Hz"),
        (["--frequencies", "2,2"], "given twice"),
        (["--cases", "skyhook"], "unknown 'skyhook'"),
        (["--realtime", "sometimes"], "'sometimes'"),
        (["--road-duration", "-1"], "--road-duration"),
    ):
        bad = runner.invoke(app, ["validate", str(SCENARIO), *args])
        assert bad.exit_code == 2, (args, bad.output)
        assert fragment in bad.stderr, (args, bad.stderr)


def test_network_rig_is_never_unpaced() -> None:
    sim = _sim()
    raises_validation(
        lambda: validate_chapter7(sim, UdpRig("127.0.0.1", 9), realtime="unpaced"),
        "always runs paced",
    )
    raises_validation(
        lambda: validate_chapter7(sim, ideal_rig(), amplitude=0.5, what=["frequency"]),
        "amplitude",
    )
