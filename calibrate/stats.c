/* Parameter uncertainty at the optimum, from the finite-difference Jacobian J (n x p) of the
 * residual vector in scaled coordinates (central differences, one-sided at a bound, step
 * fd_step x the scaled range):
 *
 *   J = U S V^T (GSL SVD),  s^2 = S(u*) / (n - p),  cov(u) = s^2 (J^T J)^-1 = s^2 V S^-2 V^T,
 *
 * standard errors sqrt(diag cov), the correlation matrix, 95% intervals u +- t_{0.975,n-p} se
 * mapped back to physical units (asymmetric for a log-scale parameter; the standard error in
 * physical units is the delta-method x ln(10) se_u). A parameter is flagged as not
 * identifiable when it takes part in a correlation |rho| > 0.95, or when J is near-singular
 * (s_min < 1e-8 s_max): then the parameters that dominate the weakest singular direction are
 * named. Also flagged: a parameter whose 95% interval is wider than its whole search range
 * (poorly determined though not strongly correlated with one other), and one that sits on a
 * bound (its interval is then not a confidence interval). */
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cal.h"

#define CORR_LIMIT 0.95
#define SINGULAR_RATIO 1e-8

static void add_warning(cal_stats *st, const char *fmt, const char *a, const char *b, double v) {
  size_t used = strlen(st->warning);
  if (used + 2 >= sizeof st->warning) return;
  if (used) st->warning[used++] = ' ';
  snprintf(st->warning + used, sizeof st->warning - used, fmt, a, b, v);
}

