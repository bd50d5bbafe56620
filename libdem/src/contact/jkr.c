/* `jkr`: full JKR elastic-adhesive contact (thesis section 3.4.3.1, eqs 3.40-3.42;
 * paper Appendix B, eqs B1-B11), with restitution-based viscous damping.
 *
 * The contact radius a follows from the overlap through eq (3.42); dem/jkr.h (the solver
 * shared with `thornton-ning`) solves it in closed form and derives the landmarks. Branches (history word: 0 apart, 1 in contact):
 *
 *   apart, alpha <  0:                 no force (the surfaces approach without attraction)
 *   apart, alpha >= 0:                 the contact forms: F jumps to -8/9 f_c (jump-in)
 *   in contact, alpha >= alpha_f:      F on the JKR curve (3.41), loading and unloading alike
 *   in contact, alpha <  alpha_f:      the contact breaks (F was -5/9 f_c at alpha_f)
 *
 * alpha_f = -(3/4) (pi^2 Gamma^2 R* / E*^2)^(1/3), f_c = 3/2 pi Gamma R*. A broken contact
 * re-forms only at alpha = 0 again (hysteresis between alpha_f and 0: the work of adhesion,
 * 7.09 (Gamma^5 R*^4 / E*^2)^(1/3), is lost in every contact).
 *
 * Damping: f_d = eta_H(e) sqrt(m* k_d) alpha_dot with k_d = max(dF/dalpha, 0) and eta_H the
 * velocity-independent Hertz constant (damping.c): the JKR curve tends to Hertz at large
 * overlap, so e is the restitution at high impact velocity. dF/dalpha is positive on the whole
 * curve above the pull-off point (s > 1, alpha > -delta_c/3) and falls to zero there; on the
 * short stretch from the pull-off point to the break (alpha_f < alpha < -delta_c/3) it is
 * negative (the branch that is unstable under force control) and tends to -infinity at the
 * break, so there the damping is zero. k_d is continuous and is also what `k` reports.
 * Sliding limit (thesis 3.49): mu (F_n + 2 f_c), so f_adh = 2 f_c while in contact.
 */
#include <float.h>
#include <math.h>

#include "dem/contact.h"
#include "dem/material.h"
#include "dem/jkr.h"
#include "jkr_law.h"

const dem_coef_spec dem_jkrlaw_coefs[] = {
    DEM_COEF_ELASTIC,
    {"gamma", "J/m^2", "interface energy Gamma (f_c = 1.5 pi Gamma R*)", 1e-6, 1e4, NAN},
    {"e", "-", "restitution of the viscous damping (reached at high impact velocity)", 1e-2, 1.0,
     1.0},
};

int dem_jkrlaw_set_coeffs(const dem_params *ps, double *c, dem_err *err) {
  c[DEM_JKR_C_ES] = dem_contact_reduced_modulus(ps);
  c[DEM_JKR_C_GAMMA] = dem_params_get_or(ps, "gamma", NAN);
  double e = dem_params_get_or(ps, "e", 1.0);
  c[DEM_JKR_C_E] = e;
  c[DEM_JKR_C_ETA] = dem_damping_eta_hertz(e, 0);
  if (c[DEM_JKR_C_ETA] < 0.0)
    return dem_err_set(err, DEM_EPHYSICS,
                       "%sjkr law: no damping constant reproduces e = %g (allowed [0.01, 1])",
                       dem_params_origin(ps, "e"), e);
  return DEM_OK;
}

void dem_jkrlaw_force(const double *c, const dem_geom *g, double *hist, double alpha,
                   double alpha_dot, dem_normal *out, int break_at_zero) {
  if (hist[DEM_HIST_STATE] == 0.0) {
    if (!(alpha >= 0.0)) {
      dem_normal_zero(out);
      return;
    }
    /* Jump-in at alpha = 0 (thesis 3.4.3.1): cache the scales of this contact. */
    double dc;
    hist[DEM_HIST_STATE] = 1.0;
    dem_jkr_scales(c[DEM_JKR_C_GAMMA], c[DEM_JKR_C_ES], g->R, &hist[DEM_JKR_H_FC], NULL, &dc);
    hist[DEM_JKR_H_IDC] = 1.0 / dc;
    hist[DEM_JKR_H_DC] = dc;
  }
  double fc = hist[DEM_JKR_H_FC], idc = hist[DEM_JKR_H_IDC];
  double A = alpha * idc;
  if (break_at_zero ? !(alpha >= 0.0) : !(A >= DEM_JKR_AF)) {
    hist[DEM_HIST_STATE] = 0.0;
    dem_normal_zero(out);
    return;
  }
  double s = dem_jkr_root(A);
  double k = fc * idc * dem_jkr_khat(s);
  if (!(k > 0.0)) k = 0.0;
  out->k = k;
  out->f_el = fc * dem_jkr_fhat(s);
  out->f_damp = c[DEM_JKR_C_ETA] > 0.0 ? c[DEM_JKR_C_ETA] * sqrt(g->m * k) * alpha_dot : 0.0;
  out->f = out->f_el + out->f_damp;
  out->f_adh = 2.0 * fc;
  double s2 = s * s;
  out->alpha_t = s2 * s2 * hist[DEM_JKR_H_DC]; /* a^2/R* = delta_c s^4 (dem/jkr.h) */
  out->contact = 1;
}

/* Stiffness at the maximum overlap of an impact at v, estimated as the Hertz maximum
 * overlap (15 m* v^2 / (16 E* sqrt(R*)))^(2/5) shifted by the zero-force overlap alpha_0
 * (the JKR curve is close to Hertz shifted by alpha_0 at large load); never below the
 * stiffness at alpha_0. */
double dem_jkrlaw_kref(const double *c, const dem_geom *g, double v) {
  double Es = c[DEM_JKR_C_ES], fc, dc;
  dem_jkr_scales(c[DEM_JKR_C_GAMMA], Es, g->R, &fc, NULL, &dc);
  double ahz = pow(15.0 * g->m * v * v / (16.0 * Es * sqrt(g->R)), 0.4);
  double a0 = (2.0 / 3.0) * cbrt(2.0) * dc;
  return (fc / dc) * dem_jkr_khat(dem_jkr_root((ahz + a0) / dc));
}

static void force(const double *c, const dem_geom *g, double *hist, double alpha,
                  double alpha_dot, dem_normal *out) {
  dem_jkrlaw_force(c, g, hist, alpha, alpha_dot, out, 0);
}

const dem_law dem_law_jkr = {
    .name = "jkr",
    .title = "JKR elastic-adhesive (full: contact radius from the overlap), breaks at alpha_f",
    .source = "thesis eqs (3.40)-(3.42); paper eqs (B1)-(B11)",
    .ncoef = DEM_JKR_NCOEFS,
    .coef = dem_jkrlaw_coefs,
    .nhist = DEM_JKR_NHIST,
    .flags = DEM_LAW_ADHESIVE | DEM_LAW_NONLINEAR,
    .set_coeffs = dem_jkrlaw_set_coeffs,
    .init = NULL,
    .force = force,
    .kref = dem_jkrlaw_kref,
};
