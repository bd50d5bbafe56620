/* Guards of the plastic and adhesive laws (issue 3, "Stability where methods fail"), run over
 * every law of the registry with the DEM_LAW_PLASTIC or DEM_LAW_ADHESIVE flag, so that laws
 * added later are covered without editing this file:
 *  - breakdown: an absurd time step is reported as an error (DEM_EUNSTABLE, DEM_ERUNAWAY or
 *    DEM_ENONFINITE, with a message naming the law and the step), never as numbers — every
 *    result field is NaN;
 *  - parameter sets the laws cannot represent are rejected with errors naming the values:
 *    k_e < k_p (every law with `ke`/`ke_max` and `kp`), a yield overlap beyond R* (laws with
 *    `py`: thornton-ning, nan);
 *  - the pull-off equations never meet a negative discriminant on the overlaps the drivers
 *    accept (a path to R* and back gives finite forces), and the permanent overlap of an impact
 *    lies in [0, alpha_max].
 * The parameter pool is the reference case of scripts/jobs/10-single-contact.sh (thesis Tables
 * 4.1/4.2), with `nan` taking k_el, k_p, k_cl from its own correlations (physics notes).
 */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dem/contact.h"
#include "dem/impact.h"
#include "dem/nan.h"
#include "dem/params.h"

typedef struct {
  const char *key;
  double value;
} kv;

static const kv pool[] = {
    {"E", 1.2e9},   {"nu", 0.3},    {"wall_E", 182e9}, {"wall_nu", 0.3}, {"gamma", 0.2},
    {"py", 35.3e6}, {"kn", 1500.0}, {"ke", 1500.0},    {"kp", 210.0},    {"kc", 20.0},
    {"kcp", 20.0},  {"f0", 2.1e-6}, {"f0p", 4.0e-6},   {"ke_max", 1500.0}, {"phi_f", 0.02},
    {"e", 1.0},     {NULL, 0.0}};

/* The law at registry index i if it is plastic or adhesive, else NULL. */
static const dem_law *pa_law(int i) {
  const dem_law *law = dem_contact_law_at(i);
  return law && (law->flags & (DEM_LAW_PLASTIC | DEM_LAW_ADHESIVE)) ? law : NULL;
}

static void pool_params(const dem_law *law, dem_params *ps) {
  dem_params_init(ps);
  ck_assert_int_eq(dem_params_set(ps, "R", 2.45e-6, "test", NULL), DEM_OK);
  ck_assert_int_eq(dem_params_set(ps, "rho", 1350.0, "test", NULL), DEM_OK);
  for (const kv *k = pool; k->key; k++) {
    int scene = strcmp(k->key, "E") == 0 || strcmp(k->key, "nu") == 0;
    if (!scene && !dem_contact_law_has_coef(law, k->key)) continue;
    if (strcmp(law->name, "nan") == 0 &&
        (!strcmp(k->key, "ke") || !strcmp(k->key, "kp") || !strcmp(k->key, "kc")))
      continue;
    ck_assert_int_eq(dem_params_set(ps, k->key, k->value, "test", NULL), DEM_OK);
  }
}

static int is_breakdown(int rc) {
  return rc == DEM_EUNSTABLE || rc == DEM_ERUNAWAY || rc == DEM_ENONFINITE;
}

static void assert_no_numbers(const dem_impact_result *r) {
  ck_assert(isnan(r->e) && isnan(r->v_rebound) && isnan(r->alpha_max) && isnan(r->alpha_p) &&
            isnan(r->f_max) && isnan(r->f_pulloff) && isnan(r->t_contact));
  ck_assert_int_eq(r->stuck, 0);
}

/* The reference set is accepted by every plastic/adhesive law (else the loops below would
 * test nothing for it). */
START_TEST(test_reference_set_accepted) {
  const dem_law *law = pa_law(_i);
  if (!law) return;
  dem_params ps;
  pool_params(law, &ps);
  dem_impact_scene sc;
  dem_err e = {0};
  ck_assert_msg(dem_impact_setup(&sc, law, &ps, DEM_TARGET_WALL, &e) == DEM_OK, "%s: %s",
                law->name, e.msg);
}
END_TEST

