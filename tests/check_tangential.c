/* Tangential friction, rolling resistance and the Hertz damping comparison
 * (dem/tangential.h, dem/contact.h). One tcase per behaviour.
 *
 * Tolerances: the kernels are a handful of floating-point operations per step, so single
 * steps are checked to 1e-12 relative; accumulated paths (thousands of steps) to 1e-9.
 */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dem/contact.h"
#include "dem/material.h"
#include "dem/tangential.h"

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static double norm3(const double a[3]) { return sqrt(dot3(a, a)); }

static void set(dem_params *ps, const char *key, double v) {
  dem_err e = {0};
  ck_assert_int_eq(dem_params_set(ps, key, v, "test", &e), DEM_OK);
}

/* A linear spring, mu = 0.385, no damping. */
static dem_tangential linear_law(double kt, double mu) {
  dem_params ps;
  dem_params_init(&ps);
  set(&ps, "kt", kt);
  set(&ps, "mu", mu);
  dem_tangential t;
  dem_err e = {0};
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_OK);
  ck_assert_double_eq(t.eta, 0.0);
  return t;
}

/* An oblique unit normal and two unit tangents orthogonal to it. */
static void frame(double n[3], double t1[3], double t2[3]) {
  double a[3] = {0.3, -0.5, 0.81};
  double l = norm3(a);
  for (int i = 0; i < 3; i++) n[i] = a[i] / l;
  double b[3] = {1.0, 0.0, 0.0};
  double bn = dot3(b, n);
  for (int i = 0; i < 3; i++) t1[i] = b[i] - bn * n[i];
  l = norm3(t1);
  for (int i = 0; i < 3; i++) t1[i] /= l;
  t2[0] = n[1] * t1[2] - n[2] * t1[1];
  t2[1] = n[2] * t1[0] - n[0] * t1[2];
  t2[2] = n[0] * t1[1] - n[1] * t1[0];
}

/* Stick: F_t = -k_t * displacement, whatever the direction in the tangent plane; a normal
 * component of the relative velocity does not load the spring. */
START_TEST(test_stick) {
  const double kt = 1234.5, dt = 1e-9;
  dem_tangential t = linear_law(kt, 0.385);
  double n[3], t1[3], t2[3];
  frame(n, t1, t2);
  double xi[3] = {0, 0, 0}, ft[3], u[3] = {0, 0, 0};
  for (int s = 0; s < 1000; s++) {
    double v[3];
    double c1 = 2.385e-3 * cos(1e-2 * s), c2 = 1.1e-3 * sin(3e-2 * s), cn = 7e-3;
    for (int i = 0; i < 3; i++) {
      v[i] = c1 * t1[i] + c2 * t2[i] + cn * n[i];
      u[i] += (c1 * t1[i] + c2 * t2[i]) * dt;
    }
    int slid = dem_tangential_force(&t, xi, n, v, dt, 1e-6, 1e-8, 1e-13, 1e-3, 0.0, ft);
    ck_assert_int_eq(slid, 0);
    for (int i = 0; i < 3; i++) ck_assert_double_eq_tol(ft[i], -kt * u[i], 1e-12 * kt * norm3(u));
  }
  ck_assert(fabs(dot3(xi, n)) < 1e-15 * norm3(xi));
}
END_TEST

/* Slide at exactly mu (F_n + f_adh), spring truncated to k_t |xi| = limit, force opposite
 * to the displacement; adhesion raises the limit; no capacity gives no force. */
