/* Impacts through the laws of tests/check_laws.c (dem/impact.h): closed-form restitution,
 * yield and sticking velocities of a sphere on a rigid wall, undamped (e = 1).
 *
 * Reference case of the physics notes: R = 2.45 um, rho = 1350 kg/m^3, E = 1.2 GPa,
 * nu = 0.3, Gamma = 0.2 J/m^2, p_y = 35.3 MPa, rigid wall (wall_E = 1e30), so R* = R,
 * m* = 4/3 pi R^3 rho, E* = E / (1 - nu^2) = 1.3187 GPa.
 *
 * Closed forms (derivations in docs/contact-laws.md):
 * - JKR (Thornton & Ning 1998): critical sticking velocity
 *       v_s = 1.84 (Gamma / R)^(5/6) / (rho^(1/2) E*^(1/3))     (0.566 m/s here)
 *   from 1/2 m v_s^2 = W_adh = 7.09 (Gamma^5 R^4 / E*^2)^(1/3); above it, since the only loss
 *   of the undamped law is W_adh, e = sqrt(1 - (v_s / v)^2).
 * - Thornton (1997): yield velocity V_y = (pi^4 / 40)^(1/2) (p_y^5 / (E*^4 rho))^(1/2)
 *   (= 1.56 (...)^(1/2), 0.181 m/s here) and, for V_i > V_y, x = V_y / V_i,
 *       e = (6 sqrt3 / 5)^(1/2) (1 - x^2/6)^(1/2) [x / (x + 2 sqrt(6/5 - x^2/5))]^(1/4).
 * - Walton-Braun: e = sqrt(k_p / k_e) at every velocity.
 * Tolerances: 1% where the task states one (sticking velocity; observed 0.01%); elsewhere
 * 5e-4 to 2e-3, well above the O(dt^2) integration error at the default dt factor 0.01
 * (observed: Thornton e to 5e-6, v_stick to 2e-5 of the exact constant) and far below the
 * effects being tested.
 */
#include <check.h>
#include <math.h>
#include <stdlib.h>

#include "dem/contact.h"
#include "dem/error.h"
#include "dem/impact.h"
#include "dem/material.h"
#include "dem/params.h"

#define R_REF 2.45e-6
#define RHO_REF 1350.0
#define E_REF 1.2e9
#define NU_REF 0.3
#define GAMMA_REF 0.2
#define PY_REF 35.3e6

static double Es_ref(void) { return dem_reduced_modulus(E_REF, NU_REF, 1e30, 0.3); }

static void scene(dem_impact_scene *sc, const char *law, const char *k1, double v1,
                  const char *k2, double v2) {
  dem_params ps;
  dem_err err = {0};
  dem_params_init(&ps);
  dem_params_set(&ps, "R", R_REF, "test", &err);
  dem_params_set(&ps, "rho", RHO_REF, "test", &err);
  const dem_law *l = dem_contact_law_find(law);
  ck_assert_ptr_nonnull(l);
  if (dem_contact_law_has_coef(l, "E")) {
    dem_params_set(&ps, "E", E_REF, "test", &err);
    dem_params_set(&ps, "nu", NU_REF, "test", &err);
    dem_params_set(&ps, "wall_E", 1e30, "test", &err);
    dem_params_set(&ps, "wall_nu", 0.3, "test", &err);
  }
  if (k1) dem_params_set(&ps, k1, v1, "test", &err);
  if (k2) dem_params_set(&ps, k2, v2, "test", &err);
  ck_assert_msg(dem_impact_setup(sc, l, &ps, DEM_TARGET_WALL, &err) == DEM_OK, "%s", err.msg);
}

static dem_impact_result run(const dem_impact_scene *sc, double v) {
  dem_impact_opts o;
  dem_impact_opts_default(&o);
  dem_impact_result r;
  dem_err err = {0};
  ck_assert_msg(dem_impact_run(sc, &o, v, &r, &err) == DEM_OK, "v = %g: %s", v, err.msg);
  return r;
}

