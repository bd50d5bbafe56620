/* run.c — tiers, beds prepared once and reused, indentation runs and their statistics.
 *
 * A bed is prepared by the scene pipeline (fill, settle, consolidate to 10 kPa, unload;
 * dem/scene.h) and saved as a scene checkpoint; every indentation restores it with its own
 * indenter (dem_scene_restore), so the variants of a case start from the identical bed.
 * Hardness is recomputed here from the indenter tip and force of the time series with the
 * depth measured from the bed surface under the footprint (dem_bed_surface, docs/analysis.md):
 * H = F / A(h), thesis 2.7-2.9, h/r thesis 5.5.
 */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "dem/params.h"
#include "dem/table.h"
#include "vh_run.h"

/* The tiers (geometry in d; docs/validation.md gives the reasons).
 * quick:  thesis geometry scaled by ~0.6 (die 20 d, bed 12 d, sphere 8 d: indenter/die 0.4
 *         as the thesis' 16/45; bed heights 8 and 12 d under an 8 d ball keep the ratios
 *         bed/indenter 1.0 and 1.5 of its 13 and 20 mm beds under a 13 mm ball); cases 1-3.
 * medium: the quick geometry for all eleven cases (bed heights 8, 12, 18, 30 d = the thesis'
 *         13, 20, 30, 50 scaled by 8/13; indenter sizes 4-10 d; replicate beds).
 * full:   thesis scale (chapters 5-7: die 45 d, bed 20 d, sphere 16 d, bed heights 13, 20,
 *         30, 50 d, sizes 7-22 d, the 25 d ball on the 13 d bed); hours on 2 cores.
 * smoke:  the smallest scene that exercises every path (tests; not a validation).
 * Shallow-bed die: the thesis' 13 mm bed (case 2's shallowest, and the bed of the
 *         wall-confinement runs of case 3, Figs 5.2-5.11) is in a 39 mm die, its 20-50 mm
 *         beds in the 45 mm die (5.2); full keeps 39 d, quick and medium the same ratio
 *         (20 x 39/45 = 17.3 d); smoke keeps one die (it tests the program, not the physics).
 * Stiffness: every stiffness of Tables 6.2/6.3 x0.01 (the speed-versus-accuracy study,
 * docs/validation-study.md), but stiffer for the beds of the high-rate cases 10 and 11
 * (x0.1 quick/medium, x0.3 full): an indenter driving the bed at v presses the contacts
 * under it with about F = C v sqrt(m k_p), C <~ 2, so their overlap F / k_p peaks at
 * alpha_bed + C v sqrt(m / k_p) / r (measured, docs/validation.md "What stops the high-rate
 * runs"). At gamma* 2.3 (v = 2.5 m/s medium, 4.3 m/s full) that is > 0.25 r at x0.01 on the
 * medium tier and ~0.21 r at x0.1 with the full tier's 16 d ball (its thesis-scale run
 * stopped at the engine's 0.25 r), 0.08 r at x0.1 medium and 0.12 r at x0.3 full; H did not
 * differ between x0.1 and x0.3 at any rate.
 * Plateau window: h/r 0.2-0.5 (thesis: stress constant from ~0.1, hardness from ~0.35-0.4,
 * stresses rise again beyond 0.5), starting no earlier than one particle diameter of depth
 * under the reference sphere (the thesis shows data only beyond one diameter, 5.2): 0.25
 * for the 8 d sphere of quick/medium. */