START_TEST(test_slide_and_adhesion) {
  /* Limits chosen so that lim / (k_t * 1e-12 m) is not an integer (no tie at onset). */
  const double kt = 1500.0, mu = 0.3, fn = 2.3851e-6, dt = 1e-12;
  dem_tangential t = linear_law(kt, mu);
  double n[3], t1[3], t2[3];
  frame(n, t1, t2);
  const double f_adh_list[3] = {0.0, 2.0 * 2.309e-6, 1.7e-6};
  double lim_prev = 0.0;
  for (int a = 0; a < 3; a++) {
    double f_adh = f_adh_list[a], lim = mu * (fn + f_adh);
    double xi[3] = {0, 0, 0}, ft[3];
    double v[3];
    for (int i = 0; i < 3; i++) v[i] = 0.6 * t1[i] - 0.8 * t2[i]; /* 1 m/s */
    int first_slide = -1;
    for (int s = 0; s < 20000; s++) {
      int slid = dem_tangential_force(&t, xi, n, v, dt, 1e-6, 1e-8, 1e-13, fn, f_adh, ft);
      if (slid && first_slide < 0) first_slide = s;
      ck_assert(norm3(ft) <= lim * (1 + 1e-14));
    }
    ck_assert_int_ge(first_slide, 0);
    /* Sliding starts where k_t u first exceeds the limit: u = (s+1) * 1e-12 m. */
    ck_assert_int_eq(first_slide, (int)floor(lim / kt / 1e-12));
    ck_assert_double_eq_tol(norm3(ft), lim, 1e-12 * lim);
    ck_assert_double_eq_tol(kt * norm3(xi), lim, 1e-12 * lim);
    for (int i = 0; i < 3; i++) ck_assert_double_eq_tol(ft[i], -lim * v[i], 1e-12 * lim);
    if (a == 1) ck_assert(lim > 2.0 * lim_prev); /* JKR 2 f_c more than doubles it here */
    lim_prev = lim;
  }
  /* F_n + f_adh <= 0: no friction capacity, spring reset, no force. */
  double xi[3] = {1e-9, 0, 0}, ft[3], v[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
  int slid = dem_tangential_force(&t, xi, nz, v, dt, 1e-6, 1e-8, 1e-13, -2e-6, 1.5e-6, ft);
  ck_assert_int_eq(slid, 1);
  ck_assert_double_eq(norm3(ft), 0.0);
  ck_assert_double_eq(norm3(xi), 0.0);
}
END_TEST

/* Rotating the contact frame (pure rotation of the pair, no relative sliding) keeps |xi|
 * and the stored energy, and keeps xi tangent; in-plane rotation is followed exactly. */
START_TEST(test_rotation) {
  dem_tangential t = linear_law(1500.0, 0.3);
  /* n turns from z towards x about y by 90 degrees in 900 steps; xi starts along x. */
  double xi[3] = {2.385e-10, 0, 0}, ft[3], v[3] = {0, 0, 0};
  const double m0 = norm3(xi);
  const int N = 900;
  for (int s = 1; s <= N; s++) {
    double th = 0.5 * M_PI * s / N, n[3] = {sin(th), 0.0, cos(th)};
    dem_tangential_force(&t, xi, n, v, 1e-9, 1e-6, 1e-8, 1e-13, 1e-3, 0.0, ft);
    ck_assert_double_eq_tol(norm3(xi), m0, 1e-13 * m0);
    ck_assert(fabs(dot3(xi, n)) < 1e-14 * m0);
  }
  /* Rigid rotation takes x to -z. */
  ck_assert_double_eq_tol(xi[2], -m0, 1e-12 * m0);
  ck_assert_double_eq_tol(xi[0], 0.0, 1e-12 * m0);
  /* An oblique spring and an oblique axis: length (and energy k|xi|^2/2) still kept. */
  double xj[3] = {1e-10, 2e-10, 0}, axis[3] = {0.48, 0.6, 0.64}; /* unit */
  double n0[3] = {0, 0, 1};
  const double mj = norm3(xj), e0 = 0.5 * 1500.0 * mj * mj;
  for (int s = 1; s <= 2000; s++) {
    double th = 2.0 * M_PI * s / 2000.0, c = cos(th), sn = sin(th), n[3], kx[3];
    /* Rodrigues: n = n0 c + (a x n0) s + a (a.n0)(1 - c) */
    kx[0] = axis[1] * n0[2] - axis[2] * n0[1];
    kx[1] = axis[2] * n0[0] - axis[0] * n0[2];
    kx[2] = axis[0] * n0[1] - axis[1] * n0[0];
    double an = dot3(axis, n0);
    for (int i = 0; i < 3; i++) n[i] = n0[i] * c + kx[i] * sn + axis[i] * an * (1 - c);
    dem_tangential_force(&t, xj, n, v, 1e-9, 1e-6, 1e-8, 1e-13, 1e-3, 0.0, ft);
    ck_assert(fabs(dot3(xj, n)) < 1e-14 * mj);
    double en = 0.5 * 1500.0 * dot3(xj, xj);
    ck_assert_double_eq_tol(en, e0, 1e-12 * e0);
    ck_assert_double_eq_tol(norm3(ft), 1500.0 * mj, 1e-12 * 1500.0 * mj);
  }
}
END_TEST

/* Mindlin no-slip stiffness 8 G* sqrt(R* alpha) (thesis 3.25) with G* of dem/material.h,
 * and k_t / S_n = 4 G* / E* = 2 (1 - nu) / (2 - nu) for equal materials (paper eq 22). */
START_TEST(test_mindlin) {
  dem_params ps;
  dem_params_init(&ps);
  set(&ps, "E", 1.2e9);
  set(&ps, "nu", 0.3);
  set(&ps, "mu", 0.5);
  dem_tangential t;
  dem_err e = {0};
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_MINDLIN, &ps, &e), DEM_OK);
  /* G = E / 2.6 = 4.61538e8 Pa; G* = G / (2 * 1.7) = 1.357466e8 Pa. */
  ck_assert_double_eq_tol(t.G, 1.2e9 / 2.6 / 3.4, 1e-6);
  const double R = 1.225e-6, alpha = 1.7e-8, kt = 8.0 * t.G * sqrt(R * alpha);
  double Es = dem_reduced_modulus(1.2e9, 0.3, 1.2e9, 0.3), Sn = 2.0 * Es * sqrt(R * alpha);
  ck_assert_double_eq_tol(kt / Sn, 2.0 * 0.7 / 1.7, 1e-12);
  double n[3] = {0, 0, 1}, xi[3] = {0, 0, 0}, ft[3], v[3] = {1e-3, -2e-3, 0};
  dem_tangential_force(&t, xi, n, v, 1e-9, R, alpha, 1e-13, 1.0, 0.0, ft);
  ck_assert_double_eq_tol(ft[0], -kt * 1e-12, 1e-12 * kt * 1e-12);
  ck_assert_double_eq_tol(ft[1], 2.0 * kt * 1e-12, 1e-12 * kt * 1e-12);
  /* A different wall material enters through G*. */
  set(&ps, "wall_E", 1.69e11);
  set(&ps, "wall_nu", 0.28);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_MINDLIN, &ps, &e), DEM_OK);
  ck_assert_double_eq_tol(t.G, dem_reduced_shear_modulus(1.2e9, 0.3, 1.69e11, 0.28), 1e-6);
  /* No stiffness at alpha_eff <= 0: no force (the spring keeps its displacement). */
  dem_tangential_force(&t, xi, n, v, 1e-9, R, -1e-9, 1e-13, 1.0, 0.0, ft);
  ck_assert_double_eq(norm3(ft), 0.0);
  ck_assert(norm3(xi) > 0.0);
}
END_TEST

