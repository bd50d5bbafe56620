/* `thornton-ning`: Thornton & Ning (1998), adhesive elastic-perfectly-plastic spheres — the
 * nonlinear reference law (thesis section 3.4.4.1, eqs 3.55-3.59, Figs 3.20-3.22; primary
 * paper Powder Technol. 99:154-162, its eqs 58-77). Every assumption is listed in
 * docs/contact-laws.md ("thornton-ning").
 *
 * JKR geometry with radius R (thesis 3.41-3.42):
 *   alpha = a^2/R - sqrt(2 pi Gamma a / E*),    F_JKR(a; R) = 4 E* a^3/(3R) - sqrt(8 pi Gamma E* a^3)
 * 1. Loading before yield: JKR with R*, first contact at alpha = 0 with F = -8/9 f_c.
 * 2. Yield when the JKR pressure at the centre reaches p_y (3.55):
 *      p_y = 2 E* a_y / (pi R*) - sqrt(2 Gamma E* / (pi a_y)).
 * 3. Plastic loading (a > a_y, alpha > alpha_max): the JKR pressure cut off at p_y over the
 *    central disc a_p, with a^2 = a_p^2 + a_y^2 as in the non-adhesive case, gives
 *      F = 4 E* a_y^3/(3R*) + pi p_y (a^2 - a_y^2) - a_y sqrt(8 pi Gamma E* a),
 *    still with the JKR relation alpha(a; R*). Its slope dF/dalpha is thesis eq (3.56); it is
 *    tangent to the JKR curve at yield.
 * 4. Unloading / reloading below alpha_max: JKR with the flattened radius R_p (3.58),
 *      R_p = R* F*_max / (F_max + sqrt(4 f_c F*_max)),  F*_max = 4 E* a_max^3 / (3 R*),
 *    i.e. the JKR(R_p) curve through (a_max, F_max), shifted by alpha_c0 = a_max^2 (1/R* -
 *    1/R_p) so that it also passes through alpha_max. Pull-off f_cp = 1.5 pi Gamma R_p (3.59).
 * 5. Breakage at the minimum overlap of that curve (F = -5/9 f_cp); re-contact at alpha_c0
 *    with F = -8/9 f_cp (thesis Fig 3.20, [44]).
 * Damping (optional, e < 1): f_d = eta_lin(e) sqrt(m* k) alpha_dot, k = max(dF/dalpha, 0) —
 * Thornton & Ning had none; e = 1 (default) is the reference law.
 */
#include <float.h>
#include <gsl/gsl_poly.h>
#include <math.h>

#include "dem/contact.h"
#include "dem/jkr.h"
#include "dem/material.h"

enum { C_ES, C_GAMMA, C_PY, C_ETA, C_K1, C_K2 };

/* History. Every JKR curve of radius rho is used in the dimensionless form of dem/jkr.h
 * (the solver shared with `jkr`): with a_c = (9 pi Gamma rho^2 / (8 E*))^(1/3) and
 * delta_c = a_c^2 / rho,
 *   alpha = delta_c (s^4 - 4/3 s),  a = a_c s^2,  F = f_c(rho) (s^6 - 2 s^3),
 *   dF/dalpha = (f_c(rho) / delta_c) (9/2) s^2 (s^3 - 1) / (3 s^3 - 1),  f_c = 1.5 pi Gamma rho,
 * (s^3 = 4/3: jump-in, -8/9 f_c; s = 1: pull-off, -f_c; s^3 = 1/3: breakage, -5/9 f_c), so
 * that an evaluation costs one quartic solve and no further roots; the scales are cached. */
