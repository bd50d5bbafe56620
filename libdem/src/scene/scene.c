/* The ball-indentation scene (thesis 5.1.3, 6.1, 7.1): materials, die, stages, time series.
 *
 * Geometry: die axis z through the origin, base plane z = 0 (normal +z), die cylinder of
 * radius die_diameter d / 2, piston a disc of the die's radius facing down (normal -z),
 * indenter on the axis moving down. Gravity -9.81 m/s^2 along z.
 *
 * Strain rate (physics notes: "the project must state how gamma_dot is defined"):
 * gamma_dot = v / h_bed for the piston and for the indenter, h_bed the bed height at the
 * start of the stage; gamma* = gamma_dot sqrt(d/g) (thesis 5.4 / 7.1).
 *
 * Time step (thesis 4.29-4.31, 7.2-7.3): dt = dt_factor sqrt(m^* / k^*) with m* = m_min/2 and
 * k* = k_max/2, i.e. dt_factor sqrt(m_min / k_max); m_min the mass of the smallest size of
 * the table, k_max the largest stiffness of the interactions (dem_contact_kref; for the
 * Hertz/JKR laws evaluated for an impact at 0.5 m/s, above the settling velocities).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dem/material.h"
#include "scene_internal.h"

#define G_ACC 9.81

static double wall_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void set(dem_params *ps, const char *k, double v) {
  dem_err e;
  dem_params_set(ps, k, v, "default", &e);
}

const char *const dem_scene_materials_names[] = {"pasha-simplified", "hertz-jkr", NULL};

void dem_scene_config_defaults(dem_scene_config *c, dem_scene_materials m) {
  memset(c, 0, sizeof *c);
  c->materials = m;
  dem_params_init(&c->pp);
  dem_params_init(&c->pw);
  dem_params_init(&c->pi);
  if (m == DEM_SCENE_HERTZ_JKR) {
    /* Tables 5.2/5.3: Material 1 (particles, indenter) E 55 GPa, nu 0.25, 2456 kg/m^3;
     * Material 2 (die, piston) 182 GPa, 0.3, 7800 kg/m^3; 1-1: e 0.5, mu 0.15, mu_r 0.1,
     * Gamma 0.5 J/m^2; 1-2: e 0.3, no friction, no cohesion. Indenter: Material 1,
     * "cohesionless" (5.1.3): Hertz with the 1-1 restitution and friction. */
    c->rho = 2456.0;
    c->rho_wall = 7800.0;
    set(&c->pp, "E", 55e9), set(&c->pp, "nu", 0.25), set(&c->pp, "gamma", 0.5);
    set(&c->pp, "e", 0.5), set(&c->pp, "mu", 0.15), set(&c->pp, "mu_r", 0.1);
    set(&c->pw, "E", 55e9), set(&c->pw, "nu", 0.25), set(&c->pw, "wall_E", 182e9);
    set(&c->pw, "wall_nu", 0.3), set(&c->pw, "e", 0.3), set(&c->pw, "mu", 0.0);
    set(&c->pi, "E", 55e9), set(&c->pi, "nu", 0.25), set(&c->pi, "wall_E", 55e9);
    set(&c->pi, "wall_nu", 0.25), set(&c->pi, "e", 0.5), set(&c->pi, "mu", 0.15);
    c->psd = DEM_SCENE_PSD_T51;
  } else {
    /* Tables 6.2/6.3: particles ke 1, kp 0.1, kcp 0.01, kt 1 MN/m, 2500 kg/m^3; Gamma 2
     * J/m^2, e 0.5, mu 0.15, mu_r 0.01; geometries (die, piston, indenter) elastic 8 MN/m,
     * kt 8 MN/m, 7800 kg/m^3; particle-wall e 0.3, mu 0, mu_r 0, no cohesion. */
    c->rho = 2500.0;
    c->rho_wall = 7800.0;
    set(&c->pp, "ke", 1e6), set(&c->pp, "kp", 1e5), set(&c->pp, "kcp", 1e4);
    set(&c->pp, "gamma", 2.0), set(&c->pp, "e", 0.5), set(&c->pp, "kt", 1e6);
    set(&c->pp, "mu", 0.15), set(&c->pp, "mu_r", 0.01);
    set(&c->pw, "kn", 8e6), set(&c->pw, "e", 0.3), set(&c->pw, "mu", 0.0);
    set(&c->pw, "kt", 8e6);
    set(&c->pi, "kn", 8e6), set(&c->pi, "e", 0.3), set(&c->pi, "mu", 0.0);
    set(&c->pi, "kt", 8e6);
    c->psd = DEM_SCENE_PSD_T61;
  }
  c->d_mean = 1e-3;
  c->die_diameter = 20.0;
  c->bed_height = 12.0;
  c->phi_est = 0.55;
  c->n_particles = 0;
  c->fill_fraction = 0.30;
  c->seed = 1;
  c->settle_ke = 1e-4;
  c->settle_min_time = 0.02;
  c->settle_max_time = 1.0;
  c->sigma_pre = 1e4;
  c->strain_rate = 1.0;
  c->servo_band = 0.1;
  c->servo_steps = 4.0;
  c->hold_time = 2e-3;
  c->hold_tol = 0.02;
  c->shape = DEM_INDENTER_SPHERE;
  c->indenter_diameter = 8.0;
  c->indent_rate = 0.0;
  c->h_over_r = 0.5;
  c->unload = 0;
  c->dt_factor = 0.2;
  c->stiffness_scale = 1.0;
  c->skin = 0.1;
  c->threads = 1;
  c->sample_interval = 1e-4;
  c->output_stress = 1;
}

#define RANGE(field, lo, hi, unit)                                                           \
  if (!(c->field >= (lo) && c->field <= (hi)))                                               \
    return dem_err_set(err, DEM_ERANGE, "scene: " #field " = %g %s (allowed [%g, %g])",      \
                       (double)c->field, unit, (double)(lo), (double)(hi));

