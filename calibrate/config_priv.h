/* calibrate/config_priv.h — helpers shared by the config readers (config*.c). Every error
 * they produce reads "file:line: field: message". */
#ifndef CAL_CONFIG_PRIV_H
#define CAL_CONFIG_PRIV_H

#include <libconfig.h>

#include "cal.h"

typedef struct cal_cfg_ctx {
  const char *file; /* the config file, for messages */
  dem_err *err;
} cal_cfg_ctx;

/* Scene keys a calibration may fix besides the law's coefficients (dem_impact_setup). */
extern const char *const cal_cfg_scene_keys[];

int cal_cfg_line_of(const config_setting_t *s);
int cal_cfg_fail(const cal_cfg_ctx *cx, const config_setting_t *s, const char *field, int code,
                 const char *fmt, ...) __attribute__((format(printf, 5, 6)));
/* A number (int or float) / string / integer in [lo, hi] member of grp; 1 if present, with *rc
 * set on a malformed value. */
int cal_cfg_get_num(const cal_cfg_ctx *cx, const config_setting_t *grp, const char *key,
                    const char *field, double *v, int *rc);
int cal_cfg_get_str(const cal_cfg_ctx *cx, const config_setting_t *grp, const char *key,
                    const char *field, const char **v, int *rc);
int cal_cfg_get_int(const cal_cfg_ctx *cx, const config_setting_t *grp, const char *key,
                    const char *field, int lo, int hi, int *v, int *rc);
const dem_coef_spec *cal_cfg_coef_spec(const dem_law *law, const char *key);
int cal_cfg_is_scene_key(const char *k);
void cal_cfg_law_keys(const dem_law *law, char *buf, size_t n);
/* A group { key = number; ... } of law coefficients (and scene keys if scene_ok) into ps. */
int cal_cfg_read_fixed(const cal_cfg_ctx *cx, cal_config *c, const config_setting_t *grp,
                       const char *field0, dem_params *ps, int scene_ok);
/* targets[i] (config_targets.c). */
int cal_cfg_read_target(const cal_cfg_ctx *cx, cal_config *c, const config_setting_t *g, int i);

#endif
