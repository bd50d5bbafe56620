/* `hertz`: Hertz elastic contact with restitution-based viscous damping.
 *
 *   f_el = 4/3 E* sqrt(R*) alpha^{3/2}                    thesis eq (3.14)
 *   S_n  = d f_el / d alpha = 2 E* sqrt(R* alpha)          (N/m)
 *   f_d  = eta_H(e) sqrt(m* S_n) alpha_dot                 velocity-independent damping
 *
 * E* from eq (3.15) with the particle's (E, nu) and the wall's or second particle's
 * (wall_E, wall_nu; absent = same as the particle). With damping proportional to
 * sqrt(m* S_n) the restitution is independent of impact velocity; eta_H(e) is found by
 * root finding on the dimensionless impact (damping.c) so that the restitution is exactly e
 * when the contact ends at zero overlap with the tensile end force kept. No force for
 * alpha <= 0.
 */
#include <float.h>
#include <math.h>

#include "dem/contact.h"
#include "dem/material.h"
#include "hertz_kernel.h"

enum { C_ES = DEM_HERTZ_C_ES, C_ETA = DEM_HERTZ_C_ETA, C_E = DEM_HERTZ_C_E };

static const dem_coef_spec coefs[] = {
    DEM_COEF_ELASTIC,
    {"e", "-", "coefficient of restitution of the viscous damping", 1e-2, 1.0, 1.0},
};

static int set_coeffs(const dem_params *ps, double *c, dem_err *err) {
  c[C_ES] = dem_contact_reduced_modulus(ps);
  double e = dem_params_get_or(ps, "e", 1.0);
  c[C_E] = e;
  c[C_ETA] = dem_damping_eta_hertz(e, 0);
  if (c[C_ETA] < 0.0)
    return dem_err_set(err, DEM_EPHYSICS,
                       "%slaw 'hertz': no damping constant reproduces e = %g (allowed [0.01, 1])",
                       dem_params_origin(ps, "e"), e);
  return DEM_OK;
}

static void force(const double *c, const dem_geom *g, double *hist, double alpha,
                  double alpha_dot, dem_normal *out) {
  (void)hist;
  if (!(alpha > 0.0)) {
    dem_normal_zero(out);
    return;
  }
  dem_hertz_terms t; /* S_n = 2 E* sqrt(R* alpha), f_el = 4/3 E* sqrt(R*) alpha^{3/2} */
  dem_hertz_eval(c, g->R, g->m, alpha, alpha_dot, &t);
  out->k = t.k;
  out->f_el = t.f_el;
  out->f_damp = t.f_damp;
  out->f = out->f_el + out->f_damp;
  out->f_adh = 0.0;
  out->alpha_t = alpha > 0.0 ? alpha : 0.0; /* contact.h: max(alpha, 0) for Mindlin */
  out->contact = 1;
}

/* Stiffness at the elastic maximum overlap of an impact at v:
 * alpha_max = (15 m* v^2 / (16 E* sqrt(R*)))^{2/5}. */
static double kref(const double *c, const dem_geom *g, double v) {
  double amax = pow(15.0 * g->m * v * v / (16.0 * c[C_ES] * sqrt(g->R)), 0.4);
  return 2.0 * c[C_ES] * sqrt(g->R * amax);
}

const dem_law dem_law_hertz = {
    .name = "hertz",
    .title = "Hertz elastic + restitution-based viscous damping",
    .source = "thesis eqs (3.14)-(3.16); damping after (4.24)-(4.25), velocity-independent form",
    .ncoef = sizeof coefs / sizeof coefs[0],
    .coef = coefs,
    .nhist = 1,
    .flags = DEM_LAW_NONLINEAR,
    .set_coeffs = set_coeffs,
    .init = NULL,
    .force = force,
    .kref = kref,
};