int dem_scene_config_check(const dem_scene_config *c, dem_err *err) {
  RANGE(rho, 1.0, 1e5, "kg/m^3");
  RANGE(d_mean, 1e-7, 1.0, "m");
  RANGE(die_diameter, 3.0, 1000.0, "d");
  RANGE(bed_height, 1.0, 1000.0, "d");
  RANGE(phi_est, 0.05, 0.74, "-");
  RANGE(n_particles, 0, 1e8, "");
  RANGE(fill_fraction, 0.01, 0.38, "-");
  RANGE(settle_ke, 1e-12, 1.0, "x m g d");
  RANGE(settle_min_time, 0.0, 100.0, "s");
  RANGE(settle_max_time, c->settle_min_time, 100.0, "s");
  RANGE(sigma_pre, 1.0, 1e9, "Pa");
  RANGE(strain_rate, 1e-4, 1e4, "1/s");
  RANGE(servo_band, 1e-3, 1.0, "-");
  RANGE(servo_steps, 2.0, 1e6, "steps");
  RANGE(hold_time, 0.0, 100.0, "s");
  RANGE(hold_tol, 1e-4, 0.5, "-");
  RANGE(shape, 0, 2, "(0 sphere, 1 cylinder, 2 cube)");
  RANGE(indenter_diameter, 0.5, 1000.0, "d");
  RANGE(indenter_length, 0.0, 1000.0, "d (0: the diameter)");
  RANGE(indent_rate, 0.0, 1e4, "1/s (0: strain_rate)");
  RANGE(h_over_r, 0.01, 2.0, "-");
  RANGE(unload, 0, 1, "");
  RANGE(dt_factor, 1e-4, 1.0, "-");
  RANGE(stiffness_scale, 1e-6, 1.0, "-");
  RANGE(skin, 0.0, 2.0, "d");
  RANGE(threads, 1, 64, "");
  RANGE(sample_interval, 0.0, 10.0, "s");
  RANGE(output_stress, 0, 1, "");
  if (c->indenter_diameter >= c->die_diameter)
    return dem_err_set(err, DEM_ERANGE,
                       "scene: indenter_diameter = %g d must be below die_diameter = %g d",
                       c->indenter_diameter, c->die_diameter);
  return DEM_OK;
}

/* Scale every stiffness-like key of a parameter set. */
static void scale_params(dem_params *ps, double s) {
  static const char *const keys[] = {"ke", "kp", "kcp", "kt", "kn", "kc", "ke_max", "E",
                                     "wall_E", NULL};
  for (int k = 0; keys[k]; k++) {
    dem_param *p = (dem_param *)dem_params_find(ps, keys[k]);
    if (p) p->value *= s;
  }
}

static int make_inter(dem_scene *sc, int a, int b, const dem_params *src, const char *law,
                      const char *what, double *kmax, double m_min, double R_min,
                      dem_err *err) {
  dem_params ps = *src;
  scale_params(&ps, sc->cfg.stiffness_scale);
  dem_contact ct;
  dem_tangential tg;
  dem_rolling rl;
  int rc;
  const dem_law *L = dem_contact_law_find(law);
  if (!L) return dem_err_set(err, DEM_ENOTFOUND, "scene %s: law '%s' not found", what, law);
  static const char *const extra[] = {"mu", "mu_r", "kt", NULL};
  char msg[sizeof err->msg];
  if ((rc = dem_contact_check_keys(L, &ps, extra, err)) ||
      (rc = dem_contact_setup(&ct, L, &ps, err)))
    goto fail;
  double mu = dem_params_get_or(&ps, "mu", 0.0);
  const dem_tangential *tp = NULL;
  if (mu > 0.0) {
    dem_tangential_kind kind =
        dem_params_find(&ps, "kt") ? DEM_TANGENTIAL_LINEAR : DEM_TANGENTIAL_MINDLIN;
    if ((rc = dem_tangential_setup(&tg, kind, &ps, err))) goto fail;
    tp = &tg;
  }
  if ((rc = dem_rolling_setup(&rl, &ps, err))) goto fail;
  if ((rc = dem_sim_set_interaction(sc->sim, a, b, &ct, tp, &rl, err))) goto fail;
  /* pair: R* = r/2, m* = m/2 ; wall: R* = r, m* = m — k at the smallest size */
  dem_geom g = {a == b ? 0.5 * R_min : R_min, a == b ? 0.5 * m_min : m_min};
  double k = dem_contact_kref(&ct, &g, 0.5);
  if (tp && tg.kind == DEM_TANGENTIAL_LINEAR && tg.kt > k) k = tg.kt;
  if (k > *kmax) *kmax = k;
  return DEM_OK;
fail:
  memcpy(msg, err->msg, sizeof msg);
  return dem_err_set(err, rc, "scene %s interaction: %s", what, msg);
}

static const char *const series_names[] = {
    "t", "stage", "piston_z", "piston_stress", "indenter_z", "depth", "h_over_r",
    "indenter_force", "hardness", "kinetic_energy", "contacts", "wall_contacts",
    "bin_p", "bin_q", "bin_phi", "base_p", "indenter_contacts", "contact_radius"};
static const char *const series_units[] = {"s", "-", "m", "Pa", "m", "m", "-", "N", "Pa", "J",
                                           "-", "-", "Pa", "Pa", "-", "Pa", "-", "m"};
/* The last SCENE_NCONTACT come from scene_stress_row (stress.c). indenter_contacts and
 * contact_radius were added on 2026-12-07; a checkpoint written before has the first
 * SCENE_NSERIES_V3 columns, and its rows are read with the two new ones NaN (restart.c). */
#define NSERIES SCENE_NSERIES
_Static_assert(sizeof series_names / sizeof *series_names == NSERIES &&
                   sizeof series_units / sizeof *series_units == NSERIES,
               "a name and a unit per column");
_Static_assert(NSERIES - SCENE_NCONTACT == 12, "record() fills the first 12 columns");

