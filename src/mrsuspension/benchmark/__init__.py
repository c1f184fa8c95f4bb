"""The semi-active optimum: the lower bound every control law is scored against.

For a road record known in advance, the best any damper inside the MR damper's force band
can do for a weighted objective of comfort (Wk-weighted body acceleration), road holding
(dynamic tyre force) and rattle space (stroke): an optimal control problem solved offline
by direct transcription with IPOPT through CasADi (``pip install "mrsuspension[optimal]"``).
``docs/benchmark.md`` states the problem, the equations, the solver settings and the
numbers of a 10 s ISO 8608 class C record at 50 km/h.

* :func:`semi_active_optimum`, :class:`BenchmarkProblem` - the optimum and the same
  discretised model for reference laws (passive, skyhook through the band);
* :func:`pareto_front` - the optimum over a sweep of the comfort weight;
* :func:`replay` - the optimal force re-simulated with the toolkit's engine;
* :class:`HalfCarProblem` - the same on the half car (a damper per axle, the rear wheel
  on the front wheel's road later);
* :class:`MRBand`, :class:`MREnvelopeBand`, :class:`LinearBand`, :class:`ActiveBand` - force
  bands;
* :func:`~mrsuspension.benchmark.model.wk_state_space` - the Wk weighting as a state-space
  system;
* :func:`run_benchmark`, :class:`BenchmarkSpec` - the benchmark of semi-active laws: each
  tuned on a training road, scored on other roads, speeds and vehicles against the
  passive car and the optimum (``mrsus benchmark``).

Only :mod:`mrsuspension.report` and the command line import this package; it imports
the engine, the vehicle, the dampers, the excitations and the measures, and the
benchmark of laws the optimiser (:mod:`mrsuspension.optimize`) and a study's scheduler
check (:mod:`mrsuspension.studies`).
"""

from __future__ import annotations

from mrsuspension.benchmark.band import ActiveBand, ForceBand, LinearBand, MRBand, MREnvelopeBand
from mrsuspension.benchmark.halfcar import HalfCarOptimum, HalfCarProblem
from mrsuspension.benchmark.model import wk_state_space
from mrsuspension.benchmark.optimum import (
    TERMS,
    BenchmarkProblem,
    OptimumResult,
    ParetoFront,
    Trajectory,
    Weights,
    pareto_front,
    replay,
    semi_active_optimum,
)
from mrsuspension.benchmark.study import (
    LAW_TABLE,
    BenchmarkResult,
    BenchmarkRoad,
    BenchmarkSpec,
    TunedOption,
    default_laws,
    run_benchmark,
)

__all__ = [
    "LAW_TABLE",
    "TERMS",
    "ActiveBand",
    "BenchmarkProblem",
    "BenchmarkResult",
    "BenchmarkRoad",
    "BenchmarkSpec",
    "ForceBand",
    "HalfCarOptimum",
    "HalfCarProblem",
    "LinearBand",
    "MRBand",
    "MREnvelopeBand",
    "OptimumResult",
    "ParetoFront",
    "Trajectory",
    "TunedOption",
    "Weights",
    "default_laws",
    "pareto_front",
    "replay",
    "run_benchmark",
    "semi_active_optimum",
    "wk_state_space",
]
