"""The writers of an identification's outputs (parameter sets, tables, plots, HTML).

They live beside the result types in :mod:`mrsuspension.identify.results` (so nothing
imports in a circle); this module names them for callers that import them from here.
"""

from __future__ import annotations

from mrsuspension.identify.results import evidence_text, plot_test, summary_text, write_outputs

__all__ = ["evidence_text", "plot_test", "summary_text", "write_outputs"]
