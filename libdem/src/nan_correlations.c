/* Parameter correlations of the improved linear elasto-plastic-adhesive law (dem/nan.h).
 *
 * Source: second seed (Nan, Goh & Rahman), section 2 (eqs 3-20), section 3 (eqs 27-72) and
 * section 4 (eqs 73-81), Appendix A (works W_0..W_6). SI units throughout.
 *
 * The force-overlap line of Fig 1: loading from (0, -f_0) with k_el to the yield point
 * (alpha_y, f_y), plastic line k_p to (alpha_max, f_max), elastic unloading k_e(alpha_max) to
 * the pull-off point (alpha_cp, -f_cp), adhesive branch k_c to breakage (alpha_fp, -5/9 f_cp);
 * re-contact at (alpha_c0, -8/9 f_cp). Before yield alpha_max = alpha_y, k_e = k_el,
 * alpha_p = alpha_0, f_cp = f_ce, k_c = k_cl (the paper's remark after eq 16).
 */
#include <math.h>
#include <stddef.h>

#include "dem/nan.h"

static int pos(double x) { return x > 0.0 && isfinite(x); }

double dem_nan_fce(double R, double gamma) {
  if (!pos(R) || !(gamma >= 0.0)) return NAN;
  return 1.5 * M_PI * gamma * R;
}

double dem_nan_fy0(double R, double Es, double py) {
  if (!pos(R) || !pos(Es) || !pos(py)) return NAN;
  return M_PI * M_PI * M_PI * R * R * py * py * py / (6.0 * Es * Es);
}

double dem_nan_alpha_y0(double R, double Es, double py) {
  if (!pos(R) || !pos(Es) || !pos(py)) return NAN;
  return M_PI * M_PI * R * py * py / (4.0 * Es * Es);
}

double dem_nan_fy(double R, double Es, double py, double kel) {
  if (!pos(kel)) return NAN;
  return dem_nan_fy0(R, Es, py) * sqrt(1.2 * kel / (M_PI * R * py));
}

double dem_nan_dalpha_y(double R, double Es, double py, double kel) {
  if (!pos(kel)) return NAN;
  return dem_nan_alpha_y0(R, Es, py) * sqrt(8.0 / 15.0 * M_PI * R * py / kel);
}

double dem_nan_kel_py(double R, double py) {
  if (!pos(R) || !pos(py)) return NAN;
  return M_PI * R * py;
}

double dem_nan_kel_kcl(double R, double Es, double gamma, double kel) {
  if (!pos(R) || !pos(Es) || !pos(gamma) || !pos(kel)) return NAN;
  return 0.92 * kel / cbrt(gamma * Es * Es * R * R) - 0.3;
}

double dem_nan_w_jkr(double R, double Es, double gamma) {
  if (!pos(R) || !pos(Es) || !(gamma >= 0.0)) return NAN;
  double g2 = gamma * gamma;
  return 7.09 * cbrt(g2 * g2 * gamma * R * R * R * R / (Es * Es));
}

double dem_nan_kel_kcl_exact(double R, double Es, double gamma, double kel) {
  if (!pos(kel) || !pos(gamma)) return NAN;
  double fce = dem_nan_fce(R, gamma), w = fce * fce / kel;
  return (dem_nan_w_jkr(R, Es, gamma) - 17.0 / 162.0 * w) / (56.0 / 162.0 * w);
}

double dem_nan_ke(int ke_eq, double kel, double kp, double alpha_max, double alpha_y) {
  double t = alpha_max > alpha_y ? sqrt(alpha_max / alpha_y) : 1.0;
  if (ke_eq == 46) return kel * t;
  if (ke_eq == 48) return kp + (kel - kp) * t;
  return NAN;
}

