/* Config: the targets list. A target's data come from a file (through the project's CSV loader,
 * dem/refdata.h), from inline arrays named like the file's columns, or, for a curve, from an
 * impact of another law (generate.c). */
#include <ctype.h>
#include <errno.h>
#include <libconfig.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "config_priv.h"
#include "targets_io.h"

static const char *const type_names[] = {"curve", "sticking", "restitution", "unloading"};
static const int type_ncols[] = {2, 2, 2, 4};
static const char *const type_cols[][4] = {{"alpha", "f", NULL, NULL},
                                           {"R", "v_stick", NULL, NULL},
                                           {"v", "e", NULL, NULL},
                                           {"alpha_max", "f_max", "alpha_p", "f_pulloff"}};

/* Inline arrays of numbers. */
static int read_array(const cal_cfg_ctx *cx, const config_setting_t *g, const char *key,
                      const char *field, double **out, int *n) {
  const config_setting_t *a = config_setting_get_member(g, key);
  if (!a) return DEM_OK;
  if (!config_setting_is_array(a) && !config_setting_is_list(a))
    return cal_cfg_fail(cx, a, field, DEM_EPARSE, "expected an array [ ... ] of numbers");
  int len = config_setting_length(a);
  *out = calloc((size_t)(len > 0 ? len : 1), sizeof **out);
  if (!*out) return cal_cfg_fail(cx, a, field, DEM_ENOMEM, "out of memory");
  for (int i = 0; i < len; i++) {
    const config_setting_t *e = config_setting_get_elem(a, (unsigned)i);
    int t = config_setting_type(e);
    if (t == CONFIG_TYPE_FLOAT)
      (*out)[i] = config_setting_get_float(e);
    else if (t == CONFIG_TYPE_INT || t == CONFIG_TYPE_INT64)
      (*out)[i] = (double)config_setting_get_int64(e);
    else
      return cal_cfg_fail(cx, a, field, DEM_EPARSE, "element %d is not a number", i);
    if (!isfinite((*out)[i])) return cal_cfg_fail(cx, a, field, DEM_ENONFINITE, "element %d", i);
  }
  *n = len;
  return DEM_OK;
}

