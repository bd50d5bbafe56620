/* Calibration config files (libconfig syntax), validated once; every error names
 * "file:line: field: what is wrong". The format is documented in docs/calibration.md. */
#include <ctype.h>
#include <errno.h>
#include <libconfig.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <nlopt.h>

#include "cal.h"
#include "targets_io.h"

/* Scene keys a calibration may fix besides the law's coefficients (dem_impact_setup). */
static const char *const scene_keys[] = {"R", "rho", "E", "nu", NULL};

typedef struct ctx {
  const char *file;
  dem_err *err;
} ctx;

static int line_of(const config_setting_t *s) { return s ? (int)config_setting_source_line(s) : 0; }

static int fail(const ctx *cx, const config_setting_t *s, const char *field, int code,
                const char *fmt, ...) __attribute__((format(printf, 5, 6)));
static int fail(const ctx *cx, const config_setting_t *s, const char *field, int code,
                const char *fmt, ...) {
  char msg[DEM_ERRMSG_LEN];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return dem_err_set(cx->err, code, "%s:%d: %s: %s", cx->file, line_of(s), field, msg);
}

/* A number setting (int or float); 1 if present. */
static int get_num(const ctx *cx, const config_setting_t *grp, const char *key,
                   const char *field, double *v, int *rc) {
  const config_setting_t *s = config_setting_get_member(grp, key);
  *rc = DEM_OK;
  if (!s) return 0;
  switch (config_setting_type(s)) {
  case CONFIG_TYPE_INT: *v = (double)config_setting_get_int(s); break;
  case CONFIG_TYPE_INT64: *v = (double)config_setting_get_int64(s); break;
  case CONFIG_TYPE_FLOAT: *v = config_setting_get_float(s); break;
  default:
    *rc = fail(cx, s, field, DEM_EPARSE, "expected a number");
    return 0;
  }
  if (!isfinite(*v)) *rc = fail(cx, s, field, DEM_ENONFINITE, "not finite");
  return 1;
}

static int get_str(const ctx *cx, const config_setting_t *grp, const char *key,
                   const char *field, const char **v, int *rc) {
  const config_setting_t *s = config_setting_get_member(grp, key);
  *rc = DEM_OK;
  if (!s) return 0;
  if (config_setting_type(s) != CONFIG_TYPE_STRING) {
    *rc = fail(cx, s, field, DEM_EPARSE, "expected a string");
    return 0;
  }
  *v = config_setting_get_string(s);
  return 1;
}

static int get_int(const ctx *cx, const config_setting_t *grp, const char *key,
                   const char *field, int lo, int hi, int *v, int *rc) {
  double d;
  if (!get_num(cx, grp, key, field, &d, rc)) return 0;
  if (*rc) return 0;
  if (d != floor(d) || d < lo || d > hi) {
    *rc = fail(cx, config_setting_get_member(grp, key), field, DEM_ERANGE,
               "%g is not an integer in [%d, %d]", d, lo, hi);
    return 0;
  }
  *v = (int)d;
  return 1;
}

/* The allowed range of a law coefficient or scene key, for bounds checks. */
static const dem_coef_spec *coef_spec(const dem_law *law, const char *key) {
  for (int i = 0; i < law->ncoef; i++)
    if (strcmp(law->coef[i].key, key) == 0) return &law->coef[i];
  return NULL;
}

static int is_scene_key(const char *k) {
  for (const char *const *s = scene_keys; *s; s++)
    if (strcmp(*s, k) == 0) return 1;
  return 0;
}

static void law_keys(const dem_law *law, char *buf, size_t n) {
  size_t used = 0;
  buf[0] = '\0';
  for (int i = 0; i < law->ncoef && used + 8 < n; i++)
    used += (size_t)snprintf(buf + used, n - used, "%s%s", i ? ", " : "", law->coef[i].key);
}

