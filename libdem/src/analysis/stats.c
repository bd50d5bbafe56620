/* Statistics of fluctuating series: plateau mean, spread, correlation-aware standard error,
 * slope, and the z-test between two means (dem/analysis.h, docs/analysis.md).
 *
 * Integrated autocorrelation time (Sokal 1997, "Monte Carlo methods in statistical
 * mechanics", automatic windowing; Madras & Sokal 1988):
 *   C(t)   = (1/n) sum_{i < n-t} (y_i - ybar)(y_{i+t} - ybar),   rho(t) = C(t)/C(0)
 *   tau(W) = 1/2 + sum_{t=1..W} rho(t),   W the smallest lag with W >= c tau(W), c = 6
 *   var(ybar) = 2 tau C(0) / (n - 2 tau)
 * (n - 2 tau instead of n: the first-order correction for the subtracted mean,
 * E[C(0)] ~ sigma^2 (1 - 2 tau / n)). tau is floored at 1/2 (anticorrelation is not
 * credited). If no W <= n/4 satisfies the condition, W = n/4 and `reliable` = 0.
 * For AR(1) with coefficient phi, tau = (1 + phi) / (2 (1 - phi)).
 *
 * Batch means: nb batches of length L = floor(n / nb) (the last n - nb L samples dropped),
 * var(ybar) = var(batch means) / nb; `reliable` if L >= 10 tau.
 */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_fit.h>

#include "dem/analysis.h"

/* tau and window of y (length n >= 4, mean ybar); c = window constant. */
static double iat(size_t n, const double *y, double ybar, double c, size_t *window,
                  int *reliable) {
  double c0 = 0.0;
  for (size_t i = 0; i < n; i++) c0 += (y[i] - ybar) * (y[i] - ybar);
  c0 /= (double)n;
  *reliable = 1;
  if (!(c0 > 0.0)) {
    *window = 0;
    return 0.5;
  }
  size_t wmax = n / 4;
  double tau = 0.5;
  size_t W = 0;
  for (size_t t = 1; t <= wmax; t++) {
    double ct = 0.0;
    for (size_t i = 0; i + t < n; i++) ct += (y[i] - ybar) * (y[i + t] - ybar);
    tau += ct / (double)n / c0;
    W = t;
    if ((double)t >= c * tau) break;
  }
  if ((double)W < c * tau) *reliable = 0;
  *window = W;
  return tau > 0.5 ? tau : 0.5;
}

