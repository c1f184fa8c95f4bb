"""Monitor load: ``python benchmarks/bench_monitor.py [--duration S] [--pairs N] [--browser PATH] [--realtime MODE] [--isolate] [--floor]``.

Alternates unmonitored HiL runs and runs with the browser monitor attached (a WebSocket
client reading every frame, or with ``--browser /usr/bin/chromium`` the real page in
headless chromium) and prints each run's in-deadline share, the client's frame rate and
the median miss rates (:mod:`mrsuspension.monitor.loadtest`). ``--isolate`` moves every
other movable task off the loop's core during each run and the floor (docs/hil.md).
"""

from __future__ import annotations

import argparse

from mrsuspension.monitor.loadtest import measure


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    ap.add_argument("--duration", type=float, default=10.0, help="seconds per run")
    ap.add_argument("--rate", type=float, default=1000.0, help="loop rate [Hz]")
    ap.add_argument("--pairs", type=int, default=3, help="unmonitored/monitored pairs")
    ap.add_argument("--rig", default="simulated", help="simulated | ideal | udp://HOST:PORT")
    ap.add_argument("--browser", default=None, help="chromium executable (attach the page)")
    ap.add_argument("--realtime", default="auto", help="loop scheduling: auto | fifo | spin | off")
    ap.add_argument(
        "--isolate",
        action="store_true",
        help="move every other movable task off the loop's core during each run (and the floor)",
    )
    ap.add_argument(
        "--floor",
        action="store_true",
        help="first measure the machine's floor (mrsus hil latency, same rate, mode, duration)",
    )
    args = ap.parse_args()
    if args.floor:
        from mrsuspension.hil.latency import measure_latency

        floor = measure_latency(
            args.rate, args.duration, args.realtime, process=True, isolate=args.isolate
        )
        print(f"    floor: {floor.summary()}")
    d = measure(
        args.duration, args.rate, args.rig, args.pairs, args.browser, realtime=args.realtime,
        isolate=args.isolate,
    )  # fmt: skip
    for kind in ("plain", "monitored"):
        for r in d[kind]:
            rate = f", frames {r['frame_rate']:.1f} Hz" if "frame_rate" in r else ""
            print(f"{kind:>9}: {100 * r['in_deadline']:.2f} % in deadline ({r['misses']} misses "
                  f"in {r['ticks']} ticks){rate}")  # fmt: skip
    print(
        f"median miss rate: unmonitored {100 * d['miss_plain']:.2f} %, monitored "
        f"{100 * d['miss_monitored']:.2f} % ({d['client']} client, realtime "
        f"{d['realtime']}{', isolated' if d['isolate'] else ''}); load average "
        f"{d['loadavg'][0]:.2f} -> {d['loadavg'][1]:.2f}"
    )


if __name__ == "__main__":
    main()
