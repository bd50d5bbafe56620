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
#include "config_priv.h"

static int read_free(const cal_cfg_ctx *cx, cal_config *c, const config_setting_t *list) {
  if (config_setting_type(list) != CONFIG_TYPE_LIST)
    return cal_cfg_fail(cx, list, "free", DEM_EPARSE, "expected a list ( { name = ...; }, ... )");
  int n = config_setting_length(list);
  if (n < 1 || n > CAL_MAX_FREE)
    return cal_cfg_fail(cx, list, "free", DEM_ERANGE, "%d free parameters (allowed 1 to %d)", n,
                CAL_MAX_FREE);
  for (int i = 0; i < n; i++) {
    const config_setting_t *g = config_setting_get_elem(list, (unsigned)i);
    cal_free *f = &c->fr[i];
    char field[96];
    int rc;
    const char *name = NULL, *scale = "linear";
    f->line = cal_cfg_line_of(g);
    snprintf(field, sizeof field, "free[%d].name", i);
    if (!cal_cfg_get_str(cx, g, "name", field, &name, &rc))
      return rc ? rc : cal_cfg_fail(cx, g, field, DEM_EMISSING, "missing");
    if (!dem_contact_law_has_coef(c->law, name)) {
      char keys[256];
      cal_cfg_law_keys(c->law, keys, sizeof keys);
      return cal_cfg_fail(cx, config_setting_get_member(g, "name"), field, DEM_ENOTFOUND,
                  "law '%s' has no parameter '%s' (its parameters: %s)", c->law->name, name,
                  keys);
    }
    for (int j = 0; j < i; j++)
      if (strcmp(c->fr[j].name, name) == 0)
        return cal_cfg_fail(cx, g, field, DEM_EINVAL, "'%s' is already free (free[%d])", name, j);
    snprintf(f->name, sizeof f->name, "%s", name);
    snprintf(field, sizeof field, "free[%d].min", i);
    if (!cal_cfg_get_num(cx, g, "min", field, &f->lo, &rc))
      return rc ? rc : cal_cfg_fail(cx, g, field, DEM_EMISSING, "missing lower bound");
    snprintf(field, sizeof field, "free[%d].max", i);
    if (!cal_cfg_get_num(cx, g, "max", field, &f->hi, &rc))
      return rc ? rc : cal_cfg_fail(cx, g, field, DEM_EMISSING, "missing upper bound");
    if (!(f->lo < f->hi))
      return cal_cfg_fail(cx, config_setting_get_member(g, "max"), field, DEM_ERANGE,
                  "bounds of '%s' are inverted or empty: min = %g >= max = %g", name, f->lo,
                  f->hi);
    snprintf(field, sizeof field, "free[%d].scale", i);
    if (cal_cfg_get_str(cx, g, "scale", field, &scale, &rc) || !rc) {
      if (strcmp(scale, "log") == 0)
        f->scale = CAL_SCALE_LOG;
      else if (strcmp(scale, "linear") == 0)
        f->scale = CAL_SCALE_LINEAR;
      else
        return cal_cfg_fail(cx, config_setting_get_member(g, "scale"), field, DEM_EINVAL,
                    "'%s' is neither \"log\" nor \"linear\"", scale);
    }
    if (rc) return rc;
    if (f->scale == CAL_SCALE_LOG && !(f->lo > 0.0))
      return cal_cfg_fail(cx, config_setting_get_member(g, "min"), field, DEM_ERANGE,
                  "log scale needs min > 0 (min = %g)", f->lo);
    const dem_coef_spec *sp = cal_cfg_coef_spec(c->law, name);
    if (sp && (f->lo < sp->min || f->hi > sp->max)) {
      snprintf(field, sizeof field, "free[%d].min/max", i);
      return cal_cfg_fail(cx, g, field, DEM_ERANGE,
                  "bounds [%g, %g] of '%s' leave the law's allowed range [%g, %g] %s", f->lo,
                  f->hi, name, sp->min, sp->max, sp->unit);
    }
    f->start = NAN;
    snprintf(field, sizeof field, "free[%d].start", i);
    if (cal_cfg_get_num(cx, g, "start", field, &f->start, &rc)) {
      if (!(f->start >= f->lo && f->start <= f->hi))
        return cal_cfg_fail(cx, config_setting_get_member(g, "start"), field, DEM_ERANGE,
                    "start %g is outside [%g, %g]", f->start, f->lo, f->hi);
    }
    if (rc) return rc;
    if (dem_params_find(&c->fixed, name))
      return cal_cfg_fail(cx, g, field, DEM_EINVAL, "'%s' is both fixed and free", name);
  }
  c->nfree = n;
  return DEM_OK;
}

