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
 * steps the kinetic energy is computed: non-finite -> DEM_ENONFINITE; a gain over the
 * interval, beyond the work done by gravity and the walls, larger than bd.ke_growth times
 * the kinetic energy at the start of the interval counts as a strike, and bd.ke_strikes
 * consecutive strikes -> DEM_EUNSTABLE. (Elastic energy released by overlaps present at the
 * start is such a gain too, but it grows like a power of time, whose ratio between
 * consecutive intervals soon falls below 1 + ke_growth; an unstable time step makes the
 * energy grow geometrically, the same ratio interval after interval. The dense benchmark bed,
 * starting at rest, strikes 5 times in a row with ke_growth = 0.5: hence 1 and 10.)
 */
#include <math.h>
#include <string.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

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

/* Forces in parallel, spills reduced, wall loads summed in thread order. If kick != 0 the
 * second half kick follows in the same parallel region. */
static void compute_forces(dem_sim *s, int kick) {
  const int nt = s->nthreads;
#pragma omp parallel num_threads(nt)
  {
    int t = thread_id();
    dem_tdata *td = &s->td[t];
    forces_local(s, td);
#pragma omp barrier
    reduce_spills(s, t);
    if (kick) half_kick(s, td->row_begin, td->row_end);
  }
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
    for (int t = 0; t < nt; t++) {
      for (int k = 0; k < 3; k++) {
        wl->f[k] += s->td[t].wf[w][k];
        wl->t[k] += s->td[t].wt[w][k];
      }
      pw += s->td[t].wpow[w];
    }
    wl->work += pw * s->dt;
  }
  s->st.contacts = c;
  s->st.wall_contacts = wc;
  s->st.spills = sp;
  s->st.max_overlap_frac = mo;
}

static double potential_gravity(const dem_sim *s) {
  const dem_particles *p = &s->p;
  double e = 0.0;
  for (size_t i = 0; i < p->n; i++)
    e -= p->mass[i] * (s->g[0] * p->x[3 * i] + s->g[1] * p->x[3 * i + 1] +
                       s->g[2] * p->x[3 * i + 2]);
  return e;
}

static double wall_work(const dem_sim *s) {
  double w = 0.0;
  for (int k = 0; k < s->nwall; k++) w += s->wall[k].work;
  return w;
}

static int overlap_error(dem_sim *s, dem_err *err) {
  return dem_err_set(err, DEM_ERUNAWAY,
                     "step %ld (t = %g s): an overlap reached %.3g of the smaller radius "
                     "(allowed %.3g); the time step is too large or the stiffness too low",
                     s->st.steps, s->st.time, s->st.max_overlap_frac, s->bd.max_overlap_frac);
}

int dem_sim_run(dem_sim *s, long nsteps, dem_err *err) {
  int rc;
  if ((rc = check_ready(s, err))) return rc;
  if (nsteps < 0) return dem_err_set(err, DEM_ERANGE, "steps = %ld (allowed >= 0)", nsteps);
  double t0 = now_s();
  if (s->need_build || s->nh == 0)
    if ((rc = dem_engine_build(s, err))) return rc;
  if (s->need_forces) {
    compute_forces(s, 0);
    s->need_forces = 0; /* forces at the current state for the first half kick */
    if (s->st.max_overlap_frac > s->bd.max_overlap_frac) return overlap_error(s, err);
  }
  const int nt = s->nthreads;
  const double half_skin2 = 0.25 * s->skin * s->skin;
  double ke_prev = dem_sim_kinetic_energy(s);
  double epot_prev = potential_gravity(s), work_prev = wall_work(s);
  int strikes = 0;
  for (long step = 0; step < nsteps; step++) {
    double md2 = 0.0;
#pragma omp parallel num_threads(nt) reduction(max : md2)
    {
      const dem_tdata *td = &s->td[thread_id()];
      md2 = kick_drift(s, td->row_begin, td->row_end);
    }
    for (int w = 0; w < s->nwall; w++)
      for (int k = 0; k < 3; k++) s->wall[w].spec.p[k] += s->dt * s->wall[w].spec.v[k];
    if (md2 > half_skin2 || !(md2 == md2) || dem_engine_walls_moved(s)) {
      if ((rc = dem_engine_build(s, err))) {
        s->st.loop_seconds += now_s() - t0;
        return rc;
      }
    }
    compute_forces(s, 1);
    s->st.steps++;
    s->st.time += s->dt;
    if (s->st.max_overlap_frac > s->bd.max_overlap_frac) {
      s->st.loop_seconds += now_s() - t0;
      return overlap_error(s, err);
    }
    if (s->st.steps % s->bd.check_interval == 0) {
      double ke = dem_sim_kinetic_energy(s);
      if (!isfinite(ke)) {
        s->st.loop_seconds += now_s() - t0;
        return dem_err_set(err, DEM_ENONFINITE,
                           "step %ld (t = %g s): non-finite velocity or position", s->st.steps,
                           s->st.time);
      }
      double epot = potential_gravity(s), work = wall_work(s);
      double w_in = (epot_prev - epot) + (work - work_prev);
      double gain = ke - ke_prev - w_in;
      if (ke > s->bd.ke_floor && gain > s->bd.ke_growth * ke_prev) strikes++;
      else strikes = 0;
      if (strikes >= s->bd.ke_strikes) {
        s->st.loop_seconds += now_s() - t0;
        return dem_err_set(err, DEM_EUNSTABLE,
                           "step %ld (t = %g s): kinetic energy grew by more than %g of itself "
                           "without work input in %d consecutive intervals of %d steps "
                           "(now %.3g J); the time step is too large",
                           s->st.steps, s->st.time, s->bd.ke_growth, strikes,
                           s->bd.check_interval, ke);
      }
      ke_prev = ke;
      epot_prev = epot;
      work_prev = work;
    }
  }
  s->st.kinetic_energy = dem_sim_kinetic_energy(s);
  s->st.loop_seconds += now_s() - t0;
  return DEM_OK;
}