int dem_nan_kel_from_unloading(double R, double Es, double gamma, double py, double ke0,
                               double alpha_max0, int ke_eq, double kp, double *kel,
                               double *alpha_y, dem_err *err) {
  if (!pos(R) || !pos(Es) || !pos(gamma) || !pos(py) || !pos(ke0) || !pos(alpha_max0))
    return dem_err_set(err, DEM_ERANGE,
                       "nan k_el from unloading data: R* = %g m, E* = %g Pa, gamma = %g J/m^2, "
                       "py = %g Pa, ke0 = %g N/m, amax0 = %g m must all be finite and > 0",
                       R, Es, gamma, py, ke0, alpha_max0);
  if (ke_eq != 46 && ke_eq != 48)
    return dem_err_set(err, DEM_ERANGE, "nan: ke_eq = %d is not 46 or 48", ke_eq);
  int with_kp = (ke_eq == 48) && pos(kp);
  if (with_kp && !(kp < ke0))
    return dem_err_set(err, DEM_EPHYSICS,
                       "nan eq (49): kp = %g N/m must be below ke0 = %g N/m", kp, ke0);
  double fce = dem_nan_fce(R, gamma);
  double ay = dem_nan_alpha_y0(R, Es, py), k = ke0; /* the paper starts at alpha_y = alpha_y0 */
  for (int it = 0; it < 500; it++) {
    double s = sqrt(ay / alpha_max0);
    double knew = with_kp ? kp + (ke0 - kp) * s : ke0 * s; /* eq (49) or (45) */
    double aynew = 8.0 / 9.0 * fce / knew + dem_nan_dalpha_y(R, Es, py, knew); /* (6)+(29) */
    double dk = fabs(knew - k), da = fabs(aynew - ay);
    k = knew;
    ay = aynew;
    if ((dk <= 1e-15 * k && da <= 1e-15 * ay) || (it > 100 && dk <= 1e-14 * k)) {
      *kel = k;
      *alpha_y = ay;
      return DEM_OK;
    }
  }
  /* A contraction mapping for all physical inputs (|d k_new / d k| < 1/2); a failure means
   * the inputs are not physical. */
  return dem_err_set(err, DEM_EMAXITER,
                     "nan: eqs (45)/(49) with (29) did not converge for ke0 = %g N/m, amax0 = "
                     "%g m (last k_el = %g N/m)",
                     ke0, alpha_max0, k);
}

double dem_nan_A(double kel_kcl) {
  return (16.0 / 27.0) / (56.0 / 162.0 * kel_kcl + 17.0 / 162.0);
}

double dem_nan_fcp59(double A, double ke_kel, double ap_a0) {
  double disc = A * A + 4.0 * ke_kel * (ap_a0 * A + 1.0);
  if (!(disc >= 0.0)) return NAN;
  return 0.5 * (-A + sqrt(disc));
}

double dem_nan_fcp61(double ke_kel, double ap_ay_a0, double ap_ay_R) {
  double r = 96.0 / 137.0 * ke_kel * ap_ay_a0 * (2.0 - ap_ay_R);
  return r > 0.0 ? sqrt(r) : 0.0;
}

double dem_nan_fcp64(double fy, double ke, double kp, double amax_ay) {
  return (fy + ke * amax_ay) / (fy + kp * amax_ay);
}

double dem_nan_fcp67(double ke_kel) { return ke_kel * sqrt(ke_kel); }

int dem_nan_coeffs_init(dem_nan_coeffs *k, const dem_nan_input *in, dem_err *err) {
  if (!pos(in->R) || !pos(in->Es) || !pos(in->gamma) || !pos(in->py))
    return dem_err_set(err, DEM_ERANGE,
                       "nan: R* = %g m, E* = %g Pa, gamma = %g J/m^2, py = %g Pa must all be "
                       "finite and > 0",
                       in->R, in->Es, in->gamma, in->py);
  if (in->ke_eq != 46 && in->ke_eq != 48)
    return dem_err_set(err, DEM_ERANGE, "nan: ke_eq = %d is not 46 (eq 46) or 48 (eq 48)",
                       in->ke_eq);
  if (in->fcp_eq != 59 && in->fcp_eq != 64 && in->fcp_eq != 67)
    return dem_err_set(err, DEM_ERANGE, "nan: fcp_eq = %d is not 59, 64 or 67", in->fcp_eq);
  k->R = in->R;
  k->Es = in->Es;
  k->gamma = in->gamma;
  k->py = in->py;
  k->ke_eq = in->ke_eq;
  k->fcp_eq = in->fcp_eq;
  k->kel = pos(in->kel) ? in->kel : dem_nan_kel_py(in->R, in->py);
  k->kp = pos(in->kp) ? in->kp : k->kel;
  if (k->kp > k->kel)
    return dem_err_set(err, DEM_EPHYSICS,
                       "nan: kp = %g N/m exceeds k_el = %g N/m (R* = %g m): the plastic line "
                       "would lie above the elastic one (eq 20 needs kp <= k_el <= k_e)",
                       k->kp, k->kel, k->R);
  k->r_kc = pos(in->kel_kcl) ? in->kel_kcl : dem_nan_kel_kcl(k->R, k->Es, k->gamma, k->kel);
  if (!pos(k->r_kc))
    return dem_err_set(err, DEM_EPHYSICS,
                       "nan: eq (38) gives k_el/k_cl = %g <= 0 for k_el = %g N/m, gamma = %g "
                       "J/m^2, E* = %g Pa, R* = %g m: k_el is too small to give the JKR "
                       "adhesive work (needs k_el > %g N/m)",
                       k->r_kc, k->kel, k->gamma, k->Es, k->R,
                       0.3 / 0.92 * cbrt(k->gamma * k->Es * k->Es * k->R * k->R));
  k->kcl = k->kel / k->r_kc;
  k->A = dem_nan_A(k->r_kc);
  k->fce = dem_nan_fce(k->R, k->gamma);
  k->f0 = 8.0 / 9.0 * k->fce;                                 /* eq (4) */
  k->alpha0 = k->f0 / k->kel;                                 /* eq (6) */
  k->fy = dem_nan_fy(k->R, k->Es, k->py, k->kel);             /* eq (28) */
  k->alphay = k->alpha0 + k->fy / k->kel;                     /* eq (7) */
  /* The yield overlap must lie inside the overlap range of the law's small-overlap geometry
   * (eqs 30-31 are Hertz/JKR results, a^2 = R* alpha): alpha_y >= R* would make every impact
   * elastic up to overlaps beyond the radius (the sibling law `thornton` rejects
   * alpha_y > R* the same way). */
  if (!(k->alphay < k->R))
    return dem_err_set(err, DEM_EPHYSICS,
                       "nan: the yield overlap alpha_y = %g m (eqs 7, 29) is not below R* = %g m "
                       "for py = %g Pa, E* = %g Pa, k_el = %g N/m: p_y is too large for the "
                       "law's small-overlap geometry",
                       k->alphay, k->R, k->py, k->Es, k->kel);
  return DEM_OK;
}