static double jkr_vs(void) {
  return 1.84 * pow(GAMMA_REF / R_REF, 5.0 / 6.0) / (sqrt(RHO_REF) * cbrt(Es_ref()));
}

START_TEST(test_jkr_sticking_velocity) {
  dem_impact_scene sc;
  scene(&sc, "jkr", "gamma", GAMMA_REF, NULL, 0);
  dem_impact_opts o;
  dem_impact_opts_default(&o);
  dem_err err = {0};
  double vs;
  ck_assert_msg(dem_impact_sticking(&sc, &o, 0.05, 5.0, 1e-4, &vs, &err) == DEM_OK, "%s",
                err.msg);
  double ref = jkr_vs();
  ck_assert_msg(fabs(vs - ref) < 0.01 * ref, "v_stick = %g m/s, T&N 1998: %g m/s", vs, ref);
  /* The exact constant of this curve, sqrt(3 x 7.0922 / (2 pi)) = 1.8402. */
  ck_assert_msg(fabs(vs / ref * 1.84 - 1.8402) < 2e-3 * 1.84, "constant %g", vs / ref * 1.84);
  ck_assert(run(&sc, 0.98 * ref).stuck);
  ck_assert(!run(&sc, 1.02 * ref).stuck);
}
END_TEST

START_TEST(test_jkr_restitution) {
  /* Undamped JKR loses exactly the work of adhesion: e = sqrt(1 - (v_s/v)^2). */
  dem_impact_scene sc;
  scene(&sc, "jkr", "gamma", GAMMA_REF, NULL, 0);
  double vs = 1.8402 / 1.84 * jkr_vs();
  const double v[] = {0.8, 2.0, 5.0, 10.0};
  for (int i = 0; i < 4; i++) {
    dem_impact_result r = run(&sc, v[i]);
    double e = sqrt(1.0 - (vs / v[i]) * (vs / v[i]));
    ck_assert_msg(!r.stuck && fabs(r.e - e) < 2e-3, "v = %g: e = %g, closed form %g", v[i], r.e,
                  e);
    /* Pull-off force f_c = 1.5 pi Gamma R* during the unloading. */
    ck_assert_msg(fabs(r.f_pulloff - 1.5 * M_PI * GAMMA_REF * R_REF) <
                      1e-2 * 1.5 * M_PI * GAMMA_REF * R_REF,
                  "v = %g: pull-off %g", v[i], r.f_pulloff);
  }
}
END_TEST

START_TEST(test_jkr_damped) {
  /* With e = 0.5 (Hertz-type damping on k_d = max(dF/dalpha, 0)): e(v) rises with v towards
   * 0.5 (the JKR curve tends to Hertz at large overlap) and sticking happens at higher speed
   * than without damping. */
  dem_impact_scene sc;
  scene(&sc, "jkr", "gamma", GAMMA_REF, "e", 0.5);
  const double v[] = {2.0, 5.0, 10.0, 50.0};
  double prev = 0.0;
  for (int i = 0; i < 4; i++) {
    dem_impact_result r = run(&sc, v[i]);
    ck_assert_msg(!r.stuck && r.e > prev && r.e <= 0.5, "v = %g: e = %g", v[i], r.e);
    prev = r.e;
  }
  ck_assert_msg(prev > 0.49, "e(50 m/s) = %g", prev);
  dem_impact_opts o;
  dem_impact_opts_default(&o);
  dem_err err = {0};
  double vs;
  ck_assert_msg(dem_impact_sticking(&sc, &o, 0.05, 50.0, 1e-3, &vs, &err) == DEM_OK, "%s",
                err.msg);
  ck_assert_msg(vs > 1.5 * jkr_vs(), "damped v_stick %g", vs);
}
END_TEST

