"""The excitation registry and ``make_excitation`` (the scenario ``[excitation]`` table)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from _helpers import raises_validation as _raises
from mrsuspension.excitation import (
    EXCITATION_OPTIONS,
    EXCITATIONS,
    PRESET_ROADS,
    Excitation,
    Harmonic,
    RoadBandWarning,
    RoadProfile,
    RoundedPulse,
    SteppedSweep,
    make_excitation,
    preset_road,
)


def test_registry_kinds():
    assert set(EXCITATIONS) == {"harmonic", "swept", "pulse", "road"}
    assert set(EXCITATION_OPTIONS) == set(EXCITATIONS)
    for kind, cls in EXCITATIONS.items():
        assert cls.name == kind


# the minimal options of each kind, as a scenario would give them
MINIMAL = {
    "harmonic": {"frequency": 1.5, "amplitude": 0.025},
    "swept": {"amplitude": 0.025},
    "pulse": {"amplitude": 0.05, "severity": 2},
    "road": {"profile": "smooth"},
}


@pytest.mark.parametrize("kind", sorted(MINIMAL))
def test_every_kind_builds_and_describes_itself(kind):
    exc = make_excitation(kind, **MINIMAL[kind])
    assert isinstance(exc, EXCITATIONS[kind])
    d = exc.describe()
    assert d["kind"] == kind
    assert exc.duration > 0
    if isinstance(exc, Excitation):
        t = np.linspace(0.0, exc.duration, 257)
        for signal in (exc.displacement(t), exc.velocity(t), exc.acceleration(t)):
            assert signal.shape == t.shape
            assert np.all(np.isfinite(signal))
        t0, t1 = exc.measure_window()
        assert 0.0 <= t0 < t1 <= exc.duration + 1e-12


def test_harmonic():
    assert make_excitation("harmonic", frequency=1.5, amplitude=0.025) == Harmonic(1.5, 0.025)


def test_swept_defaults_and_options():
    sweep = make_excitation("swept", amplitude=0.025)
    assert isinstance(sweep, SteppedSweep)
    assert len(sweep) == 30
    assert sweep.frequencies[0] == pytest.approx(0.5)
    assert sweep.frequencies[-1] == pytest.approx(15.0)
    assert sweep.transition_frequency == 2.1
    custom = make_excitation("swept", amplitude=0.01, transition_frequency=2.0, frequencies=[1, 4])
    assert custom.amplitudes == pytest.approx([0.01, 0.0025])


def test_pulse_speed_option():
    p = make_excitation("pulse", amplitude=0.035, severity=3, speed=100.0, delay=0.2)
    assert isinstance(p, RoundedPulse)
    assert p.omega == pytest.approx(20.8)
    assert p.delay == 0.2
    assert make_excitation("pulse", amplitude=0.02, severity=1, omega0=5.0).omega == 5.0


def test_road_preset_scale_and_speed():
    road = make_excitation("road", profile="rough", speed=100.0, scale=0.5)
    assert isinstance(road, RoadProfile)
    assert road.peak_elevation == pytest.approx(0.5 * preset_road("rough").peak_elevation)
    assert road.spectrum is not None
    assert road.spectrum.level == pytest.approx(0.25 * PRESET_ROADS["rough"].level)
    assert road.speed_kmh == 100.0
    np.testing.assert_array_equal(road.elevation, preset_road("rough").elevation * 0.5)


def test_road_preset_seed():
    """A preset takes a seed: another road of the same PSD level (rms), other phases."""
    road = make_excitation("road", profile="rough", seed=5)
    assert isinstance(road, RoadProfile)
    assert "seed 5" in road.source
    np.testing.assert_array_equal(road.elevation, preset_road("rough", seed=5).elevation)
    default = preset_road("rough")
    assert road.rms_elevation == pytest.approx(default.rms_elevation, rel=1e-12)
    assert not np.allclose(road.elevation, default.elevation)


def test_road_iso_class():
    road = make_excitation("road", iso_class="D", seed=3, length=200.0)
    assert road.distance.size == 4001  # 0.05 m: the whole band 0.011-2.83 cycle/m
    assert road.source == "ISO 8608 class D, seed 3, band 0.011-2.83 cycle/m at 0.05 m spacing"


def test_road_iso_class_spacing_that_cuts_the_band_is_warned_and_stated():
    """Issue 27: 0.25 m spacing (Nyquist 2 cycle/m) cuts ISO's band; the user is told."""
    with pytest.warns(RoadBandWarning) as caught:
        road = make_excitation("road", iso_class="D", seed=3, length=200.0, spacing=0.25)
    message = str(caught[0].message)
    assert "cuts the band 0.011-2.83 cycle/m at its Nyquist frequency 2 cycle/m" in message
    assert "give at most 0.106 m" in message
    assert road.distance.size == 801
    assert road.spectrum is not None
    assert road.spectrum.band == (0.011, 2.0)
    assert "band 0.011-2 cycle/m (cut from 2.83 by the spacing) at 0.25 m spacing" in road.source
    with pytest.warns(RoadBandWarning, match="at 94% of its Nyquist frequency"):
        make_excitation("road", iso_class="D", length=200.0, spacing=0.166)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        make_excitation("road", iso_class="D", length=200.0, spacing=0.1)  # 57 %: quiet
        make_excitation("road", profile="rough")  # the preset's 0.3 m is its definition


