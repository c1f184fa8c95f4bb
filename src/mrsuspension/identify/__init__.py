"""Parameter identification from measured damper data (model reference, section 10, eq. 2.22).

The pipeline of ``mrsus identify``, usable piece by piece:

* :mod:`~mrsuspension.identify.readers` - test records from delimited text or ``.mat``
  files, column mapping and units (:func:`read_test`);
* :mod:`~mrsuspension.identify.manifest` - the tests of a campaign (:func:`read_manifest`);
* :mod:`~mrsuspension.identify.preprocess` - frequency detection, steady whole cycles
  (the plateau of a ramped test: :mod:`~mrsuspension.identify.plateau`), resampling to
  360 points per loop (:func:`preprocess`);
* :mod:`~mrsuspension.identify.fit` - global multi-start least squares over all tests
  (:func:`fit_loops`);
* :mod:`~mrsuspension.identify.campaign` - all of it, with per-test outcomes
  (:func:`identify`);
* :mod:`~mrsuspension.identify.results` - the result types and their outputs (parameter
  set, tables, plots, HTML; also named by :mod:`~mrsuspension.identify.report`);
* :mod:`~mrsuspension.identify.results` - the result types (per test, per band, all);
* :mod:`~mrsuspension.identify.synthetic` - synthetic campaigns from any model (with a
  rig's ramps: :func:`ramped_campaign`), and the example campaign shipped with the
  package (:func:`example_campaign`);
* :mod:`~mrsuspension.identify.record` and :mod:`~mrsuspension.identify.timedomain` -
  records of any motion (random displacement, switched coil) and models with internal
  states integrated over them (:func:`read_record`, :func:`fit_time_domain`).

Examples
--------
>>> import tempfile
>>> from mrsuspension.identify import identify, synthetic_campaign
>>> manifest = synthetic_campaign(tempfile.mkdtemp(), "linear", [(2.0, 0.01, 0.0)])
>>> round(identify(manifest, "linear").parameters["c"], 3)
2500.0
"""

from __future__ import annotations

from mrsuspension.identify.campaign import (
    IdentificationResult,
    TestOutcome,
    identify,
    load_campaign,
    loop_metrics,
)
from mrsuspension.identify.fit import FitError, FitProblem, FitResult, fit_loops
from mrsuspension.identify.manifest import Manifest, TestEntry, read_manifest
from mrsuspension.identify.preprocess import (
    Loop,
    PreprocessOptions,
    detect_frequency,
    preprocess,
    smooth_derivative,
)
from mrsuspension.identify.readers import RawTest, TestDataError, read_test
from mrsuspension.identify.record import TimeRecord, read_record
from mrsuspension.identify.synthetic import (
    example_campaign,
    field_campaign,
    ramped_campaign,
    synthetic_campaign,
)
from mrsuspension.identify.timedomain import (
    TIME_DOMAIN_MODELS,
    TimeDomainResult,
    fit_time_domain,
    synthetic_record,
)

__all__ = [
    "TIME_DOMAIN_MODELS",
    "FitError",
    "FitProblem",
    "FitResult",
    "IdentificationResult",
    "Loop",
    "Manifest",
    "PreprocessOptions",
    "RawTest",
    "TestDataError",
    "TestEntry",
    "TestOutcome",
    "TimeDomainResult",
    "TimeRecord",
    "detect_frequency",
    "example_campaign",
    "field_campaign",
    "fit_loops",
    "fit_time_domain",
    "identify",
    "load_campaign",
    "loop_metrics",
    "preprocess",
    "ramped_campaign",
    "read_manifest",
    "read_record",
    "read_test",
    "smooth_derivative",
    "synthetic_campaign",
    "synthetic_record",
]
