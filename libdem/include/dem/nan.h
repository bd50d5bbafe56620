/* dem/nan.h — the parameter correlations of the improved linear elasto-plastic-adhesive
 * law (second seed: Nan, Goh & Rahman, "Elasto-plastic and adhesive contact: an improved
 * linear model and its application"; the `nan` contact law uses them).
 *
 * Every function takes the reduced quantities of one contact: R* (m), E* (Pa), the interface
 * energy Gamma (J/m^2, f_ce = 1.5 pi Gamma R*), the limiting contact pressure p_y (Pa) and
 * stiffnesses in N/m. Equation numbers are the paper's. Functions returning a double return
 * NAN for inputs outside their domain (non-positive radius, modulus, ...); the functions
 * returning int report errors through dem_err, naming the values.
 */
#ifndef DEM_NAN_H
#define DEM_NAN_H

#include "dem/error.h"

/* ---- elementary correlations ---------------------------------------------------------- */

/* f_ce = 1.5 pi Gamma R*, eq (5). N. */
double dem_nan_fce(double R, double gamma);
/* Thornton-Ning yield force f_y0 = pi^3 R*^2 p_y^3 / (6 E*^2), eq (30). N. */
double dem_nan_fy0(double R, double Es, double py);
/* Thornton-Ning yield overlap alpha_y0 = pi^2 R* p_y^2 / (4 E*^2), eq (31). m. */
double dem_nan_alpha_y0(double R, double Es, double py);
/* Yield force of the linear law, f_y = f_y0 sqrt(6/5 k_el / (pi R* p_y)), eq (28): the same
 * yield work as Thornton-Ning, eq (27). N. */
double dem_nan_fy(double R, double Es, double py, double kel);
/* alpha_y - alpha_0 = f_y / k_el = alpha_y0 sqrt(8/15 pi R* p_y / k_el), eq (29). m. */
double dem_nan_dalpha_y(double R, double Es, double py, double kel);
/* k_el = 2 E* sqrt(R* alpha_y0) = pi R* p_y, eq (52). N/m. */
double dem_nan_kel_py(double R, double py);
/* k_el/k_cl = 0.92 k_el / (Gamma^1/3 E*^2/3 R*^2/3) - 0.3, eq (38) (the rounded form). */
double dem_nan_kel_kcl(double R, double Es, double gamma, double kel);
/* The same ratio from eqs (36)-(37) without rounding the coefficients:
 * k_el/k_cl = (W_JKR - 17/162 f_ce^2/k_el) / (56/162 f_ce^2/k_el), W_JKR eq (37). */
double dem_nan_kel_kcl_exact(double R, double Es, double gamma, double kel);
/* W_JKR = 7.09 (Gamma^5 R*^4 / E*^2)^(1/3), eq (37). J. */
double dem_nan_w_jkr(double R, double Es, double gamma);
/* Unloading stiffness after yield from k_el (the lower limit at alpha_max = alpha_y):
 * ke_eq = 46: k_e = k_el sqrt(alpha_max/alpha_y), eq (46) (the default of the law);
 * ke_eq = 48: k_e = k_p + (k_el - k_p) sqrt(alpha_max/alpha_y), the form of eqs (47)-(49).
 * alpha_max < alpha_y gives k_el. NAN for another ke_eq. N/m. */
double dem_nan_ke(int ke_eq, double kel, double kp, double alpha_max, double alpha_y);
/* k_el from a measured unloading line (k_e0 at alpha_max0): eq (45) (kp NAN or ke_eq 46) or
 * eq (49) (ke_eq 48 with kp), solved together with eq (29) by fixed-point iteration from
 * alpha_y = alpha_y0, as the paper prescribes. Writes k_el (N/m) and alpha_y (m). */
int dem_nan_kel_from_unloading(double R, double Es, double gamma, double py, double ke0,
                               double alpha_max0, int ke_eq, double kp, double *kel,
                               double *alpha_y, dem_err *err);

/* ---- the law's constants for one contact ---------------------------------------------- */

typedef struct dem_nan_input {
  double R;        /* m, R* */
  double Es;       /* Pa, E* */
  double gamma;    /* J/m^2 */
  double py;       /* Pa */
  double kel;      /* N/m, elastic stiffness before yield; NAN or <= 0: eq (52) */
  double kp;       /* N/m, plastic stiffness; NAN or <= 0: k_el (paper section 3.6) */
  double kel_kcl;  /* k_el/k_cl; NAN or <= 0: eq (38) */
  int ke_eq;       /* 46 (default) or 48 */
  int fcp_eq;      /* 59 (default), 64 or 67 (eq 61 is a comparison function only) */
} dem_nan_input;

typedef struct dem_nan_coeffs {
  double R, Es, gamma, py; /* m, Pa, J/m^2, Pa */
  double kel, kp, kcl;     /* N/m */
  double r_kc;             /* k_el/k_cl = k_e/k_c (paper: the ratio is kept after yield) */
  double A;                /* eq (56) */
  double fce, f0, fy;      /* N: eqs (5), (4), (28) */
  double alpha0, alphay;   /* m: eqs (6), (7)/(29) */
  int ke_eq, fcp_eq;
} dem_nan_coeffs;

/* Validate and derive: k_p <= k_el (the plastic line must lie below the elastic one),
 * k_el/k_cl > 0, ke_eq and fcp_eq known; errors name the values. */
int dem_nan_coeffs_init(dem_nan_coeffs *k, const dem_nan_input *in, dem_err *err);

