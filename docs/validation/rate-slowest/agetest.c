/* A bed left to age before it is indented (an analysis aid for docs/validation.md, "The
 * slowest rate of case 10 on more beds"; not part of the suite). Usage:
 *   agetest BED.h5 HOLD_S OUT.csv
 * restores the unloaded bed BED.h5 (dem-run's checkpoint_unloaded.h5), runs it without the
 * indenter for HOLD_S seconds, printing every 1 ms the kinetic energy, the centre-of-mass
 * drift and the mean drift of the top 2 d of particles within 4 d of the axis, then indents
 * it as the bed's own configuration says (its strain_rate) and writes the series to OUT.csv.
 * Build (from the repository root, after the Release build):
 *   gcc -O2 -std=gnu11 -fopenmp -Ilibdem/include docs/validation/rate-slowest/agetest.c \
 *       -o agetest build/lib/libdem.a -I/usr/include/hdf5/serial \
 *       -L/usr/lib/x86_64-linux-gnu/hdf5/serial -lhdf5 -lgsl -lgslcblas -lm */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "dem/engine.h"
#include "dem/scene.h"
#include "dem/table.h"
int main(int argc, char **argv) {
  if (argc < 4) { fprintf(stderr, "usage: agetest BED.h5 HOLD_S OUT.csv\n"); return 2; }
  dem_err err = {0};
  dem_scene *sc = dem_scene_restore(argv[1], NULL, NULL, &err);
  if (!sc) { fprintf(stderr, "%s\n", err.msg); return 1; }
  double hold = atof(argv[2]);
  dem_sim *s = dem_scene_sim(sc);
  if (dem_sim_set_threads(s, 2, &err)) { fprintf(stderr, "%s\n", err.msg); return 1; }
  dem_particles *p = dem_sim_particles(s);
  dem_scene_info in; dem_scene_get_info(sc, &in);
  const double d = in.mean_d, top = in.bed_top;
  size_t *sel = malloc(p->n * sizeof *sel), ns = 0;
  double M = 0, z0 = 0, zt0 = 0;
  for (size_t i = 0; i < p->n; i++) {
    M += p->mass[i]; z0 += p->mass[i] * p->x[3 * i + 2];
    if (hypot(p->x[3 * i], p->x[3 * i + 1]) < 4 * d && p->x[3 * i + 2] > top - 2 * d)
      sel[ns++] = i, zt0 += p->x[3 * i + 2];
  }
  z0 /= M; zt0 /= (double)ns;
  long per = lround(1e-3 / in.dt);
  printf("# bed_top %.6g m, %zu particles in the top 2 d within 4 d of the axis, dt %.4g s\n",
         top, ns, in.dt);
  printf("# t_hold[ms] KE[J] dz_com[um] dz_top[um]\n");
  for (int k = 0; k * 1e-3 <= hold + 1e-12; k++) {
    if (k && dem_sim_run(s, per, &err)) { fprintf(stderr, "%s\n", err.msg); return 1; }
    double zc = 0, zt = 0;
    for (size_t i = 0; i < p->n; i++) zc += p->mass[i] * p->x[3 * i + 2];
    for (size_t j = 0; j < ns; j++) zt += p->x[3 * sel[j] + 2];
    printf("%d %.4g %.4f %.4f\n", k, dem_sim_kinetic_energy(s), (zc / M - z0) * 1e6,
           (zt / (double)ns - zt0) * 1e6);
  }
  fflush(stdout);
  if (dem_scene_indent(sc, &err)) { fprintf(stderr, "%s\n", err.msg); return 1; }
  if (dem_table_write(dem_scene_series(sc), argv[3], &err)) { fprintf(stderr, "%s\n", err.msg); return 1; }
  free(sel);
  dem_scene_free(sc);
  return 0;
}
