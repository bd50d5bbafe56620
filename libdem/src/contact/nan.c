/* `nan`: the improved linear elasto-plastic-adhesive law of the second seed (Nan, Goh &
 * Rahman), eqs (3)-(26); the correlations (27)-(59) are in src/nan_correlations.c.
 *
 *   f_e = k_e (alpha - alpha_p)                      elastic line BC / DE   eq (17)
 *   f_p = f_y + k_p (alpha - alpha_y)                plastic line CD        eq (18)
 *   f_c = -f_cp + k_c (alpha_cp - alpha)             adhesive line EF       eq (19)
 *   f   = f_e (alpha_cp < alpha <= alpha_max), f_p (alpha > alpha_max: alpha_max moves),
 *         f_c (alpha_fp <= alpha <= alpha_cp), 0 after breakage (alpha < alpha_fp) until
 *         re-contact at alpha >= alpha_c0 (first contact: alpha_c0 = 0)        eq (20)
 *   f_d = eta(e0) beta sqrt(m* k_branch) alpha_dot, beta = 1 before yield and 0.1 after
 *         (paper eqs 24-26; eta = 2 gamma / beta = 2|ln e0| / sqrt(pi^2 + ln^2 e0))
 *
 * Eq (20) selects f_e where f_p > f_e: with k_p <= k_el <= k_e (enforced) that is exactly
 * alpha <= alpha_max, so the law compares alpha with alpha_max (no tie at alpha_max).
 * k_e(alpha_max) eq (46) (default) or (48); k_c = k_e k_cl/k_el (section 3.2); f_cp eq (59)
 * (default) or (64), (67). Coefficients that depend on R* (k_el = pi R* p_y by default,
 * eq 52; f_y, alpha_y, k_cl...) are computed once per contact in init and cached in the
 * history block; force only reads them and recomputes the unloading line when alpha_max
 * grows. Units: SI.
 */
#include <float.h>
#include <math.h>

#include "dem/contact.h"
#include "dem/material.h"
#include "dem/nan.h"

enum { C_ES, C_GAMMA, C_PY, C_KEL, C_KP, C_KCL, C_KE0, C_AMAX0, C_KEEQ, C_FCPEQ, C_ETA,
       C_BETA, C_BETAY };

/* History block (16 doubles). */
enum {
  H_STATE, /* 0 fresh, 1 in contact, 2 separated after breakage (memory kept) */
  H_KEL,   /* N/m */
  H_KP,    /* N/m */
  H_RKC,   /* k_el/k_cl */
  H_FCE,   /* N */
  H_A0,    /* alpha_0, m */
  H_AY,    /* alpha_y, m */
  H_FY,    /* N */
  H_AMAX,  /* alpha_max (>= alpha_y), m */
  H_KE,    /* k_e of the current unloading line, N/m */
  H_AP,    /* alpha_p, m */
  H_FCP,   /* f_cp, N */
  H_KC,    /* k_c, N/m */
  H_ACP,   /* alpha_cp, m */
  H_AFP,   /* alpha_fp, m */
  H_AC0,   /* alpha_c0, m */
  H_N
};

enum { ST_FRESH = 0, ST_CONTACT = 1, ST_APART = 2 };

static const dem_coef_spec coefs[] = {
    DEM_COEF_ELASTIC,
    {"gamma", "J/m^2", "interface energy Gamma, f_ce = 1.5 pi Gamma R* (eq 5)", DBL_MIN, 1e3, NAN},
    {"py", "Pa", "limiting contact (yield) pressure p_y", DBL_MIN, 1e12, NAN},
    {"ke", "N/m", "k_el, elastic stiffness before yield (default: pi R* p_y, eq 52)", DBL_MIN,
     1e12, -1.0},
    {"kp", "N/m", "plastic stiffness (default: k_el)", DBL_MIN, 1e12, -1.0},
    {"kc", "N/m", "k_cl, adhesive stiffness before yield (default: eq 38)", DBL_MIN, 1e12, -1.0},
    {"ke0", "N/m", "measured unloading stiffness k_e0 at amax0: k_el from eq (45)/(49)", DBL_MIN,
     1e12, -1.0},
    {"amax0", "m", "overlap alpha_max0 at which ke0 was measured", DBL_MIN, 1.0, -1.0},
    {"ke_eq", "-", "k_e(alpha_max): 46 = eq (46) square root (default), 48 = eq (48) with k_p",
     46, 48, 46},
    {"fcp_eq", "-", "pull-off force: 59 = eq (59) (default), 64 = eq (64), 67 = eq (67)", 59, 67,
     59},
    {"e", "-", "restitution coefficient e0 of the viscous damping, eq (26)", 1e-3, 1.0, 1.0},
    {"beta", "-", "damping factor before yield (paper: 1)", 0.0, 10.0, 1.0},
    {"beta_y", "-", "damping factor after yield (paper: 0.1)", 0.0, 10.0, 0.1},
};