static int read_fixed(const ctx *cx, cal_config *c, const config_setting_t *grp,
                      const char *field0, dem_params *ps, int scene_ok) {
  if (config_setting_type(grp) != CONFIG_TYPE_GROUP)
    return fail(cx, grp, field0, DEM_EPARSE, "expected a group { key = value; ... }");
  for (int i = 0; i < config_setting_length(grp); i++) {
    config_setting_t *s = config_setting_get_elem(grp, (unsigned)i);
    const char *k = config_setting_name(s);
    char field[128];
    snprintf(field, sizeof field, "%s.%s", field0, k);
    if (!dem_contact_law_has_coef(c->law, k) && !(scene_ok && is_scene_key(k))) {
      char keys[256];
      law_keys(c->law, keys, sizeof keys);
      return fail(cx, s, field, DEM_ENOTFOUND,
                  "law '%s' has no parameter '%s' (its parameters: %s; scene keys: R, rho, E, "
                  "nu)",
                  c->law->name, k, keys);
    }
    double v;
    int rc;
    if (!get_num(cx, grp, k, field, &v, &rc)) return rc ? rc : fail(cx, s, field, DEM_EPARSE, "expected a number");
    if (rc) return rc;
    char origin[DEM_ORIGIN_LEN];
    snprintf(origin, sizeof origin, "%s:%d", cx->file, line_of(s));
    dem_err e2 = {0};
    if (dem_params_set(ps, k, v, origin, &e2))
      return fail(cx, s, field, e2.code, "%s", e2.msg);
  }
  return DEM_OK;
}

static int read_free(const ctx *cx, cal_config *c, const config_setting_t *list) {
  if (config_setting_type(list) != CONFIG_TYPE_LIST)
    return fail(cx, list, "free", DEM_EPARSE, "expected a list ( { name = ...; }, ... )");
  int n = config_setting_length(list);
  if (n < 1 || n > CAL_MAX_FREE)
    return fail(cx, list, "free", DEM_ERANGE, "%d free parameters (allowed 1 to %d)", n,
                CAL_MAX_FREE);
  for (int i = 0; i < n; i++) {
    const config_setting_t *g = config_setting_get_elem(list, (unsigned)i);
    cal_free *f = &c->fr[i];
    char field[96];
    int rc;
    const char *name = NULL, *scale = "linear";
    f->line = line_of(g);
    snprintf(field, sizeof field, "free[%d].name", i);
    if (!get_str(cx, g, "name", field, &name, &rc))
      return rc ? rc : fail(cx, g, field, DEM_EMISSING, "missing");
    if (!dem_contact_law_has_coef(c->law, name)) {
      char keys[256];
      law_keys(c->law, keys, sizeof keys);
      return fail(cx, config_setting_get_member(g, "name"), field, DEM_ENOTFOUND,
                  "law '%s' has no parameter '%s' (its parameters: %s)", c->law->name, name,
                  keys);
    }
    for (int j = 0; j < i; j++)
      if (strcmp(c->fr[j].name, name) == 0)
        return fail(cx, g, field, DEM_EINVAL, "'%s' is already free (free[%d])", name, j);
    snprintf(f->name, sizeof f->name, "%s", name);
    snprintf(field, sizeof field, "free[%d].min", i);
    if (!get_num(cx, g, "min", field, &f->lo, &rc))
      return rc ? rc : fail(cx, g, field, DEM_EMISSING, "missing lower bound");
    snprintf(field, sizeof field, "free[%d].max", i);
    if (!get_num(cx, g, "max", field, &f->hi, &rc))
      return rc ? rc : fail(cx, g, field, DEM_EMISSING, "missing upper bound");
    if (!(f->lo < f->hi))
      return fail(cx, config_setting_get_member(g, "max"), field, DEM_ERANGE,
                  "bounds of '%s' are inverted or empty: min = %g >= max = %g", name, f->lo,
                  f->hi);
    snprintf(field, sizeof field, "free[%d].scale", i);
    if (get_str(cx, g, "scale", field, &scale, &rc) || !rc) {
      if (strcmp(scale, "log") == 0)
        f->scale = CAL_SCALE_LOG;
      else if (strcmp(scale, "linear") == 0)
        f->scale = CAL_SCALE_LINEAR;
      else
        return fail(cx, config_setting_get_member(g, "scale"), field, DEM_EINVAL,
                    "'%s' is neither \"log\" nor \"linear\"", scale);
    }
    if (rc) return rc;
    if (f->scale == CAL_SCALE_LOG && !(f->lo > 0.0))
      return fail(cx, config_setting_get_member(g, "min"), field, DEM_ERANGE,
                  "log scale needs min > 0 (min = %g)", f->lo);
    const dem_coef_spec *sp = coef_spec(c->law, name);
    if (sp && (f->lo < sp->min || f->hi > sp->max)) {
      snprintf(field, sizeof field, "free[%d].min/max", i);
      return fail(cx, g, field, DEM_ERANGE,
                  "bounds [%g, %g] of '%s' leave the law's allowed range [%g, %g] %s", f->lo,
                  f->hi, name, sp->min, sp->max, sp->unit);
    }
    f->start = NAN;
    snprintf(field, sizeof field, "free[%d].start", i);
    if (get_num(cx, g, "start", field, &f->start, &rc)) {
      if (!(f->start >= f->lo && f->start <= f->hi))
        return fail(cx, config_setting_get_member(g, "start"), field, DEM_ERANGE,
                    "start %g is outside [%g, %g]", f->start, f->lo, f->hi);
    }
    if (rc) return rc;
    if (dem_params_find(&c->fixed, name))
      return fail(cx, g, field, DEM_EINVAL, "'%s' is both fixed and free", name);
  }
  c->nfree = n;
  return DEM_OK;
}

