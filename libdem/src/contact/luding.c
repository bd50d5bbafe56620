/* `luding`: the linear elasto-plastic-adhesive law of Luding (2008), thesis section 3.4.4.5,
 * eqs (3.71)-(3.75), Fig 3.26, as used by the thesis in section 4.1.5 (with a constant
 * adhesive force f_0 at first contact, Table 4.2 and Appendix III).
 *
 * Luding's hysteretic force f_h (his k_1 = k_p, k_2 = k_e(alpha_max)) with
 * delta_0 the zero of the current un/reloading line:
 *
 *   f_h = k_p alpha                 if k_e (alpha - delta_0) >= k_p alpha       plastic loading
 *   f_h = k_e (alpha - delta_0)     if k_p alpha > k_e (alpha - delta_0) > -k_c alpha
 *   f_h = -k_c alpha                if k_e (alpha - delta_0) <= -k_c alpha      adhesive branch
 *
 * and the normal force  F = f_h - f_0  for alpha >= 0; the contact breaks at alpha < 0
 * (Luding: "contacts break at zero overlap regardless of history", the flaw the thesis
 * criticises), and every memory is lost with it: re-contact starts a fresh contact.
 * With f_0 the loading line is F = k_p (alpha - alpha_0), alpha_0 = f_0/k_p, and the unloading
 * line crosses F = 0 at alpha_p = delta_0 + f_0/k_e and F = -f_0 at alpha_fe = delta_0,
 * exactly the geometry of the thesis' Appendix III (Fig A3.1b); f_0 = 0 is Luding's law.
 *
 * History: on the plastic line alpha_max = alpha, k_e = k_e(alpha_max) and
 * delta_0 = (1 - k_p/k_e) alpha_max. On the adhesive branch Luding moves the unloading line
 * so that reloading starts from the current point on a line PARALLEL to the unloading line
 * (thesis 3.4.4.5): delta_0 = alpha (1 + k_c/k_e) with k_e kept, and alpha_max is adapted
 * to where that line meets the plastic line, alpha_max = delta_0 k_e/(k_e - k_p) (Luding's
 * delta_max = (k_2 + k_c)/(k_2 - k_1) delta). Reloading then follows the new line up to
 * that (smaller) alpha_max and the plastic line beyond it, where k_e(alpha_max) is
 * re-evaluated (the force is continuous; the slope of the next unloading line may differ).
 *
 * Elastic stiffness (3.71), (3.74):  alpha* = ke_max/(ke_max - k_p) phi_f 2 R*,
 *   k_e = k_p + (ke_max - k_p) alpha_max/alpha*   for alpha_max < alpha*,
 *   k_e = ke_max beyond (ke_capped = 1, Luding's law, the default); with ke_capped = 0 the
 *   linear growth continues without bound (the variant of thesis 4.1.5, last paragraph).
 *
 * Damping (thesis 4.24-4.25): f_d = eta(e) sqrt(m* k) alpha_dot with k the magnitude of the
 * slope of the branch in use: k_p (plastic), k_e (un/reloading), k_c (adhesive branch).
 * Sliding limit (3.75): mu (F + k_c alpha + f_0), i.e. f_adh = k_c alpha + f_0 (the reference
 * level is the adhesive branch -k_c alpha - f_0; with f_0 = 0 this is eq 3.75).
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "dem/contact.h"
#include "epa.h"

static const dem_coef_spec coefs[] = {
    {"kp", "N/m", "plastic loading stiffness k_p (Luding's k_1)", DBL_MIN, 1e12, NAN},
    {"ke_max", "N/m", "maximum elastic un/reloading stiffness (eq 3.71, 3.74); > kp", DBL_MIN,
     1e12, NAN},
    {"kc", "N/m", "adhesive stiffness k_c of the branch -k_c alpha", 0.0, 1e12, NAN},
    {"phi_f", "-", "dimensionless plasticity depth (eq 3.71)", DBL_MIN, 1.0, NAN},
    {"f0", "N", "constant adhesive force at first contact (thesis Table 4.2: 8/9 f_ce)", 0.0,
     1e3, 0.0},
    {"ke_capped", "-",
     "1: k_e = ke_max for alpha_max >= alpha* (Luding); 0: k_e(alpha_max) uncapped", 0.0, 1.0,
     1.0},
    {"e", "-", "coefficient of restitution of the viscous damping", 1e-3, 1.0, 1.0},
};

static int set_coeffs(const dem_params *ps, double *c, dem_err *err) {
  double kp = dem_params_get_or(ps, "kp", NAN), kemax = dem_params_get_or(ps, "ke_max", NAN);
  double capped = dem_params_get_or(ps, "ke_capped", 1.0);
  if (!(kemax > kp))
    return dem_err_set(err, DEM_EPHYSICS,
                       "%slaw 'luding': ke_max = %g N/m must exceed kp = %g N/m (the "
                       "un/reloading line must be stiffer than plastic loading; eq 3.71 "
                       "divides by ke_max - kp)",
                       dem_params_origin(ps, "ke_max"), kemax, kp);
  if (capped != 0.0 && capped != 1.0)
    return dem_err_set(err, DEM_ERANGE,
                       "%slaw 'luding': ke_capped = %g must be 0 (uncapped k_e(alpha_max)) or 1 "
                       "(capped at ke_max beyond alpha*)",
                       dem_params_origin(ps, "ke_capped"), capped);
  c[DEM_LUD_KP] = kp;
  c[DEM_LUD_KEMAX] = kemax;
  c[DEM_LUD_KC] = dem_params_get_or(ps, "kc", NAN);
  c[DEM_LUD_ASTAR] = kemax / (kemax - kp) * dem_params_get_or(ps, "phi_f", NAN) * 2.0;
  c[DEM_LUD_F0] = dem_params_get_or(ps, "f0", 0.0);
  c[DEM_LUD_CAPPED] = capped;
  c[DEM_LUD_ETA] = dem_damping_eta_linear(dem_params_get_or(ps, "e", 1.0));
  return DEM_OK;
}

double dem_luding_ke(const double *c, double R, double alpha_max) {
  double astar = c[DEM_LUD_ASTAR] * R;
  if (c[DEM_LUD_CAPPED] != 0.0 && alpha_max >= astar) return c[DEM_LUD_KEMAX];
  return c[DEM_LUD_KP] + (c[DEM_LUD_KEMAX] - c[DEM_LUD_KP]) * alpha_max / astar;
}

void dem_luding_unload(const double *c, double R, double alpha_max, dem_epa_unload *u) {
  double kp = c[DEM_LUD_KP], kc = c[DEM_LUD_KC], f0 = c[DEM_LUD_F0];
  double ke = dem_luding_ke(c, R, alpha_max);
  double d0 = (1.0 - kp / ke) * alpha_max;
  u->ke = ke;
  u->alpha_0 = f0 / kp;
  u->alpha_max = alpha_max;
  u->f_max = kp * alpha_max - f0;
  u->alpha_fe = d0;
  u->alpha_p = d0 + f0 / ke;
  /* Unloading line meets the adhesive branch: k_e (a - d0) = -k_c a. */
  u->alpha_cp = ke * d0 / (ke + kc);
  u->f_cp = kc * u->alpha_cp + f0;
  u->alpha_fp = 0.0;
}

