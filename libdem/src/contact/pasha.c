/* `pasha`: the thesis' new linear elasto-plastic-adhesive law, full form (thesis 4.1,
 * eqs 4.1-4.11, Appendix I, Fig 4.1). Forces F > 0 repulsive; f_ce, f_cp are magnitudes.
 *
 * Before yield (linear version of JKR, Fig 4.1 A-B-alpha_0), f_ce = 1.5 pi Gamma R* (4.1):
 *   first contact at alpha = 0 with F = -8/9 f_ce (like JKR);
 *   F = k_e alpha - 8/9 f_ce                  alpha >= alpha_B = -f_ce/(9 k_e)    (4.2)
 *   F = -k_e alpha - 10/9 f_ce                alpha_fe <= alpha < alpha_B          (Fig 4.1)
 *   breaks at alpha_fe = -5/9 f_ce/k_e (F = -5/9 f_ce); reversible; after breakage a
 *   never-yielded contact is forgotten (re-contact at alpha = 0 as a fresh one).
 * Yield at alpha_0 = 8/9 f_ce/k_e (where 4.2 crosses zero); plastic loading
 *   F = k_p (alpha - alpha_0)                                                        (4.3)
 * Unloading from alpha_max (F_max = k_p (alpha_max - alpha_0)), reversible:
 *   F = k_e (alpha - alpha_p),  alpha_p = alpha_max - F_max/k_e,  down to alpha_cp      (4.4)
 *   F = k_e (2 alpha_cp - alpha_p - alpha)   from alpha_cp down to alpha_fp           (4.5)
 *   breaks at alpha_fp = 13/9 alpha_cp - 4/9 alpha_p (F = -5/9 f_cp), (A1.5);
 *   re-contact after breakage at alpha_fp (thesis 4.1: "established at alpha_fp"),
 *   following E-D-C back up, and the plastic line beyond alpha_max.
 * Pull-off force from the energy balance W_ad = A_p Gamma (4.6)-(4.11), App. I:
 *   alpha_pd = alpha_p - alpha_0, A_p = pi (2 R* alpha_pd - alpha_pd^2),
 *   |W_ad| = 137/162 k_e (alpha_p - alpha_cp)^2   =>   f_cp = k_e (alpha_p - alpha_cp)
 *          = sqrt(162/137 k_e pi Gamma (2 R* alpha_pd - alpha_pd^2)),
 *   which is eq (4.10)-(4.11) rewritten: alpha_p^2 - C = 162 W_ad/(137 k_e) (no cancellation).
 * Decisions (docs/contact-laws.md):
 *   - f_cp = max(f_ce, energy value): the energy balance counts only the plastic area, which
 *     vanishes at alpha_pd -> 0; the thesis states f_cp is always above f_ce (4.1.1), and the
 *     floor makes the law continuous with its elastic part at alpha_max -> alpha_0.
 *   - alpha_pd is clamped to R* (A_p = pi R*^2 at most: the cap formula 4.7 falls beyond R*
 *     and its discriminant turns negative beyond 2 R*).
 *   - option ke_load = 1: the unloading stiffness after yield is the load-dependent k_e of
 *     eq (4.23) with maximum ke_max (uncapped, as the thesis states); the initial
 *     linear-JKR part keeps k_e.
 * Damping (4.24)-(4.25): k = k_e on the elastic parts, k_p on plastic loading, the unloading
 * k_e on 4.4 and 4.5 (slope magnitude). Sliding limit (4.27): f_adh = f_cp - f_ce after
 * yield, 0 before.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "dem/contact.h"
#include "epa.h"

static const dem_coef_spec coefs[] = {
    {"ke", "N/m", "elastic stiffness k_e (linear JKR part, unloading); >= kp", DBL_MIN, 1e12,
     NAN},
    {"kp", "N/m", "plastic stiffness k_p", DBL_MIN, 1e12, NAN},
    {"gamma", "J/m^2", "interface energy Gamma (f_ce = 1.5 pi Gamma R*, eq 4.1)", 0.0, 1e3,
     NAN},
    {"ke_max", "N/m", "maximum of the load-dependent unloading k_e (eq 4.23; with ke_load = 1)",
     0.0, 1e12, 0.0},
    {"ke_load", "-", "0: constant k_e; 1: load-dependent unloading k_e of eq (4.23)", 0.0, 1.0,
     0.0},
    {"e", "-", "coefficient of restitution of the viscous damping", 1e-3, 1.0, 1.0},
};

static int set_coeffs(const dem_params *ps, double *c, dem_err *err) {
  double ke = dem_params_get_or(ps, "ke", NAN), kp = dem_params_get_or(ps, "kp", NAN);
  double kemax = dem_params_get_or(ps, "ke_max", 0.0), gam = dem_params_get_or(ps, "gamma", 0);
  double load = dem_params_get_or(ps, "ke_load", 0.0);
  if (ke < kp)
    return dem_err_set(err, DEM_EPHYSICS,
                       "%slaw 'pasha': ke = %g N/m is less than kp = %g N/m: the plastic "
                       "deformation alpha_p - alpha_0 (eq 4.6) would be negative and the "
                       "discriminant alpha_p^2 - C of the pull-off equation (4.10) negative",
                       dem_params_origin(ps, "ke"), ke, kp);
  if (load != 0.0 && load != 1.0)
    return dem_err_set(err, DEM_ERANGE,
                       "%slaw 'pasha': ke_load = %g must be 0 (constant k_e) or 1 (load-dependent "
                       "k_e of eq 4.23)",
                       dem_params_origin(ps, "ke_load"), load);
  if (load == 1.0 && !(kemax > 0.0))
    return dem_err_set(err, DEM_EMISSING,
                       "law 'pasha': ke_load = 1 needs 'ke_max' (N/m, >= kp), the maximum of the "
                       "load-dependent k_e of eq 4.23");
  if (load == 1.0 && kemax < kp)
    return dem_err_set(err, DEM_EPHYSICS,
                       "%slaw 'pasha': ke_max = %g N/m is less than kp = %g N/m (eq 4.23 "
                       "needs ke_max >= kp)",
                       dem_params_origin(ps, "ke_max"), kemax, kp);
  c[DEM_PAS_KE] = ke;
  c[DEM_PAS_KP] = kp;
  c[DEM_PAS_FCE_R] = 1.5 * M_PI * gam;
  c[DEM_PAS_PIG] = M_PI * gam;
  c[DEM_PAS_KEMAX] = load == 1.0 ? kemax : 0.0;
  c[DEM_PAS_ETA] = dem_damping_eta_linear(dem_params_get_or(ps, "e", 1.0));
  return DEM_OK;
}

double dem_epa_ke_load_dependent(double kp, double ke_max, double R, double alpha_max) {
  double a = fmin(fmax(alpha_max, 0.0), R) / R;
  return kp + (2.0 * a - a * a) * (ke_max - kp); /* (r/R*)^2 = 2a/R* - (a/R*)^2 */
}

