/* The simulation handle: creation, materials, interactions, settings, accessors. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

void dem_breakdown_defaults(dem_breakdown *b) {
  b->max_overlap_frac = 0.25;
  b->check_interval = 100;
  b->ke_growth = 1.0;
  b->ke_strikes = 10;
  b->ke_floor = 0.0;
}

dem_sim *dem_sim_create(dem_err *err) {
  dem_sim *s = calloc(1, sizeof *s);
  if (!s) {
    dem_err_set(err, DEM_ENOMEM, "dem_sim_create: out of memory");
    return NULL;
  }
  s->nthreads = 1;
  s->sort_every = 10;
  s->need_build = 1;
  s->need_forces = 1;
  s->last_good = -1;
  dem_breakdown_defaults(&s->bd);
  return s;
}

void dem_sim_free(dem_sim *s) {
  if (!s) return;
  dem_particles *p = &s->p;
  free(p->x);
  free(p->v);
  free(p->omega);
  free(p->f);
  free(p->torque);
  free(p->radius);
  free(p->mass);
  free(p->inertia);
  free(p->material);
  free(p->id);
  free(s->x0);
  free(s->invr);
  free(s->invm);
  free(s->invI);
  for (int w = 0; w < s->nwall; w++) {
    free(s->wall[w].hist);
    free(s->wall[w].list);
  }
  dem_nlist_free(&s->nl);
  dem_nlist_free(&s->nl_old);
  free(s->cell_first);
  free(s->cell_idx);
  free(s->cell_of);
  free(s->perm);
  free(s->iperm);
  free(s->tmp);
  for (int t = 0; t < DEM_MAX_THREADS; t++) {
    free(s->td[t].spill);
    free(s->td[t].cand);
  }
  free(s);
}

int dem_sim_add_material(dem_sim *s, double rho, int *index, dem_err *err) {
  if (s->nmat >= DEM_ENGINE_MAX_MATERIALS)
    return dem_err_set(err, DEM_ERANGE, "materials: at most %d allowed",
                       DEM_ENGINE_MAX_MATERIALS);
  if (!(rho > 0.0 && isfinite(rho)))
    return dem_err_set(err, DEM_ERANGE, "material rho = %g kg/m^3 (allowed: > 0, finite)", rho);
  s->rho[s->nmat] = rho;
  if (index) *index = s->nmat;
  s->nmat++;
  return DEM_OK;
}

int dem_sim_set_interaction(dem_sim *s, int a, int b, const dem_contact *normal,
                            const dem_tangential *t, const dem_rolling *r, dem_err *err) {
  if (a < 0 || a >= s->nmat || b < 0 || b >= s->nmat)
    return dem_err_set(err, DEM_ERANGE, "interaction (%d, %d): material index outside [0, %d)",
                       a, b, s->nmat);
  if (!normal || !normal->law)
    return dem_err_set(err, DEM_EINVAL, "interaction (%d, %d): no normal law", a, b);
  if (s->nh > 0 && normal->law->nhist > s->hoff)
    return dem_err_set(err, DEM_EUNSUPPORTED,
                       "interaction (%d, %d): law '%s' needs %d history doubles but the "
                       "histories were laid out for %d at the first step; set every "
                       "interaction before running",
                       a, b, normal->law->name, normal->law->nhist, s->hoff);
  if (r && !(r->mu_r >= 0.0 && isfinite(r->mu_r)))
    return dem_err_set(err, DEM_ERANGE, "interaction (%d, %d): mu_r = %g (allowed >= 0)", a, b,
                       r->mu_r);
  dem_inter in;
  memset(&in, 0, sizeof in);
  in.set = 1;
  in.normal = *normal;
  if (t) in.tang = *t;
  else in.tang.kind = DEM_TANGENTIAL_NONE;
  if (r) in.roll = *r;
  dem_engine_inter_compile(&in);
  s->inter[a][b] = in;
  s->inter[b][a] = in;
  return DEM_OK;
}

dem_particles *dem_sim_particles(dem_sim *s) { return &s->p; }

void dem_sim_invalidate(dem_sim *s) {
  s->need_build = 1;
  s->need_forces = 1;
}

int dem_sim_set_dt(dem_sim *s, double dt, dem_err *err) {
  if (!(dt > 0.0 && isfinite(dt)))
    return dem_err_set(err, DEM_ERANGE, "dt = %g s (allowed: > 0, finite)", dt);
  if (dt != s->dt) { /* the clock goes on from here with the new step */
    s->t_base = s->st.time;
    s->steps_base = s->st.steps;
  }
  s->dt = dt;
  return DEM_OK;
}

void dem_sim_set_gravity(dem_sim *s, const double g[3]) {
  for (int k = 0; k < 3; k++) s->g[k] = g[k];
  s->need_forces = 1; /* the stored forces include the old gravity */
}

int dem_sim_set_skin(dem_sim *s, double skin, dem_err *err) {
  if (!(skin >= 0.0 && isfinite(skin)))
    return dem_err_set(err, DEM_ERANGE, "skin = %g m (allowed: >= 0, finite)", skin);
  s->skin = skin;
  s->need_build = 1;
  return DEM_OK;
}

