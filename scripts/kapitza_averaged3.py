#!/usr/bin/env python3
"""The third-order averaged model of Kapitza's pendulum (`averaged3`,
src/physics/kapitza/averaged3.rs), derived and printed as the Rust code of
src/physics/kapitza/averaged3_terms.rs.

The expansion is scripts/kapitza_averaged.py's, carried two orders further:

    theta'' = (a + (b/eps) cos tau) sin theta,   tau = t/eps
    theta   = Theta + sum_n eps^n xi_n(Theta, P, tau)   (each xi_n of zero tau-mean)
    Theta'' = sum_m eps^m F_m(Theta, P),                P = Theta'

At each power eps^m the tau-mean of the residual fixes F_m and the rest fixes
d^2 xi_{m+2} / d tau^2. This script does it with F_0 … F_4 and xi_1 … xi_6, so the slow motion
lifted back is within O(eps^6) of the full one (averaged2: O(eps^4)).

sympy's `expand` on the nested trigonometric series takes hours at this order, so the algebra
here is exact and its own: a term is a monomial sin^i(Theta) cos^j(Theta) P^p a^q b^r z^k
(z = exp(i tau), i in {0, 1} after sin^2 = 1 - cos^2) with a Gaussian-rational coefficient
(Python's Fraction), and d/dTheta, d/dP, d/dtau, the tau-mean and the zero-mean double
antiderivative act on those terms directly. The check: the first orders equal
kapitza_averaged.py's (F_2 printed in src/physics/kapitza/averaged.rs) and F_1 = F_3 = 0.

Prints the Rust module on stdout (sympy only turns the finished polynomials into code, with
common subexpressions). Needs python3 with sympy; about a minute.
Run: PYTHONHASHSEED=0 python3 scripts/kapitza_averaged3.py > src/physics/kapitza/averaged3_terms.rs
"""
import os
import sys
import time
from fractions import Fraction

M = 4  # F_0 … F_M, xi_1 … xi_{M+2}
ZERO = (Fraction(0), Fraction(0))


def log(msg):
    print(msg, file=sys.stderr, flush=True)


# ---- Gaussian rationals
def cadd(x, y):
    return (x[0] + y[0], x[1] + y[1])


def cmul(x, y):
    return (x[0] * y[0] - x[1] * y[1], x[0] * y[1] + x[1] * y[0])


def real(r):
    return (Fraction(r), Fraction(0))


# ---- polynomials: {(i, j, p, q, r, k): coefficient}, i = power of sin, j of cos, p of P,
# q of a, r of b, k of z
def add_term(out, key, c):
    if c[0] == 0 and c[1] == 0:
        return
    i, j, p, q, r, k = key
    if i >= 2:  # sin^i = sin^(i-2) (1 - cos^2)
        add_term(out, (i - 2, j, p, q, r, k), c)
        add_term(out, (i - 2, j + 2, p, q, r, k), (-c[0], -c[1]))
        return
    old = out.get(key)
    if old is None:
        out[key] = c
    else:
        s = cadd(old, c)
        if s[0] == 0 and s[1] == 0:
            del out[key]
        else:
            out[key] = s


def padd(*polys):
    out = {}
    for poly in polys:
        for key, c in poly.items():
            add_term(out, key, c)
    return out


def pscale(poly, c):
    out = {}
    for key, v in poly.items():
        add_term(out, key, cmul(v, c))
    return out


def pmul(x, y):
    out = {}
    for (i1, j1, p1, q1, r1, k1), c1 in x.items():
        for (i2, j2, p2, q2, r2, k2), c2 in y.items():
            add_term(out, (i1 + i2, j1 + j2, p1 + p2, q1 + q2, r1 + r2, k1 + k2), cmul(c1, c2))
    return out


def d_theta(poly):
    out = {}
    for (i, j, p, q, r, k), c in poly.items():
        if i == 1:  # d(s c^j) = c^(j+1) - j s^2 c^(j-1)
            add_term(out, (0, j + 1, p, q, r, k), c)
            if j:
                add_term(out, (2, j - 1, p, q, r, k), cmul(c, real(-j)))
        elif j:  # d(c^j) = -j s c^(j-1)
            add_term(out, (1, j - 1, p, q, r, k), cmul(c, real(-j)))
    return out


def d_p(poly):
    out = {}
    for (i, j, p, q, r, k), c in poly.items():
        if p:
            add_term(out, (i, j, p - 1, q, r, k), cmul(c, real(p)))
    return out