/* An absurd time step (dt factor 50 of the Rayleigh step, 10 of sqrt(m* / k_ref), an explicit
 * 1 us step) is an error, never a result, at 2, 5 and 10 m/s. */
START_TEST(test_absurd_dt_is_error) {
  const dem_law *law = pa_law(_i);
  if (!law) return;
  dem_params ps;
  pool_params(law, &ps);
  dem_impact_scene sc;
  dem_err e = {0};
  ck_assert_int_eq(dem_impact_setup(&sc, law, &ps, DEM_TARGET_WALL, &e), DEM_OK);
  const double vs[3] = {2.0, 5.0, 10.0};
  for (int k = 0; k < 3; k++)
    for (int mode = 0; mode < 3; mode++) {
      dem_impact_opts o;
      dem_impact_opts_default(&o);
      if (mode == 0) {
        o.dt_rule = DEM_DT_RAYLEIGH;
        o.dt_factor = 50.0;
      } else if (mode == 1) {
        o.dt_rule = DEM_DT_MASS_SPRING;
        o.dt_factor = 10.0;
      } else {
        o.dt = 1e-6; /* s; the contact lasts ~50 ns */
      }
      dem_impact_result r;
      memset(&e, 0, sizeof e);
      int rc = dem_impact_run(&sc, &o, vs[k], &r, &e);
      ck_assert_msg(is_breakdown(rc), "%s at v = %g, mode %d: status %d (%s), e = %g", law->name,
                    vs[k], mode, rc, dem_strerror(rc), r.e);
      ck_assert_int_eq(e.code, rc);
      ck_assert_msg(strstr(e.msg, law->name) && strstr(e.msg, "dt"),
                    "message should name the law and the step: %s", e.msg);
      assert_no_numbers(&r);
    }
}
END_TEST

/* The same through the sticking search: the breakdown propagates with its message. */
START_TEST(test_absurd_dt_sticking_is_error) {
  const dem_law *law = pa_law(_i);
  if (!law || !(law->flags & DEM_LAW_ADHESIVE)) return;
  dem_params ps;
  pool_params(law, &ps);
  dem_impact_scene sc;
  dem_err e = {0};
  ck_assert_int_eq(dem_impact_setup(&sc, law, &ps, DEM_TARGET_WALL, &e), DEM_OK);
  dem_impact_opts o;
  dem_impact_opts_default(&o);
  o.dt_factor = 50.0;
  double v = 0.0;
  int rc = dem_impact_sticking(&sc, &o, 0.1, 50.0, 1e-3, &v, &e);
  ck_assert_msg(is_breakdown(rc), "%s: status %d", law->name, rc);
  ck_assert(isnan(v));
  ck_assert_msg(strstr(e.msg, "sticking search") && strstr(e.msg, law->name), "%s", e.msg);
}
END_TEST

/* k_e < k_p: every law with both an elastic (ke, or ke_max for Luding-type laws and the
 * load-dependent variants) and a plastic stiffness rejects it, naming both values. */