static const vh_tier tiers[] = {
    {"quick", 20.0, 12.0, 8.0, 0.1, 0.01, 0.1, 0.2, 0.36, 0.5, 0.25, 0.5, 0.02, 0.1,
     2, {8.0, 12.0}, 8.0, 4, {4.0, 6.0, 8.0, 10.0}, 8.0, 12.0, 17.3, 1, 0x7},
    {"medium", 20.0, 12.0, 8.0, 0.1, 0.01, 0.1, 0.2, 0.36, 0.5, 0.25, 0.5, 0.02, 0.1,
     4, {8.0, 12.0, 18.0, 30.0}, 8.0, 6, {4.0, 5.0, 6.0, 7.0, 8.0, 10.0}, 7.0, 12.0, 17.3, 2,
     0x7ff},
    {"full", 45.0, 20.0, 16.0, 0.1, 0.01, 0.3, 0.2, 0.36, 0.5, 0.2, 0.5, 0.02, 0.1,
     4, {13.0, 20.0, 30.0, 50.0}, 13.0, 6, {7.0, 10.0, 13.0, 16.0, 19.0, 22.0}, 16.0, 25.0, 39.0,
     2, 0x7ff},
    {"smoke", 10.0, 6.0, 4.0, 0.2, 0.01, 0.1, 0.2, 0.36, 0.5, 0.2, 0.5, 0.02, 0.1,
     2, {4.0, 6.0}, 4.0, 3, {3.0, 4.0, 5.0}, 4.0, 7.0, 0.0, 1, 0x7},
};

const vh_tier *vh_tier_find(const char *name) {
  for (size_t i = 0; i < sizeof tiers / sizeof tiers[0]; i++)
    if (strcmp(tiers[i].name, name) == 0) return &tiers[i];
  return NULL;
}

double vh_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void vh_log(const vh *h, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  if (h->nranks > 1) fprintf(stderr, "[rank %d %6.0f s] ", h->rank, vh_now() - h->t0);
  else fprintf(stderr, "[%6.0f s] ", vh_now() - h->t0);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  fflush(stderr);
  va_end(ap);
}

/* gamma* = gamma_dot sqrt(d/g) (thesis 5.4 / 7.1) -> gamma_dot in 1/s. */
static double rate_of(double gamma_star) { return gamma_star / sqrt(D_MEAN / G_ACC); }

vh_bed vh_bed_ref(const vh *h, int replicate) {
  vh_bed b;
  memset(&b, 0, sizeof b);
  b.bed = h->tier->bed;
  b.die = h->tier->die;
  b.seed = 1 + (unsigned long)replicate;
  b.mu = 0.15;   /* Tables 5.3, 6.3 */
  /* J/m^2: Table 6.3 (pasha-simplified), Table 5.3 (hertz-jkr, Material 1 - Material 1) */
  b.gamma = h->materials == DEM_SCENE_HERTZ_JKR ? 0.5 : 2.0;
  b.kscale = h->tier->stiffness_scale;
  b.gamma_star = h->tier->gamma_star;
  return b;
}

double vh_gamma_star_of_bed(const vh *h, double bed) {
  const vh_tier *t = h->tier;
  return bed > t->bed ? t->gamma_star * t->bed / bed : t->gamma_star;
}

vh_bed vh_bed_rate(const vh *h) {
  vh_bed b = vh_bed_ref(h, 0);
  b.kscale = h->tier->rate_stiffness_scale;
  return b;
}

vh_indent vh_indent_ref(const vh *h) {
  /* particle-indenter friction: 0 in chapters 6/7 (Table 6.3, the geometries); 0.15 in
   * chapter 5, whose indenter is Material 1 (Table 5.3, 5.1.3) */
  double mu_i = h->materials == DEM_SCENE_HERTZ_JKR ? 0.15 : 0.0;
  vh_indent i = {DEM_INDENTER_SPHERE, h->tier->indenter, h->tier->gamma_star, 1.0, mu_i, 1.0};
  return i;
}

/* The scene configuration of a bed (and of the reference indentation on it). */
static int bed_config(const vh *h, const vh_bed *b, dem_scene_config *c, dem_err *err) {
  const vh_tier *t = h->tier;
  dem_scene_config_defaults(c, h->materials);
  c->die_diameter = b->die;
  c->bed_height = b->bed;
  c->seed = b->seed;
  c->fill_fraction = t->fill_fraction;
  c->settle_max_time = 2.0;
  c->strain_rate = rate_of(b->gamma_star);
  c->stiffness_scale = b->kscale;
  c->dt_factor = t->dt_factor;
  c->threads = h->threads;
  c->indenter_diameter = fmin(t->indenter, 0.9 * b->die);
  c->h_over_r = t->h_end;
  int rc;
  if ((rc = dem_params_set(&c->pp, "mu", b->mu, "dem-validate", err)) ||
      (rc = dem_params_set(&c->pp, "gamma", b->gamma, "dem-validate", err)))
    return rc;
  return dem_scene_config_check(c, err);
}

