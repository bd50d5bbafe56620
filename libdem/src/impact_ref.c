/* The reference integration of a normal impact (dem/impact.h): GSL's adaptive
 * Runge-Kutta-Prince-Dormand (8,9) (gsl_odeiv2_step_rk8pd) at a tight tolerance.
 *
 * State y = (alpha, alpha_dot, W_damp) with W_damp' = f_damp alpha_dot (the damping work).
 *
 * Laws with history. An adaptive stepper evaluates the right-hand side at trial points that
 * may be rejected, so the law must never update its history there. Choice made here:
 *   - within a step the history is FROZEN: every right-hand-side call evaluates the law on a
 *     scratch copy of the history committed at the start of the step;
 *   - after each accepted step the law is evaluated once more on the real history at the
 *     accepted state: that commits it (alpha_max, F_max, branch flags...);
 *   - events at which history is created are never stepped over: when an accepted step
 *     contains a turning point (the sign of alpha_dot changes: alpha_max or alpha_min is
 *     made there), the end of contact, or (plastic laws) the zero of the unloading force,
 *     the step is redone from its start with a fixed rk8pd sub-stepping to the event, found
 *     by bisection on the event's condition; the history is committed exactly there and the
 *     stepper restarts (gsl_odeiv2_evolve_reset).
 * With the frozen history a law whose branch depends on alpha relative to its memory
 * (loading above alpha_max, breaking below alpha_b) still evaluates the right branch
 * everywhere inside a step, because within a step without a turning point the memory the law
 * would build is exactly what the frozen copy lets it compute. So the reference converges to
 * the same solution as Verlet as dt -> 0 (tests/check_impact.c checks it).
 *
 * The step is also bounded by pi sqrt(m* / k)/100 so that f_max is sampled finely; it is
 * refined by a parabola through the three samples around the largest one.
 */
#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <string.h>

#include "dem/impact.h"
#include "impact_priv.h"

typedef struct {
  const dem_impact_scene *sc;
  const double *hist; /* the committed history (frozen over a step) */
  int nhist, clip, started;
} ref_sys;

/* The law on a scratch copy of the committed history. At the very first contact (never
 * started, overlap <= 0, approaching) the right limit alpha -> 0+ is used. */
static void ref_eval(const ref_sys *p, double alpha, double v, dem_normal *n) {
  double h[DEM_LAW_NHIST_MAX];
  memcpy(h, p->hist, sizeof(double) * (size_t)p->nhist);
  if (!p->started && alpha <= 0.0 && v > 0.0) alpha = DBL_MIN;
  dem_contact_force(&p->sc->law, &p->sc->geom, h, alpha, v, n);
}

static int ref_rhs(double t, const double y[], double dydt[], void *params) {
  (void)t;
  const ref_sys *p = (const ref_sys *)params;
  dem_normal n;
  ref_eval(p, y[0], y[1], &n);
  dydt[0] = y[1];
  dydt[1] = -dem_impact_applied(&n, p->clip) / p->sc->geom.m;
  dydt[2] = n.f_damp * y[1];
  return (isfinite(dydt[1]) && isfinite(dydt[2])) ? GSL_SUCCESS : GSL_EBADFUNC;
}

/* Integrate from y0 over tau with fixed rk8pd sub-steps (far below the adaptive error). */
static int ref_fixed(gsl_odeiv2_step *st, gsl_odeiv2_system *sys, const double y0[3],
                     double tau, double y[3]) {
  const int nsub = 16;
  double yerr[3];
  memcpy(y, y0, 3 * sizeof(double));
  gsl_odeiv2_step_reset(st);
  for (int i = 0; i < nsub; i++) {
    int rc = gsl_odeiv2_step_apply(st, 0.0, tau / nsub, y, yerr, NULL, NULL, sys);
    if (rc != GSL_SUCCESS) return rc;
  }
  return GSL_SUCCESS;
}

enum { EV_NONE = 0, EV_TURN = 1, EV_END = 2, EV_PZERO = 4 };

