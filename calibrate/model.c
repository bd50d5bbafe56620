/* The model side of a calibration: the law evaluated at trial parameters on every target.
 *
 * curve        dem_contact_path along the reference's own overlap path (start at 0, its
 *              turning points, its end), quasi-statically; the rows are interpolated on each
 *              branch at the compared overlaps;
 * sticking     dem_impact_sticking for each radius (scene key R overridden);
 * restitution  dem_impact_run for each impact velocity.
 *
 * The simulations of one evaluation are independent: they run as an OpenMP loop over jobs
 * (a curve, or one point of a sticking or restitution target), each writing its own slice of
 * model[]; the first failure in job order is reported, so the result and the message do not
 * depend on the number of threads.
 *
 * The impact solver and the overlap-path driver come from libdem (dem/impact.h, the `impact`
 * branch); CMake defines CAL_HAVE_CONTACT_PATH / CAL_HAVE_IMPACT once their definitions exist.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cal.h"
#include "curve.h"
#include "dem/material.h"

#if defined(CAL_HAVE_CONTACT_PATH) || defined(CAL_HAVE_IMPACT)
/* The parameter set of one target: the trial set with the target's overrides. */
static int target_params(const cal_target *t, const dem_params *ps, dem_params *out,
                         dem_err *err) {
  *out = *ps;
  for (int i = 0; i < t->over.n; i++) {
    int rc = dem_params_set(out, t->over.p[i].key, t->over.p[i].value, t->over.p[i].origin, err);
    if (rc) return rc;
  }
  return DEM_OK;
}
#endif

typedef struct rows {
  double *a, *f;
  int n, cap;
  int oom;
} rows;

#ifdef CAL_HAVE_CONTACT_PATH
static void row_cb(double alpha, const dem_normal *nm, void *user) {
  rows *r = user;
  if (r->oom) return;
  if (r->n == r->cap) {
    int cap = r->cap ? 2 * r->cap : 1024;
    double *a = realloc(r->a, sizeof(double) * (size_t)cap);
    if (!a) {
      r->oom = 1;
      return;
    }
    r->a = a;
    double *f = realloc(r->f, sizeof(double) * (size_t)cap);
    if (!f) {
      r->oom = 1;
      return;
    }
    r->f = f;
    r->cap = cap;
  }
  r->a[r->n] = alpha;
  r->f[r->n++] = nm->f;
}
#endif

#ifdef CAL_HAVE_CONTACT_PATH
/* The law of c with the parameters ps (+ the target's overrides) along a path. */
static int law_path(const cal_config *c, const cal_target *t, const dem_params *ps,
                    const double *turn, int nt, rows *r, dem_err *err) {
  dem_params tp;
  int rc = target_params(t, ps, &tp, err);
  if (rc) return rc;
  double R = dem_params_get_or(&tp, "R", NAN), rho = dem_params_get_or(&tp, "rho", 1000.0);
  if (!(R > 0.0))
    return dem_err_set(err, DEM_EMISSING,
                       "target '%s': a force-overlap path needs the particle radius R (fixed "
                       "or set)",
                       t->name);
  dem_contact ct;
  if ((rc = dem_contact_setup(&ct, c->law, &tp, err))) return rc;
  double m = dem_sphere_mass(R, rho);
  dem_geom g = {t->pair ? R / 2 : R, t->pair ? m / 2 : m};
  double lo = 0.0, hi = 0.0;
  for (int k = 0; k < nt; k++) {
    if (turn[k] < lo) lo = turn[k];
    if (turn[k] > hi) hi = turn[k];
  }
  double step = (hi - lo) / c->path_steps;
  rc = dem_contact_path(&ct, &g, turn, nt, step > 0 ? step : 1e-12, row_cb, r, err);
  if (!rc && r->oom) rc = dem_err_set(err, DEM_ENOMEM, "out of memory");
  if (!rc && r->n < 2)
    rc = dem_err_set(err, DEM_EINVAL, "target '%s': the overlap path gave %d rows", t->name, r->n);
  for (int k = 0; !rc && k < r->n; k++)
    if (!isfinite(r->f[k]))
      rc = dem_err_set(err, DEM_ENONFINITE, "target '%s': non-finite force at alpha = %g m",
                       t->name, r->a[k]);
  if (rc) {
    free(r->a);
    free(r->f);
    memset(r, 0, sizeof *r);
  }
  return rc;
}
#endif

