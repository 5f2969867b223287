#!/usr/bin/env python3
"""The third-order averaged model of the holonomic rattleback (`averaged3`,
src/physics/rattleback/averaged3_terms.rs), derived and printed as the Rust code that file holds.

The derivation is the Lie-transform (Deprit) normal form of docs/averaging/second-order.md §3,
whose `--derive` option in docs/averaging/averaging2.py this script extends by two orders:

    K = I w(a) + (P + I c(a) sin 2 phi)^2 / (2 iz),   w = sqrt(k/g),  c = g'/(4g),  w' = -2 c w

with the bookkeeping eps = k^(-1/2), I = eps J, w = Om/eps. The generator W = W2 + ... + W6 and
the averaged Hamiltonian Kbar = Kbar0 + Kbar2 + Kbar4 (Kbar1 = Kbar3 = Kbar5 = 0, checked here)
give a slow model whose error at fixed T is O(eps^6) = O(k^-3) when

  * the slow flow is that of Kbar through eps^4,
  * the maps (physical -> averaged at the start, averaged -> physical at output) are carried
    through eps^5 in alpha, P, p_alpha and the relative action, and through eps^5 in the phase
    (the phase enters alpha-dot through the O(eps) ripple, so eps^4 would do; eps^5 is free).

Prints Kbar_1 ... Kbar_5 as it goes, then the whole Rust module on stdout (diagnostics go to
stderr). Requires python3 with sympy; takes about 20 minutes on one core. The module is
declared `#[rustfmt::skip]`, so the checked-in file is byte for byte what this prints. Run:

    python3 scripts/rattleback_averaged3.py > src/physics/rattleback/averaged3_terms.rs
"""
import os
import re
import sys
import time

# sympy's common-subexpression pass walks sets: a fixed hash seed makes the output byte-identical
# from run to run (the check that the checked-in file is what this script prints).
if os.environ.get("PYTHONHASHSEED") != "0":
    os.environ["PYTHONHASHSEED"] = "0"
    os.execv(sys.executable, [sys.executable] + sys.argv)

import sympy as sp

NMAX = 5  # R_1 ... R_5: Kbar_1 ... Kbar_5 and W_2 ... W_6
NM = 5    # maps through eps^5
T0 = time.time()


def log(*a):
    print("[%6.1fs]" % (time.time() - T0), *a, file=sys.stderr, flush=True)


z, J, a, P, eps, iz = sp.symbols("z J a P epsilon i_z", positive=True)
Om, C = sp.Function("Om")(a), sp.Function("C")(a)
Ii = sp.I
ex = sp.expand
sin2 = (z**2 - z**-2) / (2 * Ii)  # z = exp(i phi)


def d_phi(f):
    return ex(Ii * z * sp.diff(f, z))


def br(f, h):  # {f,h} with I = eps J (so d/dI = d/dJ / eps)
    return ex((d_phi(f) * sp.diff(h, J) - sp.diff(f, J) * d_phi(h)) / eps
              + sp.diff(f, a) * sp.diff(h, P) - sp.diff(f, P) * sp.diff(h, a))


def trunc(f, N):
    f = ex(f)
    return ex(sum(f.coeff(eps, n) * eps**n for n in range(0, N + 1)))


def lie(f, W, N):  # exp(L_W) f through eps^N
    total = term = trunc(f, N)
    for n in range(1, N + 2):
        term = trunc(br(term, W) / n, N)
        if term == 0:
            break
        total += term
    return ex(total)


def zpow(f):
    return sorted({sp.degree(t * z**40, z) - 40 for t in sp.Add.make_args(ex(f)) if t != 0})


def integ(f):  # antiderivative in phi of a zero-mean Laurent polynomial
    f = ex(f)
    return ex(sum(f.coeff(z, m) * z**m / (Ii * m) for m in zpow(f) if m != 0))


