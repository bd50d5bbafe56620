/* Contact-law tests.
 *
 * 1. A loop over EVERY law of the registry (dem_contact_law_count): every error of the
 *    generic coefficient check provoked on purpose (each required coefficient missing, each
 *    coefficient below its minimum and above its maximum, NaN, +-infinity), and finite,
 *    consistent output along a load-unload-reload path with and without an overlap rate.
 * 2. Per law, closed forms along prescribed overlap paths (the force function driven
 *    directly, alpha_dot = 0) and every branch transition: `jkr`, `jkr-modified`,
 *    `thornton`, `walton-braun`; the law-specific errors of their set_coeffs.
 *
 * Material: the reference case of the physics notes (ammonium fluorescein, R = 2.45 um,
 * rho = 1350 kg/m^3, E = 1.2 GPa, nu = 0.3, Gamma = 0.2 J/m^2, p_y = 35.3 MPa) against a
 * rigid wall (wall_E = 1e30), so R* = R, m* = m, E* = E / (1 - nu^2).
 */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dem/contact.h"
#include "dem/error.h"
#include "dem/jkr.h"
#include "dem/material.h"
#include "dem/params.h"

#define R_REF 2.45e-6
#define RHO_REF 1350.0
#define E_REF 1.2e9
#define NU_REF 0.3
#define GAMMA_REF 0.2
#define PY_REF 35.3e6

static dem_geom ref_geom(void) {
  dem_geom g = {R_REF, dem_sphere_mass(R_REF, RHO_REF)};
  return g;
}

/* Values for every key of the physics notes, consistent with one another (thesis Table
 * 4.1/4.2 where they exist). */
static const struct {
  const char *key;
  double value;
} universe[] = {
    {"E", E_REF},   {"nu", NU_REF},   {"wall_E", 1e30}, {"wall_nu", 0.3}, {"gamma", GAMMA_REF},
    {"py", PY_REF}, {"kn", 1500.0},   {"ke", 1500.0},   {"kp", 210.0},    {"kc", 20.0},
    {"kt", 1500.0}, {"ke_max", 3e3},  {"phi_f", 0.05},  {"kcp", 20.0},    {"f0", 2.1e-6},
    {"f0p", 4e-6},  {"e", 0.5},       {"beta", 1.0},    {"mu", 0.3},      {"mu_r", 0.01},
};

/* An in-range value for a coefficient that is not in the universe. */
static double generic_value(const dem_coef_spec *s) {
  if (!isnan(s->def) && s->def >= s->min && s->def <= s->max) return s->def;
  if (s->min > 0.0 && isfinite(s->max)) return sqrt(s->min * s->max);
  if (s->min > 0.0) return 2.0 * s->min;
  if (isfinite(s->max)) return 0.5 * (s->min + s->max);
  return s->min + 1.0;
}

/* The base parameter set of a law: the universe's value for each of its coefficients when
 * in range, an in-range value for other required coefficients, defaults for the rest. */
static void base_params(const dem_law *law, dem_params *ps) {
  dem_params_init(ps);
  for (int i = 0; i < law->ncoef; i++) {
    const dem_coef_spec *s = &law->coef[i];
    double v = NAN;
    for (size_t j = 0; j < sizeof universe / sizeof universe[0]; j++)
      if (strcmp(universe[j].key, s->key) == 0) v = universe[j].value;
    if (!(v >= s->min && v <= s->max)) v = isnan(s->def) ? generic_value(s) : NAN;
    if (!isnan(v)) ck_assert_int_eq(dem_params_set(ps, s->key, v, "base.cfg:1", NULL), DEM_OK);
  }
}

static void set(dem_params *ps, const char *key, double v) {
  ck_assert_int_eq(dem_params_set(ps, key, v, "test", NULL), DEM_OK);
}

static void remove_key(dem_params *ps, const char *key) {
  for (int i = 0; i < ps->n; i++)
    if (strcmp(ps->p[i].key, key) == 0) {
      ps->p[i] = ps->p[ps->n - 1];
      ps->n--;
      return;
    }
}

static int key_index(const dem_params *ps, const char *key) {
  for (int i = 0; i < ps->n; i++)
    if (strcmp(ps->p[i].key, key) == 0) return i;
  return -1;
}

/* Expect dem_contact_setup to fail with `code` and a message naming `key`. */
static void expect_error(const dem_law *law, const dem_params *ps, int code, const char *key,
                         const char *what) {
  dem_contact ct;
  dem_err err = {0};
  int rc = dem_contact_setup(&ct, law, ps, &err);
  ck_assert_msg(rc == code, "law '%s', %s of '%s': status %d (%s), expected %d; message: %s",
                law->name, what, key, rc, dem_strerror(rc), code, err.msg);
  ck_assert_msg(strstr(err.msg, key) != NULL, "law '%s', %s: message does not name '%s': %s",
                law->name, what, key, err.msg);
  ck_assert_ptr_null(ct.law);
}

/* --- 1. Every law of the registry ------------------------------------------------------ */

