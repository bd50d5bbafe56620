/* surface_shift BED.h5 R_FOOT_D... : the bed surface under the footprint of radius R_FOOT (in
 * mean diameters d = 1 mm, axis at the die centre) by dem_bed_surface as fixed on 2026-12-01
 * and by the selection it replaced (particles by their own distance to the axis), one line
 * per radius: "r_foot_d z_old_m z_new_m sd_old_m sd_new_m". A one-off tool of the full-tier
 * reanalysis (README.md here); built against libdem:
 *   gcc -O2 -std=c11 -D_POSIX_C_SOURCE=200809L -Ilibdem/include surface_shift.c \
 *       build/lib/libdem.a -L/usr/lib/x86_64-linux-gnu/hdf5/serial -lhdf5_serial \
 *       -lgsl -lgslcblas -fopenmp -lm -o surface_shift */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dem/analysis.h"
#include "dem/engine.h"
#include "dem/scene.h"

/* The selection before the fix: particles whose centres lie within r_foot, binned into
 * columns of one mean diameter of those particles; the mean and sd of the column tops. */
static void old_surface(const dem_particles *p, double r_foot, double *z, double *sd) {
  double rs = 0;
  size_t m = 0;
  for (size_t i = 0; i < p->n; i++)
    if (hypot(p->x[3 * i], p->x[3 * i + 1]) <= r_foot) rs += p->radius[i], m++;
  double cell = 2.0 * rs / (double)m;
  long K = (long)ceil(r_foot / cell), w = 2 * K + 1;
  double *top = malloc((size_t)(w * w) * sizeof *top);
  for (long c = 0; c < w * w; c++) top[c] = -INFINITY;
  for (size_t i = 0; i < p->n; i++) {
    double dx = p->x[3 * i], dy = p->x[3 * i + 1];
    if (dx * dx + dy * dy > r_foot * r_foot) continue;
    long ix = lround(dx / cell) + K, iy = lround(dy / cell) + K;
    if (ix < 0) ix = 0;
    if (iy < 0) iy = 0;
    if (ix >= w) ix = w - 1;
    if (iy >= w) iy = w - 1;
    double t = p->x[3 * i + 2] + p->radius[i];
    if (t > top[iy * w + ix]) top[iy * w + ix] = t;
  }
  double s = 0, s2 = 0;
  size_t nc = 0;
  for (long c = 0; c < w * w; c++)
    if (top[c] > -INFINITY) s += top[c], s2 += top[c] * top[c], nc++;
  *z = s / (double)nc;
  *sd = sqrt(fmax(0.0, (s2 - (double)nc * *z * *z) / (double)(nc - 1)));
  free(top);
}

int main(int argc, char **argv) {
  dem_err e = {0};
  if (argc < 3) return fprintf(stderr, "usage: surface_shift BED.h5 R_FOOT_D...\n"), 2;
  dem_scene *sc = dem_scene_restore(argv[1], NULL, NULL, &e);
  if (!sc) return fprintf(stderr, "%s: %s\n", argv[1], e.msg), 1;
  const dem_particles *p = dem_sim_particles(dem_scene_sim(sc));
  for (int a = 2; a < argc; a++) {
    double rf = atof(argv[a]) * 1e-3, zo, so;
    dem_surface su;
    if (dem_bed_surface(p->n, p->x, p->radius, 0.0, 0.0, rf, 0.0, 90.0, &su, &e))
      return fprintf(stderr, "%s\n", e.msg), 1;
    old_surface(p, rf, &zo, &so);
    printf("%s %.17g %.17g %.17g %.17g\n", argv[a], zo, su.z, so, su.sd);
  }
  dem_scene_free(sc);
  return 0;
}