K = ex(J * Om + P**2 / (2 * iz) + eps * J * C * P * sin2 / iz
       + eps**2 * J**2 * C**2 * sin2**2 / (2 * iz))
W = 0
Kbar = J * Om + P**2 / (2 * iz)
for n in range(1, NMAX + 1):
    Rn = ex(lie(K, W, n).coeff(eps, n))
    Kb = ex(Rn.coeff(z, 0))
    W = ex(W + eps**(n + 1) * integ(ex(Rn - Kb) / Om))
    Kbar = Kbar + eps**n * Kb
    log("Kbar_%d =" % n, sp.factor(sp.simplify(Kb)))
    if n % 2 == 1:
        assert sp.simplify(Kb) == 0, "odd orders of Kbar vanish (note §3)"

# ---- physical variables: J -> I, Om -> w, eps -> 1, Om' = -2 C Om --------------------------
NC = 7
Iv, w, PP = sp.symbols("i w p")
cs = sp.symbols("c0:%d" % NC)


def om_derivs(n):
    """d^n Om / da^n as (polynomial in C and its derivatives) * Om."""
    f = Om
    out = [Om]
    for _ in range(n):
        f = ex(sp.diff(f, a).subs(sp.Derivative(Om, a), -2 * C * Om))
        out.append(f)
    return out


OMD = om_derivs(NC)


def phys(f):
    f = ex(f)
    for n in range(NC, 0, -1):
        f = f.subs(sp.Derivative(Om, (a, n)), OMD[n])
    for n in range(NC - 1, 0, -1):
        f = f.subs(sp.Derivative(C, (a, n)), cs[n])
    f = f.subs(C, cs[0])
    return ex(f.subs({Om: w, J: Iv, eps: 1, P: PP}))


S = {m: sp.Symbol("s%d" % m) for m in range(1, 16)}
Cc = {m: sp.Symbol("k%d" % m) for m in range(1, 16)}


def real(f):
    """A real Laurent polynomial in z as a sum over cos m phi (k_m) and sin m phi (s_m)."""
    f = ex(f)
    out = 0
    for m in zpow(f):
        if m < 0:
            continue
        if m == 0:
            out += f.coeff(z, 0)
        else:
            ap_, am_ = f.coeff(z, m), f.coeff(z, -m)
            out += ex(ap_ + am_) * Cc[m] + ex(Ii * (ap_ - am_)) * S[m]
    out = ex(out)
    assert not out.has(Ii), "not real"
    return out


# ---- the slow flow -------------------------------------------------------------------------
Kb_phys = phys(Kbar)
dKda = phys(sp.diff(Kbar, a))
dKdP = phys(sp.diff(Kbar, P))
dKdJ = phys(sp.diff(Kbar, J) / eps)  # d/dI = d/dJ / eps
log("slow flow ready")

# ---- the maps ------------------------------------------------------------------------------
W = trunc(W, NM + 1)
maps = {}
for name, sgn in (("fwd", 1), ("inv", -1)):
    Ws = ex(sgn * W)
    funcs = {"alpha": a, "j": J, "p": P}
    if sgn == 1:
        funcs["p_alpha"] = P + eps * J * C * sin2
    out = {}
    for key, f in funcs.items():
        s = lie(f, Ws, NM)
        out[key] = real(phys(trunc(s, NM)))
        log(name, key, "done")
    # phase: phi - phibar = sum_n L_W^n phi / n!, with L_W phi = dW/dI = dW/dJ / eps
    term = first = trunc(sp.diff(Ws, J) / eps, NM)
    total = first
    for n in range(2, NM + 2):
        term = trunc(br(term, Ws) / n, NM)
        total += term
    out["phi"] = real(phys(trunc(total, NM)))
    log(name, "phi done")
    maps[name] = out