/* Drive the law along the reference path of t; rows of (alpha, f). *shift: the number of
 * model branches that precede the reference's first branch (1 if the path had to be started
 * at alpha = 0 moving the other way). */
static int curve_rows(const cal_config *c, const cal_target *t, const dem_params *ps, rows *r,
                      int *shift, dem_err *err) {
  memset(r, 0, sizeof *r);
  *shift = 0;
#ifndef CAL_HAVE_CONTACT_PATH
  (void)c;
  (void)t;
  (void)ps;
  return dem_err_set(err, DEM_EUNSUPPORTED,
                     "curve targets need dem_contact_path (dem/impact.h, `impact` branch), not "
                     "merged yet");
#else
  /* Turning points: 0, every local extremum of the reference sequence, its last point. */
  double *tp_a = malloc(sizeof(double) * (size_t)(t->n + 2));
  if (!tp_a) return dem_err_set(err, DEM_ENOMEM, "out of memory");
  int nt = 0;
  tp_a[nt++] = 0.0;
  if (t->x[0] != 0.0) {
    tp_a[nt++] = t->x[0];
    if (cal_first_direction(t->x, t->n) * (t->x[0] > 0 ? 1 : -1) < 0) *shift = 1;
  }
  int dir = 0;
  for (int k = 1; k < t->n; k++) {
    double d = t->x[k] - t->x[k - 1];
    int s = d > 0 ? 1 : (d < 0 ? -1 : 0);
    if (s != 0 && dir != 0 && s != dir) tp_a[nt++] = t->x[k - 1];
    if (s != 0) dir = s;
  }
  if (tp_a[nt - 1] != t->x[t->n - 1]) tp_a[nt++] = t->x[t->n - 1];
  int rc = law_path(c, t, ps, tp_a, nt, r, err);
  free(tp_a);
  return rc;
#endif
}

int cal_model_curve(const cal_config *c, const cal_target *t, const dem_params *ps,
                    double **alpha, double **f, int *n, dem_err *err) {
  rows r;
  int shift;
  int rc = curve_rows(c, t, ps, &r, &shift, err);
  *alpha = r.a;
  *f = r.f;
  *n = r.n;
  return rc;
}

static int eval_curve(const cal_config *c, const cal_target *t, const dem_params *ps,
                      double *model, dem_err *err) {
  rows r;
  int shift;
  int rc = curve_rows(c, t, ps, &r, &shift, err);
  if (rc) return rc;
  if (t->mode == CAL_CURVE_SUMMARY) {
    double s[3];
    int has[3];
    cal_curve_summary(r.a, r.f, r.n, s, has);
    for (int k = 0; k < t->nres; k++) {
      int q = -1 - t->branch[k];
      model[k] = has[q] ? s[q] : 0.0; /* a missing feature counts as zero */
    }
  } else {
    int *run = malloc(sizeof(int) * (size_t)r.n);
    if (!run) rc = dem_err_set(err, DEM_ENOMEM, "out of memory");
    else {
      int nruns = cal_runs(r.a, r.n, run);
      for (int k = 0; k < t->nres; k++) {
        int b = t->branch[k] + shift;
        if (b >= nruns) b = nruns - 1;
        model[k] = cal_interp_run(r.a, r.f, run, r.n, b, t->xr[k]);
      }
      free(run);
    }
  }
  free(r.a);
  free(r.f);
  return rc;
}

/* One row of an unloading target: 0 -> alpha_max -> -alpha_max; f_max, alpha_p, pull-off. */
static int eval_unloading_row(const cal_config *c, const cal_target *t, const dem_params *ps,
                              int k, double *model, dem_err *err) {
#ifndef CAL_HAVE_CONTACT_PATH
  (void)c;
  (void)t;
  (void)ps;
  (void)k;
  (void)model;
  return dem_err_set(err, DEM_EUNSUPPORTED,
                     "unloading targets need dem_contact_path (dem/impact.h, `impact` branch), "
                     "not merged yet");
#else
  double turn[3] = {0.0, t->x[k], -t->x[k]};
  rows r;
  memset(&r, 0, sizeof r);
  int rc = law_path(c, t, ps, turn, 3, &r, err);
  if (rc) return rc;
  double s[3];
  int has[3];
  cal_curve_summary(r.a, r.f, r.n, s, has);
  for (int q = 0; q < 3; q++) model[q] = has[q] ? s[q] : 0.0; /* a missing feature is zero */
  free(r.a);
  free(r.f);
  return DEM_OK;
#endif
}

