/* Impacts of a sphere on a wall with the `nan` and `thornton-ning` laws, through the 1-DOF
 * impact solver (dem/impact.h), against
 *  - the closed-form energy balance of the second seed (eqs 73-79, dem_nan_impact,
 *    dem_nan_vys): the integration must agree to 0.5 % at a small time step;
 *  - the second seed's Table 6 (V_ys with viscous damping e0 = 0.81, beta = 1 / 0.1), a DEM
 *    result in the paper: 3 % (reference_data/nan_wall1990_sticking/SOURCE.md);
 *  - the second seed's Table 2 (Ning 1995 unloading curves digitised: f_max, alpha_max,
 *    alpha_p, f_cp at 2, 5, 10 m/s), the lowest detaching velocity (~1.6 m/s, thesis 4.1.5)
 *    and the shape of e(v) (thesis Figs 3.22 / 4.24) for `thornton-ning`.
 * Where the law's equations give other numbers than the published ones, the test asserts the
 * equations (with the published value inside a stated band) and docs/contact-laws.md gives the
 * cause.
 */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dem/contact.h"
#include "dem/impact.h"
#include "dem/material.h"
#include "dem/nan.h"
#include "dem/params.h"

#define REL(a, b, tol)                                                                    \
  ck_assert_msg(fabs((double)(a) - (double)(b)) <= (tol)*fabs((double)(b)),               \
                "%s = %.10g, expected %.10g (rel tol %g)", #a, (double)(a), (double)(b), \
                (double)(tol))

static void set(dem_params *ps, const char *k, double v) {
  dem_err e = {0};
  ck_assert_int_eq(dem_params_set(ps, k, v, "test", &e), DEM_OK);
}

/* Table 5 (Kim & Dunn 2007) with the interface energy 0.24 J/m^2 that reproduces V_s. */
static void t5_params(dem_params *ps, double R, double py, double e0) {
  dem_params_init(ps);
  set(ps, "R", R);
  set(ps, "rho", 1350);
  set(ps, "E", 1.2e9);
  set(ps, "nu", 0.33);
  set(ps, "wall_E", 166e9);
  set(ps, "wall_nu", 0.28);
  set(ps, "gamma", 0.24);
  set(ps, "py", py);
  set(ps, "e", e0);
}

static void scene(dem_impact_scene *sc, const char *law, const dem_params *ps) {
  dem_err e = {0};
  ck_assert_msg(dem_impact_setup(sc, dem_contact_law_find(law), ps, DEM_TARGET_WALL, &e) ==
                    DEM_OK,
                "%s", e.msg);
}

static void nan_cf(double R, double py, dem_nan_coeffs *k) {
  dem_nan_input in = {R, dem_reduced_modulus(1.2e9, 0.33, 166e9, 0.28), 0.24, py, NAN, NAN, NAN,
                      46, 59};
  dem_err e = {0};
  ck_assert_int_eq(dem_nan_coeffs_init(k, &in, &e), DEM_OK);
}

/* Undamped: the integrated impact against the closed form (Appendix A, eqs 78-79). */
START_TEST(test_nan_closed_form) {
  double R = 2.45e-6, py = 30e6, m = dem_sphere_mass(R, 1350);
  dem_params ps;
  t5_params(&ps, R, py, 1.0);
  dem_impact_scene sc;
  scene(&sc, "nan", &ps);
  dem_nan_coeffs k;
  nan_cf(R, py, &k);
  dem_impact_opts o;
  dem_impact_opts_default(&o);
  o.dt_factor = 0.002;
  dem_err e = {0};
  const double vs[] = {2.5, 4.0, 8.0};
  for (int i = 0; i < 3; i++) {
    dem_impact_result r;
    dem_nan_impact_cf c;
    ck_assert_msg(dem_impact_run(&sc, &o, vs[i], &r, &e) == DEM_OK, "%s", e.msg);
    ck_assert_int_eq(dem_nan_impact(&k, m, vs[i], &c, &e), DEM_OK);
    ck_assert_int_eq(r.stuck, 0);
    REL(r.e, c.e, 0.005);
    REL(r.f_max, c.f_max, 0.005);
    REL(r.alpha_max, c.alpha_max, 0.005);
    REL(r.alpha_p, c.alpha_p, 0.005);
    REL(r.f_pulloff, c.f_cp, 0.005);
  }
}
END_TEST

/* Table 6 without damping: the integrated sticking velocity equals the iterative solution of
 * eqs (78)-(79) within 0.5 %, for all four radii and both yield pressures; and above the p_y
 * where V_y = V_s (63.4 MPa here) the sticking velocity is V_s of eq (73) (Fig 9). */
