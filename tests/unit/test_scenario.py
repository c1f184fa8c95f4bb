"""Scenario files: loading, validation messages and defaults."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path
from typing import Any

import pytest

import mrsuspension.engine  # noqa: F401  (first: importing control first is circular)
from mrsuspension.control import IdealSkyhook, SlidingMode
from mrsuspension.dampers import LinearViscous, WangSymmetric
from mrsuspension.engine.simulate import DEFAULT_DT
from mrsuspension.errors import ValidationError
from mrsuspension.excitation import SteppedSweep
from mrsuspension.scenario import SCENARIO_KEYS, Scenario
from mrsuspension.vehicle import QuarterCar

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "examples" / "scenarios").glob("*.toml"))
HARMONIC = {"kind": "harmonic", "frequency": 1.5, "amplitude": 0.025}
REQUIRED = {
    "passive-harmonic.toml",
    "skyhook-hilo-acm-harmonic.toml",
    "policy-iv-pulse.toml",
    "onoff-adfg-harmonic.toml",
    "inverse-hilo-road.toml",
    "sliding-mode-pulse.toml",
    "ideal-skyhook-road.toml",
    "reference-model-swept.toml",
    "linear-swept.toml",
}


def _error(data: dict[str, Any], base_dir: Path | None = None) -> str:
    with pytest.raises(ValidationError) as info:
        Scenario.from_dict(data, base_dir)
    return str(info.value)


def test_examples_cover_every_family_and_kind() -> None:
    names = {p.name for p in EXAMPLES}
    assert names >= REQUIRED
    laws = {tomllib.loads(p.read_text())["controller"]["law"] for p in EXAMPLES}
    kinds = {tomllib.loads(p.read_text())["excitation"]["kind"] for p in EXAMPLES}
    assert {"passive", "onoff-adfg", "skyhook-hilo", "policy-iv", "inverse-hilo"} <= laws
    assert {"sliding-mode", "ideal-skyhook"} <= laws
    assert kinds == {"harmonic", "swept", "pulse", "road"}


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.name for p in EXAMPLES])
def test_every_example_loads(path: Path) -> None:
    assert path.read_text().startswith("#"), "each example says what it reproduces"
    scenario = Scenario.load(path)
    assert scenario.source == path
    sims = scenario.simulations()
    assert len(sims) == (len(scenario.excitation) if scenario.is_sweep else 1)  # type: ignore[arg-type]
    # to_dict round-trips
    again = Scenario.from_dict(scenario.to_dict(), scenario.base_dir)
    assert again.to_dict() == scenario.to_dict()


def test_examples_settings() -> None:
    load = lambda name: Scenario.load(ROOT / "examples" / "scenarios" / name)  # noqa: E731
    ref = load("reference-model-swept.toml")
    assert ref.vehicle.skyhook_damping == 6750.0
    assert isinstance(ref.damper, LinearViscous)
    assert ref.damper.values["c"] == 2500.0
    assert ref.controller.law == "passive"
    assert isinstance(ref.excitation, SteppedSweep)
    inv = load("inverse-hilo-road.toml")
    assert isinstance(inv.damper, WangSymmetric)
    assert inv.damper.force_gain == 2.5
    smc = load("sliding-mode-pulse.toml")
    assert isinstance(smc.damper, WangSymmetric)
    assert smc.damper.force_gain == 2.5
    assert isinstance(smc.controller, SlidingMode)
    assert isinstance(load("ideal-skyhook-road.toml").controller, IdealSkyhook)


def test_defaults_come_from_the_classes() -> None:
    s = Scenario.from_dict({"excitation": HARMONIC})
    assert s.vehicle == QuarterCar()
    assert isinstance(s.damper, WangSymmetric)
    assert s.damper.hysteresis
    assert s.damper.force_gain == 1
    assert s.controller.law == "passive"
    assert s.dt == DEFAULT_DT
    assert s.duration is None
    assert s.output_rate == 1000.0
    assert s.max_current == 0.5


def test_sliding_mode_spec_symbols() -> None:
    s = Scenario.from_dict(
        {
            "controller": {"law": "sliding-mode", "lambda": 0.7, "eps": 0.1, "phi": 2.0,
                           "beta": 1.5, "m_s0": 600.0, "c_s": 5000.0, "c_0": 2000.0},
            "excitation": HARMONIC,
        }
    )  # fmt: skip
    c = s.controller
    assert isinstance(c, SlidingMode)
    assert (c.slope, c.boundary_layer, c.phi, c.beta) == (0.7, 0.1, 2.0, 1.5)
    assert (c.nominal_mass, c.skyhook_damping, c.passive_damping) == (600.0, 5000.0, 2000.0)


def test_ideal_laws_accept_c_s() -> None:
    for law, attr in (("ideal-skyhook", "skyhook_damping"), ("ideal-onoff", "damping")):
        s = Scenario.from_dict({"controller": {"law": law, "c_s": 4000}, "excitation": HARMONIC})
        assert getattr(s.controller, attr) == 4000.0


def test_unknown_key_did_you_mean() -> None:
    msg = _error({"vehicle": {"sprung_mas": 500.0}, "excitation": HARMONIC})
    assert "[vehicle] sprung_mas" in msg
    assert "Did you mean 'sprung_mass'" in msg
    msg = _error({"controller": {"law": "skyhook-hilo", "gian": 3}, "excitation": HARMONIC})
    assert "[controller] gian" in msg
    assert "'gain'" in msg
    msg = _error({"excitation": {"kind": "harmonic", "frequncy": 1.5, "amplitude": 0.02}})
    assert "[excitation] frequncy" in msg
    assert "'frequency'" in msg
    msg = _error({"simulation": {"durration": 3.0}, "excitation": HARMONIC})
    assert "[simulation] durration" in msg
    assert "'duration'" in msg


def test_key_of_another_law_or_model() -> None:
    msg = _error({"controller": {"law": "passive", "gain": 3.0}, "excitation": HARMONIC})
    assert "[controller] gain" in msg
    assert "'passive'" in msg
    msg = _error({"damper": {"model": "linear", "hysteresis": False}, "excitation": HARMONIC})
    assert "[damper] hysteresis" in msg
    assert "'linear'" in msg


def test_unknown_section() -> None:
    msg = _error({"vehicel": {}, "excitation": HARMONIC})
    assert "[vehicel]" in msg
    assert "Did you mean 'vehicle'" in msg


@pytest.mark.parametrize(
    ("data", "where"),
    [
        ({"vehicle": {"sprung_mass": "heavy"}}, "[vehicle] sprung_mass"),
        ({"damper": {"hysteresis": "yes"}}, "[damper] hysteresis"),
        ({"controller": {"law": 3}}, "[controller] law"),
        ({"simulation": {"dt": "1e-4"}}, "[simulation] dt"),
        ({"excitation": {"kind": "harmonic", "frequency": "fast", "amplitude": 0.02}},
         "[excitation] frequency"),
    ],
)  # fmt: skip
def test_wrong_types_name_section_and_key(data: dict[str, Any], where: str) -> None:
    msg = _error({"excitation": HARMONIC, **data})
    assert where in msg


@pytest.mark.parametrize(
    ("section", "key", "value"),
    [
        ("vehicle", "sprung_mass", -563.0),
        ("vehicle", "unsprung_mass", 0.0),
        ("vehicle", "tire_stiffness", 0.0),
        ("damper", "force_gain", -1.0),
        ("damper", "max_current", 2.0),
        ("controller", "current", -0.1),
        ("simulation", "dt", 0.0),
        ("simulation", "duration", -1.0),
    ],
)
def test_physical_range_errors(section: str, key: str, value: float) -> None:
    data: dict[str, Any] = {"excitation": HARMONIC, section: {key: value}}
    msg = _error(data)
    assert msg.startswith(f"[{section}]")
    assert key in msg


def test_dt_too_large_for_stability() -> None:
    msg = _error({"simulation": {"dt": 5e-3}, "excitation": HARMONIC})
    assert msg.startswith("[simulation]")
    assert "too large for stability" in msg


def test_unknown_names_did_you_mean() -> None:
    assert "Did you mean 'skyhook-hilo'" in _error(
        {"controller": {"law": "skyhok-hilo"}, "excitation": HARMONIC}
    )
    assert "Did you mean 'wang-symmetric'" in _error(
        {"damper": {"model": "wang-symetric"}, "excitation": HARMONIC}
    )
    assert "Did you mean 'wang-symmetric-low'" in _error(
        {"damper": {"parameters": "wang-symmetric-lo"}, "excitation": HARMONIC}
    )
    assert "Did you mean 'harmonic'" in _error({"excitation": {"kind": "harmonc"}})
    assert "Did you mean 'rough'" in _error({"excitation": {"kind": "road", "profile": "ruogh"}})
    assert "[excitation] kind" in _error({})


def test_inverse_controller_needs_symmetric_model() -> None:
    msg = _error({"damper": {"model": "bingham"}, "controller": {"law": "inverse-hilo"},
                  "excitation": HARMONIC})  # fmt: skip
    assert "wang-symmetric" in msg


def test_relative_parameter_file(tmp_path: Path) -> None:
    (tmp_path / "sets").mkdir()
    (tmp_path / "sets" / "soft.toml").write_text(
        'name = "soft"\nmodel = "linear"\nmax_current = 0.5\n'
        '[parameters]\nc = { value = 1234.0, unit = "N s/m" }\n'
    )
    (tmp_path / "s.toml").write_text(
        '[damper]\nmodel = "linear"\nparameters = "sets/soft.toml"\n'
        '[excitation]\nkind = "harmonic"\nfrequency = 1.5\namplitude = 0.025\n'
    )
    scenario = Scenario.load(tmp_path / "s.toml")  # from another working directory
    assert scenario.damper.values["c"] == 1234.0
    msg = _error({"damper": {"model": "linear", "parameters": "sets/none.toml"},
                  "excitation": HARMONIC}, tmp_path)  # fmt: skip
    assert "[damper] parameters" in msg
    assert "none.toml" in msg


def test_bad_files(tmp_path: Path) -> None:
    with pytest.raises(ValidationError, match="not found"):
        Scenario.load(tmp_path / "missing.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[vehicle\nsprung_mass = 1")
    with pytest.raises(ValidationError, match="not valid TOML"):
        Scenario.load(bad)


def test_run_harmonic_and_sweep() -> None:
    s = Scenario.from_dict(
        {"controller": {"law": "skyhook-hilo", "mode": "ACM"}, "excitation": HARMONIC}
    )
    (result,) = s.run()
    m = result.measures()
    assert 2.0 < m["gamma"] < 3.5
    assert m["T_as"] > 0
    sweep = Scenario.from_dict(
        {"damper": {"model": "linear"},
         "excitation": {"kind": "swept", "amplitude": 0.025, "frequencies": [0.987, 4.0]}}
    )  # fmt: skip
    results = sweep.run(workers=1)
    assert len(results) == 2
    # the default run length ends on the sample grid: the steady-state rule is met
    assert all(math.isfinite(r.measures()["T_as"]) for r in results)


def test_public_sections() -> None:
    assert set(SCENARIO_KEYS) == {
        "vehicle", "damper", "controller", "excitation", "simulation", "sensing"
    }  # fmt: skip
    for key in ("model", "parameters", "hysteresis", "force_gain", "max_current", "damping"):
        assert key in SCENARIO_KEYS["damper"]
    for key in ("law", "mode", "gain", "order", "current", "lambda", "eps", "phi", "beta"):
        assert key in SCENARIO_KEYS["controller"]


def test_damper_keys_come_from_the_model_classes(monkeypatch: pytest.MonkeyPatch) -> None:
    from mrsuspension import dampers

    class Toy(LinearViscous):
        name = "toy"

    # a model registered later (no hand-kept key table): its declared options apply
    monkeypatch.setitem(dampers.DAMPERS, "toy", Toy)
    s = Scenario.from_dict({"damper": {"model": "toy", "damping": 1500.0}, "excitation": HARMONIC})
    assert isinstance(s.damper, Toy)
    assert s.damper.values["c"] == 1500.0
    msg = _error({"damper": {"model": "toy", "hysteresis": False}, "excitation": HARMONIC})
    assert "[damper] hysteresis does not apply to model 'toy'" in msg
    with pytest.raises(ValidationError, match=r"unknown damper model 'nope'.*Valid: .*toy"):
        dampers.damper_options("nope")
