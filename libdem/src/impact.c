/* Normal impact of a sphere on a wall or on an equal sphere: one degree of freedom
 * (dem/impact.h). Scene set-up, time step, the velocity-Verlet integrator, and the sticking
 * velocity search.
 *
 * Equation of motion (overlap alpha, m; rate alpha_dot, m/s, > 0 approaching):
 *     m* alpha_ddot = -f(alpha, alpha_dot, history),   alpha(0) = 0, alpha_dot(0) = v_i.
 *
 * Velocity Verlet, with the damping force evaluated at a PREDICTED velocity:
 *     alpha_{n+1} = alpha_n + dt v_n + dt^2/2 a_n
 *     v_pred      = v_n + dt a_n                      (explicit Euler predictor)
 *     a_{n+1}     = -f(alpha_{n+1}, v_pred, hist) / m*   (history committed here)
 *     v_{n+1}     = v_n + dt/2 (a_n + a_{n+1})
 * Why the predictor and not the half-step velocity v_n + dt/2 a_n (what LAMMPS-style codes
 * pass to the force): the force must be evaluated at t_{n+1}; v_half lags it by dt/2 a, an
 * O(dt) error in the damping force, which makes the whole scheme first order whenever there
 * is damping. v_pred is O(dt^2) off, which keeps velocity Verlet second order; it costs
 * nothing extra (one force call per step) and keeps the scheme explicit, so the 3-D engine
 * can use it unchanged. The measured order is in docs/impact.md (tests/check_impact.c fits it).
 *
 * Start and end of contact. The force jumps at first contact (damping c v_i for the linear
 * law, -8/9 f_c for JKR), so a_0 is the right limit alpha -> 0+ (the law evaluated at
 * alpha = DBL_MIN on a scratch copy of the history). The end (the law reports no contact, or,
 * with clip_tensile, the total force reaches zero on the way out) lies inside the last step:
 * it is located by bisection along that step's own trajectory
 *     alpha(s) = alpha_n + v_n s + a_n s^2 / 2,   v(s) = v_n + a_n s,
 * evaluating the law on a scratch copy of the step's starting history; the rebound speed is
 * v(s_end). This is an O(dt^2) one-off error, so e and t_contact keep second order (taking
 * the Verlet velocity of the step that jumped past the end would make them first order).
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "dem/impact.h"
#include "dem/material.h"
#include "impact_priv.h"

static const char *const scene_keys[] = {"R", "rho", "E", "nu", NULL};

void dem_impact_opts_default(dem_impact_opts *o) {
  memset(o, 0, sizeof *o);
  o->integrator = DEM_INTEGRATOR_VERLET;
  o->dt_rule = DEM_DT_RAYLEIGH; /* falls back to mass-spring when E, nu are unknown */
  o->dt_factor = 0.01;
  o->dt = 0.0;
  o->rtol = 1e-10;
  o->t_max_factor = 200.0;
  o->clip_tensile = 0;
  o->runaway_overlap = 1.0;
  o->trace = NULL;
  o->trace_every = 1;
}

/* A required scene value in (lo, hi]. */
static int scene_value(const dem_params *ps, const char *key, const char *about,
                       const char *unit, double lo, double hi, int required, double *out,
                       dem_err *err) {
  double v;
  *out = NAN;
  if (!dem_params_get(ps, key, &v)) {
    if (!required) return DEM_OK;
    return dem_err_set(err, DEM_EMISSING,
                       "impact scene needs '%s' (%s, %s; allowed (%g, %g])", key, about, unit,
                       lo, hi);
  }
  if (!isfinite(v))
    return dem_err_set(err, DEM_ENONFINITE, "%simpact scene: '%s' = %g is not finite",
                       dem_params_origin(ps, key), key, v);
  if (!(v > lo && v <= hi))
    return dem_err_set(err, DEM_ERANGE,
                       "%simpact scene: '%s' = %g %s is outside the allowed range (%g, %g] (%s)",
                       dem_params_origin(ps, key), key, v, unit, lo, hi, about);
  *out = v;
  return DEM_OK;
}