START_TEST(test_ke_below_kp_rejected) {
  const dem_law *law = pa_law(_i);
  if (!law || !dem_contact_law_has_coef(law, "kp")) return;
  int tried = 0;
  for (int which = 0; which < 2; which++) {
    const char *key = which == 0 ? "ke" : "ke_max";
    if (!dem_contact_law_has_coef(law, key)) continue;
    dem_params ps;
    pool_params(law, &ps);
    ck_assert_int_eq(dem_params_set(&ps, "kp", 210.0, "test", NULL), DEM_OK);
    ck_assert_int_eq(dem_params_set(&ps, key, 123.5, "test", NULL), DEM_OK);
    /* ke_max only acts in the load-dependent variant where the law has a switch. */
    if (which == 1 && dem_contact_law_has_coef(law, "ke_load"))
      ck_assert_int_eq(dem_params_set(&ps, "ke_load", 1.0, "test", NULL), DEM_OK);
    if (which == 1 && dem_contact_law_has_coef(law, "ke") && !dem_contact_law_has_coef(law, "ke_load"))
      continue; /* ke_max is not the unloading stiffness of this law */
    dem_impact_scene sc;
    dem_err e = {0};
    int rc = dem_impact_setup(&sc, law, &ps, DEM_TARGET_WALL, &e);
    ck_assert_msg(rc == DEM_EPHYSICS || rc == DEM_ERANGE, "%s: %s = 123.5 < kp = 210 accepted (%d)",
                  law->name, key, rc);
    ck_assert_msg(strstr(e.msg, "123.5") && strstr(e.msg, "210"),
                  "%s: the message should name both values: %s", law->name, e.msg);
    tried++;
  }
  ck_assert_msg(tried > 0 || !dem_contact_law_has_coef(law, "ke"), "%s", law->name);
}
END_TEST

/* A yield overlap beyond R* (p_y of the order of E*): rejected by the laws with a yield
 * pressure, naming alpha_y, R* and p_y; p_y just inside is accepted. */
START_TEST(test_yield_beyond_radius_rejected) {
  const dem_law *law = pa_law(_i);
  if (!law || !dem_contact_law_has_coef(law, "py")) return;
  dem_params ps;
  pool_params(law, &ps);
  ck_assert_int_eq(dem_params_set(&ps, "py", 1.5e9, "test", NULL), DEM_OK);
  dem_impact_scene sc;
  dem_err e = {0};
  int rc = dem_impact_setup(&sc, law, &ps, DEM_TARGET_WALL, &e);
  ck_assert_msg(rc == DEM_EPHYSICS || rc == DEM_ERANGE, "%s: py = 1.5e9 accepted", law->name);
  ck_assert_msg(strstr(e.msg, "alpha_y") && strstr(e.msg, "R*") && strstr(e.msg, "1.5e+09"),
                "%s", e.msg);
  ck_assert_int_eq(dem_params_set(&ps, "py", 3e8, "test", NULL), DEM_OK);
  ck_assert_msg(dem_impact_setup(&sc, law, &ps, DEM_TARGET_WALL, &e) == DEM_OK, "%s: %s",
                law->name, e.msg);
}
END_TEST

/* The pull-off equations (pasha 4.10-4.11, nan 59, thornton-ning 3.58-3.59...) on the largest
 * overlaps the path driver accepts: load to R* (and to 0.3 R*), unload through tension, reload:
 * every force, stiffness and sliding-limit term finite, k >= 0, f_adh >= 0. */
typedef struct {
  int bad;
  double worst;
} path_ck;

static void path_row(double alpha, const dem_normal *n, void *user) {
  path_ck *c = user;
  if (!isfinite(n->f) || !isfinite(n->f_el) || !isfinite(n->k) || !isfinite(n->f_adh) ||
      n->k < 0.0 || n->f_adh < 0.0) {
    if (!c->bad) c->worst = alpha;
    c->bad++;
  }
}

START_TEST(test_pulloff_finite_to_radius) {
  const dem_law *law = pa_law(_i);
  if (!law) return;
  dem_params ps;
  pool_params(law, &ps);
  dem_impact_scene sc;
  dem_err e = {0};
  ck_assert_int_eq(dem_impact_setup(&sc, law, &ps, DEM_TARGET_WALL, &e), DEM_OK);
  const double R = sc.geom.R;
  const double paths[2][5] = {{0.0, R, -0.5 * R, R, -R}, {0.0, 0.3 * R, 0.0, 0.3 * R, -0.3 * R}};
  for (int p = 0; p < 2; p++) {
    path_ck c = {0, 0.0};
    ck_assert_msg(dem_contact_path(&sc.law, &sc.geom, paths[p], 5, R / 2000.0, path_row, &c,
                                   &e) == DEM_OK,
                  "%s", e.msg);
    ck_assert_msg(c.bad == 0, "%s: %d non-finite or negative values, first at alpha = %g m",
                  law->name, c.bad, c.worst);
  }
}
END_TEST

