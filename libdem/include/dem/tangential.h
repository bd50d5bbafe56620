/* dem/tangential.h — tangential friction with adhesion, and rolling resistance.
 *
 * Tangential (thesis 3.4.1.1 / 4.3, eqs 3.11-3.13, 4.26-4.28; paper eqs 21-23, 25; Mindlin
 * no-slip 3.25): an elastic spring xi (m, a 3-vector kept per contact) loaded by the
 * tangential relative velocity, rotated every step into the current tangent plane, with a
 * Coulomb limit
 *     |F_t| <= F_lim = mu max(F_n + f_adh, 0)
 * where f_adh is the adhesive contribution reported by the normal law (dem_normal.f_adh:
 * 2 f_c for JKR, thesis 3.49; f_cp - f_ce or k_cp alpha + f_0p - f_ce for the thesis' laws,
 * 4.27-4.28). When the spring force k_t |xi| would exceed the limit the contact slides: the
 * spring is shortened so that k_t |xi| equals the limit, and the force is the limit, without
 * viscous damping (paper eq 23: "the energy is dissipated from the interfacial sliding
 * without introducing the viscous damping"). While sticking, the force is
 *     F_t = -k_t xi - eta sqrt(m* k_t) v_t         (3.11-3.13 / 4.26; damping paper eq 25)
 * with the total capped at the limit (damping never lifts |F_t| above F_lim).
 * No friction capacity (F_n + f_adh <= 0, e.g. a thesis-law contact pulled beyond
 * f_cp - f_ce): F_lim = 0, the contact slides freely, F_t = 0 and the spring is reset to
 * zero — grip starts again from an unstretched spring when capacity returns.
 *
 * Frame rotation (the way LAMMPS' and LIGGGHTS' history models do it): before the
 * increment, the normal component of xi is projected out and xi is rescaled to its previous
 * length, so a rigid rotation of the pair neither creates nor destroys stored energy. Spin
 * of the pair about n itself is not followed (xi keeps its direction in space).
 *
 * Stiffness: constant k_t (linear), or Mindlin no-slip k_t = 8 G* sqrt(R* alpha) (3.25)
 * applied to the total spring, F = -k_t(alpha) xi. Callers pass alpha_eff = n.alpha_t, the
 * overlap the normal law reports for it (dem_normal.alpha_t, contact.h): a^2/R* for JKR-type
 * laws, so that k_t = 8 G* a at the law's contact radius a, also at alpha <= 0 (adhesive
 * contact under tension); max(alpha, 0) for the others. alpha_eff <= 0 gives k_t = 0: no
 * tangential force, the spring keeps accumulating displacement until stiffness returns.
 *
 * Rolling resistance (physics notes; constant directional torque, the kind of the
 * commercial code of the thesis):  M_r = -mu_r |F_n| R_i omega_rel / |omega_rel|,
 * regularised below |omega_rel| = w_eps into the viscous torque -mu_r |F_n| R_i omega_rel /
 * w_eps (continuous, zero at rest, never doing positive work). With
 * w_eps >= dem_rolling_omega_eps(...) one explicit step of the rolling torque alone can
 * bring omega_rel to zero but never reverse it: no chatter, no energy injected.
 *
 * The two per-step kernels are C99 inline definitions (the bulk engine's loop inlines them);
 * libdem/src/tangential.c emits their external definitions.
 */
#ifndef DEM_TANGENTIAL_H
#define DEM_TANGENTIAL_H

#include <math.h>

#include "dem/error.h"
#include "dem/params.h"

#define DEM_TANGENTIAL_NHIST 3 /* the spring xi, m */

typedef enum { DEM_TANGENTIAL_NONE = 0, DEM_TANGENTIAL_LINEAR, DEM_TANGENTIAL_MINDLIN } dem_tangential_kind;

typedef struct dem_tangential {
  dem_tangential_kind kind;
  double kt;   /* N/m, linear kind */
  double G;    /* Pa, reduced shear modulus G*, Mindlin kind */
  double mu;   /* sliding friction coefficient */
  double eta;  /* tangential damping constant (paper eq 25), 0 for none */
} dem_tangential;

typedef struct dem_rolling {
  double mu_r; /* rolling friction coefficient, 0 for none */
} dem_rolling;

/* From keys kt (linear) or E, nu, wall_E, wall_nu (Mindlin; wall_E/wall_nu default to E/nu,
 * a pair of equal particles), mu (required), e (optional: tangential damping with the linear
 * constant eta = 2 |ln e| / sqrt(pi^2 + ln^2 e); absent or 1 means none). Errors name the key,
 * value and allowed range: DEM_EMISSING, DEM_ERANGE, DEM_ENONFINITE, DEM_EINVAL. */
int dem_tangential_setup(dem_tangential *t, dem_tangential_kind kind, const dem_params *ps,
                         dem_err *err);

