/* Config readers' shared helpers: typed getters and errors that name file, line and field. */
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

/* Scene keys a calibration may fix besides the law's coefficients (dem_impact_setup). */
const char *const cal_cfg_scene_keys[] = {"R", "rho", "E", "nu", NULL};

int cal_cfg_line_of(const config_setting_t *s) {
  return s ? (int)config_setting_source_line(s) : 0;
}

int cal_cfg_fail(const cal_cfg_ctx *cx, const config_setting_t *s, const char *field, int code,
                const char *fmt, ...) {
  char msg[DEM_ERRMSG_LEN];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return dem_err_set(cx->err, code, "%s:%d: %s: %s", cx->file, cal_cfg_line_of(s), field, msg);
}

/* A number setting (int or float); 1 if present. */
int cal_cfg_get_num(const cal_cfg_ctx *cx, const config_setting_t *grp, const char *key,
                   const char *field, double *v, int *rc) {
  const config_setting_t *s = config_setting_get_member(grp, key);
  *rc = DEM_OK;
  if (!s) return 0;
  switch (config_setting_type(s)) {
  case CONFIG_TYPE_INT: *v = (double)config_setting_get_int(s); break;
  case CONFIG_TYPE_INT64: *v = (double)config_setting_get_int64(s); break;
  case CONFIG_TYPE_FLOAT: *v = config_setting_get_float(s); break;
  default:
    *rc = cal_cfg_fail(cx, s, field, DEM_EPARSE, "expected a number");
    return 0;
  }
  if (!isfinite(*v)) *rc = cal_cfg_fail(cx, s, field, DEM_ENONFINITE, "not finite");
  return 1;
}

int cal_cfg_get_str(const cal_cfg_ctx *cx, const config_setting_t *grp, const char *key,
                   const char *field, const char **v, int *rc) {
  const config_setting_t *s = config_setting_get_member(grp, key);
  *rc = DEM_OK;
  if (!s) return 0;
  if (config_setting_type(s) != CONFIG_TYPE_STRING) {
    *rc = cal_cfg_fail(cx, s, field, DEM_EPARSE, "expected a string");
    return 0;
  }
  *v = config_setting_get_string(s);
  return 1;
}

int cal_cfg_get_int(const cal_cfg_ctx *cx, const config_setting_t *grp, const char *key,
                   const char *field, int lo, int hi, int *v, int *rc) {
  double d;
  if (!cal_cfg_get_num(cx, grp, key, field, &d, rc)) return 0;
  if (*rc) return 0;
  if (d != floor(d) || d < lo || d > hi) {
    *rc = cal_cfg_fail(cx, config_setting_get_member(grp, key), field, DEM_ERANGE,
               "%g is not an integer in [%d, %d]", d, lo, hi);
    return 0;
  }
  *v = (int)d;
  return 1;
}

/* The allowed range of a law coefficient or scene key, for bounds checks. */
const dem_coef_spec *cal_cfg_coef_spec(const dem_law *law, const char *key) {
  for (int i = 0; i < law->ncoef; i++)
    if (strcmp(law->coef[i].key, key) == 0) return &law->coef[i];
  return NULL;
}

int cal_cfg_is_scene_key(const char *k) {
  for (const char *const *s = cal_cfg_scene_keys; *s; s++)
    if (strcmp(*s, k) == 0) return 1;
  return 0;
}

void cal_cfg_law_keys(const dem_law *law, char *buf, size_t n) {
  size_t used = 0;
  buf[0] = '\0';
  for (int i = 0; i < law->ncoef && used + 8 < n; i++)
    used += (size_t)snprintf(buf + used, n - used, "%s%s", i ? ", " : "", law->coef[i].key);
}

int cal_cfg_read_fixed(const cal_cfg_ctx *cx, cal_config *c, const config_setting_t *grp,
                      const char *field0, dem_params *ps, int scene_ok) {
  if (config_setting_type(grp) != CONFIG_TYPE_GROUP)
    return cal_cfg_fail(cx, grp, field0, DEM_EPARSE, "expected a group { key = value; ... }");
  for (int i = 0; i < config_setting_length(grp); i++) {
    config_setting_t *s = config_setting_get_elem(grp, (unsigned)i);
    const char *k = config_setting_name(s);
    char field[128];
    snprintf(field, sizeof field, "%s.%s", field0, k);
    if (!dem_contact_law_has_coef(c->law, k) && !(scene_ok && cal_cfg_is_scene_key(k))) {
      char keys[256];
      cal_cfg_law_keys(c->law, keys, sizeof keys);
      return cal_cfg_fail(cx, s, field, DEM_ENOTFOUND,
                  "law '%s' has no parameter '%s' (its parameters: %s; scene keys: R, rho, E, "
                  "nu)",
                  c->law->name, k, keys);
    }
    double v;
    int rc;
    if (!cal_cfg_get_num(cx, grp, k, field, &v, &rc)) return rc ? rc : cal_cfg_fail(cx, s, field, DEM_EPARSE, "expected a number");
    if (rc) return rc;
    char origin[DEM_ORIGIN_LEN];
    snprintf(origin, sizeof origin, "%s:%d", cx->file, cal_cfg_line_of(s));
    dem_err e2 = {0};
    if (dem_params_set(ps, k, v, origin, &e2))
      return cal_cfg_fail(cx, s, field, e2.code, "%s", e2.msg);
  }
  return DEM_OK;
}