/* Run a triangle wave u(t) in [-A, A] along t1 and return the work done on the contact over
 * cycles 2..(1+ncyc) (trapezoid rule; exact when the stick-slip kinks fall on step
 * boundaries, as chosen below). */
static double loop_work(const dem_tangential *t, double A, double du, int ncyc, double fn,
                        double f_adh) {
  double n[3] = {0, 0, 1}, xi[3] = {0, 0, 0}, ft[3];
  const double dt = 1e-9;
  int quarter = (int)lround(A / du);
  double W = 0.0, fprev = 0.0;
  for (int c = 0; c < 1 + ncyc; c++) {
    for (int s = 0; s < 4 * quarter; s++) {
      double sgn = (s < quarter || s >= 3 * quarter) ? 1.0 : -1.0;
      double v[3] = {sgn * du / dt, 0, 0};
      dem_tangential_force(t, xi, n, v, dt, 1e-6, 1e-8, 1e-13, fn, f_adh, ft);
      /* The agent driving the displacement applies -F_t. */
      if (c > 0) W += 0.5 * (-fprev - ft[0]) * sgn * du;
      fprev = ft[0];
    }
  }
  return W;
}

/* Cyclic loading at constant normal force: the loop is a parallelogram of height 2 F_lim
 * and sliding length 2 (A - F_lim/k_t) per half cycle, so the work per cycle is
 *     W = 4 F_lim (A - F_lim / k_t),  F_lim = mu (F_n + f_adh),
 * and zero (a closed elastic line) when A <= F_lim / k_t. */
