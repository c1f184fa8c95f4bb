"""Road inputs per wheel: rear delay, two-track coherence, OpenCRG files, one-sided events."""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import numpy as np
import pyopencrg
import pytest
from scipy.signal import coherence

from _helpers import raises_validation as _raises
from mrsuspension.excitation import (
    FULL_CAR_CORNERS,
    HALF_CAR_CORNERS,
    ISO8608_CLASSES,
    Harmonic,
    Pothole,
    RoadSpectrum,
    RoundedPulse,
    WheelRoads,
    iso8608,
    iso8608_psd,
    isotropic_coherence,
    preset_road,
)

GEOMETRY = (2.7, 1.5)  # wheelbase, track [m]


def _write_crg(path: Path, z: np.ndarray, u_inc: float, v: np.ndarray, **kwargs: object) -> Path:
    pyopencrg.CrgRoad(z, u_inc=u_inc, v=v, **kwargs).save(path, fmt="KDBI")
    return path


# -- (a) the rear wheels see the front's road L/V later ---------------------------------------
class TestRearDelay:
    @pytest.mark.parametrize("speed_kmh", [30.0, 54.0, 100.0])
    def test_rear_is_the_front_delayed_on_a_road(self, speed_kmh):
        road = preset_road("rough")
        roads = WheelRoads.from_excitation(road, GEOMETRY, speed_kmh)
        v = speed_kmh / 3.6
        assert roads.rear_delay == pytest.approx(2.7 / v, rel=1e-15)
        t = np.linspace(0.0, roads.duration, 20001)
        z = roads.displacement(t)
        # an independent computation: the profile 2.7 m behind the front axle
        x = v * t - 2.7
        reached = x >= 0.0
        expected_rear = np.where(
            reached, road.elevation_at(np.clip(x, 0.0, road.length)), road.elevation[0]
        )
        expected_front = road.elevation_at(np.clip(v * t, 0.0, road.length))
        for row in (2, 3):  # rear_left, rear_right
            assert np.max(np.abs(z[row] - expected_rear)) < 1e-12
        for row in (0, 1):
            assert np.max(np.abs(z[row] - expected_front)) < 1e-12
        # and literally the front's signal at t - L/V
        front_then = roads.displacement(t - roads.rear_delay)[0]
        assert np.max(np.abs(z[2] - front_then)) < 1e-12

    def test_velocity_and_acceleration_are_delayed_too(self):
        roads = WheelRoads.from_excitation(Harmonic(1.3, 0.01), GEOMETRY, 72.0)
        t = np.linspace(0.0, 3.0, 3001)
        d = roads.rear_delay
        after = t >= d
        for method in (roads.velocity, roads.acceleration):
            sig = method(t)
            front = method(t - d)[0]
            np.testing.assert_allclose(sig[2][after], front[after], rtol=0, atol=1e-12)
            assert np.all(sig[2][~after] == 0.0)  # the road has not reached the rear wheels

    def test_before_the_rear_wheels_reach_the_road(self):
        road = iso8608("C", seed=4)
        roads = WheelRoads.from_excitation(road, GEOMETRY)
        t = np.linspace(0.0, 0.99 * roads.rear_delay, 50)
        np.testing.assert_array_equal(roads.displacement(t)[2], road.elevation[0])  # its start
        np.testing.assert_array_equal(roads.velocity(t)[2], 0.0)
        pulse = WheelRoads.from_excitation(Harmonic(2.0, 0.01), GEOMETRY, 50.0)
        np.testing.assert_array_equal(pulse.displacement(t)[2:], 0.0)

    def test_front_corners_are_the_excitation(self):
        bump = RoundedPulse(amplitude=0.035, severity=2.0)
        roads = WheelRoads.from_excitation(bump, GEOMETRY)
        t = np.linspace(0.0, 2.0, 2001)
        np.testing.assert_array_equal(roads.displacement(t)[0], bump.displacement(t))
        np.testing.assert_array_equal(roads.displacement(t)[1], bump.displacement(t))

    def test_half_car(self):
        road = preset_road("smooth")
        roads = WheelRoads.from_excitation(road, (2.6, None), corners="half-car")
        assert roads.corners == HALF_CAR_CORNERS
        t = np.linspace(0.0, 5.0, 501)
        z = roads.displacement(t)
        assert z.shape == (2, 501)
        np.testing.assert_array_equal(z[0], road.displacement(t))

    def test_speed_override_keeps_the_profile_over_distance(self):
        road = preset_road("rough", speed_kmh=50.0)
        roads = WheelRoads.from_excitation(road, GEOMETRY, 100.0)
        assert roads.left.speed_kmh == 100.0
        t = np.array([1.0, 2.0])
        np.testing.assert_allclose(roads.displacement(t)[0], road.displacement(2 * t), atol=1e-15)

    def test_sample_grid_agrees_with_displacement(self):
        roads = WheelRoads.two_track("C", GEOMETRY, 72.0, seed=2)
        t = 0.05 + np.arange(3001) * 1e-4
        z, v = roads.sample_grid(3001, 1e-4, start=0.05)
        np.testing.assert_allclose(z, roads.displacement(t), rtol=0, atol=1e-14)
        np.testing.assert_allclose(v, roads.velocity(t), rtol=0, atol=1e-11)


