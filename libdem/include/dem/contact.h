/* dem/contact.h — the normal contact laws, as constant tables.
 *
 * Conventions (physics notes): SI units; overlap alpha > 0 is compression; a force > 0 is
 * repulsive; alpha_dot > 0 is approach. R* and m* are the reduced radius and mass.
 *
 * A law is a `const dem_law` table (GSL-style type table): its name, its coefficients with
 * units and allowed ranges, the size of its per-contact history, flags, and pure functions:
 *
 *   set_coeffs  validates a parameter set ONCE and compiles it into a flat array of doubles
 *               (material-pair constants: E*, gamma, stiffnesses, the damping constant...);
 *               errors name the coefficient, its value and the allowed range;
 *   init        fills a fresh history block for a contact of given geometry (R*, m*) and may
 *               reject a geometry the coefficients cannot represent;
 *   force       maps (coefficients, geometry, history, alpha, alpha_dot) to the normal force
 *               and updates the history. It allocates nothing and never aborts.
 *
 * History: every law's block starts with hist[DEM_HIST_STATE]; 0 means "never touched"
 * (a fresh block is all zeros after init). A caller must call `force` for every step in
 * which alpha >= 0 or hist[DEM_HIST_STATE] != 0 (a contact may live at negative overlap,
 * and a plastic law remembers its permanent deformation after separation); it may skip the
 * call when alpha < 0 and the state is 0: no law forms a contact at negative overlap.
 *
 * Damping is part of the law: restitution-based viscous damping
 * f_d = eta(e) * beta * sqrt(m* k_branch) * alpha_dot (thesis 4.24-4.25, paper 24-26) with
 * the instantaneous stiffness of the branch in use; `force` returns it separately.
 */
#ifndef DEM_CONTACT_H
#define DEM_CONTACT_H

#include "dem/error.h"
#include "dem/params.h"

#define DEM_LAW_NCOEF_MAX 48 /* doubles in a compiled coefficient array */
#define DEM_LAW_NHIST_MAX 16 /* doubles in one contact's normal-law history block */
#define DEM_HIST_STATE 0     /* index of the state word common to all laws */

/* Flags of a law. */
enum {
  DEM_LAW_ADHESIVE = 1u << 0, /* tensile forces; contact may live at alpha < 0 */
  DEM_LAW_PLASTIC = 1u << 1,  /* permanent deformation: history-dependent */
  DEM_LAW_NONLINEAR = 1u << 2 /* stiffness depends on overlap (Hertz family) */
};

/* One coefficient a law reads from a parameter set. */
typedef struct dem_coef_spec {
  const char *key;   /* the physics-notes name, e.g. "ke" */
  const char *unit;  /* "N/m" */
  const char *about; /* one line */
  double min, max;   /* allowed closed range [min, max]; use DBL_MIN for "> 0" */
  double def;        /* default if absent; NAN means required */
} dem_coef_spec;

/* Geometry of one contact. */
typedef struct dem_geom {
  double R; /* m, reduced radius R* */
  double m; /* kg, reduced mass m* */
} dem_geom;

/* What a law returns for one evaluation. */
typedef struct dem_normal {
  double f;     /* N, total normal force = f_el + f_damp, > 0 repulsive */
  double f_el;  /* N, the rate-independent (elastic/plastic/adhesive) part */
  double f_damp;/* N, the viscous damping part (> 0 opposes approach) */
  double k;     /* N/m, instantaneous stiffness of the branch in use (damping, time step) */
  double f_adh; /* N, >= 0: adhesive addition to the Coulomb sliding limit, mu (F_n + f_adh) */
  double alpha_t; /* m, overlap at which the Mindlin stiffness 8 G* sqrt(R* alpha_t) is evaluated:
                     a^2/R* for JKR-type laws (contact radius a), max(alpha, 0) otherwise */
  int contact;  /* 1 if the surfaces are in (adhesive or compressive) contact after the call */
} dem_normal;

typedef struct dem_law dem_law;

typedef int (*dem_law_set_coeffs_fn)(const dem_params *ps, double *c, dem_err *err);
typedef int (*dem_law_init_fn)(const double *c, const dem_geom *g, double *hist, dem_err *err);
typedef void (*dem_law_force_fn)(const double *c, const dem_geom *g, double *hist, double alpha,
                                 double alpha_dot, dem_normal *out);
/* A stiffness scale for time-step estimates: the largest branch stiffness the law reaches
 * in a normal impact at velocity v (N/m). */
typedef double (*dem_law_kref_fn)(const double *c, const dem_geom *g, double v);

struct dem_law {
  const char *name;    /* id used on the command line: "hertz" */
  const char *title;   /* "Hertz elastic + restitution-based viscous damping" */
  const char *source;  /* "thesis eq (3.14)" */
  int ncoef;           /* entries in coef[] */
  const dem_coef_spec *coef;
  int nhist;           /* doubles of history, including the state word; <= DEM_LAW_NHIST_MAX */
  unsigned flags;
  dem_law_set_coeffs_fn set_coeffs; /* called after the generic range check */
  dem_law_init_fn init;             /* NULL: history all zeros */
  dem_law_force_fn force;
  dem_law_kref_fn kref;
};

