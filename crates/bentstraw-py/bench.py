"""A million image points from Python and from the command line, side by side in one run.

    python crates/bentstraw-py/bench.py [POINTS] [ROUNDS]

Each round runs `bentstraw simulate` (its own tracing time, as it reports it, and its whole
run, CSV written) and `bentstraw.simulate` (the call, numpy arrays out), alternately, and prints
the medians and the ratio Python / command line. Then the memory each needs per point: the
peak resident memory of a fresh process for POINTS points less that for a hundredth of them,
over the difference in points. The command line is $BENTSTRAW (default: the workspace's release
build).
"""

import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import bentstraw

ROOT = Path(__file__).resolve().parents[2]
BENTSTRAW = os.environ.get("BENTSTRAW", str(ROOT / "target" / "release" / "bentstraw"))
POINTS = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
ROUNDS = int(sys.argv[2]) if len(sys.argv) > 2 else 5
REF2 = dict(observer=(0.1, 0, 0.1), straw=(0.02, 0.01), water_height=0.15)
FLAGS = ["--observer", "0.1,0,0.1", "--straw", "0.02,0.01", "--water-height", "0.15"]

cli_tracing, cli_total, python = [], [], []
with tempfile.TemporaryDirectory() as tmp:
    for _ in range(ROUNDS):
        started = time.perf_counter()
        p = subprocess.run(
            [BENTSTRAW, "simulate", *FLAGS, "--points", str(POINTS), "--output", f"{tmp}/points.csv"],
            capture_output=True, text=True, check=True,
        )
        cli_total.append(time.perf_counter() - started)
        cli_tracing.append(float(re.search(r"time\s+([0-9.]+) s tracing", p.stderr).group(1)))
        started = time.perf_counter()
        sim = bentstraw.simulate(**REF2, points=POINTS)
        python.append(time.perf_counter() - started)

m = statistics.median
print(f"{len(sim)} image points, {ROUNDS} rounds, medians:")
print(f"  command line, tracing         {m(cli_tracing):.3f} s")
print(f"  command line, whole run (CSV) {m(cli_total):.3f} s")
print(f"  Python, bentstraw.simulate    {m(python):.3f} s")
print(f"  ratio Python / command line's tracing: {m(python) / m(cli_tracing):.2f}")


def peak(cmd):
    """The peak resident memory (bytes) of `cmd` and what it wrote (stdout and stderr)."""
    code = ("import resource, subprocess, sys\n"
            "p = subprocess.run(sys.argv[1:], capture_output=True, text=True)\n"
            "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n"
            "print(p.stdout + p.stderr)")
    out = subprocess.run([sys.executable, "-S", "-c", code, *cmd], capture_output=True, text=True,
                         check=True).stdout
    kb, _, said = out.partition("\n")
    # ru_maxrss is in kilobytes on Linux.
    return int(kb) * 1024, said


def memory(points):
    """Peak resident memory (bytes) and points made, command line and Python, for `points`."""
    with tempfile.TemporaryDirectory() as tmp:
        cli, said = peak([BENTSTRAW, "simulate", *FLAGS, "--points", str(points), "--output",
                          f"{tmp}/points.csv"])
        made = int(re.search(r"image points\s+(\d+)", said).group(1))
    code = f"import bentstraw; sim = bentstraw.simulate(**{REF2!r}, points={points}); print(len(sim))"
    py, said = peak([sys.executable, "-c", code])
    return (cli, made), (py, int(said.split()[0]))


if sys.platform.startswith("linux"):
    (c_small, c_n0), (p_small, p_n0) = memory(POINTS // 100)
    (c_big, c_n1), (p_big, p_n1) = memory(POINTS)
    print("memory per image point (peak resident memory):")
    print(f"  command line  {(c_big - c_small) / (c_n1 - c_n0):.0f} bytes")
    print(f"  Python        {(p_big - p_small) / (p_n1 - p_n0):.0f} bytes")
