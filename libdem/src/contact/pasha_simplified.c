/* `pasha-simplified`: the thesis' simplified linear elasto-plastic-adhesive law (thesis
 * 4.1.4-4.1.5, Fig 4.20, eq 4.17; the law of the bulk simulations, Table 6.2).
 * Forces F > 0 repulsive; f0, f0p, f_cp and f_ce are magnitudes (> 0).
 *
 *   first contact at alpha = 0 with F = -f0; plastic loading from there
 *   F = k_p (alpha - alpha_0),  alpha_0 = f0/k_p                             (Fig 4.20 A-B)
 * Unloading from alpha_max (F_max = k_p (alpha_max - alpha_0)), reversible:
 *   F = k_e (alpha - alpha_p),  alpha_p = alpha_max - F_max/k_e               (4.4, B-C)
 *   down to the linear pull-off locus  F = -(k_cp alpha + f0p)                (4.17)
 *   reached at alpha_cp = (k_e alpha_p - f0p)/(k_e + k_cp), f_cp = k_cp alpha_cp + f0p;
 *   F = k_e (2 alpha_cp - alpha_p - alpha)                                    (4.5, C-D)
 *   to zero force at alpha_fp = 2 alpha_cp - alpha_p, where the contact breaks (4.1.5:
 *   "at alpha_fp the contact force is zero"). After breakage the plastic memory stays; the
 *   contact re-forms at alpha_fp (as in the full law, 4.1) with F = 0, so the force is
 *   continuous. alpha_cp may be negative (small alpha_max): the locus is then extended.
 * Where only Gamma is given (physics notes): f0 = 8/9 * 1.5 pi Gamma R*, f0p = f0 unless
 * given. Both are computed from R* in `force` (two multiplications); `init` checks
 * f0p >= f0 for the geometry (otherwise the locus lies above the loading line near
 * alpha = 0 and the unloading line could meet it before alpha_max).
 * Option ke_load = 1: load-dependent unloading stiffness, eq (4.23) with maximum ke_max
 * (ke is then not used; with ke_load = 0, ke_max is not used).
 * Damping (4.24)-(4.25): k = k_p on plastic loading, the unloading k_e on B-C and C-D.
 * Sliding limit (4.28): F_tc = mu (F + k_cp alpha + f0p - f_ce) with alpha the current
 * overlap (the thesis' alpha_n) and f_ce = 1.5 pi Gamma R* (or 9/8 f0 if Gamma is not given:
 * the thesis' f0 = 8/9 f_ce); reported as f_adh = max(0, k_cp alpha + f0p - f_ce) since
 * dem_normal.f_adh is a non-negative addition (a negative one would make adhesion weaken
 * friction; with f0p = f0 it is negative below alpha = f_ce/(9 k_cp)).
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "dem/contact.h"
#include "epa.h"

static const dem_coef_spec coefs[] = {
    {"ke", "N/m", "constant elastic unloading stiffness (>= kp); required unless ke_load = 1",
     0.0, 1e12, 0.0},
    {"kp", "N/m", "plastic loading stiffness", DBL_MIN, 1e12, NAN},
    {"kcp", "N/m", "slope k_cp of the linear pull-off locus (eq 4.17)", 0.0, 1e12, NAN},
    {"f0", "N", "adhesive force at first contact; default 8/9 * 1.5 pi gamma R*", 0.0, 1e3,
     -1.0},
    {"f0p", "N", "intercept f_0p of the pull-off locus (eq 4.17); default f0", 0.0, 1e3, -1.0},
    {"gamma", "J/m^2", "interface energy (for f0 and f_ce = 1.5 pi gamma R*)", 0.0, 1e3, -1.0},
    {"ke_max", "N/m", "maximum of the load-dependent unloading k_e (eq 4.23; with ke_load = 1)",
     0.0, 1e12, 0.0},
    {"ke_load", "-", "0: constant ke; 1: load-dependent k_e of eq (4.23) (ke is then unused)",
     0.0, 1.0, 0.0},
    {"e", "-", "coefficient of restitution of the viscous damping", 1e-3, 1.0, 1.0},
};

static int set_coeffs(const dem_params *ps, double *c, dem_err *err) {
  double ke = dem_params_get_or(ps, "ke", 0.0), kp = dem_params_get_or(ps, "kp", NAN);
  double kemax = dem_params_get_or(ps, "ke_max", 0.0);
  double f0 = dem_params_get_or(ps, "f0", -1.0), f0p = dem_params_get_or(ps, "f0p", -1.0);
  double gam = dem_params_get_or(ps, "gamma", -1.0);
  double load = dem_params_get_or(ps, "ke_load", 0.0);
  if (load != 0.0 && load != 1.0)
    return dem_err_set(err, DEM_ERANGE,
                       "%slaw 'pasha-simplified': ke_load = %g must be 0 (constant ke) or 1 "
                       "(load-dependent k_e of eq 4.23)",
                       dem_params_origin(ps, "ke_load"), load);
  if (load == 0.0 && !(ke > 0.0))
    return dem_err_set(err, DEM_EMISSING,
                       "law 'pasha-simplified' needs coefficient 'ke' (elastic unloading "
                       "stiffness, N/m, >= kp), or ke_load = 1 with 'ke_max' (eq 4.23)");
  if (load == 0.0 && ke < kp)
    return dem_err_set(err, DEM_EPHYSICS,
                       "%slaw 'pasha-simplified': ke = %g N/m is less than kp = %g N/m: the "
                       "permanent overlap alpha_p = alpha_max - F_max/ke would fall below "
                       "alpha_0 (unloading must be stiffer than plastic loading)",
                       dem_params_origin(ps, "ke"), ke, kp);
  if (load == 1.0 && !(kemax > 0.0))
    return dem_err_set(err, DEM_EMISSING,
                       "law 'pasha-simplified': ke_load = 1 needs 'ke_max' (N/m, >= kp), the "
                       "maximum of the load-dependent k_e of eq 4.23");
  if (load == 1.0 && kemax < kp)
    return dem_err_set(err, DEM_EPHYSICS,
                       "%slaw 'pasha-simplified': ke_max = %g N/m is less than kp = %g N/m "
                       "(eq 4.23 needs ke_max >= kp)",
                       dem_params_origin(ps, "ke_max"), kemax, kp);
  if (f0 < 0.0 && gam < 0.0)
    return dem_err_set(err, DEM_EMISSING,
                       "law 'pasha-simplified' needs 'f0' (N, adhesive force at first contact) "
                       "or 'gamma' (J/m^2, for f0 = 8/9 * 1.5 pi gamma R*)");
  if (f0 >= 0.0 && f0p >= 0.0 && f0p < f0)
    return dem_err_set(err, DEM_EPHYSICS,
                       "%slaw 'pasha-simplified': f0p = %g N is less than f0 = %g N: the "
                       "pull-off locus (eq 4.17) would lie above the loading line near "
                       "alpha = 0",
                       dem_params_origin(ps, "f0p"), f0p, f0);
  c[DEM_PSS_KE] = load == 1.0 ? 0.0 : ke;
  c[DEM_PSS_KP] = kp;
  c[DEM_PSS_KCP] = dem_params_get_or(ps, "kcp", NAN);
  c[DEM_PSS_F0] = f0;
  c[DEM_PSS_F0P] = f0p;
  c[DEM_PSS_FCE_R] = gam >= 0.0 ? 1.5 * M_PI * gam : -1.0;
  c[DEM_PSS_KEMAX] = load == 1.0 ? kemax : 0.0;
  c[DEM_PSS_ETA] = dem_damping_eta_linear(dem_params_get_or(ps, "e", 1.0));
  return DEM_OK;
}

void dem_pashas_forces(const double *c, double R, double *f0, double *f0p, double *fce) {
  double fce_g = c[DEM_PSS_FCE_R] * R; /* < 0 if gamma not given */
  *f0 = c[DEM_PSS_F0] >= 0.0 ? c[DEM_PSS_F0] : 8.0 / 9.0 * fce_g;
  *f0p = c[DEM_PSS_F0P] >= 0.0 ? c[DEM_PSS_F0P] : *f0;
  *fce = fce_g >= 0.0 ? fce_g : 9.0 / 8.0 * *f0;
}