START_TEST(test_nan_table6_undamped) {
  const double Rs[4] = {3.445e-6, 2.45e-6, 1.72e-6, 1.29e-6};
  const double t25[4] = {1.51, 2.25, 3.4, 4.76}, t30[4] = {1.24, 1.86, 2.83, 3.96};
  dem_impact_opts o;
  dem_impact_opts_default(&o);
  o.dt_factor = 0.002;
  dem_err e = {0};
  for (int p = 0; p < 3; p++) {
    double py = p == 0 ? 25e6 : p == 1 ? 30e6 : 80e6;
    for (int i = 0; i < 4; i++) {
      double m = dem_sphere_mass(Rs[i], 1350), vys, vstick;
      dem_params ps;
      t5_params(&ps, Rs[i], py, 1.0);
      dem_impact_scene sc;
      scene(&sc, "nan", &ps);
      dem_nan_coeffs k;
      nan_cf(Rs[i], py, &k);
      ck_assert_int_eq(dem_nan_vys(&k, m, &vys, NULL, &e), DEM_OK);
      ck_assert_msg(dem_impact_sticking(&sc, &o, 0.2, 8.0, 1e-4, &vstick, &e) == DEM_OK, "%s",
                    e.msg);
      REL(vstick, vys, 0.005);
      if (p == 0) REL(vstick, t25[i], 0.005);
      if (p == 1) REL(vstick, t30[i], 0.005);
      if (p == 2) REL(vstick, dem_nan_vs(k.R, k.Es, k.gamma, m), 0.005);
    }
  }
}
END_TEST

/* Largest |alpha_dot| in the time window [t0, t1) of a trace "t,alpha,alpha_dot,...". */
static double trace_vmax(FILE *f, double t0, double t1) {
  char line[512];
  double vmax = 0.0;
  rewind(f);
  if (!fgets(line, sizeof line, f)) return NAN; /* header */
  while (fgets(line, sizeof line, f)) {
    double t, a, v;
    if (sscanf(line, "%lf,%lf,%lf", &t, &a, &v) == 3 && t >= t0 && t < t1)
      vmax = fmax(vmax, fabs(v));
  }
  return vmax;
}

/* Second seed Fig 3: without viscous damping a particle that cannot rebound oscillates along
 * D-E-F for ever; beta = 0.1 after yield (e0 = 0.81) lets it settle. */
START_TEST(test_nan_fig3_oscillation) {
  dem_err e = {0};
  for (int d = 0; d < 2; d++) {
    dem_params ps;
    t5_params(&ps, 2.45e-6, 30e6, d ? 0.81 : 1.0);
    dem_impact_scene sc;
    scene(&sc, "nan", &ps);
    dem_impact_opts o;
    dem_impact_opts_default(&o);
    o.dt_factor = 0.01;
    o.t_max_factor = 100;
    o.trace = tmpfile();
    ck_assert_ptr_nonnull(o.trace);
    dem_impact_result r;
    ck_assert_msg(dem_impact_run(&sc, &o, 1.0, &r, &e) == DEM_OK, "%s", e.msg);
    ck_assert_int_eq(r.stuck, 1);
    double T = r.t_contact;
    double early = trace_vmax(o.trace, 0.1 * T, 0.3 * T), late = trace_vmax(o.trace, 0.8 * T, T);
    fclose(o.trace);
    if (d == 0)
      REL(late, early, 0.02); /* undamped: the oscillation keeps its amplitude */
    else
      ck_assert_msg(late < 0.4 * early, "damped: late %g early %g", late, early); /* 0.23 */
  }
}
END_TEST

/* Table 6, p_y = 30 MPa, e0 = 0.81 (beta = 1 before yield, 0.1 after): a DEM result. */
START_TEST(test_nan_table6_damped) {
  const double Rs[4] = {3.445e-6, 2.45e-6, 1.72e-6, 1.29e-6}, vt[4] = {1.38, 2.08, 3.16, 4.43};
  dem_impact_opts o;
  dem_impact_opts_default(&o);
  o.dt_factor = 0.005;
  dem_err e = {0};
  for (int i = 0; i < 4; i++) {
    dem_params ps;
    t5_params(&ps, Rs[i], 30e6, 0.81);
    dem_impact_scene sc;
    scene(&sc, "nan", &ps);
    double v;
    ck_assert_msg(dem_impact_sticking(&sc, &o, 0.3, 8.0, 1e-3, &v, &e) == DEM_OK, "%s", e.msg);
    REL(v, vt[i], 0.03);
    /* damping raises V_ys above the undamped closed form by about 10 % (paper section 4) */
    dem_nan_coeffs k;
    double v1;
    nan_cf(Rs[i], 30e6, &k);
    ck_assert_int_eq(dem_nan_vys(&k, dem_sphere_mass(Rs[i], 1350), &v1, NULL, &e), DEM_OK);
    ck_assert(v > 1.05 * v1 && v < 1.2 * v1);
  }
}
END_TEST

/* ---------------------------------------------------------------- thornton-ning ---- */

