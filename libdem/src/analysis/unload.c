/* Contact depth from the tangent to the initial unloading (dem/analysis.h; thesis 2.3.5,
 * Fig 2.16): "h_c can be calculated by estimating the tangent to the initial elastic part of
 * the unloading curve. The slope of the tangential line determines the location of h_c on
 * the penetration depth axis."
 *
 *   S   = dF/dh at the start of unloading (from a fit to the initial part of the branch)
 *   h_c = h_max - F_max / S                (the tangent through (h_max, F_max) at F = 0)
 *   H   = F_max / (pi (D h_c - h_c^2))     (thesis 2.7, 2.9)
 *
 * This is the tangent intercept the thesis describes (Doerner & Nix 1986); Oliver & Pharr
 * (1992) would use h_max - 0.75 F_max / S for a paraboloid. Two fits (docs/analysis.md):
 *   linear: least squares F = a + S h over the points with F >= (1 - frac) F_max; on a curved
 *           branch this is a secant, biased low in S (about 3 % for frac = 0.2 on a 3/2 power);
 *   power:  F = alpha (h - h_f)^m (Oliver & Pharr), least squares of ln F on ln(h - h_f) for
 *           each trial h_f, h_f chosen by a scan then golden-section search; S = m alpha
 *           (h_max - h_f)^(m - 1).
 */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_fit.h>

#include "dem/analysis.h"

size_t dem_unload_start(size_t n, const double *h) {
  size_t k = 0;
  for (size_t i = 1; i < n; i++)
    if (h[i] > h[k]) k = i;
  return k;
}

/* Sum of squared residuals of ln F = ln alpha + m ln(h - h_f) for the trial h_f. */
static double power_ssr(double hf, size_t n, const double *h, const double *lnF, double *u,
                        double *c0, double *c1) {
  for (size_t i = 0; i < n; i++) u[i] = log(h[i] - hf);
  double cov00, cov01, cov11, ssr;
  gsl_fit_linear(u, 1, lnF, 1, n, c0, c1, &cov00, &cov01, &cov11, &ssr);
  return ssr;
}

static int fit_power(size_t n, const double *h, const double *F, double h_max, dem_unload *o,
                     dem_err *err) {
  double *buf = malloc(3 * n * sizeof *buf);
  if (!buf) return dem_err_set(err, DEM_ENOMEM, "unloading fit: %zu points", n);
  double *hh = buf, *lnF = buf + n, *u = buf + 2 * n;
  double hmin = INFINITY;
  for (size_t i = 0; i < n; i++) {
    hh[i] = h[i];
    lnF[i] = log(F[i]);
    if (h[i] < hmin) hmin = h[i];
  }
  double span = h_max - hmin, c0, c1;
  /* h_f = hmin - span * s, s from 1e-6 to 1e4 on a log scale, then golden section. */
  const int NS = 300;
  double best = INFINITY;
  int kb = 0;
  for (int k = 0; k < NS; k++) {
    double s = pow(10.0, -6.0 + 10.0 * k / (NS - 1));
    double r = power_ssr(hmin - span * s, n, hh, lnF, u, &c0, &c1);
    if (r < best) {
      best = r;
      kb = k;
    }
  }
  double la = -6.0 + 10.0 * (kb > 0 ? kb - 1 : 0) / (NS - 1);
  double lb = -6.0 + 10.0 * (kb < NS - 1 ? kb + 1 : NS - 1) / (NS - 1);
  const double gr = 0.5 * (sqrt(5.0) - 1.0);
  double l1 = lb - gr * (lb - la), l2 = la + gr * (lb - la);
  double f1 = power_ssr(hmin - span * pow(10.0, l1), n, hh, lnF, u, &c0, &c1);
  double f2 = power_ssr(hmin - span * pow(10.0, l2), n, hh, lnF, u, &c0, &c1);
  for (int it = 0; it < 200 && lb - la > 1e-13; it++) {
    if (f1 < f2) {
      lb = l2;
      l2 = l1;
      f2 = f1;
      l1 = lb - gr * (lb - la);
      f1 = power_ssr(hmin - span * pow(10.0, l1), n, hh, lnF, u, &c0, &c1);
    } else {
      la = l1;
      l1 = l2;
      f1 = f2;
      l2 = la + gr * (lb - la);
      f2 = power_ssr(hmin - span * pow(10.0, l2), n, hh, lnF, u, &c0, &c1);
    }
  }
  double hf = hmin - span * pow(10.0, 0.5 * (la + lb));
  power_ssr(hf, n, hh, lnF, u, &c0, &c1);
  free(buf);
  o->h_f = hf;
  o->m = c1;
  o->S = c1 * exp(c0) * pow(h_max - hf, c1 - 1.0);
  o->S_se = NAN;
  return DEM_OK;
}

