/* Solids fraction against depth in a cylinder on the die axis of a saved bed (an analysis
 * aid for docs/validation.md, "Case 2 with chapter 5's materials complete"; not part of the
 * suite). Usage: phiprof BED.h5 [RC_D [SURFACE_M]]: slabs of 1 d downward from SURFACE_M
 * (default: the highest particle top), cylinder radius RC_D mean diameters (default 8),
 * centred on the particles' mean x, y. A particle counts if its centre is inside the
 * cylinder; its volume between two horizontal planes is the spherical segment.
 * Build (from the repository root, after the Release build):
 *   gcc -O2 -std=gnu11 -fopenmp -Ilibdem/include docs/validation/full-hertz-jkr-bh/phiprof.c \
 *       -o phiprof build/lib/libdem.a -I/usr/include/hdf5/serial \
 *       -L/usr/lib/x86_64-linux-gnu/hdf5/serial -lhdf5 -lgsl -lgslcblas -lm */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "dem/checkpoint.h"
#include "dem/engine.h"
static double seg(double r, double zc, double a, double b) { /* sphere volume in a<z<b */
  double lo = fmax(a, zc - r), hi = fmin(b, zc + r);
  if (hi <= lo) return 0;
  double u0 = lo - zc, u1 = hi - zc;
  return M_PI * ((r * r * u1 - u1 * u1 * u1 / 3) - (r * r * u0 - u0 * u0 * u0 / 3));
}
int main(int argc, char **argv) {
  dem_err err;
  double rc_d = argc > 2 ? atof(argv[2]) : 8; double surf = argc > 3 ? atof(argv[3]) : 0;
  dem_sim *s = dem_sim_checkpoint_read(argv[1], NULL, NULL, &err);
  if (!s) { fprintf(stderr, "read failed\n"); return 1; }
  dem_particles *p = dem_sim_particles(s);
  double cx = 0, cy = 0, rm = 0, zmax = 0;
  for (size_t i = 0; i < p->n; i++) { cx += p->x[3*i]; cy += p->x[3*i+1]; rm += p->radius[i];
    if (p->x[3*i+2] + p->radius[i] > zmax) zmax = p->x[3*i+2] + p->radius[i]; }
  cx /= p->n; cy /= p->n; rm /= p->n;
  double d = 2 * rm, Rc = rc_d * d;
  if (surf > 0) zmax = surf;
  /* slabs of 1 d measured downward from the top (zmax) */
  int ns = (int)(zmax / d);
  double *v = calloc(ns, sizeof *v);
  for (size_t i = 0; i < p->n; i++) {
    double dx = p->x[3*i] - cx, dy = p->x[3*i+1] - cy;
    if (dx*dx + dy*dy > Rc*Rc) continue;
    for (int k = 0; k < ns; k++) {
      double b = zmax - k * d, a = b - d;
      v[k] += seg(p->radius[i], p->x[3*i+2], a, b);
    }
  }
  printf("# %s n %zu d %.4g mm top %.2f d Rc %.1f d\n# depth_from_top[d] phi\n", argv[1], p->n, d*1e3, zmax/d, rc_d);
  for (int k = 0; k < ns; k++) printf("%5.1f %.4f\n", k + 0.5, v[k] / (M_PI * Rc * Rc * d));
  dem_sim_free(s);
  return 0;
}