START_TEST(test_cyclic_dissipation) {
  const double kt = 1000.0, mu = 0.25, fn = 3e-7, f_adh = 1e-7;
  const double lim = mu * (fn + f_adh); /* 1e-7 N: F_lim / k_t = 1e-10 m */
  const double du = 1e-12;
  dem_tangential t = linear_law(kt, mu);
  for (int k = 0; k < 2; k++) {
    double A = k ? 3.7e-10 : 2.5e-10;
    double W = loop_work(&t, A, du, 3, fn, f_adh);
    double closed = 3.0 * 4.0 * lim * (A - lim / kt);
    ck_assert_msg(fabs(W - closed) < 1e-9 * closed, "A = %g: W = %.12g, closed form %.12g", A,
                  W, closed);
  }
  /* Below the slip amplitude: no dissipation. */
  double W = loop_work(&t, 0.8e-10, du, 3, fn, f_adh);
  ck_assert(fabs(W) < 1e-12 * lim * 1e-10);
}
END_TEST

/* Tangential damping (paper eq 25): only while sticking, never above the limit. */
START_TEST(test_damping) {
  dem_params ps;
  dem_params_init(&ps);
  set(&ps, "kt", 1500.0);
  set(&ps, "mu", 0.3);
  set(&ps, "e", 0.5);
  dem_tangential t;
  dem_err e = {0};
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_OK);
  ck_assert_double_eq_tol(t.eta, 0.430908, 1e-6);
  const double m = 8.32e-14, c = t.eta * sqrt(m * 1500.0);
  double n[3] = {0, 0, 1}, xi[3] = {0, 0, 0}, ft[3], v[3] = {1e-3, 0, 0};
  int slid = dem_tangential_force(&t, xi, n, v, 1e-9, 1e-6, 1e-8, m, 1.0, 0.0, ft);
  ck_assert_int_eq(slid, 0);
  ck_assert_double_eq_tol(ft[0], -1500.0 * 1e-12 - c * 1e-3, 1e-12 * c * 1e-3);
  /* Limit 0.3 uN; the damping part alone (c v = 4.8e-9 N at 1 m/s) is capped when large. */
  double v2[3] = {100.0, 0, 0}, xi2[3] = {0, 0, 0};
  slid = dem_tangential_force(&t, xi2, n, v2, 1e-15, 1e-6, 1e-8, m, 1e-6, 0.0, ft);
  ck_assert_int_eq(slid, 0);
  ck_assert_double_eq_tol(norm3(ft), 0.3e-6, 1e-12 * 0.3e-6);
  /* Sliding: the force is exactly the limit, no damping added. */
  double xi3[3] = {1e-9, 0, 0};
  slid = dem_tangential_force(&t, xi3, n, v, 1e-9, 1e-6, 1e-8, m, 1e-6, 0.0, ft);
  ck_assert_int_eq(slid, 1);
  ck_assert_double_eq_tol(ft[0], -0.3e-6, 1e-12 * 0.3e-6);
}
END_TEST

START_TEST(test_none) {
  dem_params ps;
  dem_params_init(&ps);
  dem_tangential t;
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_NONE, &ps, NULL), DEM_OK);
  double n[3] = {0, 0, 1}, xi[3] = {1e-9, 0, 0}, ft[3], v[3] = {1, 0, 0};
  dem_tangential_force(&t, xi, n, v, 1e-9, 1e-6, 1e-8, 1e-13, 1.0, 1.0, ft);
  ck_assert_double_eq(norm3(ft), 0.0);
}
END_TEST

/* Rolling: magnitude mu_r |F_n| R_i, direction -w/|w|, zero at w = 0, viscous below w_eps;
 * the torque never does positive work. */
