/* Scene checkpoints (dem/scene.h): the scene state as the caller blob of an engine
 * checkpoint (dem/checkpoint.h), restore with an override of the stages not yet run.
 *
 * Blob layout (native byte order and doubles, like the rest of the checkpoint):
 *   magic   char[16]  "dem-scene" (zero padded)
 *   version uint32    SCENE_BLOB_VERSION
 *   count   uint32    number of records
 *   length  uint64    total length of the blob in bytes (a truncated blob is rejected)
 *   records           each: name (uint8 length + bytes), type (uint8: 0 double, 1 int64,
 *                     2 bytes), count (uint64), then count values
 * Records are looked up by name, so a field added later makes an older blob fail with a
 * message naming the missing field rather than being misread. Every field of
 * dem_scene_config is listed in cfg_fields below (a new config field must be added there:
 * it is then saved, restored and compared against the override).
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dem/checkpoint.h"
#include "scene_internal.h"

#define SCENE_MAGIC "dem-scene"
/* 2 (2026-12-02): the unload stage ends with the bed at rest (its relax phase, scene.c; the
 * state gains t_rest); a version-1 unloaded bed was saved while it flew off the base, so it
 * is not read. */
/* 3 (2026-12-03): the consolidation loads at constant strain rate up to sigma_pre and holds
 * it with a servo whose set-point correction cannot wind up (the state gains ki); a version-2
 * bed was pre-consolidated to 12-13.5 kPa instead of 10 (docs/scene.md), so it is not read. */
#define SCENE_BLOB_VERSION 3

enum { T_F64 = 0, T_I64 = 1, T_BYTES = 2 };

/* ---- the config fields: name, offset, kind, and whether an override may change it ---- */
enum { K_DBL, K_INT, K_LONG, K_ULONG, K_PARAMS };
enum {
  OV_NEVER = 0, /* the bed: must equal the stored value */
  OV_LIMIT,     /* a stopping criterion of settle/consolidate: any time */
  OV_INDENT,    /* the indentation: until the indent stage has begun */
  OV_FREE       /* numerics without effect on the trajectory's physics */
};
typedef struct cfg_field {
  const char *name;
  size_t off;
  int kind, ov;
} cfg_field;
#define F(name, kind, ov) {#name, offsetof(dem_scene_config, name), kind, ov}
static const cfg_field cfg_fields[] = {
    F(materials, K_INT, OV_NEVER),
    F(pp, K_PARAMS, OV_NEVER),
    F(pw, K_PARAMS, OV_NEVER),
    F(pi, K_PARAMS, OV_INDENT),
    F(rho, K_DBL, OV_NEVER),
    F(rho_wall, K_DBL, OV_NEVER),
    F(d_mean, K_DBL, OV_NEVER),
    F(psd, K_INT, OV_NEVER),
    F(die_diameter, K_DBL, OV_NEVER),
    F(bed_height, K_DBL, OV_NEVER),
    F(phi_est, K_DBL, OV_NEVER),
    F(n_particles, K_LONG, OV_NEVER),
    F(fill_fraction, K_DBL, OV_NEVER),
    F(seed, K_ULONG, OV_NEVER),
    F(settle_ke, K_DBL, OV_LIMIT),
    F(settle_min_time, K_DBL, OV_LIMIT),
    F(settle_max_time, K_DBL, OV_LIMIT),
    F(sigma_pre, K_DBL, OV_NEVER),
    F(strain_rate, K_DBL, OV_NEVER),
    F(servo_band, K_DBL, OV_NEVER),
    F(servo_steps, K_DBL, OV_NEVER),
    F(hold_time, K_DBL, OV_LIMIT),
    F(hold_tol, K_DBL, OV_LIMIT),
    F(shape, K_INT, OV_INDENT),
    F(indenter_diameter, K_DBL, OV_INDENT),
    F(indenter_length, K_DBL, OV_INDENT),
    F(indent_rate, K_DBL, OV_INDENT),
    F(h_over_r, K_DBL, OV_INDENT),
    F(unload, K_INT, OV_INDENT),
    F(dt_factor, K_DBL, OV_INDENT),
    F(stiffness_scale, K_DBL, OV_NEVER),
    F(skin, K_DBL, OV_NEVER),
    F(threads, K_INT, OV_FREE),
    F(sample_interval, K_DBL, OV_FREE),
    F(output_stress, K_INT, OV_FREE),
};
#undef F
#define NCFG (sizeof cfg_fields / sizeof cfg_fields[0])