int dem_impact_setup(dem_impact_scene *sc, const dem_law *law, const dem_params *ps,
                     dem_impact_target target, dem_err *err) {
  if (!sc || !law || !ps) return dem_err_set(err, DEM_EINVAL, "dem_impact_setup: NULL argument");
  memset(sc, 0, sizeof *sc);
  if (target != DEM_TARGET_WALL && target != DEM_TARGET_PAIR)
    return dem_err_set(err, DEM_EINVAL, "impact target %d is neither wall (0) nor pair (1)",
                       (int)target);
  int rc = dem_contact_check_keys(law, ps, scene_keys, err);
  if (rc) return rc;
  if ((rc = scene_value(ps, "R", "particle radius", "m", 0.0, 10.0, 1, &sc->R, err)) ||
      (rc = scene_value(ps, "rho", "particle density", "kg/m^3", 0.0, 1e5, 1, &sc->rho, err)) ||
      (rc = scene_value(ps, "E", "Young's modulus of the particle", "Pa", 0.0, 1e13, 0, &sc->E,
                        err)) ||
      (rc = scene_value(ps, "nu", "Poisson's ratio of the particle", "-", -1.0, 0.5, 0, &sc->nu,
                        err)))
    return rc;
  sc->mass = dem_sphere_mass(sc->R, sc->rho);
  sc->target = target;
  /* Wall: R2 = m2 = infinity. Equal spheres: R* = R/2, m* = m/2. */
  sc->geom.R = target == DEM_TARGET_WALL ? sc->R : 0.5 * sc->R;
  sc->geom.m = target == DEM_TARGET_WALL ? sc->mass : 0.5 * sc->mass;
  if ((rc = dem_contact_setup(&sc->law, law, ps, err))) return rc;
  double hist[DEM_LAW_NHIST_MAX];
  return dem_contact_init(&sc->law, &sc->geom, hist, err);
}

double dem_impact_tscale(const dem_impact_scene *sc, double v) {
  return dem_dt_sdof(sc->geom.m, dem_contact_kref(&sc->law, &sc->geom, v));
}

double dem_impact_tmax(const dem_impact_scene *sc, const dem_impact_opts *o, double v) {
  return o->t_max_factor * M_PI * dem_impact_tscale(sc, v);
}

double dem_impact_dt(const dem_impact_scene *sc, const dem_impact_opts *o, double v) {
  if (o->dt > 0.0) return o->dt;
  /* Rayleigh (thesis eq 3.1) with the particle's R, rho, E, nu; mass-spring
   * sqrt(m* / k) with the law's largest stiffness in this impact (thesis 4.29-4.31). */
  if (o->dt_rule == DEM_DT_RAYLEIGH && isfinite(sc->E) && isfinite(sc->nu))
    return o->dt_factor * dem_dt_rayleigh(sc->R, sc->rho, sc->E, sc->nu);
  return o->dt_factor * dem_impact_tscale(sc, v);
}

void dem_impact_sum_init(dem_impact_sum *s, const dem_impact_scene *sc) {
  memset(s, 0, sizeof *s);
  s->plastic = (sc->law.law->flags & DEM_LAW_PLASTIC) != 0;
}

void dem_impact_sum_add(dem_impact_sum *s, double alpha, double alpha_dot, const dem_normal *n,
                        double f_applied) {
  if (n->contact) s->started = 1;
  if (alpha > s->alpha_max) s->alpha_max = alpha;
  if (f_applied > s->f_max) s->f_max = f_applied;
  if (alpha_dot < 0.0 && s->started) s->unloading = 1;
  if (s->unloading && n->contact && -n->f_el > s->pulloff) s->pulloff = -n->f_el;
  /* Permanent overlap: the unloading elastic-plastic force crosses zero (interpolated). */
  if (s->plastic && s->unloading && !s->have_p && s->f_el_last > 0.0 && n->f_el <= 0.0) {
    double w = s->f_el_last / (s->f_el_last - n->f_el);
    s->alpha_p = s->alpha_last + w * (alpha - s->alpha_last);
    s->have_p = 1;
  }
  s->f_el_last = n->f_el;
  s->alpha_last = alpha;
}