static int set_coeffs(const dem_params *ps, double *c, dem_err *err) {
  c[C_ES] = dem_contact_reduced_modulus(ps);
  c[C_GAMMA] = dem_params_get_or(ps, "gamma", NAN);
  c[C_PY] = dem_params_get_or(ps, "py", NAN);
  c[C_KEL] = dem_params_get_or(ps, "ke", -1.0);
  c[C_KP] = dem_params_get_or(ps, "kp", -1.0);
  c[C_KCL] = dem_params_get_or(ps, "kc", -1.0);
  c[C_KE0] = dem_params_get_or(ps, "ke0", -1.0);
  c[C_AMAX0] = dem_params_get_or(ps, "amax0", -1.0);
  double keq = dem_params_get_or(ps, "ke_eq", 46), feq = dem_params_get_or(ps, "fcp_eq", 59);
  if (keq != 46.0 && keq != 48.0)
    return dem_err_set(err, DEM_ERANGE,
                       "%slaw 'nan': ke_eq = %g must be 46 (eq 46) or 48 (eq 48)",
                       dem_params_origin(ps, "ke_eq"), keq);
  if (feq != 59.0 && feq != 64.0 && feq != 67.0)
    return dem_err_set(err, DEM_ERANGE,
                       "%slaw 'nan': fcp_eq = %g must be 59, 64 or 67 (eq 61 gives no pull-off "
                       "force below alpha_y and is a comparison function only)",
                       dem_params_origin(ps, "fcp_eq"), feq);
  c[C_KEEQ] = keq;
  c[C_FCPEQ] = feq;
  if ((c[C_KE0] > 0.0) != (c[C_AMAX0] > 0.0))
    return dem_err_set(err, DEM_EMISSING,
                       "law 'nan': ke0 (= %g N/m) and amax0 (= %g m) go together: give both "
                       "(eq 45) or neither",
                       c[C_KE0], c[C_AMAX0]);
  if (c[C_KE0] > 0.0 && c[C_KEL] > 0.0)
    return dem_err_set(err, DEM_EINVAL,
                       "%slaw 'nan': give either ke (k_el = %g N/m) or ke0/amax0 (= %g N/m, %g "
                       "m), not both",
                       dem_params_origin(ps, "ke"), c[C_KEL], c[C_KE0], c[C_AMAX0]);
  if (c[C_KEL] > 0.0 && c[C_KP] > c[C_KEL])
    return dem_err_set(err, DEM_EPHYSICS,
                       "%slaw 'nan': kp = %g N/m exceeds ke = k_el = %g N/m: the plastic line "
                       "would lie above the elastic one",
                       dem_params_origin(ps, "kp"), c[C_KP], c[C_KEL]);
  c[C_ETA] = dem_damping_eta_linear(dem_params_get_or(ps, "e", 1.0));
  c[C_BETA] = dem_params_get_or(ps, "beta", 1.0);
  c[C_BETAY] = dem_params_get_or(ps, "beta_y", 0.1);
  return DEM_OK;
}

/* The per-contact constants (init and kref share this). */
static int contact_coeffs(const double *c, const dem_geom *g, dem_nan_coeffs *k, dem_err *err) {
  dem_nan_input in = {g->R, c[C_ES], c[C_GAMMA], c[C_PY], c[C_KEL], c[C_KP], -1.0,
                      (int)c[C_KEEQ], (int)c[C_FCPEQ]};
  if (c[C_KE0] > 0.0) {
    double ay;
    int rc = dem_nan_kel_from_unloading(g->R, c[C_ES], c[C_GAMMA], c[C_PY], c[C_KE0],
                                        c[C_AMAX0], in.ke_eq, c[C_KP], &in.kel, &ay, err);
    if (rc) return rc;
  }
  if (c[C_KCL] > 0.0) in.kel_kcl = (in.kel > 0.0 ? in.kel : dem_nan_kel_py(g->R, c[C_PY])) /
                                   c[C_KCL];
  return dem_nan_coeffs_init(k, &in, err);
}

static void store_unloading(double *h, const dem_nan_unload *u) {
  h[H_AMAX] = u->alpha_max;
  h[H_KE] = u->ke;
  h[H_AP] = u->alpha_p;
  h[H_FCP] = u->f_cp;
  h[H_KC] = u->kc;
  h[H_ACP] = u->alpha_cp;
  h[H_AFP] = u->alpha_fp;
  h[H_AC0] = u->alpha_c0;
}

