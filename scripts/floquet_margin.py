#!/usr/bin/env python3
"""The pendulum chart's error margin (issue 59; physics/kapitza/floquet.rs, MARGIN).

Runs `study map` on the two coarse charts of tests/fixtures/reference/charts.toml at three
tolerances and prints the worst ratio of each cell's true trace error (against the 30-digit
references) to its estimate. With the margin of 4 every ratio is below 1; the bare difference of
the two runs (the estimate over 4) read up to 2.9 at 1e-10 on kapitza-coarse.

Usage: cargo build --release && python3 scripts/floquet_margin.py
"""
import json
import os
import subprocess
import tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, 'target', 'release', 'rattleback')

with open(os.path.join(ROOT, 'tests', 'fixtures', 'reference', 'charts.toml'), 'rb') as f:
    grid = tomllib.load(f)['pendulum_grid']
for preset, rows, cases in [('kapitza-upright', '0.2,1000', grid[:48]),
                            ('kapitza-coarse', '0.2,20', grid[48:])]:
    for tol in ['1e-8', '1e-10', '1e-12']:
        out = json.loads(subprocess.run(
            [BIN, 'study', 'map', '--preset', preset, '--grid', '8x6', '--columns', '0,2',
             '--rows', rows, '--format', 'json', '--tolerance', tol],
            capture_output=True, text=True, check=True).stdout)
        worst = max(abs(c['trace'] - r['trace']) / max(c['trace_error'], 1e-300)
                    for c, r in zip(out['cells'], cases))
        print(f'{preset:16} {tol:6} worst error/estimate {worst:.3f}'
              f'  (error/difference {4 * worst:.2f})')