/* The permanent overlap of an impact at the reference case lies in [0, alpha_max]. */
START_TEST(test_permanent_overlap_in_range) {
  const dem_law *law = pa_law(_i);
  if (!law || !(law->flags & DEM_LAW_PLASTIC)) return;
  dem_params ps;
  pool_params(law, &ps);
  dem_impact_scene sc;
  dem_err e = {0};
  ck_assert_int_eq(dem_impact_setup(&sc, law, &ps, DEM_TARGET_WALL, &e), DEM_OK);
  dem_impact_opts o;
  dem_impact_opts_default(&o);
  o.t_max_factor = 20;
  const double vs[3] = {2.0, 5.0, 10.0};
  for (int k = 0; k < 3; k++) {
    dem_impact_result r;
    ck_assert_msg(dem_impact_run(&sc, &o, vs[k], &r, &e) == DEM_OK, "%s", e.msg);
    ck_assert_msg(r.alpha_p >= 0.0 && r.alpha_p <= r.alpha_max, "%s at %g m/s: alpha_p = %g, "
                  "alpha_max = %g", law->name, vs[k], r.alpha_p, r.alpha_max);
  }
}
END_TEST

/* The library's pull-off function reports a negative discriminant as NaN (never a number),
 * and the nan law's own constants can never produce one (alpha_p > 0: docs/contact-laws.md). */
START_TEST(test_fcp59_discriminant) {
  double A = dem_nan_A(1.8);
  ck_assert(isnan(dem_nan_fcp59(A, 1.0, -10.0))); /* alpha_p/alpha_0 << 0 */
  ck_assert(isfinite(dem_nan_fcp59(A, 1.0, 1.0)));
  dem_nan_input in = {2.45e-6, 1.31e9, 0.2, 35.3e6, NAN, NAN, NAN, 46, 59};
  dem_nan_coeffs k;
  dem_err e = {0};
  ck_assert_int_eq(dem_nan_coeffs_init(&k, &in, &e), DEM_OK);
  for (double am = k.alphay; am < 2.45e-6; am *= 1.1) {
    dem_nan_unload u;
    dem_nan_unloading(&k, am, &u);
    ck_assert(u.alpha_p > 0.0 && u.alpha_p < u.alpha_max && isfinite(u.f_cp) && u.f_cp > 0.0);
  }
  in.py = 1.5e9; /* yield beyond R* */
  ck_assert_int_eq(dem_nan_coeffs_init(&k, &in, &e), DEM_EPHYSICS);
  ck_assert_msg(strstr(e.msg, "alpha_y") && strstr(e.msg, "R*"), "%s", e.msg);
}
END_TEST

static Suite *suite(void) {
  Suite *s = suite_create("guards");
  const int n = dem_contact_law_count();
  TCase *t = tcase_create("reference_set");
  tcase_add_loop_test(t, test_reference_set_accepted, 0, n);
  suite_add_tcase(s, t);
  t = tcase_create("breakdown");
  tcase_set_timeout(t, 60);
  tcase_add_loop_test(t, test_absurd_dt_is_error, 0, n);
  tcase_add_loop_test(t, test_absurd_dt_sticking_is_error, 0, n);
  suite_add_tcase(s, t);
  t = tcase_create("unrepresentable_sets");
  tcase_add_loop_test(t, test_ke_below_kp_rejected, 0, n);
  tcase_add_loop_test(t, test_yield_beyond_radius_rejected, 0, n);
  tcase_add_test(t, test_fcp59_discriminant);
  suite_add_tcase(s, t);
  t = tcase_create("ranges");
  tcase_set_timeout(t, 60);
  tcase_add_loop_test(t, test_pulloff_finite_to_radius, 0, n);
  tcase_add_loop_test(t, test_permanent_overlap_in_range, 0, n);
  suite_add_tcase(s, t);
  return s;
}

int main(void) {
  SRunner *sr = srunner_create(suite());
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
