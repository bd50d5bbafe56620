/* The JKR force-overlap relation in dimensionless form, shared by `jkr` and `jkr-modified`.
 * Internal to libdem (not installed).
 *
 * JKR (thesis eqs 3.40-3.42; paper eqs B1, B3, B4):
 *
 *   F     = 4 E* a^3 / (3 R*) - sqrt(8 pi Gamma E* a^3)          (3.41) / (B1)
 *   alpha = a^2 / R* - sqrt(2 pi Gamma a / E*)                     (3.42) / (B3)
 *   f_c   = 3/2 pi Gamma R*                                        (3.40)
 *
 * Scales: a_c^3 = 3 R* f_c / (4 E*) = 9 pi Gamma R*^2 / (8 E*) (contact radius at the
 * pull-off force, thesis 3.57) and delta_c = a_c^2 / R* (m). With a = a_c s^2 the two
 * equations become, exactly (using 2 pi Gamma / E* = 16 a_c^3 / (9 R*^2)),
 *
 *   F / f_c           = s^6 - 2 s^3
 *   alpha / delta_c   = s^4 - (4/3) s                     (a quartic in s)
 *   dF/dalpha         = (f_c / delta_c) (9/2) s^2 (s^3 - 1) / (3 s^3 - 1)
 *
 * (the last is paper eq B2, 2 E* a (sqrt(f_H/f_c) - 1)/(sqrt(f_H/f_c) - 1/3), with
 * f_H/f_c = s^6). Landmarks along the curve:
 *
 *   s^3 = 4/3:  alpha = 0,                  F = -8/9 f_c   (jump-in, B5-B6)
 *   s^3 = 2:    alpha_0 = (2/3) 2^(1/3) delta_c, F = 0    (zero force, B8-B9, B11)
 *   s   = 1:    alpha = -delta_c / 3,       F = -f_c       (pull-off, minimum of F)
 *   s^3 = 1/3:  alpha_f = -3^(-1/3) delta_c, F = -5/9 f_c  (break: d alpha/ds = 0)
 *
 * alpha_f = -3^(-1/3) delta_c = -(3/4) (pi^2 Gamma^2 R* / E*^2)^(1/3).
 *
 * Solving the quartic s^4 - (4/3) s - A = 0 (A = alpha/delta_c >= A_f) for its largest real
 * root, in closed form (Ferrari). Adding 2 m s^2 + m^2 to both sides of s^4 = (4/3) s + A
 * makes the right side a perfect square when the resolvent cubic
 *
 *   m^3 + A m - 2/9 = 0
 *
 * holds; then s^2 + m = sqrt(2m) s + 2 / (3 sqrt(2m)) and
 *
 *   s = ( sqrt(2m) + sqrt(8 / (3 sqrt(2m)) - 2m) ) / 2.
 *
 * The cubic's discriminant is -(4 A^3 + 4/3): it has exactly one real root for A > A_f
 * (A_f^3 = -1/3) — the branch we need — given by Cardano, m = u + v with
 * u = cbrt(1/9 + sqrt(1/81 + A^3/27)), u v = -A/3, u^3 + v^3 = 2/9. Written as
 * m = (2/9) / (u^2 - u v + v^2), it has no cancellation for any A (u^2 - uv + v^2 >=
 * (u^2+v^2)/2 > 0, u >= cbrt(1/9)). Cost: one cube root, three sqrt, two divisions; no
 * history, no iteration over the quartic. For A > 1e12 the root is taken from s = A^(1/4) plus one Newton step
 * (converged to round-off there; it also avoids A^3 overflowing). Accuracy: the result
 * satisfies the quartic to a few ulps (backward stable); near A_f the root is a double root,
 * so the forward error grows like eps / sqrt(A - A_f), as for any method (tests/check_laws.c
 * compares with an extended-precision Newton iteration).
 */
#ifndef DEM_JKR_CORE_H
#define DEM_JKR_CORE_H

#include <math.h>
#include <stdint.h>
#include <string.h>

/* A_f = alpha_f / delta_c = -3^(-1/3): the breaking overlap. */
#define DEM_JKR_AF (-0.69336127435063470484335227478596)
/* s at the break, 3^(-1/3). */
#define DEM_JKR_SF (0.69336127435063470484335227478596)

/* Cube root of x for 1/9 <= x < 1e40 (the argument u^3 below): a first guess from the
 * exponent bits (relative error < 4%), two Halley steps (cubic convergence: ~1e-5, then
 * ~1e-15) and a final Newton step (round-off). Three divisions, no libm call: about three
 * times faster than cbrt() here, and the result is within an ulp or two of it. */
