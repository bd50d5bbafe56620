/* JKR geometry in dimensional form (dem/jkr.h), on the one contact-radius solver
 * dem_jkr_root. Thesis eqs (3.40)-(3.42), paper (B1)-(B3).
 */
#include <math.h>

#include "dem/jkr.h"

double dem_jkr_radius(double R, double Es, double gamma, double alpha) {
  double fc, ac, dc;
  dem_jkr_scales(gamma, Es, R, &fc, &ac, &dc);
  /* alpha * (1/delta_c), the laws' own arithmetic (they cache 1/delta_c): the same alpha
   * gives the same a to the last bit here and in a law. */
  double s = dem_jkr_root(alpha * (1.0 / dc));
  return ac * s * s; /* a = a_c s^2; NAN below alpha_f */
}

double dem_jkr_alpha(double R, double Es, double gamma, double a) {
  return a * a / R - sqrt(2.0 * M_PI * gamma * a / Es);
}

double dem_jkr_force(double R, double Es, double gamma, double a) {
  return 4.0 * Es * a * a * a / (3.0 * R) - sqrt(8.0 * M_PI * gamma * Es * a * a * a);
}

double dem_jkr_alpha_f(double R, double Es, double gamma) {
  double fc, dc;
  dem_jkr_scales(gamma, Es, R, &fc, NULL, &dc);
  return DEM_JKR_AF * dc;
}

double dem_jkr_stiffness(double R, double Es, double gamma, double a) {
  double ac3 = 9.0 * M_PI * gamma * R * R / (8.0 * Es);
  double r = sqrt(ac3 / (a * a * a));
  return 2.0 * Es * a * (3.0 - 3.0 * r) / (3.0 - r);
}