# -- one excitation at every wheel: in phase, or with given delays ----------------------------
class TestInPhase:
    @pytest.mark.parametrize(
        "excitation",
        [Harmonic(1.0, 0.01), RoundedPulse(amplitude=0.035, severity=2.0), preset_road("rough")],
        ids=["harmonic", "pulse", "road"],
    )
    def test_every_wheel_sees_the_excitation_at_once(self, excitation):
        roads = WheelRoads.in_phase(excitation)
        assert roads.corners == FULL_CAR_CORNERS
        assert roads.corner_delays == (0.0,) * 4
        assert roads.rear_delay == 0.0
        assert roads.duration == excitation.duration
        assert roads.excitation is excitation  # the corners measure as the quarter car
        t = 0.01 + np.arange(2000) * 1e-3
        for method in ("displacement", "velocity", "acceleration"):
            own = getattr(excitation, method)(t)
            for row in getattr(roads, method)(t):
                np.testing.assert_array_equal(row, own)
        z, v = roads.sample_grid(2000, 1e-3, start=0.01)  # the grid a run reads
        own_z, own_v = excitation.sample_grid(2000, 1e-3, start=0.01)
        for row in range(4):
            np.testing.assert_array_equal(z[row], own_z)
            np.testing.assert_array_equal(v[row], own_v)

    def test_hand_values_with_delays(self):
        # z = 0.01 sin(2 pi t); delays 0, 0.1, 0.25, 0.5 s; at t = 0.5 s and 0.3 s
        roads = WheelRoads.in_phase(Harmonic(1.0, 0.01), delays=[0.0, 0.1, 0.25, 0.5])
        z = roads.displacement([0.5, 0.3])
        expected = [
            [0.0, 0.01 * math.sin(0.6 * math.pi)],
            [0.01 * math.sin(0.8 * math.pi), 0.01 * math.sin(0.4 * math.pi)],
            [0.01, 0.01 * math.sin(0.1 * math.pi)],
            [0.0, 0.0],  # not reached yet at 0.3 s; sin(0) at 0.5 s
        ]
        np.testing.assert_allclose(z, expected, rtol=0, atol=1e-15)
        v = roads.velocity([0.3])[:, 0]
        assert v[3] == 0.0  # held, with zero velocity, until the delay
        assert v[2] == pytest.approx(0.02 * math.pi * math.cos(0.1 * math.pi), rel=1e-14)
        assert roads.rear_delay == 0.5
        assert roads.duration == Harmonic(1.0, 0.01).duration + 0.5

    def test_wheelbase_delays_are_from_excitation_to_the_bit(self):
        # the rear wheel sees the front's road wheelbase/speed later: 2.7 m at 54 km/h
        road = preset_road("rough", speed_kmh=54.0)
        driven = WheelRoads.from_excitation(road, GEOMETRY)
        assert driven.corner_delays == pytest.approx((0.0, 0.0, 0.18, 0.18), rel=1e-15, abs=0)
        rig = WheelRoads.in_phase(road, delays=driven.corner_delays)
        t = np.arange(3001) * 1e-3
        np.testing.assert_array_equal(rig.displacement(t), driven.displacement(t))
        for a, b in zip(rig.sample_grid(3001, 1e-3), driven.sample_grid(3001, 1e-3), strict=True):
            np.testing.assert_array_equal(a, b)

    def test_layouts_and_describe(self):
        import json

        from mrsuspension.vehicle import HalfCar

        half = WheelRoads.in_phase(Harmonic(2.0, 0.01), HalfCar(), delays=(0.0, 0.2))
        assert half.corners == HALF_CAR_CORNERS
        assert half.right is None
        assert (half.speed_kmh, half.speed, half.wheelbase) == (None, None, None)
        d = half.describe()
        json.dumps(d)
        assert (d["delays"], d["rear_delay"], d["speed_kmh"]) == ([0.0, 0.2], 0.2, None)
        assert "delays=[0.0, 0.2] s" in repr(half)
        assert WheelRoads.in_phase(Harmonic(2.0, 0.01), "half-car").corners == HALF_CAR_CORNERS
        assert (
            "delays"
            not in WheelRoads.from_excitation(road := preset_road("smooth"), GEOMETRY).describe()
        )
        assert WheelRoads.in_phase(road, FULL_CAR_CORNERS).describe()["delays"] == [0.0] * 4

    def test_bad_input(self):
        h = Harmonic(1.0, 0.01)
        _raises(
            lambda: WheelRoads.in_phase(h, delays=(0.0, 0.1)),
            "delays must have one value per corner",
            "(4); got [0.0, 0.1]",
        )
        _raises(
            lambda: WheelRoads.in_phase(h, delays=(0.0, 0.0, -0.1, 0.0)),
            "delays must be in [0, 10000] s; got -0.1 s at index 2",
        )
        _raises(
            lambda: WheelRoads.in_phase(h, delays="0.1"),
            "delays must be a sequence of 4 delays [s]",
        )
        _raises(
            lambda: WheelRoads.in_phase(h, "half_car"),
            "unknown corner layout",
            "Did you mean 'half-car'?",
        )
        _raises(lambda: WheelRoads.in_phase("harmonic"), "must be a single-track Excitation")
        _raises(lambda: WheelRoads(h, h), "wheelbase [m] and speed_kmh [km/h] are needed")
        _raises(lambda: WheelRoads(h, h, speed_kmh=50.0, delays=(0.0,) * 4), "not both")