static int eval_impact_point(const cal_config *c, const cal_target *t, const dem_params *ps,
                             int k, double *model, dem_err *err) {
#ifndef CAL_HAVE_IMPACT
  (void)c;
  (void)t;
  (void)ps;
  (void)k;
  (void)model;
  return dem_err_set(err, DEM_EUNSUPPORTED,
                     "sticking and restitution targets need the impact solver (dem/impact.h, "
                     "`impact` branch), not merged yet");
#else
  dem_params tp;
  int rc = target_params(t, ps, &tp, err);
  if (rc) return rc;
  if (t->type == CAL_T_STICKING && (rc = dem_params_set(&tp, "R", t->xr[k], "target", err)))
    return rc;
  dem_impact_scene sc;
  rc = dem_impact_setup(&sc, c->law, &tp, t->pair ? DEM_TARGET_PAIR : DEM_TARGET_WALL, err);
  if (rc) return rc;
  if (t->type == CAL_T_STICKING) {
    rc = dem_impact_sticking(&sc, &c->impact, t->v_lo, t->v_hi, t->tol, model, err);
  } else {
    dem_impact_result res;
    rc = dem_impact_run(&sc, &c->impact, t->xr[k], &res, err);
    if (!rc) *model = res.e;
  }
  if (!rc && !isfinite(*model))
    rc = dem_err_set(err, DEM_ENONFINITE, "target '%s' point %d: non-finite model value",
                     t->name, k);
  return rc;
#endif
}

int cal_model_eval(const cal_config *c, const dem_params *ps, double *model, dem_err *err) {
  /* The job list: (target, point); point -1 = a whole curve. */
  int njobs = 0;
  for (int i = 0; i < c->ntargets; i++)
    njobs += c->t[i].type == CAL_T_CURVE ? 1
             : (c->t[i].type == CAL_T_UNLOADING ? c->t[i].n : c->t[i].nres);
  int *jt = malloc(sizeof(int) * (size_t)njobs), *jp = malloc(sizeof(int) * (size_t)njobs);
  int *jrc = calloc((size_t)njobs, sizeof(int));
  dem_err *jerr = calloc((size_t)njobs, sizeof(dem_err));
  int rc = DEM_OK;
  if (!jt || !jp || !jrc || !jerr) {
    rc = dem_err_set(err, DEM_ENOMEM, "out of memory");
    goto done;
  }
  int j = 0;
  for (int i = 0; i < c->ntargets; i++) {
    if (c->t[i].type == CAL_T_CURVE) {
      jt[j] = i;
      jp[j++] = -1;
    } else
      for (int k = 0; k < (c->t[i].type == CAL_T_UNLOADING ? c->t[i].n : c->t[i].nres); k++) {
        jt[j] = i;
        jp[j++] = k;
      }
  }
#pragma omp parallel for schedule(dynamic, 1)
  for (int q = 0; q < njobs; q++) {
    const cal_target *t = &c->t[jt[q]];
    if (jp[q] < 0)
      jrc[q] = eval_curve(c, t, ps, model + t->off, &jerr[q]);
    else if (t->type == CAL_T_UNLOADING)
      jrc[q] = eval_unloading_row(c, t, ps, jp[q], model + t->off + 3 * jp[q], &jerr[q]);
    else
      jrc[q] = eval_impact_point(c, t, ps, jp[q], model + t->off + jp[q], &jerr[q]);
  }
  for (int q = 0; q < njobs; q++)
    if (jrc[q]) {
      rc = jrc[q];
      if (err) *err = jerr[q];
      break;
    }
done:
  free(jt);
  free(jp);
  free(jrc);
  free(jerr);
  return rc;
}