START_TEST(test_every_law_errors) {
  const dem_law *law = dem_contact_law_at(_i);
  ck_assert_ptr_nonnull(law);
  ck_assert(law->ncoef >= 0 && law->nhist >= 1 && law->nhist <= DEM_LAW_NHIST_MAX);
  ck_assert_ptr_nonnull(law->force);
  ck_assert_ptr_nonnull(law->set_coeffs);
  ck_assert_ptr_nonnull(law->kref);
  ck_assert_ptr_eq(dem_contact_law_find(law->name), law);
  dem_params base;
  base_params(law, &base);
  dem_contact ct;
  dem_err err = {0};
  ck_assert_msg(dem_contact_setup(&ct, law, &base, &err) == DEM_OK,
                "law '%s': the reference parameter set is rejected: %s", law->name, err.msg);
  for (int i = 0; i < law->ncoef; i++) {
    const dem_coef_spec *s = &law->coef[i];
    ck_assert_msg(s->key && s->unit && s->about && s->min <= s->max, "law '%s' coefficient %d",
                  law->name, i);
    dem_params ps;
    if (isnan(s->def)) { /* required: missing */
      ps = base;
      remove_key(&ps, s->key);
      expect_error(law, &ps, DEM_EMISSING, s->key, "absence");
    }
    if (s->min > -DBL_MAX) { /* below the minimum */
      double below = s->min > 0.0 ? (s->min == DBL_MIN ? 0.0 : 0.5 * s->min)
                                  : (s->min == 0.0 ? -1.0 : 2.0 * s->min);
      ps = base;
      set(&ps, s->key, below);
      expect_error(law, &ps, DEM_ERANGE, s->key, "value below the minimum");
    }
    if (s->max < DBL_MAX / 4) { /* above the maximum */
      double above = s->max > 0.0 ? 2.0 * s->max : (s->max == 0.0 ? 1.0 : 0.5 * s->max);
      ps = base;
      set(&ps, s->key, above);
      expect_error(law, &ps, DEM_ERANGE, s->key, "value above the maximum");
    }
    /* NaN and infinities: refused on entry to a parameter set ... */
    ps = base;
    ck_assert_int_eq(dem_params_set(&ps, s->key, NAN, "test", NULL), DEM_ENONFINITE);
    ck_assert_int_eq(dem_params_set(&ps, s->key, INFINITY, "test", NULL), DEM_ENONFINITE);
    ck_assert_int_eq(dem_params_set(&ps, s->key, -INFINITY, "test", NULL), DEM_ENONFINITE);
    /* ... and by the law set-up if they get into one anyway. */
    const double bad[] = {NAN, INFINITY, -INFINITY};
    for (int b = 0; b < 3; b++) {
      ps = base;
      if (key_index(&ps, s->key) < 0) set(&ps, s->key, generic_value(s));
      ps.p[key_index(&ps, s->key)].value = bad[b];
      expect_error(law, &ps, DEM_ENONFINITE, s->key, "non-finite value");
    }
  }
}
END_TEST

typedef struct {
  const dem_contact *ct;
  dem_geom g;
  double hist[DEM_LAW_NHIST_MAX];
} path_ctx;

/* Walk from a to b in n steps with overlap rate rate; check every output. */
static void walk(path_ctx *p, double a, double b, int n, double rate) {
  const char *name = p->ct->law->name;
  for (int i = 1; i <= n; i++) {
    double alpha = a + (b - a) * i / n;
    double state0 = p->hist[DEM_HIST_STATE];
    dem_normal out;
    dem_contact_force(p->ct, &p->g, p->hist, alpha, rate, &out);
    ck_assert_msg(isfinite(out.f) && isfinite(out.f_el) && isfinite(out.f_damp) &&
                      isfinite(out.k) && isfinite(out.f_adh),
                  "law '%s' at alpha = %g: non-finite output f=%g f_el=%g f_d=%g k=%g f_adh=%g",
                  name, alpha, out.f, out.f_el, out.f_damp, out.k, out.f_adh);
    ck_assert_msg(fabs(out.f - out.f_el - out.f_damp) <= 1e-12 * (fabs(out.f_el) + fabs(out.f_damp)),
                  "law '%s': f != f_el + f_damp", name);
    ck_assert_msg(out.f_adh >= 0.0, "law '%s': f_adh < 0", name);
    /* Mindlin overlap (contact.h): finite, >= 0, and 0 without contact. */
    ck_assert_msg(isfinite(out.alpha_t) && out.alpha_t >= 0.0,
                  "law '%s' at alpha = %g: alpha_t = %g", name, alpha, out.alpha_t);
    ck_assert_msg(out.contact || out.alpha_t == 0.0, "law '%s': alpha_t without contact", name);
    if (!(p->ct->law->flags & DEM_LAW_ADHESIVE) && out.contact)
      ck_assert_msg(out.alpha_t == (alpha > 0.0 ? alpha : 0.0),
                    "law '%s' at alpha = %g: alpha_t = %g, not max(alpha, 0)", name, alpha,
                    out.alpha_t);
    ck_assert_msg(out.contact == 0 || out.contact == 1, "law '%s': contact flag", name);
    ck_assert_msg(out.contact || (out.f == 0.0 && out.f_el == 0.0),
                  "law '%s' at alpha = %g: force %g without contact", name, alpha, out.f);
    if (state0 == 0.0 && alpha < 0.0)
      ck_assert_msg(!out.contact, "law '%s' formed a contact at negative overlap", name);
    for (int h = 0; h < p->ct->law->nhist; h++)
      ck_assert_msg(isfinite(p->hist[h]), "law '%s': history %d not finite", name, h);
  }
}

START_TEST(test_every_law_path) {
  const dem_law *law = dem_contact_law_at(_i);
  dem_params ps;
  base_params(law, &ps);
  dem_contact ct;
  dem_err err = {0};
  ck_assert_int_eq(dem_contact_setup(&ct, law, &ps, &err), DEM_OK);
  const double rates[] = {0.0, 0.7, -0.7};
  for (int r = 0; r < 3; r++) {
    path_ctx p = {&ct, ref_geom(), {0}};
    ck_assert_msg(dem_contact_init(&ct, &p.g, p.hist, &err) == DEM_OK, "law '%s': %s",
                  law->name, err.msg);
    ck_assert(p.hist[DEM_HIST_STATE] == 0.0);
    /* Approach from apart, load, unload past separation, reload further, unload again. */
    const double turn[] = {-0.01, 0.01, -0.01, 0.002, -0.003, 0.03, -0.02};
    double a = turn[0] * R_REF;
    for (size_t t = 1; t < sizeof turn / sizeof turn[0]; t++) {
      double b = turn[t] * R_REF;
      walk(&p, a, b, 997, r == 0 ? 0.0 : (b > a ? fabs(rates[r]) : -fabs(rates[r])));
      a = b;
    }
  }
  const double vs[] = {0.01, 1.0, 10.0};
  for (int v = 0; v < 3; v++) {
    dem_geom g = ref_geom();
    double k = dem_contact_kref(&ct, &g, vs[v]);
    ck_assert_msg(isfinite(k) && k > 0.0, "law '%s': kref(%g) = %g", law->name, vs[v], k);
  }
}
END_TEST

