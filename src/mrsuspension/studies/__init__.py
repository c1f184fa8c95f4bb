"""Studies: grids of scenarios run in batch, with results as labelled arrays.

* :class:`Study` - a declarative study file (TOML): a base scenario, a ``[grid]`` of
  fields to vary, ``[cases]`` that change several fields together, the measures to keep;
  every grid point is validated on load;
* :func:`run_study` - runs it on a local process pool or a Dask cluster, caches by a
  content hash, returns a :class:`StudyResult` (xarray Dataset, pandas, NetCDF/CSV).

See ``docs/studies.md``.
"""

from __future__ import annotations

from mrsuspension.studies.run import StudyResult, default_cache_dir, run_study
from mrsuspension.studies.study import MEASURES, Axis, Study, expand_frequencies

__all__ = [
    "MEASURES",
    "Axis",
    "Study",
    "StudyResult",
    "default_cache_dir",
    "expand_frequencies",
    "run_study",
]