static inline double dem_jkr_cbrt(double x) {
  uint64_t i;
  memcpy(&i, &x, sizeof i);
  i = i / 3 + UINT64_C(0x2a9f7893782da1ce);
  double y;
  memcpy(&y, &i, sizeof y);
  for (int k = 0; k < 2; k++) {
    double y3 = y * y * y;
    y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
  }
  return y - (y * y * y - x) / (3.0 * y * y);
}

/* Largest real root s of s^4 - (4/3) s - A = 0, for A >= A_f (below A_f: the double root
 * at A_f is returned). With c = u^3 = 1/9 + sqrt(1/81 + A^3/27), v = -A/(3u) = -A u^2/(3c)
 * (the division by c runs in parallel with the cube root), Q = u^2 - uv + v^2, m = (2/9)/Q:
 * sqrt(2m) = (2/3) sqrt(Q)/Q and 8/(3 sqrt(2m)) - 2m = 4 sqrt(Q) - (4/9)/Q. */
static inline double dem_jkr_root(double A) {
  if (A > 1e12) {
    if (A > 1e200) A = 1e200; /* guard: keeps s^6 finite for any finite input */
    double s = sqrt(sqrt(A));
    return s - (s * s * s * s - (4.0 / 3.0) * s - A) / (4.0 * s * s * s - 4.0 / 3.0);
  }
  if (!(A > DEM_JKR_AF)) return DEM_JKR_SF;
  double D = 1.0 / 81.0 + A * A * A / 27.0;
  double c = 1.0 / 9.0 + sqrt(D > 0.0 ? D : 0.0);
  double t = A / (3.0 * c);
  double u = dem_jkr_cbrt(c);
  double v = -t * u * u;
  double Q = u * u - u * v + v * v;
  double iq = 1.0 / Q, sq = sqrt(Q);
  double w = 4.0 * sq - (4.0 / 9.0) * iq;
  return 0.5 * ((2.0 / 3.0) * sq * iq + sqrt(w > 0.0 ? w : 0.0));
}

/* Dimensionless force F/f_c and stiffness (dF/dalpha) delta_c/f_c at root s. */
static inline double dem_jkr_fhat(double s) {
  double s3 = s * s * s;
  return s3 * (s3 - 2.0);
}
static inline double dem_jkr_khat(double s) {
  double s3 = s * s * s, den = 3.0 * s3 - 1.0;
  if (!(den > 1e-300)) return -INFINITY; /* at the break itself */
  return 4.5 * s * s * (s3 - 1.0) / den;
}

/* Scales of one contact: f_c = 3/2 pi Gamma R* (N), delta_c = a_c^2 / R* (m) with
 * a_c^3 = 9 pi Gamma R*^2 / (8 E*). */
static inline void dem_jkr_scales(double gamma, double Es, double R, double *fc, double *dc) {
  *fc = 1.5 * M_PI * gamma * R;
  double q = 9.0 * M_PI * gamma / (8.0 * Es); /* a_c^3 / R*^2, m */
  *dc = cbrt(q * q * R);                        /* (a_c^3)^(2/3) / R* */
}

/* The law body shared by jkr.c and jkr_modified.c (defined in jkr.c). ------------------ */
#include "dem/contact.h"

/* Compiled coefficients. */
enum { DEM_JKR_C_ES, DEM_JKR_C_GAMMA, DEM_JKR_C_ETA, DEM_JKR_C_E, DEM_JKR_NCOEF };
/* History: state (0 apart, 1 in contact), f_c (N) and 1/delta_c (1/m) cached at formation. */
enum { DEM_JKR_H_FC = 1, DEM_JKR_H_IDC = 2, DEM_JKR_NHIST = 3 };

/* The coefficient table, shared (a definition of another length fails to compile). */
#define DEM_JKR_NCOEFS 6
extern const dem_coef_spec dem_jkrlaw_coefs[DEM_JKR_NCOEFS];
int dem_jkrlaw_set_coeffs(const dem_params *ps, double *c, dem_err *err);
double dem_jkrlaw_kref(const double *c, const dem_geom *g, double v);
/* break_at_zero = 0: JKR breaks below alpha_f; 1: `jkr-modified`, breaks below alpha = 0. */
void dem_jkrlaw_force(const double *c, const dem_geom *g, double *hist, double alpha,
                   double alpha_dot, dem_normal *out, int break_at_zero);

#endif
