"""``python -m mrsuspension.report.findings``: evaluate the scorecard and print it.

Options: ``--full`` (the full report's 0.1 ms step), ``--depends-on road|sar`` (only the
claims that depend on the road presets or the SAR denominator), ``--id PREFIX`` (claims
whose id starts with it), ``--csv PATH`` (write the rows), ``--not-held`` (print only the
claims that do not hold), ``--sweep`` (check the chosen claims known not to hold over the
admissible range of the control unknowns their runs involve, ``claims.common._swept``:
the sensitivity check the full build runs for ``findings.SWEPT_IN_FULL`` and that no
build runs for the road claims).
"""

from __future__ import annotations

import argparse
from dataclasses import replace
from pathlib import Path

from mrsuspension.report.findings import CLAIMS, evaluate, write_csv
from mrsuspension.report.findings.claims.common import _swept


def main(argv: list[str] | None = None) -> int:
    """Evaluate (a selection of) the claims and print the table; returns 0."""
    parser = argparse.ArgumentParser(prog="python -m mrsuspension.report.findings")
    parser.add_argument("--full", action="store_true", help="0.1 ms step (default: quick)")
    parser.add_argument("--depends-on", choices=("road", "sar"), default=None)
    parser.add_argument("--id", default="", help="only claims whose id starts with this")
    parser.add_argument("--csv", type=Path, default=None, help="write the rows to this file")
    parser.add_argument("--not-held", action="store_true", help="print only failing claims")
    parser.add_argument(
        "--sweep",
        action="store_true",
        help="the claims known not to hold, over the ADFG centre and beta",
    )
    args = parser.parse_args(argv)
    chosen = [
        c
        for c in CLAIMS
        if c.id.startswith(args.id) and (args.depends_on is None or args.depends_on in c.depends_on)
    ]
    if args.sweep:
        chosen = [replace(c, check=_swept(c.check)) for c in chosen if c.known]
    card = evaluate(quick=not args.full, claims=chosen, workers=None)
    if args.not_held:
        card.results = [r for r in card.results if not r.holds]
    print(card.text())
    print(card.timing())
    if args.csv is not None:
        write_csv(card, args.csv)
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