int cal_statistics(cal_problem *p, const double *u0, cal_stats *st, dem_err *err) {
  const cal_config *c = p->cfg;
  int n = p->nres, np = c->nfree, rc = DEM_OK;
  memset(st, 0, sizeof *st);
  st->n = n;
  st->p = np;
  double *r0 = malloc(sizeof(double) * (size_t)n), *r1 = malloc(sizeof(double) * (size_t)n);
  double *r2 = malloc(sizeof(double) * (size_t)n), *mod = malloc(sizeof(double) * (size_t)n);
  gsl_matrix *J = gsl_matrix_alloc((size_t)(n > np ? n : np), (size_t)np);
  gsl_matrix *V = gsl_matrix_alloc((size_t)np, (size_t)np);
  gsl_vector *S = gsl_vector_alloc((size_t)np), *work = gsl_vector_alloc((size_t)np);
  if (!r0 || !r1 || !r2 || !mod || !J || !V || !S || !work) {
    rc = dem_err_set(err, DEM_ENOMEM, "out of memory");
    goto done;
  }
  gsl_matrix_set_zero(J);
  dem_err e = {0};
  p->stage = 2;
  if (cal_residuals(p, u0, r0, mod, &e)) {
    snprintf(st->warning, sizeof st->warning,
             "no statistics: the model fails at the optimum (%s)", e.msg);
    goto done;
  }
  double ssr = 0.0;
  for (int k = 0; k < n; k++) ssr += r0[k] * r0[k];
  for (int j = 0; j < np; j++) {
    double lo, hi, u[CAL_MAX_FREE];
    cal_scaled_bounds(&c->fr[j], &lo, &hi);
    double h = c->opt.fd_step * (hi - lo);
    memcpy(u, u0, sizeof(double) * (size_t)np);
    double up = u0[j] + h, dn = u0[j] - h;
    if (up > hi) up = u0[j];
    if (dn < lo) dn = u0[j];
    /* central difference; one-sided where a bound or a parameter set the law rejects
     * (a cross-field constraint such as f0p >= f0) is in the way */
    u[j] = up;
    int fail_up = up == u0[j] ? 0 : cal_residuals(p, u, r1, mod, &e);
    if (up == u0[j] || fail_up) {
      memcpy(r1, r0, sizeof(double) * (size_t)n);
      up = u0[j];
    }
    u[j] = dn;
    int fail_dn = dn == u0[j] ? 0 : cal_residuals(p, u, r2, mod, &e);
    if (dn == u0[j] || fail_dn) {
      memcpy(r2, r0, sizeof(double) * (size_t)n);
      dn = u0[j];
    }
    if (!(up > dn)) {
      snprintf(st->warning, sizeof st->warning,
               "no statistics: the model fails on both sides of the optimum in '%s' (%s)",
               c->fr[j].name, e.msg);
      goto done;
    }
    for (int k = 0; k < n; k++) gsl_matrix_set(J, (size_t)k, (size_t)j, (r1[k] - r2[k]) / (up - dn));
  }
  if (n <= np) {
    snprintf(st->warning, sizeof st->warning,
             "no statistics: %d residuals for %d parameters (need more points than parameters)",
             n, np);
    goto done;
  }
  gsl_linalg_SV_decomp(J, V, S, work);
  double smax = gsl_vector_get(S, 0), smin = gsl_vector_get(S, (size_t)np - 1);
  for (int j = 0; j < np; j++) st->sv[j] = gsl_vector_get(S, (size_t)j);
  st->cond = smin > 0.0 ? smax / smin : INFINITY;
  st->s2 = ssr / (n - np);
  int singular = !(smin > SINGULAR_RATIO * smax);
  for (int a = 0; a < np; a++)
    for (int b = 0; b < np; b++) {
      double s = 0.0;
      for (int q = 0; q < np; q++) {
        double sq = gsl_vector_get(S, (size_t)q);
        double inv = sq > SINGULAR_RATIO * smax ? 1.0 / (sq * sq) : INFINITY;
        double va = gsl_matrix_get(V, (size_t)a, (size_t)q), vb = gsl_matrix_get(V, (size_t)b, (size_t)q);
        if (isinf(inv))
          s += (va * vb != 0.0) ? copysign(INFINITY, va * vb) : 0.0;
        else
          s += va * vb * inv;
      }
      st->cov_u[a * np + b] = st->s2 * s;
    }
  double t = gsl_cdf_tdist_Pinv(0.975, (double)(n - np));
  for (int j = 0; j < np; j++) {
    double var = st->cov_u[j * np + j];
    st->se_u[j] = var >= 0.0 ? sqrt(var) : NAN;
    const cal_free *f = &c->fr[j];
    double x = cal_from_scaled(f, u0[j]);
    st->se_x[j] = f->scale == CAL_SCALE_LOG ? x * log(10.0) * st->se_u[j] : st->se_u[j];
    st->lo95[j] = cal_from_scaled(f, u0[j] - t * st->se_u[j]);
    st->hi95[j] = cal_from_scaled(f, u0[j] + t * st->se_u[j]);
  }
  for (int a = 0; a < np; a++)
    for (int b = 0; b < np; b++) {
      double d = sqrt(st->cov_u[a * np + a] * st->cov_u[b * np + b]);
      st->corr[a * np + b] = a == b ? 1.0 : (d > 0.0 && isfinite(d) ? st->cov_u[a * np + b] / d : NAN);
    }
  /* Identifiability. Correlations from the SVD directly (s^2 cancels): a noise-free fit
   * (s^2 = 0) still reports them. */
  if (!singular) {
    for (int a = 0; a < np; a++)
      for (int b = 0; b < np; b++) {
        double caa = 0, cbb = 0, cab = 0;
        for (int q = 0; q < np; q++) {
          double sq = gsl_vector_get(S, (size_t)q), inv = 1.0 / (sq * sq);
          double va = gsl_matrix_get(V, (size_t)a, (size_t)q), vb = gsl_matrix_get(V, (size_t)b, (size_t)q);
          caa += va * va * inv;
          cbb += vb * vb * inv;
          cab += va * vb * inv;
        }
        st->corr[a * np + b] = a == b ? 1.0 : cab / sqrt(caa * cbb);
      }
    for (int a = 0; a < np; a++)
      for (int b = a + 1; b < np; b++)
        if (fabs(st->corr[a * np + b]) > CORR_LIMIT)
          add_warning(st, "'%s' and '%s' are not separately identifiable (correlation %.4f).",
                      c->fr[a].name, c->fr[b].name, st->corr[a * np + b]);
  } else {
    char names[256] = "";
    size_t used = 0;
    for (int a = 0; a < np; a++)
      if (fabs(gsl_matrix_get(V, (size_t)a, (size_t)np - 1)) > 0.3 && used + 40 < sizeof names)
        used += (size_t)snprintf(names + used, sizeof names - used, "%s'%s'", used ? ", " : "",
                                 c->fr[a].name);
    size_t l = strlen(st->warning);
    snprintf(st->warning + l, sizeof st->warning - l,
             "%sThe Jacobian is near-singular (condition number %.3g): %s cannot be determined "
             "by these targets.",
             l ? " " : "", st->cond, names);
  }
  for (int j = 0; j < np; j++) {
    double lo, hi;
    cal_scaled_bounds(&c->fr[j], &lo, &hi);
    double tol = 1e-6 * (hi - lo);
    if (st->se_u[j] * t > (hi - lo)) {
      size_t l = strlen(st->warning);
      snprintf(st->warning + l, sizeof st->warning - l,
               "%s'%s' is poorly determined: its 95%% interval is wider than its whole search "
               "range.",
               l ? " " : "", c->fr[j].name);
    }
    if (u0[j] <= lo + tol || u0[j] >= hi - tol) {
      size_t l = strlen(st->warning);
      snprintf(st->warning + l, sizeof st->warning - l,
               "%s'%s' sits at its %s bound: the optimum is constrained there and its interval "
               "is not a confidence interval.",
               l ? " " : "", c->fr[j].name, u0[j] <= lo + tol ? "lower" : "upper");
    }
  }
  st->ok = 1;
done:
  free(r0);
  free(r1);
  free(r2);
  free(mod);
  if (J) gsl_matrix_free(J);
  if (V) gsl_matrix_free(V);
  if (S) gsl_vector_free(S);
  if (work) gsl_vector_free(work);
  return rc;
}