static void bed_name(const vh *h, const vh_bed *b, char *buf, size_t len) {
  const vh_tier *t = h->tier;
  /* the default materials add nothing: the names of the beds made before --materials stay */
  const int other = h->materials != DEM_SCENE_PASHA;
  snprintf(buf, len, "bed%g_die%g_seed%lu_mu%g_gamma%g_k%g_dt%g_g%g_f%g%s%s", b->bed, b->die,
           b->seed, b->mu, b->gamma, b->kscale, t->dt_factor, b->gamma_star,
           t->fill_fraction, other ? "_" : "",
           other ? dem_scene_materials_names[h->materials] : "");
}

static void progress(const char *stage, double t, double frac, double eta, void *user) {
  const vh *h = user;
  if (h->verbose < 0) return;
  char f[32] = "", e[32] = "";
  if (frac >= 0) snprintf(f, sizeof f, " %3.0f%%", 100.0 * frac);
  if (eta >= 0) snprintf(e, sizeof e, ", stage ETA %.0f s", eta);
  vh_log(h, "  %-11s t = %.4f s%s%s", stage, t, f, e);
}

static int same_bed(const vh_bed *a, const vh_bed *b) {
  return a->bed == b->bed && a->die == b->die && a->seed == b->seed && a->mu == b->mu &&
         a->gamma == b->gamma && a->kscale == b->kscale && a->gamma_star == b->gamma_star;
}

/* The plan's mark of the case being run on a bed or run it needs (none past 32 cases). */
static unsigned case_bit(const vh *h) {
  return h->cur_case >= 0 && h->cur_case < 32 ? 1u << h->cur_case : 0u;
}

int vh_bed_get(vh *h, const vh_bed *spec, dem_err *err) {
  for (int i = 0; i < h->nbeds; i++)
    if (same_bed(&h->beds[i], spec)) {
      h->beds[i].cases |= case_bit(h);
      return i;
    }
  if (h->nbeds == VH_MAX_BEDS) {
    dem_err_set(err, DEM_ERANGE, "dem-validate: more than %d beds", VH_MAX_BEDS);
    return -1;
  }
  vh_bed *b = &h->beds[h->nbeds];
  *b = *spec;
  b->cases = case_bit(h);
  char name[256];
  bed_name(h, b, name, sizeof name);
  if (dem_mkdirs(h->beds_dir, err)) {
    dem_err_prefix(err, "dem-validate: the bed folder: ");
    return -1;
  }
  snprintf(b->path, sizeof b->path, "%.300s/%.200s.h5", h->beds_dir, name);
  dem_scene_config c;
  if (bed_config(h, b, &c, err)) return -1;
  b->rho = c.rho;
  if (h->plan) { /* listed, not prepared (dist.c) */
    b->prep_s = NAN;
    return h->nbeds++;
  }
  if (h->cache_only && access(b->path, R_OK) != 0) { /* over the --budget (dist.c) */
    b->skipped = 1;
    b->prep_s = b->wall_s = b->phi = b->bed_top = b->dt = NAN;
    vh_log(h, "bed %s: not prepared (over the --budget): its runs are skipped", name);
    return h->nbeds++;
  }
  dem_scene_hooks hk = {progress, 30.0, NULL, 0.0, h};
  double t0 = vh_now();
  dem_scene *sc = NULL;
  if (access(b->path, R_OK) == 0) {
    /* A bed prepared by an earlier invocation with the same parameters (--beds DIR); one
     * this build cannot read (another checkpoint version) or that is not unloaded is
     * prepared anew. */
    sc = dem_scene_restore(b->path, NULL, &hk, err);
    if (sc && dem_scene_get_stage(sc) < DEM_SCENE_STAGE_UNLOADED) {
      dem_scene_free(sc);
      sc = NULL;
      dem_err_set(err, DEM_EINVAL, "%s is not an unloaded bed", b->path);
    }
    if (sc) {
      b->prep_s = vh_bed_info_load(b);
      vh_log(h, "bed %s: reused %s", name, b->path);
    }
    else vh_log(h, "bed %s: cannot reuse (%s): preparing it anew", name, err->msg);
    *err = (dem_err){0};
  }
  if (!sc) {
    vh_log(h, "bed %s: preparing (fill, settle, consolidate to 10 kPa, unload)", name);
    sc = dem_scene_create(&c, &hk, err);
    int rc = sc ? DEM_OK : err->code;
    if (!rc) rc = dem_scene_fill(sc, err);
    if (!rc) rc = dem_scene_settle(sc, err);
    if (!rc) rc = dem_scene_consolidate(sc, err);
    if (!rc) rc = dem_scene_unload(sc, err);
    if (!rc) rc = dem_scene_save(sc, b->path, err);
    if (rc) {
      dem_scene_free(sc);
      return -1;
    }
    b->prep_s = vh_now() - t0;
    vh_bed_info_save(b, h->threads);
  }
  dem_scene_info in;
  dem_scene_get_info(sc, &in);
  b->n = in.n;
  b->phi = in.phi;
  b->bed_top = in.bed_top;
  b->dt = in.dt;
  b->wall_s = vh_now() - t0;
  b->ready = 1;
  dem_scene_free(sc);
  vh_log(h, "bed %s: %zu particles, bed top %.2f d, solids fraction %.3f, %.0f s", name, b->n,
         b->bed_top / D_MEAN, b->phi, b->wall_s);
  return h->nbeds++;
}

