/* dem/engine.h — the 3-D discrete element engine (spheres, walls, velocity Verlet).
 *
 * A simulation is an opaque handle (create / set / run / free, NLopt style). Particles live
 * in a public struct of arrays so that kernels and callers read raw arrays; vectors are
 * stored interleaved, x[3*i + k] for k = 0, 1, 2. The engine re-orders particles in space
 * (cell order) now and then: use `id` to find a particle again.
 *
 * Contact mechanics come from the law table (dem/contact.h: normal force and its history)
 * and dem/tangential.h (tangential spring with Coulomb limit, rolling torque). Every contact
 * (particle pair or particle-wall) owns one contiguous block of history doubles:
 *     [0, law_nhist_max)                     the normal law's block (hist[0] = state word)
 *     [law_nhist_max, +DEM_TANGENTIAL_NHIST) the tangential spring xi (m)
 * where law_nhist_max is the largest nhist of the laws in use. Blocks are carried across
 * neighbour-list rebuilds and spatial re-sorting. See docs/engine.md for the design.
 *
 * Units: SI throughout (m, kg, s, N, N m, rad/s).
 */
#ifndef DEM_ENGINE_H
#define DEM_ENGINE_H

#include <stddef.h>
#include <stdint.h>

#include "dem/contact.h"
#include "dem/error.h"
#include "dem/tangential.h"

#define DEM_ENGINE_MAX_MATERIALS 8
#define DEM_ENGINE_MAX_WALLS 16

/* The particles: a struct of arrays (length n, or 3n for vectors). */
typedef struct dem_particles {
  size_t n;          /* number of particles */
  double *x;         /* m, centre positions [3n] */
  double *v;         /* m/s, velocities [3n] */
  double *omega;     /* rad/s, angular velocities [3n] */
  double *f;         /* N, total force of the last force evaluation (incl. gravity) [3n] */
  double *torque;    /* N m, total torque of the last force evaluation [3n] */
  double *radius;    /* m [n] */
  double *mass;      /* kg [n] */
  double *inertia;   /* kg m^2, moment of inertia 2/5 m r^2 [n] */
  int *material;     /* index of the particle's material [n] */
  uint32_t *id;      /* stable identifier: the order in which particles were added [n] */
} dem_particles;

/* Kinds of wall. Geometry (all vectors in m, normals unit length, normalised on input):
 *   PLANE     infinite plane through p; particles live on the side n points to.
 *   CYLINDER  the inside of a cylindrical die: axis through p along n, radius `radius`;
 *             particles live inside (no end caps: add planes or discs).
 *   DISC      a flat disc (piston) of radius `radius` centred at p with face normal n;
 *             one-sided (particles on the side n points to), with a rim contact for
 *             particles beyond the edge. */
/* Rigid indenters (libdem/src/engine/indenters.c; thesis 6.2.2), bodies that particles
 * touch from outside:
 *   SPHERE    centre p, radius `radius`.
 *   FLATCYL   a flat-ended cylinder: flat end face centred at p with outward normal n
 *             (towards the particles, e.g. (0,0,-1) for an indenter moving down), radius
 *             `radius`, closed by a flat back face at distance `length` behind the front
 *             face (`length` 0: extending without end behind the face, a punch on its rod).
 *   BOX       a square prism: leading face centred at p with outward normal n, square
 *             cross-section of half-side `radius`, closed by a back face at distance
 *             `length` (2 radius: the cube of 6.2.2; 0: without end). Edges along e1 and
 *             e2 = n x e1, e1 the coordinate axis least aligned with n projected onto the
 *             face (x and -y for a vertical indenter; ties go to x, then y), turned by
 *             `angle` about n (e1' = cos(angle) e1 + sin(angle) e2).
 * Contact: the closest point of the body's surface (face, rim/edge, side, corner, back face
 * and back edges). */
typedef enum {
  DEM_WALL_PLANE = 0,
  DEM_WALL_CYLINDER,
  DEM_WALL_DISC,
  DEM_WALL_SPHERE,
  DEM_WALL_FLATCYL,
  DEM_WALL_BOX
} dem_wall_kind;

