/* The NLopt driver: a deterministic global stage (default GN_DIRECT_L) from which a local
 * polish starts (LN_BOBYQA for smooth objectives; LN_SBPLX when a sticking target makes the
 * objective step-like through its bisection), or multi-start: the local algorithm from the
 * configured start and from `multistart - 1` points drawn uniformly in the scaled box by a GSL
 * generator seeded with the config's seed. Every stage has a maxeval; nlopt_srand(seed) is
 * called in this (the optimising) thread before each stage, so a run is reproducible. The
 * reported optimum is the best point evaluated in any stage. */
#include <gsl/gsl_rng.h>
#include <math.h>
#include <nlopt.h>
#include <string.h>

#include "cal.h"

typedef struct wrap {
  cal_problem *p;
  nlopt_opt opt;
} wrap;

static double fobj(unsigned n, const double *u, double *grad, void *data) {
  (void)n;
  (void)grad; /* derivative-free algorithms only */
  wrap *w = data;
  if (w->p->stop_after > 0 && w->p->nevals >= w->p->stop_after && w->p->stop) *w->p->stop = 1;
  if (w->p->stop && *w->p->stop) {
    nlopt_force_stop(w->opt);
    return w->p->cfg->opt.penalty;
  }
  return cal_objective(w->p, u);
}

static const char *local_name(const cal_config *c) {
  if (strcmp(c->opt.local, "auto") != 0) return c->opt.local;
  for (int i = 0; i < c->ntargets; i++)
    if (c->t[i].type == CAL_T_STICKING) return "LN_SBPLX";
  /* BOBYQA needs at least two variables; Subplex is NLopt's robust alternative. */
  return c->nfree >= 2 ? "LN_BOBYQA" : "LN_SBPLX";
}

static int run_stage(cal_problem *p, const char *algo, int maxeval, double *u, int *code,
                     dem_err *err) {
  const cal_config *c = p->cfg;
  int n = c->nfree;
  nlopt_algorithm a = nlopt_algorithm_from_string(algo);
  if ((int)a < 0) return dem_err_set(err, DEM_ENOTFOUND, "NLopt knows no algorithm '%s'", algo);
  nlopt_srand(c->seed);
  nlopt_opt opt = nlopt_create(a, (unsigned)n);
  if (!opt) return dem_err_set(err, DEM_ENOMEM, "nlopt_create(%s, %d) failed", algo, n);
  double lo[CAL_MAX_FREE], hi[CAL_MAX_FREE], step[CAL_MAX_FREE];
  for (int i = 0; i < n; i++) {
    cal_scaled_bounds(&c->fr[i], &lo[i], &hi[i]);
    step[i] = 0.1 * (hi[i] - lo[i]);
    if (u[i] < lo[i]) u[i] = lo[i];
    if (u[i] > hi[i]) u[i] = hi[i];
  }
  wrap w = {p, opt};
  nlopt_set_lower_bounds(opt, lo);
  nlopt_set_upper_bounds(opt, hi);
  nlopt_set_min_objective(opt, fobj, &w);
  nlopt_set_maxeval(opt, maxeval);
  if (algo[1] == 'N') { /* local */
    nlopt_set_xtol_rel(opt, c->opt.xtol_rel);
    nlopt_set_ftol_rel(opt, c->opt.ftol_rel);
    nlopt_set_initial_step(opt, step);
  }
  double f = 0.0;
  nlopt_result r = nlopt_optimize(opt, u, &f);
  *code = (int)r;
  int rc = DEM_OK;
  if (r == NLOPT_FORCED_STOP && p->stop && *p->stop)
    rc = dem_err_set(err, DEM_EINTERRUPTED, "interrupted during %s", algo);
  else if (r < 0 && r != NLOPT_ROUNDOFF_LIMITED && r != NLOPT_FORCED_STOP)
    rc = dem_err_set(err, DEM_EINVAL, "NLopt %s failed: %s%s%s", algo, nlopt_result_to_string(r),
                     nlopt_get_errmsg(opt) ? ": " : "",
                     nlopt_get_errmsg(opt) ? nlopt_get_errmsg(opt) : "");
  nlopt_destroy(opt);
  return rc;
}

static void start_point(const cal_config *c, double *u) {
  for (int i = 0; i < c->nfree; i++) {
    double lo, hi;
    cal_scaled_bounds(&c->fr[i], &lo, &hi);
    u[i] = isnan(c->fr[i].start) ? 0.5 * (lo + hi) : cal_to_scaled(&c->fr[i], c->fr[i].start);
  }
}

int cal_optimise(cal_problem *p, cal_result *res, dem_err *err) {
  const cal_config *c = p->cfg;
  int n = c->nfree, rc = DEM_OK;
  double u[CAL_MAX_FREE];
  memset(res, 0, sizeof *res);
  res->nlopt_global = res->nlopt_local = 0;
  const char *loc = local_name(c);
  if (c->opt.multistart > 0) {
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (!rng) return dem_err_set(err, DEM_ENOMEM, "out of memory");
    gsl_rng_set(rng, c->seed);
    p->stage = 1;
    for (int s = 0; s < c->opt.multistart && !rc; s++) {
      start_point(c, u);
      if (s > 0)
        for (int i = 0; i < n; i++) {
          double lo, hi;
          cal_scaled_bounds(&c->fr[i], &lo, &hi);
          u[i] = lo + (hi - lo) * gsl_rng_uniform(rng);
        }
      rc = run_stage(p, loc, c->opt.maxeval_local, u, &res->nlopt_local, err);
    }
    gsl_rng_free(rng);
  } else {
    start_point(c, u);
    if (c->opt.global[0] && c->opt.maxeval_global > 0) {
      p->stage = 0;
      rc = run_stage(p, c->opt.global, c->opt.maxeval_global, u, &res->nlopt_global, err);
      memcpy(u, p->best_u, sizeof(double) * (size_t)n);
    }
    if (!rc && loc[0] && c->opt.maxeval_local > 0) {
      p->stage = 1;
      rc = run_stage(p, loc, c->opt.maxeval_local, u, &res->nlopt_local, err);
    }
  }
  res->interrupted = rc == DEM_EINTERRUPTED;
  memcpy(res->u, p->best_u, sizeof(double) * (size_t)n);
  for (int i = 0; i < n; i++) res->x[i] = cal_from_scaled(&c->fr[i], res->u[i]);
  res->f = p->best_f;
  return rc;
}
