#!/usr/bin/env python3
"""Case 10 on the x0.3 full bed read over later h/r windows (docs/validation.md, "Cases 10
and 11 at thesis scale on the x0.3 bed").

Question: is the thesis' "flat up to gamma* ~ 1" ours once the window leaves the impact
transient of the first h/r (H at gamma* >= 1 falls across 0.2-0.5)? Reads the run-cache
files of the zeta-1 runs (columns h/r, H [Pa], bin p [Pa], ...; validate/cache.c) and prints,
per window, the mean H and dynamic-bin hydrostatic stress p [kPa] at each gamma*, the ratios
to gamma* 0.1, H/p, and an unweighted least-squares fit H = H0 (1 + kappa gamma*^2) with the
gamma* at which the rise is 10 % of H0, sqrt(0.1 / kappa). (The harness' own fit is
weighted by the plateau standard errors; this one is unweighted, a reading only.)

usage: windows.py BEDS_DIR
"""
import glob
import re
import sys


def mean(x):
    return sum(x) / len(x)


def main(beds):
    data = {}
    for f in sorted(glob.glob(beds + "/run_*_kn1_mui0_dts1_h0.5.dat")):
        g = float(re.search(r"sphere16_g([\d.]+)_", f).group(1))
        data[g] = [list(map(float, l.split())) for l in open(f) if not l.startswith("#")]
    if len(data) < 3:
        sys.exit("windows.py: fewer than 3 zeta-1 runs in %s" % beds)
    gs = sorted(data)
    print("gamma*:", gs)
    for lo, hi in [(0.2, 0.5), (0.3, 0.5), (0.4, 0.5)]:
        H, P = [], []
        for g in gs:
            r = [x for x in data[g] if lo <= x[0] <= hi]
            H.append(mean([x[1] for x in r]) / 1e3)
            P.append(mean([x[2] for x in r]) / 1e3)
        X = [g * g for g in gs]
        mx, my = mean(X), mean(H)
        b = sum((x - mx) * (y - my) for x, y in zip(X, H)) / sum((x - mx) ** 2 for x in X)
        a = my - b * mx
        i1 = gs.index(0.1)
        print("h/r %.1f-%.1f" % (lo, hi))
        print("  H [kPa]   ", " ".join("%7.2f" % h for h in H))
        print("  H / H(0.1)", " ".join("%7.2f" % (h / H[i1]) for h in H))
        print("  p [kPa]   ", " ".join("%7.2f" % p for p in P))
        print("  p / p(0.1)", " ".join("%7.2f" % (p / P[i1]) for p in P))
        print("  H / p     ", " ".join("%7.2f" % (h / p) for h, p in zip(H, P)))
        print("  fit: H0 %.2f kPa, kappa %.2f, 10 %% onset gamma* %.3f" % (a, b / a, (0.1 * a / b) ** 0.5))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
