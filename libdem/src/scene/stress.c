/* Stresses of the bed (thesis 5.1-5.3, App. IV, Figs 5.8 / 5.13 / 5.18): the contact view
 * of the scene, the stress columns of the time series and the static bins.
 *
 * The contact view is built from the engine's export (dem_sim_contacts, read-only
 * re-evaluation of the last force evaluation): a particle pair becomes two records (the
 * contact point shared, opposite forces), a wall contact one. Bins follow the thesis' size,
 * 5.2 x 5.2 x 4.2 mm for d = 1 mm, scaled with d_mean (the thesis' bins are about 5 x 5 x 4
 * particle diameters). The die axis is z through the origin, the base z = 0 (scene.c).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene_internal.h"

/* The bin size of Figs 5.8 / 5.13 / 5.18 scaled with d_mean (m). */
static void bin_size(const dem_scene *sc, double size[3]) {
  const double s = sc->cfg.d_mean / 1e-3;
  size[0] = DEM_BIN_DX * s;
  size[1] = DEM_BIN_DY * s;
  size[2] = DEM_BIN_DZ * s;
}

/* The view; evaluate: first bring the forces up to date with dem_sim_run(sim, 0) (a no-op
 * after a run; after a wall was moved, e.g. the piston withdrawn at the end of unloading, it
 * evaluates them as the next run would, so later runs are unchanged). The time-series rows
 * come right after a run and skip it. */
static int contacts(dem_scene *sc, dem_contact_view *view, int evaluate, dem_err *err) {
  if (!sc || !view) return dem_err_set(err, DEM_EINVAL, "dem_scene_contacts: NULL argument");
  memset(view, 0, sizeof *view);
  int rc;
  if (evaluate && (rc = dem_sim_run(sc->sim, 0, err))) return rc;
  size_t nc = 0;
  if ((rc = dem_sim_contacts(sc->sim, &sc->cbuf, &sc->ccap, &nc, err))) return rc;
  sc->cn = nc;
  size_t need = 0;
  for (size_t k = 0; k < nc; k++) need += sc->cbuf[k].wall < 0 ? 2 : 1;
  if (need > sc->vcap) {
    size_t cap = need + need / 4 + 64;
    size_t *pp = realloc(sc->v_part, cap * sizeof *pp);
    if (pp) sc->v_part = pp;
    double *pt = realloc(sc->v_point, 3 * cap * sizeof *pt);
    if (pt) sc->v_point = pt;
    double *fo = realloc(sc->v_force, 3 * cap * sizeof *fo);
    if (fo) sc->v_force = fo;
    if (!pp || !pt || !fo)
      return dem_err_set(err, DEM_ENOMEM, "dem_scene_contacts: out of memory (%zu records)",
                         cap);
    sc->vcap = cap;
  }
  size_t m = 0;
  for (size_t k = 0; k < nc; k++) {
    const dem_sim_contact *c = sc->cbuf + k;
    sc->v_part[m] = c->i;
    memcpy(sc->v_point + 3 * m, c->point, sizeof c->point);
    memcpy(sc->v_force + 3 * m, c->f, sizeof c->f);
    m++;
    if (c->wall < 0) {
      sc->v_part[m] = c->j;
      memcpy(sc->v_point + 3 * m, c->point, sizeof c->point);
      for (int a = 0; a < 3; a++) sc->v_force[3 * m + a] = -c->f[a];
      m++;
    }
  }
  view->n = m;
  view->particle = sc->v_part;
  view->point = sc->v_point;
  view->force = sc->v_force;
  return DEM_OK;
}

int dem_scene_contacts(dem_scene *sc, dem_contact_view *view, dem_err *err) {
  return contacts(sc, view, 1, err);
}

void scene_stress_free(dem_scene *sc) {
  free(sc->cbuf);
  free(sc->v_part);
  free(sc->v_point);
  free(sc->v_force);
  free(sc->fp_buf);
  sc->fp_buf = NULL;
  sc->fp_cap = sc->cn = 0;
  sc->cbuf = NULL;
  sc->v_part = NULL;
  sc->v_point = sc->v_force = NULL;
  sc->ccap = sc->vcap = 0;
}

/* The footprint of the indenter's contacts (dem_indent_footprint, docs/analysis.md 2b): each
 * contact's point and the vertical load it puts on the indenter, -f_z of the force on the
 * particle (the indenter pushes the particles down, so a pressing contact has f_z < 0). */