dem_table *scene_series_create(dem_err *err) {
  return dem_table_create(NSERIES, series_names, series_units, err);
}

int scene_interactions(dem_scene *sc, dem_err *err) {
  const dem_scene_config *c = &sc->cfg;
  const double *dd, *fr;
  int nb = dem_scene_psd_table(c->psd, &dd, &fr), rc;
  double dmin = dd[0];
  for (int k = 1; k < nb; k++) dmin = dd[k] < dmin ? dd[k] : dmin;
  const double r_min = 0.5 * dmin * c->d_mean, m_min = dem_sphere_mass(r_min, c->rho);
  double kmax = 0.0;
  const int hj = c->materials == DEM_SCENE_HERTZ_JKR;
  if ((rc = make_inter(sc, sc->mat_p, sc->mat_p, &c->pp, hj ? "jkr-modified" : "pasha-simplified",
                       "particle-particle", &kmax, m_min, r_min, err)) ||
      (rc = make_inter(sc, sc->mat_p, sc->mat_w, &c->pw, hj ? "hertz" : "linear",
                       "particle-wall", &kmax, m_min, r_min, err)) ||
      (rc = make_inter(sc, sc->mat_p, sc->mat_i, &c->pi, hj ? "hertz" : "linear",
                       "particle-indenter", &kmax, m_min, r_min, err)))
    return rc;
  sc->dt = c->dt_factor * dem_dt_mass_spring(m_min, kmax);
  sc->k_max = kmax;
  return dem_sim_set_dt(sc->sim, sc->dt, err);
}

/* Servo gain 1 / (K_bound servo_steps dt_servo): K_bound = (one contact per d^2 of piston)
 * x k_max, the stiffest bed the piston can meet; dt_servo = SERVO_DT_FACTOR sqrt(m_min /
 * k_max), the step at the thesis' factor 0.2 whatever the run's dt_factor, so the servo's
 * response is a physical time and the consolidation one protocol at every time step (with
 * the run's own dt, a larger step made a slower servo and a longer hold: docs/scene.md).
 * Stable for the explicit step: the loop gain per step, gain K dt, is at most
 * dt / (servo_steps dt_servo) = dt_factor / (SERVO_DT_FACTOR servo_steps), 0.25 at the
 * thesis' 0.2 and 1.25 (< 2) at dt_factor 1 with servo_steps 4. (servo_steps was 20 until
 * the servo read the rate-independent load, 2026-12-03: read with the dashpots of the
 * piston contacts, the piston's own speed came back through them and gain c_tot > 1
 * oscillated, which capped the gain at ~4x that of 20 steps; docs/scene.md.) */
#define SERVO_DT_FACTOR 0.2
double scene_servo_gain(const dem_scene *sc) {
  const dem_scene_config *c = &sc->cfg;
  const double A = M_PI * sc->die_radius * sc->die_radius;
  const double K_bound = A / (c->d_mean * c->d_mean) * sc->k_max;
  /* at the reference factor the run's own step, so that the gain (and every bed made at
   * 0.2) is bit for bit the earlier rule's; x / 0.2 * 0.2 need not round back to x */
  const double dt_servo = c->dt_factor == SERVO_DT_FACTOR
                              ? sc->dt
                              : sc->dt * (SERVO_DT_FACTOR / c->dt_factor);
  return 1.0 / (K_bound * c->servo_steps * dt_servo);
}

dem_scene *dem_scene_create(const dem_scene_config *c, const dem_scene_hooks *h, dem_err *err) {
  if (dem_scene_config_check(c, err)) return NULL;
  dem_scene *sc = calloc(1, sizeof *sc);
  if (!sc) {
    dem_err_set(err, DEM_ENOMEM, "scene: out of memory");
    return NULL;
  }
  sc->cfg = *c;
  if (h) sc->hooks = *h;
  sc->w_ind = -1;
  sc->surface = NAN;
  sc->reached = DEM_SCENE_STAGE_NONE;
  sc->die_radius = 0.5 * c->die_diameter * c->d_mean;
  sc->series = scene_series_create(err);
  sc->sim = dem_sim_create(err);
  if (!sc->series || !sc->sim) goto fail;
  if (dem_sim_add_material(sc->sim, c->rho, &sc->mat_p, err) ||
      dem_sim_add_material(sc->sim, c->rho_wall > 0 ? c->rho_wall : 7800.0, &sc->mat_w, err) ||
      dem_sim_add_material(sc->sim, c->rho_wall > 0 ? c->rho_wall : 7800.0, &sc->mat_i, err))
    goto fail;
  if (scene_interactions(sc, err)) goto fail;
  double g[3] = {0, 0, -G_ACC};
  dem_sim_set_gravity(sc->sim, g);
  if (dem_sim_set_skin(sc->sim, c->skin * c->d_mean, err) ||
      dem_sim_set_threads(sc->sim, c->threads, err))
    goto fail;
  dem_breakdown bd;
  dem_breakdown_defaults(&bd);
  bd.ke_floor = 1e-3 * dem_sphere_mass(0.5 * c->d_mean, c->rho) * G_ACC * c->d_mean;
  dem_sim_set_breakdown(sc->sim, &bd, err);
  return sc;
fail:
  dem_scene_free(sc);
  return NULL;
}

void dem_scene_free(dem_scene *sc) {
  if (!sc) return;
  scene_stress_free(sc);
  dem_sim_free(sc->sim);
  dem_table_free(sc->series);
  free(sc);
}

dem_sim *dem_scene_sim(dem_scene *sc) { return sc->sim; }
const dem_table *dem_scene_series(const dem_scene *sc) { return sc->series; }

double dem_scene_indent_area(dem_indenter_shape shape, double D, double h) {
  if (shape == DEM_INDENTER_CUBE) return D * D;
  if (shape == DEM_INDENTER_CYLINDER || h >= 0.5 * D) return 0.25 * M_PI * D * D;
  return h > 0.0 ? M_PI * (D * h - h * h) : 0.0;
}