typedef struct dem_wall_spec {
  dem_wall_kind kind;
  double p[3];    /* m, point on the plane / axis point / disc centre */
  double n[3];    /* -, plane or disc normal (towards the particles) / cylinder axis */
  double radius;  /* m, cylinder or disc radius (unused for a plane) */
  double v[3];    /* m/s, translation velocity of the wall (0 for a fixed wall) */
  int material;   /* index of the wall's material (selects the interaction) */
  double length;  /* m, FLATCYL and BOX: body length behind the leading face (0: without
                     end; the field may be left out of an initializer) */
  double angle;   /* rad, BOX: turn of the edges about n (0: the default frame) */
} dem_wall_spec;

/* Breakdown detection (dem_sim_run stops with an error status). */
typedef struct dem_breakdown {
  double max_overlap_frac; /* stop (DEM_ERUNAWAY) if an overlap exceeds this fraction of the
                              smaller radius of the contact; default 0.25 */
  int check_interval;      /* steps between NaN / energy checks; default 100 */
  double ke_growth;        /* an interval's kinetic-energy gain not explained by the energy
                              gravity and walls supplied (if positive), relative to the
                              kinetic energy before it, that counts as a strike; default 1
                              (more than doubling) */
  int ke_strikes;          /* consecutive strikes that stop the run (DEM_EUNSTABLE);
                              default 10: an unstable step grows geometrically (x1000 in
                              10 intervals), while energy released by initial overlaps or
                              a free fall grows like a power of time, whose ratio between
                              intervals falls below 2 after a few of them */
  double ke_floor;         /* J, kinetic energies below this never strike; default 0 */
} dem_breakdown;

/* Counters and diagnostics. */
typedef struct dem_sim_stats {
  long steps;             /* steps taken since creation */
  double time;            /* s, simulated time */
  long rebuilds;          /* neighbour-list builds */
  long sorts;             /* spatial re-orderings */
  size_t pairs;           /* pairs in the neighbour list */
  size_t contacts;        /* particle-particle contacts at the last force evaluation */
  size_t wall_contacts;   /* particle-wall contacts at the last force evaluation */
  size_t spills;          /* contacts whose reaction crossed a thread's range (last step) */
  double max_overlap_frac;/* largest alpha / min(r_i, r_j) of the last force evaluation */
  double peak_overlap_frac;/* the largest max_overlap_frac of every force evaluation since
                              the simulation was created or restored (not checkpointed:
                              a restored simulation starts it again) */
  double kinetic_energy;  /* J, translational + rotational, at the end of the last run */
  double loop_seconds;    /* wall-clock seconds spent inside dem_sim_run */
  size_t bytes;           /* bytes allocated by the engine (particles, lists, histories) */
} dem_sim_stats;

typedef struct dem_sim dem_sim;

/* Create an empty simulation: no particles, gravity 0, dt unset, skin 0, 1 thread. */
dem_sim *dem_sim_create(dem_err *err);
void dem_sim_free(dem_sim *s);

/* Materials: a density (kg/m^3). *index receives the new material's index. */
int dem_sim_add_material(dem_sim *s, double rho, int *index, dem_err *err);
/* The contact model between materials a and b (symmetric; also used for walls of material
 * b against particles of material a). normal is copied; t and r may be NULL (none). */
int dem_sim_set_interaction(dem_sim *s, int a, int b, const dem_contact *normal,
                            const dem_tangential *t, const dem_rolling *r, dem_err *err);

/* Make room for n particles in total (optional; avoids re-allocation while adding). */
int dem_sim_reserve(dem_sim *s, size_t n, dem_err *err);
/* Add a sphere: centre x (m), velocity v (m/s, may be NULL), radius (m), material index.
 * Mass and inertia follow from the material's density. */
int dem_sim_add_particle(dem_sim *s, const double x[3], const double v[3], double radius,
                         int material, dem_err *err);
/* The particle arrays (valid until the next add/reserve). Positions and velocities may be
 * changed between runs; after changing positions call dem_sim_invalidate. */
dem_particles *dem_sim_particles(dem_sim *s);
/* Force a neighbour-list rebuild before the next step (after moving particles by hand). */
void dem_sim_invalidate(dem_sim *s);