START_TEST(test_rolling_torque) {
  dem_params ps;
  dem_params_init(&ps);
  dem_rolling r;
  ck_assert_int_eq(dem_rolling_setup(&r, &ps, NULL), DEM_OK);
  ck_assert_double_eq(r.mu_r, 0.0);
  set(&ps, "mu_r", 0.01);
  ck_assert_int_eq(dem_rolling_setup(&r, &ps, NULL), DEM_OK);
  const double fn = 2.385e-3, R = 5e-4, M0 = 0.01 * fn * R, weps = 1e-3;
  double w[3] = {3.0, -4.0, 12.0}, M[3];
  dem_rolling_torque(&r, w, -fn, R, weps, M); /* |F_n| taken even if passed negative */
  ck_assert_double_eq_tol(norm3(M), M0, 1e-15 * M0);
  for (int i = 0; i < 3; i++) ck_assert_double_eq_tol(M[i], -M0 * w[i] / 13.0, 1e-15 * M0);
  double z[3] = {0, 0, 0};
  dem_rolling_torque(&r, z, fn, R, weps, M);
  ck_assert_double_eq(norm3(M), 0.0);
  dem_rolling_torque(&r, z, fn, R, 0.0, M); /* bare law: still 0 at rest, no NaN */
  ck_assert_double_eq(norm3(M), 0.0);
  double ws[3] = {0, 2.5e-4, 0};
  dem_rolling_torque(&r, ws, fn, R, weps, M);
  ck_assert_double_eq_tol(M[1], -M0 * 0.25, 1e-15 * M0);
  for (int k = 0; k < 100; k++) {
    double wr[3] = {sin(k * 1.7) * 1e-3 * k, cos(k * 0.3) * 2e-4, 1e-5 * (k - 50)};
    dem_rolling_torque(&r, wr, fn, R, weps, M);
    ck_assert(dot3(M, wr) <= 0.0);
    ck_assert(norm3(M) <= M0 * (1 + 1e-15));
  }
}
END_TEST

/* A spinning sphere braked only by rolling resistance, explicit Euler: with the
 * regularisation w_eps = dem_rolling_omega_eps it stops in finite time, never reverses and
 * its kinetic energy never increases; the bare constant torque chatters about zero. */
START_TEST(test_rolling_chatter) {
  dem_rolling r = {0.01};
  const double R = 5e-4, rho = 2500.0, m = dem_sphere_mass(R, rho), I = 0.4 * m * R * R;
  const double fn = m * 9.81, dt = 1e-5;
  const double weps = dem_rolling_omega_eps(r.mu_r, fn, R, I, dt);
  for (int reg = 0; reg < 2; reg++) {
    double w[3] = {0.8, -0.3, 0.2}, M[3];
    double ek = 0.5 * I * dot3(w, w);
    int flips = 0;
    for (int s = 0; s < 20000; s++) {
      double wold[3] = {w[0], w[1], w[2]};
      dem_rolling_torque(&r, w, fn, R, reg ? weps : 0.0, M);
      for (int i = 0; i < 3; i++) w[i] += M[i] * dt / I;
      if (dot3(w, wold) < 0.0 && norm3(w) > 1e-6 * weps) flips++;
      double ek1 = 0.5 * I * dot3(w, w);
      if (reg) ck_assert(ek1 <= ek * (1 + 1e-15));
      ek = ek1;
    }
    if (reg) {
      ck_assert_int_eq(flips, 0);
      ck_assert(norm3(w) < 1e-12 * weps);
    } else {
      ck_assert_int_gt(flips, 100); /* the problem the regularisation removes */
    }
  }
}
END_TEST