static int algo_check(const ctx *cx, const config_setting_t *g, const char *key,
                      const char *field, char *dst, size_t n, int *line, int allow_auto) {
  const char *name = NULL;
  int rc;
  if (!get_str(cx, g, key, field, &name, &rc)) return rc;
  *line = line_of(config_setting_get_member(g, key));
  if (!(allow_auto && strcmp(name, "auto") == 0) && strcmp(name, "none") != 0 &&
      (int)nlopt_algorithm_from_string(name) < 0)
    return fail(cx, config_setting_get_member(g, key), field, DEM_ENOTFOUND,
                "NLopt knows no algorithm '%s' (e.g. GN_DIRECT_L, GN_CRS2_LM, LN_BOBYQA, "
                "LN_SBPLX, LN_NELDERMEAD)",
                name);
  snprintf(dst, n, "%s", strcmp(name, "none") == 0 ? "" : name);
  return DEM_OK;
}

static int read_opt(const ctx *cx, cal_config *c, const config_setting_t *g) {
  cal_opt_settings *o = &c->opt;
  int rc;
  if (config_setting_type(g) != CONFIG_TYPE_GROUP)
    return fail(cx, g, "optimiser", DEM_EPARSE, "expected a group");
  if ((rc = algo_check(cx, g, "global", "optimiser.global", o->global, sizeof o->global,
                       &o->line_global, 0)))
    return rc;
  if ((rc = algo_check(cx, g, "local", "optimiser.local", o->local, sizeof o->local,
                       &o->line_local, 1)))
    return rc;
  get_int(cx, g, "maxeval_global", "optimiser.maxeval_global", 0, 10000000, &o->maxeval_global,
          &rc);
  if (rc) return rc;
  get_int(cx, g, "maxeval_local", "optimiser.maxeval_local", 0, 10000000, &o->maxeval_local, &rc);
  if (rc) return rc;
  get_int(cx, g, "multistart", "optimiser.multistart", 0, 10000, &o->multistart, &rc);
  if (rc) return rc;
  get_num(cx, g, "xtol_rel", "optimiser.xtol_rel", &o->xtol_rel, &rc);
  if (rc) return rc;
  get_num(cx, g, "ftol_rel", "optimiser.ftol_rel", &o->ftol_rel, &rc);
  if (rc) return rc;
  get_num(cx, g, "fd_step", "optimiser.fd_step", &o->fd_step, &rc);
  if (rc) return rc;
  if (!(o->fd_step > 0.0 && o->fd_step < 0.1))
    return fail(cx, config_setting_get_member(g, "fd_step"), "optimiser.fd_step", DEM_ERANGE,
                "%g outside (0, 0.1)", o->fd_step);
  get_num(cx, g, "penalty", "optimiser.penalty", &o->penalty, &rc);
  if (rc) return rc;
  if (!(o->penalty > 0.0))
    return fail(cx, config_setting_get_member(g, "penalty"), "optimiser.penalty", DEM_ERANGE,
                "must be > 0");
  if (o->maxeval_global + o->maxeval_local <= 0)
    return fail(cx, g, "optimiser.maxeval_local", DEM_ERANGE,
                "a calibration needs a positive maxeval");
  return DEM_OK;
}

