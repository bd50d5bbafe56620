#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "dem/scene.h"
#include "dem/engine.h"
int main(int argc, char **argv) {
  dem_err err = {0};
  dem_scene *sc = dem_scene_restore(argv[1], NULL, NULL, &err);
  if (!sc) { fprintf(stderr, "%s\n", err.msg); return 1; }
  double tend = argc > 2 ? atof(argv[2]) : 0.01;
  dem_sim *s = dem_scene_sim(sc);
  dem_sim_set_threads(s, 2, &err);
  dem_particles *p = dem_sim_particles(s);
  dem_scene_info in; dem_scene_get_info(sc, &in);
  double dt = in.dt;
  long per = (long)(2.5e-4 / dt);
  dem_sim_contact *buf = NULL; size_t cap = 0, nc = 0;
  printf("# t[ms] Fbase_up[N] nbase Fdie_z_up Fdie_radial ndie Fpiston W sumfz Mz_com[um] vz_com[um/s] KE[J] gapmin_base[um]\n");
  double z0 = 0, M = 0;
  for (size_t i = 0; i < p->n; i++) { z0 += p->mass[i] * p->x[3*i+2]; M += p->mass[i]; }
  z0 /= M;
  for (int it = 0; it * 2.5e-4 <= tend; it++) {
    if (dem_sim_run(s, it ? per : 0, &err)) { fprintf(stderr, "%s\n", err.msg); return 1; }
    dem_sim_contacts(s, &buf, &cap, &nc, &err);
    double fb = 0, fdz = 0, fdr = 0, fp = 0; size_t nb = 0, nd = 0;
    for (size_t k = 0; k < nc; k++) {
      if (buf[k].wall == 0) fb += buf[k].f[2], nb++;
      if (buf[k].wall == 1) fdz += buf[k].f[2], fdr += hypot(buf[k].f[0], buf[k].f[1]), nd++;
      if (buf[k].wall == 2) fp += buf[k].f[2];
    }
    double sf = 0, zc = 0, vz = 0, gmin = 1e9;
    for (size_t i = 0; i < p->n; i++) {
      sf += p->f[3*i+2]; zc += p->mass[i] * p->x[3*i+2]; vz += p->mass[i] * p->v[3*i+2];
      double g = p->x[3*i+2] - p->radius[i]; if (g < gmin) gmin = g;
    }
    printf("%.3f %.5g %zu %.5g %.5g %zu %.4g %.5g %.5g %.4f %.4g %.4g %.4f\n", it * 0.25, fb, nb, fdz, fdr, nd, fp,
           M * 9.81, sf, (zc / M - z0) * 1e6, vz / M * 1e6, dem_sim_kinetic_energy(s), gmin * 1e6);
  }
  dem_scene_free(sc);
  return 0;
}