/* Highest particle top and the bed height: the mean top of the highest layer (as many
 * particles as cover the die's cross-section once, (Rd/r_mean)^2), and the solids fraction
 * by centre counting in the cylinder of radius Rd - d between z = d and bed_top - d. */
static double cmp_d(const double *a, const double *b) { return *a - *b; }
static int cmp_desc(const void *a, const void *b) {
  double x = cmp_d(a, b);
  return (x < 0) - (x > 0);
}
static void bed_measure(dem_scene *sc) {
  dem_particles *p = dem_sim_particles(sc->sim);
  const size_t n = p->n;
  const double d = sc->cfg.d_mean, Rd = sc->die_radius;
  double *top = malloc((n ? n : 1) * sizeof *top);
  if (!top) return;
  for (size_t i = 0; i < n; i++) top[i] = p->x[3 * i + 2] + p->radius[i];
  qsort(top, n, sizeof *top, cmp_desc);
  size_t m = (size_t)((Rd / (0.5 * d)) * (Rd / (0.5 * d)));
  m = m < 1 ? 1 : (m > n ? n : m);
  double s = 0;
  for (size_t k = 0; k < m; k++) s += top[k];
  sc->bed_top = n ? s / (double)m : 0.0;
  free(top);
  const double zlo = d, zhi = sc->bed_top - d, ra = Rd - d;
  double vol = 0.0;
  for (size_t i = 0; i < n; i++) {
    const double *x = p->x + 3 * i;
    if (x[2] >= zlo && x[2] <= zhi && x[0] * x[0] + x[1] * x[1] <= ra * ra)
      vol += 4.0 / 3.0 * M_PI * p->radius[i] * p->radius[i] * p->radius[i];
  }
  sc->phi = zhi > zlo ? vol / (M_PI * ra * ra * (zhi - zlo)) : NAN;
}

static double highest_top(dem_scene *sc, double rad) {
  dem_particles *p = dem_sim_particles(sc->sim);
  double z = 0.0;
  for (size_t i = 0; i < p->n; i++) {
    const double *x = p->x + 3 * i;
    if (x[0] * x[0] + x[1] * x[1] <= rad * rad && x[2] + p->radius[i] > z)
      z = x[2] + p->radius[i];
  }
  return z;
}

/* Pa, the bed's stress on the piston: the rate-independent load, without the dashpots of
 * the piston contacts, which the servo must not read (dem_sim_set_wall_servo) and the hold
 * criterion and the set-point integral then must not read either, or they would chase
 * each other by c_tot v. */
static double piston_stress(dem_scene *sc) {
  double f[3];
  dem_sim_wall_load_rate_independent(sc->sim, sc->w_piston, f);
  return f[2] / (M_PI * sc->die_radius * sc->die_radius); /* particles push the piston up */
}

typedef struct row_state {
  double ind_z, depth, force;
} row_state;

static void ind_state(dem_scene *sc, row_state *rs) {
  rs->ind_z = rs->depth = rs->force = NAN;
  if (sc->w_ind < 0) return;
  dem_wall_spec w;
  dem_sim_wall(sc->sim, sc->w_ind, &w);
  double f[3];
  dem_sim_wall_load(sc->sim, sc->w_ind, f, NULL, NULL);
  rs->ind_z = w.p[2] - (sc->cfg.shape == DEM_INDENTER_SPHERE ? sc->ind_r : 0.0); /* tip */
  rs->force = f[2];
  rs->depth = isnan(sc->surface) ? 0.0 : sc->surface - rs->ind_z;
}

static int record(dem_scene *sc, dem_err *err) {
  dem_sim_stats st;
  dem_sim_get_stats(sc->sim, &st);
  dem_wall_spec pw;
  dem_sim_wall(sc->sim, sc->w_piston, &pw);
  row_state rs;
  ind_state(sc, &rs);
  const double D = 2.0 * sc->ind_r;
  double A = rs.depth > 0.0 ? dem_scene_indent_area(sc->cfg.shape, D, rs.depth) : 0.0;
  double row[NSERIES] = {st.time,
                         (double)sc->stage,
                         pw.p[2],
                         piston_stress(sc),
                         rs.ind_z,
                         rs.depth,
                         sc->ind_r > 0 ? rs.depth / sc->ind_r : NAN,
                         rs.force,
                         A > 0.0 ? rs.force / A : NAN,
                         dem_sim_kinetic_energy(sc->sim),
                         (double)st.contacts,
                         (double)st.wall_contacts};
  int rc = scene_stress_row(sc, row + NSERIES - SCENE_NCONTACT, err);
  if (rc) return rc;
  return dem_table_append(sc->series, row, err);
}

static const char *const stage_names[] = {"settle", "consolidate", "unload", "indent",
                                          "withdraw"};

/* Hooks after a row: snapshot and progress. */
static int after_row(dem_scene *sc, double frac, dem_err *err) {
  int rc;
  dem_sim_stats st;
  dem_sim_get_stats(sc->sim, &st);
  const dem_scene_hooks *h = &sc->hooks;
  if (h->snapshot && h->snapshot_interval > 0 && st.time >= sc->next_snap) {
    if ((rc = h->snapshot(sc->sim, stage_names[sc->stage], st.time, h->user, err))) return rc;
    while (sc->next_snap <= st.time) sc->next_snap += h->snapshot_interval;
  }
  double now = wall_now();
  if (h->progress && now - sc->last_progress >= h->progress_interval) {
    double eta = frac > 1e-3 ? (now - sc->stage_wall0) * (1.0 - frac) / frac : -1.0;
    /* the unload stage's relax phase (piston withdrawn, the bed coming to rest) is named in
     * the progress, so that a log shows which of the two takes the time; snapshots keep the
     * stage's name */
    const char *name = sc->stage == 2 && sc->sub == 2 ? "relax" : stage_names[sc->stage];
    h->progress(name, st.time, frac, eta, h->user);
    sc->last_progress = now;
  }
  return DEM_OK;
}