static int read_impact(const ctx *cx, cal_config *c, const config_setting_t *g) {
  int rc;
  const char *s = NULL;
  if (get_str(cx, g, "integrator", "impact.integrator", &s, &rc)) {
    if (strcmp(s, "verlet") == 0)
      c->impact.integrator = DEM_INTEGRATOR_VERLET;
    else if (strcmp(s, "reference") == 0)
      c->impact.integrator = DEM_INTEGRATOR_REFERENCE;
    else
      return fail(cx, config_setting_get_member(g, "integrator"), "impact.integrator",
                  DEM_EINVAL, "'%s' is neither \"verlet\" nor \"reference\"", s);
  }
  if (rc) return rc;
  get_num(cx, g, "dt_factor", "impact.dt_factor", &c->impact.dt_factor, &rc);
  if (rc) return rc;
  get_num(cx, g, "t_max_factor", "impact.t_max_factor", &c->impact.t_max_factor, &rc);
  return rc;
}

static const char *const type_names[] = {"curve", "sticking", "restitution", "unloading"};
static const int type_ncols[] = {2, 2, 2, 4};
static const char *const type_cols[][4] = {{"alpha", "f", NULL, NULL},
                                           {"R", "v_stick", NULL, NULL},
                                           {"v", "e", NULL, NULL},
                                           {"alpha_max", "f_max", "alpha_p", "f_pulloff"}};

/* Inline arrays of numbers. */
static int read_array(const ctx *cx, const config_setting_t *g, const char *key,
                      const char *field, double **out, int *n) {
  const config_setting_t *a = config_setting_get_member(g, key);
  if (!a) return DEM_OK;
  if (!config_setting_is_array(a) && !config_setting_is_list(a))
    return fail(cx, a, field, DEM_EPARSE, "expected an array [ ... ] of numbers");
  int len = config_setting_length(a);
  *out = calloc((size_t)(len > 0 ? len : 1), sizeof **out);
  if (!*out) return fail(cx, a, field, DEM_ENOMEM, "out of memory");
  for (int i = 0; i < len; i++) {
    const config_setting_t *e = config_setting_get_elem(a, (unsigned)i);
    int t = config_setting_type(e);
    if (t == CONFIG_TYPE_FLOAT)
      (*out)[i] = config_setting_get_float(e);
    else if (t == CONFIG_TYPE_INT || t == CONFIG_TYPE_INT64)
      (*out)[i] = (double)config_setting_get_int64(e);
    else
      return fail(cx, a, field, DEM_EPARSE, "element %d is not a number", i);
    if (!isfinite((*out)[i])) return fail(cx, a, field, DEM_ENONFINITE, "element %d", i);
  }
  *n = len;
  return DEM_OK;
}