static int init(const double *c, const dem_geom *g, double *h, dem_err *err) {
  dem_nan_coeffs k;
  int rc = contact_coeffs(c, g, &k, err);
  if (rc) return rc;
  h[H_STATE] = ST_FRESH;
  h[H_KEL] = k.kel;
  h[H_KP] = k.kp;
  h[H_RKC] = k.r_kc;
  h[H_FCE] = k.fce;
  h[H_A0] = k.alpha0;
  h[H_AY] = k.alphay;
  h[H_FY] = k.fy;
  dem_nan_unload u;
  dem_nan_unloading(&k, k.alphay, &u); /* the line BC before yield */
  store_unloading(h, &u);
  return DEM_OK;
}

/* Rebuild the coefficient struct from the cached history (plus the pair constants). */
static void coeffs_from_hist(const double *c, const dem_geom *g, const double *h,
                             dem_nan_coeffs *k) {
  k->R = g->R;
  k->Es = c[C_ES];
  k->gamma = c[C_GAMMA];
  k->py = c[C_PY];
  k->kel = h[H_KEL];
  k->kp = h[H_KP];
  k->r_kc = h[H_RKC];
  k->kcl = h[H_KEL] / h[H_RKC];
  k->A = dem_nan_A(h[H_RKC]);
  k->fce = h[H_FCE];
  k->f0 = 8.0 / 9.0 * h[H_FCE];
  k->fy = h[H_FY];
  k->alpha0 = h[H_A0];
  k->alphay = h[H_AY];
  k->ke_eq = (int)c[C_KEEQ];
  k->fcp_eq = (int)c[C_FCPEQ];
}

static void force(const double *c, const dem_geom *g, double *h, double alpha, double alpha_dot,
                  dem_normal *out) {
  if (h[H_STATE] != ST_CONTACT) {
    if (!(alpha >= h[H_AC0])) { /* cs = 0: first loading at alpha < 0, or alpha < alpha_c0 */
      dem_normal_zero(out);
      return;
    }
    h[H_STATE] = ST_CONTACT;
  }
  double f, k;
  if (alpha > h[H_AMAX]) { /* plastic line CD: alpha_max follows (eq 10) */
    f = h[H_FY] + h[H_KP] * (alpha - h[H_AY]);
    k = h[H_KP];
    dem_nan_coeffs kk;
    dem_nan_unload u;
    coeffs_from_hist(c, g, h, &kk);
    dem_nan_unloading(&kk, alpha, &u);
    store_unloading(h, &u);
  } else if (alpha > h[H_ACP]) { /* elastic line BC / DE */
    f = h[H_KE] * (alpha - h[H_AP]);
    k = h[H_KE];
  } else if (alpha >= h[H_AFP]) { /* adhesive line EF */
    f = -h[H_FCP] + h[H_KC] * (h[H_ACP] - alpha);
    k = h[H_KC];
  } else { /* breakage at alpha_fp; the plastic memory stays */
    h[H_STATE] = ST_APART;
    dem_normal_zero(out);
    return;
  }
  double beta = h[H_AMAX] > h[H_AY] ? c[C_BETAY] : c[C_BETA];
  out->f_el = f;
  out->k = k;
  out->f_damp = c[C_ETA] * beta * sqrt(g->m * k) * alpha_dot;
  out->f = f + out->f_damp;
  out->f_adh = h[H_FCP]; /* sliding limit mu (f + f_cp) >= 0 on every branch (see docs) */
  out->alpha_t = alpha > 0.0 ? alpha : 0.0; /* contact.h: max(alpha, 0) for Mindlin */
  out->contact = 1;
}

/* Largest branch stiffness of an impact at v: k_e at the alpha_max of the undamped energy
 * balance, eq (79) solved for f_max, eq (10); at least k_el and k_cl. */
static double kref(const double *c, const dem_geom *g, double v) {
  dem_nan_coeffs k;
  if (contact_coeffs(c, g, &k, NULL)) return dem_nan_kel_py(g->R, c[C_PY]);
  double e2 = g->m * v * v * k.kp + k.fy * k.fy + (k.f0 * k.f0 - k.fy * k.fy) * k.kp / k.kel;
  double fm = e2 > k.fy * k.fy ? sqrt(e2) : k.fy;
  dem_nan_unload u;
  dem_nan_unloading(&k, k.alphay + (fm - k.fy) / k.kp, &u);
  return fmax(u.ke, u.kc);
}

const dem_law dem_law_nan = {
    .name = "nan",
    .title = "improved linear elasto-plastic-adhesive (Nan et al.)",
    .source = "second seed eqs (3)-(26), (27)-(59)",
    .ncoef = sizeof coefs / sizeof coefs[0],
    .coef = coefs,
    .nhist = H_N,
    .flags = DEM_LAW_ADHESIVE | DEM_LAW_PLASTIC,
    .set_coeffs = set_coeffs,
    .init = init,
    .force = force,
    .kref = kref,
};
