/* Targets: which points of each reference data set are compared, and how they are
 * normalised (cal.h). A force-overlap curve is split into monotone branches of its overlap
 * sequence (loading, unloading, reloading...): "points" compares every reference point,
 * "grid" resamples each branch on `grid` evenly spaced overlaps (a common overlap grid for
 * reference and model), "summary" compares f_max, the permanent overlap alpha_p and the
 * pull-off force. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cal.h"
#include "curve.h"

int cal_runs(const double *a, int n, int *run) {
  int r = 0, dir = 0;
  if (n > 0) run[0] = 0;
  for (int k = 1; k < n; k++) {
    double d = a[k] - a[k - 1];
    int s = d > 0 ? 1 : (d < 0 ? -1 : 0);
    if (s != 0 && dir != 0 && s != dir) r++;
    if (s != 0) dir = s;
    run[k] = r;
  }
  return n > 0 ? r + 1 : 0;
}

int cal_first_direction(const double *a, int n) {
  for (int k = 1; k < n; k++) {
    if (a[k] > a[k - 1]) return 1;
    if (a[k] < a[k - 1]) return -1;
  }
  return 0;
}

double cal_interp_run(const double *a, const double *f, const int *run, int n, int r,
                      double x) {
  int k0 = -1, k1 = -1;
  for (int k = 0; k < n; k++)
    if (run[k] == r || (k + 1 < n && run[k + 1] == r)) {
      /* a run shares its first point with the end of the previous one */
      if (k0 < 0) k0 = k;
      k1 = k;
    }
  if (k0 < 0) return NAN;
  if (k1 == k0) return f[k0];
  int up = a[k1] > a[k0];
  double lo = up ? a[k0] : a[k1], hi = up ? a[k1] : a[k0];
  if (x <= lo) return up ? f[k0] : f[k1];
  if (x >= hi) return up ? f[k1] : f[k0];
  /* binary search on the monotone run [k0, k1] */
  int i = k0, j = k1;
  while (j - i > 1) {
    int m = (i + j) / 2;
    if ((a[m] <= x) == up)
      i = m;
    else
      j = m;
  }
  double da = a[j] - a[i];
  if (da == 0.0) return f[i];
  double w = (x - a[i]) / da;
  return f[i] + w * (f[j] - f[i]);
}

/* Summary points of a curve: f_max; alpha_p where the force first returns to zero after the
 * largest overlap; pull-off force -min f (when the curve is tensile somewhere). Sets has[3]. */
void cal_curve_summary(const double *a, const double *f, int n, double out[3], int has[3]) {
  int kmax = 0, kamax = 0, kmin = 0;
  for (int k = 1; k < n; k++) {
    if (f[k] > f[kmax]) kmax = k;
    if (a[k] > a[kamax]) kamax = k;
    if (f[k] < f[kmin]) kmin = k;
  }
  out[0] = f[kmax];
  has[0] = f[kmax] > 0.0;
  has[1] = 0;
  out[1] = NAN;
  for (int k = kamax + 1; k < n; k++)
    if (f[k - 1] > 0.0 && f[k] <= 0.0) {
      double w = f[k - 1] / (f[k - 1] - f[k]);
      out[1] = a[k - 1] + w * (a[k] - a[k - 1]);
      has[1] = out[1] > 0.0;
      break;
    }
  out[2] = -f[kmin];
  has[2] = f[kmin] < 0.0;
}

