"""Write docs/report.md: every figure and table of the report's Chapters 4-6 with its scenario.

Generated from the figure-family specs of the registered chapters
(``mrsuspension.report.chapters``), so the page cannot drift from the code; ``tests/unit/report/test_families.py`` checks it is current.

Run: ``python tools/report_docs.py``.
"""

from __future__ import annotations

from pathlib import Path

from mrsuspension.report import report_page

page = Path(__file__).resolve().parents[1] / "docs" / "report.md"
page.write_text(report_page())
print(f"wrote {page}")