static long sample_steps(const dem_scene *sc) {
  long steps = sc->cfg.sample_interval > 0 ? lround(sc->cfg.sample_interval / sc->dt) : 200;
  return steps < 1 ? 1 : steps;
}

/* Integral rate of the consolidation servo, the fraction of the force error (F - f_c) added
 * to the set point per sample (-). With the bed a spring of stiffness K under a piston at
 * v = gain (f_set - f_c), the force follows f' = (f_set - f) / tau_P, tau_P = 1 / (gain K);
 * with f_set' = (F - f) / T_i the loop is tau_P f'' + f' + f / T_i = F / T_i, critically
 * damped at T_i = 4 tau_P. K is the bed's loading stiffness over the second half of phase 1,
 * (f1 - f_half) / (z_half - z1), N/m (piston z in m, forces in N); the unloading branch is
 * stiffer, which only damps the loop more. Without a usable K (no half-load point: the
 * stress jumped past half of sigma_pre within one check; or K not positive) the stiffest
 * bed, K_bound, is assumed, which gives the cap: at most 0.5 per sample, the old rule's rate,
 * then bounded only by the clamp of f_set to F (1 +- servo_band). */
double scene_servo_ki(const dem_scene *sc, double z_half, double f_half, double z1, double f1) {
  const dem_scene_config *c = &sc->cfg;
  const double A = M_PI * sc->die_radius * sc->die_radius;
  const double K_bound = A / (c->d_mean * c->d_mean) * sc->k_max;
  double K = (f1 - f_half) / (z_half - z1);
  if (!(K > 0.0) || !isfinite(K) || K > K_bound) K = K_bound;
  const double tau_p = 1.0 / (scene_servo_gain(sc) * K);
  const double ki = (double)sample_steps(sc) * sc->dt / (4.0 * tau_p);
  return fmin(ki, 0.5);
}

/* Advance n steps (n <= the sample interval); a row is recorded whenever a sample
 * interval has elapsed since the last row. */
static int advance(dem_scene *sc, long n, double frac, dem_err *err) {
  if (sc->resume) n = sc->pending; /* the rest of the interrupted advance */
  sc->resume = 0;
  dem_sim_stats st;
  dem_sim_get_stats(sc->sim, &st);
  const long s0 = st.steps;
  int rc = n > 0 ? dem_sim_run(sc->sim, n, err) : DEM_OK;
  if (rc) {
    dem_sim_get_stats(sc->sim, &st);
    sc->since_row += st.steps - s0;
    if (rc == DEM_EINTERRUPTED) { /* a clean step boundary: resumable, also from a file */
      sc->resume = 1;
      sc->pending = n - (st.steps - s0);
    }
    return rc;
  }
  sc->since_row += n;
  if (sc->since_row >= sample_steps(sc)) {
    sc->since_row = 0;
    if ((rc = record(sc, err))) return rc;
    return after_row(sc, frac, err);
  }
  return DEM_OK;
}

/* One sample interval of steps, then the row. */
static int chunk(dem_scene *sc, double frac, dem_err *err) {
  return advance(sc, sample_steps(sc) - sc->since_row, frac, err);
}

static void stage_begin(dem_scene *sc, int stage) {
  sc->stage = stage;
  sc->stage_wall0 = wall_now();
  sc->last_progress = 0.0;
}

static double sim_time(dem_scene *sc) {
  dem_sim_stats st;
  dem_sim_get_stats(sc->sim, &st);
  return st.time;
}

/* Stage order: 1 if the stage is already done (skip it: a restored scene continues), 0 to
 * run it, an error if the stage before has not been completed. */
static const char *const reached_names[] = {"fill", "settle", "consolidate", "unload",
                                            "indent"};
static int stage_guard(dem_scene *sc, dem_scene_stage st, dem_err *err) {
  if (sc->reached >= (int)st) return 1;
  if (sc->reached < (int)st - 1) {
    int next = sc->reached + 1 < 0 ? 0 : sc->reached + 1;
    return -dem_err_set(err, DEM_EINVAL, "scene %s: run the %s stage first",
                        reached_names[st], reached_names[next > 4 ? 4 : next]);
  }
  return 0;
}
#define GUARD(st)                                                                            \
  do {                                                                                       \
    int g_ = stage_guard(sc, st, err);                                                       \
    if (g_) return g_ > 0 ? DEM_OK : -g_;                                                    \
  } while (0)

static void stage_done(dem_scene *sc, dem_scene_stage st) {
  sc->reached = (int)st;
  sc->sub = 0;
}

int dem_scene_fill(dem_scene *sc, dem_err *err) {
  int rc;
  GUARD(DEM_SCENE_STAGE_FILLED);
  if (dem_sim_particles(sc->sim)->n > 0)
    return dem_err_set(err, DEM_EINVAL, "scene fill: a failed fill left particles behind");
  if ((rc = scene_fill(sc, err))) return rc;
  dem_particles *p = dem_sim_particles(sc->sim);
  double m = 0;
  for (size_t i = 0; i < p->n; i++) m += p->mass[i];
  sc->m_mean = p->n ? m / (double)p->n : 0.0;
  const double Rd = sc->die_radius;
  dem_wall_spec base = {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 1}, 0, {0, 0, 0}, sc->mat_w};
  dem_wall_spec die = {DEM_WALL_CYLINDER, {0, 0, 0}, {0, 0, 1}, Rd, {0, 0, 0}, sc->mat_w};
  dem_wall_spec pis = {DEM_WALL_DISC, {0, 0, sc->fill_top + sc->cfg.d_mean}, {0, 0, -1}, Rd,
                       {0, 0, 0}, sc->mat_w};
  if ((rc = dem_sim_add_wall(sc->sim, &base, &sc->w_base, err)) ||
      (rc = dem_sim_add_wall(sc->sim, &die, &sc->w_die, err)) ||
      (rc = dem_sim_add_wall(sc->sim, &pis, &sc->w_piston, err)))
    return rc;
  stage_done(sc, DEM_SCENE_STAGE_FILLED);
  return DEM_OK;
}