def d_tau(poly):  # z^k -> i k z^k
    out = {}
    for (i, j, p, q, r, k), c in poly.items():
        if k:
            add_term(out, (i, j, p, q, r, k), cmul(c, (Fraction(0), Fraction(k))))
    return out


def mean(poly):
    return {key: c for key, c in poly.items() if key[5] == 0}


def oscillating(poly):
    return {key: c for key, c in poly.items() if key[5] != 0}


def integrate2(poly):  # the zero-mean xi with xi_tautau = poly (poly of zero mean)
    out = {}
    for (i, j, p, q, r, k), c in poly.items():
        assert k != 0
        add_term(out, (i, j, p, q, r, k), cmul(c, real(Fraction(-1, k * k))))
    return out


def mono(i=0, j=0, p=0, q=0, r=0, k=0, c=1):
    return {(i, j, p, q, r, k): real(c)} if c else {}


SIN, COS, PP, A, B = mono(i=1), mono(j=1), mono(p=1), mono(q=1), mono(r=1)
COS_TAU = padd(mono(k=1, c=Fraction(1, 2)), mono(k=-1, c=Fraction(1, 2)))


# ---- series in eps: {power: poly}, truncated above `top`
def sadd(*series):
    out = {}
    for s in series:
        for n, poly in s.items():
            out[n] = padd(out.get(n, {}), poly)
    return {n: v for n, v in out.items() if v}


def smul(x, y, top):
    out = {}
    for n1, p1 in x.items():
        for n2, p2 in y.items():
            if n1 + n2 <= top:
                out[n1 + n2] = padd(out.get(n1 + n2, {}), pmul(p1, p2))
    return {n: v for n, v in out.items() if v}


def sscale(x, c):
    return {n: pscale(v, c) for n, v in x.items()}


def D(g, F, top):
    """The time derivative along the slow flow: P d/dTheta + (sum eps^j F_j) d/dP + eps^-1 d/dtau."""
    out = {}
    for n, gn in g.items():
        if n <= top:
            out[n] = padd(out.get(n, {}), pmul(PP, d_theta(gn)))
        dp = d_p(gn)
        if dp:
            for j, fj in F.items():
                if n + j <= top:
                    out[n + j] = padd(out.get(n + j, {}), pmul(fj, dp))
        if n - 1 <= top:
            out[n - 1] = padd(out.get(n - 1, {}), d_tau(gn))
    return {n: v for n, v in out.items() if v}