int dem_series_analyse(size_t n, const double *x, const double *y,
                       const dem_stats_opts *opts, dem_series_stats *out, dem_err *err) {
  dem_stats_opts o = {DEM_SE_IAT, 6.0, 20};
  if (opts) {
    o.method = opts->method;
    if (opts->c_window != 0.0) o.c_window = opts->c_window;
    if (opts->nbatch != 0) o.nbatch = opts->nbatch;
  }
  if (o.method != DEM_SE_IAT && o.method != DEM_SE_BATCH)
    return dem_err_set(err, DEM_ERANGE, "series: method = %d, must be IAT or BATCH",
                       (int)o.method);
  if (!(o.c_window >= 1.0 && o.c_window <= 100.0))
    return dem_err_set(err, DEM_ERANGE, "series: c_window = %g, must be in [1, 100]",
                       o.c_window);
  if (n < 4) return dem_err_set(err, DEM_ERANGE, "series: n = %zu samples, need at least 4", n);
  if (!y) return dem_err_set(err, DEM_EINVAL, "series: NULL y");
  if (o.method == DEM_SE_BATCH && (o.nbatch < 2 || o.nbatch > n / 2))
    return dem_err_set(err, DEM_ERANGE, "series: nbatch = %zu, must be in [2, n/2 = %zu]",
                       o.nbatch, n / 2);
  for (size_t i = 0; i < n; i++)
    if (!isfinite(y[i]) || (x && !isfinite(x[i])))
      return dem_err_set(err, DEM_ENONFINITE, "series: sample %zu not finite (y = %g)", i,
                         y[i]);

  double *buf = malloc(2 * n * sizeof *buf);
  if (!buf) return dem_err_set(err, DEM_ENOMEM, "series: %zu samples", n);
  double *xx = buf, *res = buf + n;
  for (size_t i = 0; i < n; i++) xx[i] = x ? x[i] : (double)i;

  double mean = 0.0, ss = 0.0;
  for (size_t i = 0; i < n; i++) mean += y[i];
  mean /= (double)n;
  for (size_t i = 0; i < n; i++) ss += (y[i] - mean) * (y[i] - mean);
  double sd = sqrt(ss / (double)(n - 1));

  out->n = n;
  out->mean = mean;
  out->sd = sd;
  out->se_naive = sd / sqrt((double)n);
  out->cv = mean != 0.0 ? sd / fabs(mean) : NAN;
  if (o.method == DEM_SE_IAT) {
    double tau = iat(n, y, mean, o.c_window, &out->window, &out->reliable);
    double c0 = ss / (double)n;
    double den = (double)n - 2.0 * tau;
    out->tau = tau;
    out->se = den > 0.0 ? sqrt(2.0 * tau * c0 / den) : INFINITY;
  } else {
    size_t nb = o.nbatch, L = n / nb;
    double bm = 0.0, bv = 0.0;
    for (size_t b = 0; b < nb; b++) {
      double s = 0.0;
      for (size_t i = b * L; i < (b + 1) * L; i++) s += y[i];
      res[b] = s / (double)L;
      bm += res[b];
    }
    bm /= (double)nb;
    for (size_t b = 0; b < nb; b++) bv += (res[b] - bm) * (res[b] - bm);
    bv /= (double)(nb - 1);
    out->se = sqrt(bv / (double)nb);
    out->tau = sd > 0.0 ? 0.5 * out->se * out->se * (double)n / (sd * sd) : 0.5;
    out->window = L;
    out->reliable = (double)L >= 10.0 * out->tau;
  }
  out->n_eff = (double)n / (2.0 * out->tau);

  /* Slope by least squares; its standard error inflated by the residuals' correlation. */
  double xlo = xx[0], xhi = xx[0];
  for (size_t i = 1; i < n; i++) {
    if (xx[i] < xlo) xlo = xx[i];
    if (xx[i] > xhi) xhi = xx[i];
  }
  if (xhi > xlo) {
    double c0, c1, cov00, cov01, cov11, ssr;
    gsl_fit_linear(xx, 1, y, 1, n, &c0, &c1, &cov00, &cov01, &cov11, &ssr);
    double rm = 0.0;
    for (size_t i = 0; i < n; i++) {
      res[i] = y[i] - (c0 + c1 * xx[i]);
      rm += res[i];
    }
    rm /= (double)n;
    size_t w;
    int rel;
    double tr = iat(n, res, rm, o.c_window, &w, &rel);
    out->slope = c1;
    out->intercept = c0;
    out->slope_se = sqrt(cov11);
    out->slope_se_corr = out->slope_se * sqrt(2.0 * tr);
  } else {
    out->slope = out->intercept = out->slope_se = out->slope_se_corr = NAN;
  }
  out->lo = xlo;
  out->hi = xhi;
  free(buf);
  return DEM_OK;
}

