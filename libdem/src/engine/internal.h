/* Private state of the 3-D engine (libdem/src/engine/). Not installed. */
#ifndef DEM_ENGINE_INTERNAL_H
#define DEM_ENGINE_INTERNAL_H

#include <signal.h>
#include <stddef.h>
#include <stdint.h>

#include "dem/engine.h"
#include "../contact/hertz_kernel.h"

#define DEM_MAX_THREADS 64

/* Per-pair constants of the batched Hertz(-Mindlin) kernel (force.c): 2 E*, eta_H(e),
 * 8 G*, eta_t sqrt(4 G* / E*), mu, and a 0/1 factor that switches the spring off. */
enum { DEM_BC_2ES, DEM_BC_ETA, DEM_BC_8G, DEM_BC_CT, DEM_BC_MU, DEM_BC_TANG, DEM_BATCH_NC };

/* The contact model of one material pair, flattened for the force loop. */
typedef struct dem_inter {
  int set;                  /* 1 once dem_sim_set_interaction was called */
  dem_contact normal;       /* law + compiled coefficients */
  dem_tangential tang;      /* kind NONE: no tangential force */
  dem_rolling roll;         /* mu_r = 0: no rolling torque */
  unsigned fl;              /* DEM_IF_* below, read once per contact by the force loop */
  double hz_ct;             /* DEM_IF_HZMINDLIN: eta_t sqrt(4 G* / E*), so that the tangential
                               damping eta_t sqrt(m* k_t) = hz_ct sqrt(m* S_n) (force.c) */
  double bc[DEM_BATCH_NC];  /* DEM_IF_BATCH: the constants of the batched kernel (force.c) */
} dem_inter;
/* HERTZ: the law is `hertz`, evaluated inline (contact/hertz_kernel.h) instead of through
 * the table; HZMINDLIN: and the tangential spring is Mindlin, its stiffness and damping
 * formed from the Hertz terms; BATCH: Hertz with a Mindlin spring or none, no rolling
 * resistance: the pair can go through the batched kernel (force.c). */
enum { DEM_IF_INIT = 1u, DEM_IF_TANG = 2u, DEM_IF_ROLL = 4u, DEM_IF_HERTZ = 8u,
       DEM_IF_HZMINDLIN = 16u, DEM_IF_BATCH = 32u };

typedef struct dem_wall {
  dem_wall_spec spec;       /* current geometry (p advances with v) */
  double f[3], t[3];        /* N, N m: load on the wall of the last force evaluation */
  double fd[3];             /* N, the part of f from the normal dashpots (dem_normal.f_damp):
                               the servo reads f - fd, the rate-independent load */
  double work;              /* J, work done by the wall on the particles */
  double *hist;             /* [cap * nh] history of each particle against this wall */
  uint32_t *list;           /* particles within reach at the last build, ascending */
  size_t nlist, cap_list;
  double p_build[3];        /* m, the wall point at the last build */
  int servo;                /* 1: velocity from the servo law below */
  double f_target, gain, v_max; /* N, m/(s N), m/s */
  double v_eval[3];         /* m/s, the velocity the last force evaluation used (a servo
                               changes spec.v right after it); valid if have_v_eval */
  int have_v_eval;          /* 0 until the first evaluation (or after a checkpoint restore:
                               contacts.c then uses spec.v) */
} dem_wall;

/* Half Verlet list in CSR form: the neighbours j > i of particle i are
 * nbr[first[i] .. first[i+1]), ascending; hist holds nh doubles per entry. */
typedef struct dem_nlist {
  size_t n;                 /* rows */
  size_t npairs;
  size_t cap_rows, cap_pairs;
  uint32_t *first;          /* [n + 1] */
  uint32_t *nbr;            /* [npairs] */
  double *hist;             /* [npairs * nh] */
  uint8_t *touch;           /* [npairs] 1 if the pair's spring may be loaded (in contact at
                               the last evaluation, or carried over non-zero) */
} dem_nlist;

/* Per-thread scratch of the force loop. */
typedef struct dem_spill {
  uint32_t j;
  double f[3], t[3];
} dem_spill;

typedef struct dem_tdata {
  size_t row_begin, row_end;     /* rows (particles) owned by the thread */
  dem_spill *spill;              /* forces on particles beyond row_end */
  size_t nspill, cap_spill;
  uint32_t *cand;                /* scratch: a row's candidate contacts / stale springs */
  size_t cap_cand;
  double wf[DEM_ENGINE_MAX_WALLS][3], wt[DEM_ENGINE_MAX_WALLS][3];
  double wfd[DEM_ENGINE_MAX_WALLS][3]; /* N, the normal dashpots' part of wf */
  double wpow[DEM_ENGINE_MAX_WALLS]; /* W, power of the wall on the particles */
  size_t contacts, wall_contacts;
  double max_overlap;            /* largest alpha / min(r) */
  double max_disp2;              /* m^2 */
  double ke, epot;               /* J: partial kinetic and gravitational energy (checks) */
  double pad[8];                 /* keep threads' hot counters on separate cache lines */
} dem_tdata;

struct dem_sim {
  dem_particles p;
  size_t cap;                    /* allocated particles */
  double *x0;                    /* m, positions at the last neighbour-list build [3cap] */
  double *invr, *invm, *invI;    /* 1/m, 1/kg, 1/(kg m^2): refreshed at every build [cap] */