/* --- 2. Per-law closed forms ----------------------------------------------------------- */

static double Es_ref(void) { return dem_reduced_modulus(E_REF, NU_REF, 1e30, 0.3); }

static void setup_law(dem_contact *ct, const char *name, dem_params *ps) {
  dem_err err = {0};
  const dem_law *law = dem_contact_law_find(name);
  ck_assert_ptr_nonnull(law);
  ck_assert_msg(dem_contact_setup(ct, law, ps, &err) == DEM_OK, "%s", err.msg);
}

static void jkr_params(dem_params *ps) {
  dem_params_init(ps);
  set(ps, "E", E_REF);
  set(ps, "nu", NU_REF);
  set(ps, "wall_E", 1e30);
  set(ps, "wall_nu", 0.3);
  set(ps, "gamma", GAMMA_REF);
}

static dem_normal ev(const dem_contact *ct, const dem_geom *g, double *hist, double alpha) {
  dem_normal n;
  dem_contact_force(ct, g, hist, alpha, 0.0, &n);
  return n;
}

/* JKR scales computed here from the sources, independently of dem/jkr.h. */
typedef struct {
  double Es, fc, alpha_f, alpha_0, alpha_c, w_adh;
} jkr_ref;

static jkr_ref jkr_reference(double R) {
  jkr_ref j;
  double Es = Es_ref(), G = GAMMA_REF;
  j.Es = Es;
  j.fc = 1.5 * M_PI * G * R;                                             /* thesis 3.40 */
  j.alpha_f = -0.75 * cbrt(M_PI * M_PI * G * G * R / (Es * Es));          /* brief / T&N */
  j.alpha_0 = cbrt(0.75) * cbrt(M_PI * M_PI * R * G * G / (Es * Es));    /* paper B11 */
  double ac = cbrt(9.0 * M_PI * G * R * R / (8.0 * Es));                 /* thesis 3.57 */
  /* Pull-off point: a = a_c in (3.42). */
  j.alpha_c = ac * ac / R - sqrt(2.0 * M_PI * G * ac / Es);
  j.w_adh = 7.09 * cbrt(pow(G, 5) * pow(R, 4) / (Es * Es));             /* T&N 1998 */
  return j;
}

START_TEST(test_jkr_root) {
  /* The closed-form root against an extended-precision Newton iteration, over the whole
   * range of A = alpha / delta_c; backward error (residual of the quartic relative to the
   * size of its terms) at round-off everywhere, forward error within a few ulps away from the
   * double root at A_f, where the condition number grows like 1/sqrt(A - A_f). */
  double worst_back = 0.0, worst_fwd = 0.0;
  int n = 0;
  for (double t = -8.0; t <= 14.0; t += 0.01, n++) {
    /* A from just above A_f (t < 0: A_f + 10^t) up to 1e14 (t >= 0: 10^t - 1). */
    double A = t < 0.0 ? DEM_JKR_AF + pow(10.0, t) : pow(10.0, t) - 1.0;
    double s = dem_jkr_root(A);
    long double S = s > 1.0 ? (long double)s : 1.5L;
    for (int it = 0; it < 100; it++) {
      long double f = S * S * S * S - 4.0L / 3.0L * S - A, fp = 4.0L * S * S * S - 4.0L / 3.0L;
      if (fp <= 0.0L) break;
      S -= f / fp;
    }
    long double res = (long double)s * s * s * s - 4.0L / 3.0L * s - A;
    long double scale = (long double)s * s * s * s + 4.0L / 3.0L * s + fabs(A);
    double back = (double)(fabsl(res) / scale) / DBL_EPSILON;
    if (back > worst_back) worst_back = back;
    if (A - DEM_JKR_AF > 1e-2) {
      double fwd = (double)(fabsl((long double)s - S) / S) / DBL_EPSILON;
      if (fwd > worst_fwd) worst_fwd = fwd;
    }
  }
  ck_assert_msg(worst_back < 8.0, "backward error %g eps", worst_back);
  ck_assert_msg(worst_fwd < 16.0, "forward error %g ulp", worst_fwd);
  ck_assert(n > 2000);
  /* The cube root used by the closed form, against cbrtl over its whole argument range. */
  double worst_cbrt = 0.0;
  for (double lx = log(1.0 / 9.0); lx < log(1e40); lx += 1e-3) {
    double x = exp(lx);
    long double r = cbrtl((long double)x);
    double err = (double)(fabsl((long double)dem_jkr_cbrt(x) - r) / r) / DBL_EPSILON;
    if (err > worst_cbrt) worst_cbrt = err;
  }
  ck_assert_msg(worst_cbrt < 1.0, "cube root error %g ulp", worst_cbrt);
  /* Its first layer (two Halley steps), used inside dem_jkr_root before the Newton step on
   * the quartic. */
  double worst_h = 0.0;
  for (double lx = log(1.0 / 9.0); lx < log(1e40); lx += 1e-3) {
    double x = exp(lx);
    long double r = cbrtl((long double)x);
    double err = (double)(fabsl((long double)dem_jkr_cbrt_halley(x) - r) / r) / DBL_EPSILON;
    if (err > worst_h) worst_h = err;
  }
  ck_assert_msg(worst_h < 32.0, "two-Halley cube root error %g ulp", worst_h);
  /* Landmarks of dem/jkr.h exactly. */
  ck_assert_double_eq_tol(dem_jkr_fhat(dem_jkr_root(0.0)), -8.0 / 9.0, 4e-16);
  ck_assert_double_eq_tol(dem_jkr_fhat(dem_jkr_root(-1.0 / 3.0)), -1.0, 1e-8);
  ck_assert_double_eq_tol(dem_jkr_fhat(dem_jkr_root(2.0 / 3.0 * cbrt(2.0))), 0.0, 4e-15);
  ck_assert_double_eq_tol(dem_jkr_fhat(dem_jkr_root(DEM_JKR_AF * (1 - 1e-14))), -5.0 / 9.0,
                          1e-6);
  ck_assert_double_eq_tol(DEM_JKR_AF, -cbrt(1.0 / 3.0), 1e-16);
  /* Huge overlaps stay finite. */
  ck_assert(isfinite(dem_jkr_fhat(dem_jkr_root(1e300))));
}
END_TEST

