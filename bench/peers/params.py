#!/usr/bin/env python3
"""Peer contact coefficients equivalent to dem-bench's (libdem hertz + Mindlin, E = 1e8 Pa,
nu = 0.3, e = 0.5, mu = 0.3, rho = 2500, d = 1 mm). Prints shell assignments.
delta_ref: the overlap at which the LAMMPS gran/hertz/history damping (prop. to sqrt(R* delta))
is made equal to dem-bench's (prop. to (R* delta)^(1/4)); default = mean pair overlap of
dense20k.csv (2.59e-7 m, printed by csv2lammps.py)."""
import math, sys
E, nu, e, mu, rho, r = 1e8, 0.3, 0.5, 0.3, 2500.0, 0.5e-3
dref = float(sys.argv[1]) if len(sys.argv) > 1 else 2.59e-7
Es = E / (2 * (1 - nu * nu))                 # E* (particle-particle; wall of the same material)
G = E / (2 * (1 + nu))
Gs = 1.0 / (2 * (2 - nu) / G)                # G* = ((2-nu)/G + (2-nu)/G)^-1
l = math.log(e)
eta_lin = 2 * abs(l) / math.sqrt(math.pi ** 2 + l * l)   # libdem tangential eta
eta_H = math.sqrt(5.0 / 6.0) * eta_lin                     # libdem Hertz normal eta
m = rho * math.pi / 6 * (2 * r) ** 3
ms, Rs = m / 2, r / 2                        # m*, R* of two equal spheres
a = math.sqrt(Rs * dref)
kn = 4.0 / 3.0 * Es                          # LAMMPS kn (Hertz), Pa
kt = 8 * Gs                                  # LAMMPS kt (Mindlin 8 G*), Pa
gn = eta_H * math.sqrt(2 * Es / (ms * a))    # gamma_n, 1/(s m)
gt = eta_lin * math.sqrt(8 * Gs / (ms * a))  # gamma_t, 1/(s m)
# pair granular damping tsuji: eta_n = alpha(cor) sqrt(m* (4/3 E*) a); want eta_H sqrt(m* 2 E* a)
alpha_t = eta_H * math.sqrt(1.5)
tsu = lambda c: (1.2728 - 4.2783 * c + 11.087 * c**2 - 22.348 * c**3 + 27.467 * c**4
                 - 18.022 * c**5 + 4.8218 * c**6)
lo, hi = 0.01, 1.0                           # alpha(c) decreasing on (0,1]
for _ in range(200):
    mid = 0.5 * (lo + hi)
    if tsu(mid) > alpha_t: lo = mid
    else: hi = mid
cor_t = 0.5 * (lo + hi)
xt = eta_lin * math.sqrt(8 * Gs) / (alpha_t * math.sqrt(4.0 / 3.0 * Es))  # tangential/normal damping ratio
# LIGGGHTS: Hertz-Mindlin with the same eta (2 sqrt(5/6) beta) for normal; tangential with
# the same factor on sqrt(m* S_t): ratio to ours sqrt(5/6) (fixed in LIGGGHTS)
print('ESTAR=%.10g' % Es); print('GSTAR=%.10g' % Gs)
print('KN=%.10g' % kn); print('KT=%.10g' % kt)
print('GAMMAN=%.10g' % gn); print('GAMMAT=%.10g' % gt)
print('COR_TSUJI=%.10g' % cor_t); print('XT=%.10g' % xt)
print('# eta_H=%.6g eta_lin=%.6g alpha_needed=%.6g alpha_tsuji(0.5)=%.6g m=%.6g kg a_ref=%.4g m'
      % (eta_H, eta_lin, alpha_t, tsu(0.5), m, a))
