#!/usr/bin/env python3
"""Wall time of `simulate` (whole process, best of 5) for two builds, on the shipped rattleback
presets and a start at k = 1e8 (docs/benchmarks.md, "Issue 29"):

    python3 scripts/cost_compare.py OLD/rattleback NEW/rattleback
"""
import subprocess
import sys
import time

OLD, NEW = sys.argv[1], sys.argv[2]
RUNS = [["--preset", p] for p in ("subcritical", "supercritical", "just-below", "just-above",
                                   "stiff-spring", "soft-spring", "tapping", "iy-greater",
                                   "tilted-start")]
RUNS.append(["--preset", "subcritical", "--set", "spring.k=1e8", "--set", "initial.alpha_dot=0.1"])


def best(binary, args):
    t_best = float("inf")
    for _ in range(5):
        t = time.perf_counter()
        subprocess.run([binary, "simulate", "--format", "json"] + args, capture_output=True,
                       check=True)
        t_best = min(t_best, time.perf_counter() - t)
    return t_best


for args in RUNS:
    o, n = best(OLD, args), best(NEW, args)
    print("%-62s old %6.1f ms  new %6.1f ms  ratio %.2f" % (" ".join(args), o * 1e3, n * 1e3, n / o))
