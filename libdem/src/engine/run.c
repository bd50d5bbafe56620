/* Time integration (velocity Verlet for translation and rotation) and breakdown checks.
 *
 * One step of length dt:
 *   v += dt/2 F/m,  w += dt/2 T/I                 (first half kick, forces of the last step)
 *   x += dt v;  walls: p += dt v_wall             (drift)
 *   rebuild the neighbour list if some particle moved more than skin/2 since the last build
 *   F, T = gravity + wall contacts + pair contacts (the velocity-dependent parts see the
 *          half-step velocities, as in LAMMPS and LIGGGHTS)
 *   v += dt/2 F/m,  w += dt/2 T/I                 (second half kick)
 * Spheres need no orientation, so rotation is the angular velocity alone.
 *
 * Breakdown: after every force evaluation the largest overlap (relative to the smaller
 * radius) is compared with bd.max_overlap_frac (DEM_ERUNAWAY); every bd.check_interval
 * steps the kinetic energy is computed: non-finite -> DEM_ENONFINITE; a gain of kinetic
 * energy over the interval, beyond the energy supplied by gravity and the walls (counted
 * only when positive: energy leaving the particles explains no gain), larger than
 * bd.ke_growth times the kinetic energy at the start of the interval counts as a strike,
 * and bd.ke_strikes consecutive strikes -> DEM_EUNSTABLE. The contacts' elastic energy is
 * not in the balance: when a wall backs off from a compressed bed the released elastic
 * energy does work on the wall; with the work counted signed, that outflow read as a gain
 * while the kinetic energy stood still or fell. (Elastic energy released by overlaps
 * present at the start is such a gain too, but it grows like a power of time, whose ratio
 * between consecutive intervals soon falls below 1 + ke_growth; an unstable time step makes
 * the energy grow geometrically, the same ratio interval after interval. The dense
 * benchmark bed, starting at rest, strikes 5 times in a row with ke_growth = 0.5: hence 1
 * and 10.)
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "dem/checkpoint.h"
#include "internal.h"

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int thread_id(void) {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

/* Every material pair that can meet needs an interaction. */
static int check_ready(dem_sim *s, dem_err *err) {
  if (!(s->dt > 0.0)) return dem_err_set(err, DEM_EMISSING, "dt is not set");
  s->need_state = 0;
  for (int a = 0; a < s->nmat; a++)
    for (int b = 0; b < s->nmat; b++)
      if (s->inter[a][b].set &&
          (s->inter[a][b].normal.law->flags & (DEM_LAW_ADHESIVE | DEM_LAW_PLASTIC)))
        s->need_state = 1;
  int used[DEM_ENGINE_MAX_MATERIALS] = {0};
  for (size_t i = 0; i < s->p.n; i++) used[s->p.material[i]] = 1;
  /* one particle material (particles are added and materials changed only between runs) */
  s->pmat = s->p.n > 0 ? s->p.material[0] : -1;
  for (int a = 0; a < s->nmat && s->pmat >= 0; a++)
    if (used[a] && a != s->pmat) s->pmat = -1;
  for (int a = 0; a < s->nmat; a++) {
    if (!used[a]) continue;
    for (int b = 0; b < s->nmat; b++)
      if (used[b] && !s->inter[a][b].set)
        return dem_err_set(err, DEM_EMISSING, "no interaction set between materials %d and %d",
                           a, b);
    for (int w = 0; w < s->nwall; w++)
      if (!s->inter[a][s->wall[w].spec.material].set)
        return dem_err_set(err, DEM_EMISSING,
                           "no interaction set between particle material %d and wall %d "
                           "(material %d)",
                           a, w, s->wall[w].spec.material);
  }
  return DEM_OK;
}

/* Forces for the rows of thread t: gravity, walls, pairs. */
static void forces_local(dem_sim *s, dem_tdata *td) {
  dem_particles *p = &s->p;
  for (size_t i = td->row_begin; i < td->row_end; i++) {
    const double m = p->mass[i];
    for (int k = 0; k < 3; k++) {
      p->f[3 * i + k] = m * s->g[k];
      p->torque[3 * i + k] = 0.0;
    }
  }
  td->contacts = td->wall_contacts = 0;
  td->max_overlap = 0.0;
  dem_engine_wall_forces(s, td, td->row_begin, td->row_end);
  dem_engine_pair_forces(s, td);
}