static void force(const double *c, const dem_geom *g, double *hist, double alpha,
                  double alpha_dot, dem_normal *out) {
  if (alpha < 0.0) { /* separated: Luding's contact is gone, with all its memory */
    if (hist[DEM_LUD_H_STATE] != 0.0) memset(hist, 0, sizeof(double) * DEM_LUD_NHIST);
    dem_normal_zero(out);
    return;
  }
  const double kp = c[DEM_LUD_KP], kc = c[DEM_LUD_KC];
  if (hist[DEM_LUD_H_STATE] == 0.0) { /* first contact at alpha >= 0 */
    hist[DEM_LUD_H_AMAX] = 0.0;
    hist[DEM_LUD_H_K2] = kp; /* k_e(0) = k_p, eq (3.74) */
    hist[DEM_LUD_H_D0] = 0.0;
  }
  double k2 = hist[DEM_LUD_H_K2], d0 = hist[DEM_LUD_H_D0];
  double line = k2 * (alpha - d0), fh, k;
  if (line >= kp * alpha) { /* plastic loading; alpha >= alpha_max here */
    fh = kp * alpha;
    k = kp;
    k2 = dem_luding_ke(c, g->R, alpha);
    hist[DEM_LUD_H_AMAX] = alpha;
    hist[DEM_LUD_H_K2] = k2;
    hist[DEM_LUD_H_D0] = (1.0 - kp / k2) * alpha;
    hist[DEM_LUD_H_STATE] = DEM_LUD_PLASTIC;
  } else if (line <= -kc * alpha) { /* adhesive branch: move the line through this point */
    fh = -kc * alpha;
    k = kc;
    d0 = alpha * (1.0 + kc / k2);
    hist[DEM_LUD_H_D0] = d0;
    hist[DEM_LUD_H_AMAX] = (k2 > kp) ? d0 * k2 / (k2 - kp) : 0.0;
    hist[DEM_LUD_H_STATE] = DEM_LUD_ADHESIVE;
  } else { /* un/reloading */
    fh = line;
    k = k2;
    hist[DEM_LUD_H_STATE] = DEM_LUD_ELASTIC;
  }
  out->f_el = fh - c[DEM_LUD_F0];
  out->k = k;
  out->f_damp = c[DEM_LUD_ETA] * sqrt(g->m * k) * alpha_dot;
  out->f = out->f_el + out->f_damp;
  out->f_adh = kc * alpha + c[DEM_LUD_F0];
  out->alpha_t = alpha > 0.0 ? alpha : 0.0; /* contact.h: max(alpha, 0) for Mindlin */
  out->contact = 1;
}

/* The largest branch stiffness of an impact at v: k_e at the alpha_max of eq (4.18). */
static double kref(const double *c, const dem_geom *g, double v) {
  double kp = c[DEM_LUD_KP], a0 = c[DEM_LUD_F0] / kp;
  double amax = a0 + sqrt(a0 * a0 + g->m * v * v / kp);
  double k = dem_luding_ke(c, g->R, amax);
  return fmax(fmax(k, kp), c[DEM_LUD_KC]);
}

const dem_law dem_law_luding = {
    .name = "luding",
    .title = "Luding (2008) linear elasto-plastic-adhesive",
    .source = "thesis eqs (3.71)-(3.75), section 3.4.4.5, App. III",
    .ncoef = sizeof coefs / sizeof coefs[0],
    .coef = coefs,
    .nhist = DEM_LUD_NHIST,
    .flags = DEM_LAW_ADHESIVE | DEM_LAW_PLASTIC,
    .set_coeffs = set_coeffs,
    .init = NULL,
    .force = force,
    .kref = kref,
};
