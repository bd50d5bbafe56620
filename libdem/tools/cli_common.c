/* Shared code of the dem-* programs (cli_common.h). */
#include "cli_common.h"

#include <getopt.h>

#include <errno.h>
#include <float.h>
#include <libconfig.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#ifndef DEM_VERSION
#define DEM_VERSION "unknown"
#endif

void cli_config_init(cli_config *c) {
  memset(c, 0, sizeof *c);
  c->velocity = c->v_min = c->v_max = c->dt_factor = c->rtol = c->step = NAN;
  c->sticking = c->target = c->dt_rule = c->integrator = c->clip_tensile = -1;
}

int cli_parse_double(const char *flag, const char *text, double lo, double hi, double *out,
                     dem_err *err) {
  errno = 0;
  char *end = NULL;
  double v = strtod(text, &end);
  if (end == text || *end != '\0' || errno == ERANGE)
    return dem_err_set(err, DEM_EPARSE, "%s: '%s' is not a number", flag, text);
  if (!isfinite(v))
    return dem_err_set(err, DEM_ENONFINITE, "%s: '%s' is not finite", flag, text);
  if (!(v >= lo && v <= hi))
    return dem_err_set(err, DEM_ERANGE, "%s: %g is outside the allowed range [%g, %g]", flag, v,
                       lo, hi);
  *out = v;
  return DEM_OK;
}

int cli_parse_list(const char *flag, const char *text, double *out, int max, int *n,
                   dem_err *err) {
  *n = 0;
  const char *p = text;
  for (;;) {
    char buf[64];
    const char *comma = strchr(p, ',');
    size_t len = comma ? (size_t)(comma - p) : strlen(p);
    if (len == 0 || len >= sizeof buf)
      return dem_err_set(err, DEM_EPARSE, "%s: empty or over-long entry %d in '%s'", flag, *n + 1,
                         text);
    if (*n >= max)
      return dem_err_set(err, DEM_ERANGE, "%s: more than %d values", flag, max);
    memcpy(buf, p, len);
    buf[len] = '\0';
    int rc = cli_parse_double(flag, buf, -1e3, 1e3, &out[*n], err);
    if (rc) return rc;
    (*n)++;
    if (!comma) return DEM_OK;
    p = comma + 1;
  }
}

int cli_parse_set(dem_params *ps, const char *text, dem_err *err) {
  int rc = dem_params_parse_assignment(ps, text, "--set", err);
  return rc;
}

int cli_parse_word(const char *flag, const char *text, const char *const *words, int *out,
                   dem_err *err) {
  char list[256] = "";
  size_t used = 0;
  for (int i = 0; words[i]; i++) {
    if (strcmp(words[i], text) == 0) {
      *out = i;
      return DEM_OK;
    }
    used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", words[i]);
    if (used >= sizeof list) used = sizeof list - 1;
  }
  return dem_err_set(err, DEM_EINVAL, "%s: '%s' is not one of: %s", flag, text, list);
}

const dem_law *cli_find_law(const char *id, dem_err *err) {
  const dem_law *law = dem_contact_law_find(id);
  if (law) return law;
  char list[256] = "";
  size_t used = 0;
  for (int i = 0; i < dem_contact_law_count() && used < sizeof list - 1; i++)
    used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "",
                             dem_contact_law_at(i)->name);
  dem_err_set(err, DEM_ENOTFOUND, "--law: unknown law '%s' (known: %s; see --list-laws)",
              id ? id : "", list);
  return NULL;
}

static void range_text(const dem_coef_spec *s, char *buf, size_t n) {
  if (s->min == DBL_MIN && isinf(s->max))
    snprintf(buf, n, "> 0");
  else if (s->min == DBL_MIN)
    snprintf(buf, n, "(0, %g]", s->max);
  else if (isinf(s->max))
    snprintf(buf, n, ">= %g", s->min);
  else
    snprintf(buf, n, "[%g, %g]", s->min, s->max);
}

void cli_list_laws(FILE *out) {
  for (int i = 0; i < dem_contact_law_count(); i++) {
    const dem_law *law = dem_contact_law_at(i);
    fprintf(out, "%s\t%s (%s)%s%s%s\n", law->name, law->title, law->source,
            (law->flags & DEM_LAW_ADHESIVE) ? " [adhesive]" : "",
            (law->flags & DEM_LAW_PLASTIC) ? " [plastic]" : "",
            (law->flags & DEM_LAW_NONLINEAR) ? " [nonlinear]" : "");
    for (int j = 0; j < law->ncoef; j++) {
      const dem_coef_spec *s = &law->coef[j];
      char range[64], def[48];
      range_text(s, range, sizeof range);
      if (isnan(s->def))
        snprintf(def, sizeof def, "required");
      else if (!(s->def >= s->min && s->def <= s->max))
        snprintf(def, sizeof def, "optional"); /* a sentinel: the law derives it */
      else
        snprintf(def, sizeof def, "default %g", s->def);
      fprintf(out, "    %-10s %-7s %-16s %-16s %s\n", s->key, s->unit, range, def, s->about);
    }
  }
  fprintf(out, "scene keys (every law): R (m, required), rho (kg/m^3, required for impacts), "
               "E (Pa), nu (-) for the Rayleigh time step\n");
}