enum {
  H_STATE, /* 0 fresh, 1 in contact, 2 separated after breakage */
  H_RP,    /* unloading radius R_p (= R* before yield), m */
  H_AC0,   /* alpha_c0: offset of the unloading curve = re-contact overlap, m */
  H_AMAX,  /* alpha_max (>= alpha_y), m */
  H_FMAX,  /* F_max, N */
  H_AY,    /* a_y, m */
  H_ALY,   /* alpha_y, m */
  H_P0,    /* 4 E* a_y^3 / (3 R*) - pi p_y a_y^2, N */
  H_A,     /* contact radius at the last call, m (diagnostic) */
  H_FCP,   /* f_cp = 1.5 pi Gamma R_p, N */
  H_AF,    /* breakage overlap of the current curve, m */
  H_ACP,   /* a_c of the R_p curve, m */
  H_IDCP,  /* 1 / delta_c of the R_p curve, 1/m */
  H_ACS,   /* a_c of the R* curve, m */
  H_SACS,  /* sqrt(a_c of the R* curve), m^1/2 */
  H_IDCS,  /* 1 / delta_c of the R* curve, 1/m */
  H_N
};
enum { ST_FRESH = 0, ST_CONTACT = 1, ST_APART = 2 };

static const dem_coef_spec coefs[] = {
    DEM_COEF_ELASTIC,
    {"gamma", "J/m^2", "interface energy Gamma, f_c = 1.5 pi Gamma R*", DBL_MIN, 1e3, NAN},
    {"py", "Pa", "limiting contact pressure p_y (thesis 3.55)", DBL_MIN, 1e12, NAN},
    {"e", "-", "restitution of the optional viscous damping (1 = none, the reference law)", 1e-3,
     1.0, 1.0},
};

static int set_coeffs(const dem_params *ps, double *c, dem_err *err) {
  (void)err;
  c[C_ES] = dem_contact_reduced_modulus(ps);
  c[C_GAMMA] = dem_params_get_or(ps, "gamma", NAN);
  c[C_PY] = dem_params_get_or(ps, "py", NAN);
  c[C_ETA] = dem_damping_eta_linear(dem_params_get_or(ps, "e", 1.0));
  c[C_K1] = sqrt(2.0 * M_PI * c[C_GAMMA] / c[C_ES]); /* m^1/2: alpha = a^2/R - K1 sqrt(a) */
  c[C_K2] = sqrt(8.0 * M_PI * c[C_GAMMA] * c[C_ES]); /* N/m^3/2: F = ... - K2 a^3/2 */
  return DEM_OK;
}

/* a_y from thesis (3.55): with s = sqrt(a_y) and k = pi R / (2 E*),
 * s^3 - k p_y s - k sqrt(2 Gamma E* / pi) = 0: one positive root (one sign change), two
 * Newton steps polish it. */
static double yield_radius(const double *c, double R) {
  double k = M_PI * R / (2.0 * c[C_ES]);
  double b = -k * c[C_PY], d = -k * sqrt(2.0 * c[C_GAMMA] * c[C_ES] / M_PI);
  double x0 = NAN, x1 = NAN, x2 = NAN;
  int n = gsl_poly_solve_cubic(0.0, b, d, &x0, &x1, &x2);
  double s = n == 1 ? x0 : fmax(x0, fmax(x1, x2));
  for (int i = 0; i < 2; i++) s -= (s * s * s + b * s + d) / (3.0 * s * s + b);
  return s * s;
}

/* The per-contact yield constants; error if the law cannot represent the set: alpha_y <= 0
 * (adhesion-induced yield, the jump-in radius a_0 already exceeds a_y) would make the first
 * contact plastic with F_max < -8/9 f_cp, so that the re-contact overlap alpha_c0 lies
 * beyond alpha_max and the re-contact rule contradicts the loading rule. */