int dem_impact_finish(const dem_impact_scene *sc, const dem_impact_sum *s, double v0,
                      double v_sep, double t_contact, int stuck, double tol_gain,
                      dem_impact_result *res, dem_err *err) {
  res->v_impact = v0;
  res->alpha_max = s->alpha_max;
  res->alpha_p = s->have_p ? s->alpha_p : 0.0;
  res->f_max = s->f_max;
  res->f_pulloff = s->pulloff;
  res->t_contact = t_contact;
  if (!stuck && !(v_sep < 0.0)) stuck = 1; /* no outward speed left */
  res->stuck = stuck;
  res->v_rebound = stuck ? 0.0 : -v_sep;
  res->e = res->v_rebound / v0;
  /* No law has an energy source: a rebound faster than the impact beyond the integrator's
   * own error is a numerical blow-up, never a result. */
  if (res->e > 1.0 + tol_gain)
    return dem_err_set(err, DEM_EUNSTABLE,
                       "law '%s': energy gain in the impact at v = %g m/s: rebound %g m/s "
                       "(e = %.6g > 1), dt = %g s = %.3g x sqrt(m* / k); the time step is too "
                       "large for this law",
                       sc->law.law->name, v0, res->v_rebound, res->e, res->dt,
                       res->dt / dem_impact_tscale(sc, v0));
  return DEM_OK;
}

static void trace_header(FILE *f) {
  if (f) fputs("t,alpha,alpha_dot,f,f_el,f_damp\n", f);
}

static void trace_row(FILE *f, double t, double a, double v, const dem_normal *n) {
  fprintf(f, "%.10e,%.10e,%.10e,%.10e,%.10e,%.10e\n", t, a, v, n->f, n->f_el, n->f_damp);
}

/* The end of contact inside the last step, by bisection along the step's trajectory.
 * Returns the bracket [*lo, *hi] (not ended at lo, ended at hi). */
static void verlet_locate_end(const dem_impact_scene *sc, int clip, int started,
                              const double *hist0, int nhist, double a0, double v0,
                              double acc0, double dt, double *s_lo, double *s_hi) {
  double lo = 0.0, hi = dt;
  for (int k = 0; k < 80 && hi - lo > 4.0 * DBL_EPSILON * dt; k++) {
    double s = 0.5 * (lo + hi), h[DEM_LAW_NHIST_MAX];
    memcpy(h, hist0, sizeof(double) * (size_t)nhist);
    double a = a0 + v0 * s + 0.5 * acc0 * s * s, v = v0 + acc0 * s;
    dem_normal n;
    dem_contact_force(&sc->law, &sc->geom, h, a, v, &n);
    if (dem_impact_ended(&n, started || n.contact, clip, a, v))
      hi = s;
    else
      lo = s;
  }
  *s_lo = lo;
  *s_hi = hi;
}