int dem_sim_set_threads(dem_sim *s, int nthreads, dem_err *err) {
  if (nthreads < 1 || nthreads > DEM_MAX_THREADS)
    return dem_err_set(err, DEM_ERANGE, "threads = %d (allowed [1, %d])", nthreads,
                       DEM_MAX_THREADS);
#ifndef _OPENMP
  if (nthreads > 1)
    return dem_err_set(err, DEM_EUNSUPPORTED, "threads = %d: libdem was built without OpenMP",
                       nthreads);
#endif
  if (nthreads == s->nthreads) return DEM_OK; /* keeps a restored neighbour list */
  s->nthreads = nthreads;
  s->need_build = 1; /* re-partition rows and spill buffers */
  return DEM_OK;
}

void dem_sim_set_sort_interval(dem_sim *s, int every) { s->sort_every = every < 0 ? 0 : every; }

int dem_sim_set_breakdown(dem_sim *s, const dem_breakdown *b, dem_err *err) {
  if (!b) {
    dem_breakdown_defaults(&s->bd);
    return DEM_OK;
  }
  if (!(b->max_overlap_frac > 0.0))
    return dem_err_set(err, DEM_ERANGE, "breakdown max_overlap_frac = %g (allowed > 0)",
                       b->max_overlap_frac);
  if (b->check_interval < 1)
    return dem_err_set(err, DEM_ERANGE, "breakdown check_interval = %d (allowed >= 1)",
                       b->check_interval);
  if (!(b->ke_growth > 0.0) || b->ke_strikes < 1 || !(b->ke_floor >= 0.0))
    return dem_err_set(err, DEM_ERANGE,
                       "breakdown ke_growth = %g (> 0), ke_strikes = %d (>= 1), ke_floor = %g "
                       "(>= 0)",
                       b->ke_growth, b->ke_strikes, b->ke_floor);
  s->bd = *b;
  return DEM_OK;
}

int dem_sim_history_size(const dem_sim *s) { return s->nh; }

void dem_sim_get_stats(const dem_sim *s, dem_sim_stats *st) {
  *st = s->st;
  st->pairs = s->nl.npairs;
  st->bytes = dem_engine_bytes(s);
}

double dem_sim_kinetic_energy(const dem_sim *s) {
  const dem_particles *p = &s->p;
  double ke = 0.0;
  for (size_t i = 0; i < p->n; i++) {
    const double *v = p->v + 3 * i, *w = p->omega + 3 * i;
    ke += 0.5 * p->mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) +
          0.5 * p->inertia[i] * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  }
  return ke;
}

size_t dem_engine_bytes(const dem_sim *s) {
  size_t b = s->cap * (3 * 5 * sizeof(double) + 3 * sizeof(double) + 3 * sizeof(double) +
                       sizeof(int) + 4 * sizeof(uint32_t) + 3 * sizeof(double));
  b += (size_t)s->nwall * s->cap * (size_t)s->nh * sizeof(double);
  const dem_nlist *ls[2] = {&s->nl, &s->nl_old};
  for (int k = 0; k < 2; k++)
    b += (ls[k]->cap_rows + 1) * sizeof(uint32_t) +
         ls[k]->cap_pairs * (sizeof(uint32_t) + (size_t)s->nh * sizeof(double));
  b += (s->ncell_cap + 1) * sizeof(uint32_t);
  for (int t = 0; t < DEM_MAX_THREADS; t++)
    b += s->td[t].cap_spill * sizeof(dem_spill) + s->td[t].cap_cand * sizeof(uint32_t);
  for (int w = 0; w < s->nwall; w++) b += s->wall[w].cap_list * sizeof(uint32_t);
  return b;
}

size_t dem_sim_neighbour_pairs(const dem_sim *s, uint32_t *pairs, size_t cap) {
  const dem_nlist *l = &s->nl;
  size_t k = 0;
  for (size_t i = 0; i < l->n; i++)
    for (uint32_t q = l->first[i]; q < l->first[i + 1]; q++, k++)
      if (k < cap) {
        pairs[2 * k] = (uint32_t)i;
        pairs[2 * k + 1] = l->nbr[q];
      }
  return l->npairs;
}

double *dem_sim_pair_history(dem_sim *s, size_t i, size_t j) {
  if (i > j) {
    size_t t = i;
    i = j;
    j = t;
  }
  const dem_nlist *l = &s->nl;
  if (i >= l->n || s->nh == 0) return NULL;
  for (uint32_t q = l->first[i]; q < l->first[i + 1]; q++)
    if (l->nbr[q] == j) return l->hist + (size_t)q * s->nh;
  return NULL;
}

double *dem_sim_wall_history(dem_sim *s, size_t i, int wall) {
  if (wall < 0 || wall >= s->nwall || i >= s->p.n || s->nh == 0 || !s->wall[wall].hist)
    return NULL;
  return s->wall[wall].hist + i * (size_t)s->nh;
}