static int yield_point(const double *c, const dem_geom *g, double *ay, double *aly, double *p0,
                       dem_err *err) {
  double R = g->R;
  *ay = yield_radius(c, R);
  *aly = dem_jkr_alpha(R, c[C_ES], c[C_GAMMA], *ay);
  *p0 = 4.0 * c[C_ES] * *ay * *ay * *ay / (3.0 * R) - M_PI * c[C_PY] * *ay * *ay;
  if (!(*aly > 0.0) || !isfinite(*p0))
    return dem_err_set(err, DEM_EPHYSICS,
                       "law 'thornton-ning': yield at or before first contact (alpha_y = %g m, "
                       "a_y = %g m) for py = %g Pa, gamma = %g J/m^2, E* = %g Pa, R* = %g m: "
                       "adhesion-induced yield is outside the model (raise py; needs alpha_y > "
                       "0, i.e. py > %g Pa)",
                       *aly, *ay, c[C_PY], c[C_GAMMA], c[C_ES], R,
                       /* p_y at a_y = a(alpha = 0) = (2 pi Gamma R^2/E*)^(1/3) */
                       2.0 * c[C_ES] * cbrt(2.0 * M_PI * c[C_GAMMA] * R * R / c[C_ES]) /
                               (M_PI * R) -
                           sqrt(2.0 * c[C_GAMMA] * c[C_ES] /
                                (M_PI * cbrt(2.0 * M_PI * c[C_GAMMA] * R * R / c[C_ES]))));
  /* Yield beyond the radius: the JKR geometry alpha = a^2/R* - ... (thesis 3.41) is a
   * small-overlap result, and the law would stay elastic to overlaps larger than R* (the
   * non-adhesive sibling `thornton` rejects p_y > 2 E* / pi, alpha_y > R*, the same way). */
  if (!(*aly < R))
    return dem_err_set(err, DEM_EPHYSICS,
                       "law 'thornton-ning': the yield overlap alpha_y = %g m (a_y = %g m, thesis "
                       "3.55) is not below R* = %g m for py = %g Pa, gamma = %g J/m^2, E* = %g "
                       "Pa: p_y is too large for the law's small-overlap geometry (roughly "
                       "py < 2 E*/pi = %g Pa)",
                       *aly, *ay, R, c[C_PY], c[C_GAMMA], c[C_ES], 2.0 * c[C_ES] / M_PI);
  return DEM_OK;
}

/* Set the R_p curve's cached scales and breakage overlap (alpha_c0 already set). */
static void set_curve(const double *c, double *h, double rp) {
  double dc;
  dem_jkr_scales(c[C_GAMMA], c[C_ES], rp, &h[H_FCP], &h[H_ACP], &dc); /* f_cp: (3.59) */
  h[H_RP] = rp;
  h[H_IDCP] = 1.0 / dc;
  h[H_AF] = h[H_AC0] + DEM_JKR_AF * dc; /* breakage, -5/9 f_cp */
}

static int init(const double *c, const dem_geom *g, double *h, dem_err *err) {
  double ay, aly, p0;
  int rc = yield_point(c, g, &ay, &aly, &p0, err);
  if (rc) return rc;
  h[H_STATE] = ST_FRESH;
  h[H_AC0] = 0.0;
  set_curve(c, h, g->R);
  h[H_ACS] = h[H_ACP];
  h[H_SACS] = sqrt(h[H_ACP]);
  h[H_IDCS] = h[H_IDCP];
  h[H_AMAX] = aly;
  h[H_FMAX] = dem_jkr_force(g->R, c[C_ES], c[C_GAMMA], ay);
  h[H_AY] = ay;
  h[H_ALY] = aly;
  h[H_P0] = p0;
  h[H_A] = 0.0;
  return DEM_OK;
}