static int same_indent(const vh_indent *a, const vh_indent *b) {
  return a->shape == b->shape && a->D == b->D && a->gamma_star == b->gamma_star &&
         a->kn_scale == b->kn_scale && a->mu_ind == b->mu_ind && a->dt_scale == b->dt_scale;
}

static const char *shape_name(dem_indenter_shape s) {
  return s == DEM_INDENTER_SPHERE ? "sphere" : s == DEM_INDENTER_CYLINDER ? "cylinder" : "cube";
}

/* Column of the series by name, or -1. */
static int col(const dem_table *t, const char *name) { return dem_table_col(t, name); }

static int series_extract(vh *h, vh_run *r, const dem_table *t, dem_err *err) {
  const int cs = col(t, "stage"), cz = col(t, "indenter_z"), cf = col(t, "indenter_force");
  if (cs < 0 || cz < 0 || cf < 0)
    return dem_err_set(err, DEM_EINVAL, "dem-validate: the time series lacks stage, "
                                        "indenter_z or indenter_force");
  const int cp = col(t, "bin_p"), cq = col(t, "bin_q"), cphi = col(t, "bin_phi"),
            cb = col(t, "base_p"), ca = col(t, "contact_radius"),
            cn = col(t, "indenter_contacts");
  long nr = dem_table_nrows(t);
  size_t cap = (size_t)nr + 1;
  double **arr[] = {&r->hr,     &r->H, &r->bin_p, &r->bin_q, &r->bin_phi,
                    &r->base_p, &r->F, &r->ac,    &r->Hc,    &r->nind};
  for (size_t k = 0; k < sizeof arr / sizeof arr[0]; k++) {
    *arr[k] = calloc(cap, sizeof(double));
    if (!*arr[k]) return dem_err_set(err, DEM_ENOMEM, "dem-validate: out of memory");
  }
  const double D = r->ind.D * D_MEAN, rad = 0.5 * D;
  r->n = 0;
  r->base_p0 = NAN;
  for (long i = 0; i < nr; i++) {
    if ((int)dem_table_get(t, i, cs) != 3) continue; /* loading only */
    double hh = r->surface - dem_table_get(t, i, cz);
    double F = dem_table_get(t, i, cf);
    double bp = cb >= 0 ? dem_table_get(t, i, cb) : NAN;
    if (hh <= 0.0) {
      if (isfinite(bp)) r->base_p0 = bp; /* the last value before the surface is reached */
      continue;
    }
    size_t k = r->n++;
    r->hr[k] = hh / rad;
    r->F[k] = F;
    r->H[k] = F / dem_scene_indent_area(r->ind.shape, D, hh);
    r->bin_p[k] = cp >= 0 ? dem_table_get(t, i, cp) : NAN;
    r->bin_q[k] = cq >= 0 ? dem_table_get(t, i, cq) : NAN;
    r->bin_phi[k] = cphi >= 0 ? dem_table_get(t, i, cphi) : NAN;
    r->base_p[k] = bp;
    r->ac[k] = ca >= 0 ? dem_table_get(t, i, ca) : NAN;
    r->nind[k] = cn >= 0 ? dem_table_get(t, i, cn) : NAN;
    r->Hc[k] = r->ac[k] > 0.0 ? F / (M_PI * r->ac[k] * r->ac[k]) : NAN;
  }
  r->have_stress = cp >= 0 && cq >= 0;
  (void)h;
  return DEM_OK;
}

