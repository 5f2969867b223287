#!/usr/bin/env python3
"""Every shipped preset's default chart refined against `--exhaustive` (issue 70): the answer of
each cell (its count of reversals, its stability verdict, or undecided) must be the same, cell
for cell; each computed cell the same bit for bit. Prints, per chart, the cells computed and
both wall times; exits 1 on the first chart whose answers differ.

Also the rattleback's full model (`--k 1e4`) on its default preset at 100x50. The celt's
default charts (200x100, each cell integrating its whole window twice) take about a minute
each, twice: the whole run is about a quarter of an hour on two cores.

A check run by hand and recorded in docs/benchmarks.md ("Issue 70"); CI runs the smaller
comparison of tests/it/refined.rs.
    cargo build --release && python3 scripts/refine_check.py [path/to/rattleback [NAME-PART]]
"""
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
B = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "target", "release", "rattleback")
ONLY = sys.argv[2] if len(sys.argv) > 2 else ""


def presets():
    out = subprocess.run([B, "presets", "--format", "json"], check=True, capture_output=True, text=True)
    return [p["name"] for p in json.loads(out.stdout)["presets"] if p.get("source") == "shipped"]


def chart(args):
    out = subprocess.run([B, "study", "map", "--format", "json", "--force", *args],
                         check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def answer(cell):
    if cell.get("error") or cell.get("decided") is False:
        return None
    if "stable" in cell:
        return ("stable", cell["stable"])
    return ("count", cell["reversals"])


def main():
    charts = [["--preset", name] for name in presets() if ONLY in name]
    if ONLY in "subcritical":
        charts.append(["--preset", "subcritical", "--k", "1e4", "--grid", "100x50"])
    bad = 0
    print(f"{'chart':55} {'cells':>6} {'computed':>8} {'refined s':>9} {'exhaustive s':>12}")
    for args in charts:
        refined = chart(args)
        every = chart([*args, "--exhaustive"])
        r, e = refined["cells"], every["cells"]
        assert len(r) == len(e)
        wrong = [c["index"] for c, x in zip(r, e) if answer(c) != answer(x)]
        changed = [c["index"] for c, x in zip(r, e) if c.get("mark") == "computed" and c != x]
        computed = sum(1 for c in r if c.get("mark") == "computed")
        print(f"{' '.join(args):55} {len(r):6} {computed:8} {refined['wall_seconds']:9.2f} "
              f"{every['wall_seconds']:12.2f}" + (f"  DIFFERENT: {len(wrong)} answers, "
                                                  f"{len(changed)} computed cells" if wrong or changed else ""))
        bad += bool(wrong or changed)
    print("every answer equal to --exhaustive" if not bad else f"{bad} charts differ")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