int dem_sim_set_dt(dem_sim *s, double dt, dem_err *err);          /* s, > 0 */
void dem_sim_set_gravity(dem_sim *s, const double g[3]);          /* m/s^2 */
int dem_sim_set_skin(dem_sim *s, double skin, dem_err *err);      /* m, >= 0 */
int dem_sim_set_threads(dem_sim *s, int nthreads, dem_err *err);  /* >= 1 */
/* Re-order particles in space every `every` neighbour-list builds (0 = never; default 10). */
void dem_sim_set_sort_interval(dem_sim *s, int every);
/* Breakdown thresholds; NULL restores the defaults. */
int dem_sim_set_breakdown(dem_sim *s, const dem_breakdown *b, dem_err *err);
void dem_breakdown_defaults(dem_breakdown *b);

/* Walls. *index (may be NULL) receives the wall's index. */
int dem_sim_add_wall(dem_sim *s, const dem_wall_spec *w, int *index, dem_err *err);
/* Change a wall's velocity (m/s); its position advances by v dt each step. */
int dem_sim_set_wall_velocity(dem_sim *s, int wall, const double v[3], dem_err *err);
/* Servo: from the next step on, the wall moves along its normal n (towards the particles
 * for a positive speed) at v = clamp(gain (f_target - f_c), -v_max, v_max), where
 * f_c = -(rate-independent load on the wall) . n is the compressive force the particles
 * exert on it (N) without the normal dashpots (dem_sim_wall_load_rate_independent), updated
 * after every force evaluation. (The dashpots see the wall's own speed: read with them, the
 * servo fed v_n back into v_(n+1) and oscillated once gain x (sum of their coefficients)
 * exceeded 1.) f_target in N (a stress times the wall's area),
 * gain in m/(s N), v_max in m/s. dem_sim_set_wall_velocity switches the servo off. */
int dem_sim_set_wall_servo(dem_sim *s, int wall, double f_target, double gain, double v_max,
                           dem_err *err);
/* Translate a wall by dp (m) at once, without doing work (e.g. to withdraw a piston that
 * has lost contact, or to place an indenter); the neighbour lists are rebuilt. */
int dem_sim_move_wall(dem_sim *s, int wall, const double dp[3], dem_err *err);
/* Penetration depth (m, > 0 overlapping) of a sphere (centre x, radius r) into wall w, the
 * unit normal from the wall surface towards the centre, and the factor rfac with
 * R* = r rfac (1 for flat faces, edges and corners). For tests and tools. */
double dem_wall_penetration(const dem_wall_spec *w, const double x[3], double r, double n[3],
                            double *rfac);
/* The wall as it is now (position after the steps taken). */
int dem_sim_wall(const dem_sim *s, int wall, dem_wall_spec *out);
/* Force (N) and torque about the wall point p (N m) that the particles exert on the wall in
 * the last force evaluation, and the work (J) the wall has done on the particles so far. */
int dem_sim_wall_load(const dem_sim *s, int wall, double f[3], double t[3], double *work);
/* The rate-independent part of that force (N): f less the normal dashpots' part
 * (dem_normal.f_damp of each contact), i.e. springs, plasticity, adhesion and friction. A
 * servo reads this (dem_sim_set_wall_servo). */
int dem_sim_wall_load_rate_independent(const dem_sim *s, int wall, double f[3]);

/* Advance nsteps steps of velocity Verlet. Returns DEM_OK, or DEM_ENONFINITE (NaN/inf),
 * DEM_ERUNAWAY (overlap beyond the stated fraction), DEM_EUNSTABLE (kinetic energy growth
 * without work input), DEM_EMISSING (no dt, or an interaction missing) with a message;
 * after an error the state is that of the step where it was detected. */
int dem_sim_run(dem_sim *s, long nsteps, dem_err *err);

void dem_sim_get_stats(const dem_sim *s, dem_sim_stats *st);
/* Start peak_overlap_frac again from the last force evaluation's max_overlap_frac (e.g.
 * between the phases of a scene, to read the peak of one phase). */