# -- (b) and (c) the two-track random road ----------------------------------------------------
class TestTwoTrack:
    @pytest.mark.parametrize("road", ["C", "rough"])
    def test_measured_coherence_matches_the_model(self, road):
        # 20 km: the scatter of the Welch estimate over 0.05-2 cycle/m is what limits the
        # agreement (max deviation 0.016-0.033 over seeds 0-9; at 5 km 0.028-0.063)
        roads = WheelRoads.two_track(road, GEOMETRY, 72.0, length=20000.0, spacing=0.1, seed=0)
        left, right = roads.left.elevation, roads.right.elevation
        n, msc = coherence(left, right, fs=1 / 0.1, nperseg=1024)
        band = (n >= 0.05) & (n <= 2.0)
        waviness = roads.left.spectrum.waviness
        model = isotropic_coherence(n[band], 1.5, waviness) ** 2  # magnitude-squared
        assert np.max(np.abs(msc[band] - model)) < 0.05
        assert abs(np.mean(msc[band] - model)) < 0.01

    @pytest.mark.parametrize(("road_class", "seed"), [("A", 0), ("C", 1), ("E", 5)])
    def test_each_track_has_the_iso_psd(self, road_class, seed):
        # the tolerances of test_road.TestIso8608.test_spatial_psd_matches_gd
        roads = WheelRoads.two_track(road_class, GEOMETRY, seed=seed)
        for profile in (roads.left, roads.right):
            n, gd = profile.spatial_psd()
            band = (n > 0.03) & (n < 1.5)
            slope, intercept = np.polyfit(np.log(n[band] / 0.1), np.log(gd[band]), 1)
            assert slope == pytest.approx(-2.0, abs=0.1)
            assert math.exp(intercept) == pytest.approx(ISO8608_CLASSES[road_class], rel=0.15)
            ratio = gd / iso8608_psd(road_class, np.maximum(n, 1e-9))
            edges = [0.04, 0.08, 0.16, 0.32, 0.64, 1.28]
            for lo, hi in itertools.pairwise(edges):
                sel = (n >= lo) & (n < hi)
                assert np.mean(ratio[sel]) == pytest.approx(1.0, abs=0.25), (lo, hi)

    def test_left_is_the_single_track_road_and_seeds_reproduce(self):
        a = WheelRoads.two_track("D", GEOMETRY, seed=7)
        b = WheelRoads.two_track("D", GEOMETRY, seed=7)
        c = WheelRoads.two_track("D", GEOMETRY, seed=8)
        np.testing.assert_array_equal(a.left.elevation, iso8608("D", seed=7).elevation)
        np.testing.assert_array_equal(a.right.elevation, b.right.elevation)
        assert not np.array_equal(a.right.elevation, c.right.elevation)
        preset = WheelRoads.two_track("rough", GEOMETRY)
        np.testing.assert_array_equal(preset.left.elevation, preset_road("rough").elevation)

    def test_spectrum_and_half_car(self):
        spectrum = RoadSpectrum(1e-5, waviness=2.5)
        roads = WheelRoads.two_track(spectrum, GEOMETRY, seed=1)
        assert roads.details["coherence"]["waviness"] == 2.5
        half = WheelRoads.two_track("B", (2.6, None), corners="half-car", seed=1)
        assert half.right is None
        assert half.corners == HALF_CAR_CORNERS

    def test_coherence_closed_forms(self):
        n = np.array([0.0, 0.02, 0.1, 0.5, 3.0])
        x = 2 * np.pi * n * 1.5
        from scipy.special import k1

        expected = np.where(x == 0, 1.0, x * k1(np.where(x == 0, 1.0, x)))
        np.testing.assert_allclose(isotropic_coherence(n, 1.5), expected, rtol=1e-12)
        np.testing.assert_allclose(isotropic_coherence(n, 1.5, 1.0), np.exp(-x), rtol=1e-12)
        assert np.all(np.diff(isotropic_coherence(np.linspace(0, 5, 200), 1.0)) <= 0)