def test_road_csv_relative_to_base_dir(tmp_path):
    (tmp_path / "roads").mkdir()
    (tmp_path / "roads" / "r.csv").write_text("0,0\n1,1\n2,2\n3,1\n")
    road = make_excitation("road", profile="roads/r.csv", base_dir=tmp_path, elevation_unit="mm")
    assert road.elevation[1] == pytest.approx(0.001)


@pytest.mark.parametrize(
    ("kind", "options", "fragments"),
    [
        ("harmonc", {}, ("unknown excitation kind 'harmonc'", "Did you mean 'harmonic'?")),
        (
            "harmonic",
            {"frequncy": 1.0, "amplitude": 0.01},
            ("'frequncy'", "Did you mean 'frequency'?"),
        ),
        ("harmonic", {"amplitude": 0.01}, ("needs 'frequency'",)),
        ("pulse", {"amplitude": 0.01, "severity": 1, "speed_kmh": 50}, ("Did you mean 'speed'?",)),
        ("pulse", {"amplitude": 0.01}, ("needs 'severity'",)),
        ("swept", {"amplitude": 0.01, "frequencies": [1, 1]}, ("repeat",)),
        ("road", {}, ("exactly one of 'profile'",)),
        ("road", {"profile": "rough", "iso_class": "C"}, ("exactly one of",)),
        ("road", {"profile": "ruogh"}, ("unknown road profile 'ruogh'", "Did you mean 'rough'?")),
        (
            "road",
            {"profile": "rough", "length": 100.0},
            ("'length' only applies with 'iso_class'",),
        ),
        ("road", {"profile": "rough", "seed": -2}, ("seed must be an integer >= 0", "-2")),
        (
            "road",
            {"profile": "missing/road.csv", "seed": 2},
            ("'seed' only applies with 'iso_class' or a preset",),
        ),
        ("road", {"iso_class": "C", "elevation_unit": "mm"}, ("only applies to a CSV",)),
        ("road", {"profile": "rough", "scale": -1.0}, ("scale",)),
        ("road", {"profile": "missing/road.csv"}, ("not found", "road.csv")),
        ("road", {"profile": 3}, ("preset name or a file path",)),
        ("road", {"iso_class": "Q"}, ("ISO 8608 road class 'Q'",)),
    ],
)
def test_bad_options(kind, options, fragments):
    _raises(lambda: make_excitation(kind, **options), *fragments)
