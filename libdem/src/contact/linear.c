/* `linear`: the linear spring-dashpot of Cundall and Strack (thesis section 3.4.1.1).
 *
 *   f_el = k_n alpha                              thesis eq (3.9)
 *   f_d  = eta(e) sqrt(m* k_n) alpha_dot          thesis eqs (4.24)-(4.25)
 *
 * for alpha > 0; no force otherwise. With this damping the coefficient of restitution is
 * exactly e and the contact lasts pi / sqrt(k_n/m* (1 - zeta^2)), zeta = eta / 2, when the
 * contact is taken to end where the overlap returns to zero (the tensile damping force just
 * before separation is kept; a caller may clip it).
 */
#include <float.h>
#include <math.h>

#include "dem/contact.h"

enum { C_KN, C_ETA };

static const dem_coef_spec coefs[] = {
    {"kn", "N/m", "normal spring stiffness", DBL_MIN, 1e12, NAN},
    {"e", "-", "coefficient of restitution of the viscous damping", 1e-3, 1.0, 1.0},
};

static int set_coeffs(const dem_params *ps, double *c, dem_err *err) {
  (void)err;
  c[C_KN] = dem_params_get_or(ps, "kn", NAN);
  c[C_ETA] = dem_damping_eta_linear(dem_params_get_or(ps, "e", 1.0));
  return DEM_OK;
}

static void force(const double *c, const dem_geom *g, double *hist, double alpha,
                  double alpha_dot, dem_normal *out) {
  (void)hist;
  if (!(alpha > 0.0)) {
    dem_normal_zero(out);
    return;
  }
  out->k = c[C_KN];
  out->f_el = c[C_KN] * alpha;
  out->f_damp = c[C_ETA] * sqrt(g->m * c[C_KN]) * alpha_dot;
  out->f = out->f_el + out->f_damp;
  out->f_adh = 0.0;
  out->alpha_t = alpha > 0.0 ? alpha : 0.0; /* contact.h: max(alpha, 0) for Mindlin */
  out->contact = 1;
}

static double kref(const double *c, const dem_geom *g, double v) {
  (void)g;
  (void)v;
  return c[C_KN];
}

const dem_law dem_law_linear = {
    .name = "linear",
    .title = "linear spring-dashpot (Cundall-Strack)",
    .source = "thesis eqs (3.9), (4.24)-(4.25)",
    .ncoef = sizeof coefs / sizeof coefs[0],
    .coef = coefs,
    .nhist = 1,
    .flags = 0,
    .set_coeffs = set_coeffs,
    .init = NULL,
    .force = force,
    .kref = kref,
};
