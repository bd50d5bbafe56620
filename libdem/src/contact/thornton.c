/* `thornton`: Thornton (1997) elastic-perfectly-plastic normal contact (thesis section
 * 3.4.2.1, eqs 3.27-3.32), with restitution-based viscous damping.
 *
 *   Hertz loading   F = 4/3 E* sqrt(R*) alpha^{3/2}                  (3.14), alpha <= alpha_y
 *   yield           F_y = pi^3 R*^2 p_y^3 / (6 E*^2)                  (3.27)
 *                   alpha_y = pi^2 R* p_y^2 / (4 E*^2)                (3.29)
 *   plastic line    F = F_y + pi p_y R* (alpha - alpha_y)             (3.28), alpha >= alpha_max
 *   unloading       R_p* = 4 E* / (3 F_max) ((2 F_max + F_y) / (2 pi p_y))^{3/2}   (3.30)
 *                   F = 4/3 E* sqrt(R_p*) (alpha - alpha_p)^{3/2}     (3.31, see below)
 *                   alpha_p = alpha_max (1 - R* / R_p*)                 (3.32)
 *   reloading       along the unloading curve up to alpha_max, then the plastic line again.
 *
 * Eq (3.31) as printed in the thesis has sqrt(R*) in place of sqrt(R_p*); with sqrt(R*) the
 * unloading curve would not pass through (alpha_max, F_max). Thornton (1997) unloads with the
 * Hertz relation of curvature R_p* (the thesis' own text: "Hertz equations but with a
 * curvature of 1/R_p*"), which with (3.32) does pass through it: (2 F_max + F_y)/(2 pi p_y)
 * equals R* alpha_max = a_max^2, so (3.30) reads R_p* = 4 E* a_max^3 / (3 F_max) and
 * R_p* (alpha_max - alpha_p) = a_max^2. The stiffness is continuous at yield too:
 * 2 E* sqrt(R* alpha_y) = pi p_y R*.
 *
 * Stiffness of the branch in use: 2 E* sqrt(R* alpha) (Hertz), pi p_y R* (plastic),
 * 2 E* sqrt(R_p* (alpha - alpha_p)) (unloading/reloading). Damping
 * f_d = eta_H(e) sqrt(m* k) alpha_dot on every branch, with the velocity-independent Hertz
 * constant (damping.c): e = 1 (the default) reproduces Thornton's undamped model.
 *
 * History: state (0 fresh, 1 loaded elastically, 2 yielded), alpha_max, F_max, R_p*, alpha_p.
 */
#include <float.h>
#include <math.h>

#include "dem/contact.h"
#include "dem/material.h"

enum { C_ES, C_PY, C_ETA, C_E, C_AY };
enum { H_AMAX = 1, H_FMAX, H_RP, H_AP, NHIST };

static const dem_coef_spec coefs[] = {
    DEM_COEF_ELASTIC,
    {"py", "Pa", "limiting contact (yield) pressure p_y (at most 2 E* / pi)", 1.0, 1e12, NAN},
    {"e", "-", "restitution of the viscous damping (1: Thornton's undamped model)", 1e-2, 1.0,
     1.0},
};

static int set_coeffs(const dem_params *ps, double *c, dem_err *err) {
  double Es = dem_contact_reduced_modulus(ps), py = dem_params_get_or(ps, "py", NAN);
  /* alpha_y / R* = (pi p_y / (2 E*))^2 must not exceed 1: p_y <= 2 E* / pi. */
  if (!(py <= 2.0 * Es / M_PI))
    return dem_err_set(err, DEM_ERANGE,
                       "%slaw 'thornton': coefficient 'py' = %g Pa is outside the allowed range "
                       "[1, 2 E* / pi = %g] (the yield overlap alpha_y would exceed R*)",
                       dem_params_origin(ps, "py"), py, 2.0 * Es / M_PI);
  c[C_ES] = Es;
  c[C_PY] = py;
  c[C_AY] = M_PI * M_PI * py * py / (4.0 * Es * Es); /* alpha_y / R*, (3.29) */
  double e = dem_params_get_or(ps, "e", 1.0);
  c[C_E] = e;
  c[C_ETA] = dem_damping_eta_hertz(e, 0);
  if (c[C_ETA] < 0.0)
    return dem_err_set(err, DEM_EPHYSICS,
                       "%slaw 'thornton': no damping constant reproduces e = %g "
                       "(allowed [0.01, 1])",
                       dem_params_origin(ps, "e"), e);
  return DEM_OK;
}

