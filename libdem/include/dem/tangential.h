/* dem/tangential.h — tangential friction with adhesion, and rolling resistance.
 *
 * Tangential (thesis 3.4.1.1 / 4.3, eqs 3.11-3.13, 4.26-4.28; Mindlin no-slip 3.25):
 * an elastic spring xi (m, a 3-vector kept per contact) loaded by the tangential relative
 * velocity, rotated every step into the current tangent plane, with a Coulomb limit
 *     |F_t| <= mu (F_n + f_adh)
 * where f_adh is the adhesive contribution reported by the normal law (dem_normal.f_adh:
 * 2 f_c for JKR, f_cp - f_ce or k_cp alpha + f_0p - f_ce for the thesis' laws). When the
 * limit is reached the spring is shortened so that k_t |xi| equals the limit (the contact
 * slides and the stored elastic energy is the limit's).
 *
 * Stiffness: constant k_t (linear), or Mindlin no-slip k_t = 8 G* sqrt(R* alpha). With
 * alpha <= 0 (adhesive contact under tension) the Mindlin stiffness is evaluated at the
 * contact radius the law implies; callers pass alpha_eff >= 0 for it.
 *
 * Rolling resistance (physics notes; constant directional torque, the kind of the
 * commercial code of the thesis):  M_r = -mu_r |F_n| R_i omega_rel / |omega_rel|.
 */
#ifndef DEM_TANGENTIAL_H
#define DEM_TANGENTIAL_H

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

/* From keys kt (linear) or E, nu, wall_E, wall_nu (Mindlin), mu, e (optional damping). */
int dem_tangential_setup(dem_tangential *t, dem_tangential_kind kind, const dem_params *ps,
                         dem_err *err);

/* One step of the tangential spring.
 *   xi     [3] spring (history), updated
 *   n      [3] unit contact normal (from particle j to particle i)
 *   vt     [3] tangential relative velocity at the contact point (m/s)
 *   dt     time step (s)
 *   R, alpha_eff  reduced radius and overlap for the Mindlin stiffness (m)
 *   m      reduced mass (kg) for damping
 *   fn, f_adh     normal force (N, > 0 repulsive) and the law's adhesive contribution (N)
 *   ft     [3] out: tangential force on particle i (N)
 * Returns 1 if the contact slid this step, else 0. */
int dem_tangential_force(const dem_tangential *t, double xi[3], const double n[3],
                         const double vt[3], double dt, double R, double alpha_eff, double m,
                         double fn, double f_adh, double ft[3]);

/* Rolling torque on particle i (N m) for relative angular velocity w_rel = w_i - w_j
 * (rad/s), |F_n| (N) and the particle's radius R_i (m). Zero if |w_rel| is below w_eps. */
void dem_rolling_torque(const dem_rolling *r, const double w_rel[3], double fn_abs, double R_i,
                        double w_eps, double m_out[3]);

#endif
