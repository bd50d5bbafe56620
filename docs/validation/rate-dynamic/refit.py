#!/usr/bin/env python3
"""Re-fit H = H0 + beta rho_b v^2 on dem-validate summaries written before the harness
reported the fit (docs/validation.md, "The rise of H with the rate"). It does what
dem_rate_fit_dynamic (libdem/src/analysis/rate.c) does, for files that have no speeds:
v = gamma* sqrt(g/d) x bed top, the bed top (m) given on the command line (it is in the
run's log, "bed top X d"). Newer summaries carry cases[].rate_fit; use those.

usage: refit.py SUMMARY.json:BED_TOP_M [...]   (particle density 2500 kg/m^3, Table 6.2)
"""
import json, math, sys

G, D = 9.81, 1e-3


def wfit(x, y, s):
    w = [1 / si ** 2 for si in s]
    S, Sx, Sy = sum(w), sum(a * b for a, b in zip(w, x)), sum(a * b for a, b in zip(w, y))
    Sxx = sum(a * b * b for a, b in zip(w, x))
    Sxy = sum(a * b * c for a, b, c in zip(w, x, y))
    Dt = S * Sxx - Sx * Sx
    b = (S * Sxy - Sx * Sy) / Dt
    a = (Sy - b * Sx) / S
    chi2 = sum(wi * (yi - a - b * xi) ** 2 for wi, xi, yi in zip(w, x, y))
    dof = len(x) - 2
    sc = math.sqrt(chi2 / dof) if dof > 0 and chi2 > dof else 1.0
    return a, b, sc * math.sqrt(Sxx / Dt), sc * math.sqrt(S / Dt), sc * sc * (-Sx / Dt), chi2, dof


def main():
    for arg in sys.argv[1:]:
        f, top = arg.rsplit(':', 1)
        top = float(top)
        d = json.load(open(f))
        phi = d['beds'][0]['solids_fraction']
        rho_b = 2500.0 * phi
        c = [c for c in d['cases'] if c['name'] == 'strain-rate'][0]
        rr = [r for r in c['runs'] if r.get('status') == 'ok' and r['H'] and r['H'].get('mean')
              and r['H']['se'] > 0]
        v = [r['x'] * math.sqrt(G / D) * top for r in rr]
        a, b, sa, sb, cov, chi2, dof = wfit([rho_b * vi * vi for vi in v],
                                            [r['H']['mean'] for r in rr],
                                            [r['H']['se'] for r in rr])
        von = math.sqrt(0.1 * a / (b * rho_b))
        rel = 0.5 * math.sqrt((sa / a) ** 2 + (sb / b) ** 2 - 2 * cov / (a * b))
        gon = von / top * math.sqrt(D / G)
        kappa = b * rho_b * G * top ** 2 / (D * a)
        print(f"{f}: solids fraction {phi:.3f}, rho_b {rho_b:.0f} kg/m^3, {len(rr)} rates: "
              f"H0 {a / 1e3:.2f} +- {sa / 1e3:.2f} kPa, beta {b:.2f} +- {sb:.2f}, chi2 {chi2:.2f} "
              f"on {dof} dof; 10 % onset v {von:.3f} +- {von * rel:.3f} m/s, gamma* {gon:.3f} "
              f"+- {gon * rel:.3f}; kappa {kappa:.2f}")


if __name__ == '__main__':
    main()