int dem_scene_settle(dem_scene *sc, dem_err *err) {
  const dem_scene_config *c = &sc->cfg;
  GUARD(DEM_SCENE_STAGE_SETTLED);
  stage_begin(sc, 0);
  if (!sc->sub) {
    sc->t0 = sim_time(sc);
    sc->sub = 1;
  }
  const double ke_lim = c->settle_ke * sc->m_mean * G_ACC * c->d_mean;
  int rc;
  for (;;) {
    if (!sc->resume) { /* the checks come after a complete chunk */
      double t = sim_time(sc) - sc->t0;
      double kep = dem_sim_kinetic_energy(sc->sim) / (double)dem_sim_particles(sc->sim)->n;
      if (t >= c->settle_min_time && kep < ke_lim) break;
      if (t > c->settle_max_time)
        return dem_err_set(err, DEM_EPHYSICS,
                           "scene settle: kinetic energy per particle %.3g J still above %.3g "
                           "J (settle_ke = %g m g d) after settle_max_time = %g s",
                           kep, ke_lim, c->settle_ke, c->settle_max_time);
    }
    if ((rc = chunk(sc, -1.0, err))) return rc; /* no estimate of the remaining time */
  }
  bed_measure(sc);
  stage_done(sc, DEM_SCENE_STAGE_SETTLED);
  return DEM_OK;
}

int dem_scene_consolidate(dem_scene *sc, dem_err *err) {
  const dem_scene_config *c = &sc->cfg;
  GUARD(DEM_SCENE_STAGE_CONSOLIDATED);
  stage_begin(sc, 1);
  int rc;
  dem_wall_spec pw;
  const double A = M_PI * sc->die_radius * sc->die_radius, F = c->sigma_pre * A;
  if (!sc->sub) {
    bed_measure(sc);
    /* bring the piston down to just above the highest particle (no work: no contact) */
    dem_sim_wall(sc->sim, sc->w_piston, &pw);
    double top = highest_top(sc, sc->die_radius);
    double dp[3] = {0, 0, top + 0.05 * c->d_mean - pw.p[2]};
    if (dp[2] < 0 && (rc = dem_sim_move_wall(sc->sim, sc->w_piston, dp, err))) return rc;
    sc->v_piston = c->strain_rate * sc->bed_top;
    /* Phase 1: constant velocity (constant strain rate) until the stress reaches sigma_pre,
     * as the thesis loads its beds (physics.md: "consolidated by a flat piston at constant
     * strain rate to a pre-consolidation stress of 10 kPa"), checked every few steps. */
    double v[3] = {0, 0, -sc->v_piston};
    if ((rc = dem_sim_set_wall_velocity(sc->sim, sc->w_piston, v, err))) return rc;
    sc->t0 = sim_time(sc);
    sc->t_max = 1.0 / c->strain_rate; /* 100% strain: give up */
    sc->z_half = sc->f_half = NAN;
    sc->sub = 1;
  }
  if (sc->sub == 1) {
    const long sub = 10;
    while (sc->resume || piston_stress(sc) < c->sigma_pre) {
      if ((rc = advance(sc, sub, fmin(piston_stress(sc) / c->sigma_pre, 1.0), err))) return rc;
      if (isnan(sc->z_half) && piston_stress(sc) >= 0.5 * c->sigma_pre) {
        dem_sim_wall(sc->sim, sc->w_piston, &pw);
        sc->z_half = pw.p[2];
        sc->f_half = piston_stress(sc) * A;
      }
      if (sim_time(sc) - sc->t0 > sc->t_max) break;
    }
    /* Phase 2: hold sigma_pre with the engine's proportional servo, v = gain (f_set - f_c)
     * capped at the loading speed, gain from scene_servo_gain: stable for the explicit step
     * whatever the bed. (A gain from the measured loading stiffness, 10x for the unloading
     * branch at 200 dt, made the piston and the bed oscillate between 1 and 15 kPa, then
     * blamed on the bed's dynamics; the servo read the piston contacts' dashpots then, which
     * is what oscillates at gain c_tot > 1: docs/scene.md.) Hold within hold_tol for
     * hold_time. The set point f_set is corrected by an integral term (below) whose rate
     * follows from the bed's loading stiffness measured over the second half of phase 1. */
    sc->gain = scene_servo_gain(sc);
    dem_sim_wall(sc->sim, sc->w_piston, &pw);
    sc->ki = scene_servo_ki(sc, sc->z_half, sc->f_half, pw.p[2], piston_stress(sc) * A);
    /* The hold's own time limit: the proportional term's time constant tau_P = t_sample /
     * (4 ki), not the loading's 100% strain time, sets how long it may take (a fast
     * loading of a small bed, gamma* 0.5 on 113 particles, needs ~2x 1/strain_rate); 20
     * tau_P (at least 1/strain_rate) after the switch: give up. */
    sc->t_max = sim_time(sc) - sc->t0 +
                fmax(1.0 / c->strain_rate, 20.0 * (double)sample_steps(sc) * sc->dt / (4.0 * sc->ki));
    if ((rc = dem_sim_set_wall_servo(sc->sim, sc->w_piston, F, sc->gain, sc->v_piston, err)))
      return rc;
    sc->t_in = -1.0; /* time the band was entered */
    sc->f_set = F;
    sc->sub = 2;
  }
  for (;;) {
    /* no progress fraction in the hold: its length is not known in advance (the stress
     * ratio used to be shown, 93-97 % with an ETA of 20-30 s for minutes, and falling) */
    if ((rc = chunk(sc, -1.0, err))) return rc;
    const double t = sim_time(sc), s = piston_stress(sc);
    /* integral action at the sample rate: a creeping (plastic) bed leaves a proportional
     * servo ~2-4 % below its target. Rate ki from scene_servo_ki (critical damping of the
     * PI loop), the set point kept within F (1 +- servo_band): it cannot wind up. (Until
     * 2026-12-03 half the error per sample, a time constant of ~0.2 ms against the
     * proportional term's ~18 ms, applied from 0.9 sigma_pre on: it wound f_set up to ~2.8 F
     * and the beds saw 12-13.5 kPa; docs/scene.md.) */
    sc->f_set += sc->ki * (F - s * A);
    sc->f_set = fmin(fmax(sc->f_set, (1.0 - c->servo_band) * F), (1.0 + c->servo_band) * F);
    if ((rc = dem_sim_set_wall_servo(sc->sim, sc->w_piston, sc->f_set, sc->gain, sc->v_piston,
                                     err)))
      return rc;
    if (fabs(s - c->sigma_pre) <= c->hold_tol * c->sigma_pre) {
      if (sc->t_in < 0) sc->t_in = t;
      if (t - sc->t_in >= c->hold_time) break;
    } else {
      sc->t_in = -1.0; /* left the band: start the hold again */
    }
    if (t - sc->t0 > sc->t_max)
      return dem_err_set(err, DEM_EPHYSICS,
                         "scene consolidate: piston stress %.4g Pa has not held sigma_pre = "
                         "%g Pa within hold_tol = %g for hold_time = %g s after %g s (the "
                         "loading, then max(1 / strain_rate, 20 servo time constants))",
                         s, c->sigma_pre, c->hold_tol, c->hold_time, sc->t_max);
  }
  stage_done(sc, DEM_SCENE_STAGE_CONSOLIDATED);
  return DEM_OK;
}