/* ---- writing records ---- */
typedef struct wbuf {
  unsigned char *b;
  size_t n, cap;
  uint32_t count;
  int oom;
} wbuf;

static void wput(wbuf *w, const void *data, size_t len) {
  if (w->oom) return;
  if (w->n + len > w->cap) {
    size_t c = w->cap ? w->cap : 4096;
    while (c < w->n + len) c *= 2;
    unsigned char *nb = realloc(w->b, c);
    if (!nb) {
      w->oom = 1;
      return;
    }
    w->b = nb;
    w->cap = c;
  }
  if (len) memcpy(w->b + w->n, data, len);
  w->n += len;
}

static void rec(wbuf *w, const char *name, int type, uint64_t count, const void *data) {
  uint8_t nl = (uint8_t)strlen(name), t = (uint8_t)type;
  size_t sz = type == T_BYTES ? 1 : 8;
  wput(w, &nl, 1);
  wput(w, name, nl);
  wput(w, &t, 1);
  wput(w, &count, 8);
  wput(w, data, (size_t)count * sz);
  w->count++;
}
static void rec_d(wbuf *w, const char *name, double v) { rec(w, name, T_F64, 1, &v); }
static void rec_i(wbuf *w, const char *name, int64_t v) { rec(w, name, T_I64, 1, &v); }

/* A parameter set as bytes: n entries of key[DEM_KEY_LEN], value (8 bytes),
 * origin[DEM_ORIGIN_LEN]. */
#define PREC (DEM_KEY_LEN + 8 + DEM_ORIGIN_LEN)
static void rec_params(wbuf *w, const char *name, const dem_params *ps) {
  unsigned char buf[DEM_PARAMS_MAX * PREC];
  memset(buf, 0, sizeof buf);
  int n = ps->n < 0 ? 0 : (ps->n > DEM_PARAMS_MAX ? DEM_PARAMS_MAX : ps->n);
  for (int k = 0; k < n; k++) {
    unsigned char *e = buf + (size_t)k * PREC;
    memcpy(e, ps->p[k].key, DEM_KEY_LEN);
    memcpy(e + DEM_KEY_LEN, &ps->p[k].value, 8);
    memcpy(e + DEM_KEY_LEN + 8, ps->p[k].origin, DEM_ORIGIN_LEN);
  }
  rec(w, name, T_BYTES, (uint64_t)n * PREC, buf);
}

static void cfg_write(wbuf *w, const dem_scene_config *c) {
  char key[64];
  for (size_t k = 0; k < NCFG; k++) {
    const cfg_field *f = &cfg_fields[k];
    const char *at = (const char *)c + f->off;
    snprintf(key, sizeof key, "cfg.%s", f->name);
    switch (f->kind) {
    case K_DBL: rec_d(w, key, *(const double *)at); break;
    case K_INT: rec_i(w, key, *(const int *)at); break;
    case K_LONG: rec_i(w, key, *(const long *)at); break;
    case K_ULONG: rec_i(w, key, (int64_t)*(const unsigned long *)at); break;
    default: rec_params(w, key, (const dem_params *)at); break;
    }
  }
}