double dem_pasha_ke_unload(const double *c, double R, double alpha_max) {
  if (c[DEM_PAS_KEMAX] > 0.0)
    return dem_epa_ke_load_dependent(c[DEM_PAS_KP], c[DEM_PAS_KEMAX], R, alpha_max);
  return c[DEM_PAS_KE];
}

void dem_pasha_unload(const double *c, double R, double alpha_max, dem_epa_unload *u) {
  double kp = c[DEM_PAS_KP], fce = c[DEM_PAS_FCE_R] * R;
  double ke = dem_pasha_ke_unload(c, R, alpha_max);
  double a0 = 8.0 / 9.0 * fce / c[DEM_PAS_KE];
  u->ke = ke;
  u->alpha_0 = a0;
  u->alpha_max = alpha_max;
  u->f_max = kp * (alpha_max - a0);
  u->alpha_p = alpha_max - u->f_max / ke;
  double apd = fmin(fmax(u->alpha_p - a0, 0.0), R);
  double wad = c[DEM_PAS_PIG] * (2.0 * R * apd - apd * apd); /* (4.8), J */
  u->f_cp = fmax(sqrt(162.0 / 137.0 * ke * wad), fce);
  u->alpha_cp = u->alpha_p - u->f_cp / ke;
  u->alpha_fp = u->alpha_cp - 4.0 / 9.0 * u->f_cp / ke; /* (A1.5) */
  u->alpha_fe = NAN;
}

static void set_unload(const double *c, double R, double alpha_max, double *hist) {
  dem_epa_unload u;
  dem_pasha_unload(c, R, alpha_max, &u);
  hist[DEM_PAS_H_AMAX] = alpha_max;
  hist[DEM_PAS_H_KEU] = u.ke;
  hist[DEM_PAS_H_AP] = u.alpha_p;
  hist[DEM_PAS_H_ACP] = u.alpha_cp;
  hist[DEM_PAS_H_AFP] = u.alpha_fp;
  hist[DEM_PAS_H_FCP] = u.f_cp;
}