# -- (d) OpenCRG files -------------------------------------------------------------------------
class TestCrg:
    def test_round_trip(self, tmp_path):
        u_inc = 0.05
        u = np.arange(0.0, 60.0 + u_inc / 2, u_inc)
        v = np.linspace(-2.0, 2.0, 41)
        rng = np.random.default_rng(3)
        left_track = 0.01 * np.sin(0.8 * u) + 0.002 * rng.standard_normal(u.size)
        right_track = 0.005 * np.cos(0.5 * u)
        # a grid linear in v between the two wheel tracks at v = +-0.75 m
        w = (v[None, :] + 0.75) / 1.5
        z = right_track[:, None] + w * (left_track - right_track)[:, None]
        path = _write_crg(tmp_path / "road.crg", z, u_inc, v)
        roads = WheelRoads.from_crg(path, GEOMETRY, speed_kmh=36.0)
        assert roads.corners == FULL_CAR_CORNERS
        np.testing.assert_allclose(roads.left.distance, u, atol=1e-12)
        np.testing.assert_allclose(roads.left.elevation, left_track, atol=1e-12)
        np.testing.assert_allclose(roads.right.elevation, right_track, atol=1e-12)
        # and it drives: the rear left is the front left 0.27 s later
        t = np.array([1.0, 2.0, 3.0])
        z_t = roads.displacement(t)
        np.testing.assert_allclose(z_t[0], roads.left.elevation_at(10.0 * t), atol=1e-12)
        np.testing.assert_allclose(z_t[2], roads.left.elevation_at(10.0 * t - 2.7), atol=1e-12)
        d = roads.describe()
        assert d["source"] == "OpenCRG road.crg"
        assert d["details"]["v"] == {"left": 0.75, "right": -0.75}

    def test_lateral_offset_banking_and_grid_only(self, tmp_path):
        u = np.arange(0.0, 20.0 + 0.05, 0.1)
        v = np.linspace(-2.0, 2.0, 21)
        z = np.tile(v, (u.size, 1)) * 0.01  # 1 cm per metre to the left
        path = _write_crg(tmp_path / "banked.crg", z, 0.1, v, banking=0.02)
        roads = WheelRoads.from_crg(path, GEOMETRY, lateral_offset=0.5)
        np.testing.assert_allclose(roads.left.elevation, 1.25 * 0.03, atol=1e-12)
        np.testing.assert_allclose(roads.right.elevation, -0.25 * 0.03, atol=1e-12)
        grid = WheelRoads.from_crg(path, GEOMETRY, lateral_offset=0.5, absolute=False)
        np.testing.assert_allclose(grid.left.elevation, 1.25 * 0.01, atol=1e-12)
        half = WheelRoads.from_crg(path, (2.6, None), corners="half-car", lateral_offset=0.5)
        np.testing.assert_allclose(half.left.elevation, 0.5 * 0.03, atol=1e-12)

    def test_nan_on_a_wheel_track(self, tmp_path):
        u = np.arange(0.0, 20.0 + 0.05, 0.1)
        v = np.linspace(-1.5, 1.5, 31)
        z = np.zeros((u.size, v.size))
        z[73, 8] = np.nan  # v = -0.7 m: next to the right wheel track at -0.75 m
        path = _write_crg(tmp_path / "hole.crg", z, 0.1, v)
        message = _raises(
            lambda: WheelRoads.from_crg(path, GEOMETRY),
            "CRG file 'hole.crg'",
            "NaN",
            "right wheel track at u = 7.3 m, v = -0.75 m",
        )
        assert "\n" not in message
        # a hole away from the wheel tracks does not matter
        WheelRoads.from_crg(path, GEOMETRY, lateral_offset=0.3)

    def test_bad_files(self, tmp_path):
        _raises(
            lambda: WheelRoads.from_crg(tmp_path / "nope.crg", GEOMETRY),
            "CRG file not found",
            "nope.crg",
        )
        _raises(lambda: WheelRoads.from_crg(tmp_path, GEOMETRY), "is a folder")
        bad = tmp_path / "bad.crg"
        bad.write_text("this is not a road\n1 2 3\n")
        message = _raises(
            lambda: WheelRoads.from_crg(bad, GEOMETRY), "cannot read CRG file 'bad.crg'"
        )
        assert "\n" not in message
        binary = tmp_path / "binary.crg"
        binary.write_bytes(bytes(range(256)) * 4)
        _raises(lambda: WheelRoads.from_crg(binary, GEOMETRY), "cannot read CRG file 'binary.crg'")

    def test_tracks_outside_the_road(self, tmp_path):
        v = np.linspace(-1.0, 1.0, 11)
        path = _write_crg(tmp_path / "narrow.crg", np.zeros((50, 11)), 0.1, v)
        _raises(
            lambda: WheelRoads.from_crg(path, GEOMETRY, lateral_offset=0.5),
            "left wheel track at v = 1.25 m lies outside the road",
            "-1 to 1 m",
        )