int dem_scene_save(const dem_scene *sc, const char *path, dem_err *err) {
  wbuf w = {0};
  unsigned char head[32] = {0};
  wput(&w, head, sizeof head); /* filled in at the end */
  cfg_write(&w, &sc->cfg);
  rec_i(&w, "reached", sc->reached);
  rec_i(&w, "stage", sc->stage);
  rec_i(&w, "sub", sc->sub);
  rec_i(&w, "resume", sc->resume);
  rec_i(&w, "pending", sc->pending);
  rec_i(&w, "since_row", sc->since_row);
  int64_t idx[7] = {sc->mat_p, sc->mat_w, sc->mat_i, sc->w_base, sc->w_die, sc->w_piston,
                    sc->w_ind};
  rec(&w, "indices", T_I64, 7, idx);
  const double d[] = {sc->die_radius, sc->fill_top, sc->mean_d, sc->sd_d, sc->dt,
                      sc->k_max, sc->m_mean, sc->bed_top, sc->phi, sc->surface,
                      sc->v_piston, sc->v_ind, sc->ind_r, sc->next_snap, sc->t0,
                      sc->t_max, sc->z_half, sc->f_half, sc->t_in, sc->f_set, sc->gain,
                      sc->t_rest, sc->ki};
  rec(&w, "state", T_F64, sizeof d / sizeof d[0], d);
  const long nr = dem_table_nrows(sc->series);
  const int nc = dem_table_ncols(sc->series);
  rec_i(&w, "series_ncols", nc);
  rec_i(&w, "series_nrows", nr);
  double *tab = malloc(((size_t)nr * (size_t)nc + 1) * sizeof *tab);
  if (!tab) w.oom = 1;
  else {
    for (long r = 0; r < nr; r++)
      for (int q = 0; q < nc; q++) tab[(size_t)r * (size_t)nc + (size_t)q] = dem_table_get(sc->series, r, q);
    rec(&w, "series", T_F64, (uint64_t)nr * (uint64_t)nc, tab);
    free(tab);
  }
  if (w.oom) {
    free(w.b);
    return dem_err_set(err, DEM_ENOMEM, "%s: scene checkpoint: out of memory", path);
  }
  memcpy(w.b, SCENE_MAGIC, strlen(SCENE_MAGIC));
  uint32_t v = SCENE_BLOB_VERSION;
  uint64_t len = w.n;
  memcpy(w.b + 16, &v, 4);
  memcpy(w.b + 20, &w.count, 4);
  memcpy(w.b + 24, &len, 8);
  int rc = dem_sim_checkpoint_write(sc->sim, path, w.b, w.n, err);
  free(w.b);
  return rc;
}

/* ---- reading records ---- */
typedef struct rrec {
  char name[256];
  int type;
  uint64_t count;
  const unsigned char *data;
} rrec;

typedef struct rblob {
  rrec *r;
  uint32_t n;
  const char *path;
  dem_err *err;
} rblob;

static int parse(rblob *rb, const unsigned char *b, size_t len) {
  const char *path = rb->path;
  if (!b || len < 32 || memcmp(b, SCENE_MAGIC, strlen(SCENE_MAGIC)) != 0)
    return dem_err_set(rb->err, DEM_EINVAL,
                       "%s: an engine checkpoint without a scene state (no '%s' blob): not "
                       "written by dem_scene_save / dem-run",
                       path, SCENE_MAGIC);
  uint32_t v, count;
  uint64_t total;
  memcpy(&v, b + 16, 4);
  memcpy(&count, b + 20, 4);
  memcpy(&total, b + 24, 8);
  if (v != SCENE_BLOB_VERSION)
    return dem_err_set(rb->err, DEM_EUNSUPPORTED,
                       "%s: scene state version %u; this build reads version %d", path,
                       (unsigned)v, SCENE_BLOB_VERSION);
  if (total != len)
    return dem_err_set(rb->err, DEM_EPARSE,
                       "%s: scene state length %llu bytes, the header says %llu (truncated "
                       "or damaged)",
                       path, (unsigned long long)len, (unsigned long long)total);
  if (count > 100000)
    return dem_err_set(rb->err, DEM_EPARSE, "%s: scene state: %u records", path, (unsigned)count);
  rb->r = calloc(count ? count : 1, sizeof *rb->r);
  if (!rb->r) return dem_err_set(rb->err, DEM_ENOMEM, "%s: out of memory", path);
  size_t at = 32;
  for (uint32_t k = 0; k < count; k++) {
    rrec *r = &rb->r[k];
    if (at + 1 > len) goto short_;
    uint8_t nl = b[at++];
    if (at + nl + 1 + 8 > len) goto short_;
    memcpy(r->name, b + at, nl);
    r->name[nl] = 0;
    at += nl;
    r->type = b[at++];
    memcpy(&r->count, b + at, 8);
    at += 8;
    if (r->type < T_F64 || r->type > T_BYTES)
      return dem_err_set(rb->err, DEM_EPARSE, "%s: scene state record '%s': type %d", path,
                         r->name, r->type);
    uint64_t sz = r->type == T_BYTES ? 1 : 8;
    if (r->count > (len - at) / sz) goto short_;
    r->data = b + at;
    at += (size_t)(r->count * sz);
    rb->n++;
  }
  if (at != len)
    return dem_err_set(rb->err, DEM_EPARSE, "%s: scene state: %zu bytes after the records",
                       path, len - at);
  return DEM_OK;
short_:
  return dem_err_set(rb->err, DEM_EPARSE, "%s: scene state truncated in record %u of %u",
                     path, (unsigned)rb->n + 1, (unsigned)count);
}

