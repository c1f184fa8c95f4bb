"""Identify the control unknowns the seed does not give, from the dissertation's own numbers.

For one unknown (a controller option of some laws) and a list of values, every run of the
findings scorecard (and of the shock tables and road-DLC figures) that uses one of those
laws is re-run with the value; the script prints, per value, the scorecard counts, the
claims whose verdict differs from the first value's, the shock-table agreement (share of
cells within 25 %, DTR within 0.05), the road DLCs against the dissertation's, and the
target numbers of the unknown (``--targets``). Evidence for ``docs/errata.md``, "Control
unknowns identified".

Examples (quick settings: 0.5 ms step, 0.25 ms for the inverse laws; ``--full``: 0.1 ms)::

    python tools/identify_unknowns.py --laws sliding-mode --option beta \
        --values 1,1.1,1.25,1.334,1.5,2 --targets sliding
    python tools/identify_unknowns.py --laws skyhook-hilo,policy-ii,policy-iii,policy-iv,\
inverse-hilo,sliding-mode --option adfg_centre --values 1,0.5,0 --targets adfg
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from mrsuspension.report.families import merge_tables, shock_table
from mrsuspension.report.findings import CLAIMS, evaluate
from mrsuspension.report.findings.checks import (
    Check,
    Claim,
    Run,
    fig,
    run_history,
    run_key,
    table,
)


def _changed(run: Run, laws: Sequence[str], overrides: Mapping[str, Any]) -> Run:
    if run.scenario.get("controller", {}).get("law") not in laws:
        return run
    return Run.of(run.kind, merge_tables(run.scenario, overrides))


def retabled_claims(
    claims: Sequence[Claim], laws: Sequence[str], overrides: Mapping[str, Any]
) -> list[Claim]:
    """The claims with every run of ``laws`` changed by ``overrides`` (same labels)."""
    from dataclasses import replace

    out = []
    for c in claims:
        runs = {k: _changed(r, laws, overrides) for k, r in c.check.runs.items()}
        out.append(replace(c, check=Check(runs, c.check.fn)))
    return out


def shock_agreement(
    laws: Sequence[str], overrides: Mapping[str, Any], quick: bool
) -> tuple[int, int]:
    """Cells within 25 % (DTR within 0.05) over Tables 4.1-6.3, and all cells."""
    from mrsuspension.report import ch4, ch5, ch6

    within = cells = 0
    for t in (*ch4.TABLES, *ch5.TABLES, *ch6.TABLES):
        payloads = {
            v: run_key(_changed(table(t.number, v), laws, overrides).key(quick)) for v in t.variants
        }
        for s in shock_table(t, payloads, quick)["summary"].values():
            within += s["within"]
            cells += s["cells"]
    return within, cells


def road_dlcs(
    laws: Sequence[str], overrides: Mapping[str, Any], quick: bool
) -> list[tuple[str, float, float]]:
    """(figure and variant, model DLC, dissertation DLC) of every road figure with one."""
    from mrsuspension.report import ch4, ch5, ch6

    out = []
    for spec in (*ch4.FIGURES, *ch5.FIGURES, *ch6.FIGURES):
        for label, given in getattr(spec, "given", {}).items():
            if spec.kind != "psd":
                continue
            p = run_key(_changed(fig(spec.number, label), laws, overrides).key(quick))
            out.append((f"{spec.number} {label}", float(p["DLC"]), float(given)))
    return out


def _history(number: str, label: str, quick: bool, controller: Mapping[str, Any]) -> Any:
    run = fig(number, label, kind="history", controller=dict(controller))
    return run_history(run.unit(quick))


def _phase_peaks(p: Mapping[str, Any]) -> tuple[float, float, float]:
    i, v = np.asarray(p["i_d"]), np.asarray(p["v_r"])
    return float(i[v > 0].max()), float(i[v < 0].max()), float(i.mean())


def targets(kind: str, option: str, value: Any, quick: bool) -> dict[str, float]:
    """The dissertation-reported numbers the unknown is identified from (our values)."""
    c = {option: value}
    out: dict[str, float] = {}
    if kind == "sliding":
        comp, reb, mean = _phase_peaks(_history("6.7", "sliding mode ACM", quick, c))
        out |= {"6.7 comp peak [A] (<0.06)": comp, "6.7 rebound peak [A] (~0.15)": reb}
        scm = _history("6.3", "sliding mode SCM", quick, c)
        acm = _history("6.4", "sliding mode ACM", quick, c)
        out["6.4/6.3 mean i ratio (~0.5)"] = float(np.mean(acm["i_d"]) / np.mean(scm["i_d"]))
        pulse = run_key(fig("6.9", "sliding mode ACM", controller=c).key(quick))  # time above 0.1 A
        t, i = np.asarray(pulse["time"]), np.asarray(pulse["i_d"])
        out["6.9 time above 0.1 A [s] (short)"] = float(np.sum(i > 0.1) * (t[1] - t[0]))
    elif kind == "adfg":
        for number, label, given in (
            ("4.6", "ACM", "4.6 (skyhook)"),
            ("5.4", "ACM", "5.4 (inverse k_d=1)"),
            ("5.8", "inverse-model hi-lo ACM", "5.8 (inverse k_d=2.5)"),
            ("6.7", "sliding mode ACM", "6.7 (sliding)"),
        ):
            comp, reb, mean = _phase_peaks(_history(number, label, quick, c))
            out[f"{given} comp peak [A]"] = comp
            out[f"{given} rebound peak [A]"] = reb
            out[f"{given} mean [A]"] = mean
        for number, scm, acm in (
            ("4.6", "SCM", "ACM"),
            ("5.4", "SCM", "ACM"),
        ):
            a = _history(number, acm, quick, c)
            s = _history(number, scm, quick, c)
            out[f"{number} ACM/SCM mean i (~0.5)"] = float(np.mean(a["i_d"]) / np.mean(s["i_d"]))
        for number, given in (("4.6", "2.4"), ("5.4", "2.5")):
            p = run_key(fig(number, "ACM", controller=c).key(quick))
            out[f"{number} ACM gamma (~{given})"] = float(p["gamma"])
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--laws", required=True, help="comma-separated law names")
    ap.add_argument("--option", required=True, help="controller option")
    ap.add_argument("--values", required=True, help="comma-separated values (JSON each)")
    ap.add_argument("--targets", default="", choices=("", "sliding", "adfg"))
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--no-tables", action="store_true")
    args = ap.parse_args(argv)
    laws = args.laws.split(",")
    quick = not args.full
    first: dict[str, str] | None = None
    for raw in args.values.split(","):
        value = json.loads(raw)
        over = {"controller": {args.option: value}}
        card = evaluate(quick, claims=retabled_claims(CLAIMS, laws, over), workers=None)
        status = {r.claim.id: r.status for r in card.results}
        counts = card.counts()
        print(f"== {args.option} = {value}: " + ", ".join(f"{k} {v}" for k, v in counts.items()))
        if first is None:
            first = status
        else:
            for k, s in status.items():
                if s != first[k]:
                    print(f"   {k}: {first[k]} -> {s}")
        if not args.no_tables:
            w, n = shock_agreement(laws, over, quick)
            print(f"   shock tables: {w}/{n} cells within 25 % ({100 * w / n:.1f} %)")
            dl = road_dlcs(laws, over, quick)
            worst = max(abs(m / g - 1) for _, m, g in dl)
            print(
                "   road DLC model/dissertation: "
                + ", ".join(f"{k} {m / g:.2f}" for k, m, g in dl)
                + f" (worst {100 * worst:.0f} %)"
            )
        if args.targets:
            for k, v in targets(args.targets, args.option, value, quick).items():
                print(f"   {k}: {v:.3f}")
        sys.stdout.flush()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
