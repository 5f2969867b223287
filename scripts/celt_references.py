#!/usr/bin/env python3
"""Reference values for the celt scene, made without the crate.

For every shipped celt preset (presets/celt-*.toml, read with tomllib), runs the independent
reference implementation (scripts/celt_reference.py: scipy's DOP853 on the Newton-Euler
equations; Kane's method in sympy as a second derivation) and writes
tests/fixtures/celt/references.json:

- the converged run: Newton-Euler at rtol = atol = 1e-13, with its uncertainty taken as the
  largest difference in the final omega from Newton-Euler at 1e-12 and Kane's method at 1e-12;
- crossing and reversal counts and times, the energy and its drift;
- the same at tolerances 1e-8 and 1e-10 (what an honest integrator's error looks like there).

Usage: python3 scripts/celt_references.py   (numpy, scipy, sympy; about a minute)
"""
import json
import math
import os
import sys
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import celt_reference as ref  # noqa: E402


def load(path):
    with open(path, 'rb') as f:
        d = tomllib.load(f)
    c, i, r = d['celt'], d.get('initial', {}), d.get('run', {})
    p = dict(semi_axes=[c['a'], c['b'], c['c']], offset=c['offset'],
             inertia=[c['ix'], c['iy'], c['iz']], product=c['product'],
             gravity=c.get('gravity', 981.0))
    ic = dict(tilt=[i.get('roll', 0.0), i.get('pitch', 0.0)], yaw=i.get('yaw', 0.0),
              omega=[i.get('omega_x', 0.0), i.get('omega_y', 0.0), i.get('omega_z', 0.0)])
    return p, ic, float(r['t_end']), float(r.get('spin_band', 0.5))


def summary(res):
    return dict(omega=res['omega'], gamma=res['gamma'], spin=res['spin_final'],
                crossings=res['crossings'], crossing_times=res['crossing_times'],
                reversals=res['reversals'], reversal_times=res['reversal_times'],
                energy_initial=res['energy_initial'], energy_final=res['energy_final'],
                energy_max_abs_drift=res['energy_max_abs_drift'])


def main():
    names = sorted(f[:-5] for f in os.listdir(os.path.join(ROOT, 'presets'))
                   if f.startswith('celt-') and f.endswith('.toml'))
    cases = []
    for name in names:
        p, ic, t_end, band = load(os.path.join(ROOT, 'presets', name + '.toml'))
        ne = ref.NewtonEuler(p)
        best = ref.integrate(ne, ic, t_end, 1e-13, band=band)
        check = ref.integrate(ne, ic, t_end, 1e-12, band=band)
        kane = ref.integrate(ref.Kane(p), ic, t_end, 1e-12, band=band)
        spread = max(abs(a - b) for other in (check, kane)
                     for a, b in zip(best['omega'], other['omega']))
        at = {}
        for tol in (1e-8, 1e-10):
            r = ref.integrate(ne, ic, t_end, tol, band=band)
            at['%g' % tol] = dict(omega=r['omega'], crossings=r['crossings'],
                                  reversals=r['reversals'],
                                  omega_error=max(abs(a - b) for a, b in
                                                  zip(r['omega'], best['omega'])))
        agree = (best['crossings'] == check['crossings'] == kane['crossings'] and
                 best['reversals'] == check['reversals'] == kane['reversals'])
        cases.append(dict(preset=name, t_end=t_end, band=band, params=p, initial=ic,
                          reference=summary(best), omega_uncertainty=spread,
                          counts_agree_across_derivations=agree, at_tolerance=at))
        print('%-20s crossings %d reversals %d  spread %.1e  agree %s' % (
            name, best['crossings'], best['reversals'], spread, agree), file=sys.stderr)
    out = dict(source='scripts/celt_references.py (scipy DOP853 on scripts/celt_reference.py)',
               cases=cases)
    path = os.path.join(ROOT, 'tests', 'fixtures', 'celt', 'references.json')
    with open(path, 'w') as f:
        json.dump(out, f, indent=1)
        f.write('\n')
    print('wrote', path, file=sys.stderr)


if __name__ == '__main__':
    main()
