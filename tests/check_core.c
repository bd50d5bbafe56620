/* Core module tests: errors, parameter sets, reduced properties, time steps, damping. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dem/contact.h"
#include "dem/error.h"
#include "dem/material.h"
#include "dem/params.h"
#include "dem/table.h"

START_TEST(test_strerror) {
  ck_assert_str_eq(dem_strerror(DEM_OK), "success");
  ck_assert_str_eq(dem_strerror(DEM_ERANGE), "value outside its allowed range");
  ck_assert_str_eq(dem_strerror(9999), "unknown status code");
  dem_err e = {0};
  ck_assert_int_eq(dem_err_set(&e, DEM_EPARSE, "x=%d", 3), DEM_EPARSE);
  dem_err_prefix(&e, "f.cfg:%d: ", 12);
  ck_assert_str_eq(e.msg, "f.cfg:12: x=3");
  ck_assert_int_eq(dem_err_set(NULL, DEM_EIO, "ignored"), DEM_EIO);
}
END_TEST

START_TEST(test_params) {
  dem_params ps;
  dem_err e = {0};
  dem_params_init(&ps);
  ck_assert_int_eq(dem_params_parse_assignment(&ps, "ke=1500", "--set", &e), DEM_OK);
  ck_assert_int_eq(dem_params_parse_assignment(&ps, "gamma=0.2", "a.cfg:3", &e), DEM_OK);
  double v;
  ck_assert(dem_params_get(&ps, "ke", &v));
  ck_assert_double_eq(v, 1500.0);
  ck_assert_str_eq(dem_params_origin(&ps, "gamma"), "a.cfg:3: ");
  ck_assert_int_eq(dem_params_parse_assignment(&ps, "ke=abc", "--set", &e), DEM_EPARSE);
  ck_assert(strstr(e.msg, "ke") != NULL);
  ck_assert_int_eq(dem_params_parse_assignment(&ps, "=3", "--set", &e), DEM_EPARSE);
  ck_assert_int_eq(dem_params_parse_assignment(&ps, "ke=1e999", "--set", &e), DEM_EPARSE);
  ck_assert_int_eq(dem_params_set(&ps, "kp", NAN, "--set", &e), DEM_ENONFINITE);
  ck_assert_int_eq(dem_params_set(&ps, "kp", INFINITY, "--set", &e), DEM_ENONFINITE);
  ck_assert_double_eq(dem_params_get_or(&ps, "absent", 2.5), 2.5);
}
END_TEST

START_TEST(test_reduced) {
  /* Equal spheres: R* = R/2, E* = E / (2 (1 - nu^2)), m* = m/2; a wall: R* = R, m* = m. */
  ck_assert_double_eq_tol(dem_reduced_radius(2.385e-6, 2.385e-6), 1.1925e-6, 1e-18);
  ck_assert_double_eq_tol(dem_reduced_radius(2.385e-6, INFINITY), 2.385e-6, 1e-18);
  double Es = dem_reduced_modulus(1.2e9, 0.3, 1.2e9, 0.3);
  ck_assert_double_eq_tol(Es, 1.2e9 / (2 * 0.91), 1e-3);
  /* Rigid wall: E* = E / (1 - nu^2). */
  ck_assert_double_eq_tol(dem_reduced_modulus(1.2e9, 0.3, INFINITY, 0.3), 1.2e9 / 0.91, 1e-3);
  /* Mindlin ratio k_t/k_n = 4 G_eq / E_eq = 2 (1 - nu)/(2 - nu) for equal materials. */
  double Gs = dem_reduced_shear_modulus(1.2e9, 0.3, 1.2e9, 0.3);
  ck_assert_double_eq_tol(4 * Gs / Es, 2 * 0.7 / 1.7, 1e-12);
  ck_assert_double_eq_tol(dem_reduced_mass(2.0, 2.0), 1.0, 1e-15);
  ck_assert_double_eq(dem_reduced_mass(2.0, INFINITY), 2.0);
}
END_TEST

START_TEST(test_time_steps) {
  /* Rayleigh, thesis eq (3.1), against a hand calculation for R = 2.45 um, rho = 1350,
   * E = 1.2 GPa, nu = 0.3: G = 4.615e8 Pa, sqrt(rho/G) = 1.7103e-3 s/m,
   * T_R = pi * 2.45e-6 * 1.7103e-3 / 0.92553 = 1.4223e-8 s. */
  double tr = dem_dt_rayleigh(2.45e-6, 1350.0, 1.2e9, 0.3);
  ck_assert_double_eq_tol(tr, 1.4223e-8, 1e-11);
  /* Mass-spring (4.29-4.31): sqrt((m/2)/(k/2)) = sqrt(m/k). */
  ck_assert_double_eq_tol(dem_dt_mass_spring(4e-9, 1e6), sqrt(4e-15), 1e-20);
}
END_TEST

START_TEST(test_eta_linear) {
  ck_assert_double_eq(dem_damping_eta_linear(1.0), 0.0);
  ck_assert(dem_damping_eta_linear(0.0) < 0);
  ck_assert(dem_damping_eta_linear(1.5) < 0);
  /* e = 0.5: 2 ln2 / sqrt(pi^2 + ln^2 2) = 1.386294 / 3.217150 = 0.430908 */
  ck_assert_double_eq_tol(dem_damping_eta_linear(0.5), 0.430908, 1e-6);
}
END_TEST

