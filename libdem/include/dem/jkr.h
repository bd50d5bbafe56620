/* dem/jkr.h — JKR contact geometry: the one solver of the contact radius from the overlap,
 * used by every JKR-type law (`jkr`, `jkr-modified`, `thornton-ning`).
 *
 * A sphere of reduced radius R* (m) against a flat of reduced modulus E* (Pa), interface
 * energy Gamma (J/m^2) (thesis eqs 3.40-3.42; paper eqs B1, B3, B4):
 *
 *   F     = 4 E* a^3 / (3 R*) - sqrt(8 pi Gamma E* a^3)          (3.41) / (B1)
 *   alpha = a^2 / R* - sqrt(2 pi Gamma a / E*)                     (3.42) / (B3)
 *   f_c   = 3/2 pi Gamma R*                                        (3.40)
 *
 * Scales: a_c^3 = 3 R* f_c / (4 E*) = 9 pi Gamma R*^2 / (8 E*) (contact radius at the
 * pull-off force, thesis 3.57) and delta_c = a_c^2 / R* (m). With a = a_c s^2 the two
 * equations become, exactly (using 2 pi Gamma / E* = 16 a_c^3 / (9 R*^2)),
 *
 *   F / f_c           = s^6 - 2 s^3                       dem_jkr_fhat
 *   alpha / delta_c   = s^4 - (4/3) s   (= A)             a quartic in s: dem_jkr_root
 *   dF/dalpha         = (f_c / delta_c) (9/2) s^2 (s^3 - 1) / (3 s^3 - 1)    dem_jkr_khat
 *   a^2 / R*          = delta_c s^4
 *
 * (the third is paper eq B2, 2 E* a (sqrt(f_H/f_c) - 1)/(sqrt(f_H/f_c) - 1/3), with
 * f_H/f_c = s^6; the Hertz part 4 E* a^3/(3 R*) is f_c s^6). Landmarks along the curve:
 *
 *   s^3 = 4/3:  alpha = 0,                  F = -8/9 f_c   (jump-in, B5-B6)
 *   s^3 = 2:    alpha_0 = (2/3) 2^(1/3) delta_c, F = 0    (zero force, B8-B9, B11)
 *   s   = 1:    alpha = -delta_c / 3,       F = -f_c       (pull-off, minimum of F)
 *   s^3 = 1/3:  alpha_f = -3^(-1/3) delta_c, F = -5/9 f_c  (break: d alpha/ds = 0)
 *
 * alpha_f = -3^(-1/3) delta_c = -(3/4) (pi^2 Gamma^2 R* / E*^2)^(1/3).
 *
 * The solver (closed form, Ferrari). Adding 2 m s^2 + m^2 to both sides of s^4 = (4/3) s + A
 * makes the right side a perfect square when the resolvent cubic m^3 + A m - 2/9 = 0 holds;
 * then s^2 + m = sqrt(2m) s + 2 / (3 sqrt(2m)) and
 *
 *   s = ( sqrt(2m) + sqrt(8 / (3 sqrt(2m)) - 2m) ) / 2.
 *
 * The cubic's discriminant is -(4 A^3 + 4/3): one real root for A > A_f (A_f^3 = -1/3), the
 * branch we need, given by Cardano, m = u + v with u = cbrt(1/9 + sqrt(1/81 + A^3/27)),
 * u v = -A/3, u^3 + v^3 = 2/9, written as m = (2/9) / (u^2 - u v + v^2) so that nothing
 * cancels for any A. One Newton step on the quartic then removes the rounding of the closed
 * form (and the last ~30 ulp of the cube root, so that its own final Newton step is not
 * needed: the accuracy of the polish for the cost of none). Cost: one cube root in line
 * (exponent-bit guess, two Halley steps), three sqrt, five divisions; no history, no
 * iteration count, no starting guess. For A > 1e12: s = A^(1/4) plus one Newton step (also keeps A^3 finite). Near A_f the
 * root is double, so its forward error grows like eps / sqrt(A - A_f), as for any method.
 *
 * Why this solver: of the two closed forms the project had (this one without the Newton
 * step, and an x^4 - x = q form with libm cbrt and a conditional Newton polish), this one was
 * 1.7 times faster (25 vs 41 ns per root), the other more accurate (2.4 vs 24 ulp worst
 * forward error); with the Newton step moved here from the cube root: 4 ulp at 28 ns.
 * Measurements: docs/contact-laws.md ("jkr").
 */
#ifndef DEM_JKR_H
#define DEM_JKR_H

#include <math.h>
#include <stdint.h>
#include <string.h>

/* A_f = alpha_f / delta_c = -3^(-1/3): the breaking overlap. */
#define DEM_JKR_AF (-0.69336127435063470484335227478596)
/* s at the break, 3^(-1/3). */
#define DEM_JKR_SF (0.69336127435063470484335227478596)

/* 4/3 - fl(4/3): the residual of the Newton step uses 4/3 to twice double precision (the
 * rounding of the constant alone would shift the root by 7e-17 s / (4 s^3 - 4/3), i.e. by
 * ~1e-14 near the double root at A_f). */
#define DEM_JKR_43LO 7.401486830834377e-17