/* Which events have happened between the step start (y0, law output n0) and state y. */
static int ref_events(const ref_sys *p, const dem_impact_sum *s, const double y0[3],
                      const dem_normal *n0, const double y[3], dem_normal *n) {
  ref_eval(p, y[0], y[1], n);
  int ev = EV_NONE;
  if ((y0[1] > 0.0 && y[1] <= 0.0) || (y0[1] < 0.0 && y[1] >= 0.0)) ev |= EV_TURN;
  if (dem_impact_ended(n, p->started || n->contact, p->clip, y[0], y[1])) ev |= EV_END;
  if (s->plastic && !s->have_p && y[1] < 0.0 && n0->f_el > 0.0 && n->f_el <= 0.0)
    ev |= EV_PZERO;
  return ev;
}

/* Parabola through (x0,f0), (x1,f1), (x2,f2): its extreme value if f1 is the largest. */
static double parabola_peak(const double x[3], const double f[3]) {
  double d01 = (f[1] - f[0]) / (x[1] - x[0]), d12 = (f[2] - f[1]) / (x[2] - x[1]);
  double c2 = (d12 - d01) / (x[2] - x[0]);
  if (!(c2 < 0.0)) return f[1];
  double c1 = d01 - c2 * (x[0] + x[1]); /* f = c0 + c1 x + c2 x^2 */
  double xs = -c1 / (2.0 * c2);
  if (xs < x[0] || xs > x[2]) return f[1];
  double fp = f[1] + d01 * (xs - x[1]) + c2 * (xs - x[0]) * (xs - x[1]);
  return fp > f[1] ? fp : f[1];
}

