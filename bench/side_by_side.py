#!/usr/bin/env python3
"""Side by side: `bentstraw bench` against another build or Mitsuba 3's course loop, interleaved.

usage: side_by_side.py BENTSTRAW --against OLD_BENTSTRAW|mitsuba [--rounds 3] [--repeat 20]
                       [--threads N]

Runs ROUNDS rounds of (A) `BENTSTRAW bench --json` and (B) the same with OLD_BENTSTRAW (course
and fresnel), or mitsuba_course.py beside this file (course only, run by this same Python, so
start this script with the Python that has mitsuba and drjit), each on 1 and N threads. It keeps
the best rays per second of each per view, mode and thread count, and prints the ratios A/B,
their geometric mean over the four views, and each side's N-thread/1-thread ratio per view.
"""
import argparse
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def run_json(cmd):
    """One JSON object per line from `cmd`; bench's "average" lines are left out."""
    out = subprocess.run(cmd, check=True, stdout=subprocess.PIPE, text=True).stdout
    lines = [json.loads(l) for l in out.splitlines() if l.strip()]
    return [j for j in lines if j["simulation"] != "average"]


def geomean(xs):
    return math.exp(sum(map(math.log, xs)) / len(xs))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog="\n\n".join(__doc__.split("\n\n")[2:]))
    p.add_argument("bentstraw", help="the bentstraw binary measured (A)")
    p.add_argument("--against", required=True, metavar="OLD_BENTSTRAW|mitsuba",
                   help="another bentstraw binary, or `mitsuba` for the reference course loop (B)")
    p.add_argument("--rounds", type=int, default=3, help="interleaved rounds (default 3)")
    p.add_argument("--repeat", type=int, default=20, help="timed pictures per case (median)")
    p.add_argument("--threads", type=int, default=os.cpu_count(),
                   help="the multi-threaded runs' thread count (default: all cores)")
    args = p.parse_args()
    if args.rounds < 1 or args.repeat < 1 or args.threads < 1:
        p.error("--rounds, --repeat and --threads must be at least 1")

    mitsuba = args.against == "mitsuba"
    counts = [1] if args.threads == 1 else [1, args.threads]
    # `bench` times one thread and then --threads itself; Mitsuba's thread count is per process.
    bench = ["bench", "--json", "--threads", str(args.threads), "--repeat", str(args.repeat)]
    if mitsuba:
        bench += ["--mode", "course"]
        script = os.path.join(HERE, "mitsuba_course.py")
        side_b = [[sys.executable, script, "--threads", str(n), "--repeat", str(args.repeat)]
                  for n in counts]
    else:
        side_b = [[args.against] + bench]
    side_a = [[args.bentstraw] + bench]

    best = {}  # (mode, threads, view) -> {"A": rays/s, "B": rays/s}
    for r in range(args.rounds):
        # Alternate which side goes first, so that a drift in the machine's load over a round
        # (other jobs, frequency) does not always fall on the same side.
        order = [("A", side_a), ("B", side_b)]
        for who, cmds in (order if r % 2 == 0 else order[::-1]):
            for cmd in cmds:
                print(f"round {r + 1}/{args.rounds} {who}: {' '.join(cmd)}", file=sys.stderr,
                      flush=True)
                for j in run_json(cmd):
                    cell = best.setdefault((j["mode"], j["threads"], j["simulation"]), {})
                    cell[who] = max(cell.get(who, 0.0), j["rays_per_s"])

    name_b = "mitsuba" if mitsuba else "B"
    what_b = "Mitsuba 3's course loop (mitsuba_course.py)" if mitsuba else args.against
    print(f"A = {args.bentstraw}, {name_b} = {what_b}; best of {args.rounds} rounds, "
          f"median of {args.repeat} pictures each, 1024x768, M rays/s")
    print(f"{'mode':8} {'thr':>3} {'view':>4} {'A':>9} {name_b:>9} {'A/' + name_b:>9}")
    for mode, n in sorted({k[:2] for k in best}):
        ratios = []
        for view in sorted(v for (m, t, v) in best if (m, t) == (mode, n)):
            cell = best[(mode, n, view)]
            if "A" not in cell or "B" not in cell:
                continue
            ratios.append(cell["A"] / cell["B"])
            print(f"{mode:8} {n:>3} {view:>4} {cell['A'] / 1e6:9.1f} {cell['B'] / 1e6:9.1f} "
                  f"{ratios[-1]:9.2f}")
        if ratios:
            print(f"{mode:8} {n:>3} {'geomean A/' + name_b:>24} {geomean(ratios):9.2f}")
    if len(counts) == 2:
        n = counts[1]
        print(f"\n{n} threads / 1 thread, per view")
        print(f"{'mode':8} {'view':>4} {'A':>7} {name_b:>9}")
        for mode, view in sorted({(k[0], k[2]) for k in best}):
            one, many = best.get((mode, 1, view), {}), best.get((mode, n, view), {})
            scal = [f"{many[w] / one[w]:.2f}" if w in one and w in many else "-" for w in "AB"]
            print(f"{mode:8} {view:>4} {scal[0]:>7} {scal[1]:>9}")


if __name__ == "__main__":
    main()
