#!/usr/bin/env python3
"""Side by side: whole `render` commands of two bentstraw builds, interleaved.

usage: render_side_by_side.py BENTSTRAW OLD_BENTSTRAW [--rounds 5] [--size 1024x768]

For each mode (fresnel, course), thread count (1, 2: RAYON_NUM_THREADS) and reference view, runs
`render` with each build ROUNDS times, alternating which goes first, and keeps each build's best
wall time; prints the speed ratio A/B (above 1: A is faster) per view and its geometric mean. The
whole command is timed, as a user waits for it: the picture, its anti-aliasing and the PNG file.
"""
import argparse
import math
import os
import subprocess
import tempfile
import time

REFERENCES = [("0,0.1,0.1", "0.02,0.01", "0.15"), ("0.1,0,0.1", "0.02,0.01", "0.15"),
              ("0.1,0,0.3", "0.02,0.01", "0.2"), ("0.1,0,-0.1", "0,0", "0.2")]


def seconds(binary, ref, mode, threads, size, out):
    observer, straw, water = ref
    env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
    start = time.perf_counter()
    subprocess.run([binary, "render", "--observer", observer, "--straw", straw, "--water-height", water,
                    "--mode", mode, "--size", size, "--output", out],
                   check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("a", help="the bentstraw binary measured (A)")
    p.add_argument("b", help="the bentstraw binary it is compared with (B)")
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--size", default="1024x768")
    args = p.parse_args()
    out = os.path.join(tempfile.mkdtemp(), "view.png")
    print("mode     threads  A/B per reference view      geometric mean")
    for mode in ["fresnel", "course"]:
        for threads in [1, 2]:
            ratios = []
            for ref in REFERENCES:
                best = {args.a: math.inf, args.b: math.inf}
                for r in range(args.rounds):
                    for binary in ([args.a, args.b] if r % 2 == 0 else [args.b, args.a]):
                        best[binary] = min(best[binary], seconds(binary, ref, mode, threads, args.size, out))
                ratios.append(best[args.b] / best[args.a])
            mean = math.exp(sum(map(math.log, ratios)) / len(ratios))
            print(f"{mode:8} {threads:7}  {' '.join(f'{x:.2f}' for x in ratios):26}  {mean:.2f}")


if __name__ == "__main__":
    main()
