#!/usr/bin/env python3
"""Held-out references for the honesty of the rattleback's `auto` (issue 29, items 3 and 4).

Writes tests/fixtures/reference/rattleback_honesty.toml, in the format of averaged.toml plus
two numbers per case:
- `uncertainty`: how far the reference itself may be off (the largest change of alpha(T),
  alpha'(T) and the reversal times when the reference is recomputed twice as finely),
- `condition`: how much the start's rounding is amplified, max |d(output)| / |d alpha'0| for a
  relative nudge of alpha'0 by 1e-9 (reversal times included), times |alpha'0|: the factor by
  which a relative error of the start, or an error made early, grows by T.

Starts of the shapes issue 29 names, none of them in averaged.toml:
- near the finite-k separatrix, both sides, two bodies (the critical alpha'0 is found here by
  bisection on whether the full motion reverses within T; condition numbers 1e2 ... 1e5),
- small librations at very large k (alpha'0 = 0.05 ... 0.15, k = 1e6 ... 1e12, T up to 300),
  where the report's averaged half period used to hang.

Nothing here shares code with the Rust crate. The full model is integrated by the averaging
note's fixed-step 8th-order Runge-Kutta in 80-bit long double (docs/averaging/averaging2.py,
`ref_c`, compiled with gcc); beyond k = 1e8 by the note's own implementation of the averaged
model (`model_new`, scipy DOP853 at 2.5e-14), whose model error there is below 1e-18.

Run (python3 with numpy and scipy, and gcc; about 6 minutes on 2 cores):
    python3 scripts/rattleback_honesty.py
"""
import importlib.util
import math
import os

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
NOTE = os.path.join(HERE, "..", "docs", "averaging", "averaging2.py")
spec = importlib.util.spec_from_file_location("averaging2", NOTE)
av = importlib.util.module_from_spec(spec)
spec.loader.exec_module(av)

OUT = os.path.join(HERE, "..", "tests", "fixtures", "reference", "rattleback_honesty.toml")
NUDGE = 1e-9


def full(S, y0, T, nper):
    r = av.ref_c(S, y0, T, nper=nper)
    return np.array([r["y"][1], r["y"][3]]), np.array(r["rev"]), r["nsteps"]


def model(S, y0, T, rtol=None):
    if rtol is not None:
        saved = dict(av.SLOW_OPTS)
        av.SLOW_OPTS.update(rtol=rtol, atol=rtol)
    try:
        m = av.model_new(S, y0, T)
    finally:
        if rtol is not None:
            av.SLOW_OPTS.clear()
            av.SLOW_OPTS.update(saved)
    return np.array([m["a"], m["ad"]]), np.array(m["rev"]), 0


def gap(a, b):
    (ea, ra, _), (eb, rb, _) = a, b
    if len(ra) != len(rb):
        return math.inf
    d = float(np.max(np.abs(ea - eb)))
    if len(ra):
        d = max(d, float(np.max(np.abs(ra - rb))))
    return d


def reverses(S, ad, T):
    """Whether the full motion from (0, 0, 1, ad) reverses its spin within T (coarse)."""
    _, rev, _ = full(S, [0.0, 0.0, 1.0, ad], T, 60)
    return len(rev) > 0


def critical(S, T, lo, hi):
    """The alpha'0 (gamma'0 = 1) between a reversing start `lo` and a rotating one `hi`."""
    assert reverses(S, lo, T) and not reverses(S, hi, T), (lo, hi)
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if reverses(S, mid, T):
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def fl(x):
    return repr(float(x))


