/* Restitution-based viscous damping constants shared by the laws (dem/contact.h).
 *
 * Linear branch (thesis eq 4.25; paper eqs 24 and 26): for m x'' + c x' + k x = 0 the
 * restitution is e = exp(-pi zeta / sqrt(1 - zeta^2)), zeta = c / (2 sqrt(m k)), hence
 * c = eta sqrt(m k) with eta = 2 |ln e| / sqrt(pi^2 + ln^2 e).
 *
 * Hertz (velocity-independent form, f_d = eta sqrt(m* S_n) alpha_dot, S_n = 2 E* sqrt(R* a)):
 * with x = X xi, t = T tau, X and T chosen so that m X / T^2 = K X^{3/2} (K = 4/3 E* sqrt R*)
 * and X / T = v_i, the impact becomes
 *     xi'' = -xi^{3/2} - c xi^{1/4} xi',   xi(0) = 0, xi'(0) = 1,   c = eta sqrt(3/2),
 * which contains no velocity: e depends on eta alone. Kept to the end at zero overlap
 * (tensile end force kept) it has a closed form (see dem_damping_eta_hertz); with the
 * tensile force clipped it has none, and eta is found by root finding on this dimensionless
 * impact, integrated with GSL's adaptive Runge-Kutta-Prince-Dormand (8,9) at a relative
 * tolerance of 1e-12.
 */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <string.h>

#include "dem/contact.h"

double dem_damping_eta_linear(double e) {
  if (!(e > 0.0 && e <= 1.0)) return -1.0;
  double l = log(e);
  return 2.0 * fabs(l) / sqrt(M_PI * M_PI + l * l);
}

typedef struct {
  double c;
  int clipped;
} hz_par;

/* Total dimensionless force xi^{3/2} + c xi^{1/4} xi' (repulsive > 0), clipped if asked. */
static double hz_force(const double y[2], const hz_par *p) {
  double x = y[0] > 0.0 ? y[0] : 0.0;
  double f = x * sqrt(x) + p->c * sqrt(sqrt(x)) * y[1];
  return (p->clipped && f < 0.0) ? 0.0 : f;
}

static int hz_rhs(double t, const double y[], double dydt[], void *params) {
  (void)t;
  dydt[0] = y[1];
  dydt[1] = -hz_force(y, (const hz_par *)params);
  return GSL_SUCCESS;
}

/* End of contact: overlap back to zero (unclipped), or the clipped force reaching zero
 * after maximum compression (from then on the body flies free: its speed is final). */
static double hz_end(const double y[2], const hz_par *p) {
  if (!p->clipped) return y[0];
  double x = y[0] > 0.0 ? y[0] : 0.0;
  return x * sqrt(x) + p->c * sqrt(sqrt(x)) * y[1];
}

typedef struct {
  const double *y0;
  double t0;
  hz_par *p;
} hz_last;

static int fixed_step(const hz_par *p, const double y0[2], double h, double y[2]) {
  gsl_odeiv2_system sys = {hz_rhs, NULL, 2, (void *)p};
  gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 2);
  if (!s) return GSL_ENOMEM;
  double yerr[2];
  /* Sub-steps keep the fixed-step error far below the adaptive tolerance. */
  const int n = 16;
  y[0] = y0[0];
  y[1] = y0[1];
  int rc = GSL_SUCCESS;
  for (int i = 0; i < n && rc == GSL_SUCCESS; i++)
    rc = gsl_odeiv2_step_apply(s, 0.0, h / n, y, yerr, NULL, NULL, &sys);
  gsl_odeiv2_step_free(s);
  return rc;
}

static double last_step_fn(double h, void *params) {
  hz_last *l = (hz_last *)params;
  double y[2];
  fixed_step(l->p, l->y0, h, y);
  return hz_end(y, l->p);
}