/* The unloading line that starts at alpha_max (Fig 1, points D-E-F): */
typedef struct dem_nan_unload {
  double alpha_max; /* m, max(alpha_max, alpha_y), eq (10) */
  double f_max;     /* N, f_y + k_p (alpha_max - alpha_y) */
  double ke, kc;    /* N/m: eq (46) or (48); k_c = k_e k_cl/k_el */
  double alpha_p;   /* m, eq (16) */
  double f_cp;      /* N, >= 0: eq (59) (or 64, 67 as set) */
  double alpha_cp, alpha_fp, alpha_c0; /* m: eqs (13), (14), (12) */
} dem_nan_unload;
void dem_nan_unloading(const dem_nan_coeffs *k, double alpha_max, dem_nan_unload *u);

/* ---- maximum pull-off force, section 3.4 (all return f_cp / f_ce) ----------------------- */

/* Eq (56): A = (16/27) / (56/162 k_el/k_cl + 17/162). */
double dem_nan_A(double kel_kcl);
/* Eq (59), the law's default. Returns NAN if the discriminant is negative. */
double dem_nan_fcp59(double A, double ke_kel, double ap_a0);
/* Eq (61), re-derived from Pasha et al. 2014: sqrt(B k_e/k_el (a_p - a_y)/a_0 (2 - (a_p -
 * a_y)/R*)), B = 96/137 (eq 62); 0 where the radicand is negative (alpha_p < alpha_y: the
 * paper notes that the equation then predicts no pull-off force). */
double dem_nan_fcp61(double ke_kel, double ap_ay_a0, double ap_ay_R);
/* Eq (64): (f_y + k_e (a_max - a_y)) / (f_y + k_p (a_max - a_y)). */
double dem_nan_fcp64(double fy, double ke, double kp, double amax_ay);
/* Eq (67): (k_e/k_el)^(3/2). */
double dem_nan_fcp67(double ke_kel);

/* ---- time step, section 3.5 ---------------------------------------------------------- */

/* Eq (68): 2 sqrt(m/k_e). s. */
double dem_nan_dt_crit(double m, double ke);
/* Eq (70): pi R sqrt(rho/E) sqrt(8/(3 pi)) (alpha_max/R)^(-1/4) (k_e at the Hertz bound 69). */
double dem_nan_dt_crit_hertz(double R, double rho, double E, double alpha_max);
/* Eq (72): dt_crit / dt_Rayleigh = (0.1631 nu + 0.8766)/sqrt(1+nu) sqrt(4/(3 pi))
 * (alpha_max/R)^(-1/4). */
double dem_nan_dt_ratio(double nu, double amax_R);

/* ---- adhesion-induced yield, eqs (80)-(81) ---------------------------------------------- */

/* Cohesion-yield number CY = p_y^3 R* / (E*^2 Gamma), eq (81). */
double dem_nan_cy(double R, double Es, double gamma, double py);
/* The critical yield pressure of eq (80), from f_y = f_0 with k_el = pi R* p_y:
 * p_y = 2 / pi^(2/3) (5/6)^(1/6) (Gamma E*^2 / R*)^(1/3). Pa. */
double dem_nan_py_crit(double R, double Es, double gamma);

/* ---- impact on a wall: characteristic velocities, section 4 (m* = particle mass) --------- */

/* V_s = sqrt(2 W_0 / m) with W_0 = W_JKR (eq 35): eq (73). m/s. */
double dem_nan_vs(double R, double Es, double gamma, double m);
/* V_y0 = sqrt(f_y^2 / (m k_el)), eq (74). m/s. */
double dem_nan_vy0(const dem_nan_coeffs *k, double m);
/* V_y^2 = (f_y^2 - f_0^2) / (m k_el), eq (75), SIGNED: negative in the adhesion-induced yield
 * zone (f_y < f_0), where the attraction alone yields the contact. m^2/s^2. */
double dem_nan_vy2(const dem_nan_coeffs *k, double m);
/* Plastic adhesive sticking velocity V_ys (section 4): V_s if V_y >= V_s (eq 77); otherwise
 * the fixed point of eqs (10), (46), (59), (79) and (78) started at f_max = f_y, solved to
 * round-off. Writes V_ys (m/s) and, if f_max != NULL, the f_max at V_ys (N). Errors:
 * DEM_EMAXITER if the iteration does not converge. No damping (e0 = 1). */
int dem_nan_vys(const dem_nan_coeffs *k, double m, double *vys, double *f_max, dem_err *err);

/* Undamped impact on a wall at V (m/s), by the energy balance of Appendix A / Fig 4:
 * below yield f_max^2 = f_0^2 + k_el m V^2 (W_1 + 1/2 m V^2 = f_max^2 / 2k_el); above,
 * eq (79) f_max^2 = f_y^2 + k_p (m V^2 - m V_y^2); alpha_max eq (10); the unloading line;
 * rebound 1/2 m v_r^2 = W_4 - (W_5 + W_6) = f_max^2/(2 k_e) - f_cp^2/(2 k_e) (1 + 56/81 k_e/k_c)
 * (eq 78), stuck if negative. alpha_p is the zero-force overlap of the unloading line. */
typedef struct dem_nan_impact_cf {
  double f_max;     /* N */
  double alpha_max; /* m */
  double alpha_p;   /* m */
  double f_cp;      /* N */
  double v_rebound; /* m/s, 0 if stuck */
  double e;         /* v_rebound / V */
  int stuck;
} dem_nan_impact_cf;
int dem_nan_impact(const dem_nan_coeffs *k, double m, double v, dem_nan_impact_cf *r,
                   dem_err *err);

#endif
