/* JKR contact radius from the overlap, exactly (dem/jkr_radius.h).
 *
 * x^4 - x - q = 0 (depressed quartic, no x^2 term). Ferrari: (x^2 + m)^2 = 2m x^2 + x + q + m^2;
 * the right side is a perfect square when its discriminant vanishes, 1 = 8m (q + m^2), i.e.
 * m^3 + q m - 1/8 = 0 (resolvent). Then (x^2 + m)^2 = 2m (x + 1/(4m))^2 and the largest root is
 *   x = ( sqrt(2m) + sqrt(sqrt(2/m) - 2m) ) / 2.
 * The resolvent has discriminant D = 1/256 + q^3/27 >= 0 exactly on q >= q_min (D = 0 at the
 * breakage point, where m^3 = 1/2 and the two large roots merge), so Cardano gives its single
 * real root m = u + v, u = cbrt(1/16 + sqrt D), v = -q/(3u). For q > 0, u + v cancels; there
 * m = (1/8) / (u^2 - u v + v^2) (from u^3 + v^3 = 1/8) has only positive terms. One Newton
 * step on x^4 - x - q then removes the remaining rounding (accepted only if it lowers the
 * residual: near q_min the root is double and Newton is ill-conditioned).
 * Cost: one cbrt and four sqrt; no iteration, no warm start from history.
 */
#include <math.h>

#include "dem/jkr_radius.h"

double dem_jkr_quartic_root(double q) {
  if (!(q >= DEM_JKR_QMIN)) {
    /* Allow the last rounding unit below q_min: that is the breakage point itself. */
    if (q >= DEM_JKR_QMIN * (1.0 + 4e-16)) q = DEM_JKR_QMIN;
    else return NAN;
  }
  double sd;
  if (q > 1e6) { /* avoid overflow of q^3: sqrt(D) = sqrt(q^3/27) sqrt(1 + 27/(256 q^3)) */
    sd = q * sqrt(q / 27.0) * sqrt(1.0 + 27.0 / (256.0 * q * q * q));
  } else {
    double d = 1.0 / 256.0 + q * q * q / 27.0;
    sd = d > 0.0 ? sqrt(d) : 0.0;
  }
  double u = cbrt(0.0625 + sd), v = -q / (3.0 * u), m;
  if (q > 0.0)
    m = 0.125 / (u * u - u * v + v * v);
  else
    m = u + v;
  double w = sqrt(2.0 / m) - 2.0 * m;
  double x = 0.5 * (sqrt(2.0 * m) + (w > 0.0 ? sqrt(w) : 0.0));
  /* Newton polish. */
  double x3 = x * x * x, r = x3 * x - x - q, d = 4.0 * x3 - 1.0;
  if (d > 0.0) {
    double xn = x - r / d, xn3 = xn * xn * xn, rn = xn3 * xn - xn - q;
    if (fabs(rn) < fabs(r)) x = xn;
  }
  return x;
}

/* c = R sqrt(2 pi Gamma / E*): the scale of s = sqrt(a). */
static double cscale(double R, double Es, double gamma) {
  return R * sqrt(2.0 * M_PI * gamma / Es);
}

double dem_jkr_radius(double R, double Es, double gamma, double alpha) {
  double c = cscale(R, Es, gamma), c13 = cbrt(c);
  double x = dem_jkr_quartic_root(R * alpha / (c * c13));
  return c13 * c13 * x * x;
}

double dem_jkr_alpha(double R, double Es, double gamma, double a) {
  return a * a / R - sqrt(2.0 * M_PI * gamma * a / Es);
}

double dem_jkr_force(double R, double Es, double gamma, double a) {
  return 4.0 * Es * a * a * a / (3.0 * R) - sqrt(8.0 * M_PI * gamma * Es * a * a * a);
}

double dem_jkr_alpha_f(double R, double Es, double gamma) {
  double c = cscale(R, Es, gamma);
  return DEM_JKR_QMIN * c * cbrt(c) / R;
}

double dem_jkr_stiffness(double R, double Es, double gamma, double a) {
  double ac3 = 9.0 * M_PI * gamma * R * R / (8.0 * Es);
  double r = sqrt(ac3 / (a * a * a));
  return 2.0 * Es * a * (3.0 - 3.0 * r) / (3.0 - r);
}