def derive():
    xi, F = {}, {}
    t0 = time.time()
    for m in range(-1, M + 1):
        top = m + 1  # the powers of eps needed in sin(theta) (b/eps multiplies it)
        delta = {n: xi[n] for n in xi}
        # sin(Theta + delta) = sin Theta cos delta + cos Theta sin delta, delta = O(eps)
        cos_d, sin_d = {0: mono()}, {}
        power, j = {0: mono()}, 0
        while True:
            j += 1
            power = smul(power, delta, top)
            if not power:
                break
            fact = Fraction(1, 1)
            for t in range(2, j + 1):
                fact *= t
            sign = -1 if (j // 2) % 2 else 1
            term = sscale(power, real(Fraction(sign, 1) / fact))
            if j % 2:
                sin_d = sadd(sin_d, term)
            else:
                cos_d = sadd(cos_d, term)
        sin_theta = sadd(smul({0: SIN}, cos_d, top), smul({0: COS}, sin_d, top))
        rhs = sadd(smul({0: A}, sin_theta, top), smul({-1: pmul(B, COS_TAU)}, sin_theta, m))
        lhs = sadd(dict(F), D(D(delta, F, m + 1), F, m))  # D^2 Theta = D P = sum eps^j F_j
        residual = sadd(lhs, sscale(rhs, real(-1))).get(m, {})
        fm = pscale(mean(residual), real(-1))
        if m == -1:
            assert not fm
        else:
            F[m] = fm
        xi[m + 2] = integrate2(pscale(oscillating(residual), real(-1)))
        log(f"m = {m}: F has {len(fm)} terms, xi_{m + 2} {len(xi[m + 2])} ({time.time() - t0:.1f} s)")
    return F, xi


def main():
    if os.environ.get("PYTHONHASHSEED") != "0":  # sympy's cse output depends on set order
        os.environ["PYTHONHASHSEED"] = "0"
        os.execv(sys.executable, [sys.executable] + sys.argv)
    import sympy as sp

    F, xi = derive()
    assert not F[1] and not F[3], "F_1 and F_3 vanish"
    s, c, p, a, b, eps = sp.symbols("st ct p a b epsilon")
    cs = {k: sp.Symbol(f"c{k}") for k in range(1, M + 3)}
    ss = {k: sp.Symbol(f"s{k}") for k in range(1, M + 3)}

    def to_sympy(poly, harmonics=True):
        """Real form: sum_k c_k z^k -> c_0 + sum_{k>0} 2 (Re c_k cos k tau - Im c_k sin k tau)."""
        out = 0
        for (i, j, pp, q, r, k), (re, im) in poly.items():
            m_ = s**i * c**j * p**pp * a**q * b**r
            if k == 0:
                assert im == 0
                out += sp.Rational(re.numerator, re.denominator) * m_
            elif k > 0:
                assert harmonics
                out += 2 * (sp.Rational(re.numerator, re.denominator) * cs[k]
                            - sp.Rational(im.numerator, im.denominator) * ss[k]) * m_
        return sp.expand(out)

    # F_2 must be averaged2's (src/physics/kapitza/averaged.rs, fn f2).
    f2 = to_sympy(F[2], harmonics=False)
    known = (-sp.Rational(3, 2) * c * s * b**2 * p**2 + 2 * a * c**2 * s * b**2
             - sp.Rational(1, 4) * a * s**3 * b**2 - sp.Rational(25, 32) * s * b**4 * c**3
             + sp.Rational(9, 32) * c * s**3 * b**4)
    assert sp.expand((f2 - known).subs(s**2, 1 - c**2).subs(s**3, s * (1 - c**2))) == 0, "F_2"
    f4 = to_sympy(F[4], harmonics=False)

    # The lift: theta to O(eps^6), theta' = D theta to O(eps^5) inclusive.
    delta = {n: xi[n] for n in range(1, M + 3)}
    theta = {n: v for n, v in delta.items()}
    theta_dot = D(delta, {0: F[0], 2: F[2], 4: F[4]}, M + 1)
    th = sum(eps**n * to_sympy(v) for n, v in theta.items())
    thd = p + sum(eps**n * to_sympy(v) for n, v in theta_dot.items())

    import re

    def fix(code):  # sympy's Rust printer writes integer literals: make them f64
        code = code.replace("_f64", ".0")
        code = re.sub(r"powi\((\d+)\)", r"powi(@\1@)", code)
        code = re.sub(r"(?<![\w.@])(\d+)(?![\w.@])", r"\1.0", code)
        return re.sub(r"@(\d+)@", r"\1", code)

    def rust(exprs, names):
        rep, red = sp.cse([sp.collect(e_, eps) for e_ in exprs], symbols=sp.numbered_symbols("x"))
        lines = [f"    let {v} = {fix(sp.rust_code(x))};" for v, x in rep]
        lines += [f"    let {n} = {fix(sp.rust_code(r))};" for n, r in zip(names, red)]
        return "\n".join(lines)

    harm = "    let [{}] = *harmonics;".format(", ".join(f"(s{k}, c{k})" for k in range(1, M + 3)))
    print(f"""// @generated by scripts/kapitza_averaged3.py: do not edit by hand.
//
// The third-order averaged model of Kapitza's pendulum (src/physics/kapitza/averaged.rs): F_4
// of the averaged equation Theta'' = F_0 + eps^2 F_2 + eps^4 F_4, and the lift of the averaged
// state (Theta, Theta') at the fast phase t/eps to the full (theta, theta'), theta to O(eps^6)
// and theta' to O(eps^5) inclusive.
#![allow(clippy::all, clippy::pedantic, unused_parens)]

/// `F_4(Θ, Θ̇)` of the averaged equation.
#[must_use]
pub(super) fn f4(a: f64, b: f64, st: f64, ct: f64, p: f64) -> f64 {{
{rust([f4], ['f4'])}
    f4
}}

/// `(θ, θ̇)` of the averaged state `(Θ, Θ̇)` (`st`, `ct`: `sin Θ`, `cos Θ`; `p`: `Θ̇`) at the
/// fast phase `τ = t/ε`, given as its harmonics `(sin kτ, cos kτ)`, `k = 1 … {M + 2}`.
#[must_use]
pub(super) fn lift(a: f64, b: f64, epsilon: f64, theta_s: f64, st: f64, ct: f64, p: f64, harmonics: &[(f64, f64); {M + 2}]) -> (f64, f64) {{
{harm}
{rust([th, thd], ['ripple', 'theta_dot'])}
    (theta_s + ripple, theta_dot)
}}""")


if __name__ == "__main__":
    main()