START_TEST(test_jkr_cross_check) {
  /* The law's force (dimensionless form F = f_c (s^6 - 2 s^3) with cached scales) against
   * the dimensional helpers of dem/jkr.h (eq 3.41 evaluated at the radius a(alpha) of 3.42,
   * the form thornton-ning's tests use): F(a(alpha)) along the whole stable branch, to
   * round-off. (Before the two JKR solvers were merged this compared two independent
   * solvers; test_jkr_root checks the one left against extended precision.) */
  dem_params ps;
  jkr_params(&ps);
  dem_contact ct;
  setup_law(&ct, "jkr", &ps);
  dem_geom g = ref_geom();
  jkr_ref j = jkr_reference(g.R);
  double hist[DEM_LAW_NHIST_MAX] = {0};
  ev(&ct, &g, hist, 0.0);
  ck_assert_double_eq_tol(dem_jkr_alpha_f(g.R, j.Es, GAMMA_REF), j.alpha_f,
                          1e-12 * fabs(j.alpha_f));
  double worst = 0.0;
  for (double t = 0.0; t <= 1.0; t += 1e-3) {
    /* from just above alpha_f to 1000 alpha_0, denser near alpha_f */
    double a = j.alpha_f + (1000.0 * j.alpha_0 - j.alpha_f) * t * t * t + 1e-6 * fabs(j.alpha_f);
    double F = ev(&ct, &g, hist, a).f;
    double Fr = dem_jkr_force(g.R, j.Es, GAMMA_REF, dem_jkr_radius(g.R, j.Es, GAMMA_REF, a));
    double d = fabs(F - Fr) / (fabs(Fr) + j.fc);
    if (d > worst) worst = d;
  }
  ck_assert_msg(worst < 1e-11, "largest difference %g f_c", worst);
}
END_TEST

START_TEST(test_jkr_alpha_t) {
  /* dem_normal.alpha_t = a^2/R* for jkr and jkr-modified, at points where the contact
   * radius is known in closed form: jump-in alpha = 0, a^3 = 2 pi Gamma R*^2 / E* (paper
   * B5); zero force alpha_0, a^3 = 9/2 pi Gamma R*^2 / E* (B8); pull-off (jkr only),
   * a = a_c, a_c^3 = 9 pi Gamma R*^2 / (8 E*) (thesis 3.57); and along the curve against
   * dem_jkr_radius. */
  const char *names[] = {"jkr", "jkr-modified"};
  for (int l = 0; l < 2; l++) {
    dem_params ps;
    jkr_params(&ps);
    dem_contact ct;
    setup_law(&ct, names[l], &ps);
    dem_geom g = ref_geom();
    jkr_ref j = jkr_reference(g.R);
    double R = g.R, G = GAMMA_REF, Es = j.Es;
    double hist[DEM_LAW_NHIST_MAX] = {0};
    double a0 = cbrt(2.0 * M_PI * G * R * R / Es), az = cbrt(4.5 * M_PI * G * R * R / Es);
    double ac = cbrt(9.0 * M_PI * G * R * R / (8.0 * Es));
    ck_assert_double_eq_tol(ev(&ct, &g, hist, 0.0).alpha_t, a0 * a0 / R, 1e-13 * a0 * a0 / R);
    ck_assert_double_eq_tol(ev(&ct, &g, hist, j.alpha_0).alpha_t, az * az / R,
                            1e-13 * az * az / R);
    if (l == 0)
      ck_assert_double_eq_tol(ev(&ct, &g, hist, j.alpha_c).alpha_t, ac * ac / R,
                              1e-7 * ac * ac / R); /* near the minimum: a(alpha) ill-posed */
    for (double t = 0.0; t < 1.0; t += 0.01) {
      double al = (l == 0 ? 0.999 * j.alpha_f : 0.0) + t * t * 50.0 * j.alpha_0;
      double a = dem_jkr_radius(R, Es, G, al), at = ev(&ct, &g, hist, al).alpha_t;
      ck_assert_msg(fabs(at - a * a / R) <= 1e-13 * a * a / R, "%s alpha %g: alpha_t %g a^2/R %g",
                    names[l], al, at, a * a / R);
    }
  }
}
END_TEST

