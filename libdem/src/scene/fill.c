/* Scene: the size distributions (thesis Tables 5.1 and 6.1) and the random fill of the die.
 *
 * Fill: random sequential insertion without overlap. Diameters are drawn from the discrete
 * number distribution of the table (the thesis' Gaussian, as tabulated: its bins are the
 * sizes generated) with a seeded GSL mt19937 generator; the particles are then inserted
 * largest first (so that insertion succeeds at a fixed number of attempts) at uniformly
 * random positions in a cylinder of the die's radius minus the particle radius (no wall
 * overlap), of a height chosen so that the particles fill fill_fraction of it. Positions
 * are uniform over the whole volume whatever the insertion order, so sizes are not
 * stratified. A cell grid of side d_max finds the candidates for overlap.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "scene_internal.h"

/* Table 5.1 (thesis p. 135): diameters (mm for d = 1 mm) and number frequency (%). */
static const double t51_d[9] = {0.59, 0.72, 0.81, 0.90, 1.00, 1.10, 1.19, 1.28, 1.41};
static const double t51_f[9] = {0.0033, 0.0384, 0.1124, 0.2100, 0.2775,
                                0.2085, 0.1095, 0.0374, 0.0029};
/* Table 6.1 (thesis p. 159), the seven bins (the two trailing rows of the printed table
 * repeat Table 5.1: reference_data/pasha2013_ch6_indentation/SOURCE.md). */
static const double t61_d[7] = {0.724, 0.814, 0.896, 1.000, 1.104, 1.188, 1.278};
static const double t61_f[7] = {0.0387, 0.1131, 0.2114, 0.2792, 0.2099, 0.1102, 0.0376};

int dem_scene_psd_table(dem_scene_psd psd, const double **dd, const double **frac) {
  if (psd == DEM_SCENE_PSD_T51) {
    *dd = t51_d;
    *frac = t51_f;
    return 9;
  }
  *dd = t61_d;
  *frac = t61_f;
  return 7;
}

void scene_psd_moments(dem_scene_psd psd, double d_mean, double *mean, double *sd) {
  const double *dd, *fr;
  int n = dem_scene_psd_table(psd, &dd, &fr);
  double s = 0, s1 = 0, s2 = 0;
  for (int k = 0; k < n; k++) s += fr[k], s1 += fr[k] * dd[k], s2 += fr[k] * dd[k] * dd[k];
  double m = s1 / s;
  *mean = m * d_mean;
  *sd = sqrt(fmax(s2 / s - m * m, 0.0)) * d_mean;
}

static int cmp_desc(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x < y) - (x > y);
}

