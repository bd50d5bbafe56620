/* The objective S(u) = sum_i r_i^2, r_i = sqrt(w_t) (model_i - ref_i) / norm_i (cal.h).
 *
 * Every evaluation goes through the evaluation cache (keyed by the exact scaled vector u)
 * and is appended to the objective trace. A failed simulation (a parameter set the law
 * rejects, an unstable impact...) returns the finite penalty and is logged with its
 * parameters and the error: the optimiser never sees NaN and the program never crashes. */
#include <math.h>
#include <nlopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cal.h"

int cal_residuals(cal_problem *p, const double *u, double *resid, double *model, dem_err *err) {
  const cal_config *c = p->cfg;
  dem_params ps;
  double x[CAL_MAX_FREE];
  int rc = cal_params_from_scaled(c, u, x, &ps, err);
  if (rc) return rc;
  if ((rc = cal_model_eval(c, &ps, model, err))) return rc;
  for (int i = 0; i < c->ntargets; i++) {
    const cal_target *t = &c->t[i];
    double sw = sqrt(t->weight);
    for (int k = 0; k < t->nres; k++) {
      int pointwise = t->type != CAL_T_CURVE || t->mode == CAL_CURVE_SUMMARY;
      double norm = pointwise ? fabs(t->yr[k]) : t->norm;
      double r = sw * (model[t->off + k] - t->yr[k]) / norm;
      if (!isfinite(r))
        return dem_err_set(err, DEM_ENONFINITE, "target '%s' point %d: non-finite residual",
                           t->name, k);
      resid[t->off + k] = r;
    }
  }
  return DEM_OK;
}

static void log_failure(cal_problem *p, const double *u, const dem_err *e) {
  if (!p->failures) return;
  fprintf(p->failures, "eval %ld:", p->nevals);
  for (int i = 0; i < p->cfg->nfree; i++)
    fprintf(p->failures, " %s=%.10g", p->cfg->fr[i].name, cal_from_scaled(&p->cfg->fr[i], u[i]));
  fprintf(p->failures, ": %s: %s\n", dem_strerror(e->code), e->msg);
  fflush(p->failures);
}

double cal_objective(cal_problem *p, const double *u_in) {
  const cal_config *c = p->cfg;
  double u[CAL_MAX_FREE];
  for (int i = 0; i < c->nfree; i++) {
    double lo, hi;
    cal_scaled_bounds(&c->fr[i], &lo, &hi);
    u[i] = u_in[i] < lo ? lo : (u_in[i] > hi ? hi : u_in[i]);
    if (isnan(u_in[i])) u[i] = 0.5 * (lo + hi);
  }
  double f;
  int cached = p->cache && cal_cache_lookup(p->cache, u, &f);
  if (cached) {
    p->ncached++;
  } else {
    dem_err e = {0};
    int rc = cal_residuals(p, u, p->resid, p->model, &e);
    if (rc) {
      f = c->opt.penalty;
      p->nfailed++;
      log_failure(p, u, &e);
    } else {
      f = 0.0;
      for (int i = 0; i < p->nres; i++) f += p->resid[i] * p->resid[i];
      if (!isfinite(f) || f > c->opt.penalty) f = c->opt.penalty;
    }
    if (p->cache) cal_cache_store(p->cache, u, f);
  }
  p->nevals++;
  if (f < p->best_f || p->nevals == 1) {
    p->best_f = f;
    memcpy(p->best_u, u, sizeof(double) * (size_t)c->nfree);
  }
  if (p->trace) {
    fprintf(p->trace, "%ld,%d,%d,%.17g,%.17g", p->nevals, p->stage, cached, f, p->best_f);
    for (int i = 0; i < c->nfree; i++)
      fprintf(p->trace, ",%.17g", cal_from_scaled(&c->fr[i], u[i]));
    fputc('\n', p->trace);
  }
  int w = 3 + c->nfree;
  if (p->tr_n == p->tr_cap) {
    long cap = p->tr_cap ? 2 * p->tr_cap : 1024;
    double *nt = realloc(p->tr, sizeof(double) * (size_t)(cap * w));
    if (nt) {
      p->tr = nt;
      p->tr_cap = cap;
    }
  }
  if (p->tr_n < p->tr_cap) {
    double *row = p->tr + p->tr_n++ * w;
    row[0] = p->stage;
    row[1] = f;
    row[2] = p->best_f;
    for (int i = 0; i < c->nfree; i++) row[3 + i] = cal_from_scaled(&c->fr[i], u[i]);
  }
  if (p->progress) p->progress(p, p->progress_user);
  return f;
}
