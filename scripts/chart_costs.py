#!/usr/bin/env python3
"""Every chart's cost model against its time (issue 66): `study map` on every shipped preset at
three horizons (the preset's window, 10x and 100x), `predicted_seconds` beside `wall_seconds`
from the same JSON. Prints a table and the largest ratios; exits 1 when a chart's prediction is
off by more than 2x either way (charts under 50 ms of work are listed but not judged: their time
is the thread pool's start more than their cells').

A benchmark, not a test: run it on a quiet machine.
    cargo build --release && python3 scripts/chart_costs.py [path/to/rattleback [NAME-PART]]

The grids: 200x100 (the default) for the rattleback's limit map and the pendulum's chart, 16x8 (at its window) and 8x4 for
the celt's (each cell integrates the whole window: the default 200x100 at 100x the window is
hours), and the rattleback's full model at k = 1e4 on 8x4 at 1x, 3x and 10x its window.
"""
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
B = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "target", "release", "rattleback")
ONLY = sys.argv[2] if len(sys.argv) > 2 else ""
JUDGED_ABOVE = 0.05


def presets():
    out = subprocess.run([B, "presets", "--format", "json"], check=True, capture_output=True, text=True)
    return [(p["name"], p["model"]) for p in json.loads(out.stdout)["presets"] if p.get("source") == "shipped"]


def t_end_of(name):
    # The preset's own window, from its file.
    for line in open(os.path.join(ROOT, "presets", name + ".toml")):
        if line.strip().startswith("t_end"):
            return float(line.split("=")[1])
    raise SystemExit("no t_end in " + name)


def chart(args):
    p = subprocess.run([B, "study", "map", "--format", "json", "--force"] + args, capture_output=True, text=True)
    if p.returncode != 0:
        return None, p.stderr.strip()
    d = json.loads(p.stdout)
    return (d["predicted_seconds"], d["wall_seconds"], len(d["cells"])), ""


def main():
    rows, worst, bad = [], [], 0
    jobs = []
    for name, model in presets():
        if ONLY not in name:
            continue
        t = t_end_of(name)
        for f in (1, 10, 100):
            grid = ("16x8" if f == 1 else "8x4") if model == "celt" else "200x100"
            jobs.append((name, ["--preset", name, "--grid", grid, "--t-end", repr(t * f)], t * f))
        if name == "subcritical":
            for f in (1, 3, 10):
                jobs.append((name + " (full, k 1e4)", ["--preset", name, "--grid", "8x4", "--k", "1e4", "--t-end", repr(t * f)], t * f))
    print("%-34s %9s %6s %10s %10s %7s" % ("chart", "T", "cells", "predicted", "wall", "ratio"))
    for name, args, t in jobs:
        r, err = chart(args)
        if r is None:
            print("%-34s %9g refused: %s" % (name, t, err[:80]))
            continue
        pred, wall, cells = r
        ratio = wall / pred if pred > 0 else float("inf")
        judged = max(pred, wall) >= JUDGED_ABOVE
        mark = "" if not judged else ("" if 0.5 <= ratio <= 2.0 else "  <- off")
        bad += bool(mark)
        if judged:
            worst.append((ratio, name, t))
        print("%-34s %9g %6d %10.3g %10.3g %7.2f%s" % (name, t, cells, pred, wall, ratio, mark))
    worst.sort()
    if worst:
        print("judged: %d; wall/predicted from %.2f (%s, T %g) to %.2f (%s, T %g)"
              % (len(worst), worst[0][0], worst[0][1], worst[0][2], worst[-1][0], worst[-1][1], worst[-1][2]))
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
