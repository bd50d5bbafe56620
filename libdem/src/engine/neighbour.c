/* Neighbour search: a cell-linked grid feeding a half Verlet list with a skin, spatial
 * re-ordering of the particles in cell order, and the carry-over of contact histories.
 *
 * The list holds every pair (i < j) with |x_i - x_j| < r_i + r_j + skin at build time; it
 * stays valid until some particle has moved more than skin / 2 (then no pair outside the
 * list can have come into contact). Rows are sorted by j, so the list is ordered by the
 * pair key (i, j) and the histories of the previous list are merged in one pass.
 *
 * Cell size: at least 2 r_max + skin, so that every candidate of a particle is in the 27
 * cells around it. Cells are numbered x fastest, then y, then z; sorting the particles by
 * cell number puts neighbours close in memory and makes each particle's neighbours j > i
 * lie within about one layer of cells (used by the parallel force loop, force.c).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

void dem_nlist_free(dem_nlist *l) {
  free(l->first);
  free(l->nbr);
  free(l->hist);
  free(l->touch);
  memset(l, 0, sizeof *l);
}

static int nlist_reserve(dem_nlist *l, size_t rows, size_t pairs, int nh) {
  if (rows + 1 > l->cap_rows + 1 || !l->first) {
    size_t c = rows + 1;
    uint32_t *f = realloc(l->first, c * sizeof *f);
    if (!f) return DEM_ENOMEM;
    l->first = f;
    l->cap_rows = rows;
  }
  if (pairs > l->cap_pairs || !l->nbr) {
    size_t c = pairs > 16 ? pairs : 16;
    uint32_t *nb = realloc(l->nbr, c * sizeof *nb);
    if (!nb) return DEM_ENOMEM;
    l->nbr = nb;
    double *h = realloc(l->hist, c * (size_t)nh * sizeof *h);
    if (!h) return DEM_ENOMEM;
    l->hist = h;
    uint8_t *t = realloc(l->touch, c);
    if (!t) return DEM_ENOMEM;
    l->touch = t;
    l->cap_pairs = c;
  }
  return DEM_OK;
}

static int block_active(const double *h, int nh) {
  for (int k = 0; k < nh; k++)
    if (h[k] != 0.0) return 1;
  return 0;
}

/* Sort nbr[a..b) ascending, moving the history blocks along (rows are short). */
static void sort_row(uint32_t *nbr, double *hist, int nh, size_t a, size_t b, double *tmp) {
  for (size_t q = a + 1; q < b; q++) {
    uint32_t key = nbr[q];
    if (hist) memcpy(tmp, hist + q * nh, nh * sizeof(double));
    size_t r = q;
    while (r > a && nbr[r - 1] > key) {
      nbr[r] = nbr[r - 1];
      if (hist) memcpy(hist + r * nh, hist + (r - 1) * nh, nh * sizeof(double));
      r--;
    }
    nbr[r] = key;
    if (hist) memcpy(hist + r * nh, tmp, nh * sizeof(double));
  }
}

/* dst = the active entries of src renumbered by iperm (old index -> new index), as a sorted
 * half list over n rows. */
static int remap_list(const dem_nlist *src, dem_nlist *dst, const uint32_t *iperm, size_t n,
                      int nh) {
  size_t cnt = 0;
  for (size_t i = 0; i < src->n; i++)
    for (uint32_t q = src->first[i]; q < src->first[i + 1]; q++)
      cnt += (size_t)block_active(src->hist + (size_t)q * nh, nh);
  if (nlist_reserve(dst, n, cnt, nh)) return DEM_ENOMEM;
  memset(dst->first, 0, (n + 1) * sizeof(uint32_t));
  for (size_t i = 0; i < src->n; i++)
    for (uint32_t q = src->first[i]; q < src->first[i + 1]; q++)
      if (block_active(src->hist + (size_t)q * nh, nh)) {
        uint32_t a = iperm[i], b = iperm[src->nbr[q]];
        dst->first[(a < b ? a : b) + 1]++;
      }
  for (size_t i = 0; i < n; i++) dst->first[i + 1] += dst->first[i];
  /* fill using first[] as cursors, then restore */
  for (size_t i = 0; i < src->n; i++)
    for (uint32_t q = src->first[i]; q < src->first[i + 1]; q++) {
      const double *h = src->hist + (size_t)q * nh;
      if (!block_active(h, nh)) continue;
      uint32_t a = iperm[i], b = iperm[src->nbr[q]];
      uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
      uint32_t at = dst->first[lo]++;
      dst->nbr[at] = hi;
      memcpy(dst->hist + (size_t)at * nh, h, nh * sizeof(double));
    }
  for (size_t i = n; i > 0; i--) dst->first[i] = dst->first[i - 1];
  dst->first[0] = 0;
  double tmp[DEM_LAW_NHIST_MAX + DEM_TANGENTIAL_NHIST];
  for (size_t i = 0; i < n; i++) sort_row(dst->nbr, dst->hist, nh, dst->first[i], dst->first[i + 1], tmp);
  dst->n = n;
  dst->npairs = cnt;
  return DEM_OK;
}

