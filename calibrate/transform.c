/* Scaled optimisation coordinates: u = log10(x) for a log-scale parameter (stiffnesses,
 * surface energy and yield pressure span decades), u = x for a linear one. */
#include <math.h>
#include <stdio.h>

#include "cal.h"

double cal_to_scaled(const cal_free *f, double x) {
  return f->scale == CAL_SCALE_LOG ? log10(x) : x;
}

double cal_from_scaled(const cal_free *f, double u) {
  return f->scale == CAL_SCALE_LOG ? pow(10.0, u) : u;
}

void cal_scaled_bounds(const cal_free *f, double *ulo, double *uhi) {
  *ulo = cal_to_scaled(f, f->lo);
  *uhi = cal_to_scaled(f, f->hi);
}

int cal_params_from_scaled(const cal_config *c, const double *u, double *x, dem_params *ps,
                           dem_err *err) {
  *ps = c->fixed;
  for (int i = 0; i < c->nfree; i++) {
    double lo, hi, ui = u[i];
    cal_scaled_bounds(&c->fr[i], &lo, &hi);
    if (!(ui >= lo)) ui = lo; /* also catches NaN */
    if (ui > hi) ui = hi;
    double xi = cal_from_scaled(&c->fr[i], ui);
    /* pow(10, log10(x)) may land an ulp outside the physical bound. */
    if (xi < c->fr[i].lo) xi = c->fr[i].lo;
    if (xi > c->fr[i].hi) xi = c->fr[i].hi;
    if (x) x[i] = xi;
    int rc = dem_params_set(ps, c->fr[i].name, xi, "free", err);
    if (rc) return rc;
  }
  return DEM_OK;
}
