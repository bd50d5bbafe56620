#!/usr/bin/env python3
"""Convert dense20k.csv ('#' comments, header x,y,z,r; SI) to a LAMMPS/LIGGGHTS data file
(atom_style sphere: id type diameter density x y z) and print overlap statistics.

usage: csv2lammps.py IN.csv OUT.data [density=2500] [L=0.03]
"""
import math, sys
from collections import defaultdict

src, dst = sys.argv[1], sys.argv[2]
rho = float(sys.argv[3]) if len(sys.argv) > 3 else 2500.0
L = float(sys.argv[4]) if len(sys.argv) > 4 else 0.03
P = []
for line in open(src):
    if line.startswith('#') or line.startswith('x') or not line.strip():
        continue
    x, y, z, r = map(float, line.split(',')[:4])
    P.append((x, y, z, r))
n = len(P)
rmax = max(p[3] for p in P)
ztop = max(p[2] + p[3] for p in P)
zhi = ztop + 2.0e-3  # head room above the bed (fixed boundary: atoms must stay inside)
with open(dst, 'w') as f:
    f.write('# from %s: %d spheres, density %g\n\n' % (src, n, rho))
    f.write('%d atoms\n1 atom types\n\n' % n)
    f.write('0 %.17g xlo xhi\n0 %.17g ylo yhi\n0 %.17g zlo zhi\n\nAtoms # sphere\n\n' % (L, L, zhi))
    for i, (x, y, z, r) in enumerate(P, 1):
        f.write('%d 1 %.17g %.17g %.17g %.17g %.17g\n' % (i, 2 * r, rho, x, y, z))
# overlap statistics of the file (cell list)
h = 2 * rmax
cells = defaultdict(list)
for i, p in enumerate(P):
    cells[(int(p[0] // h), int(p[1] // h), int(p[2] // h))].append(i)
pairs = []
for (cx, cy, cz), lst in cells.items():
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            for dz in (-1, 0, 1):
                for j in cells.get((cx + dx, cy + dy, cz + dz), ()):
                    for i in lst:
                        if j <= i:
                            continue
                        a, b = P[i], P[j]
                        d = math.sqrt((a[0]-b[0])**2 + (a[1]-b[1])**2 + (a[2]-b[2])**2)
                        ov = a[3] + b[3] - d
                        if ov > 0:
                            pairs.append(ov)
walls = []
for x, y, z, r in P:
    for g in (x, L - x, y, L - y, z):
        if g < r:
            walls.append(r - g)
pairs.sort(); walls.sort()
med = lambda v: v[len(v) // 2] if v else 0.0
sys.stderr.write('%d spheres, top of bed %.5g m, box zhi %.5g m\n' % (n, ztop, zhi))
sys.stderr.write('pair contacts %d, wall contacts %d, contacts/particle %.3f\n'
                 % (len(pairs), len(walls), (2 * len(pairs) + len(walls)) / n))
sys.stderr.write('pair overlap mean %.3g median %.3g max %.3g m; wall overlap mean %.3g median %.3g m\n'
                 % (sum(pairs) / len(pairs), med(pairs), pairs[-1], sum(walls) / max(1, len(walls)), med(walls)))