START_TEST(test_jkr_curve) {
  dem_params ps;
  jkr_params(&ps);
  dem_contact ct;
  setup_law(&ct, "jkr", &ps);
  dem_geom g = ref_geom();
  jkr_ref j = jkr_reference(g.R);
  double hist[DEM_LAW_NHIST_MAX] = {0};
  dem_err err = {0};
  ck_assert_int_eq(dem_contact_init(&ct, &g, hist, &err), DEM_OK);

  /* Approach: no force at negative overlap, not even inside the adhesive range. */
  for (double a = 2.0 * j.alpha_f; a < 0.0; a -= j.alpha_f / 50.0) {
    dem_normal n = ev(&ct, &g, hist, a);
    ck_assert(n.contact == 0 && n.f == 0.0);
  }
  /* Jump-in at alpha = 0: F = -8/9 f_c (thesis 3.4.3.1, paper B6). */
  dem_normal n = ev(&ct, &g, hist, 0.0);
  ck_assert_int_eq(n.contact, 1);
  ck_assert_double_eq_tol(n.f, -8.0 / 9.0 * j.fc, 1e-12 * j.fc);
  ck_assert_double_eq_tol(n.f_adh, 2.0 * j.fc, 1e-12 * j.fc);
  /* Stiffness at alpha = 0, paper B7: (16 pi / 27)^(1/3) (Gamma E*^2 R*^2)^(1/3). */
  double kscale = cbrt(GAMMA_REF * j.Es * j.Es * g.R * g.R);
  ck_assert_double_eq_tol(n.k, cbrt(16.0 * M_PI / 27.0) * kscale, 1e-10 * n.k);
  /* Zero-force overlap alpha_0 (paper B11) and the stiffness there (B10). */
  n = ev(&ct, &g, hist, j.alpha_0);
  ck_assert_double_eq_tol(n.f, 0.0, 1e-12 * j.fc);
  ck_assert_double_eq_tol(n.k, 1.2 * cbrt(4.5) * cbrt(M_PI) * kscale, 1e-10 * n.k);
  /* Loading to 20 alpha_0: F rises monotonically, stiffness = dF/dalpha, tends to Hertz
   * shifted by about alpha_0 and lies above plain Hertz (adhesion widens the contact). */
  double prev = -INFINITY;
  for (double a = 0.0; a <= 20.0 * j.alpha_0; a += j.alpha_0 / 40.0) {
    n = ev(&ct, &g, hist, a);
    ck_assert(n.f > prev && n.contact == 1 && n.k > 0.0);
    prev = n.f;
  }
  for (double a = 0.5 * j.alpha_0; a < 20.0 * j.alpha_0; a *= 1.7) {
    double h = 1e-6 * a;
    double fp = ev(&ct, &g, hist, a + h).f, fm = ev(&ct, &g, hist, a - h).f;
    n = ev(&ct, &g, hist, a);
    ck_assert_msg(fabs(n.k - (fp - fm) / (2 * h)) < 1e-6 * n.k, "k at %g", a);
    ck_assert(n.f > 4.0 / 3.0 * j.Es * sqrt(g.R) * pow(a, 1.5) - j.fc);
  }
  /* Unloading along the same curve: minimum of F over a fine path = -f_c, at alpha_c. */
  double fmin = INFINITY, amin = 0.0;
  for (int i = 0; i <= 20000; i++) {
    double a = 20.0 * j.alpha_0 + (0.999999 * j.alpha_f - 20.0 * j.alpha_0) * i / 20000.0;
    n = ev(&ct, &g, hist, a);
    ck_assert_int_eq(n.contact, 1);
    if (n.f < fmin) {
      fmin = n.f;
      amin = a;
    }
  }
  ck_assert_double_eq_tol(fmin, -j.fc, 1e-6 * j.fc);                 /* pull-off, 3.40 */
  ck_assert_double_eq_tol(amin, j.alpha_c, 2e-3 * fabs(j.alpha_c));
  ck_assert_double_eq_tol(ev(&ct, &g, hist, j.alpha_c).f, -j.fc, 1e-12 * j.fc);
  /* alpha_c = -delta_c/3 and alpha_f = -3^(-1/3) delta_c: alpha_c = 3^(-2/3) alpha_f. */
  ck_assert_double_eq_tol(j.alpha_c, j.alpha_f * cbrt(1.0 / 9.0), 1e-12 * fabs(j.alpha_c));
  /* Damping is zero where dF/dalpha <= 0 (beyond the pull-off point), positive before. */
  dem_normal nd;
  dem_contact_force(&ct, &g, hist, 0.5 * (j.alpha_c + j.alpha_f), -1.0, &nd);
  ck_assert(nd.k == 0.0 && nd.f_damp == 0.0);
  /* At the breaking overlap: F = -5/9 f_c (square-root approach, hence the tolerance). */
  n = ev(&ct, &g, hist, j.alpha_f * (1.0 - 1e-12));
  ck_assert_int_eq(n.contact, 1);
  ck_assert_double_eq_tol(n.f, -5.0 / 9.0 * j.fc, 1e-5 * j.fc);
  /* Break just beyond alpha_f. */
  n = ev(&ct, &g, hist, j.alpha_f * (1.0 + 1e-9));
  ck_assert(n.contact == 0 && n.f == 0.0 && n.f_adh == 0.0);
  ck_assert(hist[DEM_HIST_STATE] == 0.0);
  /* Re-approach: no re-contact before alpha = 0 (hysteresis), re-contact at 0 with -8/9 f_c. */
  for (double a = j.alpha_f; a < 0.0; a -= j.alpha_f / 64.0)
    ck_assert_int_eq(ev(&ct, &g, hist, a).contact, 0);
  n = ev(&ct, &g, hist, 0.0);
  ck_assert(n.contact == 1 && fabs(n.f + 8.0 / 9.0 * j.fc) < 1e-12 * j.fc);
}
END_TEST

/* Work along the unloading path from a to b (a > b), trapezoid on n steps. */
static double work(const dem_contact *ct, const dem_geom *g, double *hist, double a, double b,
                   int n) {
  double w = 0.0, fprev = ev(ct, g, hist, a).f;
  for (int i = 1; i <= n; i++) {
    double x = a + (b - a) * i / n, f = ev(ct, g, hist, x).f;
    w += 0.5 * (f + fprev) * (x - (a + (b - a) * (i - 1) / n));
    fprev = f;
  }
  return w;
}