static void force(const double *c, const dem_geom *g, double *hist, double alpha,
                  double alpha_dot, dem_normal *out) {
  const double Es = c[C_ES], py = c[C_PY], R = g->R;
  double f, k;
  if (alpha > hist[H_AMAX]) {
    /* Loading beyond every earlier overlap. */
    double ay = c[C_AY] * R;
    if (alpha <= ay) {
      k = 2.0 * Es * sqrt(R * alpha);              /* Hertz, (3.14) */
      f = (2.0 / 3.0) * k * alpha;
      if (hist[DEM_HIST_STATE] < 1.0) hist[DEM_HIST_STATE] = 1.0;
    } else {
      k = M_PI * py * R;                          /* plastic line, (3.28) */
      double fy = (2.0 / 3.0) * k * ay;           /* = pi^3 R*^2 p_y^3 / (6 E*^2), (3.27) */
      f = fy + k * (alpha - ay);
      double q = (2.0 * f + fy) / (2.0 * M_PI * py); /* = R* alpha = a_max^2, m^2 */
      double rp = 4.0 * Es / (3.0 * f) * q * sqrt(q); /* (3.30) */
      hist[DEM_HIST_STATE] = 2.0;
      hist[H_RP] = rp;
      hist[H_AP] = alpha * (1.0 - R / rp);         /* (3.32) */
    }
    hist[H_AMAX] = alpha;
    hist[H_FMAX] = f;
  } else if (hist[DEM_HIST_STATE] < 2.0) {
    /* Never yielded: Hertz, reversible. */
    if (!(alpha > 0.0)) {
      dem_normal_zero(out);
      return;
    }
    k = 2.0 * Es * sqrt(R * alpha);
    f = (2.0 / 3.0) * k * alpha;
  } else {
    /* Unloading or reloading on the Hertz curve of curvature R_p*, (3.31). */
    double d = alpha - hist[H_AP];
    if (!(d > 0.0)) {
      dem_normal_zero(out);
      return;
    }
    k = 2.0 * Es * sqrt(hist[H_RP] * d);
    f = (2.0 / 3.0) * k * d;
  }
  out->k = k;
  out->f_el = f;
  out->f_damp = c[C_ETA] * sqrt(g->m * k) * alpha_dot;
  out->f = out->f_el + out->f_damp;
  out->f_adh = 0.0;
  out->alpha_t = alpha > 0.0 ? alpha : 0.0; /* contact.h: max(alpha, 0) for Mindlin */
  out->contact = 1;
}

/* The unloading stiffness at the maximum overlap of an impact at v, 2 E* sqrt(R* alpha_max)
 * (= 2 E* a_max), with alpha_max from the energy balance of the undamped law: Hertz below the
 * yield velocity, else (1/2) m* v^2 = W_y + F_y x + (pi p_y R* / 2) x^2, x = alpha_max - alpha_y,
 * W_y = 2/5 F_y alpha_y. */
static double kref(const double *c, const dem_geom *g, double v) {
  const double Es = c[C_ES], R = g->R;
  double ay = c[C_AY] * R, kp = M_PI * c[C_PY] * R, fy = (2.0 / 3.0) * kp * ay;
  double win = 0.5 * g->m * v * v, wy = 0.4 * fy * ay, amax;
  if (win <= wy)
    amax = pow(15.0 * g->m * v * v / (16.0 * Es * sqrt(R)), 0.4);
  else
    amax = ay + (sqrt(fy * fy + 2.0 * kp * (win - wy)) - fy) / kp;
  return 2.0 * Es * sqrt(R * amax);
}

const dem_law dem_law_thornton = {
    .name = "thornton",
    .title = "Thornton (1997) elastic-perfectly-plastic: Hertz, plastic line, Hertz unloading "
             "with R_p*",
    .source = "thesis eqs (3.27)-(3.32); Thornton, J. Appl. Mech. 64 (1997) 383",
    .ncoef = sizeof coefs / sizeof coefs[0],
    .coef = coefs,
    .nhist = NHIST,
    .flags = DEM_LAW_PLASTIC | DEM_LAW_NONLINEAR,
    .set_coeffs = set_coeffs,
    .init = NULL,
    .force = force,
    .kref = kref,
};