/* Add the spill lists of the threads before t that land in t's rows (fixed order). */
static void reduce_spills(dem_sim *s, int t) {
  dem_particles *p = &s->p;
  const size_t a = s->td[t].row_begin, b = s->td[t].row_end;
  for (int u = 0; u < t; u++) {
    const dem_tdata *tu = &s->td[u];
    for (size_t k = 0; k < tu->nspill; k++) {
      const dem_spill *sp = tu->spill + k;
      if (sp->j < a || sp->j >= b) continue;
      for (int c = 0; c < 3; c++) {
        p->f[3 * (size_t)sp->j + c] += sp->f[c];
        p->torque[3 * (size_t)sp->j + c] += sp->t[c];
      }
    }
  }
}

static void half_kick(dem_sim *s, size_t a, size_t b) {
  dem_particles *p = &s->p;
  const double h = 0.5 * s->dt;
  double *restrict v = p->v, *restrict w = p->omega;
  const double *restrict f = p->f, *restrict t = p->torque;
  const double *restrict invm = s->invm, *restrict invI = s->invI;
  for (size_t i = a; i < b; i++) {
    const double cm = h * invm[i], ci = h * invI[i];
    for (int k = 0; k < 3; k++) {
      v[3 * i + k] += cm * f[3 * i + k];
      w[3 * i + k] += ci * t[3 * i + k];
    }
  }
}

/* Half kick then drift; returns the largest squared displacement since the last build. */
static double kick_drift(dem_sim *s, size_t a, size_t b) {
  dem_particles *p = &s->p;
  const double dt = s->dt;
  half_kick(s, a, b);
  double *restrict x = p->x;
  const double *restrict v = p->v, *restrict x0 = s->x0;
  double md2 = 0.0;
  for (size_t i = a; i < b; i++) {
    double d2 = 0.0;
    for (int k = 0; k < 3; k++) {
      x[3 * i + k] += dt * v[3 * i + k];
      double d = x[3 * i + k] - x0[3 * i + k];
      d2 += d * d;
    }
    md2 = d2 > md2 ? d2 : md2;
  }
  return md2;
}

/* Step statistics and wall loads, summed in thread order (called by one thread); the wall
 * work advances by power x dt if add_work. */
static void collect(dem_sim *s, int add_work) {
  const int nt = s->nthreads;
  size_t c = 0, wc = 0, sp = 0;
  double mo = 0.0;
  for (int t = 0; t < nt; t++) {
    sp += s->td[t].nspill;
    c += s->td[t].contacts;
    wc += s->td[t].wall_contacts;
    mo = s->td[t].max_overlap > mo ? s->td[t].max_overlap : mo;
  }
  for (int w = 0; w < s->nwall; w++) {
    dem_wall *wl = &s->wall[w];
    double pw = 0.0;
    memset(wl->f, 0, sizeof wl->f);
    memset(wl->t, 0, sizeof wl->t);
    memset(wl->fd, 0, sizeof wl->fd);
    for (int t = 0; t < nt; t++) {
      for (int k = 0; k < 3; k++) {
        wl->f[k] += s->td[t].wf[w][k];
        wl->fd[k] += s->td[t].wfd[w][k];
        wl->t[k] += s->td[t].wt[w][k];
      }
      pw += s->td[t].wpow[w];
    }
    if (add_work) wl->work += pw * s->dt;
    memcpy(wl->v_eval, wl->spec.v, sizeof wl->v_eval); /* before the servo changes it */
    wl->have_v_eval = 1;
  }
  s->st.contacts = c;
  s->st.wall_contacts = wc;
  s->st.spills = sp;
  s->st.max_overlap_frac = mo;
  if (mo > s->st.peak_overlap_frac) s->st.peak_overlap_frac = mo;
  dem_engine_servo(s);
}

/* The largest overlap fraction of the last force evaluation (any thread may call it after
 * the barrier that follows the force loop; all get the same answer). */
static double max_overlap(const dem_sim *s) {
  double mo = 0.0;
  for (int t = 0; t < s->nthreads; t++) mo = s->td[t].max_overlap > mo ? s->td[t].max_overlap : mo;
  return mo;
}

