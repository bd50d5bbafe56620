/* dem/energy.h — closed-form energy balances of a normal impact for the linear
 * elasto-plastic-adhesive laws (thesis 4.1.3 and 4.1.5, eqs 4.12-4.20, Appendices II-III).
 *
 * A sphere (reduced mass m* = g->m, reduced radius R* = g->R) hits a flat rigid target at
 * v_i; the law's piecewise-linear force-overlap curve is integrated by hand:
 *   E_i = 1/2 m v_i^2 = W_p + W_e - |W_lt|            (4.12, A2.1, A3.1)
 *   E_r = 1/2 m v_r^2 = W_e - |W_ad|                   (4.15, A2.10, A3.9, A3.11)
 * W_e: elastic energy released on unloading (triangle alpha_p..alpha_max), W_ad: work of
 * adhesion on unloading from alpha_p to breakage. The particle sticks when W_e <= |W_ad|
 * (4.14). The balances are rate-independent: the law's viscous damping (coefficient e) is
 * ignored here. Supported laws:
 *   pasha             v_i (4.13), v_r (4.16) with alpha_c0 = alpha_p - 8/9 f_cp/k_e;
 *   pasha-simplified  v_i (4.18), v_r (4.19) = (A3.9);
 *   luding            v_i (4.18), v_r (4.20) = (A3.11).
 * (The thesis text assigns 4.19 to Luding and 4.20 to the simplified law; its Appendix III
 * derives them the other way round, which is what the figures require: see
 * docs/contact-laws.md.)
 */
#ifndef DEM_ENERGY_H
#define DEM_ENERGY_H

#include "dem/contact.h"
#include "dem/error.h"

typedef struct dem_energy_point {
  double v_impact;  /* m/s */
  double v_rebound; /* m/s, 0 if stuck */
  double e;         /* v_rebound / v_impact */
  int stuck;        /* 1 if W_e <= |W_ad| */
  double alpha_max, alpha_0, alpha_p, alpha_cp, alpha_fp; /* m (alpha_fp: breakage) */
  double f_max;     /* N */
  double f_pulloff; /* N, > 0: largest tensile force on unloading */
  double k_e;       /* N/m, unloading stiffness */
  double w_in;      /* J, impact kinetic energy 1/2 m v_i^2 */
  double w_el;      /* J, W_e */
  double w_ad;      /* J, |W_ad| (luding: |W_lt| + |W_ut| of App. III, eq A3.10) */
} dem_energy_point;

/* 1 if the law (luding, pasha, pasha-simplified) has closed forms here. */
int dem_energy_has_law(const dem_law *law);
/* The balance for a given maximum overlap (m). DEM_ERANGE if alpha_max is below the overlap
 * that the smallest impact velocity reaches (v_i^2 <= 0), DEM_EUNSUPPORTED for other laws. */
int dem_energy_at_alpha_max(const dem_contact *ct, const dem_geom *g, double alpha_max,
                            dem_energy_point *p, dem_err *err);
/* The balance for an impact velocity v > 0 (m/s): alpha_max from (4.13)/(4.18) inverted. */
int dem_energy_at_velocity(const dem_contact *ct, const dem_geom *g, double v,
                           dem_energy_point *p, dem_err *err);
/* Critical sticking velocity (m/s): the largest impact velocity at which the particle
 * sticks, searched numerically (log grid then bisection to 1e-12 relative) over maximum
 * overlaps up to alpha_lim (m; e.g. R*). INFINITY if it still sticks at alpha_lim, 0 if it
 * never sticks. */
int dem_energy_v_stick(const dem_contact *ct, const dem_geom *g, double alpha_lim,
                       double *v_stick, dem_err *err);
/* The same from the closed forms where they exist: pasha with constant k_e (W_e = W_ad is
 * linear in alpha_max - alpha_0), pasha-simplified with constant k_e (linear), luding with
 * the capped k_e when the root lies beyond alpha* (quadratic). INFINITY if the adhesive
 * work outgrows the elastic one (always sticks). DEM_EUNSUPPORTED otherwise. */
int dem_energy_v_stick_closed(const dem_contact *ct, const dem_geom *g, double *v_stick,
                              dem_err *err);
/* Limit of e(v) for v -> infinity with a constant unloading stiffness:
 * pasha-simplified  e^2 = kp/ke - 2 kcp^2 (ke-kp)^2 / (ke kp (ke+kcp)^2)
 * luding (capped)   e^2 = kp/ke - kc (ke-kp)^2 / (ke kp (ke+kc))
 * (both -> sqrt(kp/ke) as the adhesive slope -> 0; thesis 4.1.5). 0 if e^2 <= 0. */
int dem_energy_e_limit(const dem_contact *ct, double *e_inf, dem_err *err);

#endif