void dem_nan_unloading(const dem_nan_coeffs *k, double alpha_max, dem_nan_unload *u) {
  double am = alpha_max > k->alphay ? alpha_max : k->alphay; /* eq (10) */
  u->alpha_max = am;
  u->f_max = k->fy + k->kp * (am - k->alphay);
  u->ke = dem_nan_ke(k->ke_eq, k->kel, k->kp, am, k->alphay);
  u->kc = u->ke / k->r_kc;
  /* eq (16) in the form alpha_p = alpha_max - f_max / k_e (identical to eqs 11 and 16 with
   * f_y = k_el (alpha_y - alpha_0)); > 0 whenever kp <= k_el (docs/contact-laws.md). */
  u->alpha_p = am - u->f_max / u->ke;
  double x;
  if (!(am > k->alphay)) {
    x = 1.0; /* before yield every form reduces to f_cp = f_ce */
    u->alpha_p = k->alpha0;
  } else if (k->fcp_eq == 64) {
    x = dem_nan_fcp64(k->fy, u->ke, k->kp, am - k->alphay);
  } else if (k->fcp_eq == 67) {
    x = dem_nan_fcp67(u->ke / k->kel);
  } else {
    x = dem_nan_fcp59(k->A, u->ke / k->kel, u->alpha_p / k->alpha0);
    if (!(x >= 0.0)) x = 0.0; /* unreachable for alpha_p > 0 (see above) */
  }
  u->f_cp = x * k->fce;
  u->alpha_cp = u->alpha_p - u->f_cp / u->ke;                          /* eq (13) */
  u->alpha_fp = u->alpha_cp - 4.0 / 9.0 * u->f_cp / u->kc;             /* eq (14) */
  u->alpha_c0 = u->alpha_p - 8.0 / 9.0 * u->f_cp / u->ke;              /* eq (12) */
  if (!(am > k->alphay)) u->alpha_c0 = 0.0; /* exactly: the first contact forms at 0 */
}

double dem_nan_dt_crit(double m, double ke) {
  if (!pos(m) || !pos(ke)) return NAN;
  return 2.0 * sqrt(m / ke);
}

double dem_nan_dt_crit_hertz(double R, double rho, double E, double alpha_max) {
  if (!pos(R) || !pos(rho) || !pos(E) || !pos(alpha_max)) return NAN;
  return M_PI * R * sqrt(rho / E) * sqrt(8.0 / (3.0 * M_PI)) * pow(alpha_max / R, -0.25);
}

double dem_nan_dt_ratio(double nu, double amax_R) {
  if (!(nu > -1.0 && nu <= 0.5) || !pos(amax_R)) return NAN;
  return (0.1631 * nu + 0.8766) / sqrt(1.0 + nu) * sqrt(4.0 / (3.0 * M_PI)) *
         pow(amax_R, -0.25);
}