  int nmat;
  double rho[DEM_ENGINE_MAX_MATERIALS];
  dem_inter inter[DEM_ENGINE_MAX_MATERIALS][DEM_ENGINE_MAX_MATERIALS];
  int hoff;                      /* offset of the tangential spring in a history block */
  int nh;                        /* doubles per history block (0 until the first build) */
  int pmat;                      /* the material of every particle, -1 if they differ (or
                                    none); set at the start of each run */
  int need_state;                /* some law in use is adhesive or plastic: a pair apart
                                    with a live state word still needs the law */

  int nwall;
  dem_wall wall[DEM_ENGINE_MAX_WALLS];

  double dt, g[3], skin;
  int nthreads;
  int sort_every, builds_since_sort;
  int need_build;
  int need_forces;                /* forces not yet evaluated for the current state */
  int f_unkicked;                /* 1: the last force evaluation was not followed by a half
                                    kick (dem_sim_run with 0 steps); 0: v = v_half + dt/2 F/m
                                    (contacts.c recovers the half-step velocities) */
  dem_breakdown bd;
  volatile sig_atomic_t *intr;   /* polled once per step (dem/checkpoint.h), or NULL */
  long last_good;                /* step of the last breakdown check passed, -1 none */

  dem_nlist nl, nl_old;          /* current list and scratch for history carry-over */
  /* cell grid */
  size_t ncell_cap;
  uint32_t *cell_first;          /* [ncells + 1] */
  uint32_t *cell_idx;            /* particle indices grouped by cell [cap] */
  uint32_t *cell_of;             /* cell of each particle [cap] */
  uint32_t *perm;                /* scratch permutation [cap] */
  uint32_t *iperm;               /* [cap] */
  void *tmp;                     /* scratch for permuting arrays [cap * 3 * 8 bytes] */

  dem_tdata td[DEM_MAX_THREADS];

  dem_sim_stats st;
  /* st.time = t_base + (st.steps - steps_base) dt: a function of the step count, so that a
   * run split into several calls (an interruption, a restart) has bit-identical times;
   * the base moves when dt changes (dem_sim_set_dt). */
  double t_base;
  long steps_base;
};

/* particles.c */
int dem_engine_grow(dem_sim *s, size_t cap, dem_err *err);
void dem_engine_permute(dem_sim *s, const uint32_t *perm);

/* neighbour.c */
int dem_engine_build(dem_sim *s, dem_err *err);
void dem_nlist_free(dem_nlist *l);

/* walls.c: penetration depth (m, > 0 overlapping) and unit normal (from the wall towards
 * the particle centre) of a sphere at x with radius r; the reduced radius factor: R* of the
 * contact is r * rfac (1 for plane and disc, Rc / (Rc - r) for the inside of a cylinder). */
double dem_wall_gap(const dem_wall_spec *w, const double x[3], double r, double n[3],
                    double *rfac);
/* indenters.c: the same for SPHERE, FLATCYL and BOX. */
double dem_indenter_gap(const dem_wall_spec *w, const double x[3], double r, double n[3],
                        double *rfac);
void dem_engine_wall_forces(dem_sim *s, dem_tdata *td, size_t i0, size_t i1);
/* Wall neighbour lists: the particles whose surface is within `skin` of the wall (or whose
 * history with the wall is active). Valid while particles move < skin/2 and the wall moves
 * < skin/2 since the build. */
int dem_engine_wall_lists(dem_sim *s, dem_err *err);
/* Servo walls: set their velocity from their last load (after every force evaluation). */
void dem_engine_servo(dem_sim *s);
/* 1 if some wall moved more than skin/2 since the last build */
int dem_engine_walls_moved(const dem_sim *s);

/* force.c */
/* Set in->fl (DEM_IF_*) and the derived constants from in->normal, in->tang, in->roll. */
void dem_engine_inter_compile(dem_inter *in);
void dem_engine_pair_forces(dem_sim *s, dem_tdata *td);
void dem_engine_partition(dem_sim *s);
int dem_engine_spill_reserve(dem_sim *s, dem_err *err);

/* contacts.c: dem_sim_contacts (dem/engine.h) */

/* interaction lookup */
static inline const dem_inter *dem_engine_inter(const dem_sim *s, int a, int b) {
  return &s->inter[a][b];
}

size_t dem_engine_bytes(const dem_sim *s);

/* The inline Hertz(-Mindlin) normal force of a pair or wall contact (thesis 3.14 with the
 * restitution damping; Mindlin 3.25 at alpha_t = alpha): one definition for the force loop
 * (force.c) and the read-only contact export (contacts.c). kt, ct: tangential stiffness
 * (N/m) and damping (N s/m) of the contact. */
static inline void dem_engine_hertz_normal(const dem_inter *in, const dem_geom *g, double alpha,
                                           double vn, dem_normal *out, double *kt,
                                           double *ct) {
  dem_hertz_terms ht;
  dem_hertz_eval(in->normal.c, g->R, g->m, alpha, -vn, &ht);
  out->f_el = ht.f_el;
  out->f_damp = ht.f_damp;
  out->f = ht.f_el + ht.f_damp;
  out->k = ht.k;
  out->f_adh = 0.0;
  out->alpha_t = alpha;
  out->contact = 1;
  *kt = 8.0 * in->tang.G * ht.sra;
  *ct = in->hz_ct * ht.smk;
}

#endif