static int run_verlet(const dem_impact_scene *sc, const dem_impact_opts *o, double v0,
                      dem_impact_result *res, dem_err *err) {
  const dem_contact *ct = &sc->law;
  const dem_geom *g = &sc->geom;
  const int nhist = ct->law->nhist, clip = o->clip_tensile;
  const double m = g->m, inv_m = 1.0 / g->m, dt = dem_impact_dt(sc, o, v0);
  const double tscale = dem_impact_tscale(sc, v0), t_max = dem_impact_tmax(sc, o, v0);
  const double a_run = o->runaway_overlap * sc->R;
  res->dt = dt;
  if (!(dt > 0.0) || !isfinite(dt))
    return dem_err_set(err, DEM_ERANGE, "impact: time step dt = %g s must be finite and > 0",
                       dt);
  if (t_max / dt > 1e9)
    return dem_err_set(err, DEM_ERANGE,
                       "impact: dt = %g s would need more than 1e9 steps to reach the time "
                       "limit %g s (dt factor too small?)",
                       dt, t_max);

  if (dt > 2.0 * tscale)
    return dem_err_set(err, DEM_EUNSTABLE,
                       "law '%s': dt = %g s exceeds Verlet's stability limit 2 sqrt(m* / k) = %g s "
                       "for the stiffness k = %g N/m this impact reaches at v = %g m/s; reduce "
                       "the dt factor",
                       ct->law->name, dt, 2.0 * tscale, dem_contact_kref(ct, g, v0), v0);
  double hist[DEM_LAW_NHIST_MAX], hist0[DEM_LAW_NHIST_MAX];
  int rc = dem_contact_init(ct, g, hist, err);
  if (rc) return rc;
  dem_impact_sum sum;
  dem_impact_sum_init(&sum, sc);

  /* Right limit of the force at first contact, on a scratch history. */
  dem_normal n;
  memcpy(hist0, hist, sizeof(double) * (size_t)nhist);
  dem_contact_force(ct, g, hist0, DBL_MIN, v0, &n);
  if (fabs(n.f_damp / v0) * dt > 2.0 * m)
    return dem_err_set(err, DEM_EUNSTABLE,
                       "law '%s': dt = %g s exceeds the stability limit 2 m*/c = %g s of the "
                       "explicit damping term at first contact; reduce the dt factor",
                       ct->law->name, dt, 2.0 * m / fabs(n.f_damp / v0));
  double alpha = 0.0, v = v0, t = 0.0, acc = -dem_impact_applied(&n, clip) / m;
  double pw = n.f_damp * v0; /* damping power at the last state, W */
  double w_damp = 0.0;
  trace_header(o->trace);
  if (o->trace) trace_row(o->trace, t, alpha, v, &n);

  long step = 0;
  for (;;) {
    const double a_n = alpha, v_n = v, acc_n = acc, t_n = t;
    const int started_n = sum.started;
    memcpy(hist0, hist, sizeof(double) * (size_t)nhist);
    alpha = a_n + dt * v_n + 0.5 * dt * dt * acc_n;
    const double v_pred = v_n + dt * acc_n;
    dem_contact_force(ct, g, hist, alpha, v_pred, &n);
    const double f = dem_impact_applied(&n, clip);
    acc = -f * inv_m;
    v = v_n + 0.5 * dt * (acc_n + acc);
    t = t_n + dt;
    step++;
    if (!isfinite(alpha) || !isfinite(v) || !isfinite(f))
      return dem_err_set(err, DEM_ENONFINITE,
                         "law '%s': non-finite state at t = %g s (step %ld): alpha = %g m, "
                         "alpha_dot = %g m/s, f = %g N; dt = %g s is too large",
                         ct->law->name, t, step, alpha, v, f, dt);
    /* Verlet is stable for omega dt < 2 only, omega^2 = k/m* with the branch stiffness;
     * the explicit damping term for c dt / m* < 2 only. */
    if (n.k * dt * dt > 4.0 * m || fabs(n.f_damp) * dt > 2.0 * m * fabs(v_pred))
      return dem_err_set(err, DEM_EUNSTABLE,
                         "law '%s': dt = %g s exceeds Verlet's stability limit 2 sqrt(m* / k) = "
                         "%g s (or 2 m*/c = %g s for the damping) at t = %g s (step %ld, alpha = "
                         "%g m, branch stiffness k = %g N/m); reduce the dt factor",
                         ct->law->name, dt, 2.0 * sqrt(m / n.k),
                         v_pred != 0.0 ? 2.0 * m / fabs(n.f_damp / v_pred) : INFINITY, t, step,
                         alpha, n.k);
    if (alpha > a_run)
      return dem_err_set(err, DEM_ERUNAWAY,
                         "law '%s': overlap %g m exceeds %g x R = %g m at t = %g s (step %ld, "
                         "dt = %g s = %.3g x sqrt(m* / k)): runaway, the time step is too large",
                         ct->law->name, alpha, o->runaway_overlap, a_run, t, step, dt,
                         dt / tscale);
    /* The apex of this step's parabola, if it lies inside the step. */
    if (v_n > 0.0 && acc_n < 0.0 && -v_n / acc_n <= dt) {
      double peak = a_n - 0.5 * v_n * v_n / acc_n;
      if (peak > sum.alpha_max) {
        sum.alpha_max = peak;
        double h[DEM_LAW_NHIST_MAX];
        dem_normal np;
        memcpy(h, hist0, sizeof(double) * (size_t)nhist);
        dem_contact_force(ct, g, h, peak, 0.0, &np);
        double fp = dem_impact_applied(&np, clip);
        if (fp > sum.f_max) sum.f_max = fp;
      }
    }
    if (dem_impact_ended(&n, started_n || n.contact, clip, alpha, v_pred)) {
      /* A partial Verlet step of length s to the end, with the force at the last state
       * still in contact (the left limit): local error O(s^3). */
      double s_lo, s;
      verlet_locate_end(sc, clip, started_n, hist0, nhist, a_n, v_n, acc_n, dt, &s_lo, &s);
      double a_l = a_n + v_n * s_lo + 0.5 * acc_n * s_lo * s_lo, v_l = v_n + acc_n * s_lo;
      double h[DEM_LAW_NHIST_MAX];
      dem_normal nl, ne;
      memcpy(h, hist0, sizeof(double) * (size_t)nhist);
      dem_contact_force(ct, g, h, a_l, v_l, &nl);
      double acc_l = -dem_impact_applied(&nl, clip) / m;
      double a_e = a_n + v_n * s + 0.5 * acc_n * s * s, v_e = v_n + 0.5 * s * (acc_n + acc_l);
      dem_contact_force(ct, g, hist0, a_e, v_e, &ne);
      memcpy(hist, hist0, sizeof(double) * (size_t)nhist);
      w_damp += 0.5 * s * (pw + ne.f_damp * v_e);
      dem_impact_sum_add(&sum, a_e, v_e, &ne, dem_impact_applied(&ne, clip));
      if (o->trace) trace_row(o->trace, t_n + s, a_e, v_e, &ne);
      res->steps = step;
      res->w_damp = w_damp;
      /* Verlet's own error in e is O((omega dt)^2), measured below 0.06 (omega dt)^2 for the
       * linear and Hertz laws up to omega dt = 1.5; a blow-up gains far more. A law with
       * history (plastic or adhesive) has kinks where a branch changes inside a step, and
       * there the local error is first order in dt: a random probe of nearly elastic
       * pasha-simplified sets found e = 1.00001 at dt = 0.01 sqrt(m* / k), a false alarm under
       * the second-order bound, so such laws get a first-order allowance as well. */
      double r = dt / tscale;
      unsigned kinked = ct->law->flags & (DEM_LAW_PLASTIC | DEM_LAW_ADHESIVE);
      double tol = 1e-9 + 0.1 * r * r + (kinked ? 0.01 * r : 0.0);
      return dem_impact_finish(sc, &sum, v0, v_e, t_n + s, 0, tol, res, err);
    }
    w_damp += 0.5 * dt * (pw + n.f_damp * v_pred);
    pw = n.f_damp * v_pred;
    dem_impact_sum_add(&sum, alpha, v, &n, f);
    if (o->trace && step % (o->trace_every > 0 ? o->trace_every : 1) == 0)
      trace_row(o->trace, t, alpha, v, &n);
    if (t >= t_max) {
      res->steps = step;
      res->w_damp = w_damp;
      return dem_impact_finish(sc, &sum, v0, 0.0, t, 1, 0.0, res, err);
    }
  }
}