static int algo_check(const cal_cfg_ctx *cx, const config_setting_t *g, const char *key,
                      const char *field, char *dst, size_t n, int *line, int allow_auto) {
  const char *name = NULL;
  int rc;
  if (!cal_cfg_get_str(cx, g, key, field, &name, &rc)) return rc;
  *line = cal_cfg_line_of(config_setting_get_member(g, key));
  if (!(allow_auto && strcmp(name, "auto") == 0) && strcmp(name, "none") != 0 &&
      (int)nlopt_algorithm_from_string(name) < 0)
    return cal_cfg_fail(cx, config_setting_get_member(g, key), field, DEM_ENOTFOUND,
                "NLopt knows no algorithm '%s' (e.g. GN_DIRECT_L, GN_CRS2_LM, LN_BOBYQA, "
                "LN_SBPLX, LN_NELDERMEAD)",
                name);
  snprintf(dst, n, "%s", strcmp(name, "none") == 0 ? "" : name);
  return DEM_OK;
}

static int read_opt(const cal_cfg_ctx *cx, cal_config *c, const config_setting_t *g) {
  cal_opt_settings *o = &c->opt;
  int rc;
  if (config_setting_type(g) != CONFIG_TYPE_GROUP)
    return cal_cfg_fail(cx, g, "optimiser", DEM_EPARSE, "expected a group");
  if ((rc = algo_check(cx, g, "global", "optimiser.global", o->global, sizeof o->global,
                       &o->line_global, 0)))
    return rc;
  if ((rc = algo_check(cx, g, "local", "optimiser.local", o->local, sizeof o->local,
                       &o->line_local, 1)))
    return rc;
  cal_cfg_get_int(cx, g, "maxeval_global", "optimiser.maxeval_global", 0, 10000000, &o->maxeval_global,
          &rc);
  if (rc) return rc;
  cal_cfg_get_int(cx, g, "maxeval_local", "optimiser.maxeval_local", 0, 10000000, &o->maxeval_local, &rc);
  if (rc) return rc;
  cal_cfg_get_int(cx, g, "multistart", "optimiser.multistart", 0, 10000, &o->multistart, &rc);
  if (rc) return rc;
  cal_cfg_get_num(cx, g, "xtol_rel", "optimiser.xtol_rel", &o->xtol_rel, &rc);
  if (rc) return rc;
  cal_cfg_get_num(cx, g, "ftol_rel", "optimiser.ftol_rel", &o->ftol_rel, &rc);
  if (rc) return rc;
  cal_cfg_get_num(cx, g, "fd_step", "optimiser.fd_step", &o->fd_step, &rc);
  if (rc) return rc;
  if (!(o->fd_step > 0.0 && o->fd_step < 0.1))
    return cal_cfg_fail(cx, config_setting_get_member(g, "fd_step"), "optimiser.fd_step", DEM_ERANGE,
                "%g outside (0, 0.1)", o->fd_step);
  cal_cfg_get_num(cx, g, "penalty", "optimiser.penalty", &o->penalty, &rc);
  if (rc) return rc;
  if (!(o->penalty > 0.0))
    return cal_cfg_fail(cx, config_setting_get_member(g, "penalty"), "optimiser.penalty", DEM_ERANGE,
                "must be > 0");
  if (o->maxeval_global + o->maxeval_local <= 0)
    return cal_cfg_fail(cx, g, "optimiser.maxeval_local", DEM_ERANGE,
                "a calibration needs a positive maxeval");
  return DEM_OK;
}

