/* Particle storage: growth, insertion and spatial permutation of the struct of arrays. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dem/material.h"
#include "internal.h"

static int grow_array(void **a, size_t elem, size_t cap) {
  void *q = realloc(*a, elem * (cap ? cap : 1));
  if (!q) return 0;
  *a = q;
  return 1;
}

int dem_engine_grow(dem_sim *s, size_t cap, dem_err *err) {
  if (cap <= s->cap) return DEM_OK;
  if (cap > UINT32_MAX - 1)
    return dem_err_set(err, DEM_ERANGE, "particles: %zu requested, at most %u", cap,
                       (unsigned)(UINT32_MAX - 1));
  dem_particles *p = &s->p;
  int ok = grow_array((void **)&p->x, 3 * sizeof(double), cap) &&
           grow_array((void **)&p->v, 3 * sizeof(double), cap) &&
           grow_array((void **)&p->omega, 3 * sizeof(double), cap) &&
           grow_array((void **)&p->f, 3 * sizeof(double), cap) &&
           grow_array((void **)&p->torque, 3 * sizeof(double), cap) &&
           grow_array((void **)&p->radius, sizeof(double), cap) &&
           grow_array((void **)&p->mass, sizeof(double), cap) &&
           grow_array((void **)&p->inertia, sizeof(double), cap) &&
           grow_array((void **)&p->material, sizeof(int), cap) &&
           grow_array((void **)&p->id, sizeof(uint32_t), cap) &&
           grow_array((void **)&s->x0, 3 * sizeof(double), cap) &&
           grow_array((void **)&s->invr, sizeof(double), cap) &&
           grow_array((void **)&s->invm, sizeof(double), cap) &&
           grow_array((void **)&s->invI, sizeof(double), cap) &&
           grow_array((void **)&s->cell_idx, sizeof(uint32_t), cap) &&
           grow_array((void **)&s->cell_of, sizeof(uint32_t), cap) &&
           grow_array((void **)&s->perm, sizeof(uint32_t), cap) &&
           grow_array((void **)&s->iperm, sizeof(uint32_t), cap) &&
           grow_array(&s->tmp, 3 * sizeof(double), cap);
  for (int w = 0; ok && w < s->nwall; w++)
    if (s->nh > 0) {
      ok = grow_array((void **)&s->wall[w].hist, (size_t)s->nh * sizeof(double), cap);
      if (ok)
        memset(s->wall[w].hist + s->cap * s->nh, 0, (cap - s->cap) * s->nh * sizeof(double));
    }
  if (!ok) return dem_err_set(err, DEM_ENOMEM, "particles: out of memory for %zu", cap);
  s->cap = cap;
  return DEM_OK;
}

int dem_sim_reserve(dem_sim *s, size_t n, dem_err *err) { return dem_engine_grow(s, n, err); }

int dem_sim_add_particle(dem_sim *s, const double x[3], const double v[3], double radius,
                         int material, dem_err *err) {
  if (material < 0 || material >= s->nmat)
    return dem_err_set(err, DEM_ERANGE, "particle %zu: material %d outside [0, %d)", s->p.n,
                       material, s->nmat);
  if (!(radius > 0.0 && isfinite(radius)))
    return dem_err_set(err, DEM_ERANGE, "particle %zu: radius = %g m (allowed: > 0)", s->p.n,
                       radius);
  for (int k = 0; k < 3; k++)
    if (!isfinite(x[k]) || (v && !isfinite(v[k])))
      return dem_err_set(err, DEM_ENONFINITE, "particle %zu: non-finite position or velocity",
                         s->p.n);
  if (s->p.n == s->cap) {
    int rc = dem_engine_grow(s, s->cap ? 2 * s->cap : 64, err);
    if (rc) return rc;
  }
  dem_particles *p = &s->p;
  size_t i = p->n;
  for (int k = 0; k < 3; k++) {
    p->x[3 * i + k] = x[k];
    p->v[3 * i + k] = v ? v[k] : 0.0;
    p->omega[3 * i + k] = 0.0;
    p->f[3 * i + k] = 0.0;
    p->torque[3 * i + k] = 0.0;
  }
  p->radius[i] = radius;
  p->mass[i] = dem_sphere_mass(radius, s->rho[material]);
  p->inertia[i] = 0.4 * p->mass[i] * radius * radius;
  p->material[i] = material;
  p->id[i] = (uint32_t)i;
  for (int w = 0; w < s->nwall; w++)
    if (s->wall[w].hist) memset(s->wall[w].hist + i * s->nh, 0, s->nh * sizeof(double));
  p->n++;
  s->need_build = 1;
  s->need_forces = 1;
  return DEM_OK;
}

/* new[k] = old[perm[k]] for an array of `width` elements of `elem` bytes per particle. */
static void permute_array(void *a, void *tmp, size_t n, size_t width, const uint32_t *perm) {
  char *src = a, *dst = tmp;
  for (size_t k = 0; k < n; k++) memcpy(dst + k * width, src + (size_t)perm[k] * width, width);
  memcpy(a, tmp, n * width);
}

void dem_engine_permute(dem_sim *s, const uint32_t *perm) {
  dem_particles *p = &s->p;
  size_t n = p->n, v3 = 3 * sizeof(double);
  permute_array(p->x, s->tmp, n, v3, perm);
  permute_array(p->v, s->tmp, n, v3, perm);
  permute_array(p->omega, s->tmp, n, v3, perm);
  permute_array(p->f, s->tmp, n, v3, perm);
  permute_array(p->torque, s->tmp, n, v3, perm);
  permute_array(s->x0, s->tmp, n, v3, perm);
  permute_array(p->radius, s->tmp, n, sizeof(double), perm);
  permute_array(p->mass, s->tmp, n, sizeof(double), perm);
  permute_array(p->inertia, s->tmp, n, sizeof(double), perm);
  permute_array(p->material, s->tmp, n, sizeof(int), perm);
  permute_array(p->id, s->tmp, n, sizeof(uint32_t), perm);
  /* A wall history block may be wider than tmp's 3 doubles per particle: go in chunks. */
  for (int w = 0; w < s->nwall; w++) {
    double *h = s->wall[w].hist;
    if (!h) continue;
    for (int c = 0; c < s->nh; c += 3) {
      int wdt = s->nh - c < 3 ? s->nh - c : 3;
      double *t = s->tmp;
      for (size_t k = 0; k < n; k++)
        for (int q = 0; q < wdt; q++) t[3 * k + q] = h[(size_t)perm[k] * s->nh + c + q];
      for (size_t k = 0; k < n; k++)
        for (int q = 0; q < wdt; q++) h[k * s->nh + c + q] = t[3 * k + q];
    }
  }
}