# ---- Rust ----------------------------------------------------------------------------------
def fix(code):  # sympy's Rust printer writes integer literals: make them f64 (powi keeps its)
    code = code.replace("_f64", ".0")
    code = re.sub(r"powi\((-?\d+)\)", r"powi(@\1@)", code)
    code = re.sub(r"(?<![\w.@])(\d+)(?![\w.@])", r"\1.0", code)
    return re.sub(r"@(-?\d+)@", r"\1", code)


def rust(exprs, names, indent="    "):
    rep, red = sp.cse(exprs, symbols=sp.numbered_symbols("x"), optimizations="basic")
    lines = ["%slet %s = %s;" % (indent, v, fix(sp.rust_code(x))) for v, x in rep]
    for n_, r in zip(names, red):
        lines.append("%slet %s = %s;" % (indent, n_, fix(sp.rust_code(r))))
    return "\n".join(lines)


def used(exprs):
    syms = set()
    for e_ in exprs:
        syms |= e_.free_symbols
    return syms


log("writing Rust")
flow = [dKdP, ex(-dKda), dKdJ, Kb_phys]
blocks = []
for name, doc in (
    ("inv", "The initial map, physical `(φ, I, α, P)` → averaged: `[Ī, ᾱ − α, P̄, φ̄ − φ]`."),
    ("fwd", "The reconstruction, averaged → physical: `[I, α − ᾱ, p_α, φ − φ̄]`."),
):
    m = maps[name]
    exprs = [m["j"], ex(m["alpha"] - a), m["p"] if name == "inv" else m["p_alpha"], m["phi"]]
    blocks.append((name, doc, [phys(e_) for e_ in exprs]))
# How many of c, c', ... the terms take.
NCU = 1 + max(j for j in range(NC) if any(cs[j] in used(e) for e in [flow] + [b[2] for b in blocks]))


def unpack(syms):
    return "    let [%s] = *c;" % ", ".join(("c%d" % j if cs[j] in syms else "_") for j in range(NCU))


print("""// @generated by scripts/rattleback_averaged3.py: do not edit by hand.
//
// The third-order averaged model's terms (src/physics/rattleback/averaged3.rs): the slow flow of
// Kbar through eps^4 and the two maps through eps^5, in physical variables. `i` is the fast
// action, `p` the slow momentum, `w` the fast frequency, `i_z` the spin inertia and
// `c = [c, c', c'', ...]` the function c = g'/(4g) and its derivatives in alpha, all at the point
// the map or flow is evaluated at.
#![allow(clippy::all, clippy::pedantic, unused_parens)]

/// How many of `c, c', c'', ...` the terms take.
pub(super) const NC: usize = %d;
""" % NCU)

print("/// `K̄` and its flow `(dᾱ/dt, dP̄/dt, dφ̄/dt)` at `(ᾱ, P̄; Ī)`: `[dᾱ/dt, dP̄/dt, dφ̄/dt, K̄]`.")
print("#[inline]")
print("pub(super) fn flow(i: f64, p: f64, w: f64, i_z: f64, c: &[f64; NC]) -> [f64; 4] {")
print(unpack(used(flow)))
print(rust(flow, ["da", "dp", "dphi", "kbar"]))
print("    [da, dp, dphi, kbar]\n}\n")

for name, doc, exprs in blocks:
    syms = used(exprs)
    print("/// " + doc)
    print("#[inline]")
    print("pub(super) fn %s(phase: f64, i: f64, p: f64, w: f64, i_z: f64, c: &[f64; NC]) -> [f64; 4] {"
          % name)
    print(unpack(syms))
    for mm in sorted({mm for mm in S if S[mm] in syms or Cc[mm] in syms}):
        sv = ("s%d" % mm) if S[mm] in syms else "_"
        kv = ("k%d" % mm) if Cc[mm] in syms else "_"
        print("    let (%s, %s) = (%d.0 * phase).sin_cos();" % (sv, kv, mm))
    print(rust(exprs, ["r0", "r1", "r2", "r3"]))
    print("    [r0, r1, r2, r3]\n}\n")
log("done")