static int read_target(const ctx *cx, cal_config *c, const config_setting_t *g, int i) {
  cal_target *t = &c->t[i];
  char field[96];
  int rc;
  const char *s = NULL;
  t->line = line_of(g);
  t->weight = 1.0;
  t->mode = CAL_CURVE_POINTS;
  t->grid = 50;
  t->v_lo = 1e-3;
  t->v_hi = 100.0;
  t->tol = 1e-4;
  dem_params_init(&t->over);
  snprintf(field, sizeof field, "targets[%d].type", i);
  if (!get_str(cx, g, "type", field, &s, &rc))
    return rc ? rc : fail(cx, g, field, DEM_EMISSING,
                          "missing (curve, sticking, restitution, unloading)");
  int ty = -1;
  for (int k = 0; k < 4; k++)
    if (strcmp(s, type_names[k]) == 0) ty = k;
  if (ty < 0)
    return fail(cx, config_setting_get_member(g, "type"), field, DEM_EINVAL,
                "'%s' is not curve, sticking, restitution or unloading", s);
  t->type = (cal_ttype)ty;
  snprintf(t->name, sizeof t->name, "%s%d", type_names[ty], i);
  snprintf(field, sizeof field, "targets[%d].name", i);
  if (get_str(cx, g, "name", field, &s, &rc)) {
    for (const char *p = s; *p; p++)
      if (!(isalnum((unsigned char)*p) || *p == '-' || *p == '_' || *p == '.'))
        return fail(cx, config_setting_get_member(g, "name"), field, DEM_EINVAL,
                    "'%s': use letters, digits, '-', '_', '.' only (it names output files)", s);
    snprintf(t->name, sizeof t->name, "%s", s);
  }
  if (rc) return rc;
  snprintf(field, sizeof field, "targets[%d].weight", i);
  get_num(cx, g, "weight", field, &t->weight, &rc);
  if (rc) return rc;
  if (!(t->weight > 0.0))
    return fail(cx, config_setting_get_member(g, "weight"), field, DEM_ERANGE,
                "must be > 0 (%g)", t->weight);
  snprintf(field, sizeof field, "targets[%d].geometry", i);
  if (get_str(cx, g, "geometry", field, &s, &rc)) {
    if (strcmp(s, "wall") == 0)
      t->pair = 0;
    else if (strcmp(s, "pair") == 0)
      t->pair = 1;
    else
      return fail(cx, config_setting_get_member(g, "geometry"), field, DEM_EINVAL,
                  "'%s' is neither \"wall\" nor \"pair\"", s);
  }
  if (rc) return rc;
  if (t->type == CAL_T_CURVE) {
    snprintf(field, sizeof field, "targets[%d].mode", i);
    if (get_str(cx, g, "mode", field, &s, &rc)) {
      if (strcmp(s, "points") == 0)
        t->mode = CAL_CURVE_POINTS;
      else if (strcmp(s, "grid") == 0)
        t->mode = CAL_CURVE_GRID;
      else if (strcmp(s, "summary") == 0)
        t->mode = CAL_CURVE_SUMMARY;
      else
        return fail(cx, config_setting_get_member(g, "mode"), field, DEM_EINVAL,
                    "'%s' is not points, grid or summary", s);
    }
    if (rc) return rc;
    snprintf(field, sizeof field, "targets[%d].grid", i);
    get_int(cx, g, "grid", field, 2, 100000, &t->grid, &rc);
    if (rc) return rc;
  }
  if (t->type == CAL_T_STICKING) {
    snprintf(field, sizeof field, "targets[%d].v_lo", i);
    get_num(cx, g, "v_lo", field, &t->v_lo, &rc);
    if (rc) return rc;
    snprintf(field, sizeof field, "targets[%d].v_hi", i);
    get_num(cx, g, "v_hi", field, &t->v_hi, &rc);
    if (rc) return rc;
    if (!(t->v_lo > 0.0 && t->v_lo < t->v_hi))
      return fail(cx, g, field, DEM_ERANGE, "need 0 < v_lo < v_hi (v_lo = %g, v_hi = %g)",
                  t->v_lo, t->v_hi);
    snprintf(field, sizeof field, "targets[%d].tol", i);
    get_num(cx, g, "tol", field, &t->tol, &rc);
    if (rc) return rc;
    if (!(t->tol > 0.0 && t->tol < 0.1))
      return fail(cx, config_setting_get_member(g, "tol"), field, DEM_ERANGE,
                  "%g outside (0, 0.1)", t->tol);
  }
  const config_setting_t *set = config_setting_get_member(g, "set");
  if (set) {
    snprintf(field, sizeof field, "targets[%d].set", i);
    if ((rc = read_fixed(cx, c, set, field, &t->over, 1))) return rc;
  }
  /* The data: a file (through dem/refdata.h), inline arrays named like its columns, or a
   * curve generated by another law. */
  int nc = type_ncols[ty];
  double **dst[4] = {&t->x, &t->y, &t->z, &t->w};
  const char *cols[4];
  for (int k = 0; k < 4; k++) cols[k] = type_cols[ty][k];
  const char *file = NULL;
  snprintf(field, sizeof field, "targets[%d].reference_law", i);
  if (get_str(cx, g, "reference_law", field, &s, &rc)) {
    const config_setting_t *rl = config_setting_get_member(g, "reference_law");
    if (ty != CAL_T_CURVE)
      return fail(cx, rl, field, DEM_EUNSUPPORTED, "only a curve target can be generated");
    if (!dem_contact_law_find(s))
      return fail(cx, rl, field, DEM_ENOTFOUND, "unknown law '%s'", s);
    snprintf(t->gen_law, sizeof t->gen_law, "%s", s);
    snprintf(field, sizeof field, "targets[%d].v_impact", i);
    if (!get_num(cx, g, "v_impact", field, &t->gen_v, &rc) || !(t->gen_v > 0.0))
      return rc ? rc : fail(cx, g, field, DEM_EMISSING, "a generated curve needs v_impact > 0 (m/s)");
    t->gen_samples = 400;
    snprintf(field, sizeof field, "targets[%d].samples", i);
    get_int(cx, g, "samples", field, 10, 1000000, &t->gen_samples, &rc);
    if (rc) return rc;
    const config_setting_t *rs = config_setting_get_member(g, "reference_set");
    dem_params_init(&t->gen_set);
    snprintf(field, sizeof field, "targets[%d].reference_set", i);
    if (!rs) return fail(cx, g, field, DEM_EMISSING, "a generated curve needs reference_set = { ... }");
    if (config_setting_type(rs) != CONFIG_TYPE_GROUP)
      return fail(cx, rs, field, DEM_EPARSE, "expected a group { key = value; ... }");
    for (int k = 0; k < config_setting_length(rs); k++) {
      const config_setting_t *e = config_setting_get_elem(rs, (unsigned)k);
      char f2[160], origin[DEM_ORIGIN_LEN];
      double v;
      snprintf(f2, sizeof f2, "%s.%s", field, config_setting_name(e));
      if (!get_num(cx, rs, config_setting_name(e), f2, &v, &rc))
        return rc ? rc : fail(cx, e, f2, DEM_EPARSE, "expected a number");
      snprintf(origin, sizeof origin, "%s:%d", cx->file, line_of(e));
      dem_err e2 = {0};
      if (dem_params_set(&t->gen_set, config_setting_name(e), v, origin, &e2))
        return fail(cx, e, f2, e2.code, "%s", e2.msg);
    }
    dem_err e2 = {0};
    if ((rc = cal_generate_reference(c, t, &e2)))
      return fail(cx, rl, field, rc, "cannot generate the reference curve: %s", e2.msg);
  } else if (rc) {
    return rc;
  } else if (snprintf(field, sizeof field, "targets[%d].file", i),
             get_str(cx, g, "file", field, &file, &rc)) {
    size_t need = file[0] == '/' ? strlen(file) : strlen(c->dir) + 1 + strlen(file);
    if (need >= sizeof t->file)
      return fail(cx, config_setting_get_member(g, "file"), field, DEM_ERANGE, "path too long");
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
        return fail(cx, cl, cf, DEM_EPARSE, "expected an array of %d column names (%s, %s%s%s%s%s)",
                    nc, cols[0], cols[1], nc > 2 ? ", " : "", nc > 2 ? cols[2] : "",
                    nc > 2 ? ", " : "", nc > 2 ? cols[3] : "");
      for (int k = 0; k < nc; k++) cols[k] = config_setting_get_string_elem(cl, (unsigned)k);
    }
    dem_err e2 = {0};
    if (access(t->file, R_OK) != 0)
      return fail(cx, config_setting_get_member(g, "file"), field, DEM_EIO,
                  "cannot read target file '%s': %s", t->file, strerror(errno));
    double *out[4] = {NULL, NULL, NULL, NULL};
    if ((rc = cal_target_read_file(t->file, cols, nc, out, &t->n, &e2)))
      return fail(cx, config_setting_get_member(g, "file"), field, rc, "%s", e2.msg);
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
        return fail(cx, g, fx, DEM_EMISSING,
                    "a %s target needs file = \"...\", or inline arrays of %s%s%s%s%s%s%s",
                    type_names[ty], cols[0], nc > 2 ? ", " : " and ", cols[1], nc > 2 ? ", " : "",
                    nc > 2 ? cols[2] : "", nc > 2 ? " and " : "", nc > 2 ? cols[3] : "");
      if (k > 0 && nk != n0)
        return fail(cx, config_setting_get_member(g, cols[k]), fx, DEM_EINVAL,
                    "%d values but %s has %d", nk, cols[0], n0);
      n0 = nk;
    }
    t->n = n0;
  }
  snprintf(field, sizeof field, "targets[%d]", i);
  int need = t->type == CAL_T_CURVE ? 2 : 1;
  if (t->n < need)
    return fail(cx, g, field, DEM_EINVAL, "%d reference points (need at least %d)", t->n, need);
  for (int k = 0; k < t->n && t->type != CAL_T_CURVE; k++)
    for (int q = 0; q < nc; q++)
      if (!((*dst[q])[k] > 0.0))
        return fail(cx, g, field, DEM_ERANGE, "row %d: %s = %g must be > 0", k, cols[q],
                    (*dst[q])[k]);
  return DEM_OK;
}