static void force(const double *c, const dem_geom *g, double *hist, double alpha,
                  double alpha_dot, dem_normal *out) {
  const double ke = c[DEM_PAS_KE], kp = c[DEM_PAS_KP];
  const double fce = c[DEM_PAS_FCE_R] * g->R, a0 = 8.0 / 9.0 * fce / ke;
  double state = hist[DEM_PAS_H_STATE], f, k, f_adh = 0.0;
  if (state == 0.0) {
    if (alpha < 0.0) { /* no contact forms at negative overlap */
      dem_normal_zero(out);
      return;
    }
    state = hist[DEM_PAS_H_STATE] = DEM_PAS_ELASTIC;
  }
  if (state == DEM_PAS_ELASTIC && alpha > a0) { /* first yield */
    state = hist[DEM_PAS_H_STATE] = DEM_PAS_PLASTIC;
    set_unload(c, g->R, alpha, hist);
  }
  if (state == DEM_PAS_ELASTIC) {
    if (alpha >= -fce / (9.0 * ke)) { /* B to alpha_0, (4.2) */
      f = ke * alpha - 8.0 / 9.0 * fce;
    } else if (alpha >= -5.0 / 9.0 * fce / ke) { /* A to B */
      f = -ke * alpha - 10.0 / 9.0 * fce;
    } else { /* broken at alpha_fe: elastic, nothing to remember */
      memset(hist, 0, sizeof(double) * DEM_PAS_NHIST);
      dem_normal_zero(out);
      return;
    }
    k = ke;
  } else {
    double amax = hist[DEM_PAS_H_AMAX], keu = hist[DEM_PAS_H_KEU];
    double ap = hist[DEM_PAS_H_AP], acp = hist[DEM_PAS_H_ACP];
    if (alpha >= amax) { /* plastic loading (4.3) */
      f = kp * (alpha - a0);
      k = kp;
      if (alpha > amax) set_unload(c, g->R, alpha, hist);
    } else if (alpha >= acp) { /* (4.4) */
      f = keu * (alpha - ap);
      k = keu;
    } else if (alpha >= hist[DEM_PAS_H_AFP]) { /* (4.5) */
      f = keu * (2.0 * acp - ap - alpha);
      k = keu;
    } else { /* broken beyond alpha_fp; the plastic memory stays */
      hist[DEM_PAS_H_STATE] = DEM_PAS_BROKEN;
      dem_normal_zero(out);
      return;
    }
    hist[DEM_PAS_H_STATE] = DEM_PAS_PLASTIC;
    f_adh = hist[DEM_PAS_H_FCP] - fce; /* (4.27) */
  }
  out->f_el = f;
  out->k = k;
  out->f_damp = c[DEM_PAS_ETA] * sqrt(g->m * k) * alpha_dot;
  out->f = out->f_el + out->f_damp;
  out->f_adh = f_adh;
  out->alpha_t = alpha > 0.0 ? alpha : 0.0; /* contact.h: max(alpha, 0) for Mindlin */
  out->contact = 1;
}

/* The largest branch stiffness of an impact at v: the unloading k_e at the alpha_max of the
 * energy balance (4.13). */
static double kref(const double *c, const dem_geom *g, double v) {
  double ke = c[DEM_PAS_KE], kp = c[DEM_PAS_KP];
  double a0 = 8.0 / 9.0 * c[DEM_PAS_FCE_R] * g->R / ke;
  double amax = a0 + sqrt((g->m * v * v + ke * a0 * a0) / kp);
  return fmax(ke, dem_pasha_ke_unload(c, g->R, amax));
}

const dem_law dem_law_pasha = {
    .name = "pasha",
    .title = "Pasha (2013) linear elasto-plastic-adhesive, full form",
    .source = "thesis eqs (4.1)-(4.11), (4.21)-(4.25), (4.27), App. I, Fig 4.1",
    .ncoef = sizeof coefs / sizeof coefs[0],
    .coef = coefs,
    .nhist = DEM_PAS_NHIST,
    .flags = DEM_LAW_ADHESIVE | DEM_LAW_PLASTIC,
    .set_coeffs = set_coeffs,
    .init = NULL,
    .force = force,
    .kref = kref,
};