void cli_print_version(const char *prog) {
  printf("%s (dem suite) %s\n", prog, DEM_VERSION);
}

void cli_error(const char *prog, const dem_err *err) {
  fprintf(stderr, "%s: %s\n", prog, err->msg[0] ? err->msg : dem_strerror(err->code));
}

/* ---- configuration file ------------------------------------------------------------- */

static int cfg_number(const char *file, const config_setting_t *s, const char *field, double lo,
                      double hi, double *out, dem_err *err) {
  int line = config_setting_source_line(s);
  double v;
  switch (config_setting_type(s)) {
  case CONFIG_TYPE_INT:
  case CONFIG_TYPE_INT64:
    v = (double)config_setting_get_int64(s);
    break;
  case CONFIG_TYPE_FLOAT:
    v = config_setting_get_float(s);
    break;
  default:
    return dem_err_set(err, DEM_EPARSE, "%s:%d: field '%s' must be a number", file, line, field);
  }
  if (!isfinite(v))
    return dem_err_set(err, DEM_ENONFINITE, "%s:%d: field '%s' is not finite", file, line, field);
  if (!(v >= lo && v <= hi))
    return dem_err_set(err, DEM_ERANGE,
                       "%s:%d: field '%s' = %g is outside the allowed range [%g, %g]", file, line,
                       field, v, lo, hi);
  *out = v;
  return DEM_OK;
}

static int cfg_word(const char *file, const config_setting_t *s, const char *field,
                    const char *const *words, int *out, dem_err *err) {
  int line = config_setting_source_line(s);
  const char *txt = config_setting_get_string(s);
  if (!txt) return dem_err_set(err, DEM_EPARSE, "%s:%d: field '%s' must be a string", file, line, field);
  char flag[96];
  snprintf(flag, sizeof flag, "%s:%d: field '%s'", file, line, field);
  return cli_parse_word(flag, txt, words, out, err);
}

static int cfg_bool(const char *file, const config_setting_t *s, const char *field, int *out,
                    dem_err *err) {
  if (config_setting_type(s) != CONFIG_TYPE_BOOL)
    return dem_err_set(err, DEM_EPARSE, "%s:%d: field '%s' must be true or false", file,
                       config_setting_source_line(s), field);
  *out = config_setting_get_bool(s);
  return DEM_OK;
}

static const char *const w_target[] = {"wall", "pair", NULL};
static const char *const w_rule[] = {"rayleigh", "mass-spring", NULL};
static const char *const w_integ[] = {"verlet", "reference", NULL};

static int cfg_entry(const char *file, const config_setting_t *s, cli_config *c,
                     dem_params *ps, dem_err *err) {
  const char *name = config_setting_name(s);
  int line = config_setting_source_line(s);
  if (strcmp(name, "law") == 0) {
    const char *txt = config_setting_get_string(s);
    if (!txt || strlen(txt) >= sizeof c->law)
      return dem_err_set(err, DEM_EPARSE, "%s:%d: field 'law' must be a law id string", file,
                         line);
    snprintf(c->law, sizeof c->law, "%s", txt);
    return DEM_OK;
  }
  if (strcmp(name, "velocity") == 0) return cfg_number(file, s, name, 1e-9, 1e4, &c->velocity, err);
  if (strcmp(name, "v_min") == 0) return cfg_number(file, s, name, 1e-9, 1e4, &c->v_min, err);
  if (strcmp(name, "v_max") == 0) return cfg_number(file, s, name, 1e-9, 1e4, &c->v_max, err);
  if (strcmp(name, "dt_factor") == 0)
    return cfg_number(file, s, name, 1e-6, 100.0, &c->dt_factor, err);
  if (strcmp(name, "rtol") == 0) return cfg_number(file, s, name, 1e-14, 1e-3, &c->rtol, err);
  if (strcmp(name, "step") == 0) return cfg_number(file, s, name, 1e-18, 1.0, &c->step, err);
  if (strcmp(name, "sticking") == 0) return cfg_bool(file, s, name, &c->sticking, err);
  if (strcmp(name, "clip_tensile") == 0) return cfg_bool(file, s, name, &c->clip_tensile, err);
  if (strcmp(name, "target") == 0) return cfg_word(file, s, name, w_target, &c->target, err);
  if (strcmp(name, "dt_rule") == 0) return cfg_word(file, s, name, w_rule, &c->dt_rule, err);
  if (strcmp(name, "integrator") == 0)
    return cfg_word(file, s, name, w_integ, &c->integrator, err);
  if (strcmp(name, "path") == 0) {
    if (!config_setting_is_aggregate(s) || config_setting_is_group(s))
      return dem_err_set(err, DEM_EPARSE, "%s:%d: field 'path' must be a list [a0, a1, ...] (m)",
                         file, line);
    int n = config_setting_length(s);
    if (n < 1 || n > CLI_PATH_MAX)
      return dem_err_set(err, DEM_ERANGE, "%s:%d: field 'path' needs 1 to %d values, has %d",
                         file, line, CLI_PATH_MAX, n);
    for (int i = 0; i < n; i++) {
      char f[32];
      snprintf(f, sizeof f, "path[%d]", i);
      int rc = cfg_number(file, config_setting_get_elem(s, (unsigned)i), f, -1e3, 1e3,
                          &c->path[i], err);
      if (rc) return rc;
    }
    c->npath = n;
    return DEM_OK;
  }
  if (strcmp(name, "params") == 0) {
    if (!config_setting_is_group(s))
      return dem_err_set(err, DEM_EPARSE, "%s:%d: field 'params' must be a group { key = value; }",
                         file, line);
    int n = config_setting_length(s);
    for (int i = 0; i < n; i++) {
      const config_setting_t *p = config_setting_get_elem(s, (unsigned)i);
      double v;
      int rc = cfg_number(file, p, config_setting_name(p), -DBL_MAX, DBL_MAX, &v, err);
      if (rc) return rc;
      char origin[DEM_ORIGIN_LEN];
      snprintf(origin, sizeof origin, "%s:%d", file, config_setting_source_line(p));
      if (dem_params_find(ps, config_setting_name(p))) continue; /* --set given earlier wins */
      rc = dem_params_set(ps, config_setting_name(p), v, origin, err);
      if (rc) return rc;
    }
    return DEM_OK;
  }
  return dem_err_set(err, DEM_ENOTFOUND,
                     "%s:%d: unknown field '%s' (known: law, velocity, sticking, v_min, v_max, "
                     "target, dt_factor, dt_rule, integrator, rtol, clip_tensile, path, step, "
                     "params)",
                     file, line, name);
}