double dem_pashas_ke_unload(const double *c, double R, double alpha_max) {
  if (c[DEM_PSS_KEMAX] > 0.0)
    return dem_epa_ke_load_dependent(c[DEM_PSS_KP], c[DEM_PSS_KEMAX], R, alpha_max);
  return c[DEM_PSS_KE];
}

void dem_pashas_unload(const double *c, double R, double alpha_max, dem_epa_unload *u) {
  double f0, f0p, fce, kp = c[DEM_PSS_KP], kcp = c[DEM_PSS_KCP];
  dem_pashas_forces(c, R, &f0, &f0p, &fce);
  double ke = dem_pashas_ke_unload(c, R, alpha_max);
  u->ke = ke;
  u->alpha_0 = f0 / kp;
  u->alpha_max = alpha_max;
  u->f_max = kp * (alpha_max - u->alpha_0);
  u->alpha_p = alpha_max - u->f_max / ke;
  u->alpha_cp = (ke * u->alpha_p - f0p) / (ke + kcp);
  u->f_cp = kcp * u->alpha_cp + f0p;
  u->alpha_fp = 2.0 * u->alpha_cp - u->alpha_p;
  u->alpha_fe = NAN;
}

static int init(const double *c, const dem_geom *g, double *hist, dem_err *err) {
  (void)hist;
  double f0, f0p, fce;
  dem_pashas_forces(c, g->R, &f0, &f0p, &fce);
  if (f0p < f0)
    return dem_err_set(err, DEM_EPHYSICS,
                       "law 'pasha-simplified': at R* = %g m, f0p = %g N is less than f0 = %g N "
                       "(8/9 * 1.5 pi gamma R*): the pull-off locus (eq 4.17) would lie above "
                       "the loading line near alpha = 0",
                       g->R, f0p, f0);
  return DEM_OK;
}