START_TEST(test_jkr_work_of_adhesion) {
  /* Thornton & Ning (1998): separating the surfaces costs 7.09 (Gamma^5 R*^4 / E*^2)^(1/3)
   * beyond the elastic work, which is all recovered at alpha = 0; i.e. the integral of |F|
   * along the unloading path from alpha = 0 to alpha_f (here 7.0922, exact constant
   * (3/2) pi (81/64)^(1/3) pi^(2/3) x 0.6437...). From the zero-force overlap alpha_0 instead,
   * the integral is 11.695 (Gamma^5 R*^4 / E*^2)^(1/3): see docs/contact-laws.md. */
  dem_params ps;
  jkr_params(&ps);
  dem_contact ct;
  setup_law(&ct, "jkr", &ps);
  dem_geom g = ref_geom();
  jkr_ref j = jkr_reference(g.R);
  double hist[DEM_LAW_NHIST_MAX] = {0};
  ev(&ct, &g, hist, 0.0);
  ev(&ct, &g, hist, 3.0 * j.alpha_0);
  double scale = cbrt(pow(GAMMA_REF, 5) * pow(g.R, 4) / (j.Es * j.Es));
  double w0 = work(&ct, &g, hist, 0.0, j.alpha_f, 200000);
  ck_assert_msg(fabs(w0 - j.w_adh) < 0.01 * j.w_adh, "W(0 -> alpha_f) = %g, 7.09 x = %g", w0,
                j.w_adh);
  ck_assert_double_eq_tol(w0 / scale, 7.0922, 1e-3);
  ck_assert_int_eq(ev(&ct, &g, hist, 0.0).contact, 1);
  double wa = work(&ct, &g, hist, j.alpha_0, j.alpha_f, 200000);
  ck_assert_double_eq_tol(wa / scale, 11.6946, 2e-3);
  /* Loading and unloading between 0 and alpha_max are conservative. */
  ck_assert_double_eq_tol(work(&ct, &g, hist, 0.0, 5 * j.alpha_0, 100000) +
                              work(&ct, &g, hist, 5 * j.alpha_0, 0.0, 100000),
                          0.0, 1e-9 * scale);
}
END_TEST

START_TEST(test_jkr_modified_curve) {
  dem_params ps;
  jkr_params(&ps);
  dem_contact ct, cj;
  setup_law(&ct, "jkr-modified", &ps);
  setup_law(&cj, "jkr", &ps);
  dem_geom g = ref_geom();
  jkr_ref j = jkr_reference(g.R);
  double hist[DEM_LAW_NHIST_MAX] = {0}, hj[DEM_LAW_NHIST_MAX] = {0};
  /* No force while apart; forms at 0 with -8/9 f_c; the same curve as jkr for alpha >= 0. */
  ck_assert_int_eq(ev(&ct, &g, hist, 0.5 * j.alpha_f).contact, 0);
  dem_normal n = ev(&ct, &g, hist, 0.0);
  ck_assert(n.contact == 1 && fabs(n.f + 8.0 / 9.0 * j.fc) < 1e-12 * j.fc);
  ev(&cj, &g, hj, 0.0);
  for (double a = 0.0; a < 10 * j.alpha_0; a += j.alpha_0 / 7.0)
    ck_assert_double_eq(ev(&ct, &g, hist, a).f, ev(&cj, &g, hj, a).f);
  ck_assert_double_eq_tol(ev(&ct, &g, hist, j.alpha_0).f, 0.0, 1e-12 * j.fc);
  /* Unloading: still in contact at alpha = 0 (F = -8/9 f_c, the largest tension reached),
   * broken at any negative overlap. */
  double fmin = INFINITY;
  for (double a = 10 * j.alpha_0; a >= 0.0; a -= j.alpha_0 / 64.0) {
    n = ev(&ct, &g, hist, a);
    if (n.f < fmin) fmin = n.f;
  }
  n = ev(&ct, &g, hist, 0.0);
  ck_assert(n.contact == 1 && fabs(n.f + 8.0 / 9.0 * j.fc) < 1e-12 * j.fc);
  ck_assert(fmin >= -8.0 / 9.0 * j.fc * (1 + 1e-12));
  n = ev(&ct, &g, hist, -1e-18);
  ck_assert(n.contact == 0 && n.f == 0.0 && hist[DEM_HIST_STATE] == 0.0);
  /* Not re-formed at negative overlap, re-formed at 0. */
  ck_assert_int_eq(ev(&ct, &g, hist, 0.3 * j.alpha_f).contact, 0);
  ck_assert_int_eq(ev(&ct, &g, hist, 0.0).contact, 1);
  /* No work of adhesion: the closed cycle 0 -> alpha_max -> 0 does no net work. */
  ck_assert_double_eq_tol(work(&ct, &g, hist, 0.0, 4 * j.alpha_0, 50000) +
                              work(&ct, &g, hist, 4 * j.alpha_0, 0.0, 50000),
                          0.0, 1e-12 * j.fc * j.alpha_0);
}
END_TEST

START_TEST(test_jkr_damping) {
  /* f_d = eta_H(e) sqrt(m* k) alpha_dot, > 0 opposing approach; e = 1: none. */
  dem_params ps;
  jkr_params(&ps);
  set(&ps, "e", 0.6);
  dem_contact ct;
  setup_law(&ct, "jkr", &ps);
  dem_geom g = ref_geom();
  jkr_ref j = jkr_reference(g.R);
  double hist[DEM_LAW_NHIST_MAX] = {0};
  dem_normal n;
  dem_contact_force(&ct, &g, hist, 2.0 * j.alpha_0, 0.9, &n);
  double eta = dem_damping_eta_hertz(0.6, 0);
  ck_assert_double_eq_tol(n.f_damp, eta * sqrt(g.m * n.k) * 0.9, 1e-12 * fabs(n.f_damp));
  ck_assert(n.f_damp > 0.0);
  dem_contact_force(&ct, &g, hist, 2.0 * j.alpha_0, -0.9, &n);
  ck_assert(n.f_damp < 0.0);
}
END_TEST

static void thornton_params(dem_params *ps) {
  dem_params_init(ps);
  set(ps, "E", E_REF);
  set(ps, "nu", NU_REF);
  set(ps, "wall_E", 1e30);
  set(ps, "wall_nu", 0.3);
  set(ps, "py", PY_REF);
}