START_TEST(test_jkr_modified_no_sticking) {
  /* jkr-modified breaks at alpha = 0: no work of adhesion, e = 1 undamped, never sticks. */
  dem_impact_scene sc;
  scene(&sc, "jkr-modified", "gamma", GAMMA_REF, NULL, 0);
  const double v[] = {0.05, 0.3, 2.0};
  for (int i = 0; i < 3; i++) {
    dem_impact_result r = run(&sc, v[i]);
    ck_assert_msg(!r.stuck && fabs(r.e - 1.0) < 2e-3, "v = %g: e = %g", v[i], r.e);
    ck_assert(r.f_pulloff <= 8.0 / 9.0 * 1.5 * M_PI * GAMMA_REF * R_REF * (1 + 1e-9));
  }
}
END_TEST

static double thornton_vy(void) {
  double Es = Es_ref();
  return sqrt(pow(M_PI, 4) / 40.0) * sqrt(pow(PY_REF, 5) / (pow(Es, 4) * RHO_REF));
}

static double thornton_e(double v) {
  double x = thornton_vy() / v;
  if (x >= 1.0) return 1.0;
  return sqrt(6.0 * sqrt(3.0) / 5.0) * sqrt(1.0 - x * x / 6.0) *
         pow(x / (x + 2.0 * sqrt(6.0 / 5.0 - x * x / 5.0)), 0.25);
}

START_TEST(test_thornton_yield_velocity) {
  dem_impact_scene sc;
  scene(&sc, "thornton", "py", PY_REF, NULL, 0);
  double vy = thornton_vy(), R = R_REF, Es = Es_ref();
  double ay = M_PI * M_PI * R * PY_REF * PY_REF / (4.0 * Es * Es);
  double Fy = pow(M_PI, 3) * R * R * pow(PY_REF, 3) / (6.0 * Es * Es);
  ck_assert_double_eq_tol(vy / sqrt(pow(PY_REF, 5) / (pow(Es, 4) * RHO_REF)), 1.56, 1e-3);
  /* At V_y the impact just reaches the yield point; below it, elastic (e = 1, no alpha_p). */
  dem_impact_result r = run(&sc, vy);
  ck_assert_msg(fabs(r.alpha_max - ay) < 2e-3 * ay, "alpha_max %g, alpha_y %g", r.alpha_max, ay);
  ck_assert_msg(fabs(r.f_max - Fy) < 3e-3 * Fy, "f_max %g, F_y %g", r.f_max, Fy);
  r = run(&sc, 0.9 * vy);
  ck_assert(fabs(r.e - 1.0) < 2e-3 && r.alpha_p < 1e-3 * ay);
  r = run(&sc, 1.2 * vy);
  ck_assert(r.e < 1.0 - 1e-3 && r.alpha_p > 0.0);
}
END_TEST

START_TEST(test_thornton_restitution) {
  /* e(v) against Thornton's closed form, from just above yield to the reference
   * velocities of the physics notes (2, 5, 10 m/s = 11-55 V_y); alpha_p against (3.32). */
  dem_impact_scene sc;
  scene(&sc, "thornton", "py", PY_REF, NULL, 0);
  double vy = thornton_vy(), R = R_REF, Es = Es_ref(), py = PY_REF;
  double ay = M_PI * M_PI * R * py * py / (4.0 * Es * Es), kp = M_PI * py * R;
  double Fy = 2.0 / 3.0 * kp * ay, m = dem_sphere_mass(R, RHO_REF);
  const double v[] = {1.5 * vy, 3.0 * vy, 2.0, 5.0, 10.0};
  for (int i = 0; i < 5; i++) {
    dem_impact_result r = run(&sc, v[i]);
    double e = thornton_e(v[i]);
    ck_assert_msg(fabs(r.e - e) < 5e-4 * e, "v = %g m/s: e = %.6f, Thornton 1997: %.6f", v[i],
                  r.e, e);
    /* alpha_max from the energy balance, then R_p* (3.30) and alpha_p (3.32). */
    double win = 0.5 * m * v[i] * v[i], wy = 0.4 * Fy * ay;
    double amax = ay + (sqrt(Fy * Fy + 2.0 * kp * (win - wy)) - Fy) / kp;
    double Fmax = Fy + kp * (amax - ay);
    double Rp = 4.0 * Es / (3.0 * Fmax) * pow((2.0 * Fmax + Fy) / (2.0 * M_PI * py), 1.5);
    double ap = amax * (1.0 - R / Rp);
    ck_assert_msg(fabs(r.alpha_max - amax) < 2e-3 * amax, "alpha_max %g vs %g", r.alpha_max,
                  amax);
    ck_assert_msg(fabs(r.alpha_p - ap) < 5e-3 * ap, "alpha_p %g vs %g", r.alpha_p, ap);
  }
}
END_TEST