int dem_impact_run(const dem_impact_scene *sc, const dem_impact_opts *o, double v,
                   dem_impact_result *res, dem_err *err) {
  if (!sc || !o || !res || !sc->law.law)
    return dem_err_set(err, DEM_EINVAL, "dem_impact_run: NULL or unset argument");
  memset(res, 0, sizeof *res);
  res->v_rebound = res->e = res->alpha_max = res->alpha_p = NAN;
  res->f_max = res->f_pulloff = res->t_contact = res->w_damp = NAN;
  res->v_impact = v;
  if (!isfinite(v))
    return dem_err_set(err, DEM_ENONFINITE, "impact velocity %g m/s is not finite", v);
  if (!(v > 0.0) || v > 1e4)
    return dem_err_set(err, DEM_ERANGE,
                       "impact velocity %g m/s is outside the allowed range (0, 1e4] m/s", v);
  if (!(o->dt > 0.0) && !(o->dt_factor > 0.0 && o->dt_factor <= 100.0))
    return dem_err_set(err, DEM_ERANGE, "dt factor %g is outside the allowed range (0, 100]",
                       o->dt_factor);
  if (!(o->t_max_factor >= 1.0 && o->t_max_factor <= 1e7))
    return dem_err_set(err, DEM_ERANGE, "t_max_factor %g is outside the allowed range [1, 1e7]",
                       o->t_max_factor);
  if (!(o->runaway_overlap > 0.0 && o->runaway_overlap <= 10.0))
    return dem_err_set(err, DEM_ERANGE,
                       "runaway_overlap %g (fraction of R) is outside the allowed range (0, 10]",
                       o->runaway_overlap);
  if (o->clip_tensile && (sc->law.law->flags & DEM_LAW_ADHESIVE))
    return dem_err_set(err, DEM_EUNSUPPORTED,
                       "clip_tensile applies to non-adhesive laws only; law '%s' is adhesive",
                       sc->law.law->name);
  if (!(dem_contact_kref(&sc->law, &sc->geom, v) > 0.0))
    return dem_err_set(err, DEM_EPHYSICS, "law '%s' reports no stiffness for v = %g m/s",
                       sc->law.law->name, v);
  int rc;
  switch (o->integrator) {
  case DEM_INTEGRATOR_VERLET:
    rc = run_verlet(sc, o, v, res, err);
    break;
  case DEM_INTEGRATOR_REFERENCE:
    if (!(o->rtol >= 1e-14 && o->rtol <= 1e-3))
      return dem_err_set(err, DEM_ERANGE, "rtol %g is outside the allowed range [1e-14, 1e-3]",
                         o->rtol);
    rc = dem_impact_run_reference(sc, o, v, res, err);
    break;
  default:
    return dem_err_set(err, DEM_EINVAL, "unknown integrator %d", (int)o->integrator);
  }
  if (rc != DEM_OK) {
    /* A failed run reports no numbers a caller could mistake for results. */
    res->v_rebound = res->e = res->alpha_max = res->alpha_p = NAN;
    res->f_max = res->f_pulloff = res->t_contact = res->w_damp = NAN;
    res->stuck = 0;
  }
  return rc;
}