START_TEST(test_thornton_curve) {
  dem_params ps;
  thornton_params(&ps);
  dem_contact ct;
  setup_law(&ct, "thornton", &ps);
  dem_geom g = ref_geom();
  double R = g.R, Es = Es_ref(), py = PY_REF;
  double Fy = pow(M_PI, 3) * R * R * pow(py, 3) / (6.0 * Es * Es);  /* (3.27) */
  double ay = M_PI * M_PI * R * py * py / (4.0 * Es * Es);           /* (3.29) */
  double kp = M_PI * py * R;
  double hist[DEM_LAW_NHIST_MAX] = {0};
  /* Elastic below yield, reversible, no permanent overlap. */
  for (double a = 0.0; a <= 0.9 * ay; a += 0.01 * ay) {
    dem_normal n = ev(&ct, &g, hist, a);
    ck_assert_double_eq_tol(n.f, 4.0 / 3.0 * Es * sqrt(R) * pow(a, 1.5), 1e-12 * Fy);
  }
  ck_assert_double_eq_tol(ev(&ct, &g, hist, 0.3 * ay).f,
                          4.0 / 3.0 * Es * sqrt(R) * pow(0.3 * ay, 1.5), 1e-12 * Fy);
  ck_assert_int_eq(ev(&ct, &g, hist, -1e-12).contact, 0);
  /* Yield point: F_y (3.27) at alpha_y (3.29), continuity of F and of the stiffness. */
  dem_normal n = ev(&ct, &g, hist, ay);
  ck_assert_double_eq_tol(n.f, Fy, 1e-12 * Fy);
  ck_assert_double_eq_tol(n.k, kp, 1e-12 * kp);
  dem_normal n2 = ev(&ct, &g, hist, ay * (1 + 1e-9));
  ck_assert_double_eq_tol(n2.f, Fy, 1e-8 * Fy);
  ck_assert_double_eq_tol(n2.k, kp, 1e-14 * kp);
  /* Plastic line (3.28) up to alpha_max = 7 alpha_y. */
  double amax = 7.0 * ay, Fmax = Fy + kp * (amax - ay);
  for (double a = 1.5 * ay; a <= amax * (1 + 1e-12); a += 0.5 * ay)
    ck_assert_double_eq_tol(ev(&ct, &g, hist, a).f, Fy + kp * (a - ay), 1e-12 * Fmax);
  ck_assert_double_eq_tol(ev(&ct, &g, hist, amax).f, Fmax, 1e-12 * Fmax);
  /* Unloading: Hertz with R_p* (3.30), permanent overlap alpha_p (3.32), curve (3.31). */
  double Rp = 4.0 * Es / (3.0 * Fmax) * pow((2.0 * Fmax + Fy) / (2.0 * M_PI * py), 1.5);
  double ap = amax * (1.0 - R / Rp);
  ck_assert(Rp > R && ap > 0.0 && ap < amax);
  for (double a = amax; a > ap; a -= 0.05 * (amax - ap)) {
    n = ev(&ct, &g, hist, a);
    ck_assert_double_eq_tol(n.f, 4.0 / 3.0 * Es * sqrt(Rp) * pow(a - ap, 1.5), 1e-11 * Fmax);
    ck_assert_double_eq_tol(n.k, 2.0 * Es * sqrt(Rp * (a - ap)), 1e-11 * n.k + 1e-300);
  }
  /* Continuity at the turning point (needs sqrt(R_p*) in 3.31, not sqrt(R*)). */
  ck_assert_double_eq_tol(4.0 / 3.0 * Es * sqrt(Rp) * pow(amax - ap, 1.5), Fmax, 1e-12 * Fmax);
  n = ev(&ct, &g, hist, ap * (1 + 1e-9));
  ck_assert(n.contact == 1 && n.f < 1e-12 * Fmax);
  n = ev(&ct, &g, hist, 0.5 * ap);
  ck_assert(n.contact == 0 && n.f == 0.0);
  n = ev(&ct, &g, hist, -ay);
  ck_assert(n.contact == 0 && n.f == 0.0);
  /* Reloading along the unloading curve up to alpha_max, then the plastic line again. */
  for (double a = ap + 0.1 * (amax - ap); a <= amax; a += 0.1 * (amax - ap))
    ck_assert_double_eq_tol(ev(&ct, &g, hist, a).f,
                            4.0 / 3.0 * Es * sqrt(Rp) * pow(a - ap, 1.5), 1e-11 * Fmax);
  double amax2 = 9.0 * ay, Fmax2 = Fy + kp * (amax2 - ay);
  ck_assert_double_eq_tol(ev(&ct, &g, hist, amax2).f, Fmax2, 1e-12 * Fmax2);
  double Rp2 = 4.0 * Es / (3.0 * Fmax2) * pow((2.0 * Fmax2 + Fy) / (2.0 * M_PI * py), 1.5);
  double ap2 = amax2 * (1.0 - R / Rp2);
  ck_assert(ap2 > ap);
  double a = 0.5 * (ap2 + amax2);
  ck_assert_double_eq_tol(ev(&ct, &g, hist, a).f, 4.0 / 3.0 * Es * sqrt(Rp2) * pow(a - ap2, 1.5),
                          1e-11 * Fmax2);
  /* The identity behind (3.30): (2 F_max + F_y)/(2 pi p_y) = R* alpha_max. */
  ck_assert_double_eq_tol((2.0 * Fmax + Fy) / (2.0 * M_PI * py), R * amax, 1e-12 * R * amax);
}
END_TEST

START_TEST(test_thornton_errors) {
  /* p_y above 2 E* / pi would put the yield overlap beyond R*: rejected, naming py. */
  dem_params ps;
  thornton_params(&ps);
  set(&ps, "py", 0.7 * Es_ref());
  expect_error(dem_contact_law_find("thornton"), &ps, DEM_ERANGE, "py", "p_y > 2 E*/pi");
  set(&ps, "py", 0.6 * Es_ref());
  dem_contact ct;
  ck_assert_int_eq(dem_contact_setup(&ct, dem_contact_law_find("thornton"), &ps, NULL), DEM_OK);
}
END_TEST