static int prepare_curve(cal_target *t, dem_err *err) {
  int *run = malloc(sizeof(int) * (size_t)t->n);
  if (!run) return dem_err_set(err, DEM_ENOMEM, "out of memory");
  int nruns = cal_runs(t->x, t->n, run);
  t->norm = 0.0;
  for (int k = 0; k < t->n; k++)
    if (fabs(t->y[k]) > t->norm) t->norm = fabs(t->y[k]);
  if (!(t->norm > 0.0)) {
    free(run);
    return dem_err_set(err, DEM_EINVAL, "target '%s': the reference force is zero everywhere",
                       t->name);
  }
  int cap = t->mode == CAL_CURVE_POINTS ? t->n : (t->mode == CAL_CURVE_GRID ? nruns * t->grid : 3);
  t->xr = calloc((size_t)cap, sizeof(double));
  t->yr = calloc((size_t)cap, sizeof(double));
  t->branch = calloc((size_t)cap, sizeof(int));
  if (!t->xr || !t->yr || !t->branch) {
    free(run);
    return dem_err_set(err, DEM_ENOMEM, "out of memory");
  }
  int m = 0;
  if (t->mode == CAL_CURVE_POINTS) {
    for (int k = 0; k < t->n; k++) {
      t->xr[m] = t->x[k];
      t->yr[m] = t->y[k];
      t->branch[m++] = run[k];
    }
  } else if (t->mode == CAL_CURVE_GRID) {
    for (int r = 0; r < nruns; r++) {
      double lo = INFINITY, hi = -INFINITY;
      for (int k = 0; k < t->n; k++)
        if (run[k] == r || (k + 1 < t->n && run[k + 1] == r)) {
          if (t->x[k] < lo) lo = t->x[k];
          if (t->x[k] > hi) hi = t->x[k];
        }
      if (!(hi > lo)) continue;
      for (int g = 0; g < t->grid; g++) {
        double x = lo + (hi - lo) * g / (t->grid - 1);
        t->xr[m] = x;
        t->yr[m] = cal_interp_run(t->x, t->y, run, t->n, r, x);
        t->branch[m++] = r;
      }
    }
  } else {
    double s[3];
    int has[3];
    cal_curve_summary(t->x, t->y, t->n, s, has);
    for (int q = 0; q < 3; q++)
      if (has[q]) {
        t->xr[m] = q;
        t->yr[m] = s[q];
        t->branch[m++] = -1 - q;
      }
  }
  free(run);
  t->nres = m;
  if (m == 0)
    return dem_err_set(err, DEM_EINVAL, "target '%s': no points to compare", t->name);
  return DEM_OK;
}

int cal_targets_prepare(cal_config *c, int *nres, dem_err *err) {
  int off = 0;
  for (int i = 0; i < c->ntargets; i++) {
    cal_target *t = &c->t[i];
    free(t->xr);
    free(t->yr);
    free(t->branch);
    t->xr = t->yr = NULL;
    t->branch = NULL;
    if (t->type == CAL_T_CURVE) {
      int rc = prepare_curve(t, err);
      if (rc) return rc;
    } else if (t->type == CAL_T_UNLOADING) {
      /* three compared points per row: f_max, alpha_p, pull-off (at abscissa alpha_max) */
      size_t m = 3 * (size_t)t->n;
      t->xr = malloc(sizeof(double) * m);
      t->yr = malloc(sizeof(double) * m);
      t->branch = malloc(sizeof(int) * m);
      if (!t->xr || !t->yr || !t->branch) return dem_err_set(err, DEM_ENOMEM, "out of memory");
      for (int k = 0; k < t->n; k++) {
        const double v[3] = {t->y[k], t->z[k], t->w[k]};
        for (int q = 0; q < 3; q++) {
          t->xr[3 * k + q] = t->x[k];
          t->yr[3 * k + q] = v[q];
          t->branch[3 * k + q] = -1 - q;
        }
      }
      t->nres = (int)m;
      t->norm = NAN;
    } else {
      t->xr = malloc(sizeof(double) * (size_t)t->n);
      t->yr = malloc(sizeof(double) * (size_t)t->n);
      if (!t->xr || !t->yr) return dem_err_set(err, DEM_ENOMEM, "out of memory");
      memcpy(t->xr, t->x, sizeof(double) * (size_t)t->n);
      memcpy(t->yr, t->y, sizeof(double) * (size_t)t->n);
      t->nres = t->n;
      t->norm = NAN;
    }
    t->off = off;
    off += t->nres;
  }
  *nres = off;
  return DEM_OK;
}

void cal_residual_norms(const cal_config *c, double *norm) {
  for (int i = 0; i < c->ntargets; i++) {
    const cal_target *t = &c->t[i];
    for (int k = 0; k < t->nres; k++) {
      int pointwise = t->type != CAL_T_CURVE || t->mode == CAL_CURVE_SUMMARY;
      norm[t->off + k] = pointwise ? fabs(t->yr[k]) : t->norm;
    }
  }
}
