#include <math.h>
#include <stdio.h>
#include "dem/scene.h"
#include "dem/engine.h"
/* After unloading a consolidated bed: how much of its translational kinetic energy is a rigid
 * rotation about the die axis (L_z / I_z)? */
int main(int argc, char **argv) {
  dem_err err = {0};
  dem_scene *sc = dem_scene_restore(argv[1], NULL, NULL, &err);
  if (!sc || dem_scene_unload(sc, &err)) { fprintf(stderr, "%s\n", err.msg); return 1; }
  const dem_particles *p = dem_sim_particles(dem_scene_sim(sc));
  double L = 0, I = 0, ke = 0;
  size_t fast = 0;
  for (size_t i = 0; i < p->n; i++) {
    const double *x = p->x + 3 * i, *v = p->v + 3 * i;
    L += p->mass[i] * (x[0] * v[1] - x[1] * v[0]);
    I += p->mass[i] * (x[0] * x[0] + x[1] * x[1]);
    ke += 0.5 * p->mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    fast += v[0] * v[0] + v[1] * v[1] + v[2] * v[2] >= 1.4e-3 * 1.4e-3;
  }
  double w = L / I;
  printf("n %zu: omega_z %.4g rad/s, rigid-rotation KE %.4g J of translational KE %.4g J (%.1f%%), %.3f of particles >= 1.4 mm/s\n",
         p->n, w, 0.5 * I * w * w, ke, 100 * 0.5 * I * w * w / ke, (double)fast / p->n);
  dem_scene_free(sc);
  return 0;
}
