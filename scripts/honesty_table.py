#!/usr/bin/env python3
"""The rattleback's `auto` against the reference sets, for one or more builds (issue 29).

    python3 scripts/honesty_table.py NAME=PATH/TO/rattleback [NAME=PATH ...]

For each reference file, tolerance (1e-6, 1e-8, 1e-10) and build: claims held / made (a claim
holds when the error, less the reference's own uncertainty, is within the tolerance), runs
declined and how many of them were in fact within it, and estimates below the error. Prints a
Markdown table (docs/benchmarks.md, "Issue 29"). Needs python3 >= 3.11 (tomllib).
"""
import json, subprocess, tomllib, math, sys
from concurrent.futures import ThreadPoolExecutor
files = {'averaged': 'tests/fixtures/reference/averaged.toml', 'held-out': 'tests/fixtures/reference/rattleback_honesty.toml'}
bins = dict(a.split('=', 1) for a in sys.argv[1:]) or {'this build': './target/release/rattleback'}
def one(b, c, tol):
    sets = []
    for k, key in (('body.ix','ix'),('body.iy','iy'),('body.iz','iz'),('spring.k','k'),('initial.gamma','gamma0'),('initial.alpha','alpha0'),('initial.gamma_dot','gamma_dot0'),('initial.alpha_dot','alpha_dot0'),('run.t_end','t_end')):
        sets += ['--set', '%s=%r' % (k, c[key])]
    sets += ['--set', 'run.tolerance=%g' % tol]
    d = json.loads(subprocess.run([b,'simulate','--preset','subcritical','--format','json']+sets, capture_output=True, text=True).stdout)
    f = d['final']; revs = d['reversals']['times']
    err = max(abs(f['alpha']-c['alpha_end']), abs(f['alpha_dot']-c['alpha_dot_end']))
    err = max([err] + [abs(a-b) for a,b in zip(revs, c['reversals'])]) if len(revs)==len(c['reversals']) else math.inf
    unc = c.get('uncertainty', 3e-11 if c['k'] >= 1e8 else 2e-12)
    return d['auto']['met'], err, unc, d['auto']['error_estimate'] or math.inf
print("| references | tolerance | build | claims held / made | declined (within) | estimates below the error |")
print("|---|---|---|---|---|---|")
for fname, path in files.items():
    cases = list(tomllib.load(open(path,'rb'))['case'].values())
    for tol in (1e-6, 1e-8, 1e-10):
        for bname, b in bins.items():
            with ThreadPoolExecutor(2) as ex:
                rs = list(ex.map(lambda c: one(b, c, tol), cases))
            made = sum(1 for m,e,u,s in rs if m); held = sum(1 for m,e,u,s in rs if m and e - u <= tol)
            dec = sum(1 for m,e,u,s in rs if not m); within = sum(1 for m,e,u,s in rs if not m and e + u <= tol)
            low = sum(1 for m,e,u,s in rs if s < e - u)
            print("| %s (%d) | %g | %s | %d / %d | %d (%d) | %d |" % (fname, len(cases), tol, bname, held, made, dec, within, low), flush=True)
