/* `walton-braun`: Walton and Braun's linear elasto-plastic normal contact (thesis section
 * 3.4.2.3, eqs 3.36-3.38), with restitution-based viscous damping.
 *
 *   loading      F = k_p alpha                      (3.36), alpha >= alpha_max
 *   unloading    F = k_e (alpha - alpha_0)          (3.37), alpha_0 < alpha < alpha_max
 *                alpha_0 = alpha_max - F_max / k_e  (permanent overlap: the line passes
 *                                                    through (alpha_max, F_max))
 *   apart        F = 0 for alpha <= alpha_0; the permanent overlap is remembered
 *   reloading    along the unloading line up to alpha_max, then k_p again.
 *
 * k_e is either a constant (coefficient `ke`, at least `kp`) or load-dependent,
 * k_e = k_p + S F_max (3.38, coefficient `S` in 1/m so that S F_max is in N/m), fixed at the
 * turning point for the unloading and reloading that follow. Give one of the two. The
 * restitution of the undamped law is e = sqrt(k_p / k_e) (thesis 3.4.2.3).
 *
 * Damping f_d = eta(e) sqrt(m* k) alpha_dot with the linear constant eta(e)
 * (dem_damping_eta_linear: exact restitution e for a linear spring) and k = k_p on loading,
 * k_e on unloading/reloading.
 *
 * History: state (0 fresh, 1 loaded), alpha_max, F_max, k_e in use, alpha_0.
 */
#include <float.h>
#include <math.h>

#include "dem/contact.h"

enum { C_KP, C_KE, C_S, C_ETA };
enum { H_AMAX = 1, H_FMAX, H_KE, H_A0, NHIST };

static const dem_coef_spec coefs[] = {
    {"kp", "N/m", "plastic (loading) stiffness k_p", DBL_MIN, 1e12, NAN},
    {"ke", "N/m", "elastic (unloading) stiffness k_e >= k_p (absent when S is given)", DBL_MIN,
     1e12, -1.0},
    {"S", "1/m", "slope of k_e = k_p + S F_max (3.38); 0: constant ke", 0.0, 1e15, 0.0},
    {"e", "-", "coefficient of restitution of the viscous damping", 1e-3, 1.0, 1.0},
};

static int set_coeffs(const dem_params *ps, double *c, dem_err *err) {
  double kp = dem_params_get_or(ps, "kp", NAN), ke = dem_params_get_or(ps, "ke", -1.0);
  double S = dem_params_get_or(ps, "S", 0.0);
  if (S > 0.0 && ke > 0.0)
    return dem_err_set(err, DEM_EUNSUPPORTED,
                       "%slaw 'walton-braun': give either 'ke' (constant, here %g N/m) or 'S' "
                       "(k_e = k_p + S F_max, here %g 1/m), not both",
                       dem_params_origin(ps, "ke"), ke, S);
  if (S == 0.0 && !(ke > 0.0))
    return dem_err_set(err, DEM_EMISSING,
                       "law 'walton-braun' needs coefficient 'ke' (elastic unloading stiffness, "
                       "N/m; allowed [kp = %g, 1e+12]) or 'S' > 0 (1/m)",
                       kp);
  if (S == 0.0 && !(ke >= kp))
    return dem_err_set(err, DEM_ERANGE,
                       "%slaw 'walton-braun': coefficient 'ke' = %g N/m is outside the allowed "
                       "range [kp = %g, 1e+12] (unloading must be at least as stiff as loading)",
                       dem_params_origin(ps, "ke"), ke, kp);
  c[C_KP] = kp;
  c[C_KE] = S > 0.0 ? 0.0 : ke;
  c[C_S] = S;
  c[C_ETA] = dem_damping_eta_linear(dem_params_get_or(ps, "e", 1.0));
  return DEM_OK;
}

static void force(const double *c, const dem_geom *g, double *hist, double alpha,
                  double alpha_dot, dem_normal *out) {
  double f, k;
  if (alpha > hist[H_AMAX]) {
    /* Plastic loading, (3.36); fresh history has alpha_max = 0. */
    k = c[C_KP];
    f = k * alpha;
    double ke = c[C_S] > 0.0 ? c[C_KP] + c[C_S] * f : c[C_KE]; /* (3.38) or constant */
    hist[DEM_HIST_STATE] = 1.0;
    hist[H_AMAX] = alpha;
    hist[H_FMAX] = f;
    hist[H_KE] = ke;
    hist[H_A0] = alpha - f / ke;
  } else {
    /* Elastic unloading / reloading, (3.37). */
    double d = alpha - hist[H_A0];
    if (hist[DEM_HIST_STATE] == 0.0 || !(d > 0.0)) {
      dem_normal_zero(out);
      return;
    }
    k = hist[H_KE];
    f = k * d;
  }
  out->k = k;
  out->f_el = f;
  out->f_damp = c[C_ETA] * sqrt(g->m * k) * alpha_dot;
  out->f = out->f_el + out->f_damp;
  out->f_adh = 0.0;
  out->alpha_t = alpha > 0.0 ? alpha : 0.0; /* contact.h: max(alpha, 0) for Mindlin */
  out->contact = 1;
}

/* The largest stiffness of an impact at v: k_e, or k_p + S F_max with the undamped plastic
 * loading F_max = v sqrt(m* k_p). */
static double kref(const double *c, const dem_geom *g, double v) {
  if (c[C_S] > 0.0) return c[C_KP] + c[C_S] * v * sqrt(g->m * c[C_KP]);
  return c[C_KE];
}

const dem_law dem_law_walton_braun = {
    .name = "walton-braun",
    .title = "Walton-Braun linear plastic loading / elastic unloading (optional ke = kp + S F_max)",
    .source = "thesis eqs (3.36)-(3.38)",
    .ncoef = sizeof coefs / sizeof coefs[0],
    .coef = coefs,
    .nhist = NHIST,
    .flags = DEM_LAW_PLASTIC,
    .set_coeffs = set_coeffs,
    .init = NULL,
    .force = force,
    .kref = kref,
};