/* First build: fix the history layout from the interactions set so far. */
static int layout(dem_sim *s, dem_err *err) {
  int hmax = 1;
  for (int a = 0; a < s->nmat; a++)
    for (int b = 0; b < s->nmat; b++)
      if (s->inter[a][b].set && s->inter[a][b].normal.law->nhist > hmax)
        hmax = s->inter[a][b].normal.law->nhist;
  s->hoff = hmax;
  s->nh = hmax + DEM_TANGENTIAL_NHIST;
  for (int w = 0; w < s->nwall; w++) {
    free(s->wall[w].hist);
    s->wall[w].hist = calloc(s->cap ? s->cap : 1, (size_t)s->nh * sizeof(double));
    if (!s->wall[w].hist) return dem_err_set(err, DEM_ENOMEM, "wall histories: out of memory");
  }
  return DEM_OK;
}

typedef struct grid {
  double lo[3], h, inv_h;
  long nc[3];
} grid;

static int make_grid(dem_sim *s, grid *gr, dem_err *err) {
  const dem_particles *p = &s->p;
  size_t n = p->n;
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  double rmax = 0.0;
  for (size_t i = 0; i < n; i++) {
    for (int k = 0; k < 3; k++) {
      double x = p->x[3 * i + k];
      if (!isfinite(x))
        return dem_err_set(err, DEM_ENONFINITE, "particle id %u: non-finite position",
                           (unsigned)p->id[i]);
      if (x < lo[k]) lo[k] = x;
      if (x > hi[k]) hi[k] = x;
    }
    if (p->radius[i] > rmax) rmax = p->radius[i];
  }
  double h = 2.0 * rmax + s->skin;
  /* Limit the number of cells to a few per particle (a stray particle far away would
   * otherwise make the grid huge): coarsen until it fits. */
  double limit = 4.0 * (double)n + 64.0;
  for (;;) {
    double tot = 1.0;
    for (int k = 0; k < 3; k++) tot *= floor((hi[k] - lo[k]) / h) + 1.0;
    if (tot <= limit) break;
    h *= 1.25;
  }
  gr->h = h;
  gr->inv_h = 1.0 / h;
  for (int k = 0; k < 3; k++) {
    gr->lo[k] = lo[k];
    gr->nc[k] = (long)floor((hi[k] - lo[k]) * gr->inv_h) + 1;
  }
  size_t ncell = (size_t)(gr->nc[0] * gr->nc[1] * gr->nc[2]);
  if (ncell + 1 > s->ncell_cap + 1 || !s->cell_first) {
    uint32_t *c = realloc(s->cell_first, (ncell + 1) * sizeof *c);
    if (!c) return dem_err_set(err, DEM_ENOMEM, "cell grid: out of memory (%zu cells)", ncell);
    s->cell_first = c;
    s->ncell_cap = ncell;
  }
  /* counting sort of the particles by cell (stable: keeps the current order in a cell) */
  memset(s->cell_first, 0, (ncell + 1) * sizeof(uint32_t));
  for (size_t i = 0; i < n; i++) {
    long c[3];
    for (int k = 0; k < 3; k++) {
      c[k] = (long)((p->x[3 * i + k] - lo[k]) * gr->inv_h);
      if (c[k] >= gr->nc[k]) c[k] = gr->nc[k] - 1;
    }
    uint32_t id = (uint32_t)((c[2] * gr->nc[1] + c[1]) * gr->nc[0] + c[0]);
    s->cell_of[i] = id;
    s->cell_first[id + 1]++;
  }
  for (size_t c = 0; c < ncell; c++) s->cell_first[c + 1] += s->cell_first[c];
  for (size_t i = 0; i < n; i++) s->cell_idx[s->cell_first[s->cell_of[i]]++] = (uint32_t)i;
  for (size_t c = ncell; c > 0; c--) s->cell_first[c] = s->cell_first[c - 1];
  s->cell_first[0] = 0;
  return DEM_OK;
}

static void swap_lists(dem_sim *s) {
  dem_nlist t = s->nl;
  s->nl = s->nl_old;
  s->nl_old = t;
}

/* Re-order the particles in cell order; the previous list is renumbered into nl_old. */
static int spatial_sort(dem_sim *s, const grid *gr, dem_err *err) {
  size_t n = s->p.n;
  int identity = 1;
  for (size_t k = 0; k < n && identity; k++) identity = s->cell_idx[k] == k;
  if (identity) {
    swap_lists(s);
    return DEM_OK;
  }
  memcpy(s->perm, s->cell_idx, n * sizeof(uint32_t));
  for (size_t k = 0; k < n; k++) s->iperm[s->perm[k]] = (uint32_t)k;
  /* previous list (in nl) -> renumbered active entries (in nl_old) */
  if (s->nl.first && s->nl.n == n) {
    if (remap_list(&s->nl, &s->nl_old, s->iperm, n, s->nh))
      return dem_err_set(err, DEM_ENOMEM, "neighbour list: out of memory");
  } else {
    s->nl_old.n = 0;
    s->nl_old.npairs = 0;
  }
  dem_engine_permute(s, s->perm);
  for (size_t k = 0; k < n; k++) s->perm[k] = s->cell_of[s->perm[k]];
  memcpy(s->cell_of, s->perm, n * sizeof(uint32_t));
  for (size_t k = 0; k < n; k++) s->cell_idx[k] = (uint32_t)k;
  s->st.sorts++;
  (void)gr;
  return DEM_OK;
}

