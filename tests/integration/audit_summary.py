"""Run issue 17's audit (``test_audit.py``) and print ``category | cases | clean``.

Usage::

    python tests/integration/audit_summary.py [pytest options]

A case is clean when it passed; a skipped case (a check owned by another branch) is
counted in ``skipped`` and not as clean. The exit code is pytest's.
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

    def __init__(self) -> None:
        self.outcomes: dict[str, dict[str, str]] = defaultdict(dict)

    def pytest_runtest_logreport(self, report: Any) -> None:
        if "[" not in report.nodeid or "test_audit.py" not in report.nodeid:
            return
        category, _, name = report.nodeid.split("[", 1)[1].rstrip("]").partition("/")
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
    return int(
        pytest.main(
            [str(HERE / "test_audit.py"), "-q", "-p", "no:cacheprovider", *argv],
            plugins=[AuditSummary()],
        )
    )


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