int dem_unload_analyse(size_t n, const double *h, const double *F, double D,
                       dem_unload_fit method, double frac, dem_unload *out, dem_err *err) {
  if (!(frac > 0.0 && frac <= 1.0))
    return dem_err_set(err, DEM_ERANGE, "unloading: frac = %g, must be in (0, 1]", frac);
  if (!(D > 0.0) || !isfinite(D))
    return dem_err_set(err, DEM_ERANGE, "unloading: indenter diameter D = %g m, must be > 0",
                       D);
  if (method != DEM_UNLOAD_LINEAR && method != DEM_UNLOAD_POWER)
    return dem_err_set(err, DEM_ERANGE, "unloading: method = %d, must be LINEAR or POWER",
                       (int)method);
  if (n < 3)
    return dem_err_set(err, DEM_ERANGE, "unloading: %zu points, need at least 3", n);
  if (!h || !F) return dem_err_set(err, DEM_EINVAL, "unloading: NULL h or F");
  for (size_t i = 0; i < n; i++)
    if (!isfinite(h[i]) || !isfinite(F[i]))
      return dem_err_set(err, DEM_ENONFINITE, "unloading: point %zu: h = %g m, F = %g N", i,
                         h[i], F[i]);
  double hmax = h[0], Fmax = F[0];
  if (!(Fmax > 0.0))
    return dem_err_set(err, DEM_ERANGE, "unloading: F_max = F[0] = %g N, must be > 0", Fmax);
  double thr = (1.0 - frac) * Fmax;
  double *sel = malloc(2 * n * sizeof *sel);
  if (!sel) return dem_err_set(err, DEM_ENOMEM, "unloading: %zu points", n);
  double *sh = sel, *sF = sel + n;
  size_t m = 0;
  double hlo = hmax;
  for (size_t i = 0; i < n; i++) {
    if (F[i] < thr || (method == DEM_UNLOAD_POWER && !(F[i] > 0.0))) continue;
    if (h[i] > hmax) {
      free(sel);
      return dem_err_set(err, DEM_ERANGE, "unloading: h[%zu] = %g m exceeds h[0] = %g m: the "
                         "branch must start at the reversal point (dem_unload_start)", i, h[i],
                         hmax);
    }
    sh[m] = h[i];
    sF[m] = F[i];
    if (h[i] < hlo) hlo = h[i];
    m++;
  }
  if (m < 3 || !(hlo < hmax)) {
    free(sel);
    return dem_err_set(err, DEM_ERANGE, "unloading: %zu points with F >= %g N over a depth "
                       "range of %g m; need 3 at distinct depths (raise frac = %g)", m, thr,
                       hmax - hlo, frac);
  }
  out->h_max = hmax;
  out->F_max = Fmax;
  out->nfit = m;
  int st = DEM_OK;
  if (method == DEM_UNLOAD_LINEAR) {
    double c0, c1, cov00, cov01, cov11, ssr;
    gsl_fit_linear(sh, 1, sF, 1, m, &c0, &c1, &cov00, &cov01, &cov11, &ssr);
    out->S = c1;
    out->S_se = sqrt(cov11);
    out->h_f = NAN;
    out->m = 1.0;
  } else {
    st = fit_power(m, sh, sF, hmax, out, err);
  }
  free(sel);
  if (st) return st;
  if (!(out->S > 0.0) || !isfinite(out->S))
    return dem_err_set(err, DEM_EPHYSICS, "unloading: fitted stiffness S = %g N/m, must be > 0 "
                       "(the force does not fall on unloading)", out->S);
  out->h_c = hmax - Fmax / out->S;
  if (!(out->h_c > 0.0))
    return dem_err_set(err, DEM_EPHYSICS, "unloading: contact depth h_c = %g m <= 0 (S = %g "
                       "N/m too soft for F_max = %g N at h_max = %g m)", out->h_c, out->S,
                       Fmax, hmax);
  out->H = dem_hardness(Fmax, D, out->h_c);
  return DEM_OK;
}
