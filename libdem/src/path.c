/* A prescribed overlap path through a contact law (dem/impact.h): load, unload, reload.
 *
 * The path visits the turning points a[0] -> a[1] -> ... -> a[n-1] (m). Each leg is cut into
 * ceil(|a[i+1] - a[i]| / d_alpha) equal steps, so every turning point is hit exactly (points
 * are computed as a[i] + k * step, not accumulated). Quasi-static: alpha_dot = 0, so no
 * damping force. The law is called at every point, in order, on one history block, exactly as
 * a contact in a simulation would see it.
 */
#include <math.h>

#include "dem/impact.h"

#define PATH_MAX_POINTS 100000000L

int dem_contact_path(const dem_contact *ct, const dem_geom *g, const double *turning, int n,
                     double d_alpha, dem_path_row_fn row, void *user, dem_err *err) {
  if (!ct || !ct->law || !g || !turning || !row)
    return dem_err_set(err, DEM_EINVAL, "dem_contact_path: NULL or unset argument");
  if (n < 1)
    return dem_err_set(err, DEM_EINVAL, "overlap path: need at least one turning point, got %d",
                       n);
  if (!isfinite(d_alpha))
    return dem_err_set(err, DEM_ENONFINITE, "overlap path: step d_alpha = %g is not finite",
                       d_alpha);
  if (!(d_alpha > 0.0))
    return dem_err_set(err, DEM_ERANGE, "overlap path: step d_alpha = %g m must be > 0", d_alpha);
  long total = 1;
  for (int i = 0; i < n; i++) {
    if (!isfinite(turning[i]))
      return dem_err_set(err, DEM_ENONFINITE, "overlap path: turning point %d = %g is not finite",
                         i, turning[i]);
    if (fabs(turning[i]) > g->R)
      return dem_err_set(err, DEM_ERANGE,
                         "overlap path: turning point %d = %g m is beyond R* = %g m in size", i,
                         turning[i], g->R);
    if (i > 0) {
      double legs = ceil(fabs(turning[i] - turning[i - 1]) / d_alpha);
      if (legs > (double)PATH_MAX_POINTS || (total += (long)legs) > PATH_MAX_POINTS)
        return dem_err_set(err, DEM_ERANGE,
                           "overlap path: step d_alpha = %g m gives more than %ld points "
                           "(allowed); use a larger step",
                           d_alpha, PATH_MAX_POINTS);
    }
  }
  double hist[DEM_LAW_NHIST_MAX];
  int rc = dem_contact_init(ct, g, hist, err);
  if (rc) return rc;
  dem_normal out;
  dem_contact_force(ct, g, hist, turning[0], 0.0, &out);
  row(turning[0], &out, user);
  for (int i = 1; i < n; i++) {
    double a0 = turning[i - 1], a1 = turning[i];
    long legs = (long)ceil(fabs(a1 - a0) / d_alpha);
    for (long k = 1; k <= legs; k++) {
      double a = (k == legs) ? a1 : a0 + (a1 - a0) * ((double)k / (double)legs);
      dem_contact_force(ct, g, hist, a, 0.0, &out);
      row(a, &out, user);
    }
  }
  return DEM_OK;
}