# -- (e) one-sided bumps and potholes ---------------------------------------------------------
class TestEvents:
    @pytest.mark.parametrize("side", ["left", "right"])
    def test_bump_on_one_side_only(self, side):
        roads = WheelRoads.bump(side, 0.05, 0.4, GEOMETRY, speed_kmh=36.0, position=1.0)
        t = np.linspace(0.0, roads.duration, 20001)
        z, v = roads.displacement(t), roads.velocity(t)
        on = [i for i, c in enumerate(FULL_CAR_CORNERS) if c.endswith(side)]
        off = [i for i, c in enumerate(FULL_CAR_CORNERS) if not c.endswith(side)]
        assert np.all(z[off] == 0.0)
        assert np.all(v[off] == 0.0)
        assert z[on].max(axis=1) == pytest.approx([0.05, 0.05], rel=1e-4)  # on the grid
        # the front wheel meets it at 0.1 s (1 m at 10 m/s), the rear 0.27 s later
        first = [t[np.flatnonzero(z[i] > 0)[0]] for i in on]
        assert first == pytest.approx([0.1, 0.37], abs=2e-4)
        # the rounded pulse shape, w0 = 3 pi V / length
        assert roads.describe()["tracks"][side]["omega0"] == pytest.approx(3 * np.pi * 10 / 0.4)

    def test_pothole_is_rounded_and_one_sided(self):
        roads = WheelRoads.pothole("left", 0.04, 0.8, GEOMETRY, speed_kmh=36.0, position=2.0)
        t = np.linspace(0.0, roads.duration, 40001)
        z = roads.displacement(t)
        assert np.all(z[[1, 3]] == 0.0)
        assert z[0].min() == pytest.approx(-0.04)
        assert z[0].max() == 0.0
        # twice continuously differentiable: the acceleration changes no faster than the
        # largest jerk of the C2 edge, 60 depth V^3 / edge^3 (no jumps)
        a = roads.acceleration(t)[0]
        jerk = 60 * 0.04 * 10.0**3 / 0.1**3
        assert np.max(np.abs(np.diff(a))) <= 1.01 * jerk * (t[1] - t[0])
        assert a[0] == 0.0
        assert np.max(np.abs(a)) == pytest.approx(0.04 * 10.0**2 / 0.1**2 * 5.7735, rel=1e-3)

    def test_both_sides_and_half_car(self):
        both = WheelRoads.bump("both", 0.03, 0.5, GEOMETRY)
        t = np.linspace(0.0, 2.0, 201)
        z = both.displacement(t)
        np.testing.assert_array_equal(z[0], z[1])
        half = WheelRoads.pothole("left", 0.03, 0.5, (2.6, None), corners="half-car")
        assert half.displacement(t).shape == (2, 201)


