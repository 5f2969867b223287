#!/usr/bin/env python3
"""Independent references for Kapitza's pendulum (issue 11): tests/fixtures/reference/kapitza.toml.

The full model  theta'' = (a + (b/eps) cos(t/eps)) sin(theta)  is integrated by
scripts/kapitza_taylor.c, a fixed-step Taylor-series method of order 28 in 80-bit long double
(step min(eps, 0.1)/2), which shares no code with the crate. Each case is run twice, the second
time with the step divided by 3; the larger difference of the two over the samples is written
as `accuracy` (1e-18 to 2e-15 for eps >= 1e-3; rounding over the 1e7 steps of eps = 1e-6
leaves up to 2.2e-11), far below any tolerance tested. The parameters reach the C program as
hexadecimal floats, so it integrates exactly the doubles the crate does (issue 27: read as
decimal text, eps was the long double nearest 1e-6, and the fast phase t/eps turned that
relative 4.5e-17 into 2e-10 in theta' at T = 5).

Run (needs python3 and gcc; about 1.5 minutes on 2 cores):
    python3 scripts/kapitza_references.py > tests/fixtures/reference/kapitza.toml
"""
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = [
    # name, a, b, theta0, theta_dot0
    ("upright", 1.0, 2.0, 0.3, 0.0),    # b^2 = 4a: upright stable, the slow motion oscillates about it
    ("falls", 1.0, 1.2, 0.3, 0.0),      # b^2 = 1.44 < 2a: the upright is unstable, it falls
    ("hanging", 1.0, 2.0, 2.5, 0.5),    # a large swing about the hanging position
]
EPSILONS = [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6]
T_END = 5.0
SAMPLES = 20


def run(exe, args):
    # Floats go as hexadecimal: strtold reads them exactly, so the reference integrates the
    # doubles the crate does. (Decimal text made eps the long double nearest 1e-6, not the
    # double: a relative 4.5e-17 that the fast phase t/eps turns into 2e-10 in theta' at T = 5.)
    out = subprocess.run([exe] + [x.hex() if isinstance(x, float) else str(x) for x in args],
                         check=True, capture_output=True, text=True).stdout
    return [tuple(float(v) for v in line.split()) for line in out.splitlines()]


def print_case(name, start, params, coarse, fine):
    """One `[case.NAME]` table: the parameters, the accuracy (the largest difference between the
    run and its refinement `fine`) and the samples of `coarse`; `start` is omitted when None."""
    acc = max(max(abs(x[1] - y[1]), abs(x[2] - y[2])) for x, y in zip(coarse, fine))
    print()
    print("[case.%s]" % name)
    if start is not None:
        print("start = %r" % start)
    for k, v in zip(("a", "b", "epsilon", "theta0", "theta_dot0", "t_end"), params):
        print("%s = %r" % (k, v))
    print('source = "taylor28-long-double"')
    print("accuracy = %.1e" % max(acc, 1e-18))
    print("theta = [%s]" % ", ".join(repr(x[1]) for x in coarse))
    print("theta_dot = [%s]" % ", ".join(repr(x[2]) for x in coarse))


def main():
    tmp = tempfile.mkdtemp()
    exe = os.path.join(tmp, "kapitza_taylor")
    subprocess.run(["gcc", "-O2", "-o", exe, os.path.join(HERE, "kapitza_taylor.c"), "-lm"], check=True)
    jobs = []
    for name, a, b, th, thd in CASES:
        for eps in EPSILONS:
            jobs.append((name, a, b, th, thd, eps))
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        coarse = list(pool.map(lambda j: run(exe, [j[1], j[2], j[5], j[3], j[4], T_END, SAMPLES]), jobs))
        fine = list(pool.map(lambda j: run(exe, [j[1], j[2], j[5], j[3], j[4], T_END, SAMPLES, 3]), jobs))
    print(__doc__.strip().replace("\n", "\n# ").join(["# ", ""]))
    print("# Per case: a, b, epsilon, theta0, theta_dot0, t_end; samples at t = i t_end / %d, i = 0..%d." % (SAMPLES, SAMPLES))
    for (name, a, b, th, thd, eps), c, f in zip(jobs, coarse, fine):
        print_case("%s_eps%s" % (name, ("%.0e" % eps).replace("-0", "-")), name,
                   (a, b, eps, th, thd, T_END), c, f)


if __name__ == "__main__":
    sys.exit(main())