START_TEST(test_walton_braun_restitution) {
  dem_impact_scene sc;
  scene(&sc, "walton-braun", "kp", 210.0, "ke", 1500.0);
  const double v[] = {0.5, 2.0, 10.0};
  for (int i = 0; i < 3; i++) {
    dem_impact_result r = run(&sc, v[i]);
    ck_assert_msg(fabs(r.e - sqrt(210.0 / 1500.0)) < 2e-3, "v = %g: e = %g", v[i], r.e);
  }
  /* With damping: both branches are linear springs with the same damping ratio
   * zeta = eta(e)/2, and the phases of the loading (equilibrium to rest) and of the
   * unloading (rest to equilibrium) add up to half a damped period, so the restitution is
   * exactly e x sqrt(k_p / k_e) (observed to 1e-8 with the reference integrator). */
  scene(&sc, "walton-braun", "kp", 210.0, "ke", 1500.0);
  {
    dem_params ps;
    dem_err err = {0};
    dem_params_init(&ps);
    dem_params_set(&ps, "R", R_REF, "test", &err);
    dem_params_set(&ps, "rho", RHO_REF, "test", &err);
    dem_params_set(&ps, "kp", 210.0, "test", &err);
    dem_params_set(&ps, "ke", 1500.0, "test", &err);
    dem_params_set(&ps, "e", 0.5, "test", &err);
    ck_assert_int_eq(dem_impact_setup(&sc, dem_contact_law_find("walton-braun"), &ps,
                                      DEM_TARGET_WALL, &err),
                     DEM_OK);
    dem_impact_result r = run(&sc, 1.0);
    ck_assert_msg(fabs(r.e - 0.5 * sqrt(210.0 / 1500.0)) < 2e-3, "damped e = %g", r.e);
  }
  /* k_e = k_p + S F_max: e falls with velocity, e = sqrt(k_p / (k_p + S v sqrt(m k_p))). */
  scene(&sc, "walton-braun", "kp", 210.0, "S", 2e8);
  double m = dem_sphere_mass(R_REF, RHO_REF), prev = 1.0;
  for (int i = 0; i < 3; i++) {
    dem_impact_result r = run(&sc, v[i]);
    double e = sqrt(210.0 / (210.0 + 2e8 * v[i] * sqrt(m * 210.0)));
    ck_assert_msg(fabs(r.e - e) < 2e-3 * e && r.e < prev, "v = %g: e = %g vs %g", v[i], r.e, e);
    prev = r.e;
  }
}
END_TEST

static Suite *suite(void) {
  Suite *s = suite_create("laws_impact");
  TCase *tc = tcase_create("impact");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, test_jkr_sticking_velocity);
  tcase_add_test(tc, test_jkr_restitution);
  tcase_add_test(tc, test_jkr_damped);
  tcase_add_test(tc, test_jkr_modified_no_sticking);
  tcase_add_test(tc, test_thornton_yield_velocity);
  tcase_add_test(tc, test_thornton_restitution);
  tcase_add_test(tc, test_walton_braun_restitution);
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
