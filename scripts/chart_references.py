#!/usr/bin/env python3
"""Reference values for the charts of issue 59, made without the crate.

The pendulum: the monodromy matrix of Mathieu's equation th'' + (delta + q cos tau) th = 0 over one
period 2 pi, integrated in 30-digit arithmetic by mpmath's Taylor-series ODE solver
(mpmath.odefun), for the upright (delta = -eps^2 a, q = eps b) and the hanging position
(delta = +eps^2 a). Two sets of cells:

- `pendulum_grid`: every cell centre of `study map --grid 8x6 --columns 0,2 --rows 0.2,1000` at
  eps = 1e-3 (kapitza-upright's) and of `--rows 0.2,20` at eps = 0.15 (kapitza-coarse's), the
  rows log-spaced as the command documents (`min + (i + 0.5)/n (max - min)` across; the same in
  log up);
- `pendulum_sample`: a held-out sample of random (a, b, eps, position) drawn with a fixed seed.

The celt: the reversal count in [0, T] and the first reversal time of every cell centre of
`study map --preset celt-clockwise --grid 6x4` (omega_z over +-10 rad/s, the product of inertia D
over +-0.4, T and the tilt the preset's), by the independent implementation
scripts/celt_reference.py (scipy's DOP853 at rtol = atol = 1e-12, Newton-Euler), with the count
checked at 1e-11; and the growth rate of steady spin at each cell, from a central-difference
Jacobian of that implementation's field (numpy's eigenvalues).

Writes tests/fixtures/reference/charts.toml. Usage: python3 scripts/chart_references.py
(mpmath, numpy, scipy; a few minutes).
"""
import math
import os
import random
import sys
import tomllib

import mpmath as mp
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import celt_reference as ref  # noqa: E402

mp.mp.dps = 30


def trace(delta, q):
    d, qq = mp.mpf(delta), mp.mpf(q)

    def f(t, y):
        c = -(d + qq * mp.cos(t))
        return [y[1], c * y[0], y[3], c * y[2]]

    sol = mp.odefun(f, 0, [mp.mpf(1), mp.mpf(0), mp.mpf(0), mp.mpf(1)])
    y = sol(2 * mp.pi)
    return y[0] + y[3]


def pendulum_case(a, b, eps, position):
    delta = (-1 if position == 'upright' else 1) * eps * eps * a
    tr = trace(delta, eps * b)
    return dict(a=a, b=b, epsilon=eps, position=position, trace=float(tr),
                trace_text=mp.nstr(tr, 30), stable=bool(abs(tr) < 2))


def centres(lo, hi, n, log):
    if log:
        return [math.exp(math.log(lo) + (i + 0.5) / n * math.log(hi / lo)) for i in range(n)]
    return [lo + (i + 0.5) / n * (hi - lo) for i in range(n)]


def celt_cases():
    with open(os.path.join(ROOT, 'presets', 'celt-clockwise.toml'), 'rb') as f:
        d = tomllib.load(f)
    c, i, r = d['celt'], d['initial'], d['run']
    band, t_end = float(r['spin_band']), float(r['t_end'])
    out = []
    for product in centres(-0.4, 0.4, 4, False):
        for wz in centres(-10.0, 10.0, 6, False):
            p = dict(semi_axes=[c['a'], c['b'], c['c']], offset=c['offset'],
                     inertia=[c['ix'], c['iy'], c['iz']], product=product,
                     gravity=c['gravity'])
            ic = dict(tilt=[i['roll'], i['pitch']], yaw=i['yaw'],
                      omega=[i['omega_x'], i['omega_y'], wz])
            ne = ref.NewtonEuler(p)
            best = ref.integrate(ne, ic, t_end, 1e-12, band=band)
            check = ref.integrate(ne, ic, t_end, 1e-11, band=band)
            times = best['reversal_times']
            out.append(dict(omega_z=wz, product=product, reversals=best['reversals'],
                            first_reversal=times[0] if times else -1.0,
                            counts_agree=best['reversals'] == check['reversals'],
                            first_spread=(abs(times[0] - check['reversal_times'][0])
                                          if times and check['reversal_times'] else 0.0),
                            growth_rate=growth(ne, wz)))
            print('celt', wz, product, out[-1]['reversals'], out[-1]['first_reversal'],
                  file=sys.stderr)
    return out


def growth(ne, n):
    y0 = np.array([0, 0, n, 0, 0, 1.0])
    h = 1e-6 * max(1.0, abs(n))
    J = np.zeros((6, 6))
    for k in range(6):
        up, down = y0.copy(), y0.copy()
        up[k] += h
        down[k] -= h
        fu = np.array(ne.omega_dot(*up)[:6])
        fd = np.array(ne.omega_dot(*down)[:6])
        J[:, k] = (fu - fd) / (2 * h)
    return float(max(np.linalg.eigvals(J).real))


def toml_value(v):
    if isinstance(v, bool):
        return 'true' if v else 'false'
    if isinstance(v, str):
        return '"%s"' % v
    return repr(float(v)) if isinstance(v, float) else str(v)


def table(name, rows):
    lines = []
    for row in rows:
        lines.append('[[%s]]' % name)
        lines += ['%s = %s' % (k, toml_value(v)) for k, v in row.items()]
        lines.append('')
    return lines


def main():
    grid = []
    for eps, b_max in ((1e-3, 1000.0), (0.15, 20.0)):
        for b in centres(0.2, b_max, 6, True):
            for a in centres(0.0, 2.0, 8, False):
                grid.append(pendulum_case(a, b, eps, 'upright'))
                print('pendulum', eps, a, b, file=sys.stderr)
    rng = random.Random(59)
    sample = []
    for _ in range(40):
        eps = 10 ** rng.uniform(-3, -0.5)
        a = rng.uniform(-3, 3)
        b = 10 ** rng.uniform(-1, math.log10(0.8 / eps))
        position = rng.choice(['upright', 'hanging'])
        sample.append(pendulum_case(a, b, eps, position))
    celt = celt_cases()
    head = ['# Made by scripts/chart_references.py (mpmath 40 digits; scripts/celt_reference.py).',
            '# Do not edit: re-run the script.', '']
    text = '\n'.join(head + table('pendulum_grid', grid) + table('pendulum_sample', sample)
                     + table('celt_grid', celt))
    with open(os.path.join(ROOT, 'tests', 'fixtures', 'reference', 'charts.toml'), 'w') as f:
        f.write(text)


if __name__ == '__main__':
    main()
