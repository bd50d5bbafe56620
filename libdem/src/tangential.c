/* Tangential friction and rolling resistance (dem/tangential.h): set-up and the external
 * definitions of the inline per-step kernels.
 *
 * Set-up validates once, outside the force loop (LAMMPS-style: incompatible or out-of-range
 * input is rejected at set-up, never in the loop):
 *   linear   kt in (0, 1e12] N/m                                   thesis 3.11 / 4.26
 *   mindlin  G* = ((2-nu1)/G1 + (2-nu2)/G2)^-1 from E, nu, wall_E, wall_nu (Mindlin 1949;
 *            see dem/material.h on the thesis' eq 3.20), k_t = 8 G* sqrt(R* alpha)   3.25
 *   mu       in [0, 10], required for both kinds                   3.22 / 4.27
 *   e        in [1e-3, 1], optional: eta = 2 |ln e| / sqrt(pi^2 + ln^2 e)  paper 25-26
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "dem/contact.h"
#include "dem/material.h"
#include "dem/tangential.h"

/* External definitions of the inline kernels (C99 6.7.4). */
extern inline void dem_tangential_stiffness(const dem_tangential *t, double R, double alpha_eff,
                                            double m, double *k_out, double *c_out);
extern inline int dem_tangential_spring(const dem_tangential *t, double xi[3],
                                        const double n[3], const double v[3], double dt,
                                        double k, double c, double fn, double f_adh,
                                        double ft[3]);
extern inline int dem_tangential_force(const dem_tangential *t, double xi[3], const double n[3],
                                       const double vt[3], double dt, double R,
                                       double alpha_eff, double m, double fn, double f_adh,
                                       double ft[3]);
extern inline void dem_rolling_torque(const dem_rolling *r, const double w_rel[3],
                                      double fn_abs, double R_i, double w_eps,
                                      double m_out[3]);

/* Read key into *v: present, finite and within [lo, hi] (lo_open: > lo), or absent with a
 * default (def not NaN). Errors name the key, its value, unit and allowed range. */
static int get_key(const dem_params *ps, const char *what, const char *key, const char *unit,
                   double lo, int lo_open, double hi, double def, double *v, dem_err *err) {
  if (!dem_params_get(ps, key, v)) {
    if (isnan(def))
      return dem_err_set(err, DEM_EMISSING, "%s needs '%s' (%s, allowed %s%g, %g])", what, key,
                         unit, lo_open ? "(" : "[", lo, hi);
    *v = def;
    return DEM_OK;
  }
  if (!isfinite(*v))
    return dem_err_set(err, DEM_ENONFINITE, "%s%s: '%s' = %g is not finite",
                       dem_params_origin(ps, key), what, key, *v);
  if (!(lo_open ? *v > lo : *v >= lo) || !(*v <= hi))
    return dem_err_set(err, DEM_ERANGE, "%s%s: '%s' = %g %s is outside the allowed range %s%g, %g]",
                       dem_params_origin(ps, key), what, key, *v, unit, lo_open ? "(" : "[", lo,
                       hi);
  return DEM_OK;
}

int dem_tangential_setup(dem_tangential *t, dem_tangential_kind kind, const dem_params *ps,
                         dem_err *err) {
  if (!t || !ps) return dem_err_set(err, DEM_EINVAL, "dem_tangential_setup: NULL argument");
  memset(t, 0, sizeof *t);
  if (kind == DEM_TANGENTIAL_NONE) return DEM_OK;
  if (kind != DEM_TANGENTIAL_LINEAR && kind != DEM_TANGENTIAL_MINDLIN)
    return dem_err_set(err, DEM_EINVAL, "dem_tangential_setup: unknown tangential kind %d",
                       (int)kind);
  const char *what =
      kind == DEM_TANGENTIAL_LINEAR ? "tangential 'linear'" : "tangential 'mindlin'";
  int rc;
  if (kind == DEM_TANGENTIAL_LINEAR) {
    rc = get_key(ps, what, "kt", "N/m", 0.0, 1, 1e12, NAN, &t->kt, err);
    if (rc) return rc;
  } else {
    double E, nu, E2, nu2;
    if ((rc = get_key(ps, what, "E", "Pa", 0.0, 1, 1e30, NAN, &E, err))) return rc;
    if ((rc = get_key(ps, what, "nu", "-", -1.0, 1, 0.5, NAN, &nu, err))) return rc;
    /* wall_E = 1e30 stands for a rigid wall (dem_params holds finite values only). */
    if ((rc = get_key(ps, what, "wall_E", "Pa", 0.0, 1, 1e30, E, &E2, err))) return rc;
    if ((rc = get_key(ps, what, "wall_nu", "-", -1.0, 1, 0.5, nu, &nu2, err))) return rc;
    t->G = dem_reduced_shear_modulus(E, nu, E2, nu2);
  }
  if ((rc = get_key(ps, what, "mu", "-", 0.0, 0, 10.0, NAN, &t->mu, err))) return rc;
  double e;
  if ((rc = get_key(ps, what, "e", "-", 1e-3, 0, 1.0, 1.0, &e, err))) return rc;
  t->eta = dem_damping_eta_linear(e);
  t->kind = kind;
  return DEM_OK;
}

int dem_rolling_setup(dem_rolling *r, const dem_params *ps, dem_err *err) {
  if (!r || !ps) return dem_err_set(err, DEM_EINVAL, "dem_rolling_setup: NULL argument");
  r->mu_r = 0.0;
  return get_key(ps, "rolling resistance", "mu_r", "-", 0.0, 0, 1.0, 0.0, &r->mu_r, err);
}