static unsigned long long fnv(unsigned long long h, const void *p, size_t n) {
  const unsigned char *b = p;
  for (size_t i = 0; i < n; i++) {
    h ^= b[i];
    h *= 1099511628211ULL;
  }
  return h;
}

static int load(cal_config *c, config_t *cf, const char *path, const char *text, dem_err *err) {
  ctx cx = {path, err};
  config_setting_t *root = config_root_setting(cf);
  int rc;
  const char *s = NULL;
  /* Defaults. */
  snprintf(c->opt.global, sizeof c->opt.global, "GN_DIRECT_L");
  snprintf(c->opt.local, sizeof c->opt.local, "auto");
  c->opt.maxeval_global = 300;
  c->opt.maxeval_local = 300;
  c->opt.xtol_rel = 1e-8;
  c->opt.ftol_rel = 1e-12;
  c->opt.fd_step = 1e-4;
  c->opt.penalty = 1e6;
  c->seed = 1;
  c->path_steps = 2000;
#ifdef CAL_HAVE_IMPACT
  dem_impact_opts_default(&c->impact);
#else
  /* dem/impact.h documents these defaults; the solver itself is not merged yet. */
  memset(&c->impact, 0, sizeof c->impact);
  c->impact.dt_factor = 0.01;
  c->impact.rtol = 1e-10;
  c->impact.t_max_factor = 200.0;
  c->impact.runaway_overlap = 1.0;
  c->impact.trace_every = 1;
#endif
  dem_params_init(&c->fixed);

  const char *slash = strrchr(path, '/');
  if (slash)
    snprintf(c->dir, sizeof c->dir, "%.*s", (int)(slash - path), path);
  else
    snprintf(c->dir, sizeof c->dir, ".");
  snprintf(c->path, sizeof c->path, "%s", path);
  const char *base = slash ? slash + 1 : path;
  snprintf(c->name, sizeof c->name, "%.*s", (int)strcspn(base, "."), base);
  if (get_str(&cx, root, "name", "name", &s, &rc)) snprintf(c->name, sizeof c->name, "%s", s);
  if (rc) return rc;

  if (!get_str(&cx, root, "law", "law", &s, &rc))
    return rc ? rc : fail(&cx, root, "law", DEM_EMISSING, "missing (e.g. law = \"hertz\";)");
  c->law = dem_contact_law_find(s);
  if (!c->law) {
    char names[256] = "";
    size_t used = 0;
    for (int i = 0; i < dem_contact_law_count() && used + 24 < sizeof names; i++)
      used += (size_t)snprintf(names + used, sizeof names - used, "%s%s", i ? ", " : "",
                               dem_contact_law_at(i)->name);
    return fail(&cx, config_setting_get_member(root, "law"), "law", DEM_ENOTFOUND,
                "unknown law '%s' (known: %s)", s, names);
  }
  double seed = 1;
  if (get_num(&cx, root, "seed", "seed", &seed, &rc)) {
    if (seed < 0 || seed != floor(seed) || seed > 4294967295.0)
      return fail(&cx, config_setting_get_member(root, "seed"), "seed", DEM_ERANGE,
                  "%g is not an integer in [0, 2^32)", seed);
    c->seed = (unsigned long)seed;
  }
  if (rc) return rc;
  get_int(&cx, root, "path_steps", "path_steps", 10, 10000000, &c->path_steps, &rc);
  if (rc) return rc;

  const config_setting_t *g = config_setting_get_member(root, "fixed");
  if (g && (rc = read_fixed(&cx, c, g, "fixed", &c->fixed, 1))) return rc;
  g = config_setting_get_member(root, "free");
  if (!g) return fail(&cx, root, "free", DEM_EMISSING, "no free parameters");
  if ((rc = read_free(&cx, c, g))) return rc;
  g = config_setting_get_member(root, "optimiser");
  if (g && (rc = read_opt(&cx, c, g))) return rc;
  g = config_setting_get_member(root, "impact");
  if (g && (rc = read_impact(&cx, c, g))) return rc;
  g = config_setting_get_member(root, "targets");
  if (!g || !config_setting_is_list(g) || config_setting_length(g) < 1)
    return fail(&cx, g ? g : root, "targets", DEM_EMISSING,
                "expected a non-empty list of targets ( { type = ...; }, ... )");
  if (config_setting_length(g) > CAL_MAX_TARGETS)
    return fail(&cx, g, "targets", DEM_ERANGE, "at most %d targets", CAL_MAX_TARGETS);
  c->ntargets = config_setting_length(g);
  for (int i = 0; i < c->ntargets; i++)
    if ((rc = read_target(&cx, c, config_setting_get_elem(g, (unsigned)i), i))) return rc;

  /* Unknown top-level settings are mistakes (a misspelt "optimizer" would be ignored). */
  static const char *const known[] = {"name", "law", "seed", "path_steps", "fixed", "free",
                                      "optimiser", "impact", "targets", NULL};
  for (int i = 0; i < config_setting_length(root); i++) {
    const config_setting_t *e = config_setting_get_elem(root, (unsigned)i);
    int ok = 0;
    for (const char *const *k = known; *k; k++)
      if (strcmp(*k, config_setting_name(e)) == 0) ok = 1;
    if (!ok)
      return fail(&cx, e, config_setting_name(e), DEM_ENOTFOUND,
                  "unknown setting (known: name, law, seed, path_steps, fixed, free, optimiser, "
                  "impact, targets)");
  }

  unsigned long long h = 1469598103934665603ULL;
  h = fnv(h, text, strlen(text));
  for (int i = 0; i < c->ntargets; i++) {
    h = fnv(h, c->t[i].x, sizeof(double) * (size_t)c->t[i].n);
    h = fnv(h, c->t[i].y, sizeof(double) * (size_t)c->t[i].n);
  }
  c->hash = h;
  return DEM_OK;
}