int dem_engine_build(dem_sim *s, dem_err *err) {
  int rc;
  if (s->nh == 0 && (rc = layout(s, err))) return rc;
  const dem_particles *p = &s->p;
  size_t n = p->n;
  int nh = s->nh;
  grid gr;
  if ((rc = make_grid(s, &gr, err))) return rc;

  int do_sort = s->sort_every > 0 && (s->st.rebuilds == 0 || ++s->builds_since_sort >= s->sort_every);
  if (do_sort) {
    s->builds_since_sort = 0;
    if ((rc = spatial_sort(s, &gr, err))) return rc;
  } else {
    swap_lists(s);
  }
  /* nl_old: the previous list in the current numbering (or empty). Build the new one. */
  dem_nlist *nl = &s->nl;
  const dem_nlist *old = &s->nl_old;
  int have_old = old->first && old->n == n;
  size_t guess = nl->cap_pairs > 8 * n ? nl->cap_pairs : 8 * n;
  if (nlist_reserve(nl, n, guess, nh)) return dem_err_set(err, DEM_ENOMEM, "neighbour list: out of memory");
  double tmp[DEM_LAW_NHIST_MAX + DEM_TANGENTIAL_NHIST];
  size_t np = 0;
  const double skin = s->skin;
  for (size_t i = 0; i < n; i++) {
    nl->first[i] = (uint32_t)np;
    const double *xi = p->x + 3 * i;
    double ri = p->radius[i];
    uint32_t c = s->cell_of[i];
    long cx = (long)(c % (uint32_t)gr.nc[0]);
    long cy = (long)((c / (uint32_t)gr.nc[0]) % (uint32_t)gr.nc[1]);
    long cz = (long)(c / (uint32_t)(gr.nc[0] * gr.nc[1]));
    for (long z = cz - 1; z <= cz + 1; z++) {
      if (z < 0 || z >= gr.nc[2]) continue;
      for (long y = cy - 1; y <= cy + 1; y++) {
        if (y < 0 || y >= gr.nc[1]) continue;
        for (long x = cx - 1; x <= cx + 1; x++) {
          if (x < 0 || x >= gr.nc[0]) continue;
          size_t cell = (size_t)((z * gr.nc[1] + y) * gr.nc[0] + x);
          for (uint32_t q = s->cell_first[cell]; q < s->cell_first[cell + 1]; q++) {
            uint32_t j = s->cell_idx[q];
            if (j <= i) continue;
            const double *xj = p->x + 3 * (size_t)j;
            double dx = xi[0] - xj[0], dy = xi[1] - xj[1], dz = xi[2] - xj[2];
            double cut = ri + p->radius[j] + skin;
            if (dx * dx + dy * dy + dz * dz < cut * cut) {
              if (np == nl->cap_pairs &&
                  nlist_reserve(nl, n, 2 * nl->cap_pairs, nh))
                return dem_err_set(err, DEM_ENOMEM, "neighbour list: out of memory");
              nl->nbr[np++] = j;
            }
          }
        }
      }
    }
    sort_row(nl->nbr, NULL, nh, nl->first[i], np, tmp);
    /* histories: merge with the previous row i (both sorted by j) */
    double *h = nl->hist + (size_t)nl->first[i] * nh;
    memset(h, 0, (np - nl->first[i]) * nh * sizeof(double));
    memset(nl->touch + nl->first[i], 0, np - nl->first[i]);
    if (have_old) {
      uint32_t q = old->first[i], qe = old->first[i + 1];
      for (size_t r = nl->first[i]; r < np && q < qe; r++) {
        while (q < qe && old->nbr[q] < nl->nbr[r]) q++;
        if (q < qe && old->nbr[q] == nl->nbr[r]) {
          memcpy(nl->hist + r * nh, old->hist + (size_t)q * nh, nh * sizeof(double));
          nl->touch[r] = (uint8_t)block_active(nl->hist + r * nh, nh);
        }
      }
    }
  }
  nl->first[n] = (uint32_t)np;
  nl->n = n;
  nl->npairs = np;
  memcpy(s->x0, p->x, 3 * n * sizeof(double));
  for (size_t i = 0; i < n; i++) {
    s->invr[i] = 1.0 / p->radius[i];
    s->invm[i] = 1.0 / p->mass[i];
    s->invI[i] = 1.0 / p->inertia[i];
  }
  if ((rc = dem_engine_wall_lists(s, err))) return rc;
  s->st.rebuilds++;
  s->need_build = 0;
  dem_engine_partition(s);
  return dem_engine_spill_reserve(s, err);
}

int dem_sim_build_neighbours(dem_sim *s, dem_err *err) { return dem_engine_build(s, err); }
