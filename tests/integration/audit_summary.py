"""Run an audit's cases and print ``category | cases | clean``.

Usage::

    python tests/integration/audit_summary.py [pytest options]            # issue 17
    python tests/integration/audit_summary.py --marked [pytest options]   # issue 26

Issue 17's audit is ``test_audit.py`` (ids ``category/name``). Issue 26's audit (safe rig,
safe files, locked monitor) is every test of ``tests/`` marked
``@pytest.mark.audit("category")``, wherever it lives: the tests that do the checking are
the cases, so a case cannot pass without its check running.

A case is clean when it passed; a skipped case is counted in ``skipped`` and not as
clean. The exit code is pytest's.
"""

from __future__ import annotations

import sys
from collections import defaultdict
from pathlib import Path
from typing import Any

import pytest

HERE = Path(__file__).resolve().parent


class AuditSummary:
    """A pytest plugin collecting each audit case's outcome by category."""

    def __init__(self, marked: bool = False) -> None:
        self.outcomes: dict[str, dict[str, str]] = defaultdict(dict)
        self.marked = marked
        self.categories: dict[str, str] = {}  # nodeid -> category (marked audits)

    def pytest_collection_modifyitems(self, items: list[Any]) -> None:
        for item in items:
            marker = item.get_closest_marker("audit")
            if marker is not None and marker.args:
                self.categories[item.nodeid] = str(marker.args[0])

    def _case(self, nodeid: str) -> tuple[str, str] | None:
        if self.marked:
            category = self.categories.get(nodeid)
            return None if category is None else (category, nodeid)
        if "[" not in nodeid or "test_audit.py" not in nodeid:
            return None
        category, _, name = nodeid.split("[", 1)[1].rstrip("]").partition("/")
        return category, name

    def pytest_runtest_logreport(self, report: Any) -> None:
        case = self._case(report.nodeid)
        if case is None:
            return
        category, name = case
        # the call's outcome; a setup error or skip, or a later teardown error, overrides it
        if report.outcome != "passed" or (
            report.when == "call" and name not in self.outcomes[category]
        ):
            self.outcomes[category][name] = report.outcome

    def pytest_terminal_summary(self, terminalreporter: Any) -> None:
        rows = [
            (
                c,
                len(v),
                sum(o == "passed" for o in v.values()),
                sum(o == "skipped" for o in v.values()),
            )
            for c, v in self.outcomes.items()
        ]
        width = max([len("category"), *(len(r[0]) for r in rows)])
        write = terminalreporter.write_line
        write("")
        write(f"{'category':<{width}} | cases | clean | skipped")
        write(f"{'-' * width}-|-------|-------|--------")
        for category, cases, clean, skipped in rows:
            write(f"{category:<{width}} | {cases:5d} | {clean:5d} | {skipped:7d}")
        total = [sum(r[i] for r in rows) for i in (1, 2, 3)]
        write(f"{'total':<{width}} | {total[0]:5d} | {total[1]:5d} | {total[2]:7d}")


def main(argv: list[str]) -> int:
    """Run the audit with the summary plugin; pytest's exit code."""
    if "--marked" in argv:
        argv = [a for a in argv if a != "--marked"]
        paths = [str(HERE.parent), "-m", "audit"]
        plugin = AuditSummary(marked=True)
    else:
        paths = [str(HERE / "test_audit.py")]
        plugin = AuditSummary()
    return int(pytest.main([*paths, "-q", "-p", "no:cacheprovider", *argv], plugins=[plugin]))


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