int dem_plateau_stats(size_t n, const double *hd, const double *y, double lo, double hi,
                      const dem_stats_opts *opts, dem_series_stats *out, dem_err *err) {
  if (!(lo < hi) || !isfinite(lo) || !isfinite(hi))
    return dem_err_set(err, DEM_ERANGE, "plateau: window [%g, %g] of h/r, need lo < hi", lo,
                       hi);
  if (n > 0 && (!hd || !y))
    return dem_err_set(err, DEM_EINVAL, "plateau: NULL hd or y with n = %zu", n);
  size_t m = 0;
  for (size_t i = 0; i < n; i++)
    if (hd[i] >= lo && hd[i] <= hi) m++;
  if (m < 4)
    return dem_err_set(err, DEM_ERANGE, "plateau: %zu samples with h/r in [%g, %g], need at "
                       "least 4", m, lo, hi);
  double *buf = malloc(2 * m * sizeof *buf);
  if (!buf) return dem_err_set(err, DEM_ENOMEM, "plateau: %zu samples", m);
  size_t k = 0;
  for (size_t i = 0; i < n; i++)
    if (hd[i] >= lo && hd[i] <= hi) {
      buf[k] = hd[i];
      buf[m + k] = y[i];
      k++;
    }
  int st = dem_series_analyse(m, buf, buf + m, opts, out, err);
  free(buf);
  if (st) return st;
  out->lo = lo;
  out->hi = hi;
  return DEM_OK;
}

/* The z-test (nu = INFINITY) or Welch's t-test. */
static int compare(double mean1, double se1, double nu1, double mean2, double se2, double nu2,
                   double level, dem_alternative alt, dem_comparison *out, dem_err *err) {
  if (!isfinite(mean1) || !isfinite(mean2) || !isfinite(se1) || !isfinite(se2))
    return dem_err_set(err, DEM_ENONFINITE, "compare: mean1 = %g, se1 = %g, mean2 = %g, se2 = "
                       "%g", mean1, se1, mean2, se2);
  if (!(se1 >= 0.0 && se2 >= 0.0) || !(se1 > 0.0 || se2 > 0.0))
    return dem_err_set(err, DEM_ERANGE, "compare: se1 = %g, se2 = %g, must be >= 0 and not both "
                       "0", se1, se2);
  if (!(level > 0.0 && level < 0.5))
    return dem_err_set(err, DEM_ERANGE, "compare: level = %g, must be in (0, 0.5)", level);
  if (!(nu1 >= 1.0) || !(nu2 >= 1.0))
    return dem_err_set(err, DEM_ERANGE, "compare: degrees of freedom nu1 = %g, nu2 = %g, must "
                       "be >= 1", nu1, nu2);
  out->diff = mean1 - mean2;
  out->se = sqrt(se1 * se1 + se2 * se2);
  out->z = out->diff / out->se;
  out->level = level;
  double a1 = se1 * se1, a2 = se2 * se2;
  double den = (isinf(nu1) ? 0.0 : a1 * a1 / nu1) + (isinf(nu2) ? 0.0 : a2 * a2 / nu2);
  double nu = den > 0.0 ? (a1 + a2) * (a1 + a2) / den : INFINITY;
  out->nu = nu;
  /* Upper tail Q(z) and its inverse for the distribution in use. */
#define TAIL_Q(t) (isinf(nu) ? gsl_cdf_ugaussian_Q(t) : gsl_cdf_tdist_Q((t), nu))
#define TAIL_QINV(p) (isinf(nu) ? gsl_cdf_ugaussian_Qinv(p) : gsl_cdf_tdist_Qinv((p), nu))
  switch (alt) {
  case DEM_TEST_TWO_SIDED:
    out->p = 2.0 * TAIL_Q(fabs(out->z));
    out->z_crit = TAIL_QINV(0.5 * level);
    out->different = fabs(out->z) > out->z_crit;
    break;
  case DEM_TEST_GREATER:
    out->p = TAIL_Q(out->z);
    out->z_crit = TAIL_QINV(level);
    out->different = out->z > out->z_crit;
    break;
  case DEM_TEST_LESS:
    out->p = TAIL_Q(-out->z);
    out->z_crit = -TAIL_QINV(level);
    out->different = out->z < out->z_crit;
    break;
  default:
    return dem_err_set(err, DEM_ERANGE, "compare: alternative = %d, must be TWO_SIDED, GREATER "
                       "or LESS", (int)alt);
  }
#undef TAIL_Q
#undef TAIL_QINV
  return DEM_OK;
}

