/* stages BED.h5...: per stage of a prepared bed's time series (0 settle, 1 consolidate,
 * 2 unload), its start and end time (s) and the largest and last piston stress (Pa): the
 * numbers of docs/validation.md, "Time step 0.4 at thesis scale, and the servo".
 * Build (from the source tree, after the Release build):
 *   cc -O2 -std=c11 -Ilibdem/include stages.c -o stages build/lib/libdem.a \
 *      -L/usr/lib/x86_64-linux-gnu/hdf5/serial -lhdf5 -lgsl -lgslcblas -ljansson -lm -fopenmp */
#include <stdio.h>
#include <math.h>
#include "dem/scene.h"
#include "dem/table.h"
int main(int argc, char **argv) {
  for (int a = 1; a < argc; a++) {
    dem_err err = {0};
    dem_scene *sc = dem_scene_restore(argv[a], NULL, NULL, &err);
    if (!sc) { fprintf(stderr, "%s: %s\n", argv[a], err.msg); return 1; }
    const dem_table *t = dem_scene_series(sc);
    long n = dem_table_nrows(t);
    dem_scene_info in; dem_scene_get_info(sc, &in);
    printf("%s: %ld rows\n", argv[a], n);
    int st = -1; double t0 = 0, pmax = 0;
    for (long r = 0; r <= n; r++) {
      int s = r < n ? (int)dem_table_get(t, r, 1) : -2;
      double tt = r < n ? dem_table_get(t, r, 0) : NAN;
      if (s != st) {
        if (st >= 0) printf("  stage %d: %.5f - %.5f s (%.5f s), piston stress max %.0f Pa, last %.0f Pa\n", st, t0, dem_table_get(t, r - 1, 0), dem_table_get(t, r - 1, 0) - t0, pmax, dem_table_get(t, r - 1, 3));
        st = s; t0 = tt; pmax = 0;
      }
      if (r < n) pmax = fmax(pmax, dem_table_get(t, r, 3));
    }
    dem_scene_free(sc);
  }
  return 0;
}
