/* Rate dependence of the hardness: the fit H(v) = H0 + beta rho_b v^2 (dem/analysis.h,
 * docs/analysis.md "Rate dependence").
 *
 * Why this form: an indenter moving at v must set the material ahead of it moving at about
 * v; per second and per unit projected area that is a mass rho_b v, carrying momentum
 * rho_b v^2. So on top of the quasi-static resistance H0 the indenter feels a dynamic
 * pressure proportional to rho_b v^2, with a dimensionless coefficient beta (the term
 * quadratic in v of granular impact drag, F = m g + k z + m v^2 / d1 in Katsuragi & Durian,
 * Nature Physics 3 (2007) 420). It is a scaling argument, not a derivation: beta is
 * measured, not predicted. The fit is linear in x = rho_b v^2 and is solved by
 * gsl_fit_wlinear. */
#include <math.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_fit.h>

#include "dem/analysis.h"

/* The most runs a fit takes (the harness has at most a handful of rates). */
#define RATE_FIT_MAX 64

int dem_rate_fit_dynamic(size_t n, const double *v, const double *H, const double *se,
                         double rho_b, dem_rate_fit *out, dem_err *err) {
  if (n < 2 || n > RATE_FIT_MAX)
    return dem_err_set(err, DEM_ERANGE, "rate fit: n = %zu runs, need 2 to %d", n, RATE_FIT_MAX);
  if (!isfinite(rho_b))
    return dem_err_set(err, DEM_ENONFINITE, "rate fit: rho_b = %g kg/m^3", rho_b);
  if (!(rho_b > 0.0))
    return dem_err_set(err, DEM_ERANGE, "rate fit: rho_b = %g kg/m^3, must be > 0", rho_b);
  double x[RATE_FIT_MAX], w[RATE_FIT_MAX];
  double xmin = INFINITY, xmax = -INFINITY;
  for (size_t i = 0; i < n; i++) {
    if (!isfinite(v[i]) || !isfinite(H[i]) || !isfinite(se[i]))
      return dem_err_set(err, DEM_ENONFINITE, "rate fit: run %zu: v = %g m/s, H = %g +- %g Pa",
                         i, v[i], H[i], se[i]);
    if (!(v[i] >= 0.0))
      return dem_err_set(err, DEM_ERANGE, "rate fit: run %zu: v = %g m/s, must be >= 0", i,
                         v[i]);
    if (!(se[i] > 0.0))
      return dem_err_set(err, DEM_ERANGE, "rate fit: run %zu: se = %g Pa, must be > 0", i,
                         se[i]);
    x[i] = rho_b * v[i] * v[i];
    w[i] = 1.0 / (se[i] * se[i]);
    if (x[i] < xmin) xmin = x[i];
    if (x[i] > xmax) xmax = x[i];
  }
  if (!(xmax > xmin))
    return dem_err_set(err, DEM_ERANGE, "rate fit: every run has v = %g m/s, need at least two "
                       "distinct speeds", v[0]);
  double c0, c1, cov00, cov01, cov11, chi2;
  gsl_fit_wlinear(x, 1, w, 1, H, 1, n, &c0, &c1, &cov00, &cov01, &cov11, &chi2);
  out->H0 = c0;
  out->beta = c1;
  out->chi2 = chi2;
  out->dof = (int)n - 2;
  out->p = out->dof > 0 ? gsl_cdf_chisq_Q(chi2, (double)out->dof) : NAN;
  out->scale = (out->dof > 0 && chi2 > (double)out->dof) ? sqrt(chi2 / (double)out->dof) : 1.0;
  out->H0_se = out->scale * sqrt(cov00);
  out->beta_se = out->scale * sqrt(cov11);
  out->cov = out->scale * out->scale * cov01;
  return DEM_OK;
}

double dem_rate_onset_speed(const dem_rate_fit *f, double rho_b, double frac, double *se) {
  if (se) *se = NAN;
  if (!(f->H0 > 0.0 && f->beta > 0.0 && rho_b > 0.0 && frac > 0.0)) return NAN;
  double v = sqrt(frac * f->H0 / (f->beta * rho_b));
  if (se) {
    double a = f->H0_se / f->H0, b = f->beta_se / f->beta, c = f->cov / (f->H0 * f->beta);
    double r2 = a * a + b * b - 2.0 * c;
    *se = 0.5 * v * sqrt(r2 > 0.0 ? r2 : 0.0);
  }
  return v;
}
