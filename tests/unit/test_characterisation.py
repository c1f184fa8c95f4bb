"""The laboratory characterisation (Table 2.1) and its loop measures."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest

from mrsuspension.characterisation import (
    CharacterisationResult,
    TestCondition,
    characterise,
    harmonic_loop,
    table_2_1,
)
from mrsuspension.dampers import LinearViscous, WangSymmetric
from mrsuspension.errors import ValidationError

# Table 2.1: frequencies tested at each amplitude
FREQUENCIES = [0.1, 0.5, 1.5, 2.5, 5.0, 7.5, 10.0, 12.5, 15.0]
HIGHEST = {0.0025: 15.0, 0.0125: 12.5, 0.025: 10.0, 0.05: 5.0, 0.075: 2.5}
COUNTS = {0.0025: 9, 0.0125: 8, 0.025: 7, 0.05: 5, 0.075: 4}
CURRENTS = [0.0, 0.1, 0.2, 0.3, 0.4]


def test_table_2_1_has_165_tests():
    tests = table_2_1()
    assert len(tests) == 165
    assert len(set(tests)) == 165
    assert all(isinstance(t, TestCondition) for t in tests)
    assert sorted({t.current for t in tests}) == CURRENTS


@pytest.mark.parametrize("amplitude", sorted(HIGHEST))
def test_table_2_1_frequency_limits_per_amplitude(amplitude):
    tests = [t for t in table_2_1() if math.isclose(t.amplitude, amplitude)]
    freqs = sorted({t.frequency for t in tests})
    assert freqs == [f for f in FREQUENCIES if f <= HIGHEST[amplitude]]
    assert len(freqs) == COUNTS[amplitude]
    assert max(freqs) == HIGHEST[amplitude]
    assert len(tests) == 5 * COUNTS[amplitude]
    for f in freqs:
        assert sorted(t.current for t in tests if t.frequency == f) == CURRENTS


def test_table_2_1_restrictions():
    assert len(table_2_1(frequencies=[0.5, 1.5, 2.5, 5.0])) == 4 * 4 * 5 + 3 * 5
    assert len(table_2_1(amplitudes=[0.075])) == 20
    assert len(table_2_1(currents=[0.0])) == 33
    # a frequency above the amplitude's limit is not invented
    assert table_2_1(frequencies=[15.0], amplitudes=[0.075]) == []


def test_condition_peak_velocity_and_label():
    c = TestCondition(1.5, 0.0125, 0.2)
    assert c.peak_velocity == pytest.approx(2 * math.pi * 1.5 * 0.0125, rel=1e-15)
    assert c.label() == "1.5 Hz, 12.5 mm, 0.2 A"


@pytest.mark.parametrize(("frequency", "amplitude"), [(1.5, 0.0125), (0.1, 0.075), (15.0, 0.0025)])
@pytest.mark.parametrize("damping", [1000.0, 2500.0])
def test_linear_damper_energy_per_cycle_is_pi_c_omega_a_squared(frequency, amplitude, damping):
    loop = harmonic_loop(LinearViscous(damping=damping), frequency, amplitude)
    omega = 2 * math.pi * frequency
    closed_form = math.pi * damping * omega * amplitude**2
    assert loop.energy_per_cycle() == pytest.approx(closed_form, rel=1e-3)
    assert loop.equivalent_damping() == pytest.approx(damping, rel=1e-3)
    # the loop is one cycle of the sinusoid
    assert loop.force.size == 360
    assert loop.stroke.max() == pytest.approx(amplitude, rel=1e-3)
    assert loop.max_compression_force == pytest.approx(damping * omega * amplitude, rel=1e-9)
    assert loop.max_rebound_force == pytest.approx(damping * omega * amplitude, rel=1e-3)


def test_wang_loop_uses_the_known_peak_velocity():
    loop = harmonic_loop(WangSymmetric(), 1.5, 0.0125, current=0.2)
    assert loop.peak_velocity == pytest.approx(2 * math.pi * 1.5 * 0.0125, rel=1e-15)
    ref = WangSymmetric().force(
        0.0, loop.velocity, -np.sign(loop.stroke), 0.2, peak_velocity=loop.peak_velocity
    )
    np.testing.assert_allclose(loop.force, ref, rtol=1e-12, atol=1e-9)
    assert loop.energy_per_cycle() > 0


def test_harmonic_loop_validation():
    with pytest.raises(ValidationError, match="frequency"):
        harmonic_loop(LinearViscous(), 0.0, 0.01)
    with pytest.raises(ValidationError, match="amplitude"):
        harmonic_loop(LinearViscous(), 1.0, -0.01)
    with pytest.raises(ValidationError, match=r"drive current must be in \[0, 0.5\]"):
        harmonic_loop(LinearViscous(), 1.0, 0.01, current=0.6)
    with pytest.raises(ValidationError, match="peak_velocity"):
        harmonic_loop(LinearViscous(), 1.0, 0.01, peak_velocity="guess")
    with pytest.raises(ValidationError, match="points_per_cycle"):
        harmonic_loop(LinearViscous(), 1.0, 0.01, points_per_cycle=3)


def test_characterise_and_save(tmp_path):
    conditions = table_2_1(frequencies=[1.5], amplitudes=[0.0125, 0.025], currents=[0.0, 0.2])
    assert len(conditions) == 4
    damping = 2500.0
    result = characterise(LinearViscous(damping=damping), conditions)
    assert isinstance(result, CharacterisationResult)
    assert len(result) == 4
    loop = result.find(1.5, 0.025, 0.2)
    assert loop.condition == TestCondition(1.5, 0.025, 0.2)
    with pytest.raises(ValidationError, match="no test"):
        result.find(2.5, 0.025, 0.2)

    summary_path, loops_path = result.save(tmp_path / "out")
    assert summary_path.name == "summary.csv"
    assert loops_path.name == "loops.csv"
    with summary_path.open(newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 4
    for row in rows:
        a, f = float(row["amplitude [m]"]), float(row["frequency [Hz]"])
        closed_form = math.pi * damping * 2 * math.pi * f * a**2
        assert float(row["energy per cycle [J]"]) == pytest.approx(closed_form, rel=1e-3)
        assert float(row["equivalent damping [N s/m]"]) == pytest.approx(damping, rel=1e-3)
    with loops_path.open(newline="") as fh:
        reader = csv.reader(fh)
        header = next(reader)
        body = list(reader)
    assert header[0] == "frequency [Hz]"
    assert "force [N]" in header
    assert len(body) == 4 * 360
    forces = np.array([float(r[header.index("force [N]")]) for r in body])
    speeds = np.array([float(r[header.index("velocity [m/s]")]) for r in body])
    np.testing.assert_allclose(forces, damping * speeds, rtol=1e-5, atol=1e-6)


def test_characterise_rejects_currents_above_the_limit():
    model = LinearViscous(max_current=0.3)
    with pytest.raises(ValidationError, match=r"drive current must be in \[0, 0.3\] A; got 0.4"):
        characterise(model, table_2_1(frequencies=[1.5], amplitudes=[0.0125]))
    with pytest.raises(ValidationError, match="no test conditions"):
        characterise(model, [])