/* Forces at the current state (no kick), e.g. before the first step. */
static void compute_forces(dem_sim *s) {
#pragma omp parallel num_threads(s->nthreads)
  {
    int t = thread_id();
    forces_local(s, &s->td[t]);
#pragma omp barrier
    reduce_spills(s, t);
  }
  collect(s, 0); /* no time elapses: no work */
  s->f_unkicked = 1;
}

/* Kinetic and gravitational energy of rows [a, b). */
static void energies(const dem_sim *s, size_t a, size_t b, double *ke, double *epot) {
  const dem_particles *p = &s->p;
  double k = 0.0, e = 0.0;
  for (size_t i = a; i < b; i++) {
    const double *v = p->v + 3 * i, *w = p->omega + 3 * i, *x = p->x + 3 * i;
    k += 0.5 * p->mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) +
         0.5 * p->inertia[i] * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    e -= p->mass[i] * (s->g[0] * x[0] + s->g[1] * x[1] + s->g[2] * x[2]);
  }
  *ke = k;
  *epot = e;
}

static double wall_work(const dem_sim *s) {
  double w = 0.0;
  for (int k = 0; k < s->nwall; k++) w += s->wall[k].work;
  return w;
}

void dem_sim_reset_peak_overlap(dem_sim *s) { s->st.peak_overlap_frac = s->st.max_overlap_frac; }

static const char *const wall_kind_name[] = {"plane", "die", "disc", "sphere",
                                              "flat cylinder", "box"};

/* The runaway message names the contact: which bodies, their radii, where, how hard they
 * were pressed and how fast they approached, so that a user can tell an unstable step (many
 * contacts, growing geometrically) from a contact driven too fast for its stiffness (an
 * indenter driving the bed at v loads the contacts under it with ~v sqrt(m k), overlap
 * ~v sqrt(m / k): docs/validation.md "What stops the high-rate runs") or a particle squeezed
 * against a wall. The
 * hot loops keep only the largest fraction; the contact is found here, once, by the
 * read-only contact export (contacts.c: about one single-threaded force evaluation). If
 * the export fails (out of memory) the message is the short one. */
static int overlap_error(dem_sim *s, dem_err *err) {
  char who[360] = "";
  dem_sim_contact *buf = NULL;
  size_t cap = 0, n = 0, best = SIZE_MAX, above = 0;
  if (dem_sim_contacts(s, &buf, &cap, &n, NULL) == DEM_OK) {
    const double *rad = s->p.radius;
    double bf = -1.0;
    for (size_t k = 0; k < n; k++) {
      const dem_sim_contact *c = buf + k;
      double rm = rad[c->i];
      if (c->wall < 0 && rad[c->j] < rm) rm = rad[c->j];
      const double fr = c->alpha / rm;
      if (fr > s->bd.max_overlap_frac) above++;
      if (fr > bf) {
        bf = fr;
        best = k;
      }
    }
  }
  if (best != SIZE_MAX) {
    const dem_sim_contact *c = buf + best;
    const dem_particles *p = &s->p;
    const double *x = p->x + 3 * c->i, *vi = p->v + 3 * c->i;
    double vo[3] = {0.0, 0.0, 0.0}, vn = 0.0;
    char other[128];
    if (c->wall < 0) {
      for (int a = 0; a < 3; a++) vo[a] = p->v[3 * c->j + a];
      snprintf(other, sizeof other, "particle %u (r = %.3g m)", (unsigned)p->id[c->j],
               p->radius[c->j]);
    } else {
      const dem_wall *w = &s->wall[c->wall];
      for (int a = 0; a < 3; a++) vo[a] = w->have_v_eval ? w->v_eval[a] : w->spec.v[a];
      snprintf(other, sizeof other, "wall %d (%s)", c->wall,
               (unsigned)w->spec.kind < sizeof wall_kind_name / sizeof *wall_kind_name
                   ? wall_kind_name[w->spec.kind]
                   : "?");
    }
    /* n points from the other body towards i: approaching means (v_i - v_o) . n < 0 */
    for (int a = 0; a < 3; a++) vn -= (vi[a] - vo[a]) * c->n[a];
    snprintf(who, sizeof who,
             " between particle %u (r = %.3g m, at (%.4g, %.4g, %.4g) m) and %s: normal "
             "force %.3g N, approach speed %.3g m/s; %zu contact%s above the limit",
             (unsigned)p->id[c->i], p->radius[c->i], x[0], x[1], x[2], other, c->fn, vn,
             above, above == 1 ? "" : "s");
  }
  free(buf);
  return dem_err_set(err, DEM_ERUNAWAY,
                     "step %ld (t = %g s): an overlap reached %.3g of the smaller radius "
                     "(allowed %.3g)%s; the time step is too large or the stiffness too low "
                     "for the load or the speed",
                     s->st.steps, s->st.time, s->st.max_overlap_frac, s->bd.max_overlap_frac,
                     who);
}