static const rrec *find(rblob *rb, const char *name, int type, uint64_t count) {
  for (uint32_t k = 0; k < rb->n; k++)
    if (!strcmp(rb->r[k].name, name)) {
      if (rb->r[k].type != type || (count && rb->r[k].count != count)) {
        dem_err_set(rb->err, DEM_EPARSE,
                    "%s: scene state record '%s' has type %d and %llu values (expected type "
                    "%d, %llu values)",
                    rb->path, name, rb->r[k].type, (unsigned long long)rb->r[k].count, type,
                    (unsigned long long)count);
        return NULL;
      }
      return &rb->r[k];
    }
  dem_err_set(rb->err, DEM_EPARSE,
              "%s: scene state record '%s' is missing (written by another version?)",
              rb->path, name);
  return NULL;
}
static int get_d(rblob *rb, const char *name, double *v) {
  const rrec *r = find(rb, name, T_F64, 1);
  if (!r) return rb->err->code;
  memcpy(v, r->data, 8);
  return DEM_OK;
}
static int get_i(rblob *rb, const char *name, int64_t *v) {
  const rrec *r = find(rb, name, T_I64, 1);
  if (!r) return rb->err->code;
  memcpy(v, r->data, 8);
  return DEM_OK;
}
static int get_params(rblob *rb, const char *name, dem_params *ps) {
  for (uint32_t k = 0; k < rb->n; k++)
    if (!strcmp(rb->r[k].name, name)) {
      const rrec *r = &rb->r[k];
      if (r->type != T_BYTES || r->count % PREC || r->count / PREC > DEM_PARAMS_MAX)
        return dem_err_set(rb->err, DEM_EPARSE, "%s: scene state record '%s': %llu bytes",
                           rb->path, name, (unsigned long long)r->count);
      dem_params_init(ps);
      ps->n = (int)(r->count / PREC);
      for (int q = 0; q < ps->n; q++) {
        const unsigned char *e = r->data + (size_t)q * PREC;
        memcpy(ps->p[q].key, e, DEM_KEY_LEN);
        ps->p[q].key[DEM_KEY_LEN - 1] = 0;
        memcpy(&ps->p[q].value, e + DEM_KEY_LEN, 8);
        memcpy(ps->p[q].origin, e + DEM_KEY_LEN + 8, DEM_ORIGIN_LEN);
        ps->p[q].origin[DEM_ORIGIN_LEN - 1] = 0;
      }
      return DEM_OK;
    }
  find(rb, name, T_BYTES, 0);
  return rb->err->code;
}