int dem_compare_means(double mean1, double se1, double mean2, double se2, double level,
                      dem_alternative alt, dem_comparison *out, dem_err *err) {
  return compare(mean1, se1, INFINITY, mean2, se2, INFINITY, level, alt, out, err);
}

int dem_compare_means_t(double mean1, double se1, double nu1, double mean2, double se2,
                        double nu2, double level, dem_alternative alt, dem_comparison *out,
                        dem_err *err) {
  return compare(mean1, se1, nu1, mean2, se2, nu2, level, alt, out, err);
}

int dem_replicates_mean(size_t k, const double *means, double *mean, double *se, dem_err *err) {
  if (k < 2) return dem_err_set(err, DEM_ERANGE, "replicates: k = %zu, need at least 2", k);
  double m = 0.0, ss = 0.0;
  for (size_t i = 0; i < k; i++) {
    if (!isfinite(means[i]))
      return dem_err_set(err, DEM_ENONFINITE, "replicates: mean %zu = %g", i, means[i]);
    m += means[i];
  }
  m /= (double)k;
  for (size_t i = 0; i < k; i++) ss += (means[i] - m) * (means[i] - m);
  *mean = m;
  *se = sqrt(ss / (double)(k - 1) / (double)k);
  return DEM_OK;
}

int dem_compare_paired(size_t k, const double *a, const double *se_a, const double *b,
                       const double *se_b, double level, dem_alternative alt,
                       dem_comparison *out, double *q, dem_err *err) {
  if (q) *q = 0.0;
  if (k == 0) return dem_err_set(err, DEM_ERANGE, "compare_paired: k = 0, need at least 1");
  if (k == 1) return dem_compare_means(a[0], se_a[0], b[0], se_b[0], level, alt, out, err);
  if (!(level > 0.0 && level < 0.5))
    return dem_err_set(err, DEM_ERANGE, "compare_paired: level = %g, must be in (0, 0.5)",
                       level);
  double dbar = 0.0, sw2 = 0.0, wsum = 0.0, dw = 0.0;
  for (size_t i = 0; i < k; i++) {
    if (!isfinite(a[i]) || !isfinite(b[i]) || !isfinite(se_a[i]) || !isfinite(se_b[i]))
      return dem_err_set(err, DEM_ENONFINITE, "compare_paired: pair %zu: %g +- %g, %g +- %g",
                         i, a[i], se_a[i], b[i], se_b[i]);
    if (!(se_a[i] > 0.0) || !(se_b[i] > 0.0))
      return dem_err_set(err, DEM_ERANGE, "compare_paired: pair %zu: se %g, %g, must be > 0", i,
                         se_a[i], se_b[i]);
    double s2 = se_a[i] * se_a[i] + se_b[i] * se_b[i];
    dbar += (a[i] - b[i]) / (double)k;
    sw2 += s2 / ((double)k * (double)k);
    wsum += 1.0 / s2;
    dw += (a[i] - b[i]) / s2;
  }
  dw /= wsum;
  double Q = 0.0, ss = 0.0;
  for (size_t i = 0; i < k; i++) {
    double d = a[i] - b[i];
    Q += (d - dw) * (d - dw) / (se_a[i] * se_a[i] + se_b[i] * se_b[i]);
    ss += (d - dbar) * (d - dbar);
  }
  if (q) *q = Q;
  /* Cochran's Q against chi^2_{k-1}: the spread of d between beds is judged by the runs'
   * own errors (z) unless it is significantly larger (t with k - 1 dof on the spread). */
  if (Q > gsl_cdf_chisq_Qinv(level, (double)(k - 1)))
    return compare(dbar, sqrt(ss / (double)(k - 1) / (double)k), (double)(k - 1), 0.0, 0.0,
                   INFINITY, level, alt, out, err);
  return compare(dbar, sqrt(sw2), INFINITY, 0.0, 0.0, INFINITY, level, alt, out, err);
}