/* Cube root of x for 1/9 <= x < 1e40 (the argument u^3 below), in two layers.
 * dem_jkr_cbrt_halley: a first guess from the exponent bits (relative error < 4%) and two
 * Halley steps (cubic convergence: ~1e-5, then ~1e-14; within 32 ulp, tested); enough inside
 * dem_jkr_root, whose final Newton step on the quartic removes that error too.
 * dem_jkr_cbrt: one more Newton step, round-off (within an ulp of cbrtl, tested). Two or
 * three divisions, no libm call: about three times faster than cbrt() here. */
static inline double dem_jkr_cbrt_halley(double x) {
  uint64_t i;
  memcpy(&i, &x, sizeof i);
  i = i / 3 + UINT64_C(0x2a9f7893782da1ce);
  double y;
  memcpy(&y, &i, sizeof y);
  for (int k = 0; k < 2; k++) {
    double y3 = y * y * y;
    y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
  }
  return y;
}
static inline double dem_jkr_cbrt(double x) {
  double y = dem_jkr_cbrt_halley(x);
  return y - (y * y * y - x) / (3.0 * y * y);
}

/* Largest real root s of s^4 - (4/3) s - A = 0 (the stable branch, s >= 3^(-1/3)).
 * A = alpha / delta_c. For A in [A_f (1 + 4e-16), A_f] (the last rounding units below the
 * break, which a caller's own rounding may produce) it returns DEM_JKR_SF; further below,
 * NAN (no contact there). The result never lies below DEM_JKR_SF.
 * Closed form: with c = u^3 = 1/9 + sqrt(1/81 + A^3/27), v = -A/(3u) = -A u^2/(3c) (the
 * division by c runs in parallel with the cube root), Q = u^2 - uv + v^2, m = (2/9)/Q:
 * sqrt(2m) = (2/3) sqrt(Q)/Q and 8/(3 sqrt(2m)) - 2m = 4 sqrt(Q) - (4/9)/Q. */
static inline double dem_jkr_root(double A) {
  if (A > 1e12) {
    if (A > 1e200) A = 1e200; /* guard: keeps s^6 finite for any finite input */
    double s = sqrt(sqrt(A));
    return s - (s * s * s * s - (4.0 / 3.0) * s - A) / (4.0 * s * s * s - 4.0 / 3.0);
  }
  if (!(A > DEM_JKR_AF)) return A >= DEM_JKR_AF * (1.0 + 4e-16) ? DEM_JKR_SF : NAN;
  double D = 1.0 / 81.0 + A * A * A / 27.0;
  double c = 1.0 / 9.0 + sqrt(D > 0.0 ? D : 0.0);
  double t = A / (3.0 * c);
  double u = dem_jkr_cbrt_halley(c);
  double v = -t * u * u;
  double Q = u * u - u * v + v * v;
  double iq = 1.0 / Q, sq = sqrt(Q);
  double w = 4.0 * sq - (4.0 / 9.0) * iq;
  double s = 0.5 * ((2.0 / 3.0) * sq * iq + sqrt(w > 0.0 ? w : 0.0));
  /* Newton polish. Next to the double root at A_f the step is at the level of the root's
   * own conditioning; it may not leave the stable branch (nor return NaN if d = 0). */
  double s3 = s * s * s;
  double r = (s3 * s - A) - (4.0 / 3.0) * s - DEM_JKR_43LO * s;
  double sn = s - r / (4.0 * s3 - 4.0 / 3.0);
  return sn > DEM_JKR_SF ? sn : DEM_JKR_SF;
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

/* Scales of a JKR curve of radius R (m; R* or a flattened radius): f_c = 3/2 pi Gamma R (N),
 * a_c = (9 pi Gamma R^2 / (8 E*))^(1/3) (m), delta_c = a_c^2 / R (m). ac may be NULL. */
static inline void dem_jkr_scales(double gamma, double Es, double R, double *fc, double *ac,
                                  double *dc) {
  *fc = 1.5 * M_PI * gamma * R;
  double q = 9.0 * M_PI * gamma / (8.0 * Es); /* a_c^3 / R^2, m */
  *dc = cbrt(q * q * R);                        /* (a_c^3)^(2/3) / R */
  if (ac) *ac = sqrt(*dc * R);
}

/* Dimensional forms (libdem/src/contact/jkr_geometry.c), on the same solver. gamma > 0. */

/* Contact radius a (m) on the stable branch at overlap alpha (m); NAN below the breakage
 * overlap alpha_f (bar the last rounding units, see dem_jkr_root). */
double dem_jkr_radius(double R, double Es, double gamma, double alpha);
/* alpha(a) (3.42) and F(a) (3.41) above. */
double dem_jkr_alpha(double R, double Es, double gamma, double a);
double dem_jkr_force(double R, double Es, double gamma, double a);
/* Breakage overlap alpha_f = A_f delta_c = -(3/4) (pi^2 Gamma^2 R / E*^2)^(1/3) (m, < 0). */
double dem_jkr_alpha_f(double R, double Es, double gamma);
/* Tangent stiffness dF/dalpha on the stable branch at contact radius a (N/m):
 * 2 E* a (3 - 3 r)/(3 - r), r = (a_c/a)^(3/2) (paper B2); 0 at the pull-off point a_c,
 * -> -infinity at breakage. */
double dem_jkr_stiffness(double R, double Es, double gamma, double a);

#endif
