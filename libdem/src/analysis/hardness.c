/* Hardness of ball indentation, the bed surface under the indenter, and the dimensionless
 * strain rate (dem/analysis.h).
 *
 *   A = pi r_b^2 = pi (D h - h^2)      thesis 2.8-2.9 (spherical cap of height h, base r_b)
 *   H = F / A                          thesis 2.7 (during loading: the current force)
 *   h_d = h / r = 2 h / D              thesis 5.5
 *   gamma* = gamma_dot sqrt(d / g)     thesis 5.4 / 7.1 (Tardos et al.)
 */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

#include "dem/analysis.h"

double dem_indent_area(double D, double h) {
  if (!(D > 0.0) || !(h >= 0.0) || !isfinite(D) || !isfinite(h)) return NAN;
  if (h > 0.5 * D) h = 0.5 * D; /* deeper than the equator: the full circle */
  return M_PI * (D * h - h * h);
}

double dem_hardness(double F, double D, double h) {
  if (!(h > 0.0) || !isfinite(F)) return NAN;
  return F / dem_indent_area(D, h);
}

double dem_hardness_origin_sensitivity(double D, double h) {
  if (!(D > 0.0) || !(h > 0.0) || !isfinite(D) || !isfinite(h)) return NAN;
  if (h >= 0.5 * D) return 0.0;
  return (D - 2.0 * h) / (D * h - h * h);
}

int dem_hardness_curve(size_t n, const double *F, const double *h, double D, double *H,
                       double *hd, dem_err *err) {
  if (!(D > 0.0) || !isfinite(D))
    return dem_err_set(err, DEM_ERANGE, "hardness: indenter diameter D = %g m, must be > 0", D);
  if (n > 0 && (!F || !h || !H))
    return dem_err_set(err, DEM_EINVAL, "hardness: NULL F, h or H array with n = %zu", n);
  for (size_t i = 0; i < n; i++) {
    if (!isfinite(F[i]) || !isfinite(h[i]))
      return dem_err_set(err, DEM_ENONFINITE, "hardness: sample %zu: F = %g N, h = %g m", i,
                         F[i], h[i]);
    H[i] = dem_hardness(F[i], D, h[i]);
    if (hd) hd[i] = 2.0 * h[i] / D;
  }
  return DEM_OK;
}

