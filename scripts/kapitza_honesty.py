#!/usr/bin/env python3
"""Held-out references for the pendulum's `auto` claims (issue 29): tests/fixtures/reference/kapitza_honesty.toml.

Starts of the shapes that broke the claim: a falling start that keeps returning near the unstable
upright over a long horizon (the issue's case: a = 1, b = 1.2, eps = 1e-2, theta0 = 0.1, T = 50),
the same at a finer eps, and long runs of the upright and hanging starts. Integrated by
scripts/kapitza_taylor.c (order-28 Taylor series in 80-bit long double, no code shared with the
crate), twice, the second with the step divided by 3; `accuracy` is their largest difference.

Run (needs python3 and gcc; a few seconds):
    python3 scripts/kapitza_honesty.py > tests/fixtures/reference/kapitza_honesty.toml
"""
import os
import subprocess
import tempfile

from kapitza_references import print_case, run  # the same driver of kapitza_taylor.c

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = [
    # name, a, b, eps, theta0, theta_dot0, t_end
    ("returns_eps1e-2", 1.0, 1.2, 1e-2, 0.1, 0.0, 50.0),
    ("returns_eps1e-3", 1.0, 1.2, 1e-3, 0.1, 0.0, 20.0),
    ("returns_eps3e-2", 1.0, 1.2, 3e-2, 0.1, 0.0, 50.0),
    ("upright_long", 1.0, 2.0, 1e-2, 0.3, 0.0, 50.0),
    ("hanging_long", 1.0, 2.0, 1e-2, 2.5, 0.5, 50.0),
    ("near_threshold", 1.0, 1.45, 1e-2, 0.2, 0.0, 40.0),
]
SAMPLES = 20


def main():
    tmp = tempfile.mkdtemp()
    exe = os.path.join(tmp, "kapitza_taylor")
    subprocess.run(["gcc", "-O2", "-o", exe, os.path.join(HERE, "kapitza_taylor.c"), "-lm"], check=True)
    print(__doc__.strip().replace("\n", "\n# ").join(["# ", ""]))
    print("# Per case: a, b, epsilon, theta0, theta_dot0, t_end; samples at t = i t_end / %d, i = 0..%d." % (SAMPLES, SAMPLES))
    for name, a, b, eps, th, thd, t_end in CASES:
        c = run(exe, [a, b, eps, th, thd, t_end, SAMPLES])
        f = run(exe, [a, b, eps, th, thd, t_end, SAMPLES, 3])
        print_case(name, None, (a, b, eps, th, thd, t_end), c, f)


if __name__ == "__main__":
    main()