int cal_cfg_read_target(const cal_cfg_ctx *cx, cal_config *c, const config_setting_t *g, int i) {
  cal_target *t = &c->t[i];
  char field[96];
  int rc;
  const char *s = NULL;
  t->line = cal_cfg_line_of(g);
  t->weight = 1.0;
  t->mode = CAL_CURVE_POINTS;
  t->grid = 50;
  t->v_lo = 1e-3;
  t->v_hi = 100.0;
  t->tol = 1e-4;
  dem_params_init(&t->over);
  snprintf(field, sizeof field, "targets[%d].type", i);
  if (!cal_cfg_get_str(cx, g, "type", field, &s, &rc))
    return rc ? rc : cal_cfg_fail(cx, g, field, DEM_EMISSING,
                          "missing (curve, sticking, restitution, unloading)");
  int ty = -1;
  for (int k = 0; k < 4; k++)
    if (strcmp(s, type_names[k]) == 0) ty = k;
  if (ty < 0)
    return cal_cfg_fail(cx, config_setting_get_member(g, "type"), field, DEM_EINVAL,
                "'%s' is not curve, sticking, restitution or unloading", s);
  t->type = (cal_ttype)ty;
  snprintf(t->name, sizeof t->name, "%s%d", type_names[ty], i);
  snprintf(field, sizeof field, "targets[%d].name", i);
  if (cal_cfg_get_str(cx, g, "name", field, &s, &rc)) {
    for (const char *p = s; *p; p++)
      if (!(isalnum((unsigned char)*p) || *p == '-' || *p == '_' || *p == '.'))
        return cal_cfg_fail(cx, config_setting_get_member(g, "name"), field, DEM_EINVAL,
                    "'%s': use letters, digits, '-', '_', '.' only (it names output files)", s);
    snprintf(t->name, sizeof t->name, "%s", s);
  }
  if (rc) return rc;
  snprintf(field, sizeof field, "targets[%d].weight", i);
  cal_cfg_get_num(cx, g, "weight", field, &t->weight, &rc);
  if (rc) return rc;
  if (!(t->weight > 0.0))
    return cal_cfg_fail(cx, config_setting_get_member(g, "weight"), field, DEM_ERANGE,
                "must be > 0 (%g)", t->weight);
  snprintf(field, sizeof field, "targets[%d].geometry", i);
  if (cal_cfg_get_str(cx, g, "geometry", field, &s, &rc)) {
    if (strcmp(s, "wall") == 0)
      t->pair = 0;
    else if (strcmp(s, "pair") == 0)
      t->pair = 1;
    else
      return cal_cfg_fail(cx, config_setting_get_member(g, "geometry"), field, DEM_EINVAL,
                  "'%s' is neither \"wall\" nor \"pair\"", s);
  }
  if (rc) return rc;
  if (t->type == CAL_T_CURVE) {
    snprintf(field, sizeof field, "targets[%d].mode", i);
    if (cal_cfg_get_str(cx, g, "mode", field, &s, &rc)) {
      if (strcmp(s, "points") == 0)
        t->mode = CAL_CURVE_POINTS;
      else if (strcmp(s, "grid") == 0)
        t->mode = CAL_CURVE_GRID;
      else if (strcmp(s, "summary") == 0)
        t->mode = CAL_CURVE_SUMMARY;
      else
        return cal_cfg_fail(cx, config_setting_get_member(g, "mode"), field, DEM_EINVAL,
                    "'%s' is not points, grid or summary", s);
    }
    if (rc) return rc;
    snprintf(field, sizeof field, "targets[%d].grid", i);
    cal_cfg_get_int(cx, g, "grid", field, 2, 100000, &t->grid, &rc);
    if (rc) return rc;
  }
  if (t->type == CAL_T_STICKING) {
    snprintf(field, sizeof field, "targets[%d].v_lo", i);
    cal_cfg_get_num(cx, g, "v_lo", field, &t->v_lo, &rc);
    if (rc) return rc;
    snprintf(field, sizeof field, "targets[%d].v_hi", i);
    cal_cfg_get_num(cx, g, "v_hi", field, &t->v_hi, &rc);
    if (rc) return rc;
    if (!(t->v_lo > 0.0 && t->v_lo < t->v_hi))
      return cal_cfg_fail(cx, g, field, DEM_ERANGE, "need 0 < v_lo < v_hi (v_lo = %g, v_hi = %g)",
                  t->v_lo, t->v_hi);
    snprintf(field, sizeof field, "targets[%d].tol", i);
    cal_cfg_get_num(cx, g, "tol", field, &t->tol, &rc);
    if (rc) return rc;
    if (!(t->tol > 0.0 && t->tol < 0.1))
      return cal_cfg_fail(cx, config_setting_get_member(g, "tol"), field, DEM_ERANGE,
                  "%g outside (0, 0.1)", t->tol);
  }
  const config_setting_t *set = config_setting_get_member(g, "set");
  if (set) {
    snprintf(field, sizeof field, "targets[%d].set", i);
    if ((rc = cal_cfg_read_fixed(cx, c, set, field, &t->over, 1))) return rc;
  }
  /* The data: a file (through dem/refdata.h), inline arrays named like its columns, or a
   * curve generated by another law. */
  int nc = type_ncols[ty];
  double **dst[4] = {&t->x, &t->y, &t->z, &t->w};
  const char *cols[4];
  for (int k = 0; k < 4; k++) cols[k] = type_cols[ty][k];
  const char *file = NULL;
  snprintf(field, sizeof field, "targets[%d].reference_law", i);
  if (cal_cfg_get_str(cx, g, "reference_law", field, &s, &rc)) {
    const config_setting_t *rl = config_setting_get_member(g, "reference_law");
    if (ty != CAL_T_CURVE)
      return cal_cfg_fail(cx, rl, field, DEM_EUNSUPPORTED, "only a curve target can be generated");
    if (!dem_contact_law_find(s))
      return cal_cfg_fail(cx, rl, field, DEM_ENOTFOUND, "unknown law '%s'", s);
    snprintf(t->gen_law, sizeof t->gen_law, "%s", s);
    snprintf(field, sizeof field, "targets[%d].v_impact", i);
    if (!cal_cfg_get_num(cx, g, "v_impact", field, &t->gen_v, &rc) || !(t->gen_v > 0.0))
      return rc ? rc : cal_cfg_fail(cx, g, field, DEM_EMISSING, "a generated curve needs v_impact > 0 (m/s)");
    t->gen_samples = 400;
    snprintf(field, sizeof field, "targets[%d].samples", i);
    cal_cfg_get_int(cx, g, "samples", field, 10, 1000000, &t->gen_samples, &rc);
    if (rc) return rc;
    const config_setting_t *rs = config_setting_get_member(g, "reference_set");
    dem_params_init(&t->gen_set);
    snprintf(field, sizeof field, "targets[%d].reference_set", i);
    if (!rs) return cal_cfg_fail(cx, g, field, DEM_EMISSING, "a generated curve needs reference_set = { ... }");
    if (config_setting_type(rs) != CONFIG_TYPE_GROUP)
      return cal_cfg_fail(cx, rs, field, DEM_EPARSE, "expected a group { key = value; ... }");
    for (int k = 0; k < config_setting_length(rs); k++) {
      const config_setting_t *e = config_setting_get_elem(rs, (unsigned)k);
      char f2[160], origin[DEM_ORIGIN_LEN];
      double v;
      snprintf(f2, sizeof f2, "%s.%s", field, config_setting_name(e));
      if (!cal_cfg_get_num(cx, rs, config_setting_name(e), f2, &v, &rc))
        return rc ? rc : cal_cfg_fail(cx, e, f2, DEM_EPARSE, "expected a number");
      snprintf(origin, sizeof origin, "%s:%d", cx->file, cal_cfg_line_of(e));
      dem_err e2 = {0};
      if (dem_params_set(&t->gen_set, config_setting_name(e), v, origin, &e2))
        return cal_cfg_fail(cx, e, f2, e2.code, "%s", e2.msg);
    }
    dem_err e2 = {0};
    if ((rc = cal_generate_reference(c, t, &e2)))
      return cal_cfg_fail(cx, rl, field, rc, "cannot generate the reference curve: %s", e2.msg);
  } else if (rc) {
    return rc;
  } else if (snprintf(field, sizeof field, "targets[%d].file", i),
             cal_cfg_get_str(cx, g, "file", field, &file, &rc)) {
    size_t need = file[0] == '/' ? strlen(file) : strlen(c->dir) + 1 + strlen(file);
    if (need >= sizeof t->file)
      return cal_cfg_fail(cx, config_setting_get_member(g, "file"), field, DEM_ERANGE, "path too long");
    if (file[0] == '/')
      memcpy(t->file, file, strlen(file) + 1);
    else {
      memcpy(t->file, c->dir, strlen(c->dir));
      t->file[strlen(c->dir)] = '/';
      memcpy(t->file + strlen(c->dir) + 1, file, strlen(file) + 1);
    }
    const config_setting_t *cl = config_setting_get_member(g, "columns");
    if (cl) {
      char cf[96];
      snprintf(cf, sizeof cf, "targets[%d].columns", i);
      if (!config_setting_is_array(cl) || config_setting_length(cl) != nc ||
          config_setting_type(config_setting_get_elem(cl, 0)) != CONFIG_TYPE_STRING)
        return cal_cfg_fail(cx, cl, cf, DEM_EPARSE, "expected an array of %d column names (%s, %s%s%s%s%s)",
                    nc, cols[0], cols[1], nc > 2 ? ", " : "", nc > 2 ? cols[2] : "",
                    nc > 2 ? ", " : "", nc > 2 ? cols[3] : "");
      for (int k = 0; k < nc; k++) cols[k] = config_setting_get_string_elem(cl, (unsigned)k);
    }
    dem_err e2 = {0};
    if (access(t->file, R_OK) != 0)
      return cal_cfg_fail(cx, config_setting_get_member(g, "file"), field, DEM_EIO,
                  "cannot read target file '%s': %s", t->file, strerror(errno));
    double *out[4] = {NULL, NULL, NULL, NULL};
    if ((rc = cal_target_read_file(t->file, cols, nc, out, &t->n, &e2)))
      return cal_cfg_fail(cx, config_setting_get_member(g, "file"), field, rc, "%s", e2.msg);
    for (int k = 0; k < nc; k++) *dst[k] = out[k];
  } else if (rc) {
    return rc;
  } else {
    int n0 = -1;
    for (int k = 0; k < nc; k++) {
      char fx[96];
      int nk = -1;
      snprintf(fx, sizeof fx, "targets[%d].%s", i, cols[k]);
      if ((rc = read_array(cx, g, cols[k], fx, dst[k], &nk))) return rc;
      if (nk < 0)
        return cal_cfg_fail(cx, g, fx, DEM_EMISSING,
                    "a %s target needs file = \"...\", or inline arrays of %s%s%s%s%s%s%s",
                    type_names[ty], cols[0], nc > 2 ? ", " : " and ", cols[1], nc > 2 ? ", " : "",
                    nc > 2 ? cols[2] : "", nc > 2 ? " and " : "", nc > 2 ? cols[3] : "");
      if (k > 0 && nk != n0)
        return cal_cfg_fail(cx, config_setting_get_member(g, cols[k]), fx, DEM_EINVAL,
                    "%d values but %s has %d", nk, cols[0], n0);
      n0 = nk;
    }
    t->n = n0;
  }
  snprintf(field, sizeof field, "targets[%d]", i);
  int need = t->type == CAL_T_CURVE ? 2 : 1;
  if (t->n < need)
    return cal_cfg_fail(cx, g, field, DEM_EINVAL, "%d reference points (need at least %d)", t->n, need);
  for (int k = 0; k < t->n && t->type != CAL_T_CURVE; k++)
    for (int q = 0; q < nc; q++)
      if (!((*dst[q])[k] > 0.0))
        return cal_cfg_fail(cx, g, field, DEM_ERANGE, "row %d: %s = %g must be > 0", k, cols[q],
                    (*dst[q])[k]);
  return DEM_OK;
}
