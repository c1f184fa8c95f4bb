"""``hil validate --masses``: the Chapter 7 comparisons at several sprung masses.

Dissertation Figs 7.14, 7.16, 7.18 and 7.21 repeat the comparisons at m_s = 703 kg
beside the nominal 563 kg; each (case, mass) pair runs in HiL and offline.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
import typer
from typer.testing import CliRunner

from _helpers import raises_validation
from mrsuspension.cli.hil import hil_validate_command
from mrsuspension.hil import ideal_rig
from mrsuspension.hil.chapter7 import FREQUENCY_MEASURES, parse_masses
from mrsuspension.hil.recorder import load_recording
from mrsuspension.report.ch7 import validate_chapter7
from mrsuspension.scenario import Scenario

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "examples" / "scenarios" / "skyhook-hilo-acm-harmonic.toml"
#: one engine step (1e-4 s) per tick: the ideal rig then reproduces the offline run
RATE = 10000.0
G = 9.81


def _sim():  # type: ignore[no-untyped-def]
    return Scenario.load(SCENARIO).simulations()[0]


def _app() -> typer.Typer:
    app = typer.Typer(pretty_exceptions_enable=False)
    app.command("validate")(hil_validate_command)
    app.command("other")(lambda: None)
    return app


def test_each_mass_agrees_and_the_heavier_body_is_heavier(tmp_path: Path) -> None:
    sim = _sim()
    assert sim.vehicle.sprung_mass == 563.0
    data = validate_chapter7(
        sim, ideal_rig(sim.damper), tmp_path, what=["frequency", "pulse", "road"],
        cases=["skyhook-acm"], masses=(563, 703), frequencies=[4.0], road_duration=4.0,
        rate=RATE,
    )  # fmt: skip
    assert data["masses"] == [563.0, 703.0]
    keys = ["skyhook-acm@563kg", "skyhook-acm@703kg"]
    for what in ("frequency", "pulse", "road"):
        assert list(data[what]) == keys, what
        for key, mass in zip(keys, (563.0, 703.0), strict=True):
            assert data[what][key]["sprung_mass"] == mass
            assert data[what][key]["case"] == "skyhook-acm"
    # every (case, mass) pair: HiL and offline agree as at the scenario's own mass
    for key in keys:
        fr = data["frequency"][key]
        assert fr["reasons"] == ["completed"]
        for k in FREQUENCY_MEASURES:
            assert abs(fr["relative_difference"][k][0]) < 0.01, (key, k)
        pulse = data["pulse"][key]
        assert pulse["reason"] == "completed"
        for k in ("SDR_s", "SAR_s", "RDR", "peak_F_d", "peak_F_T"):
            assert abs(pulse["relative_difference"][k]) < 0.01, (key, k)
        road = data["road"][key]
        assert road["reason"] == "completed"
        for label, b in road["band_rms"].items():
            assert abs(b["relative_difference"]) < 0.02, (key, label)
        for label in ("x_s", "x_u"):
            assert road["band_rms"][label]["max_pointwise_relative_difference"] < 0.05
    # the 703 kg entries really carry 703 kg, in both runs
    light, heavy = (data["pulse"][k] for k in keys)
    for side in ("hil", "offline"):
        # the tire carries the extra 140 kg: the peak tire force rises by about its weight
        rise = heavy[side]["peak_F_T"] - light[side]["peak_F_T"]
        assert rise == pytest.approx((703 - 563) * G, rel=0.05), side
        # at 4 Hz, well above both body resonances (1.6 and 1.4 Hz), the suspension force
        # hardly depends on m_s, so the body acceleration scales with 1/m_s
        t_as = [data["frequency"][k][side]["T_as"][0] for k in keys]
        assert t_as[1] / t_as[0] == pytest.approx(563 / 703, rel=0.05), side
    # outputs: nothing overwritten, the overlays of the masses, headings naming the Figs
    saved = json.loads((tmp_path / "validation.json").read_text())
    assert saved["pulse"]["skyhook-acm@703kg"]["sprung_mass"] == 703.0
    for name in (
        "frequency_response_m563.png", "frequency_response_m703.png",
        "pulse_skyhook-acm_m703.png", "pulse_masses_skyhook-acm.png",
        "road_psd_skyhook-acm_m703.png", "road_psd_masses_skyhook-acm.png",
    ):  # fmt: skip
        assert (tmp_path / name).stat().st_size > 1000, name
    assert not (tmp_path / "frequency_response.png").exists()
    page = (tmp_path / "index.html").read_text()
    for fragment in ("Fig 7.16", "Fig 7.18", "Fig 7.21", "m_s = 703 kg",
                     "pulse_masses_skyhook-acm.png", "road_psd_masses_skyhook-acm.png",
                     "frequency_response_m703.png"):  # fmt: skip
        assert fragment in page, fragment


def test_cli_masses(tmp_path: Path) -> None:
    runner = CliRunner()
    app = _app()
    base = ["validate", str(SCENARIO), "--what", "pulse", "--rate", "1000", "--json"]
    # one mass: the keys stay the case names; the mass is applied
    own = json.loads(runner.invoke(app, base).stdout)
    heavy = runner.invoke(app, [*base, "--masses", "703"])
    assert heavy.exit_code == 0, heavy.output
    heavy_info = json.loads(heavy.stdout)
    assert own["masses"] == [563.0]
    assert heavy_info["masses"] == [703.0]
    assert own["pulse"]["scenario"]["sprung_mass"] == 563.0
    assert heavy_info["pulse"]["scenario"]["sprung_mass"] == 703.0
    rise = heavy_info["pulse"]["scenario"]["hil"]["peak_F_T"]
    rise -= own["pulse"]["scenario"]["hil"]["peak_F_T"]
    assert rise == pytest.approx(140 * G, rel=0.05)
    # two masses, the time histories (Fig 7.14), as text: one block per mass
    out = tmp_path / "v"
    text = runner.invoke(
        app,
        ["validate", str(SCENARIO), "--what", "time", "--duration", "0.5", "--rate",
         "10000", "--masses", "563, 703", "--out", str(out)],
    )  # fmt: skip
    assert text.exit_code == 0, text.output
    for mass in (563, 703):
        assert f"time histories, m_s = {mass} kg: HiL stopped: completed" in text.stdout
        assert f"figure: {out / f'm{mass}' / 'time_histories.png'}" in text.stdout
        assert (out / f"m{mass}" / "recording").is_dir()
    saved = json.loads((out / "validation.json").read_text())
    assert list(saved["time"]) == ["scenario@563kg", "scenario@703kg"]
    for key, t in saved["time"].items():
        assert t["reason"] == "completed"
        assert key == f"scenario@{t['sprung_mass']:g}kg"
        for m in t["rms"].values():  # HiL and offline agree at each mass
            assert abs(m["relative_difference"]) < 0.01, (key, m["label"])
        # the HiL recording of each mass starts at its static tire load (m_s + m_u) g
        first = load_recording(out / f"m{t['sprung_mass']:g}" / "recording")["F_T"][0]
        assert first == pytest.approx((t["sprung_mass"] + 90.0) * G, rel=0.01), key
    page = (out / "index.html").read_text()
    assert "Fig 7.14" in page
    assert "m703/fv_loop.png" in page


@pytest.mark.parametrize(
    ("masses", "fragment"),
    [
        ("0", "finite and > 0 kg; got 0"),
        ("-1", "got -1"),
        ("nan", "got nan"),
        ("inf", "got inf"),
        ("563,703,563", "563 kg is given twice"),
        ("heavy", "'heavy' is not a number"),
        ("500,550,600,650,700,750,800", "at most 6 sprung masses; got 7"),
        ("0.5", "must be in [1, 100000] kg; got 0.5 kg"),
    ],
)
def test_bad_masses_are_refused(masses: str, fragment: str) -> None:
    sim = _sim()
    values = [float(m) if m not in ("heavy",) else m for m in masses.split(",")]
    raises_validation(
        lambda: validate_chapter7(sim, ideal_rig(sim.damper), masses=values),  # type: ignore[arg-type]
        fragment,
    )
    bad = CliRunner().invoke(_app(), ["validate", str(SCENARIO), "--masses", masses])
    assert bad.exit_code == 2, bad.output
    assert fragment in bad.stderr
    assert bad.stderr.strip().count("\n") == 0, bad.stderr  # one line


def test_parse_masses() -> None:
    assert parse_masses(" 563 , 703.5 ") == (563.0, 703.5)
    assert parse_masses("") == parse_masses(None) == ()
    assert parse_masses([703]) == (703.0,)
    raises_validation(lambda: parse_masses([True]), "not a number")
    assert math.isfinite(parse_masses("1e3")[0])