static char *slurp(const char *path, dem_err *err) {
  FILE *f = fopen(path, "rb");
  if (!f) {
    dem_err_set(err, DEM_EIO, "%s: cannot open config: %s", path, strerror(errno));
    return NULL;
  }
  size_t cap = 4096, n = 0;
  char *buf = malloc(cap);
  for (;;) {
    if (!buf) break;
    if (n + 1024 > cap) {
      char *nb = realloc(buf, cap *= 2);
      if (!nb) {
        free(buf);
        buf = NULL;
        break;
      }
      buf = nb;
    }
    size_t got = fread(buf + n, 1, cap - n - 1, f);
    n += got;
    if (got == 0) break;
  }
  fclose(f);
  if (!buf) dem_err_set(err, DEM_ENOMEM, "%s: out of memory", path);
  else buf[n] = '\0';
  return buf;
}

int cal_config_load_string(cal_config *c, const char *text, const char *path, dem_err *err) {
  memset(c, 0, sizeof *c);
  config_t cf;
  config_init(&cf);
  int rc;
  if (config_read_string(&cf, text) != CONFIG_TRUE) {
    rc = dem_err_set(err, DEM_EPARSE, "%s:%d: syntax: %s", path, config_error_line(&cf),
                     config_error_text(&cf));
  } else {
    rc = load(c, &cf, path, text, err);
  }
  config_destroy(&cf);
  if (rc) cal_config_free(c);
  return rc;
}

int cal_config_load(cal_config *c, const char *path, dem_err *err) {
  char *text = slurp(path, err);
  if (!text) {
    memset(c, 0, sizeof *c);
    return err ? err->code : DEM_EIO;
  }
  int rc = cal_config_load_string(c, text, path, err);
  free(text);
  return rc;
}

void cal_config_free(cal_config *c) {
  for (int i = 0; i < CAL_MAX_TARGETS; i++) {
    cal_target *t = &c->t[i];
    free(t->x);
    free(t->y);
    free(t->z);
    free(t->w);
    free(t->xr);
    free(t->yr);
    free(t->branch);
    t->x = t->y = t->z = t->w = t->xr = t->yr = NULL;
    t->branch = NULL;
  }
}