static int read_impact(const cal_cfg_ctx *cx, cal_config *c, const config_setting_t *g) {
  int rc;
  const char *s = NULL;
  if (cal_cfg_get_str(cx, g, "integrator", "impact.integrator", &s, &rc)) {
    if (strcmp(s, "verlet") == 0)
      c->impact.integrator = DEM_INTEGRATOR_VERLET;
    else if (strcmp(s, "reference") == 0)
      c->impact.integrator = DEM_INTEGRATOR_REFERENCE;
    else
      return cal_cfg_fail(cx, config_setting_get_member(g, "integrator"), "impact.integrator",
                  DEM_EINVAL, "'%s' is neither \"verlet\" nor \"reference\"", s);
  }
  if (rc) return rc;
  cal_cfg_get_num(cx, g, "dt_factor", "impact.dt_factor", &c->impact.dt_factor, &rc);
  if (rc) return rc;
  cal_cfg_get_num(cx, g, "t_max_factor", "impact.t_max_factor", &c->impact.t_max_factor, &rc);
  return rc;
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
  cal_cfg_ctx cx = {path, err};
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
  if (cal_cfg_get_str(&cx, root, "name", "name", &s, &rc)) snprintf(c->name, sizeof c->name, "%s", s);
  if (rc) return rc;

  if (!cal_cfg_get_str(&cx, root, "law", "law", &s, &rc))
    return rc ? rc : cal_cfg_fail(&cx, root, "law", DEM_EMISSING, "missing (e.g. law = \"hertz\";)");
  c->law = dem_contact_law_find(s);
  if (!c->law) {
    char names[256] = "";
    size_t used = 0;
    for (int i = 0; i < dem_contact_law_count() && used + 24 < sizeof names; i++)
      used += (size_t)snprintf(names + used, sizeof names - used, "%s%s", i ? ", " : "",
                               dem_contact_law_at(i)->name);
    return cal_cfg_fail(&cx, config_setting_get_member(root, "law"), "law", DEM_ENOTFOUND,
                "unknown law '%s' (known: %s)", s, names);
  }
  double seed = 1;
  if (cal_cfg_get_num(&cx, root, "seed", "seed", &seed, &rc)) {
    if (seed < 0 || seed != floor(seed) || seed > 4294967295.0)
      return cal_cfg_fail(&cx, config_setting_get_member(root, "seed"), "seed", DEM_ERANGE,
                  "%g is not an integer in [0, 2^32)", seed);
    c->seed = (unsigned long)seed;
  }
  if (rc) return rc;
  cal_cfg_get_int(&cx, root, "path_steps", "path_steps", 10, 10000000, &c->path_steps, &rc);
  if (rc) return rc;

  const config_setting_t *g = config_setting_get_member(root, "fixed");
  if (g && (rc = cal_cfg_read_fixed(&cx, c, g, "fixed", &c->fixed, 1))) return rc;
  g = config_setting_get_member(root, "free");
  if (!g) return cal_cfg_fail(&cx, root, "free", DEM_EMISSING, "no free parameters");
  if ((rc = read_free(&cx, c, g))) return rc;
  g = config_setting_get_member(root, "optimiser");
  if (g && (rc = read_opt(&cx, c, g))) return rc;
  g = config_setting_get_member(root, "impact");
  if (g && (rc = read_impact(&cx, c, g))) return rc;
  g = config_setting_get_member(root, "targets");
  if (!g || !config_setting_is_list(g) || config_setting_length(g) < 1)
    return cal_cfg_fail(&cx, g ? g : root, "targets", DEM_EMISSING,
                "expected a non-empty list of targets ( { type = ...; }, ... )");
  if (config_setting_length(g) > CAL_MAX_TARGETS)
    return cal_cfg_fail(&cx, g, "targets", DEM_ERANGE, "at most %d targets", CAL_MAX_TARGETS);
  c->ntargets = config_setting_length(g);
  for (int i = 0; i < c->ntargets; i++)
    if ((rc = cal_cfg_read_target(&cx, c, config_setting_get_elem(g, (unsigned)i), i))) return rc;

  /* Unknown top-level settings are mistakes (a misspelt "optimizer" would be ignored). */
  static const char *const known[] = {"name", "law", "seed", "path_steps", "fixed", "free",
                                      "optimiser", "impact", "targets", NULL};
  for (int i = 0; i < config_setting_length(root); i++) {
    const config_setting_t *e = config_setting_get_elem(root, (unsigned)i);
    int ok = 0;
    for (const char *const *k = known; *k; k++)
      if (strcmp(*k, config_setting_name(e)) == 0) ok = 1;
    if (!ok)
      return cal_cfg_fail(&cx, e, config_setting_name(e), DEM_ENOTFOUND,
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