static int cfg_read(rblob *rb, dem_scene_config *c) {
  char key[64];
  int rc;
  for (size_t k = 0; k < NCFG; k++) {
    const cfg_field *f = &cfg_fields[k];
    char *at = (char *)c + f->off;
    snprintf(key, sizeof key, "cfg.%s", f->name);
    double d = 0;
    int64_t i = 0;
    switch (f->kind) {
    case K_DBL:
      if ((rc = get_d(rb, key, &d))) return rc;
      *(double *)at = d;
      break;
    case K_PARAMS:
      if ((rc = get_params(rb, key, (dem_params *)at))) return rc;
      break;
    default:
      if ((rc = get_i(rb, key, &i))) return rc;
      if (f->kind == K_INT) *(int *)at = (int)i;
      else if (f->kind == K_LONG) *(long *)at = (long)i;
      else *(unsigned long *)at = (unsigned long)i;
    }
  }
  return DEM_OK;
}

/* ---- the override ---- */
/* Same keys with the same values (order and origins do not matter). */
static int params_equal(const dem_params *a, const dem_params *b, const char **key) {
  for (int k = 0; k < a->n; k++) {
    double v;
    if (!dem_params_get(b, a->p[k].key, &v) || !(v == a->p[k].value)) {
      *key = a->p[k].key;
      return 0;
    }
  }
  for (int k = 0; k < b->n; k++)
    if (!dem_params_find(a, b->p[k].key)) {
      *key = b->p[k].key;
      return 0;
    }
  return 1;
}

static int field_equal(const cfg_field *f, const dem_scene_config *a,
                       const dem_scene_config *b, const char **key, double *va, double *vb) {
  const char *x = (const char *)a + f->off, *y = (const char *)b + f->off;
  *key = NULL;
  switch (f->kind) {
  case K_DBL:
    *va = *(const double *)x, *vb = *(const double *)y;
    return *va == *vb || (isnan(*va) && isnan(*vb));
  case K_INT: *va = *(const int *)x, *vb = *(const int *)y; return *va == *vb;
  case K_LONG: *va = (double)*(const long *)x, *vb = (double)*(const long *)y;
    return *(const long *)x == *(const long *)y;
  case K_ULONG: *va = (double)*(const unsigned long *)x, *vb = (double)*(const unsigned long *)y;
    return *(const unsigned long *)x == *(const unsigned long *)y;
  default: {
    int eq = params_equal((const dem_params *)x, (const dem_params *)y, key);
    if (!eq) {
      const dem_params *pa = (const dem_params *)x, *pb = (const dem_params *)y;
      *va = dem_params_get_or(pa, *key, NAN);
      *vb = dem_params_get_or(pb, *key, NAN);
    }
    return eq;
  }
  }
}

/* Check the override against the stored config c; on success copy the allowed fields. */
static int apply_override(dem_scene *sc, const dem_scene_config *ov, const char *path,
                          int *pi_changed, dem_err *err) {
  dem_scene_config *c = &sc->cfg;
  /* the indentation has begun (or is done): its fields are part of the trajectory */
  const int indent_begun = sc->reached >= DEM_SCENE_STAGE_INDENTED ||
                           (sc->reached == DEM_SCENE_STAGE_UNLOADED && sc->sub > 0);
  *pi_changed = 0;
  for (size_t k = 0; k < NCFG; k++) {
    const cfg_field *f = &cfg_fields[k];
    const char *key;
    double va = 0, vb = 0;
    if (field_equal(f, c, ov, &key, &va, &vb)) continue;
    char what[160];
    if (key) snprintf(what, sizeof what, "%s.%s", f->name, key);
    else snprintf(what, sizeof what, "%s", f->name);
    if (f->ov == OV_NEVER)
      return dem_err_set(err, DEM_EINVAL,
                         "%s: the override changes %s (stored %g, given %g): only the "
                         "indentation (shape, indenter_diameter, indenter_length, indent_rate, "
                         "h_over_r, unload, pi, dt_factor), threads, sample_interval, "
                         "output_stress and the settle/hold limits may differ from the "
                         "checkpoint's config",
                         path, what, va, vb);
    if (f->ov == OV_INDENT && indent_begun)
      return dem_err_set(err, DEM_EINVAL,
                         "%s: the override changes %s (stored %g, given %g) but the "
                         "checkpoint's indentation has already begun",
                         path, what, va, vb);
    /* new indenter coefficients or time-step factor: interactions, k_max and dt anew */
    if (f->kind == K_PARAMS || f->off == offsetof(dem_scene_config, dt_factor))
      *pi_changed = 1;
  }
  dem_scene_config merged = *ov;
  if (dem_scene_config_check(&merged, err)) {
    char msg[sizeof err->msg];
    memcpy(msg, err->msg, sizeof msg);
    return dem_err_set(err, err->code, "%s: override: %s", path, msg);
  }
  /* the origins of the stored parameter sets stay (the values are equal) except for pi */
  merged.pp = c->pp;
  merged.pw = c->pw;
  *c = merged;
  return DEM_OK;
}