double vh_footprint_ratio(const vh_run *r, size_t i) {
  if (r->ind.shape != DEM_INDENTER_SPHERE || !(r->ac[i] > 0.0)) return NAN;
  const double D = r->ind.D * D_MEAN;
  const double A = dem_indent_area(D, r->hr[i] * 0.5 * D); /* eq. 2.9, pi (D h - h^2) */
  return A > 0.0 ? M_PI * r->ac[i] * r->ac[i] / A : NAN;
}

/* Plateau statistics of y over [lo, hi]; on failure mean = NaN. */
static void stats(const vh_run *r, const double *y, double lo, double hi, dem_series_stats *s) {
  dem_err e = {0};
  memset(s, 0, sizeof *s);
  /* only finite samples: the stress columns are NaN where undefined */
  double *x = malloc((r->n + 1) * sizeof *x), *v = malloc((r->n + 1) * sizeof *v);
  size_t m = 0;
  for (size_t i = 0; x && v && i < r->n; i++)
    if (isfinite(y[i]) && isfinite(r->hr[i])) x[m] = r->hr[i], v[m++] = y[i];
  if (!x || !v || dem_plateau_stats(m, x, v, lo, hi, NULL, s, &e)) {
    memset(s, 0, sizeof *s);
    s->mean = s->se = s->sd = s->cv = s->slope = NAN;
  }
  free(x);
  free(v);
}

static void run_stats(const vh *h, vh_run *r) {
  const vh_tier *t = h->tier;
  if (r->status != DEM_OK) return;
  stats(r, r->H, t->plateau_lo, t->plateau_hi, &r->sH);
  stats(r, r->H, t->early_lo, t->early_hi, &r->sEarly);
  stats(r, r->bin_p, t->plateau_lo, t->plateau_hi, &r->sp);
  stats(r, r->bin_q, t->plateau_lo, t->plateau_hi, &r->sq);
  stats(r, r->bin_phi, t->plateau_lo, t->plateau_hi, &r->sphi);
  stats(r, r->Hc, t->plateau_lo, t->plateau_hi, &r->sHc);
  double *ratio = r->ind.shape == DEM_INDENTER_SPHERE ? malloc((r->n + 1) * sizeof *ratio) : NULL;
  for (size_t i = 0; ratio && i < r->n; i++) ratio[i] = vh_footprint_ratio(r, i);
  if (ratio) stats(r, ratio, t->plateau_lo, t->plateau_hi, &r->sfoot);
  else {
    memset(&r->sfoot, 0, sizeof r->sfoot); /* not a sphere: no eq. 2.9 area to compare with */
    r->sfoot.mean = r->sfoot.se = r->sfoot.sd = r->sfoot.cv = r->sfoot.slope = NAN;
    r->sfoot.n_eff = NAN;
  }
  free(ratio);
}

void vh_run_release(vh_run *u) {
  free(u->hr), free(u->H), free(u->bin_p), free(u->bin_q), free(u->bin_phi);
  free(u->base_p), free(u->F), free(u->ac), free(u->Hc), free(u->nind);
  u->hr = u->H = u->bin_p = u->bin_q = u->bin_phi = u->base_p = u->F = NULL;
  u->ac = u->Hc = u->nind = NULL;
  u->n = 0;
}

void vh_reset(vh *h) {
  for (int i = 0; i < h->nruns; i++) vh_run_release(&h->runs[i]);
  h->nruns = 0;
  h->nbeds = 0;
}

/* A run that is listed but not made (the plan, or over the --budget): status
 * DEM_EINTERRUPTED and no statistics, so the cases see it as unavailable. Its index. */
