/* dem/jkr_radius.h — JKR geometry helpers (exact contact radius from the overlap).
 *
 * For a sphere of reduced radius R (m) on a flat of reduced modulus E* (Pa) with interface
 * energy Gamma (J/m^2; pull-off force f_c = 1.5 pi Gamma R):
 *
 *   alpha(a) = a^2 / R - sqrt(2 pi Gamma a / E*)               thesis eq (3.42), paper (B3)
 *   F(a)     = 4 E* a^3 / (3 R) - sqrt(8 pi Gamma E* a^3)       thesis eq (3.41), paper (B1)
 *
 * With s = sqrt(a) the first is the quartic s^4 - c s - R alpha = 0, c = R sqrt(2 pi Gamma/E*),
 * and with s = c^(1/3) x it becomes x^4 - x = q, q = R alpha / c^(4/3): one parameter. The
 * stable (large-radius) branch exists for q >= q_min = -(3/4) 4^(-1/3), where the contact
 * breaks (a_f^3 = pi Gamma R^2 / (8 E*), F = -5/9 f_c). dem_jkr_quartic_root solves it in
 * closed form (Ferrari with the resolvent cubic 8 m^3 + 8 q m - 1 = 0, Cardano written
 * without cancellation) plus one Newton correction: no iteration count to tune, no history.
 *
 * Written for the `thornton-ning` law; a plain `jkr` law can share it (all names dem_jkr_).
 */
#ifndef DEM_JKR_RADIUS_H
#define DEM_JKR_RADIUS_H

/* q_min = -(3/4) 4^(-1/3): the smallest q with a real root on the stable branch. */
#define DEM_JKR_QMIN (-0.47247039371057744)

/* Largest real root x of x^4 - x = q (x >= 4^(-1/3)); NAN for q < q_min. */
double dem_jkr_quartic_root(double q);

/* Contact radius a (m) on the stable branch for overlap alpha (m); NAN if alpha is below
 * the breakage overlap alpha_f. gamma > 0. */
double dem_jkr_radius(double R, double Es, double gamma, double alpha);
/* alpha(a) and F(a) above. */
double dem_jkr_alpha(double R, double Es, double gamma, double a);
double dem_jkr_force(double R, double Es, double gamma, double a);
/* Breakage overlap alpha_f = -(3/4) (pi^2 Gamma^2 R / E*^2)^(1/3)... written as
 * q_min c^(4/3) / R (m, < 0). */
double dem_jkr_alpha_f(double R, double Es, double gamma);
/* Tangent stiffness dF/dalpha on the stable branch at contact radius a (N/m):
 * 2 E* a (3 - 3 r)/(3 - r), r = (a_c/a)^(3/2), a_c^3 = 9 pi Gamma R^2 / (8 E*) (paper B2);
 * 0 at the pull-off point a_c, -> -infinity at breakage. */
double dem_jkr_stiffness(double R, double Es, double gamma, double a);

#endif