int dem_scene_unload(dem_scene *sc, dem_err *err) {
  const dem_scene_config *c = &sc->cfg;
  GUARD(DEM_SCENE_STAGE_UNLOADED);
  stage_begin(sc, 2);
  int rc;
  double v[3] = {0, 0, sc->v_piston};
  if (!sc->sub) {
    if ((rc = dem_sim_set_wall_velocity(sc->sim, sc->w_piston, v, err))) return rc;
    sc->t0 = sim_time(sc);
    sc->sub = 1;
  }
  if (sc->sub == 1) {
    for (;;) {
      if ((rc = chunk(sc, fmax(0.0, 1.0 - piston_stress(sc) / c->sigma_pre), err))) return rc;
      double f[3];
      dem_sim_wall_load(sc->sim, sc->w_piston, f, NULL, NULL);
      if (f[2] == 0.0) break;
      if (sim_time(sc) - sc->t0 > 1.0 / c->strain_rate)
        return dem_err_set(err, DEM_EPHYSICS, "scene unload: the bed still pushes the piston");
    }
    /* withdraw the piston out of reach of the indentation (no contact: no work) */
    v[2] = 0.0;
    dem_sim_set_wall_velocity(sc->sim, sc->w_piston, v, err);
    double dp[3] = {0, 0, 4.0 * c->indenter_diameter * c->d_mean + 5.0 * c->d_mean};
    if ((rc = dem_sim_move_wall(sc->sim, sc->w_piston, dp, err))) return rc;
    sc->t0 = sim_time(sc);
    sc->t_rest = -1.0;
    sc->sub = 2;
  }
  /* Relax: the bed leaves the piston moving. It expanded with the piston, its velocity rising
   * from 0 at the base to v at the top, so its centre of mass leaves at up to v/2 upward and
   * the whole bed flies up by up to v^2 / (8 g) and lands again about v / g later (found
   * 2026-12-02: at gamma* 0.1 on the 20 d bed, v = 0.19 m/s, a flight of ~0.4 d and ~20 ms,
   * which the indentation used to meet; at the thesis' 1 1/s on 20 mm, 5 um). The bed is
   * ready when it is at rest as a whole: its centre of mass slower than the rms speed of the
   * settle criterion, v_lim = sqrt(2 settle_ke g d_mean) (1.4 mm/s), and the base and die
   * carrying at least half its weight, at every sample for at least the flight time v / g
   * (which bounds any later, lower bounce; a single sample would also be met at the deepest
   * point of the landing). Not the settle criterion on the kinetic energy: the bed may turn
   * about the die axis as a rigid body on the frictionless base and die (Table 6.3, mu 0),
   * which nothing stops; the consolidated tiny bed of the CLI tests turns at 0.62 rad/s
   * after unloading, 96% of its translational kinetic energy, half its particles above
   * 1.4 mm/s (docs/validation/bed-at-rest/bed_spin.c). */
  const double v_lim = sqrt(2.0 * c->settle_ke * G_ACC * c->d_mean);
  const double t_min = fabs(sc->v_piston) / G_ACC;
  const dem_particles *p = dem_sim_particles(sc->sim);
  double mass = 0;
  for (size_t i = 0; i < p->n; i++) mass += p->mass[i];
  for (;;) {
    if (!sc->resume) { /* the checks come after a complete chunk */
      double t = sim_time(sc) - sc->t0, fb[3], fd[3], mv = 0;
      for (size_t i = 0; i < p->n; i++) mv += p->mass[i] * p->v[3 * i + 2];
      const double v_com = mass > 0 ? mv / mass : 0.0;
      dem_sim_wall_load(sc->sim, sc->w_base, fb, NULL, NULL);
      dem_sim_wall_load(sc->sim, sc->w_die, fd, NULL, NULL);
      /* N, upward force of base and die on the bed, as a fraction of its weight */
      const double support = mass > 0 ? -(fb[2] + fd[2]) / (mass * G_ACC) : 1.0;
      if (fabs(v_com) < v_lim && support >= 0.5) {
        if (sc->t_rest < 0) sc->t_rest = t;
        if (t - sc->t_rest >= t_min) break;
      }
      else sc->t_rest = -1.0;
      if (t > c->settle_max_time)
        return dem_err_set(err, DEM_EPHYSICS,
                           "scene unload: the bed is not at rest %g s after leaving the "
                           "piston (settle_max_time): centre of mass at %.3g m/s (limit "
                           "%.3g m/s from settle_ke), base and die carry %.3g of its weight "
                           "(at least 0.5), held for %.3g s of the %.3g s needed",
                           c->settle_max_time, v_com, v_lim, support,
                           sc->t_rest < 0 ? 0.0 : t - sc->t_rest, t_min);
    }
    if ((rc = chunk(sc, -1.0, err))) return rc;
  }
  bed_measure(sc);
  stage_done(sc, DEM_SCENE_STAGE_UNLOADED);
  return DEM_OK;
}