static void force(const double *c, const dem_geom *g, double *hist, double alpha,
                  double alpha_dot, dem_normal *out) {
  double f0, f0p, fce;
  if (hist[DEM_PSS_H_STATE] == 0.0) {
    if (alpha < 0.0) { /* no contact forms at negative overlap */
      dem_normal_zero(out);
      return;
    }
    hist[DEM_PSS_H_AMAX] = -1.0; /* below any alpha: the first call loads plastically */
  }
  dem_pashas_forces(c, g->R, &f0, &f0p, &fce);
  const double kp = c[DEM_PSS_KP];
  double amax = hist[DEM_PSS_H_AMAX], keu = hist[DEM_PSS_H_KEU];
  double ap = hist[DEM_PSS_H_AP], acp = hist[DEM_PSS_H_ACP], f, k;
  if (alpha >= amax) { /* plastic loading (Fig 4.20 A-B) */
    f = kp * alpha - f0;
    k = kp;
    if (alpha > amax) {
      dem_epa_unload u;
      dem_pashas_unload(c, g->R, alpha, &u);
      hist[DEM_PSS_H_AMAX] = alpha;
      hist[DEM_PSS_H_KEU] = u.ke;
      hist[DEM_PSS_H_AP] = u.alpha_p;
      hist[DEM_PSS_H_ACP] = u.alpha_cp;
      hist[DEM_PSS_H_AFP] = u.alpha_fp;
    }
  } else if (alpha >= acp) { /* B-C (4.4) */
    f = keu * (alpha - ap);
    k = keu;
  } else if (alpha >= hist[DEM_PSS_H_AFP]) { /* C-D (4.5) */
    f = keu * (2.0 * acp - ap - alpha);
    k = keu;
  } else { /* broken at zero force; memory kept, re-contact at alpha_fp */
    hist[DEM_PSS_H_STATE] = DEM_PSS_BROKEN;
    dem_normal_zero(out);
    return;
  }
  hist[DEM_PSS_H_STATE] = DEM_PSS_CONTACT;
  out->f_el = f;
  out->k = k;
  out->f_damp = c[DEM_PSS_ETA] * sqrt(g->m * k) * alpha_dot;
  out->f = out->f_el + out->f_damp;
  out->f_adh = fmax(0.0, c[DEM_PSS_KCP] * alpha + f0p - fce); /* (4.28) */
  out->alpha_t = alpha > 0.0 ? alpha : 0.0; /* contact.h: max(alpha, 0) for Mindlin */
  out->contact = 1;
}

static double kref(const double *c, const dem_geom *g, double v) {
  double f0, f0p, fce, kp = c[DEM_PSS_KP];
  dem_pashas_forces(c, g->R, &f0, &f0p, &fce);
  double a0 = f0 / kp, amax = a0 + sqrt(a0 * a0 + g->m * v * v / kp); /* (4.18) */
  return fmax(kp, dem_pashas_ke_unload(c, g->R, amax));
}

const dem_law dem_law_pasha_simplified = {
    .name = "pasha-simplified",
    .title = "Pasha (2013) simplified linear elasto-plastic-adhesive (bulk law)",
    .source = "thesis Fig 4.20, eqs (4.4), (4.5), (4.17), (4.23)-(4.25), (4.28), 4.1.5",
    .ncoef = sizeof coefs / sizeof coefs[0],
    .coef = coefs,
    .nhist = DEM_PSS_NHIST,
    .flags = DEM_LAW_ADHESIVE | DEM_LAW_PLASTIC,
    .set_coeffs = set_coeffs,
    .init = init,
    .force = force,
    .kref = kref,
};
