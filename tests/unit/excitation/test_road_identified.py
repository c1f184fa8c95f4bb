"""The preset roads' identified spectra (issue 30, group 4): the ``spectrum`` option and the
targets the fit reproduces, checked on spectra only (a linear quarter car's DLC from
``|H|^2`` times the road PSD; the nonlinear runs are ``tools/identify_roads.py``'s)."""

from __future__ import annotations

import functools

import numpy as np
import pytest
from scipy.signal import periodogram

from mrsuspension.errors import ValidationError
from mrsuspension.excitation import make_excitation, preset_road
from mrsuspension.excitation.road import (
    PRESET_IDENTIFIED,
    PRESET_ROADS,
    PRESET_SPACING,
    RoadSpectrum,
)
from mrsuspension.vehicle import QuarterCar, linear_frequency_response

#: frequency grid of the linear DLC [Hz] and the linear damper [N s/m] (c_s0 of section 6)
_F = np.geomspace(0.05, 60.0, 1500)
_DAMPING = 2500.0


def _temporal(spectrum: RoadSpectrum, speed_kmh: float, f: np.ndarray) -> np.ndarray:
    """One-sided temporal road PSD [m^2/Hz] of a preset at 0.3 m spacing (band cut at
    its Nyquist frequency, as the synthesis does)."""
    v = speed_kmh / 3.6
    n = f / v
    top = min(spectrum.band[1], 0.5 / PRESET_SPACING)
    inside = (n >= spectrum.band[0]) & (n <= top)
    return np.where(inside, spectrum.level * (n / 0.1) ** -spectrum.waviness, 0.0) / v


@functools.cache
def _h() -> np.ndarray:
    """The linear quarter car's DLC per metre of road amplitude (rms) on :data:`_F`."""
    return np.asarray(linear_frequency_response(QuarterCar(), _DAMPING, _F)["DLC"])


def _linear_dlc(spectrum: RoadSpectrum, speed_kmh: float) -> float:
    """std(F_T) / static load of the linear quarter car on a road of ``spectrum``."""
    h = _h()
    return float(np.sqrt(np.trapezoid(2.0 * h**2 * _temporal(spectrum, speed_kmh, _F), _F)))


@pytest.fixture(scope="module")
def roads() -> dict[str, dict[str, RoadSpectrum]]:
    return {
        "reference": {k: p.spectrum for k, p in PRESET_ROADS.items()},
        "identified": {k: p.spectrum for k, p in PRESET_IDENTIFIED.items()},
    }


def test_identified_presets_differ_in_shape_not_only_in_level() -> None:
    rough, medium = PRESET_IDENTIFIED["rough"], PRESET_IDENTIFIED["medium-rough"]
    assert (rough.waviness, rough.band) != (medium.waviness, medium.band)
    assert PRESET_IDENTIFIED["smooth"] == PRESET_ROADS["smooth"]  # nothing to fit
    for name in PRESET_ROADS:  # the same profiles' geometry and seeds
        a, b = PRESET_IDENTIFIED[name], PRESET_ROADS[name]
        assert (a.seed, a.length, a.spacing) == (b.seed, b.length, b.spacing)


@pytest.mark.parametrize("name", ["rough", "medium-rough"])
def test_identified_profile_holds_its_spectrum(name: str) -> None:
    road = preset_road(name, spectrum="identified")
    spectrum = PRESET_IDENTIFIED[name].spectrum
    assert road.spectrum is not None
    assert road.spectrum.level == spectrum.level
    assert road.spectrum.waviness == spectrum.waviness
    assert f"spectrum {spectrum.label()}" in road.source
    n, p = periodogram(road.elevation, fs=1 / 0.3, window="boxcar", detrend=False)
    band = (n >= spectrum.band[0]) & (n <= spectrum.band[1])
    np.testing.assert_allclose(p[band], spectrum.density(n[band]), rtol=1e-9)
    assert np.max(p[~band]) < 1e-20 * np.max(p)
    assert preset_road(name).source != road.source  # the default is the reference's


def test_scenario_options_choose_and_change_a_preset_spectrum() -> None:
    road = make_excitation("road", profile="rough", spectrum="identified", speed=100.0)
    np.testing.assert_array_equal(
        road.elevation, preset_road("rough", spectrum="identified").elevation
    )
    changed = make_excitation("road", profile="rough", waviness=0.8, band=[0.05, 1.0], level=1e-5)
    assert changed.spectrum == RoadSpectrum(1e-5, 0.8, (0.05, 1.0))
    with pytest.raises(ValidationError, match="only applies to a preset profile"):
        make_excitation("road", iso_class="C", waviness=0.8)
    with pytest.raises(ValidationError, match="valid: reference, identified"):
        preset_road("rough", spectrum="measured")
    with pytest.raises(ValidationError, match="band must be a pair"):
        make_excitation("road", profile="rough", band=1.0)
    with pytest.raises(ValidationError, match="n_max > n_min"):
        make_excitation("road", profile="rough", band=[1.0, 0.5])


def test_identified_roads_reproduce_the_speed_and_roughness_targets(roads) -> None:
    """On the identified roads a linear quarter car's DLC at 100 km/h is 1.0-1.05 times that
    at 50 km/h (the dissertation: 1.01-1.03; the reference's n^-1 presets: 1.12), the rough
    road's DLC is 2-3.9 times the medium-rough road's (the dissertation: 2.0-3.1) and
    within the dissertation's rough-road DLCs (0.111-0.139, 15 %), and the temporal road PSD
    falls a little with speed in the ride range (Fig 3.10 b/c)."""
    ratio = {
        k: _linear_dlc(r["rough"], 100.0) / _linear_dlc(r["rough"], 50.0) for k, r in roads.items()
    }
    assert 1.0 <= ratio["identified"] <= 1.05, ratio
    assert ratio["reference"] > 1.1, ratio  # what the fit repairs
    rough, medium = roads["identified"]["rough"], roads["identified"]["medium-rough"]
    assert 2.0 <= _linear_dlc(rough, 50.0) / _linear_dlc(medium, 50.0) <= 1.25 * 3.07
    assert 0.85 * 0.111 <= _linear_dlc(rough, 50.0) <= 1.15 * 0.139
    ride = np.linspace(2.0, 5.0, 31)
    slower = _temporal(rough, 100.0, ride) / _temporal(rough, 50.0, ride)
    assert np.all((slower < 1.0) & (slower > 0.5)), slower
    # Fig 3.10 (a): the rougher road's spatial PSD is the larger, wherever both are defined
    n = np.linspace(medium.band[0], medium.band[1], 50)
    assert np.all(rough.density(n) > medium.density(n))


def test_identified_roads_bring_the_ride_range_together(roads) -> None:
    """The input side of 4.4.3's 'comparable in the ride range (2-5 Hz)': the identified
    rough road's temporal PSD over 2-5 Hz at 50 km/h is at most 3x the medium-rough
    road's, where the reference presets differ by their level ratio, 6.4x, at every
    frequency (the controllers' responses then come within 0.7-1.9x: identify_roads.py)."""
    ride = np.linspace(2.0, 5.0, 31)
    ratio = {
        k: float(
            np.mean(_temporal(r["rough"], 50.0, ride))
            / np.mean(_temporal(r["medium-rough"], 50.0, ride))
        )
        for k, r in roads.items()
    }
    assert ratio["identified"] <= 3.0, ratio
    assert ratio["reference"] == pytest.approx(2.7e-5 / 4.2e-6, rel=1e-6)
