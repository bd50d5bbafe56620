/* Named parameter sets (dem/params.h). */
#include "dem/params.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void dem_params_init(dem_params *ps) { memset(ps, 0, sizeof *ps); }

const dem_param *dem_params_find(const dem_params *ps, const char *key) {
  for (int i = 0; i < ps->n; i++)
    if (strcmp(ps->p[i].key, key) == 0) return &ps->p[i];
  return NULL;
}

int dem_params_set(dem_params *ps, const char *key, double value, const char *origin,
                   dem_err *err) {
  const char *where = origin ? origin : "";
  size_t len = strlen(key);
  if (len == 0 || len >= DEM_KEY_LEN)
    return dem_err_set(err, DEM_EINVAL, "%s%sparameter key '%s' must have 1 to %d characters",
                       where, *where ? ": " : "", key, DEM_KEY_LEN - 1);
  if (!isfinite(value))
    return dem_err_set(err, DEM_ENONFINITE, "%s%sparameter '%s' is not finite (%g)", where,
                       *where ? ": " : "", key, value);
  dem_param *p = (dem_param *)dem_params_find(ps, key);
  if (!p) {
    if (ps->n >= DEM_PARAMS_MAX)
      return dem_err_set(err, DEM_ERANGE, "%s%stoo many parameters (at most %d)", where,
                         *where ? ": " : "", DEM_PARAMS_MAX);
    p = &ps->p[ps->n++];
    memcpy(p->key, key, len + 1);
  }
  p->value = value;
  snprintf(p->origin, sizeof p->origin, "%s", where);
  return DEM_OK;
}

int dem_params_parse_assignment(dem_params *ps, const char *text, const char *origin,
                                dem_err *err) {
  const char *where = origin ? origin : "";
  const char *eq = strchr(text, '=');
  if (!eq || eq == text)
    return dem_err_set(err, DEM_EPARSE, "%s%sexpected key=value, got '%s'", where,
                       *where ? ": " : "", text);
  char key[DEM_KEY_LEN];
  size_t klen = (size_t)(eq - text);
  if (klen >= sizeof key)
    return dem_err_set(err, DEM_EINVAL, "%s%skey too long in '%s'", where, *where ? ": " : "",
                       text);
  memcpy(key, text, klen);
  key[klen] = '\0';
  errno = 0;
  char *end = NULL;
  double v = strtod(eq + 1, &end);
  if (end == eq + 1 || *end != '\0' || errno == ERANGE)
    return dem_err_set(err, DEM_EPARSE, "%s%svalue of '%s' is not a number: '%s'", where,
                       *where ? ": " : "", key, eq + 1);
  return dem_params_set(ps, key, v, origin, err);
}

int dem_params_get(const dem_params *ps, const char *key, double *value) {
  const dem_param *p = dem_params_find(ps, key);
  if (!p) return 0;
  if (value) *value = p->value;
  return 1;
}

double dem_params_get_or(const dem_params *ps, const char *key, double fallback) {
  const dem_param *p = dem_params_find(ps, key);
  return p ? p->value : fallback;
}

const char *dem_params_origin(const dem_params *ps, const char *key) {
  /* A per-thread scratch buffer keeps the call convenient inside printf arguments. */
  static _Thread_local char buf[DEM_ORIGIN_LEN + 4];
  const dem_param *p = dem_params_find(ps, key);
  if (!p || !p->origin[0]) return "";
  snprintf(buf, sizeof buf, "%s: ", p->origin);
  return buf;
}
