#!/usr/bin/env python3
"""References for Kapitza's pendulum where the full model cannot be resolved (issue 27):
tests/fixtures/reference/kapitza_small_eps.toml, for eps = 1e-7, 1e-8, 1e-9 on the three starts
of tests/fixtures/reference/kapitza.toml (whose Taylor-series references stop at 1e-6: below, a
resolved run takes 1e8 steps and more).

Here the third-order averaged equation  Theta'' = F0 + eps^2 F2 + eps^4 F4  and its lift to
(theta, theta') (scripts/kapitza_averaged3.py's exact series: its model error is O(eps^6),
about (eps (b^2 + |a| + 1))^6 < 1e-36 here) are evaluated in 30-digit arithmetic by mpmath: the
averaged start by solving the lift at t = 0 (findroot), the slow motion by mpmath's Taylor-series
ODE solver, and the fast phase t/eps exactly. This shares the derivation with the crate's
`averaged3` (checked against the Taylor-series references at eps = 1e-2, where its error is
1e-10 … 8e-9 and `averaged2`'s 1e-7 … 3e-6, so a wrong term would show), and no code or
arithmetic: the crate integrates in double precision with DOP853 and rounds the phase.
`accuracy` is the largest difference of the samples from a second evaluation at 40 digits.

Run (needs python3 with mpmath; about four minutes):
    python3 scripts/kapitza_small_eps_references.py > tests/fixtures/reference/kapitza_small_eps.toml
"""
import os
import sys

import mpmath as mp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from kapitza_averaged3 import D, derive  # noqa: E402

CASES = [
    ("upright", 1.0, 2.0, 0.3, 0.0),
    ("falls", 1.0, 1.2, 0.3, 0.0),
    ("hanging", 1.0, 2.0, 2.5, 0.5),
]
EPSILONS = [1e-7, 1e-8, 1e-9]
T_END = 5.0
SAMPLES = 20

F, XI = derive()
THETA_DOT = D({n: XI[n] for n in XI}, {0: F[0], 2: F[2], 4: F[4]}, 5)


def evaluate(poly, a, b, st, ct, p, z):
    total = mp.mpc(0)
    for (i, j, pp, q, r, k), (re, im) in poly.items():
        c = mp.mpc(mp.mpf(re.numerator) / re.denominator, mp.mpf(im.numerator) / im.denominator)
        total += c * st**i * ct**j * p**pp * a**q * b**r * z**k
    return total.real


def series(polys, eps, *args):
    return sum(eps**n * evaluate(poly, *args) for n, poly in polys.items())


def case(a, b, eps, theta0, theta_dot0, dps):
    with mp.workdps(dps):
        a, b, eps = mp.mpf(a), mp.mpf(b), mp.mpf(eps)
        slow_f = {0: F[0], 2: F[2], 4: F[4]}

        def lift(th, p, t):
            z = mp.expjpi(t / eps / mp.pi)  # exp(i t/eps), the phase exact
            st, ct = mp.sin(th), mp.cos(th)
            theta = th + series(XI, eps, a, b, st, ct, p, z)
            theta_dot = p + series(THETA_DOT, eps, a, b, st, ct, p, z)
            return theta, theta_dot

        start = mp.findroot(
            lambda th, p: [x - y for x, y in zip(lift(th, p, mp.mpf(0)), (theta0, theta_dot0))],
            (mp.mpf(theta0), mp.mpf(theta_dot0)))

        def field(t, y):
            st, ct = mp.sin(y[0]), mp.cos(y[0])
            return [y[1], series(slow_f, eps, a, b, st, ct, y[1], mp.mpc(1))]

        solution = mp.odefun(field, 0, [start[0], start[1]])
        out = []
        for i in range(SAMPLES + 1):
            t = mp.mpf(T_END) * i / SAMPLES
            th, p = solution(t)
            out.append(lift(th, p, t))
        return out


def main():
    print("# References for Kapitza's pendulum at eps = 1e-7 … 1e-9 (issue 27):")
    print("# tests/fixtures/reference/kapitza_small_eps.toml, written by")
    print("# scripts/kapitza_small_eps_references.py (see its documentation): the third-order averaged")
    print("# equation and its lift, model error O(eps^6) < 1e-36, evaluated in 30 digits by mpmath.")
    print("# Per case: a, b, epsilon, theta0, theta_dot0, t_end; samples at t = i t_end / 20, i = 0..20.")
    for eps in EPSILONS:
        for name, a, b, th0, thd0 in CASES:
            coarse = case(a, b, eps, th0, thd0, 30)
            fine = case(a, b, eps, th0, thd0, 40)
            accuracy = max(max(abs(x[0] - y[0]), abs(x[1] - y[1])) for x, y in zip(coarse, fine))
            print(f"\n[case.{name}_eps{eps:.0e}]".replace("e-0", "e-"))
            print(f"start = '{name}'")
            for k, v in [("a", a), ("b", b), ("epsilon", eps), ("theta0", th0),
                         ("theta_dot0", thd0), ("t_end", T_END)]:
                print(f"{k} = {v!r}")
            print('source = "averaged3-mpmath-30-digits"')
            print(f"accuracy = {float(accuracy) + 1e-36:.1e}")
            print("theta = [" + ", ".join(repr(float(x[0])) for x in coarse) + "]")
            print("theta_dot = [" + ", ".join(repr(float(x[1])) for x in coarse) + "]")
            print(f"{name} eps {eps:e}: accuracy {float(accuracy):.1e}", file=sys.stderr, flush=True)


if __name__ == "__main__":
    main()
