#!/usr/bin/env python3
"""The second-order averaged model of Kapitza's pendulum (`averaged2`,
src/physics/kapitza/averaged.rs), derived and printed as the Rust code that file holds.

    theta'' = (a + (b/eps) cos tau) sin theta,   tau = t/eps
    theta   = Theta + sum_n eps^n xi_n(Theta, P, tau)   (each xi_n of zero tau-mean)
    Theta'' = sum_m eps^m F_m(Theta, P),                P = Theta'

At each power of eps the tau-mean fixes F_m and the rest fixes d^2 xi_{m+2} / d tau^2; the
tau-dependence is kept as Laurent polynomials in z = exp(i tau). Prints F_0 … F_2 as it goes,
then the Rust code of F_2 and of the ripple (theta to O(eps^4), theta' to O(eps^3) inclusive).
Requires python3 with sympy; takes about six minutes. Run: python3 scripts/kapitza_averaged.py
"""
import sympy as sp, sys, time
M = 2  # F0 … F2, ξ1 … ξ4
Th, P, z, e, a, b = sp.symbols('Theta P z epsilon a b')
S, C = sp.sin(Th), sp.cos(Th)
cos_tau = (z + 1/z) / 2

def tau_d(expr):  # ∂/∂τ: z^k -> i k z^k
    return sp.expand(z * sp.diff(expr, z) * sp.I)

def coeffs(expr):
    expr = sp.expand(expr)
    out = {}
    for term in sp.Add.make_args(expr):
        powz = sp.Poly(term * z**40, z).degree() - 40 if term.has(z) else 0
        out[powz] = out.get(powz, 0) + term / z**powz
    return out

def avg(expr):
    return sp.expand(coeffs(expr).get(0, 0))

def integrate2(expr):  # zero-mean solution of ξ_ττ = expr (expr zero-mean)
    out = 0
    for k, c in coeffs(expr).items():
        if k == 0:
            assert sp.expand(c) == 0, c
            continue
        out += -c * z**k / k**2
    return sp.expand(out)

xi = {}
F = {}
t0 = time.time()
for m in range(-1, M + 1):
    N = m + 2  # highest order needed in eps
    theta = Th + sum(e**n * xi[n] for n in xi)
    Fser = sum(e**j * F[j] for j in F)
    def D(g):
        return sp.diff(g, Th) * P + sp.diff(g, P) * Fser + tau_d(g) / e
    # θ'' : D(D(θ)); D(Th) = P, D(P) = F
    lhs = sp.expand(D(D(theta)))
    delta = theta - Th
    # sin(Θ+δ) to order δ^(N+1)
    sd = sum((-1)**j * delta**(2*j+1) / sp.factorial(2*j+1) for j in range((N + 3)//2 + 1))
    cd = sum((-1)**j * delta**(2*j) / sp.factorial(2*j) for j in range((N + 3)//2 + 1))
    sin_theta = S * cd + C * sd
    rhs = sp.expand((a + b / e * cos_tau) * sin_theta)
    R = sp.expand((lhs - rhs) * e).coeff(e, m + 1)   # coefficient of e^m
    Fm = -avg(R)
    F[m] = sp.expand(Fm) if m >= 0 else 0
    if m == -1:
        assert sp.expand(Fm) == 0
        F.pop(-1)
    osc = sp.expand(-(R - coeffs(R).get(0, 0)))
    xi[m + 2] = integrate2(osc)
    print(f"m={m}: F = {F.get(m)}  ({time.time()-t0:.1f}s)", flush=True)


# ---- the Rust code
# From the derived series: Rust code for F2 and the ripple to the order kept.
Th, P, z, e, a, b = sp.symbols('Theta P z epsilon a b')
Fser = F[0] + e**2 * F[2]
theta = Th + sum(e**n * xi[n] for n in range(1, 5))
def D(g): return sp.diff(g, Th)*P + sp.diff(g, P)*Fser + z*sp.diff(g, z)*sp.I/e
theta_dot = sp.expand(D(theta))
theta_dot = sum(theta_dot.coeff(e, k) * e**k for k in range(0, 4))
theta = sum(sp.expand(theta).coeff(e, k) * e**k for k in range(0, 5))
# real form: Σ_k c_k z^k -> c_0 + Σ_{k>0} 2 (Re c_k cos kτ − Im c_k sin kτ)
cs = {k: sp.Symbol(f'c{k}') for k in range(1, 9)}
ss = {k: sp.Symbol(f's{k}') for k in range(1, 9)}
St, Ct = sp.symbols('st ct')
def real(expr):
    out = 0
    for k, c in coeffs(expr).items():
        c = sp.expand(c)
        im = c.coeff(sp.I); re = sp.expand(c - sp.I*im)
        if k == 0:
            assert sp.expand(im) == 0
            out += re
        elif k > 0:
            out += 2*(re*cs[k] - im*ss[k])
    return sp.expand(out)
th_r = real(theta); thd_r = real(theta_dot); F2 = sp.expand(F[2])
for name, ex in [('theta', th_r), ('theta_dot', thd_r)]:
    ks = sorted({int(str(s)[1:]) for s in ex.free_symbols if str(s)[0] in 'cs' and str(s)[1:].isdigit()})
    print(name, 'harmonics', ks)
def rust(exprs, names):
    exprs = [e_.subs({sp.sin(Th): St, sp.cos(Th): Ct}) for e_ in exprs]
    exprs = [sp.expand(sp.expand_trig(e_)) for e_ in exprs]
    exprs = [e_.subs({sp.sin(Th): St, sp.cos(Th): Ct}) for e_ in exprs]
    rep, red = sp.cse([sp.collect(e_, e) for e_ in exprs], symbols=sp.numbered_symbols('x'))
    lines = [f"    let {v} = {sp.rust_code(x)};" for v, x in rep]
    for n, r in zip(names, red):
        lines.append(f"    let {n} = {sp.rust_code(r)};")
    return "\n".join(lines)
print("F2:", F2)
import re
def fix(code):  # sympy's Rust printer writes integer literals: make them f64 (powi keeps its)
    code = code.replace('_f64', '.0')
    code = re.sub(r'powi\((\d+)\)', r'powi(@\1@)', code)
    code = re.sub(r'(?<![\w.@])(\d+)(?![\w.@])', r'\1.0', code)
    code = re.sub(r'@(\d+)@', r'\1', code)
    code = re.sub(r'\bTheta\b', 'theta_s', code)
    return re.sub(r'\bP\b', 'p', code)
print('// f2 (src/physics/kapitza/averaged.rs, fn f2):')
print(fix(rust([F2], ['f2'])))
print('// the ripple (fn to_full):')
print(fix(rust([th_r, thd_r], ['theta', 'theta_dot'])))