static int footprint(dem_scene *sc, const dem_wall_spec *w, double out[2], dem_err *err) {
  size_t m = 0;
  for (size_t k = 0; k < sc->cn; k++) m += sc->cbuf[k].wall == sc->w_ind;
  out[0] = (double)m;
  if (m > sc->fp_cap) {
    size_t cap = m + m / 4 + 64;
    double *b = realloc(sc->fp_buf, 4 * cap * sizeof *b);
    if (!b)
      return dem_err_set(err, DEM_ENOMEM, "scene footprint: out of memory (%zu contacts)", cap);
    sc->fp_buf = b;
    sc->fp_cap = cap;
  }
  double *pt = sc->fp_buf, *ld = sc->fp_buf + 3 * sc->fp_cap;
  size_t j = 0;
  for (size_t k = 0; k < sc->cn; k++) {
    const dem_sim_contact *c = sc->cbuf + k;
    if (c->wall != sc->w_ind) continue;
    memcpy(pt + 3 * j, c->point, sizeof c->point);
    ld[j++] = -c->f[2];
  }
  dem_footprint f;
  int rc = dem_indent_footprint(m, pt, ld, w->p[0], w->p[1], &f, err);
  if (rc) return rc;
  out[1] = f.a;
  return DEM_OK;
}

int scene_stress_row(dem_scene *sc, double out[SCENE_NCONTACT], dem_err *err) {
  for (int k = 0; k < SCENE_NCONTACT; k++) out[k] = NAN;
  dem_particles *p = dem_sim_particles(sc->sim);
  if (!sc->cfg.output_stress || p->n == 0) return DEM_OK;
  dem_contact_view v;
  int rc;
  if ((rc = contacts(sc, &v, 0, err))) return rc;
  double size[3], sig[9];
  bin_size(sc, size);
  /* base bin: on the axis, bottom face on the base */
  const dem_box base = {{-0.5 * size[0], -0.5 * size[1], 0.0},
                        {0.5 * size[0], 0.5 * size[1], size[2]}};
  if ((rc = dem_stress_box(&v, p->n, p->x, &base, 0.0, sig, NULL, err))) return rc;
  out[3] = dem_stress_hydrostatic(sig);
  if (sc->w_ind < 0 || sc->stage < 3) return DEM_OK;
  /* dynamic bin of Fig 5.18: top face at the indenter tip */
  dem_wall_spec w;
  dem_sim_wall(sc->sim, sc->w_ind, &w);
  const int sphere = sc->cfg.shape == DEM_INDENTER_SPHERE;
  const double tip[3] = {0.0, 0.0, w.p[2] - (sphere ? sc->ind_r : 0.0)};
  const dem_box bin = dem_dynamic_bin(tip, size, 0.0);
  /* the indenter's share of the bin (zero with the top face at the tip; kept so that a
   * gap < 0 or another bin stays right) */
  const double vol = sphere ? dem_box_free_volume(&bin, w.p, sc->ind_r) : dem_box_volume(&bin);
  if ((rc = dem_stress_box(&v, p->n, p->x, &bin, vol, sig, NULL, err))) return rc;
  out[0] = dem_stress_hydrostatic(sig);
  out[1] = dem_stress_deviatoric(sig);
  if ((rc = dem_solids_fraction(p->n, p->x, p->radius, &bin, vol, &out[2], err))) return rc;
  return footprint(sc, &w, out + 4, err);
}

int dem_scene_stress_grid(dem_scene *sc, size_t nz, double *sigma, dem_grid *grid_out,
                          dem_err *err) {
  if (!sc || !sigma) return dem_err_set(err, DEM_EINVAL, "dem_scene_stress_grid: NULL argument");
  if (nz < 1 || nz > 100000)
    return dem_err_set(err, DEM_ERANGE, "dem_scene_stress_grid: nz = %zu (allowed [1, 100000])",
                       nz);
  dem_grid g = dem_grid_thesis(0.0, 0.0, 0.0, nz);
  const double s = sc->cfg.d_mean / 1e-3;
  for (int k = 0; k < 3; k++) {
    g.cell[k] *= s;
    g.origin[k] *= s;
  }
  if (grid_out) *grid_out = g;
  dem_contact_view v;
  int rc;
  if ((rc = dem_scene_contacts(sc, &v, err))) return rc;
  const dem_particles *p = dem_sim_particles(sc->sim);
  return dem_stress_grid(&v, p->n, p->x, &g, sigma, err);
}