START_TEST(test_eta_hertz) {
  /* Monotone in e and finite; e = 1 needs no damping. */
  ck_assert_double_eq(dem_damping_eta_hertz(1.0, 0), 0.0);
  double prev = 0.0;
  for (double e = 0.95; e > 0.1; e -= 0.15) {
    double eta = dem_damping_eta_hertz(e, 0);
    ck_assert_msg(eta > prev, "eta(%g) = %g not increasing", e, eta);
    prev = eta;
    /* Clipping the tensile end force removes less energy: it needs more damping. */
    ck_assert(dem_damping_eta_hertz(e, 1) > eta);
  }
  ck_assert(dem_damping_eta_hertz(-0.1, 0) < 0);
  /* The closed form (unclipped) against the integrated dimensionless impact. */
  for (double e = 0.1; e < 0.95; e += 0.2) {
    double eta = dem_damping_eta_hertz(e, 0);
    ck_assert_double_eq_tol(dem_damping_restitution_hertz(eta, 0), e, 1e-9);
    ck_assert_double_eq_tol(dem_damping_restitution_hertz(dem_damping_eta_hertz(e, 1), 1), e,
                            1e-9);
  }
}
END_TEST

START_TEST(test_hertz_force) {
  /* f = 4/3 E* sqrt(R*) alpha^1.5 and k = df/dalpha (central difference); wall_E/wall_nu
   * default to the particle's values. */
  dem_params ps;
  dem_err err = {0};
  dem_params_init(&ps);
  dem_params_set(&ps, "E", 1.2e9, "t", &err);
  dem_params_set(&ps, "nu", 0.3, "t", &err);
  dem_contact ct;
  ck_assert_int_eq(dem_contact_setup(&ct, &dem_law_hertz, &ps, &err), DEM_OK);
  dem_geom g = {2.385e-6, 4.1e-14};
  double hist[1] = {0}, a = 3.7e-8;
  dem_normal n, np, nm;
  dem_contact_force(&ct, &g, hist, a, 0.0, &n);
  double Es = dem_reduced_modulus(1.2e9, 0.3, 1.2e9, 0.3);
  ck_assert_double_eq_tol(n.f, 4.0 / 3.0 * Es * sqrt(g.R) * pow(a, 1.5), 1e-12 * n.f);
  dem_contact_force(&ct, &g, hist, a * (1 + 1e-6), 0.0, &np);
  dem_contact_force(&ct, &g, hist, a * (1 - 1e-6), 0.0, &nm);
  ck_assert_double_eq_tol(n.k, (np.f - nm.f) / (2e-6 * a), 1e-6 * n.k);
  dem_contact_force(&ct, &g, hist, -1e-9, -1.0, &n);
  ck_assert_int_eq(n.contact, 0);
  ck_assert_double_eq(n.f, 0.0);
  /* Damping: e outside (0, 1] is rejected by the generic range check, naming the key. */
  dem_params_set(&ps, "e", 1.5, "x.cfg:4", &err);
  ck_assert_int_eq(dem_contact_setup(&ct, &dem_law_hertz, &ps, &err), DEM_ERANGE);
  ck_assert(strstr(err.msg, "x.cfg:4") && strstr(err.msg, "'e'"));
}
END_TEST

START_TEST(test_mkdirs) {
  /* mkdir -p makes every level, is idempotent, and names the level that fails and why. */
  const char *base = DEM_BINARY_DIR "/test-out/check_core_mkdirs";
  char d[700], f[512];
  dem_err err = {0};
  snprintf(d, sizeof d, "%s/a/b/c", base);
  ck_assert_int_eq(dem_mkdirs(d, &err), DEM_OK);
  ck_assert_int_eq(dem_mkdirs(d, &err), DEM_OK);
  snprintf(d, sizeof d, "%s/a/b/c/", base); /* a trailing slash is the same folder */
  ck_assert_int_eq(dem_mkdirs(d, &err), DEM_OK);
  snprintf(f, sizeof f, "%s/file", base);
  FILE *fp = fopen(f, "w");
  ck_assert_ptr_nonnull(fp);
  fclose(fp);
  ck_assert_int_eq(dem_mkdirs(f, &err), DEM_EIO); /* exists, but is not a folder */
  ck_assert_ptr_nonnull(strstr(err.msg, "file': Not a directory"));
  snprintf(d, sizeof d, "%s/x/y", f); /* through a file: the first level below it fails */
  ck_assert_int_eq(dem_mkdirs(d, &err), DEM_EIO);
  char want[800];
  snprintf(want, sizeof want, "cannot create the folder '%s/x': Not a directory", f);
  ck_assert_str_eq(err.msg, want);
  ck_assert_int_eq(dem_mkdirs("", &err), DEM_EINVAL);
  char *longp = malloc(DEM_PATH_MAX + 1);
  memset(longp, 'a', DEM_PATH_MAX);
  longp[DEM_PATH_MAX] = '\0';
  ck_assert_int_eq(dem_mkdirs(longp, &err), DEM_EINVAL);
  ck_assert_ptr_nonnull(strstr(err.msg, "allowed up to 4095"));
  free(longp);
}
END_TEST

static Suite *suite(void) {
  Suite *s = suite_create("core");
  TCase *tc = tcase_create("core");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_strerror);
  tcase_add_test(tc, test_params);
  tcase_add_test(tc, test_reduced);
  tcase_add_test(tc, test_time_steps);
  tcase_add_test(tc, test_eta_linear);
  tcase_add_test(tc, test_eta_hertz);
  tcase_add_test(tc, test_hertz_force);
  tcase_add_test(tc, test_mkdirs);
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