static void force(const double *c, const dem_geom *g, double *h, double alpha, double alpha_dot,
                  dem_normal *out) {
  if (h[H_STATE] != ST_CONTACT) {
    if (!(alpha >= h[H_AC0])) {
      dem_normal_zero(out);
      return;
    }
    h[H_STATE] = ST_CONTACT;
  }
  double a, f, k;
  if (alpha > h[H_AMAX]) { /* plastic loading on the R* geometry, thesis (3.56) */
    const double R = g->R, fc = 1.5 * M_PI * c[C_GAMMA] * R;
    double s = dem_jkr_root(alpha * h[H_IDCS]), s3 = s * s * s;
    a = h[H_ACS] * s * s;
    double ky = h[H_AY] * c[C_K2] * h[H_SACS]; /* a_y sqrt(8 pi Gamma E*) sqrt(a_c) */
    f = h[H_P0] + M_PI * c[C_PY] * a * a - ky * s;
    k = (4.0 * M_PI * c[C_PY] * a * a / s - ky) * h[H_IDCS] / (4.0 * s3 - 4.0 / 3.0);
    /* (3.58): R_p = R* F*_max / (F_max + sqrt(4 f_c F*_max)), F*_max = f_c s^6 and
     * sqrt(4 f_c F*_max) = 2 f_c s^3 */
    double fh = fc * s3 * s3;
    double rp = R * fh / (f + 2.0 * fc * s3);
    h[H_AC0] = a * a * (1.0 / R - 1.0 / rp);
    h[H_AMAX] = alpha;
    h[H_FMAX] = f;
    set_curve(c, h, rp);
  } else {
    if (!(alpha >= h[H_AF])) { /* breakage at -5/9 f_cp; R_p and alpha_c0 are kept */
      h[H_STATE] = ST_APART;
      dem_normal_zero(out);
      return;
    }
    double s = dem_jkr_root((alpha - h[H_AC0]) * h[H_IDCP]);
    if (!(s > 0.0)) s = DEM_JKR_SF; /* rounding at the breakage point */
    a = h[H_ACP] * s * s;
    f = h[H_FCP] * dem_jkr_fhat(s);
    /* dF/dalpha > 0 only above the pull-off point s = 1; below it the branch softens to
     * -infinity at breakage (s^3 = 1/3), where rounding could flip the sign of the vanishing
     * denominator: the damping stiffness is 0 there. */
    k = s > 1.0 ? h[H_FCP] * h[H_IDCP] * dem_jkr_khat(s) : 0.0;
  }
  if (!(k > 0.0) || !isfinite(k)) k = 0.0;
  h[H_A] = a;
  out->f_el = f;
  out->k = k;
  out->f_damp = c[C_ETA] * sqrt(g->m * k) * alpha_dot;
  out->f = f + out->f_damp;
  out->f_adh = 2.0 * h[H_FCP]; /* Thornton-Yin limit mu (F + 2 f_cp), Ning's extension */
  out->alpha_t = a * a / g->R; /* Mindlin at the contact radius (8 G* a), also on R_p curves */
  out->contact = 1;
}

/* Stiffness scale: 2 E* a at the deepest overlap of an impact at v, estimated as the larger of
 * the Hertz overlap and the plastic-line overlap (k_N = pi R* p_y); the JKR unloading
 * stiffness never exceeds 2 E* a. */
static double kref(const double *c, const dem_geom *g, double v) {
  double R = g->R, Es = c[C_ES];
  double ah = pow(15.0 * g->m * v * v / (16.0 * Es * sqrt(R)), 0.4);
  double ap = v * sqrt(g->m / (M_PI * R * c[C_PY])) + M_PI * M_PI * R * c[C_PY] * c[C_PY] /
                                                          (4.0 * Es * Es);
  double a0 = cbrt(2.0 * M_PI * c[C_GAMMA] * R * R / Es);
  return 2.0 * Es * fmax(sqrt(R * fmax(ah, ap)), a0);
}

const dem_law dem_law_thornton_ning = {
    .name = "thornton-ning",
    .title = "Thornton & Ning 1998 elastic-plastic adhesive (JKR, p_y cut-off, R_p unloading)",
    .source = "thesis eqs (3.41)-(3.42), (3.55)-(3.59); Thornton & Ning 1998 eqs (58)-(77)",
    .ncoef = sizeof coefs / sizeof coefs[0],
    .coef = coefs,
    .nhist = H_N,
    .flags = DEM_LAW_ADHESIVE | DEM_LAW_PLASTIC | DEM_LAW_NONLINEAR,
    .set_coeffs = set_coeffs,
    .init = init,
    .force = force,
    .kref = kref,
};