def main():
    jobs = []  # (name, (ix, iy, iz), k, start, T, how, shape)
    # Near the separatrix. The critical alpha'0 at each k (bisection over T = 200, so that
    # starts trapped with half periods up to ~100 count as trapped).
    for (body, ks, bracket) in (((2.0, 1.0, 1.0), (1e2, 1e3, 1e4), (0.8, 1.0)),
                                ((80.0, 20.0, 40.0), (1e3, 1e4), (0.3, 3.0))):
        for k in ks:
            S = av.Sys(*body, k)
            ac = critical(S, 200.0, *bracket)
            print("critical alpha'0 at", body, k, "=", ac, flush=True)
            for tag, f in (("in3", 1 - 1e-3), ("in5", 1 - 1e-5), ("out4", 1 + 1e-4)):
                name = "sep_%s_%s_k%s" % ("b1" if body[0] == 2.0 else "b2", tag,
                                          ("%.0e" % k).replace("+", ""))
                jobs.append((name, body, k, [0.0, 0.0, 1.0, ac * f], 60.0, "full",
                             "near the separatrix"))
    # Small librations at very large k.
    for ad in (0.05, 0.15):
        for k in (1e6,):
            jobs.append(("lib_b1_a%03d_k1e06" % int(ad * 100), (2.0, 1.0, 1.0), k,
                         [0.0, 0.0, 1.0, ad], 30.0, "full", "small libration"))
        for k in (1e10, 1e12):
            jobs.append(("lib_b1_a%03d_k%s" % (int(ad * 100), ("%.0e" % k).replace("+", "")),
                         (2.0, 1.0, 1.0), k, [0.0, 0.0, 1.0, ad], 30.0, "model",
                         "small libration"))
    jobs.append(("lib_b1_a010_k1e08", (2.0, 1.0, 1.0), 1e8, [0.0, 0.0, 1.0, 0.10], 30.0, "full",
                 "small libration"))
    jobs.append(("lib_b2_a005_k1e06", (80.0, 20.0, 40.0), 1e6, [0.0, 0.0, 1.0, 0.05], 30.0,
                 "full", "small libration"))
    jobs.append(("lib_b2_a005_k1e10_T300", (80.0, 20.0, 40.0), 1e10, [0.0, 0.0, 1.0, 0.05],
                 300.0, "model", "small libration"))

    lines = [
        "# Held-out references for the honesty of the rattleback's auto (issue 29).",
        "# Generated by scripts/rattleback_honesty.py (see it for how); same keys as averaged.toml,",
        "# plus `uncertainty` (the reference's own error bound: recomputed twice as finely) and",
        "# `condition` (amplification of a relative nudge of alpha'0, reversal times included).",
        "# source = \"rk8-long-double\": the full model, fixed-step RK8 in 80-bit long double;",
        "# source = \"note-averaged-model\": the note's averaged model (k >= 1e10; model error < 1e-18).",
        "",
    ]
    for name, body, k, y0, T, how, shape in jobs:
        S = av.Sys(*body, k)
        if how == "full":
            nper = 200 if k < 1e7 else 300
            ref = full(S, y0, T, nper)
            fine = full(S, y0, T, 2 * nper)
            nudged = full(S, y0[:3] + [y0[3] * (1 + NUDGE)], T, nper)
            source = "rk8-long-double"
        else:
            ref = model(S, y0, T)
            fine = model(S, y0, T, rtol=1e-13)
            nudged = model(S, y0[:3] + [y0[3] * (1 + NUDGE)], T)
            source = "note-averaged-model"
        unc = gap(ref, fine)
        cond = gap(ref, nudged) / NUDGE
        lines.append("[case.%s]" % name)
        lines.append("start = \"%s\"" % shape)
        lines.append("ix = %s\niy = %s\niz = %s\nk = %s" % tuple(fl(v) for v in (*body, k)))
        lines.append("gamma0 = %s\nalpha0 = %s\ngamma_dot0 = %s\nalpha_dot0 = %s"
                     % tuple(fl(v) for v in y0))
        lines.append("t_end = %s" % fl(T))
        lines.append("source = \"%s\"" % source)
        lines.append("uncertainty = %s" % fl(max(unc, 1e-13)))
        lines.append("condition = %s" % fl(cond))
        lines.append("alpha_end = %s\nalpha_dot_end = %s" % (fl(ref[0][0]), fl(ref[0][1])))
        lines.append("reversals = [%s]" % ", ".join(fl(t) for t in ref[1]))
        lines.append("")
        print(name, how, "unc %.1e cond %.1e revs %d" % (unc, cond, len(ref[1])), flush=True)
    with open(OUT, "w") as fh:
        fh.write("\n".join(lines))


if __name__ == "__main__":
    main()