/* Restitution of the dimensionless Hertz impact with damping constant eta; < 0 on failure. */
static double hz_restitution(double eta, int clipped) {
  hz_par p = {eta * sqrt(1.5), clipped};
  gsl_odeiv2_system sys = {hz_rhs, NULL, 2, &p};
  gsl_odeiv2_step *s = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 2);
  gsl_odeiv2_control *c = gsl_odeiv2_control_y_new(1e-13, 1e-12);
  gsl_odeiv2_evolve *ev = gsl_odeiv2_evolve_alloc(2);
  double result = -1.0;
  if (!s || !c || !ev) goto done;
  double t = 0.0, h = 1e-4, y[2] = {0.0, 1.0}, yprev[2];
  int compressed = 0;
  for (int iter = 0; iter < 1000000; iter++) {
    double tprev = t;
    memcpy(yprev, y, sizeof y);
    if (gsl_odeiv2_evolve_apply(ev, c, s, &sys, &t, 100.0, &h, y) != GSL_SUCCESS) goto done;
    if (y[1] < 0.0) compressed = 1;
    if (compressed && hz_end(y, &p) <= 0.0) {
      /* The end lies inside the last step: find it by bisection on a fixed step. */
      hz_last l = {yprev, tprev, &p};
      gsl_function F = {last_step_fn, &l};
      gsl_root_fsolver *rs = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
      if (!rs) goto done;
      double lo = 0.0, hi = t - tprev;
      if (hz_end(yprev, &p) <= 0.0) hi = 0.0;
      double root = hi;
      if (hi > 0.0 && gsl_root_fsolver_set(rs, &F, lo, hi) == GSL_SUCCESS) {
        for (int k = 0; k < 200; k++) {
          gsl_root_fsolver_iterate(rs);
          root = gsl_root_fsolver_root(rs);
          lo = gsl_root_fsolver_x_lower(rs);
          hi = gsl_root_fsolver_x_upper(rs);
          if (gsl_root_test_interval(lo, hi, 0.0, 1e-14) == GSL_SUCCESS) break;
        }
      }
      gsl_root_fsolver_free(rs);
      double yend[2];
      fixed_step(&p, yprev, root, yend);
      result = -yend[1];
      goto done;
    }
    if (t >= 100.0) goto done; /* never separated: e = 0 for our purposes */
  }
done:
  if (ev) gsl_odeiv2_evolve_free(ev);
  if (c) gsl_odeiv2_control_free(c);
  if (s) gsl_odeiv2_step_free(s);
  return result;
}

double dem_damping_restitution_hertz(double eta, int clipped) {
  if (!(eta >= 0.0) || !isfinite(eta)) return -1.0;
  if (eta == 0.0) return 1.0;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  double e = hz_restitution(eta, clipped);
  gsl_set_error_handler(old);
  return e;
}

typedef struct {
  double e;
  int clipped;
} eta_target;

static double eta_fn(double eta, void *params) {
  const eta_target *t = (const eta_target *)params;
  return hz_restitution(eta, t->clipped) - t->e;
}

double dem_damping_eta_hertz(double e, int clipped) {
  if (!(e > 0.0 && e <= 1.0)) return -1.0;
  if (e == 1.0) return 0.0;
  /* Unclipped: exact closed form. With z = alpha^{5/4} and a rescaled time the damped Hertz
   * impact becomes a linear damped oscillator, so eta = sqrt(5/6) eta_linear(e) — the
   * constant of EDEM/LIGGGHTS (2 sqrt(5/6) |ln e| / sqrt(ln^2 e + pi^2)). The root finding
   * below agrees with it to 1e-11 (tests/check_core.c); it is still needed when the tensile
   * end force is clipped, where no closed form exists. */
  if (!clipped) return sqrt(5.0 / 6.0) * dem_damping_eta_linear(e);
  /* One-entry cache per thread: the calibration loop sets laws up with the same e. */
  static _Thread_local double cache_e = -1.0, cache_eta = -1.0;
  static _Thread_local int cache_clipped = -1;
  if (e == cache_e && clipped == cache_clipped) return cache_eta;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  eta_target tg = {e, clipped};
  /* Bracket: e(0) = 1 > target; expand upward until e(eta) < target. The linear value is a
   * good first guess (the Hertz constant is within a factor of two of it). */
  double lo = 0.0, hi = fmax(2.0 * dem_damping_eta_linear(e), 1e-3);
  double result = -1.0;
  for (int i = 0; i < 40 && eta_fn(hi, &tg) > 0.0; i++) {
    lo = hi;
    hi *= 2.0;
  }
  if (eta_fn(hi, &tg) <= 0.0) {
    gsl_function F = {eta_fn, &tg};
    gsl_root_fsolver *rs = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (rs && gsl_root_fsolver_set(rs, &F, lo, hi) == GSL_SUCCESS) {
      for (int k = 0; k < 200; k++) {
        gsl_root_fsolver_iterate(rs);
        result = gsl_root_fsolver_root(rs);
        double a = gsl_root_fsolver_x_lower(rs), b = gsl_root_fsolver_x_upper(rs);
        if (gsl_root_test_interval(a, b, 0.0, 1e-12) == GSL_SUCCESS) break;
      }
    }
    if (rs) gsl_root_fsolver_free(rs);
  }
  gsl_set_error_handler(old);
  if (result >= 0.0) {
    cache_e = e;
    cache_clipped = clipped;
    cache_eta = result;
  }
  return result;
}
