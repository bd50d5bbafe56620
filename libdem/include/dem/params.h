/* dem/params.h — named parameter sets (key = value, SI units).
 *
 * The key names are the ones fixed in the physics notes (R, rho, E, nu, wall_E, wall_nu,
 * gamma, py, kn, ke, kp, kc, kt, ke_max, phi_f, kcp, f0, f0p, e, beta, mu, mu_r); a law may
 * declare further keys of its own in its coefficient table. A dem_params is a small value
 * type (no allocation): it remembers, for each value, where it came from (a file and line,
 * or a command-line flag) so that an error can point back at it.
 */
#ifndef DEM_PARAMS_H
#define DEM_PARAMS_H

#include "dem/error.h"

#define DEM_PARAMS_MAX 64
#define DEM_KEY_LEN 32
#define DEM_ORIGIN_LEN 96

typedef struct dem_param {
  char key[DEM_KEY_LEN];
  double value;
  char origin[DEM_ORIGIN_LEN]; /* e.g. "impact.cfg:12" or "--set"; "" if unknown */
} dem_param;

typedef struct dem_params {
  int n;
  dem_param p[DEM_PARAMS_MAX];
} dem_params;

void dem_params_init(dem_params *ps);
/* Set (or overwrite) key. Rejects NaN/inf, over-long keys and a full set. */
int dem_params_set(dem_params *ps, const char *key, double value, const char *origin,
                   dem_err *err);
/* Parse "key=value" (value a C floating-point literal, SI units). */
int dem_params_parse_assignment(dem_params *ps, const char *text, const char *origin,
                                dem_err *err);
/* 1 and *value if present, else 0. */
int dem_params_get(const dem_params *ps, const char *key, double *value);
/* The value if present, else fallback. */
double dem_params_get_or(const dem_params *ps, const char *key, double fallback);
const dem_param *dem_params_find(const dem_params *ps, const char *key);
/* Where a key came from, for messages: "impact.cfg:12: " or "--set gamma: " or "". */
const char *dem_params_origin(const dem_params *ps, const char *key);

#endif