int dem_bed_surface(size_t n, const double *x, const double *radius, double ax, double ay,
                    double r_foot, double cell, double pct, dem_surface *out, dem_err *err) {
  if (n > 0 && (!x || !radius))
    return dem_err_set(err, DEM_EINVAL, "bed surface: NULL particle arrays with n = %zu", n);
  if (!(r_foot > 0.0) || !isfinite(r_foot))
    return dem_err_set(err, DEM_ERANGE, "bed surface: r_foot = %g m, must be > 0", r_foot);
  if (!(cell >= 0.0) || !isfinite(cell))
    return dem_err_set(err, DEM_ERANGE, "bed surface: cell = %g m, must be >= 0", cell);
  if (!(pct >= 0.0 && pct <= 100.0))
    return dem_err_set(err, DEM_ERANGE, "bed surface: pct = %g, must be in [0, 100]", pct);
  if (!isfinite(ax) || !isfinite(ay))
    return dem_err_set(err, DEM_ENONFINITE, "bed surface: axis (%g, %g) not finite", ax, ay);

  /* The footprint particles and their mean radius. */
  size_t m = 0;
  double rsum = 0.0, zmax = -INFINITY;
  for (size_t i = 0; i < n; i++) {
    double dx = x[3 * i] - ax, dy = x[3 * i + 1] - ay;
    if (dx * dx + dy * dy > r_foot * r_foot) continue;
    if (!isfinite(x[3 * i + 2]) || !isfinite(radius[i]))
      return dem_err_set(err, DEM_ENONFINITE, "bed surface: particle %zu not finite", i);
    m++;
    rsum += radius[i];
    if (x[3 * i + 2] + radius[i] > zmax) zmax = x[3 * i + 2] + radius[i];
  }
  if (m == 0)
    return dem_err_set(err, DEM_EINVAL,
                       "bed surface: no particle centre within r_foot = %g m of the axis "
                       "(%g, %g)", r_foot, ax, ay);
  if (cell == 0.0) cell = 2.0 * rsum / (double)m;
  if (!(cell > 0.0))
    return dem_err_set(err, DEM_ERANGE, "bed surface: zero mean radius and cell = 0");
  double kf = ceil(r_foot / cell);
  if (kf > 1000.0)
    return dem_err_set(err, DEM_ERANGE, "bed surface: cell = %g m is too small for r_foot = "
                       "%g m (more than 2001^2 columns)", cell, r_foot);
  size_t K = (size_t)kf, w = 2 * K + 1;
  double *top = malloc(w * w * sizeof *top);
  if (!top) return dem_err_set(err, DEM_ENOMEM, "bed surface: %zu columns", w * w);
  for (size_t c = 0; c < w * w; c++) top[c] = -INFINITY;
  /* A column belongs to the footprint if its centre lies within r_foot of the axis, and its
   * top is the highest particle whose centre lies anywhere in the column. (Selecting the
   * particles by their own distance instead, as before, made the columns cut by the circle
   * take their top from whichever inner particle was left, possibly many layers down: on
   * the 50 d bed the surface came out 0.4 d low with a spread of 3.3 d instead of 0.3 d.) */
  for (size_t i = 0; i < n; i++) {
    double dx = x[3 * i] - ax, dy = x[3 * i + 1] - ay;
    if (!isfinite(dx) || !isfinite(dy) || fabs(dx) > r_foot + cell || fabs(dy) > r_foot + cell)
      continue;
    long ix = lround(dx / cell) + (long)K, iy = lround(dy / cell) + (long)K;
    if (ix < 0 || iy < 0 || ix >= (long)w || iy >= (long)w) continue;
    double cx = (double)(ix - (long)K) * cell, cy = (double)(iy - (long)K) * cell;
    if (cx * cx + cy * cy > r_foot * r_foot) continue;
    if (!isfinite(x[3 * i + 2]) || !isfinite(radius[i]))
      return dem_err_set(err, DEM_ENONFINITE, "bed surface: particle %zu not finite", i);
    double t = x[3 * i + 2] + radius[i];
    size_t c = (size_t)iy * w + (size_t)ix;
    if (t > top[c]) top[c] = t;
  }
  size_t nc = 0;
  for (size_t c = 0; c < w * w; c++)
    if (top[c] > -INFINITY) top[nc++] = top[c];
  gsl_sort(top, 1, nc);
  out->z = gsl_stats_mean(top, 1, nc);
  out->sd = nc > 1 ? gsl_stats_sd_m(top, 1, nc, out->z) : 0.0;
  out->se = out->sd / sqrt((double)nc);
  out->z_pct = gsl_stats_quantile_from_sorted_data(top, 1, nc, pct / 100.0);
  out->z_max = zmax;
  out->ncol = nc;
  out->nparticles = m;
  free(top);
  return DEM_OK;
}

/* a_c^2 = 2 sum(w rho^2) / sum(w): the load-weighted second moment of a uniform disk is
 * a^2 / 2 (dem/analysis.h, docs/analysis.md section 2b). */
int dem_indent_footprint(size_t n, const double *point, const double *w, double ax, double ay,
                         dem_footprint *out, dem_err *err) {
  if (!out) return dem_err_set(err, DEM_EINVAL, "indent footprint: NULL out");
  out->a = out->rho_max = NAN;
  out->w = 0.0;
  out->n = 0;
  if (n > 0 && (!point || !w))
    return dem_err_set(err, DEM_EINVAL, "indent footprint: NULL point or w array with n = %zu",
                       n);
  if (!isfinite(ax) || !isfinite(ay))
    return dem_err_set(err, DEM_ENONFINITE, "indent footprint: axis (%g, %g) m", ax, ay);
  double sw = 0.0, swr2 = 0.0, rmax = 0.0;
  size_t m = 0;
  for (size_t k = 0; k < n; k++) {
    const double *x = point + 3 * k;
    if (!isfinite(w[k]) || !isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2]))
      return dem_err_set(err, DEM_ENONFINITE,
                         "indent footprint: contact %zu: w = %g N, point (%g, %g, %g) m", k,
                         w[k], x[0], x[1], x[2]);
    if (!(w[k] > 0.0)) continue;
    const double dx = x[0] - ax, dy = x[1] - ay, r2 = dx * dx + dy * dy;
    sw += w[k];
    swr2 += w[k] * r2;
    if (r2 > rmax) rmax = r2;
    m++;
  }
  if (m == 0) return DEM_OK;
  out->a = sqrt(2.0 * swr2 / sw);
  out->rho_max = sqrt(rmax);
  out->w = sw;
  out->n = m;
  return DEM_OK;
}

double dem_gamma_star(double gamma_dot, double d, double g) {
  if (!(d > 0.0) || !(g > 0.0)) return NAN;
  return gamma_dot * sqrt(d / g);
}

double dem_indent_strain_rate(double v, double h_bed) {
  if (!(h_bed > 0.0)) return NAN;
  return fabs(v) / h_bed;
}