/* From key mu_r (optional, default 0 = none; allowed [0, 1]). */
int dem_rolling_setup(dem_rolling *r, const dem_params *ps, dem_err *err);

/* One step of the tangential spring.
 *   xi     [3] spring (history), updated
 *   n      [3] unit contact normal (from particle j to particle i)
 *   vt     [3] relative velocity of i with respect to j at the contact point (m/s); its
 *              normal component, if any, is ignored
 *   dt     time step (s)
 *   R, alpha_eff  reduced radius and overlap for the Mindlin stiffness (m): pass the
 *                 normal law's dem_normal.alpha_t
 *   m      reduced mass (kg) for damping
 *   fn, f_adh     normal force (N, > 0 repulsive; pass dem_normal.f) and the law's adhesive
 *                 contribution (N, dem_normal.f_adh)
 *   ft     [3] out: tangential force on particle i (N)
 * Returns 1 if the contact slid this step, else 0. */
inline int dem_tangential_force(const dem_tangential *t, double xi[3], const double n[3],
                                const double vt[3], double dt, double R, double alpha_eff,
                                double m, double fn, double f_adh, double ft[3]) {
  /* Stiffness: the kind is loop-invariant, so this select is perfectly predicted. */
  /* (Ternaries, not fmax: without -ffinite-math-only fmax is a library call.) */
  double ae = alpha_eff > 0.0 ? alpha_eff : 0.0;
  double k = t->kind == DEM_TANGENTIAL_MINDLIN ? 8.0 * t->G * sqrt(R * ae) : t->kt;
  k = t->kind == DEM_TANGENTIAL_NONE ? 0.0 : k;
  /* Rotate into the current tangent plane, keeping |xi|. */
  double m0 = xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2];
  double xn = xi[0] * n[0] + xi[1] * n[1] + xi[2] * n[2];
  double p[3] = {xi[0] - xn * n[0], xi[1] - xn * n[1], xi[2] - xn * n[2]};
  double m1 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
  double sc = m1 > 0.0 ? sqrt(m0 / m1) : 0.0; /* xi along n (a 90-degree turn): spring lost */
  /* Tangential part of the relative velocity and the spring increment. */
  double vn = vt[0] * n[0] + vt[1] * n[1] + vt[2] * n[2];
  double v[3] = {vt[0] - vn * n[0], vt[1] - vn * n[1], vt[2] - vn * n[2]};
  for (int i = 0; i < 3; i++) xi[i] = sc * p[i] + v[i] * dt;
  /* Coulomb limit with the adhesive contribution (thesis 4.27-4.28, 3.49). */
  double cap = fn + f_adh;
  double flim = (t->kind == DEM_TANGENTIAL_NONE ? 0.0 : t->mu) * (cap > 0.0 ? cap : 0.0);
  double fs = k * sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
  int slide = fs > flim;
  /* Sliding: shorten the spring so that k |xi| = F_lim (k = 0 never slides: fs = 0). */
  double s = slide ? flim / fs : 1.0;
  /* Damping only while sticking (paper eq 23/25). */
  double c = slide ? 0.0 : t->eta * sqrt(m * k);
  for (int i = 0; i < 3; i++) {
    xi[i] *= s;
    ft[i] = -k * xi[i] - c * v[i];
  }
  /* Damping may not lift the total above the limit. */
  double f2 = ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2];
  double q = f2 > flim * flim ? flim / sqrt(f2) : 1.0;
  for (int i = 0; i < 3; i++) ft[i] *= q;
  return slide;
}

/* Smallest w_eps (rad/s) for which one explicit step dt of the rolling torque on a body of
 * moment of inertia I (kg m^2; for two free particles the relative-rotation inertia
 * (1/I_i + R_j/(R_i I_j))^-1) cannot reverse omega_rel: mu_r |F_n| R_i dt / I. */
static inline double dem_rolling_omega_eps(double mu_r, double fn_abs, double R_i, double I,
                                           double dt) {
  return mu_r * fn_abs * R_i * dt / I;
}

/* Rolling torque on particle i (N m) for relative angular velocity w_rel = w_i - w_j
 * (rad/s), |F_n| (N) and the particle's radius R_i (m):
 *   M = -mu_r |F_n| R_i w_rel / max(|w_rel|, w_eps)
 * i.e. the constant directional torque above w_eps, viscous below it, zero at w_rel = 0.
 * w_eps = 0 gives the bare constant torque (which chatters in an explicit scheme). */
inline void dem_rolling_torque(const dem_rolling *r, const double w_rel[3], double fn_abs,
                               double R_i, double w_eps, double m_out[3]) {
  double w = sqrt(w_rel[0] * w_rel[0] + w_rel[1] * w_rel[1] + w_rel[2] * w_rel[2]);
  double d = w > w_eps ? w : w_eps;
  double g = d > 0.0 ? -r->mu_r * fabs(fn_abs) * R_i / d : 0.0;
  for (int i = 0; i < 3; i++) m_out[i] = g * w_rel[i];
}

#endif
