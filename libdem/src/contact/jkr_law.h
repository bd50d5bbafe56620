/* The law body shared by `jkr` (jkr.c, where it is defined) and `jkr-modified`
 * (jkr_modified.c). Internal to libdem (not installed). The JKR geometry and its solver are
 * in the public dem/jkr.h, shared with `thornton-ning`.
 */
#ifndef DEM_JKR_LAW_H
#define DEM_JKR_LAW_H

#include "dem/contact.h"
#include "dem/jkr.h"

/* Compiled coefficients. */
enum { DEM_JKR_C_ES, DEM_JKR_C_GAMMA, DEM_JKR_C_ETA, DEM_JKR_C_E, DEM_JKR_NCOEF };
/* History: state (0 apart, 1 in contact), f_c (N), 1/delta_c (1/m) and delta_c (m) cached at
 * formation (delta_c for alpha_t = delta_c s^4: a division there cost 10 ns per force). */
enum { DEM_JKR_H_FC = 1, DEM_JKR_H_IDC = 2, DEM_JKR_H_DC = 3, DEM_JKR_NHIST = 4 };

/* The coefficient table, shared (a definition of another length fails to compile). */
#define DEM_JKR_NCOEFS 6
extern const dem_coef_spec dem_jkrlaw_coefs[DEM_JKR_NCOEFS];
int dem_jkrlaw_set_coeffs(const dem_params *ps, double *c, dem_err *err);
double dem_jkrlaw_kref(const double *c, const dem_geom *g, double v);
/* break_at_zero = 0: JKR breaks below alpha_f; 1: `jkr-modified`, breaks below alpha = 0. */
void dem_jkrlaw_force(const double *c, const dem_geom *g, double *hist, double alpha,
                   double alpha_dot, dem_normal *out, int break_at_zero);

#endif