static int run_placeholder(vh *h, vh_run *r, const char *why) {
  r->status = DEM_EINTERRUPTED;
  snprintf(r->error, sizeof r->error, "%s", why);
  r->sH.mean = r->sp.mean = r->sq.mean = r->sphi.mean = r->sEarly.mean = NAN;
  r->wall_s = 0.0;
  return h->nruns++;
}

int vh_run_get(vh *h, const vh_bed *bspec, const vh_indent *ind, dem_err *err) {
  int bi = vh_bed_get(h, bspec, err);
  if (bi < 0) return -1;
  for (int i = 0; i < h->nruns; i++)
    if (h->runs[i].bed == bi && same_indent(&h->runs[i].ind, ind)) {
      h->runs[i].cases |= case_bit(h);
      return i;
    }
  if (h->nruns == VH_MAX_RUNS) {
    dem_err_set(err, DEM_ERANGE, "dem-validate: more than %d runs", VH_MAX_RUNS);
    return -1;
  }
  const vh_tier *t = h->tier;
  vh_bed *b = &h->beds[bi];
  vh_run *r = &h->runs[h->nruns];
  memset(r, 0, sizeof *r);
  r->bed = bi;
  r->ind = *ind;
  r->cases = case_bit(h);
  r->v = b->ready ? rate_of(ind->gamma_star) * b->bed_top : NAN;
  snprintf(r->label, sizeof r->label, "bed %g d, %s %g d, gamma* %g, kn x%g, mu_i %g, dt x%g",
           b->bed, shape_name(ind->shape), ind->D, ind->gamma_star, ind->kn_scale, ind->mu_ind,
           ind->dt_scale);
  if (b->kscale != t->stiffness_scale) {
    size_t len = strlen(r->label);
    snprintf(r->label + len, sizeof r->label - len, ", k x%g", b->kscale);
  }
  if (b->seed != 1) { /* a replicate bed */
    size_t len = strlen(r->label);
    snprintf(r->label + len, sizeof r->label - len, ", seed %lu", b->seed);
  }
  if (h->plan) /* listed, not run: a placeholder the cases see as not (yet) available */
    return run_placeholder(h, r, "planned");
  char cpath[700] = "";
  if (h->use_cache) {
    char bname[256];
    bed_name(h, b, bname, sizeof bname);
    vh_cache_path(h, bname, ind, cpath, sizeof cpath);
    if (vh_cache_load(h, cpath, b->path, r) == 0) {
      h->nruns++;
      run_stats(h, r);
      if (r->status != DEM_OK) /* a run the engine's checks stopped: no plateau to show */
        vh_log(h, "run %d: %s: cached (%s; made in %.0f s with %d threads): FAILED: %s",
               h->nruns - 1, r->label, cpath, r->wall_s, r->threads, r->error);
      else
        vh_log(h, "run %d: %s: cached (%s; made in %.0f s with %d threads): H plateau %.0f +- "
               "%.0f Pa", h->nruns - 1, r->label, cpath, r->wall_s, r->threads, r->sH.mean,
               r->sH.se);
      return h->nruns - 1;
    }
  }
  if (h->cache_only || b->skipped) { /* over the --budget (dist.c): the cases see N/A */
    r->skipped = 1;
    vh_log(h, "run %d: %s: not made (over the --budget)", h->nruns, r->label);
    return run_placeholder(h, r, "not made (over the --budget)");
  }
  r->threads = h->threads;
  dem_scene_config o;
  if (bed_config(h, b, &o, err)) return -1;
  o.shape = ind->shape;
  o.indenter_diameter = ind->D;
  o.indent_rate = rate_of(ind->gamma_star);
  o.h_over_r = t->h_end;
  o.dt_factor = t->dt_factor * ind->dt_scale;
  /* particle-indenter stiffness and friction (Table 6.3; 6.2.1, 6.2.3); with chapter 5's
   * materials the indenter's stiffness is its Young's modulus (Table 5.2, `wall_E`) */
  if (h->materials == DEM_SCENE_HERTZ_JKR) {
    double E = dem_params_get_or(&o.pi, "wall_E", 55e9);
    if (dem_params_set(&o.pi, "wall_E", E * ind->kn_scale, "dem-validate", err) ||
        dem_params_set(&o.pi, "mu", ind->mu_ind, "dem-validate", err))
      return -1;
  } else {
    double kn = dem_params_get_or(&o.pi, "kn", 8e6), kt = dem_params_get_or(&o.pi, "kt", 8e6);
    if (dem_params_set(&o.pi, "kn", kn * ind->kn_scale, "dem-validate", err) ||
        dem_params_set(&o.pi, "kt", kt * ind->kn_scale, "dem-validate", err) ||
        dem_params_set(&o.pi, "mu", ind->mu_ind, "dem-validate", err))
      return -1;
  }
  /* one sample every 0.0025 h/r: the same resolution for every rate and size */
  double v = r->v; /* = o.indent_rate x bed top */
  o.sample_interval = 0.0025 * 0.5 * ind->D * D_MEAN / v;
  h->nruns++;
  vh_log(h, "run %d: %s", h->nruns - 1, r->label);
  double t0 = vh_now();
  dem_scene_hooks hk = {progress, 30.0, NULL, 0.0, h};
  /* The bed surface under the footprint first (dem_bed_surface: mean column top, docs/
   * analysis.md). The scene stops at h/r measured from the first contact, which lies at most
   * at the highest particle top of the footprint: ask it for the difference more, so that
   * h/r_end is reached from this surface. */
  int rc = DEM_OK;
  {
    dem_scene *s0 = dem_scene_restore(b->path, NULL, NULL, err);
    if (!s0) rc = err->code;
    else {
      const dem_particles *p = dem_sim_particles(dem_scene_sim(s0));
      dem_surface su;
      rc = dem_bed_surface(p->n, p->x, p->radius, 0.0, 0.0, 0.5 * ind->D * D_MEAN, 0.0, 90.0,
                           &su, err);
      r->surface = su.z;
      r->surface_sd = su.sd;
      o.h_over_r = fmin(2.0, t->h_end + (su.z_max - su.z) / (0.5 * ind->D * D_MEAN));
      dem_scene_free(s0);
    }
  }
  dem_scene *sc = rc ? NULL : dem_scene_restore(b->path, &o, &hk, err);
  if (!rc && !sc) rc = err->code;
  if (!rc) {
    dem_sim *s = dem_scene_sim(sc);
    dem_sim_stats st0;
    dem_sim_get_stats(s, &st0);
    if (!rc) rc = dem_scene_indent(sc, err);
    dem_sim_stats st;
    dem_sim_get_stats(s, &st);
    r->steps = st.steps - st0.steps;
    r->peak_overlap = st.peak_overlap_frac;
    dem_scene_info in;
    dem_scene_get_info(sc, &in);
    r->dt = in.dt;
    if (!rc) rc = series_extract(h, r, dem_scene_series(sc), err);
  }
  dem_scene_free(sc);
  r->wall_s = vh_now() - t0;
  r->status = rc;
  if (rc) snprintf(r->error, sizeof r->error, "%.40s: %.590s", dem_strerror(rc), err->msg);
  /* Kept for later invocations: a finished run, or one the engine's own checks stopped (the
   * same code stops it again at the same step); not an interruption or a resource error. */
  if (cpath[0] && (rc == DEM_OK || rc == DEM_ERUNAWAY || rc == DEM_EUNSTABLE ||
                   rc == DEM_ENONFINITE || rc == DEM_EPHYSICS)) {
    dem_err e2 = {0};
    if (vh_cache_save(h, cpath, b->path, r, &e2))
      vh_log(h, "run %d: not kept: %s", h->nruns - 1, e2.msg);
  }
  if (rc) {
    vh_log(h, "run %d FAILED: %s", h->nruns - 1, r->error);
    *err = (dem_err){0};
    return h->nruns - 1;
  }
  run_stats(h, r);
  vh_log(h, "run %d: %zu samples to h/r %.3f, H plateau %.0f +- %.0f Pa (sd %.0f), bin p %.0f Pa, "
         "%.0f s, %ld steps", h->nruns - 1, r->n, r->n ? r->hr[r->n - 1] : 0.0, r->sH.mean,
         r->sH.se, r->sH.sd, r->sp.mean, r->wall_s, r->steps);
  return h->nruns - 1;
}