# -- (f) velocity is the derivative of displacement ---------------------------------------------
@pytest.mark.parametrize(
    "build",
    [
        lambda: WheelRoads.two_track("C", GEOMETRY, 72.0, seed=1),
        lambda: WheelRoads.from_excitation(Harmonic(1.7, 0.01), GEOMETRY, 50.0),
        lambda: WheelRoads.bump("right", 0.05, 0.5, GEOMETRY, 36.0, position=1.0),
        lambda: WheelRoads.pothole("left", 0.04, 0.8, GEOMETRY, 36.0, position=1.0),
    ],
    ids=["two-track", "harmonic", "bump", "pothole"],
)
def test_velocity_is_the_derivative_of_displacement(build):
    roads = build()
    t = np.linspace(0.05, min(roads.duration, 4.0), 4001)
    h = 1e-6
    v_fd = (roads.displacement(t + h) - roads.displacement(t - h)) / (2 * h)
    a_fd = (roads.velocity(t + h) - roads.velocity(t - h)) / (2 * h)
    v, a = roads.velocity(t), roads.acceleration(t)
    # away from a kink (a pulse's onset, a wheel reaching the road)
    kink = np.zeros(t.size, bool)
    for onset in (0.1, 0.1 + roads.rear_delay, roads.rear_delay):
        kink |= np.abs(t - onset) < 2 * h
    np.testing.assert_allclose(v_fd[:, ~kink], v[:, ~kink], atol=1e-6 * max(np.abs(v).max(), 1e-3))
    np.testing.assert_allclose(a_fd[:, ~kink], a[:, ~kink], atol=1e-3 * max(np.abs(a).max(), 1e-3))


