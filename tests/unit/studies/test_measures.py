"""``studies.MEASURES`` is what ``SimulationResult.measures()`` returns, kind by kind."""

from __future__ import annotations

import pytest

from mrsuspension.engine.result import MEASURE_NOTES, MEASURES_BY_KIND
from mrsuspension.engine.simulate import Simulation
from mrsuspension.excitation import EXCITATIONS, SteppedSweep, make_excitation
from mrsuspension.studies import MEASURES


def test_every_kind_has_its_measures() -> None:
    assert set(MEASURES) == set(EXCITATIONS)
    for kind, cls in EXCITATIONS.items():
        assert MEASURES[kind] == MEASURES_BY_KIND[cls.measures_kind]


@pytest.mark.parametrize("kind", sorted(EXCITATIONS))
def test_measures_match_what_a_run_returns(kind: str) -> None:
    exc = make_excitation(kind, **EXCITATIONS[kind].example_options)
    run = next(iter(exc)) if isinstance(exc, SteppedSweep) else exc
    duration = None if EXCITATIONS[kind].measures_kind == "harmonic" else min(run.duration, 3.0)
    result = Simulation(run).run(duration, dt=5e-4)
    got = result.measures()
    notes = MEASURE_NOTES.get(EXCITATIONS[kind].measures_kind, ())
    assert set(got) == set(MEASURES[kind]) | set(notes)
    for name in MEASURES[kind]:
        float(got[name])  # numeric
