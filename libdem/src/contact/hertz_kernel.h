/* The force of law `hertz` (hertz.c) for alpha > 0, as a static inline kernel shared by the
 * law's table entry and the bulk engine's Hertz path (libdem/src/engine/force.c), so that
 * there is one implementation of the physics. Private to libdem.
 *
 *   sra  = sqrt(R* alpha)                                 m
 *   S_n  = 2 E* sra                                       N/m
 *   f_el = 4/3 E* sqrt(R*) alpha^{3/2} = 2/3 S_n alpha    thesis eq (3.14), N
 *   smk  = sqrt(m* S_n)                                   kg/s
 *   f_d  = eta_H(e) smk alpha_dot                         N
 * The engine reuses sra (Mindlin stiffness 8 G* sra, thesis 3.25) and smk (tangential
 * damping, paper eq 25: sqrt(m* k_t) = sqrt(4 G* / E*) smk) instead of new square roots. */
#ifndef DEM_HERTZ_KERNEL_H
#define DEM_HERTZ_KERNEL_H

#include <math.h>

/* hertz.c's compiled coefficient array */
enum { DEM_HERTZ_C_ES, DEM_HERTZ_C_ETA, DEM_HERTZ_C_E };

typedef struct dem_hertz_terms {
  double sra;    /* m, sqrt(R* alpha) */
  double k;      /* N/m, S_n */
  double smk;    /* kg/s, sqrt(m* S_n) */
  double f_el;   /* N */
  double f_damp; /* N */
} dem_hertz_terms;

/* c: the law's coefficients; R, m: R* (m), m* (kg); alpha > 0 (m); alpha_dot (m/s, > 0
 * approaching). */
static inline void dem_hertz_eval(const double *c, double R, double m, double alpha,
                                  double alpha_dot, dem_hertz_terms *o) {
  o->sra = sqrt(R * alpha);
  o->k = 2.0 * c[DEM_HERTZ_C_ES] * o->sra;
  o->f_el = (2.0 / 3.0) * o->k * alpha;
  o->smk = sqrt(m * o->k);
  o->f_damp = c[DEM_HERTZ_C_ETA] * o->smk * alpha_dot;
}

#endif
