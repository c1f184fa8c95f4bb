"""The report's scorecard in a real browser: a summary first, the claims folded away,
and a filter by status and text that shows and hides rows (issue 31, item 7)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from mrsuspension.report.findings import ClaimResult, Scorecard, html_section
from mrsuspension.report.findings.claims import Claim

pytestmark = pytest.mark.browser


def _card() -> Scorecard:
    def claim(i: str, words: str) -> Claim:
        return Claim(i, i.split("-")[0], "a quote of twenty characters", words, None)  # type: ignore[arg-type]

    return Scorecard(
        [
            ClaimResult(
                claim("4.3-a", "Skyhook lowers the body's peak"), True, "held", "0.8 < 0.9"
            ),
            ClaimResult(claim("5.4-b", "Pulse current stays low"), False, "not held", "0.4 A"),
            ClaimResult(claim("6.2-c", "Sliding mode tracks"), True, "held", "1.01"),
        ],
        quick=False,
    )


def test_summary_first_claims_folded_and_filtered(browser: Any, tmp_path: Path) -> None:
    page_file = tmp_path / "index.html"
    page_file.write_text(f"<!doctype html><html><body>{html_section(_card())}</body></html>")
    page = browser.new_page()
    try:
        page.goto(page_file.as_uri())
        summary = page.locator("table.summary")
        assert "Chapter 4" in summary.inner_text()
        rows = page.locator("#findings-table tr[data-status]")
        assert not rows.first.is_visible()  # folded: the summary reads first
        page.locator("#findings-claims summary").click()
        assert rows.first.is_visible()
        assert page.locator("#findings-shown").inner_text() == "3"
        page.locator("#findings-filter input[value='held']").uncheck()
        assert page.locator("#findings-shown").inner_text() == "1"
        assert page.locator("#findings-table tr[data-status='not held']").is_visible()
        page.locator("#findings-filter input[value='held']").check()
        page.locator("#findings-text").fill("sliding")
        assert page.locator("#findings-shown").inner_text() == "1"
        assert page.locator("#findings-table tr[data-status]").nth(2).is_visible()
    finally:
        page.close()