/* Every error of the set-up functions, provoked. */
START_TEST(test_setup_errors) {
  dem_params ps;
  dem_tangential t;
  dem_rolling r;
  dem_err e = {0};
  dem_params_init(&ps);
  ck_assert_int_eq(dem_tangential_setup(NULL, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_EINVAL);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, NULL, &e), DEM_EINVAL);
  ck_assert_int_eq(dem_tangential_setup(&t, (dem_tangential_kind)7, &ps, &e), DEM_EINVAL);
  ck_assert(strstr(e.msg, "7") != NULL);
  /* linear: kt missing, <= 0, too large, non-finite */
  set(&ps, "mu", 0.3);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_EMISSING);
  ck_assert(strstr(e.msg, "'kt'") != NULL);
  dem_params_set(&ps, "kt", -1500.0, "t.cfg:7", &e);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_ERANGE);
  ck_assert_msg(strncmp(e.msg, "t.cfg:7: ", 9) == 0 && strstr(e.msg, "-1500"), "%s", e.msg);
  set(&ps, "kt", 0.0);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_ERANGE);
  set(&ps, "kt", 2e12);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_ERANGE);
  ((dem_param *)dem_params_find(&ps, "kt"))->value = NAN; /* bypasses dem_params_set */
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_ENONFINITE);
  ck_assert(strstr(e.msg, "'kt'") != NULL);
  set(&ps, "kt", 1500.0);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_OK);
  /* mu: negative, too large, NaN, missing */
  set(&ps, "mu", -0.1);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_ERANGE);
  ck_assert(strstr(e.msg, "'mu'") != NULL);
  set(&ps, "mu", 11.0);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_ERANGE);
  ((dem_param *)dem_params_find(&ps, "mu"))->value = NAN;
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_ENONFINITE);
  ((dem_param *)dem_params_find(&ps, "mu"))->value = INFINITY;
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_ENONFINITE);
  set(&ps, "mu", 0.0); /* frictionless is allowed */
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_OK);
  /* e: outside [1e-3, 1] */
  set(&ps, "e", 0.0);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_ERANGE);
  ck_assert(strstr(e.msg, "'e'") != NULL);
  set(&ps, "e", 1.2);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_ERANGE);
  ((dem_param *)dem_params_find(&ps, "e"))->value = NAN;
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_LINEAR, &ps, &e), DEM_ENONFINITE);
  /* Mindlin: E, nu missing or out of range; wall values out of range or NaN */
  dem_params_init(&ps);
  set(&ps, "mu", 0.3);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_MINDLIN, &ps, &e), DEM_EMISSING);
  ck_assert(strstr(e.msg, "'E'") != NULL);
  set(&ps, "E", 1.2e9);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_MINDLIN, &ps, &e), DEM_EMISSING);
  ck_assert(strstr(e.msg, "'nu'") != NULL);
  set(&ps, "nu", 0.6);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_MINDLIN, &ps, &e), DEM_ERANGE);
  set(&ps, "nu", -1.0);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_MINDLIN, &ps, &e), DEM_ERANGE);
  set(&ps, "nu", 0.3);
  set(&ps, "E", -1.0);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_MINDLIN, &ps, &e), DEM_ERANGE);
  ((dem_param *)dem_params_find(&ps, "E"))->value = INFINITY;
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_MINDLIN, &ps, &e), DEM_ENONFINITE);
  set(&ps, "E", 1.2e9);
  set(&ps, "wall_E", 0.0);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_MINDLIN, &ps, &e), DEM_ERANGE);
  ck_assert(strstr(e.msg, "'wall_E'") != NULL);
  set(&ps, "wall_E", 1.69e11);
  set(&ps, "wall_nu", 0.7);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_MINDLIN, &ps, &e), DEM_ERANGE);
  ((dem_param *)dem_params_find(&ps, "wall_nu"))->value = NAN;
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_MINDLIN, &ps, &e), DEM_ENONFINITE);
  set(&ps, "wall_nu", 0.28);
  ck_assert_int_eq(dem_tangential_setup(&t, DEM_TANGENTIAL_MINDLIN, &ps, &e), DEM_OK);
  /* A failed set-up leaves a contact that exerts no force. */
  set(&ps, "mu", -1.0);
  ck_assert_int_ne(dem_tangential_setup(&t, DEM_TANGENTIAL_MINDLIN, &ps, &e), DEM_OK);
  ck_assert_int_eq(t.kind, DEM_TANGENTIAL_NONE);
  /* Rolling: NULL, negative, too large, NaN */
  ck_assert_int_eq(dem_rolling_setup(NULL, &ps, &e), DEM_EINVAL);
  ck_assert_int_eq(dem_rolling_setup(&r, NULL, &e), DEM_EINVAL);
  set(&ps, "mu_r", -0.01);
  ck_assert_int_eq(dem_rolling_setup(&r, &ps, &e), DEM_ERANGE);
  ck_assert(strstr(e.msg, "'mu_r'") != NULL);
  set(&ps, "mu_r", 1.5);
  ck_assert_int_eq(dem_rolling_setup(&r, &ps, &e), DEM_ERANGE);
  ((dem_param *)dem_params_find(&ps, "mu_r"))->value = NAN;
  ck_assert_int_eq(dem_rolling_setup(&r, &ps, &e), DEM_ENONFINITE);
}
END_TEST

