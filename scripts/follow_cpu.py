#!/usr/bin/env python3
"""CPU of every `rattleback follow` process over a window (issue 14, docs/benchmarks.md).

Usage: start a lecturer (`rattleback --record /tmp/lect/l.jsonl` in tmux) and N followers
(`rattleback follow /tmp/lect/l.jsonl`, one tmux window each), then
`python3 scripts/follow_cpu.py SECONDS`. Reads utime + stime from /proc/PID/stat before and
after; prints the mean and the largest share of one core per follower.
"""
import os
import subprocess
import sys
import time

pids = [int(p) for p in subprocess.check_output(["pgrep", "-f", "rattleback follow"]).split()]
tck = os.sysconf(os.sysconf_names["SC_CLK_TCK"])


def cpu(pid):
    fields = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
    return int(fields[11]) + int(fields[12])


before = {p: cpu(p) for p in pids}
t0 = time.time()
time.sleep(float(sys.argv[1]) if len(sys.argv) > 1 else 10.0)
after = {p: cpu(p) for p in pids}
dt = time.time() - t0
use = [(after[p] - before[p]) / tck / dt * 100 for p in pids]
print(f"{len(pids)} followers over {dt:.1f} s: mean {sum(use) / len(use):.2f} % "
      f"max {max(use):.2f} % CPU each")