/* The registry of laws (libdem/src/contact/laws.def). */
int dem_contact_law_count(void);
const dem_law *dem_contact_law_at(int i);
const dem_law *dem_contact_law_find(const char *name);
/* 1 if key is one of the law's coefficients. */
int dem_contact_law_has_coef(const dem_law *law, const char *key);

/* A compiled law: the table and its validated coefficients (a plain value). */
typedef struct dem_contact {
  const dem_law *law;
  double c[DEM_LAW_NCOEF_MAX];
} dem_contact;

/* Check every coefficient the law reads against its range (and reject NaN/inf), apply
 * defaults, then call the law's own set_coeffs for cross-field checks and derived values.
 * Keys in ps that the law does not read are ignored here (the caller decides whether an
 * unknown key is an error: see dem_contact_check_keys). */
int dem_contact_setup(dem_contact *ct, const dem_law *law, const dem_params *ps, dem_err *err);
/* Error (DEM_ENOTFOUND) naming the first key of ps that is neither a coefficient of the law
 * nor in the NULL-terminated list `extra` (scene keys such as "R", "rho"). */
int dem_contact_check_keys(const dem_law *law, const dem_params *ps, const char *const *extra,
                           dem_err *err);
/* Initialise a history block (all zeros, then the law's init). */
int dem_contact_init(const dem_contact *ct, const dem_geom *g, double *hist, dem_err *err);
/* Evaluate the law; f and everything in out are finite for finite input. */
static inline void dem_contact_force(const dem_contact *ct, const dem_geom *g, double *hist,
                                     double alpha, double alpha_dot, dem_normal *out) {
  ct->law->force(ct->c, g, hist, alpha, alpha_dot, out);
}
/* Stiffness scale for a time step (N/m). */
double dem_contact_kref(const dem_contact *ct, const dem_geom *g, double v);

/* Helpers shared by the law files. -------------------------------------------------- */

/* The damping constant of restitution-based viscous damping for a linear spring,
 * eta = 2 |ln e| / sqrt(pi^2 + ln^2 e), so that f_d = eta sqrt(m* k) alpha_dot gives exactly
 * restitution e for a linear spring-dashpot (thesis eq 4.25 written as 2*gamma of paper
 * eq 24/26). e in (0, 1]; e = 1 gives 0. */
double dem_damping_eta_linear(double e);
/* The damping constant for Hertz with f_d = eta sqrt(m* S_n) alpha_dot,
 * S_n = 2 E* sqrt(R* alpha): the restitution is then independent of impact velocity, and
 * eta is found (once, by root finding on the dimensionless impact) so that it equals e.
 * clipped != 0: the total force is clipped at zero (no tensile force from damping at the
 * end of contact). Returns a negative number if e is outside (0, 1]. */
double dem_damping_eta_hertz(double e, int clipped);
/* The inverse: the restitution of a Hertz impact damped by f_d = eta sqrt(m* S_n) alpha_dot
 * (independent of impact velocity), found by integrating the dimensionless impact; used to
 * check other damping constants, e.g. the EDEM/LIGGGHTS 2 sqrt(5/6) |ln e|/sqrt(ln^2 e + pi^2)
 * (docs/contact-laws.md, "Damping"). eta >= 0; returns a negative number on failure. */
double dem_damping_restitution_hertz(double eta, int clipped);

/* The four material coefficients of every law that needs the reduced modulus E* (thesis
 * eq 3.15): the particle's E, nu and the wall's or second particle's wall_E, wall_nu (absent:
 * the particle's values, i.e. an equal sphere; wall_E = 1e30 stands for a rigid wall). Put
 * DEM_COEF_ELASTIC first in the law's coefficient table and read E* with
 * dem_contact_reduced_modulus. */
#define DEM_COEF_ELASTIC                                                                      \
  {"E", "Pa", "Young's modulus of the particle", 1e3, 1e13, NAN},                          \
      {"nu", "-", "Poisson's ratio of the particle", -0.99, 0.5, NAN},                     \
      {"wall_E", "Pa",                                                                     \
       "Young's modulus of the wall or second particle (default: E; 1e30 = rigid)", 1e3,   \
       1e30, -1.0},                                                                        \
  {                                                                                        \
    "wall_nu", "-", "Poisson's ratio of the wall or second particle (default: nu)", -0.99, \
        0.5, -2.0                                                                          \
  }
/* E* (Pa) from a parameter set holding the DEM_COEF_ELASTIC keys (defaults applied). */
double dem_contact_reduced_modulus(const dem_params *ps);

/* Fill out for "no contact". */
static inline void dem_normal_zero(dem_normal *out) {
  out->f = out->f_el = out->f_damp = out->k = out->f_adh = out->alpha_t = 0.0;
  out->contact = 0;
}

/* The laws (one file each under libdem/src/contact/). */
#define DEM_LAW(sym) extern const dem_law sym;
#include "dem/laws.def"
#undef DEM_LAW

#endif
