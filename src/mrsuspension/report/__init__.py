"""Figures and the HTML report (matplotlib is imported lazily, inside the functions)."""

from __future__ import annotations

from mrsuspension.report.html import FigureRecord, build_report

__all__ = ["FigureRecord", "build_report"]