/* Why a run stopped inside the parallel loop. */
enum { STOP_NONE = 0, STOP_BUILD, STOP_OVERLAP, STOP_NONFINITE, STOP_UNSTABLE, STOP_INTR };

void dem_sim_set_interrupt_flag(dem_sim *s, volatile sig_atomic_t *flag) { s->intr = flag; }

long dem_sim_last_good_step(const dem_sim *s) { return s->last_good; }

int dem_sim_run(dem_sim *s, long nsteps, dem_err *err) {
  int rc;
  if ((rc = check_ready(s, err))) return rc;
  if (nsteps < 0) return dem_err_set(err, DEM_ERANGE, "steps = %ld (allowed >= 0)", nsteps);
  if (s->intr && *s->intr)
    return dem_err_set(err, DEM_EINTERRUPTED, "step %ld (t = %g s): interrupted before the run",
                       s->st.steps, s->st.time);
  double t0 = now_s();
  if (s->need_build || s->nh == 0)
    if ((rc = dem_engine_build(s, err))) return rc;
  if (s->need_forces) {
    compute_forces(s);
    s->need_forces = 0;
    if (s->st.max_overlap_frac > s->bd.max_overlap_frac) return overlap_error(s, err);
  }
  const int nt = s->nthreads;
  const double half_skin2 = 0.25 * s->skin * s->skin;
  const long step0 = s->st.steps;
  int stop = STOP_NONE, build_rc = DEM_OK, strikes = 0;
  int intr_seen = 0; /* the interrupt flag as thread 0 read it this step (shared) */
  int walls_moved = 0; /* thread 0's verdict after moving the walls (shared): evaluated by
                          each thread, it could read a wall point that another thread,
                          already inside the rebuild, has just reset */
  long done = 0;
  double ke_last = 0.0;
  /* One parallel region for the whole run: per step, a barrier after the drift (forces read
   * every position), one after the force loop (spills), and on check steps one after the
   * kick; neighbour-list builds run on one thread. Decisions that every thread must share
   * (rebuild, stop) are computed by each thread from the same data after a barrier, so
   * they agree without further synchronisation. */
#pragma omp parallel num_threads(nt)
  {
    const int t = thread_id();
    double ke_prev = 0.0, epot_prev = 0.0, work_prev = 0.0;
    int my_strikes = 0;
    {
      double k, e;
      energies(s, s->td[t].row_begin, s->td[t].row_end, &k, &e);
      s->td[t].ke = k;
      s->td[t].epot = e;
    }
#pragma omp barrier
    for (int u = 0; u < nt; u++) {
      ke_prev += s->td[u].ke;
      epot_prev += s->td[u].epot;
    }
    work_prev = wall_work(s);
#pragma omp barrier
    for (long step = 0; step < nsteps; step++) {
      dem_tdata *td = &s->td[t];
      td->max_disp2 = kick_drift(s, td->row_begin, td->row_end);
      if (t == 0)
        for (int w = 0; w < s->nwall; w++)
          for (int k = 0; k < 3; k++) s->wall[w].spec.p[k] += s->dt * s->wall[w].spec.v[k];
      if (t == 0) walls_moved = dem_engine_walls_moved(s);
#pragma omp barrier
      double md2 = 0.0;
      for (int u = 0; u < nt; u++) md2 = s->td[u].max_disp2 > md2 || !(s->td[u].max_disp2 == s->td[u].max_disp2) ? s->td[u].max_disp2 : md2;
      if (md2 > half_skin2 || !(md2 == md2) || walls_moved) {
#pragma omp single
        {
          build_rc = dem_engine_build(s, err);
          if (build_rc) stop = STOP_BUILD;
        }
        if (stop) break;
      }
      td = &s->td[t]; /* the partition may have changed */
      forces_local(s, td);
      /* read before the barrier, used by all after it: every thread takes the same exit */
      if (t == 0) intr_seen = s->intr ? *s->intr != 0 : 0;
#pragma omp barrier
      reduce_spills(s, t);
      half_kick(s, td->row_begin, td->row_end);
      const long stepno = step0 + step + 1;
      if (max_overlap(s) > s->bd.max_overlap_frac) {
        if (t == 0) {
          stop = STOP_OVERLAP;
          done = step + 1;
        }
        break;
      }
      if (stepno % s->bd.check_interval == 0) {
        double k, e;
        energies(s, td->row_begin, td->row_end, &k, &e);
        td->ke = k;
        td->epot = e;
        if (t == 0) collect(s, 1); /* wall work up to date for the check */
#pragma omp barrier
        double ke = 0.0, epot = 0.0;
        for (int u = 0; u < nt; u++) {
          ke += s->td[u].ke;
          epot += s->td[u].epot;
        }
        double work = wall_work(s);
        if (!isfinite(ke)) {
          if (t == 0) {
            stop = STOP_NONFINITE;
            done = step + 1;
          }
          break;
        }
        /* the gain not paid for by gravity or the walls; energy the particles give away
         * (climbing, pushing a retreating wall) pays for nothing, so the gain is never
         * more than the kinetic energy's own growth (a bed at rest under a backing-off
         * servo piston released elastic energy into it and was called unstable) */
        double input = (epot_prev - epot) + (work - work_prev);
        double gain = ke - ke_prev - fmax(input, 0.0);
        if (ke > s->bd.ke_floor && gain > s->bd.ke_growth * ke_prev) my_strikes++;
        else my_strikes = 0;
        if (my_strikes >= s->bd.ke_strikes) {
          if (t == 0) {
            stop = STOP_UNSTABLE;
            done = step + 1;
            strikes = my_strikes;
            ke_last = ke;
          }
          break;
        }
        ke_prev = ke;
        epot_prev = epot;
        work_prev = work;
        if (t == 0) s->last_good = stepno;
#pragma omp barrier /* nobody overwrites td->ke/epot or the wall loads before all read them */
      } else if (t == 0) {
        collect(s, 1);
      }
      if (t == 0) done = step + 1;
      if (intr_seen) {
        if (t == 0) stop = STOP_INTR;
        break;
      }
    }
  }
  if (stop == STOP_OVERLAP) collect(s, 1); /* that step's loads were not collected */
  s->st.steps += done;
  s->st.time = s->t_base + (double)(s->st.steps - s->steps_base) * s->dt;
  if (done > 0) s->f_unkicked = 0;
  s->st.loop_seconds += now_s() - t0;
  switch (stop) {
  case STOP_BUILD:
    return build_rc;
  case STOP_OVERLAP:
    return overlap_error(s, err);
  case STOP_NONFINITE:
    return dem_err_set(err, DEM_ENONFINITE,
                       "step %ld (t = %g s): non-finite velocity or position", s->st.steps,
                       s->st.time);
  case STOP_UNSTABLE:
    return dem_err_set(err, DEM_EUNSTABLE,
                       "step %ld (t = %g s): kinetic energy grew by more than %g of itself "
                       "without work input in %d consecutive intervals of %d steps "
                       "(now %.3g J); the time step is too large",
                       s->st.steps, s->st.time, s->bd.ke_growth, strikes, s->bd.check_interval,
                       ke_last);
  case STOP_INTR:
    s->st.kinetic_energy = dem_sim_kinetic_energy(s);
    return dem_err_set(err, DEM_EINTERRUPTED,
                       "step %ld (t = %g s): interrupted after %ld of %ld steps (a clean step "
                       "boundary: the state may be checkpointed)",
                       s->st.steps, s->st.time, done, nsteps);
  default:
    break;
  }
  s->st.kinetic_energy = dem_sim_kinetic_energy(s);
  return DEM_OK;
}