/* Hertz damping. With z = alpha^{5/4} and the time s, ds = alpha^{1/4} dt, the damped Hertz
 * impact m a'' = -(4/3) E* sqrt(R*) a^{3/2} - eta sqrt(m S_n) a', S_n = 2 E* sqrt(R* a),
 * becomes exactly linear, z_ss + c z_s + (5/4) z = 0 (dimensionless, c = eta sqrt(3/2)), and
 * da/dt is proportional to z_s: so the restitution of the unclipped contact is
 * exp(-pi zeta / sqrt(1 - zeta^2)) with zeta = eta sqrt(3/10), i.e. the EDEM/LIGGGHTS constant
 *     eta_L = 2 sqrt(5/6) |ln e| / sqrt(ln^2 e + pi^2)
 * is exact. The root-finding of damping.c must reproduce it (to its 1e-12 tolerances); with
 * the tensile end force clipped the same eta gives a larger e (docs/contact-laws.md,
 * "Damping"). DEM_PRINT_TABLES=1 prints the table of the docs. */
START_TEST(test_damping_hertz_comparison) {
  const int print = getenv("DEM_PRINT_TABLES") != NULL;
  ck_assert_double_eq(dem_damping_restitution_hertz(0.0, 0), 1.0);
  ck_assert(dem_damping_restitution_hertz(-1.0, 0) < 0.0);
  ck_assert(dem_damping_restitution_hertz(NAN, 0) < 0.0);
  /* Restitution with eta_L when the tensile end force is clipped (this test's own output,
   * recorded in the docs; 1e-6 covers the integrator tolerance). */
  static const double e_clip[9] = {0.252729, 0.324863, 0.397140, 0.472014, 0.550283,
                                   0.632291, 0.718201, 0.808099, 0.902026};
  if (print)
    printf("%5s %12s %12s %12s %10s %10s %10s\n", "e", "eta_L", "eta_hertz", "eta_hz_clip",
           "e(eta_L)", "e_clip", "e(eta_lin)");
  for (int i = 1; i <= 9; i++) {
    double e = 0.1 * i;
    for (int clip = 0; clip < 2; clip++) {
      double eta = dem_damping_eta_hertz(e, clip);
      ck_assert(eta > 0.0);
      ck_assert_double_eq_tol(dem_damping_restitution_hertz(eta, clip), e, 1e-8);
    }
    double l = log(e), etaL = 2.0 * sqrt(5.0 / 6.0) * fabs(l) / sqrt(l * l + M_PI * M_PI);
    ck_assert_double_eq_tol(dem_damping_eta_hertz(e, 0), etaL, 1e-9 * etaL);
    double eL = dem_damping_restitution_hertz(etaL, 0);
    double eLc = dem_damping_restitution_hertz(etaL, 1);
    ck_assert_double_eq_tol(eL, e, 1e-9);
    ck_assert_double_eq_tol(eLc, e_clip[i - 1], 1e-6);
    /* The linear-spring constant used on Hertz gives too little restitution. */
    double elin = dem_damping_restitution_hertz(dem_damping_eta_linear(e), 0);
    ck_assert(elin < e);
    if (print)
      printf("%5.2f %12.9f %12.9f %12.9f %10.6f %10.6f %10.6f\n", e, etaL,
             dem_damping_eta_hertz(e, 0), dem_damping_eta_hertz(e, 1), eL, eLc, elin);
  }
}
END_TEST

static Suite *suite(void) {
  Suite *s = suite_create("tangential");
  struct {
    const char *name;
    const TTest *fn;
  } cases[] = {
      {"stick", test_stick},
      {"slide_adhesion", test_slide_and_adhesion},
      {"rotation", test_rotation},
      {"mindlin", test_mindlin},
      {"cyclic_dissipation", test_cyclic_dissipation},
      {"damping", test_damping},
      {"none", test_none},
      {"rolling_torque", test_rolling_torque},
      {"rolling_chatter", test_rolling_chatter},
      {"setup_errors", test_setup_errors},
      {"damping_hertz_comparison", test_damping_hertz_comparison},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    TCase *tc = tcase_create(cases[i].name);
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, cases[i].fn);
    suite_add_tcase(s, tc);
  }
  return s;
}

int main(void) {
  SRunner *sr = srunner_create(suite());
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