int scene_fill(dem_scene *sc, dem_err *err) {
  const dem_scene_config *c = &sc->cfg;
  const double *dd, *fr;
  int nb = dem_scene_psd_table(c->psd, &dd, &fr);
  double fsum = 0.0, v3 = 0.0;
  for (int k = 0; k < nb; k++) fsum += fr[k], v3 += fr[k] * dd[k] * dd[k] * dd[k];
  v3 /= fsum; /* <d^3> in units of d_mean^3 */
  const double d = c->d_mean, Rd = sc->die_radius;
  const double vmean = M_PI / 6.0 * v3 * d * d * d;
  long n = c->n_particles;
  if (n <= 0) n = lround(c->phi_est * M_PI * Rd * Rd * c->bed_height * d / vmean);
  if (n < 1) return dem_err_set(err, DEM_ERANGE, "scene: the bed holds no particle");
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  double *diam = malloc((size_t)n * sizeof *diam);
  if (!rng || !diam) {
    gsl_rng_free(rng);
    free(diam);
    return dem_err_set(err, DEM_ENOMEM, "scene fill: out of memory");
  }
  gsl_rng_set(rng, c->seed);
  for (long i = 0; i < n; i++) {
    double u = gsl_rng_uniform(rng) * fsum, acc = 0.0;
    int k = 0;
    for (; k < nb - 1; k++) {
      acc += fr[k];
      if (u < acc) break;
    }
    diam[i] = dd[k] * d;
  }
  double m1 = 0, m2 = 0;
  for (long i = 0; i < n; i++) m1 += diam[i], m2 += diam[i] * diam[i];
  sc->mean_d = m1 / (double)n;
  sc->sd_d = n > 1 ? sqrt(fmax((m2 - m1 * m1 / (double)n) / (double)(n - 1), 0.0)) : 0.0;
  qsort(diam, (size_t)n, sizeof *diam, cmp_desc);
  const double dmax = diam[0];
  const double H = (double)n * vmean / (c->fill_fraction * M_PI * Rd * Rd);
  sc->fill_top = H;
  /* cell grid over [-Rd, Rd]^2 x [0, H] */
  const double cs = dmax;
  const int nx = (int)ceil(2.0 * Rd / cs) + 1, nz = (int)ceil(H / cs) + 1;
  const size_t ncell = (size_t)nx * (size_t)nx * (size_t)nz;
  long *head = malloc(ncell * sizeof *head), *next = malloc((size_t)n * sizeof *next);
  double *pos = malloc((size_t)n * 3 * sizeof *pos);
  int rc = DEM_OK;
  if (!head || !next || !pos) {
    rc = dem_err_set(err, DEM_ENOMEM, "scene fill: out of memory");
    goto out;
  }
  for (size_t k = 0; k < ncell; k++) head[k] = -1;
  for (long i = 0; i < n; i++) {
    const double r = 0.5 * diam[i];
    const double ra = Rd - r, zlo = r, zhi = H - r;
    int ok = 0;
    for (int att = 0; att < 20000 && !ok; att++) {
      double x, y;
      do {
        x = (2.0 * gsl_rng_uniform(rng) - 1.0) * ra;
        y = (2.0 * gsl_rng_uniform(rng) - 1.0) * ra;
      } while (x * x + y * y > ra * ra);
      double z = zlo + gsl_rng_uniform(rng) * (zhi > zlo ? zhi - zlo : 0.0);
      int cx = (int)((x + Rd) / cs), cy = (int)((y + Rd) / cs), cz = (int)(z / cs);
      ok = 1;
      for (int a = cx - 1; a <= cx + 1 && ok; a++)
        for (int b = cy - 1; b <= cy + 1 && ok; b++)
          for (int e = cz - 1; e <= cz + 1 && ok; e++) {
            if (a < 0 || b < 0 || e < 0 || a >= nx || b >= nx || e >= nz) continue;
            for (long j = head[((size_t)e * nx + b) * nx + a]; j >= 0; j = next[j]) {
              double dx = x - pos[3 * j], dy = y - pos[3 * j + 1], dz = z - pos[3 * j + 2];
              double rr = r + 0.5 * diam[j];
              if (dx * dx + dy * dy + dz * dz < rr * rr) {
                ok = 0;
                break;
              }
            }
          }
      if (ok) {
        pos[3 * i] = x, pos[3 * i + 1] = y, pos[3 * i + 2] = z;
        size_t cell = ((size_t)cz * nx + cy) * nx + cx;
        next[i] = head[cell];
        head[cell] = i;
      }
    }
    if (!ok) {
      rc = dem_err_set(err, DEM_EPHYSICS,
                       "scene fill: no room for particle %ld of %ld after 20000 attempts; "
                       "lower fill_fraction = %g (allowed [0.01, 0.38])",
                       i + 1, n, c->fill_fraction);
      goto out;
    }
  }
  if ((rc = dem_sim_reserve(sc->sim, (size_t)n, err))) goto out;
  for (long i = 0; i < n; i++)
    if ((rc = dem_sim_add_particle(sc->sim, pos + 3 * i, NULL, 0.5 * diam[i], sc->mat_p, err)))
      goto out;
out:
  gsl_rng_free(rng);
  free(diam);
  free(head);
  free(next);
  free(pos);
  return rc;
}