/* Ammonium fluorescein on a rigid silicon wall (second seed Table 1 / Ning 1995). */
static void af_params(dem_params *ps) {
  dem_params_init(ps);
  set(ps, "R", 2.45e-6);
  set(ps, "rho", 1350);
  set(ps, "E", 1.2e9);
  set(ps, "nu", 0.3);
  set(ps, "wall_E", 1e30);
  set(ps, "gamma", 0.2);
  set(ps, "py", 35.3e6);
}

START_TEST(test_tn_table2) {
  dem_params ps;
  af_params(&ps);
  dem_impact_scene sc;
  scene(&sc, "thornton-ning", &ps);
  dem_impact_opts o, oref;
  dem_impact_opts_default(&o);
  o.dt_factor = 0.002;
  dem_impact_opts_default(&oref);
  oref.integrator = DEM_INTEGRATOR_REFERENCE;
  oref.rtol = 1e-10;
  dem_err e = {0};
  const double v[3] = {2, 5, 10};
  /* Table 2 (digitised from Ning 1995): f_max uN, alpha_max nm, alpha_p nm, f_cp uN */
  const double t2[3][4] = {{8.3, 53.9, 41.3, 4.6}, {20.9, 112.6, 91.1, 6.1},
                           {42.4, 210.5, 177.3, 8.4}};
  /* What the law's equations give (Verlet at dt = 2e-11 s, independent prototype). */
  const double eq[3][4] = {{9.381, 47.7, 33.5, 3.651}, {23.22, 101.4, 75.6, 4.923},
                           {46.69, 190.7, 151.7, 6.599}};
  for (int i = 0; i < 3; i++) {
    dem_impact_result r, rr;
    ck_assert_msg(dem_impact_run(&sc, &o, v[i], &r, &e) == DEM_OK, "%s", e.msg);
    ck_assert_msg(dem_impact_run(&sc, &oref, v[i], &rr, &e) == DEM_OK, "%s", e.msg);
    ck_assert_int_eq(r.stuck, 0);
    double got[4] = {r.f_max * 1e6, r.alpha_max * 1e9, r.alpha_p * 1e9, r.f_pulloff * 1e6};
    double ref[4] = {rr.f_max * 1e6, rr.alpha_max * 1e9, rr.alpha_p * 1e9, rr.f_pulloff * 1e6};
    for (int j = 0; j < 4; j++) {
      REL(got[j], ref[j], 0.005);  /* Verlet vs adaptive reference */
      REL(got[j], eq[i][j], 0.01); /* the equations' values recorded in the docs */
      REL(got[j], t2[i][j], 0.25); /* Table 2: within 25 % (docs: plastic slope) */
    }
    REL(r.e, rr.e, 0.005);
  }
}
END_TEST

START_TEST(test_tn_sticking_and_e_of_v) {
  dem_params ps;
  af_params(&ps);
  dem_impact_scene sc;
  scene(&sc, "thornton-ning", &ps);
  dem_impact_opts o;
  dem_impact_opts_default(&o);
  o.dt_factor = 0.005;
  dem_err e = {0};
  double vst;
  ck_assert_msg(dem_impact_sticking(&sc, &o, 0.2, 5.0, 1e-3, &vst, &e) == DEM_OK, "%s", e.msg);
  REL(vst, 1.425, 0.01); /* the equations */
  REL(vst, 1.6, 0.15);   /* thesis 4.1.5: ~1.6 m/s */
  /* e(v) rises from 0 at the sticking velocity, peaks, then falls (Fig 3.22(c) / 4.24) */
  const double vs[] = {1.6, 2.0, 3.0, 4.0, 6.0, 10.0, 15.0, 20.0};
  double ev[8];
  for (int i = 0; i < 8; i++) {
    dem_impact_result r;
    ck_assert_msg(dem_impact_run(&sc, &o, vs[i], &r, &e) == DEM_OK, "%s", e.msg);
    ev[i] = r.e;
  }
  ck_assert(ev[0] > 0 && ev[0] < ev[1] && ev[1] < ev[2] && ev[2] < ev[3]);
  ck_assert(ev[4] > ev[5] && ev[5] > ev[6] && ev[6] > ev[7]);
  REL(ev[3], 0.451, 0.02); /* peak ~0.45 near 4-5 m/s */
}
END_TEST

static Suite *suite(void) {
  Suite *s = suite_create("energy_nan_tn");
  TCase *t = tcase_create("nan");
  tcase_set_timeout(t, 120);
  tcase_add_test(t, test_nan_closed_form);
  tcase_add_test(t, test_nan_table6_undamped);
  tcase_add_test(t, test_nan_table6_damped);
  tcase_add_test(t, test_nan_fig3_oscillation);
  suite_add_tcase(s, t);
  t = tcase_create("thornton_ning");
  tcase_set_timeout(t, 120);
  tcase_add_test(t, test_tn_table2);
  tcase_add_test(t, test_tn_sticking_and_e_of_v);
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