int dem_impact_run_reference(const dem_impact_scene *sc, const dem_impact_opts *o, double v0,
                             dem_impact_result *res, dem_err *err) {
  const dem_contact *ct = &sc->law;
  const int nhist = ct->law->nhist;
  const double tscale = dem_impact_tscale(sc, v0), t_max = dem_impact_tmax(sc, o, v0);
  const double a_run = o->runaway_overlap * sc->R, h_max = M_PI * tscale / 100.0;
  double hist[DEM_LAW_NHIST_MAX];
  int rc = dem_contact_init(ct, &sc->geom, hist, err);
  if (rc) return rc;
  ref_sys p = {sc, hist, nhist, o->clip_tensile, 0};
  gsl_odeiv2_system sys = {ref_rhs, NULL, 3, &p};
  gsl_odeiv2_step *st = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 3);
  gsl_odeiv2_step *fx = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 3);
  /* Absolute tolerances scaled to the problem: overlap ~ v0 tscale, rate ~ v0, damping work
   * ~ the impact kinetic energy. */
  const double scale_abs[3] = {v0 * tscale, v0, 0.5 * sc->geom.m * v0 * v0};
  gsl_odeiv2_control *ctl =
      gsl_odeiv2_control_scaled_new(o->rtol * 1e-3, o->rtol, 1.0, 0.0, scale_abs, 3);
  gsl_odeiv2_evolve *ev = gsl_odeiv2_evolve_alloc(3);
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  rc = DEM_OK;
  if (!st || !fx || !ctl || !ev) {
    rc = dem_err_set(err, DEM_ENOMEM, "reference integrator: out of memory");
    goto done;
  }

  dem_impact_sum sum;
  dem_impact_sum_init(&sum, sc);
  double t = 0.0, h = 1e-3 * tscale, y[3] = {0.0, v0, 0.0}, y0[3];
  dem_normal n, n0;
  ref_eval(&p, 0.0, v0, &n0);
  if (o->trace) {
    fputs("t,alpha,alpha_dot,f,f_el,f_damp\n", o->trace);
  }
  double fx3[3] = {0, 0, 0}, ff3[3] = {0, 0, 0}; /* last three (t, f) samples */
  int turn3[3] = {0, 0, 0};                     /* sample is a turning point */
  int nf = 0;
  long steps = 0;
  for (;;) {
    const double t0 = t;
    memcpy(y0, y, sizeof y);
    double hh = h > h_max ? h_max : h;
    int grc = gsl_odeiv2_evolve_apply(ev, ctl, st, &sys, &t, t_max, &hh, y);
    h = hh;
    steps++;
    if (grc != GSL_SUCCESS || !isfinite(y[0]) || !isfinite(y[1])) {
      rc = dem_err_set(err, DEM_ENONFINITE,
                       "law '%s': reference integration failed at t = %g s (%s): alpha = %g m, "
                       "alpha_dot = %g m/s",
                       ct->law->name, t, gsl_strerror(grc), y[0], y[1]);
      goto done;
    }
    if (y[0] > a_run) {
      rc = dem_err_set(err, DEM_ERUNAWAY,
                       "law '%s': overlap %g m exceeds %g x R = %g m at t = %g s (reference "
                       "integrator)",
                       ct->law->name, y[0], o->runaway_overlap, a_run, t);
      goto done;
    }
    int evs = ref_events(&p, &sum, y0, &n0, y, &n);
    if (evs) {
      /* Redo the step to the first event: bisection on "some event has happened". */
      double lo = 0.0, hi = t - t0, yh[3], ym[3];
      dem_normal nm;
      memcpy(yh, y, sizeof y);
      for (int k = 0; k < 100 && hi - lo > 4.0 * DBL_EPSILON * (t0 + hi); k++) {
        double mid = 0.5 * (lo + hi);
        if (ref_fixed(fx, &sys, y0, mid, ym) != GSL_SUCCESS) break;
        if (ref_events(&p, &sum, y0, &n0, ym, &nm)) {
          hi = mid;
          memcpy(yh, ym, sizeof ym);
        } else {
          lo = mid;
        }
      }
      memcpy(y, yh, sizeof y);
      t = t0 + hi;
      evs = ref_events(&p, &sum, y0, &n0, y, &n);
      gsl_odeiv2_evolve_reset(ev);
      gsl_odeiv2_step_reset(st);
      if (evs & EV_PZERO) {
        sum.alpha_p = y[0];
        sum.have_p = 1;
      }
    }
    /* Commit the history at the accepted state. */
    dem_contact_force(ct, &sc->geom, hist, y[0], y[1], &n);
    if (n.contact) p.started = 1;
    double f = dem_impact_applied(&n, p.clip);
    dem_impact_sum_add(&sum, y[0], y[1], &n, f);
    /* f_max refinement through the last three samples. */
    fx3[0] = fx3[1]; fx3[1] = fx3[2]; fx3[2] = t;
    ff3[0] = ff3[1]; ff3[1] = ff3[2]; ff3[2] = f;
    turn3[0] = turn3[1]; turn3[1] = turn3[2]; turn3[2] = (evs & EV_TURN) != 0;
    /* Not across a turning point: a plastic law's force has a kink there (loading and
     * unloading stiffness differ), and the event sample is then the exact maximum. */
    if (++nf >= 3 && !turn3[1] && ff3[1] >= ff3[0] && ff3[1] >= ff3[2] && fx3[0] < fx3[1] &&
        fx3[1] < fx3[2]) {
      double fp = parabola_peak(fx3, ff3);
      if (fp > sum.f_max) sum.f_max = fp;
    }
    if (o->trace && steps % (o->trace_every > 0 ? o->trace_every : 1) == 0)
      fprintf(o->trace, "%.10e,%.10e,%.10e,%.10e,%.10e,%.10e\n", t, y[0], y[1], n.f, n.f_el,
              n.f_damp);
    n0 = n;
    res->dt = t - t0;
    if (evs & EV_END) {
      res->steps = steps;
      res->w_damp = y[2];
      rc = dem_impact_finish(sc, &sum, v0, y[1], t, 0, 1e-6 + 100.0 * o->rtol, res, err);
      goto done;
    }
    if (t >= t_max) {
      res->steps = steps;
      res->w_damp = y[2];
      rc = dem_impact_finish(sc, &sum, v0, 0.0, t, 1, 0.0, res, err);
      goto done;
    }
    if (steps > 100000000L) {
      rc = dem_err_set(err, DEM_EMAXITER, "reference integrator: more than 1e8 steps");
      goto done;
    }
  }
done:
  gsl_set_error_handler(old);
  if (ev) gsl_odeiv2_evolve_free(ev);
  if (ctl) gsl_odeiv2_control_free(ctl);
  if (fx) gsl_odeiv2_step_free(fx);
  if (st) gsl_odeiv2_step_free(st);
  return rc;
}
