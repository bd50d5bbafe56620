/* `jkr-modified`: the JKR variant of thesis section 5.1.1 (Fig 5.1), used with Hertz-Mindlin
 * for the bulk simulations of chapter 5.
 *
 * As `jkr` (jkr.c, jkr_law.h, dem/jkr.h): the contact forms at alpha = 0 with F = -8/9 f_c and follows
 * the JKR curve (thesis 3.41-3.42) in compression; but on unloading it breaks as soon as the
 * overlap becomes negative ("the contact for this model breaks once the overlap becomes
 * zero"), so the tensile stretch alpha_f < alpha < 0 of full JKR, and the work of adhesion
 * done there, are absent: the largest tensile force reached is 8/9 f_c, not f_c. Without
 * damping a contact then returns all the work done on it (e = 1 at any velocity, no
 * sticking). Coefficients, damping and the sliding limit mu (F_n + 2 f_c) are those of `jkr`.
 */
#include "dem/contact.h"
#include "jkr_law.h"

static void force(const double *c, const dem_geom *g, double *hist, double alpha,
                  double alpha_dot, dem_normal *out) {
  dem_jkrlaw_force(c, g, hist, alpha, alpha_dot, out, 1);
}

const dem_law dem_law_jkr_modified = {
    .name = "jkr-modified",
    .title = "modified JKR: JKR curve for alpha >= 0, breaks at alpha = 0",
    .source = "thesis section 5.1.1 and Fig 5.1; curve eqs (3.40)-(3.42)",
    .ncoef = DEM_JKR_NCOEFS,
    .coef = dem_jkrlaw_coefs,
    .nhist = DEM_JKR_NHIST,
    .flags = DEM_LAW_ADHESIVE | DEM_LAW_NONLINEAR,
    .set_coeffs = dem_jkrlaw_set_coeffs,
    .init = NULL,
    .force = force,
    .kref = dem_jkrlaw_kref,
};