dem_scene *dem_scene_restore(const char *path, const dem_scene_config *override,
                             const dem_scene_hooks *h, dem_err *err) {
  void *blob = NULL;
  size_t blen = 0;
  dem_sim *sim = dem_sim_checkpoint_read(path, &blob, &blen, err);
  if (!sim) return NULL;
  rblob rb = {NULL, 0, path, err};
  dem_scene *sc = calloc(1, sizeof *sc);
  double *tab = NULL;
  if (!sc) {
    dem_err_set(err, DEM_ENOMEM, "%s: out of memory", path);
    goto fail;
  }
  sc->sim = sim;
  sim = NULL;
  if (h) sc->hooks = *h;
  if (parse(&rb, blob, blen) || cfg_read(&rb, &sc->cfg)) goto fail;
  int64_t iv[6];
  static const char *const inames[] = {"reached", "stage", "sub", "resume", "pending",
                                       "since_row"};
  for (int k = 0; k < 6; k++)
    if (get_i(&rb, inames[k], &iv[k])) goto fail;
  if (iv[0] < DEM_SCENE_STAGE_NONE || iv[0] > DEM_SCENE_STAGE_INDENTED || iv[1] < 0 ||
      iv[1] > 4 || iv[2] < 0 || iv[2] > 2 || iv[4] < 0 || iv[5] < 0) {
    dem_err_set(err, DEM_EPARSE,
                "%s: scene state: stage reached %lld, stage %lld, phase %lld, pending %lld, "
                "since_row %lld (out of range)",
                path, (long long)iv[0], (long long)iv[1], (long long)iv[2], (long long)iv[4],
                (long long)iv[5]);
    goto fail;
  }
  sc->reached = (int)iv[0];
  sc->stage = (int)iv[1];
  sc->sub = (int)iv[2];
  sc->resume = iv[3] != 0;
  sc->pending = (long)iv[4];
  sc->since_row = (long)iv[5];
  const rrec *r = find(&rb, "indices", T_I64, 7);
  if (!r) goto fail;
  int64_t idx[7];
  memcpy(idx, r->data, sizeof idx);
  dem_wall_spec ws;
  int nwall = 0;
  while (dem_sim_wall(sc->sim, nwall, &ws) == DEM_OK) nwall++;
  const int nmat = 3;
  for (int k = 0; k < 7; k++)
    if (idx[k] < (k < 3 ? 0 : -1) || idx[k] >= (k < 3 ? nmat : nwall)) {
      dem_err_set(err, DEM_EPARSE, "%s: scene state: index %d = %lld (materials %d, walls %d)",
                  path, k, (long long)idx[k], nmat, nwall);
      goto fail;
    }
  sc->mat_p = (int)idx[0], sc->mat_w = (int)idx[1], sc->mat_i = (int)idx[2];
  sc->w_base = (int)idx[3], sc->w_die = (int)idx[4], sc->w_piston = (int)idx[5];
  sc->w_ind = (int)idx[6];
  if (!(r = find(&rb, "state", T_F64, 23))) goto fail;
  double d[23];
  memcpy(d, r->data, sizeof d);
  sc->die_radius = d[0], sc->fill_top = d[1], sc->mean_d = d[2], sc->sd_d = d[3];
  sc->dt = d[4], sc->k_max = d[5], sc->m_mean = d[6], sc->bed_top = d[7], sc->phi = d[8];
  sc->surface = d[9], sc->v_piston = d[10], sc->v_ind = d[11], sc->ind_r = d[12];
  sc->next_snap = d[13], sc->t0 = d[14], sc->t_max = d[15], sc->z_half = d[16];
  sc->f_half = d[17], sc->t_in = d[18], sc->f_set = d[19], sc->gain = d[20];
  sc->t_rest = d[21], sc->ki = d[22];
  int64_t nc = 0, nr = 0;
  if (get_i(&rb, "series_ncols", &nc) || get_i(&rb, "series_nrows", &nr)) goto fail;
  if (!(sc->series = scene_series_create(err))) goto fail;
  /* a checkpoint written before the footprint columns (SCENE_NSERIES_V3) keeps its beds:
   * its rows are read with the appended columns NaN (not measured then) */
  const int nc_now = dem_table_ncols(sc->series);
  if ((nc != nc_now && nc != SCENE_NSERIES_V3) || nr < 0) {
    dem_err_set(err, DEM_EPARSE,
                "%s: scene state: the time series has %lld columns, this build reads %d or "
                "%d (written by another version?)",
                path, (long long)nc, nc_now, SCENE_NSERIES_V3);
    goto fail;
  }
  if (!(r = find(&rb, "series", T_F64, 0))) goto fail;
  if (r->count != (uint64_t)nr * (uint64_t)nc) {
    dem_err_set(err, DEM_EPARSE, "%s: scene state: %llu series values for %lld x %lld", path,
                (unsigned long long)r->count, (long long)nr, (long long)nc);
    goto fail;
  }
  tab = malloc((r->count ? r->count : 1) * sizeof *tab);
  if (!tab) {
    dem_err_set(err, DEM_ENOMEM, "%s: out of memory", path);
    goto fail;
  }
  memcpy(tab, r->data, (size_t)r->count * sizeof *tab);
  for (int64_t k = 0; k < nr; k++) {
    double row[SCENE_NSERIES]; /* nc_now: scene_series_create makes SCENE_NSERIES */
    for (int q = 0; q < nc_now; q++)
      row[q] = q < nc ? tab[(size_t)k * (size_t)nc + (size_t)q] : NAN;
    if (dem_table_append(sc->series, row, err)) goto fail;
  }
  /* the stored config must pass today's checks too */
  if (dem_scene_config_check(&sc->cfg, err)) {
    char msg[sizeof err->msg];
    memcpy(msg, err->msg, sizeof msg);
    dem_err_set(err, err->code, "%s: stored config: %s", path, msg);
    goto fail;
  }
  int pi_changed = 0;
  if (override && apply_override(sc, override, path, &pi_changed, err)) goto fail;
  if (pi_changed) {
    /* new particle-indenter coefficients: the three interactions again (the unchanged two
     * compile to the same coefficients), k_max and dt from all three */
    if (scene_interactions(sc, err)) {
      char msg[sizeof err->msg];
      memcpy(msg, err->msg, sizeof msg);
      dem_err_set(err, err->code, "%s: override: %s", path, msg);
      goto fail;
    }
    /* inside the consolidation servo: its gain from the new k_max (scene.c) */
    if (sc->reached == DEM_SCENE_STAGE_SETTLED && sc->sub == 2) {
      const double g0 = sc->gain;
      sc->gain = scene_servo_gain(sc);
      sc->ki *= sc->gain / g0; /* ki = t_sample gain K / 4 (scene_servo_ki) */
      if (dem_sim_set_wall_servo(sc->sim, sc->w_piston, sc->f_set, sc->gain, sc->v_piston,
                                 err))
        goto fail;
    }
  }
  if (dem_sim_set_threads(sc->sim, sc->cfg.threads, err)) goto fail;
  free(rb.r);
  free(tab);
  free(blob);
  return sc;
fail:
  free(rb.r);
  free(tab);
  free(blob);
  dem_sim_free(sim);
  dem_scene_free(sc);
  return NULL;
}

dem_scene_stage dem_scene_get_stage(const dem_scene *sc) {
  return (dem_scene_stage)sc->reached;
}
