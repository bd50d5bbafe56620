/* Stress tensor in measurement volumes (dem/analysis.h; thesis 5.1, A4.2 after Bagi 1996;
 * hydrostatic 5.2 and deviatoric 5.3 parts).
 *
 *   sigma_ij = -(1/V) sum_{p in V} sum_{c of p} (x^c - x^p)_i F^c_j          (5.1, A4.2)
 *
 * (x^c - x^p) is the branch vector from the particle centre to the contact point, written
 * |x^c - x^p| n_i in the thesis, and F^c the force on p at c. With a repulsive contact F^c
 * points from the contact towards the centre, so the sum is negative under compression and
 * the leading minus makes compressive stress positive (the thesis plots positive kPa).
 * Units: m * N / m^3 = Pa.
 */
#include <math.h>
#include <string.h>

#include "dem/analysis.h"

static int in_box(const double *p, const dem_box *b) {
  return p[0] >= b->lo[0] && p[0] < b->hi[0] && p[1] >= b->lo[1] && p[1] < b->hi[1] &&
         p[2] >= b->lo[2] && p[2] < b->hi[2];
}

static int check_view(const dem_contact_view *c, size_t np, const double *x, dem_err *err) {
  if (!c) return dem_err_set(err, DEM_EINVAL, "stress: NULL contact view");
  if (c->n > 0 && (!c->particle || !c->point || !c->force))
    return dem_err_set(err, DEM_EINVAL, "stress: contact view with n = %zu has NULL arrays",
                       c->n);
  if (np > 0 && !x) return dem_err_set(err, DEM_EINVAL, "stress: NULL positions, np = %zu", np);
  for (size_t k = 0; k < c->n; k++)
    if (c->particle[k] >= np)
      return dem_err_set(err, DEM_ERANGE,
                         "stress: contact record %zu: particle = %zu, must be < np = %zu", k,
                         c->particle[k], np);
  return DEM_OK;
}

/* Adds (x^c - x^p) (x) F of record k to s[9]. */
static void add_record(const dem_contact_view *c, const double *x, size_t k, double *s) {
  const double *xp = x + 3 * c->particle[k], *xc = c->point + 3 * k, *f = c->force + 3 * k;
  double br[3] = {xc[0] - xp[0], xc[1] - xp[1], xc[2] - xp[2]};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) s[3 * i + j] += br[i] * f[j];
}

int dem_stress_box(const dem_contact_view *c, size_t np, const double *x, const dem_box *b,
                   double volume, double sigma[9], size_t *nparticles, dem_err *err) {
  int st = check_view(c, np, x, err);
  if (st) return st;
  double V = volume > 0.0 ? volume : dem_box_volume(b);
  if (!(V > 0.0) || !isfinite(V))
    return dem_err_set(err, DEM_ERANGE, "stress: volume = %g m^3, must be > 0", V);
  double s[9] = {0};
  for (size_t k = 0; k < c->n; k++)
    if (in_box(x + 3 * c->particle[k], b)) add_record(c, x, k, s);
  for (int i = 0; i < 9; i++) sigma[i] = -s[i] / V;
  if (nparticles) {
    size_t m = 0;
    for (size_t p = 0; p < np; p++) m += (size_t)in_box(x + 3 * p, b);
    *nparticles = m;
  }
  return DEM_OK;
}

int dem_stress_grid(const dem_contact_view *c, size_t np, const double *x, const dem_grid *g,
                    double *sigma, dem_err *err) {
  int st = check_view(c, np, x, err);
  if (st) return st;
  if (!g || g->nx == 0 || g->ny == 0 || g->nz == 0)
    return dem_err_set(err, DEM_ERANGE, "stress grid: every bin count must be >= 1");
  for (int d = 0; d < 3; d++)
    if (!(g->cell[d] > 0.0) || !isfinite(g->cell[d]) || !isfinite(g->origin[d]))
      return dem_err_set(err, DEM_ERANGE, "stress grid: cell[%d] = %g m, must be > 0", d,
                         g->cell[d]);
  size_t nb = g->nx * g->ny * g->nz;
  memset(sigma, 0, 9 * nb * sizeof *sigma);
  size_t nn[3] = {g->nx, g->ny, g->nz};
  for (size_t k = 0; k < c->n; k++) {
    const double *xp = x + 3 * c->particle[k];
    size_t ijk[3];
    int ok = 1;
    for (int d = 0; d < 3 && ok; d++) {
      double u = floor((xp[d] - g->origin[d]) / g->cell[d]);
      if (!(u >= 0.0 && u < (double)nn[d])) ok = 0;
      else ijk[d] = (size_t)u;
    }
    if (ok) add_record(c, x, k, sigma + 9 * ((ijk[2] * g->ny + ijk[1]) * g->nx + ijk[0]));
  }
  double V = g->cell[0] * g->cell[1] * g->cell[2];
  for (size_t i = 0; i < 9 * nb; i++) sigma[i] = -sigma[i] / V;
  return DEM_OK;
}

double dem_stress_hydrostatic(const double s[9]) { return (s[0] + s[4] + s[8]) / 3.0; }

double dem_stress_deviatoric(const double s[9]) {
  double a = s[0] - s[4], b = s[0] - s[8], c = s[4] - s[8];
  return sqrt((a * a + b * b + c * c) / 6.0);
}

double dem_stress_sqrt_j2(const double s[9]) {
  double a = s[0] - s[4], b = s[0] - s[8], c = s[4] - s[8];
  double xy = 0.5 * (s[1] + s[3]), yz = 0.5 * (s[5] + s[7]), zx = 0.5 * (s[2] + s[6]);
  return sqrt((a * a + b * b + c * c) / 6.0 + xy * xy + yz * yz + zx * zx);
}

double dem_stress_asymmetry(const double s[9]) {
  double n = 0.0, d = 0.0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double t = s[3 * i + j] - s[3 * j + i];
      d += t * t;
      n += s[3 * i + j] * s[3 * i + j];
    }
  return n > 0.0 ? sqrt(d / n) : 0.0;
}