START_TEST(test_walton_braun_curve) {
  dem_params ps;
  dem_params_init(&ps);
  set(&ps, "kp", 210.0);
  set(&ps, "ke", 1500.0);
  dem_contact ct;
  setup_law(&ct, "walton-braun", &ps);
  dem_geom g = ref_geom();
  double hist[DEM_LAW_NHIST_MAX] = {0}, kp = 210.0, ke = 1500.0, am = 2.385e-8;
  ck_assert_int_eq(ev(&ct, &g, hist, -1e-9).contact, 0);
  for (int i = 1; i <= 10; i++) { /* (3.36) */
    dem_normal n = ev(&ct, &g, hist, am * i / 10);
    ck_assert_double_eq_tol(n.f, kp * am * i / 10, 1e-12 * kp * am);
    ck_assert_double_eq(n.k, kp);
  }
  double Fm = ev(&ct, &g, hist, am).f, a0 = am * (1.0 - kp / ke);
  for (double a = am; a > a0; a -= (am - a0) / 10) {               /* (3.37) */
    dem_normal n = ev(&ct, &g, hist, a);
    ck_assert_double_eq_tol(n.f, ke * (a - a0), 1e-12 * Fm);
    ck_assert_double_eq(n.k, ke);
  }
  dem_normal n = ev(&ct, &g, hist, 0.99 * a0);
  ck_assert(n.contact == 0 && n.f == 0.0);
  ck_assert_int_eq(ev(&ct, &g, hist, -am).contact, 0);
  /* Reload along the unloading line to alpha_max, then plastic again. */
  ck_assert_double_eq_tol(ev(&ct, &g, hist, 0.5 * (a0 + am)).f, ke * 0.5 * (am - a0), 1e-12 * Fm);
  ck_assert_double_eq_tol(ev(&ct, &g, hist, am).f, Fm, 1e-12 * Fm);
  ck_assert_double_eq_tol(ev(&ct, &g, hist, 1.5 * am).f, kp * 1.5 * am, 1e-12 * Fm);
  /* New permanent overlap from the new turning point. */
  double a02 = 1.5 * am * (1.0 - kp / ke);
  ck_assert_double_eq_tol(ev(&ct, &g, hist, a02 + 0.1 * am).f, ke * 0.1 * am, 1e-12 * Fm);
  ck_assert_int_eq(ev(&ct, &g, hist, 0.999 * a02).contact, 0);

  /* Load-dependent k_e = k_p + S F_max (3.38): S in 1/m. */
  dem_params_init(&ps);
  set(&ps, "kp", 210.0);
  set(&ps, "S", 4.2e8);
  setup_law(&ct, "walton-braun", &ps);
  memset(hist, 0, sizeof hist);
  Fm = ev(&ct, &g, hist, am).f;
  double kes = kp + 4.2e8 * Fm;
  n = ev(&ct, &g, hist, 0.95 * am);
  ck_assert_double_eq_tol(n.k, kes, 1e-12 * kes);
  ck_assert_double_eq_tol(n.f, Fm - kes * 0.05 * am, 1e-12 * Fm);
  ck_assert_int_eq(ev(&ct, &g, hist, am * (1.0 - kp / kes) * 0.999).contact, 0);
  /* A larger F_max stiffens the unloading: the undamped restitution sqrt(k_p/k_e) falls. */
  ev(&ct, &g, hist, 3.0 * am);
  ck_assert(ev(&ct, &g, hist, 2.99 * am).k > kes);
  ck_assert_double_eq_tol(dem_contact_kref(&ct, &g, 1.0), kp + 4.2e8 * sqrt(g.m * kp), 1e-9 * kp);
}
END_TEST

START_TEST(test_walton_braun_errors) {
  const dem_law *law = dem_contact_law_find("walton-braun");
  dem_params ps;
  dem_params_init(&ps);
  set(&ps, "kp", 210.0);
  expect_error(law, &ps, DEM_EMISSING, "ke", "neither ke nor S");
  set(&ps, "ke", 200.0);
  expect_error(law, &ps, DEM_ERANGE, "ke", "ke < kp");
  set(&ps, "ke", 210.0);
  dem_contact ct;
  ck_assert_int_eq(dem_contact_setup(&ct, law, &ps, NULL), DEM_OK); /* ke = kp: e = 1 */
  set(&ps, "S", 1e8);
  expect_error(law, &ps, DEM_EUNSUPPORTED, "S", "both ke and S");
}
END_TEST

START_TEST(test_jkr_errors) {
  /* gamma is required and must be > 0 (f_c and the overlap scale vanish with it). */
  const dem_law *law = dem_contact_law_find("jkr");
  dem_params ps;
  jkr_params(&ps);
  set(&ps, "gamma", 0.0);
  expect_error(law, &ps, DEM_ERANGE, "gamma", "gamma = 0");
  jkr_params(&ps);
  remove_key(&ps, "gamma");
  expect_error(law, &ps, DEM_EMISSING, "gamma", "no gamma");
}
END_TEST

static Suite *suite(void) {
  Suite *s = suite_create("laws");
  int n = dem_contact_law_count();
  TCase *tc = tcase_create("every_law");
  tcase_set_timeout(tc, 60);
  tcase_add_loop_test(tc, test_every_law_errors, 0, n);
  tcase_add_loop_test(tc, test_every_law_path, 0, n);
  suite_add_tcase(s, tc);
  tc = tcase_create("jkr");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_jkr_root);
  tcase_add_test(tc, test_jkr_cross_check);
  tcase_add_test(tc, test_jkr_curve);
  tcase_add_test(tc, test_jkr_work_of_adhesion);
  tcase_add_test(tc, test_jkr_alpha_t);
  tcase_add_test(tc, test_jkr_modified_curve);
  tcase_add_test(tc, test_jkr_damping);
  tcase_add_test(tc, test_jkr_errors);
  suite_add_tcase(s, tc);
  tc = tcase_create("thornton");
  tcase_add_test(tc, test_thornton_curve);
  tcase_add_test(tc, test_thornton_errors);
  suite_add_tcase(s, tc);
  tc = tcase_create("walton_braun");
  tcase_add_test(tc, test_walton_braun_curve);
  tcase_add_test(tc, test_walton_braun_errors);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) {
  SRunner *sr = srunner_create(suite());
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
