/* dem/impact.h — normal impact of a sphere on a flat wall (or on an equal sphere) as a
 * one-degree-of-freedom problem, and prescribed overlap paths through a law.
 *
 * The state is the overlap alpha (m) and its rate alpha_dot (m/s, > 0 approaching); the
 * equation of motion is m* alpha_ddot = -f(alpha, alpha_dot, history). The body starts at
 * alpha = 0 with alpha_dot = v_impact and ends when it separates: for a non-adhesive law when
 * the overlap returns to zero (or, with clip_tensile, when the total force reaches zero on
 * the way out), for an adhesive law when the law reports the contact broken. It "sticks"
 * when it never separates within the time limit or is left with no outward speed.
 *
 * Two integrators: velocity Verlet with dt = dt_factor x (Rayleigh or mass-spring step), the
 * one the 3-D engine uses; and a reference integration with GSL's adaptive ODE solver at a
 * tight tolerance, for checking the first.
 */
#ifndef DEM_IMPACT_H
#define DEM_IMPACT_H

#include <stdio.h>

#include "dem/contact.h"
#include "dem/error.h"
#include "dem/params.h"

typedef enum { DEM_INTEGRATOR_VERLET = 0, DEM_INTEGRATOR_REFERENCE = 1 } dem_integrator;
typedef enum { DEM_DT_RAYLEIGH = 0, DEM_DT_MASS_SPRING = 1 } dem_dt_rule;
typedef enum { DEM_TARGET_WALL = 0, DEM_TARGET_PAIR = 1 } dem_impact_target;

/* The scene: particle, target, law. Filled by dem_impact_setup from a parameter set:
 * scene keys R, rho (particle), E, nu (for the Rayleigh step), and the law's coefficients. */
typedef struct dem_impact_scene {
  dem_contact law;          /* the compiled law */
  dem_geom geom;            /* R*, m* */
  double R, rho, mass;      /* m, kg/m^3, kg: the moving particle */
  double E, nu;             /* Pa, -: the particle's, for the Rayleigh step (NAN if absent) */
  dem_impact_target target; /* wall (R2 = inf, m2 = inf) or an equal sphere */
} dem_impact_scene;

typedef struct dem_impact_opts {
  dem_integrator integrator; /* default verlet */
  dem_dt_rule dt_rule;       /* default: Rayleigh if E and nu are known, else mass-spring */
  double dt_factor;          /* default 0.01 (impacts: 0.01-0.1, paper section 3.5) */
  double dt;                 /* if > 0, use this step (s) and ignore dt_rule/dt_factor */
  double rtol;               /* reference integrator relative tolerance, default 1e-10 */
  double t_max_factor;       /* give up (stuck) after this many contact-time scales; 200 */
  int clip_tensile;          /* non-adhesive laws: no tensile total force (default 0) */
  double runaway_overlap;    /* fraction of R: overlap beyond it is an error; default 1.0 */
  FILE *trace;               /* if non-NULL, write "t,alpha,alpha_dot,f,f_el,f_damp" rows */
  int trace_every;           /* write every n-th step (default 1) */
} dem_impact_opts;

typedef struct dem_impact_result {
  double v_impact;   /* m/s */
  double v_rebound;  /* m/s, >= 0 (0 if stuck) */
  double e;          /* v_rebound / v_impact */
  double alpha_max;  /* m */
  double alpha_p;    /* m, permanent overlap: where the unloading force reaches zero (0 if
                        the law has no plastic memory) */
  double f_max;      /* N */
  double f_pulloff;  /* N, >= 0: the largest tensile force during unloading */
  double t_contact;  /* s, from first contact to separation (or to t_max if stuck) */
  int stuck;         /* 1 if the particle did not separate */
  double dt;         /* s, the step used (Verlet) or the last accepted step (reference) */
  long steps;        /* steps taken */
  double w_damp;     /* J, energy dissipated by viscous damping */
} dem_impact_result;

void dem_impact_opts_default(dem_impact_opts *o);
/* Build the scene from a parameter set: keys R, rho required; E, nu optional (the law may
 * read them too); the law's coefficients. Unknown keys are an error naming them. */
int dem_impact_setup(dem_impact_scene *sc, const dem_law *law, const dem_params *ps,
                     dem_impact_target target, dem_err *err);
/* The time step the options imply for a given impact velocity (s). */
double dem_impact_dt(const dem_impact_scene *sc, const dem_impact_opts *o, double v);
/* One impact at velocity v > 0 (m/s). Errors: DEM_EUNSTABLE, DEM_ERUNAWAY, DEM_ENONFINITE
 * (breakdown: NaN, overlap beyond runaway_overlap * R, energy gain), each with a message. */
int dem_impact_run(const dem_impact_scene *sc, const dem_impact_opts *o, double v,
                   dem_impact_result *res, dem_err *err);
/* Critical sticking velocity: the largest v in [v_lo, v_hi] at which the particle sticks,
 * by bracketing and bisection to relative tolerance tol. Laws whose e(v) is not monotone
 * (several sticking bands) are bracketed on a log grid first (n_grid points). */
int dem_impact_sticking(const dem_impact_scene *sc, const dem_impact_opts *o, double v_lo,
                        double v_hi, double tol, double *v_stick, dem_err *err);

/* A prescribed overlap path: turning points a[0] -> a[1] -> ... with a step d_alpha (m),
 * evaluated quasi-statically (alpha_dot = 0). Calls row(alpha, f, user) for every point. */
typedef void (*dem_path_row_fn)(double alpha, const dem_normal *n, void *user);
int dem_contact_path(const dem_contact *ct, const dem_geom *g, const double *turning, int n,
                     double d_alpha, dem_path_row_fn row, void *user, dem_err *err);

#endif
