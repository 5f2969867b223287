#!/usr/bin/env python3
"""Random pendulum chart windows for the reviews' refine-vs-exhaustive comparison (issue 80):

    python3 scripts/heldout_windows.py SEED COUNT > windows.txt

eps log-uniform in [1e-2, 0.5], windows around the Mathieu tongues' roots a = n^2/(4 eps^2) or
anywhere, log rows, grids 96x64 to 150x150, both positions; one `study map` argument line each.
"""
import random,sys
r=random.Random(int(sys.argv[1]))
for _ in range(int(sys.argv[2])):
    eps=10**r.uniform(-2,-0.3); scale=1/(4*eps*eps)
    c=r.uniform(-2,12)*scale; w=10**r.uniform(-1,1.3)*scale
    lo=10**r.uniform(-3,0); hi=lo*10**r.uniform(1,4)
    pos=r.choice(['--position hanging',''])
    g=r.choice(['200x100','120x80','96x64','150x150'])
    print(f"--preset kapitza-upright --grid {g} --set pendulum.epsilon={eps:.4g} --columns {c-w/2:.6g},{c+w/2:.6g} --rows {lo:.4g},{hi:.4g} {pos} --force")