int cli_config_load(const char *path, cli_config *c, dem_params *ps, dem_err *err) {
  config_t cfg;
  config_init(&cfg);
  int rc = DEM_OK;
  if (config_read_file(&cfg, path) != CONFIG_TRUE) {
    if (config_error_type(&cfg) == CONFIG_ERR_FILE_IO)
      rc = dem_err_set(err, DEM_EIO, "%s: cannot read the configuration file", path);
    else
      rc = dem_err_set(err, DEM_EPARSE, "%s:%d: %s", path, config_error_line(&cfg),
                       config_error_text(&cfg));
    config_destroy(&cfg);
    return rc;
  }
  const config_setting_t *root = config_root_setting(&cfg);
  int n = config_setting_length(root);
  for (int i = 0; i < n && rc == DEM_OK; i++)
    rc = cfg_entry(path, config_setting_get_elem(root, (unsigned)i), c, ps, err);
  config_destroy(&cfg);
  return rc;
}

int cli_getopt_error(char *const *argv, dem_err *err) {
  if (optopt)
    return dem_err_set(err, DEM_EINVAL, "option '%s' needs a value or takes none",
                       argv[optind - 1]);
  return dem_err_set(err, DEM_EINVAL, "unknown option '%s'", argv[optind - 1]);
}

int cli_no_operands(int argc, char *const *argv, dem_err *err) {
  if (optind < argc)
    return dem_err_set(err, DEM_EINVAL, "unexpected argument '%s'", argv[optind]);
  return DEM_OK;
}

/* Other runnable threads right now: the fourth field of /proc/loadavg ("running/total")
 * counts this process too. The least of a few samples 20 ms apart, so that a short-lived
 * process is not counted; -1 where /proc is missing. (The load average itself lags by a
 * minute and would warn after a job that has just ended.) */
static int other_runnable(void) {
  int least = -1;
  for (int k = 0; k < 5; k++) {
    FILE *f = fopen("/proc/loadavg", "r");
    int run = 0, tot = 0;
    if (!f) return -1;
    int got = fscanf(f, "%*f %*f %*f %d/%d", &run, &tot);
    fclose(f);
    if (got != 2) return -1;
    if (least < 0 || run - 1 < least) least = run - 1;
    if (k < 4) nanosleep(&(struct timespec){0, 20000000L}, NULL);
  }
  return least < 0 ? 0 : least;
}

int cli_warn_contention(const char *prog, int threads) {
  const long cores = sysconf(_SC_NPROCESSORS_ONLN);
  if (threads < 2 || cores < 1) return 0;
  const int others = other_runnable();
  if (others < 0 || others + threads <= cores) return 0;
  fprintf(stderr,
          "%s: warning: %d threads on %ld cores with %d other runnable thread%s: the threads "
          "will wait on one another (OpenMP barriers every step) and the run may be many times "
          "slower; use --threads 1 or run when the machine is free\n",
          prog, threads, cores, others, others == 1 ? "" : "s");
  return 1;
}
