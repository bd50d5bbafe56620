/* Private to impact.c / impact_ref.c: the bookkeeping both integrators share.
 *
 * Both integrators report through the same running summary so that e, alpha_max, alpha_p,
 * f_max, f_pulloff and the breakdown checks mean exactly the same thing for either. */
#ifndef DEM_IMPACT_PRIV_H
#define DEM_IMPACT_PRIV_H

#include "dem/impact.h"

/* Running summary of one impact. */
typedef struct dem_impact_sum {
  double alpha_max;    /* m */
  double f_max;        /* N, largest total (applied) force */
  double f_el_last;    /* N, f_el at the previous accepted state (for alpha_p) */
  double alpha_last;   /* m, alpha at the previous accepted state */
  double alpha_p;      /* m */
  double pulloff;      /* N, >= 0 */
  int unloading;       /* 1 once the overlap rate has turned negative */
  int have_p;          /* alpha_p found */
  int plastic;         /* the law has plastic memory */
  int started;         /* the law has reported contact at least once */
} dem_impact_sum;

/* 1/omega of the contact: sqrt(m* / kref(v)), s. */
double dem_impact_tscale(const dem_impact_scene *sc, double v);
/* Simulated-time limit (s): t_max_factor half periods pi sqrt(m* / kref). */
double dem_impact_tmax(const dem_impact_scene *sc, const dem_impact_opts *o, double v);

void dem_impact_sum_init(dem_impact_sum *s, const dem_impact_scene *sc);
/* Record an accepted state (alpha, alpha_dot) with the law's output n and the applied force. */
void dem_impact_sum_add(dem_impact_sum *s, double alpha, double alpha_dot, const dem_normal *n,
                        double f_applied);

/* The force actually applied: the law's total force, clipped at zero if asked. */
static inline double dem_impact_applied(const dem_normal *n, int clip) {
  return (clip && n->f < 0.0) ? 0.0 : n->f;
}

/* Has the impact ended at this state?  The law no longer reports contact (after having
 * reported it, or once the overlap is negative), or, with clipping, the unclipped total force
 * has fallen to zero while the body moves out. */
static inline int dem_impact_ended(const dem_normal *n, int started, int clip, double alpha,
                                   double alpha_dot) {
  if (!n->contact) return started || alpha < 0.0;
  return clip && alpha_dot < 0.0 && n->f <= 0.0;
}

/* Final checks and fields shared by both integrators: v_sep is the overlap rate at
 * separation (< 0 leaving). tol_gain: the relative energy gain accepted as integration
 * error. Returns DEM_OK or DEM_EUNSTABLE. */
int dem_impact_finish(const dem_impact_scene *sc, const dem_impact_sum *s, double v0,
                      double v_sep, double t_contact, int stuck, double tol_gain,
                      dem_impact_result *res, dem_err *err);

/* The reference integration (impact_ref.c). */
int dem_impact_run_reference(const dem_impact_scene *sc, const dem_impact_opts *o, double v,
                             dem_impact_result *res, dem_err *err);

#endif