# -- validation -------------------------------------------------------------------------------------
class TestValidation:
    def test_speed_wheelbase_track(self):
        road = preset_road("smooth")
        _raises(
            lambda: WheelRoads.from_excitation(road, GEOMETRY, 0.0),
            "speed_kmh must be in (0, 500] km/h; got 0",
        )
        _raises(lambda: WheelRoads.from_excitation(road, GEOMETRY, -30.0), "speed_kmh", "got -30")
        _raises(
            lambda: WheelRoads.from_excitation(road, (0.0, 1.5)),
            "wheelbase must be in (0, 100] m; got 0",
        )
        _raises(lambda: WheelRoads.from_excitation(road, (2.7, -1.0)), "track must be in (0, 10] m")
        _raises(lambda: WheelRoads.from_excitation(road, (2.7, None)), "a full car needs a track")
        _raises(lambda: WheelRoads.from_excitation(road, 2.7), "geometry must be a pair")
        _raises(
            lambda: WheelRoads.from_excitation(Harmonic(1.0, 0.01), GEOMETRY), "speed_kmh is needed"
        )
        _raises(
            lambda: WheelRoads.from_excitation("rough", GEOMETRY),
            "must be a single-track Excitation",
        )

    def test_geometry_object(self):
        class Car:
            wheelbase = 2.5
            track = 1.6

        roads = WheelRoads.from_excitation(preset_road("smooth"), Car())
        assert (roads.wheelbase, roads.track) == (2.5, 1.6)

    def test_names_with_did_you_mean(self):
        _raises(
            lambda: WheelRoads.bump("lef", 0.05, 0.5, GEOMETRY),
            "unknown side 'lef'. Did you mean 'left'? Valid: both, left, right.",
        )
        _raises(
            lambda: WheelRoads.from_excitation(
                preset_road("smooth"),
                GEOMETRY,
                corners=("front_left", "front_rigth", "rear_left", "rear_right"),
            ),
            "unknown corner 'front_rigth'. Did you mean 'front_right'?",
        )
        _raises(lambda: WheelRoads.two_track("rouhg", GEOMETRY), "Did you mean 'rough'?")
        _raises(
            lambda: WheelRoads.two_track("C", GEOMETRY, corners="full_car"),
            "unknown corner layout",
            "Did you mean 'full-car'?",
        )
        _raises(lambda: WheelRoads.two_track("C", GEOMETRY).index("rear"), "unknown corner 'rear'")
        _raises(
            lambda: WheelRoads.pothole("right", 0.03, 0.5, (2.6, None), corners="half-car"),
            "side 'right' leaves a half car unexcited",
        )

    def test_event_arguments(self):
        _raises(lambda: WheelRoads.bump("left", 0.0, 0.5, GEOMETRY), "amplitude must be nonzero")
        _raises(
            lambda: WheelRoads.bump("left", 0.05, -1.0, GEOMETRY), "length must be in (0, 1000] m"
        )
        _raises(lambda: WheelRoads.bump("left", 0.05, 0.001, GEOMETRY), "length must be at least")
        _raises(
            lambda: WheelRoads.bump("left", 0.05, 0.5, GEOMETRY, position=-1.0),
            "position must be in [0",
        )
        _raises(
            lambda: WheelRoads.pothole("left", -0.04, 0.5, GEOMETRY), "depth must be in (0, 1] m"
        )
        _raises(
            lambda: WheelRoads.pothole("left", 0.04, 0.1, GEOMETRY),
            "length must be in [0.2, 1000] m; got 0.1 m",
        )
        _raises(lambda: Pothole(0.04, 0.5, edge=0.0), "edge must be in (0")
        _raises(
            lambda: WheelRoads.two_track("C", GEOMETRY, seed=-1), "seed must be an integer >= 0"
        )
        _raises(
            lambda: WheelRoads.two_track(RoadSpectrum(1e-5, waviness=0.0), GEOMETRY), "waviness > 0"
        )
        _raises(lambda: isotropic_coherence([-0.1], 1.5), "spatial_frequency must be in [0, inf)")

    def test_describe_is_plain_data(self):
        import json

        for roads in (
            WheelRoads.two_track("C", GEOMETRY, seed=1),
            WheelRoads.bump("left", 0.05, 0.5, GEOMETRY),
            WheelRoads.pothole("right", 0.04, 0.5, GEOMETRY),
            WheelRoads.from_excitation(Harmonic(1.0, 0.01), (2.6, None), 50.0, corners="half-car"),
        ):
            d = roads.describe()
            json.dumps(d)
            assert d["corners"] == list(roads.corners)
            assert d["duration"] == roads.duration > roads.rear_delay