/* Sticking velocity: log grid, then bisection between the fastest sticking grid point and
 * the next (non-sticking) one. */
#define STICK_GRID 16
int dem_impact_sticking(const dem_impact_scene *sc, const dem_impact_opts *o, double v_lo,
                        double v_hi, double tol, double *v_stick, dem_err *err) {
  if (!sc || !o || !v_stick) return dem_err_set(err, DEM_EINVAL, "dem_impact_sticking: NULL");
  *v_stick = NAN;
  if (!isfinite(v_lo) || !isfinite(v_hi) || !isfinite(tol))
    return dem_err_set(err, DEM_ENONFINITE, "sticking search: non-finite bound or tolerance");
  if (!(v_lo > 0.0 && v_hi > v_lo))
    return dem_err_set(err, DEM_ERANGE,
                       "sticking search: need 0 < v_min < v_max, got v_min = %g, v_max = %g m/s",
                       v_lo, v_hi);
  if (!(tol >= 1e-12 && tol <= 0.1))
    return dem_err_set(err, DEM_ERANGE, "sticking search: tolerance %g outside [1e-12, 0.1]",
                       tol);
  dem_impact_opts oo = *o;
  oo.trace = NULL;
  dem_impact_result r;
  double grid[STICK_GRID];
  int stuck[STICK_GRID];
  for (int i = 0; i < STICK_GRID; i++) {
    grid[i] = v_lo * pow(v_hi / v_lo, (double)i / (STICK_GRID - 1));
    if (i == STICK_GRID - 1) grid[i] = v_hi;
    int rc = dem_impact_run(sc, &oo, grid[i], &r, err);
    if (rc) {
      dem_err_prefix(err, "sticking search at v = %g m/s: ", grid[i]);
      return rc;
    }
    stuck[i] = r.stuck;
  }
  if (stuck[STICK_GRID - 1])
    return dem_err_set(err, DEM_ERANGE,
                       "law '%s': the particle still sticks at v_max = %g m/s; raise v_max",
                       sc->law.law->name, v_hi);
  int i = STICK_GRID - 2;
  while (i >= 0 && !stuck[i]) i--;
  if (i < 0)
    return dem_err_set(err, DEM_ERANGE,
                       "law '%s': the particle does not stick even at v_min = %g m/s (a law "
                       "without adhesion never sticks; otherwise lower v_min)",
                       sc->law.law->name, v_lo);
  double lo = grid[i], hi = grid[i + 1];
  while (hi - lo > tol * hi) {
    double mid = 0.5 * (lo + hi);
    int rc = dem_impact_run(sc, &oo, mid, &r, err);
    if (rc) {
      dem_err_prefix(err, "sticking search at v = %g m/s: ", mid);
      return rc;
    }
    if (r.stuck)
      lo = mid;
    else
      hi = mid;
  }
  *v_stick = 0.5 * (lo + hi);
  return DEM_OK;
}