int dem_scene_indent(dem_scene *sc, dem_err *err) {
  const dem_scene_config *c = &sc->cfg;
  GUARD(DEM_SCENE_STAGE_INDENTED);
  stage_begin(sc, sc->sub == 2 ? 4 : 3);
  int rc;
  if (!sc->sub) {
    if (sc->w_ind >= 0) return dem_err_set(err, DEM_EINVAL, "scene indent: already indented");
    const double D = c->indenter_diameter * c->d_mean;
    sc->ind_r = 0.5 * D;
    const double top =
        highest_top(sc, 0.5 * D * (c->shape == DEM_INDENTER_CUBE ? M_SQRT2 : 1.0));
    const double tip = top + 0.2 * c->d_mean;
    /* a bed restored with a larger indenter than the one it was unloaded for: keep the
     * piston out of reach as dem_scene_unload does (never moves it in a plain run) */
    dem_wall_spec pw;
    dem_sim_wall(sc->sim, sc->w_piston, &pw);
    double dp[3] = {0, 0, tip + 4.0 * D + 4.0 * c->d_mean - pw.p[2]};
    if (dp[2] > 0 && (rc = dem_sim_move_wall(sc->sim, sc->w_piston, dp, err))) return rc;
    sc->v_ind = (c->indent_rate > 0 ? c->indent_rate : c->strain_rate) * sc->bed_top;
    dem_wall_spec w = {DEM_WALL_SPHERE, {0, 0, tip}, {0, 0, -1}, 0.5 * D, {0, 0, -sc->v_ind},
                       sc->mat_i};
    if (c->shape == DEM_INDENTER_SPHERE) w.p[2] += 0.5 * D;
    else w.kind = c->shape == DEM_INDENTER_CYLINDER ? DEM_WALL_FLATCYL : DEM_WALL_BOX;
    /* closed bodies: the cube of side D, the cylinder D long unless configured */
    if (c->shape == DEM_INDENTER_CUBE) w.length = D;
    if (c->shape == DEM_INDENTER_CYLINDER)
      w.length = c->indenter_length > 0 ? c->indenter_length * c->d_mean : D;
    if ((rc = dem_sim_add_wall(sc->sim, &w, &sc->w_ind, err))) return rc;
    sc->surface = NAN;
    sc->t0 = sim_time(sc);
    sc->t_max = (tip - 0.0) / sc->v_ind; /* reaching the base: give up */
    sc->sub = 1;
  }
  row_state rs;
  if (sc->sub == 1) {
    const double h_end = c->h_over_r * sc->ind_r;
    for (;;) {
      ind_state(sc, &rs);
      double frac = isnan(sc->surface) ? 0.0 : rs.depth / h_end;
      if ((rc = chunk(sc, frac, err))) return rc;
      ind_state(sc, &rs);
      if (isnan(sc->surface) && rs.force > 0.0) {
        /* first contact: the surface is where the tip is now, minus the travel of this
         * chunk's contact period (at most one chunk: sample_interval v) — taken as now */
        sc->surface = rs.ind_z;
      }
      if (!isnan(sc->surface) && sc->surface - rs.ind_z >= h_end) break;
      if (sim_time(sc) - sc->t0 > sc->t_max)
        return dem_err_set(err, DEM_EPHYSICS, "scene indent: the indenter reached the base");
    }
    if (!c->unload) {
      stage_done(sc, DEM_SCENE_STAGE_INDENTED);
      return DEM_OK;
    }
    stage_begin(sc, 4);
    double v[3] = {0, 0, sc->v_ind};
    if ((rc = dem_sim_set_wall_velocity(sc->sim, sc->w_ind, v, err))) return rc;
    sc->sub = 2;
  }
  for (;;) {
    if ((rc = chunk(sc, -1.0, err))) return rc;
    ind_state(sc, &rs);
    if (rs.force <= 0.0) break;
    if (sc->surface - rs.ind_z < -c->d_mean) break;
  }
  double v[3] = {0, 0, 0};
  dem_sim_set_wall_velocity(sc->sim, sc->w_ind, v, err);
  stage_done(sc, DEM_SCENE_STAGE_INDENTED);
  return DEM_OK;
}

int dem_scene_run(dem_scene *sc, dem_err *err) {
  int rc;
  if ((rc = dem_scene_fill(sc, err)) || (rc = dem_scene_settle(sc, err)) ||
      (rc = dem_scene_consolidate(sc, err)) || (rc = dem_scene_unload(sc, err)) ||
      (rc = dem_scene_indent(sc, err)))
    return rc;
  return DEM_OK;
}

void dem_scene_get_info(const dem_scene *sc, dem_scene_info *in) {
  memset(in, 0, sizeof *in);
  dem_scene *s = (dem_scene *)sc;
  in->n = dem_sim_particles(s->sim)->n;
  in->dt = sc->dt;
  in->die_radius = sc->die_radius;
  in->mean_d = sc->mean_d;
  in->sd_d = sc->sd_d;
  scene_psd_moments(sc->cfg.psd, sc->cfg.d_mean, &in->table_mean, &in->table_sd);
  in->bed_top = sc->bed_top;
  in->phi = sc->phi;
  in->surface = sc->surface;
  in->piston_stress = sc->w_piston >= 0 && in->n ? piston_stress(s) : 0.0;
  row_state rs;
  ind_state(s, &rs);
  in->indenter_force = rs.force;
  in->depth = rs.depth;
  in->v_piston = sc->v_piston;
  in->v_indenter = sc->v_ind;
}