void dem_sim_reset_peak_overlap(dem_sim *s);
/* Kinetic energy now (J): translational + rotational. */
double dem_sim_kinetic_energy(const dem_sim *s);

/* The current neighbour list as pairs of particle indices (i < j), for tests and tools:
 * copies at most cap pairs into pairs[2*k], returns the number of pairs in the list. The
 * list is valid after a run (or dem_sim_build_neighbours). */
size_t dem_sim_neighbour_pairs(const dem_sim *s, uint32_t *pairs, size_t cap);
/* Build the neighbour list now (re-sorting if due). */
int dem_sim_build_neighbours(dem_sim *s, dem_err *err);
/* The history block of the pair (i, j) (particle indices, any order), or NULL if the pair
 * is not in the list; and the block size in doubles. */
double *dem_sim_pair_history(dem_sim *s, size_t i, size_t j);
int dem_sim_history_size(const dem_sim *s);
/* The history block of particle i against wall w. */
double *dem_sim_wall_history(dem_sim *s, size_t i, int wall);

/* ---- contact export (libdem/src/engine/contacts.c; docs/engine.md "Contact export") ----
 * Every particle-particle and particle-wall contact of the last force evaluation, with the
 * force it applied, for stresses (dem/analysis.h, thesis 5.1) and tests. A separate pass
 * over the neighbour and wall lists re-evaluates each contact from the stored state: the
 * positions (unchanged since the evaluation), the half-step velocities the evaluation saw
 * (recovered as v - dt/2 F/m after a step), the wall velocities it used (a servo changes
 * them afterwards) and the histories as the evaluation left them, WITHOUT modifying
 * anything (normal laws run on a copy of the history block; the tangential force is rebuilt
 * from the stored spring: -k xi when sliding, -k xi - c v_t capped at the Coulomb limit when
 * sticking). The sum of a particle's contact forces plus m g equals dem_particles.f to
 * round-off, and the wall contacts sum to -dem_sim_wall_load (tests/check_scene_stress.c).
 * Assumes the normal law is idempotent at an unchanged overlap (true of every law in
 * laws.def: a second call at the same alpha with the updated history gives the same force).
 *
 * Contact point (documented convention):
 *   pair    on the line of centres in the middle of the overlap region,
 *           x_i - (r_i - alpha/2) n = x_j + (r_j - alpha/2) n — the point the engine uses
 *           for the torques of the tangential force (force.c), shared by both particles;
 *   wall    on the wall surface, x_i - (r_i - alpha) n — the point of the engine's torques
 *           on the particle and the wall (walls.c), rigid walls do not deform.
 * With these points a particle in moment equilibrium (without rolling resistance) gives a
 * symmetric stress tensor. */
typedef struct dem_sim_contact {
  size_t i;          /* particle index (current dem_particles order) */
  size_t j;          /* the other particle (i < j), or SIZE_MAX for a wall contact */
  int wall;          /* wall index, -1 for a particle pair */
  double alpha;      /* m, overlap (> 0 compression; < 0 an adhesive contact in tension) */
  double n[3];       /* unit normal from j (or the wall) towards i */
  double point[3];   /* m, contact point (above) */
  double fn;         /* N, normal force incl. damping (> 0 repulsive), f = fn n + f_t */
  double f[3];       /* N, total force on i (normal + tangential); on j (or the wall): -f */
} dem_sim_contact;

/* Lists the contacts into *buf (grown with realloc as needed: *cap is its capacity in
 * records; start with *buf = NULL, *cap = 0 and free(*buf) at the end); *n receives the
 * count. Pairs come first (by i, then j), then walls (by wall, then particle). DEM_EINVAL
 * if the forces are not evaluated for the current state (particles added, walls moved,
 * gravity changed since the last run: dem_sim_run(s, 0, err) evaluates them), DEM_ENOMEM.
 * Valid right after dem_sim_run; velocities changed by hand since then change the damping
 * parts. Cost: about one single-threaded force evaluation. */
int dem_sim_contacts(const dem_sim *s, dem_sim_contact **buf, size_t *cap, size_t *n,
                     dem_err *err);

#endif