double dem_nan_cy(double R, double Es, double gamma, double py) {
  if (!pos(R) || !pos(Es) || !pos(gamma) || !pos(py)) return NAN;
  return py * py * py * R / (Es * Es * gamma);
}

double dem_nan_py_crit(double R, double Es, double gamma) {
  if (!pos(R) || !pos(Es) || !pos(gamma)) return NAN;
  return 2.0 / cbrt(M_PI * M_PI) * pow(5.0 / 6.0, 1.0 / 6.0) * cbrt(gamma * Es * Es / R);
}

double dem_nan_vs(double R, double Es, double gamma, double m) {
  if (!pos(m)) return NAN;
  return sqrt(2.0 * dem_nan_w_jkr(R, Es, gamma) / m);
}

double dem_nan_vy0(const dem_nan_coeffs *k, double m) {
  if (!pos(m)) return NAN;
  return k->fy / sqrt(m * k->kel);
}

double dem_nan_vy2(const dem_nan_coeffs *k, double m) {
  if (!pos(m)) return NAN;
  return (k->fy * k->fy - k->f0 * k->f0) / (m * k->kel);
}

int dem_nan_vys(const dem_nan_coeffs *k, double m, double *vys, double *f_max, dem_err *err) {
  if (!pos(m)) return dem_err_set(err, DEM_ERANGE, "nan V_ys: mass m = %g kg must be > 0", m);
  double vs = dem_nan_vs(k->R, k->Es, k->gamma, m), vy2 = dem_nan_vy2(k, m);
  if (vy2 >= vs * vs) { /* eq (77): not yielded at V_ys = V_s */
    *vys = vs;
    if (f_max) *f_max = sqrt(2.0 * k->kel * 0.5 * m * vs * vs + k->f0 * k->f0);
    return DEM_OK;
  }
  /* Fixed point on f_max: alpha_max (10), k_e (46/48), alpha_p (16), f_cp (59), then
   * f_max from W_e = W_c (78): f_max = f_cp sqrt(1 + 56/81 k_e/k_c). */
  double fm = k->fy, g = sqrt(1.0 + 56.0 / 81.0 * k->r_kc);
  dem_nan_unload u;
  for (int it = 0; it < 2000; it++) {
    dem_nan_unloading(k, k->alphay + (fm - k->fy) / k->kp, &u);
    double fn = u.f_cp * g;
    if (fabs(fn - fm) <= 1e-15 * fn || (it > 200 && fabs(fn - fm) <= 1e-13 * fn)) {
      fm = fn;
      double v2 = vy2 + (fm * fm - k->fy * k->fy) / (m * k->kp); /* eq (79) */
      *vys = sqrt(v2);
      if (f_max) *f_max = fm;
      return DEM_OK;
    }
    fm = fn;
  }
  return dem_err_set(err, DEM_EMAXITER,
                     "nan V_ys: eqs (78)-(79) did not converge (R* = %g m, py = %g Pa, last "
                     "f_max = %g N)",
                     k->R, k->py, fm);
}

int dem_nan_impact(const dem_nan_coeffs *k, double m, double v, dem_nan_impact_cf *r,
                   dem_err *err) {
  if (!pos(m) || !(v > 0.0) || !isfinite(v))
    return dem_err_set(err, DEM_ERANGE,
                       "nan impact: mass m = %g kg and velocity v = %g m/s must be > 0", m, v);
  double f2 = k->f0 * k->f0 + k->kel * m * v * v, am;
  dem_nan_unload u;
  if (f2 <= k->fy * k->fy) { /* no yield: the line BC */
    r->f_max = sqrt(f2);
    am = k->alpha0 + r->f_max / k->kel;
    dem_nan_unloading(k, k->alphay, &u);
  } else {
    r->f_max = sqrt(k->fy * k->fy + k->kp * (m * v * v - m * dem_nan_vy2(k, m)));
    am = k->alphay + (r->f_max - k->fy) / k->kp;
    dem_nan_unloading(k, am, &u);
  }
  r->alpha_max = am;
  r->alpha_p = u.alpha_p;
  r->f_cp = u.f_cp;
  double w = r->f_max * r->f_max / (2.0 * u.ke) -
             0.5 * u.f_cp * u.f_cp / u.ke * (1.0 + 56.0 / 81.0 * u.ke / u.kc);
  r->stuck = !(w > 0.0);
  r->v_rebound = r->stuck ? 0.0 : sqrt(2.0 * w / m);
  r->e = r->v_rebound / v;
  return DEM_OK;
}
