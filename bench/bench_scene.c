/* dem-bench-scene: speed-versus-accuracy study and stability map of the ball-indentation
 * scene (issue 6, "Tiers, cost, and modelling no more than a scene needs").
 *
 * Usage: dem-bench-scene --study speed|stability [--out DIR] [--budget S] [--threads N]
 *                        [--json] [--quick]
 *
 * Every variant is a complete scene (dem/scene.h): fill, settle, consolidate to 10 kPa,
 * unload, indent with a sphere to h/r = h_over_r. EVERY VARIANT PREPARES ITS OWN BED with its
 * own stiffness, rate and time step (stiffness and rate change the consolidated bed: the
 * overlaps at 10 kPa scale like 1/k and a fast piston leaves a different packing), from the
 * same fill seed. The consolidation strain rate equals the indentation rate:
 * gamma* = gamma_dot sqrt(d/g) (thesis 5.4 / 7.1).
 *
 * Measured per variant: particles, steps, simulated time, wall-clock and CPU seconds, the
 * plateau hardness H over the h/r window [0.1, h_over_r] (dem_plateau_stats: mean, standard
 * error from the integrated autocorrelation time), the deviation from the reference in units
 * of the reference's standard error and the z value with the combined standard error
 * z = (H - H_ref) / sqrt(se^2 + se_ref^2), the largest overlap fraction seen (alpha over the
 * smaller radius, sampled at every time-series row, and the engine's own stop at 0.25), the
 * peak kinetic energy per particle during the indentation in units of m g d, and the status
 * of the run (the engine's breakdown detection: DEM_ENONFINITE, DEM_EUNSTABLE, DEM_ERUNAWAY;
 * dem_engine.h). "Within the reference" means |z| <= 1.96 (two-sided 95 %).
 *
 * speed: the reference (the most faithful affordable settings) and one-at-a-time variants of
 *   stiffness_scale, gamma*, dt_factor and die diameter, then a candidate combining the
 *   cheapest passing value of each; writes DIR/study_speed.{csv,json,gp,png}.
 * stability: a grid dt_factor x stiffness_scale at gamma* 0.1 and a rate line at the default
 *   stiffness on a tiny bed; categories ok / overlap (> 5 % of the radius) / biased (|z| >
 *   1.96 against the grid's most faithful point) / failed (a stage's own limit) / breakdown
 *   (the engine's detection); writes DIR/study_stability.{csv,json,gp,png}.
 * --budget S: variants not started within S seconds of wall clock are skipped, a running
 *   variant is interrupted at 1.25 S (status DEM_EINTERRUPTED); --quick: 2 tiny variants
 *   (the smoke test; fill fraction 0.35 and settle_ke 1e-3 to shorten the settling). docs/validation-study.md describes the study and its results.
 * Exit status 0, 2 on a usage error, 1 if the reference run fails or a file cannot be written.
 */
#include <errno.h>
#include <getopt.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <time.h>

#include "dem/analysis.h"
#include "dem/engine.h"
#include "dem/scene.h"
#include "dem/table.h"

#define G_ACC 9.81
#define D_MEAN 1e-3          /* m */
#define Z_LEVEL 1.96         /* two-sided 95 % */
#define OVERLAP_LIMIT 0.05   /* of the smaller radius: "overlaps beyond a few %" */
#define MAXV 64

enum { EXIT_OK_ = 0, EXIT_RUN_ = 1, EXIT_USAGE_ = 2 };

typedef struct variant {
  char name[48];
  const char *pair;    /* NULL, or the variant it is compared with besides the reference
                          (same settings but the one varied parameter) */
  const char *group;   /* reference, stiffness, rate, dt, die, candidate, grid, rate-line */
  double scale;        /* stiffness_scale */
  double gstar;        /* gamma*, consolidation and indentation */
  double dtf;          /* dt_factor */
  double die, bed, ind; /* d */
  double hr;           /* final h/r */
  unsigned long seed;  /* fill seed (1 unless replicated) */
  /* results */
  int ran, rc;
  char msg[600];
  size_t n;
  double dt, sim_t, wall_s, cpu_s;
  long steps;
  double H_mean, H_se, H_sd, tau;
  size_t H_n;
  int H_reliable;
  double dev_ref_se, z, z_pair;
  int within, within_pair;
  double max_ovl, max_ovl_indent, ke_peak, phi;
  double t_stage[4];   /* s simulated: settle, consolidate, unload, indent */
  const char *category;
} variant;

typedef struct run_ctx {
  double max_ovl, max_ovl_indent, ke_peak, m_g_d;
  size_t n;
  double t_start, deadline;
} run_ctx;

static double now_wall(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
static double now_cpu(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static const char *code_name(int rc) {
#define DEM_X_NAME(sym, num, text) \
  case sym:                        \
    return #sym;
  switch (rc) {
    DEM_ERROR_LIST(DEM_X_NAME)
    default: return "?";
  }
#undef DEM_X_NAME
}

/* gamma* -> gamma_dot (1/s): gamma* = gamma_dot sqrt(d/g). */
static double rate_of(double gstar) { return gstar / sqrt(D_MEAN / G_ACC); }

/* Called after every time-series row (the snapshot hook at the row interval): the peak
 * kinetic energy of the indentation; stops the run past the hard deadline. (The overlaps
 * are the engine's peak over every step, read in run_variant.) */
static int row_hook(dem_sim *s, const char *stage, double t, void *user, dem_err *err) {
  (void)t;
  run_ctx *c = user;
  if (strcmp(stage, "indent") == 0) {
    double ke = dem_sim_kinetic_energy(s) / ((double)c->n * c->m_g_d);
    if (ke > c->ke_peak) c->ke_peak = ke;
  }
  if (c->deadline > 0 && now_wall() > c->deadline)
    return dem_err_set(err, DEM_EINTERRUPTED, "bench: wall-clock budget exhausted");
  return DEM_OK;
}

static int g_quick; /* --quick: a shorter fall and a looser settling criterion */

static void config_of(const variant *v, int threads, dem_scene_config *c) {
  dem_scene_config_defaults(c, DEM_SCENE_PASHA);
  c->d_mean = D_MEAN;
  c->die_diameter = v->die;
  c->bed_height = v->bed;
  c->indenter_diameter = v->ind;
  c->h_over_r = v->hr;
  c->fill_fraction = 0.33;
  c->seed = v->seed ? v->seed : 1;
  if (g_quick) c->fill_fraction = 0.35, c->settle_ke = 1e-3;
  c->settle_min_time = 0.01;
  c->hold_time = 1e-3;
  c->strain_rate = rate_of(v->gstar);
  c->indent_rate = c->strain_rate;
  c->dt_factor = v->dtf;
  c->stiffness_scale = v->scale;
  c->threads = threads;
  c->unload = 0;
  /* about 200 rows over the plateau window whatever the rate: depth 0.2 r at v = rate h */
  double t_win = (v->hr - 0.1) * 0.5 * v->ind * D_MEAN / (c->indent_rate * v->bed * D_MEAN);
  c->sample_interval = fmin(1e-4, t_win / 200.0);
  /* dt factors beyond the scene's allowed 1 (the stability map): the scene is built with
   * dt_factor 1 and the engine's step is multiplied afterwards (run_variant); the row
   * interval and the servo's time constant in steps are rescaled so that they stay the same
   * in seconds. */
  if (v->dtf > 1.0) {
    c->dt_factor = 1.0;
    c->sample_interval /= v->dtf;
    c->servo_steps *= v->dtf;
  }
}

static void run_variant(variant *v, int threads, double deadline, double lo) {
  dem_scene_config c;
  config_of(v, threads, &c);
  dem_err err = {0};
  run_ctx ctx = {0};
  ctx.deadline = deadline;
  dem_scene_hooks h = {0};
  h.snapshot = row_hook;
  h.snapshot_interval = c.sample_interval; /* about every row (the scene advances the next
                                              snapshot time by whole intervals) */
  h.user = &ctx;
  v->ran = 1;
  v->H_mean = v->H_se = v->H_sd = v->tau = NAN;
  v->dev_ref_se = v->z = NAN;
  double w0 = now_wall(), c0 = now_cpu();
  dem_scene *sc = NULL;
  int rc = dem_scene_config_check(&c, &err);
  if (!rc) {
    sc = dem_scene_create(&c, &h, &err);
    if (!sc) rc = err.code ? err.code : DEM_ENOMEM;
  }
  if (!rc && v->dtf > 1.0) {
    dem_scene_info in0;
    dem_scene_get_info(sc, &in0);
    rc = dem_sim_set_dt(dem_scene_sim(sc), in0.dt * v->dtf, &err);
  }
  if (!rc) rc = dem_scene_fill(sc, &err);
  if (!rc) {
    dem_particles *p = dem_sim_particles(dem_scene_sim(sc));
    double m = 0;
    for (size_t i = 0; i < p->n; i++) m += p->mass[i];
    ctx.n = p->n;
    ctx.m_g_d = (p->n ? m / (double)p->n : 1.0) * G_ACC * D_MEAN;
    rc = dem_scene_settle(sc, &err);
  }
  if (!rc) rc = dem_scene_consolidate(sc, &err);
  if (!rc) rc = dem_scene_unload(sc, &err);
  int indented = 0;
  if (!rc) {
    /* the engine's peak over every step: before the indentation, then of it alone */
    dem_sim *s = dem_scene_sim(sc);
    dem_sim_stats st;
    dem_sim_get_stats(s, &st);
    if (st.peak_overlap_frac > ctx.max_ovl) ctx.max_ovl = st.peak_overlap_frac;
    dem_sim_reset_peak_overlap(s);
    indented = 1;
    rc = dem_scene_indent(sc, &err);
  }
  v->wall_s = now_wall() - w0;
  v->cpu_s = now_cpu() - c0;
  v->rc = rc;
  snprintf(v->msg, sizeof v->msg, "%s", rc ? err.msg : "");
  v->max_ovl = ctx.max_ovl;
  v->max_ovl_indent = ctx.max_ovl_indent;
  v->ke_peak = ctx.ke_peak;
  if (!sc) return;
  dem_sim_stats st;
  dem_sim *s = dem_scene_sim(sc);
  dem_sim_get_stats(s, &st);
  if (st.peak_overlap_frac > v->max_ovl) v->max_ovl = st.peak_overlap_frac;
  if (indented && st.peak_overlap_frac > v->max_ovl_indent)
    v->max_ovl_indent = st.peak_overlap_frac;
  dem_scene_info in;
  dem_scene_get_info(sc, &in);
  v->n = in.n;
  v->dt = in.dt * (v->dtf > 1.0 ? v->dtf : 1.0);
  v->phi = in.phi;
  v->steps = st.steps;
  v->sim_t = st.time;
  if (!rc) {
    /* the plateau window of the indentation rows */
    const dem_table *t = dem_scene_series(sc);
    long nr = dem_table_nrows(t);
    double *hd = malloc(sizeof(double) * (size_t)(nr > 0 ? nr : 1));
    double *H = malloc(sizeof(double) * (size_t)(nr > 0 ? nr : 1));
    size_t k = 0;
    for (long i = 0; hd && H && i < nr; i++) {
      double stage = dem_table_get(t, i, 1), x = dem_table_get(t, i, 6),
             y = dem_table_get(t, i, 8);
      if (stage == 3.0 && isfinite(x) && isfinite(y)) hd[k] = x, H[k] = y, k++;
    }
    /* simulated time per stage: last row time of each stage minus the previous stage's */
    double t_end[4] = {0, 0, 0, 0};
    for (long i = 0; i < nr; i++) {
      int sg = (int)dem_table_get(t, i, 1);
      if (sg >= 0 && sg < 4) t_end[sg] = dem_table_get(t, i, 0);
    }
    for (int g = 0; g < 4; g++) v->t_stage[g] = t_end[g] - (g ? t_end[g - 1] : 0.0);
    dem_series_stats ps;
    dem_err e2;
    if (hd && H && dem_plateau_stats(k, hd, H, lo, v->hr + 1e-9, NULL, &ps, &e2) == DEM_OK) {
      v->H_mean = ps.mean;
      v->H_se = ps.se;
      v->H_sd = ps.sd;
      v->tau = ps.tau;
      v->H_n = ps.n;
      v->H_reliable = ps.reliable;
    } else {
      snprintf(v->msg, sizeof v->msg, "plateau: %s", e2.msg);
    }
    free(hd);
    free(H);
  }
  dem_scene_free(sc);
}

static double zval(const variant *a, const variant *b) {
  return (a->H_mean - b->H_mean) / sqrt(a->H_se * a->H_se + b->H_se * b->H_se);
}

static void compare(variant *v, const variant *ref, const variant *vs, int nv) {
  v->z_pair = NAN;
  if (!v->ran || !isfinite(v->H_mean) || !isfinite(ref->H_mean)) return;
  v->dev_ref_se = (v->H_mean - ref->H_mean) / ref->H_se;
  v->z = zval(v, ref);
  v->within = fabs(v->z) <= Z_LEVEL;
  for (int i = 0; v->pair && i < nv; i++)
    if (strcmp(vs[i].name, v->pair) == 0 && vs[i].ran && isfinite(vs[i].H_mean)) {
      v->z_pair = zval(v, &vs[i]);
      v->within_pair = fabs(v->z_pair) <= Z_LEVEL;
    }
}

static void categorise(variant *v) {
  if (!v->ran) v->category = "skipped";
  else if (v->rc == DEM_ENONFINITE || v->rc == DEM_EUNSTABLE || v->rc == DEM_ERUNAWAY)
    v->category = "breakdown";
  else if (v->rc == DEM_EINTERRUPTED) v->category = "skipped";
  else if (v->rc || !isfinite(v->H_mean)) v->category = "failed";
  else if (isfinite(v->z) && !v->within) v->category = "biased";
  else if (v->max_ovl > OVERLAP_LIMIT) v->category = "overlap";
  else v->category = "ok";
}

static int category_index(const char *c) {
  static const char *const names[] = {"ok", "overlap", "biased", "failed", "breakdown",
                                      "skipped"};
  for (int i = 0; i < 6; i++)
    if (strcmp(c, names[i]) == 0) return i;
  return 5;
}

static void set_v(variant *v, const char *name, const char *group, double scale, double gstar,
                  double dtf, double die, double bed, double ind, double hr) {
  memset(v, 0, sizeof *v);
  snprintf(v->name, sizeof v->name, "%s", name);
  v->group = group;
  v->scale = scale, v->gstar = gstar, v->dtf = dtf;
  v->die = die, v->bed = bed, v->ind = ind, v->hr = hr;
}

/* ---- output ------------------------------------------------------------------------------ */

static json_t *num(double x) { return isfinite(x) ? json_real(x) : json_null(); }

static json_t *variant_json(const variant *v) {
  json_t *o = json_object();
  json_object_set_new(o, "name", json_string(v->name));
  json_object_set_new(o, "group", json_string(v->group));
  json_object_set_new(o, "stiffness_scale", num(v->scale));
  json_object_set_new(o, "gamma_star", num(v->gstar));
  json_object_set_new(o, "strain_rate", num(rate_of(v->gstar)));
  json_object_set_new(o, "dt_factor", num(v->dtf));
  json_object_set_new(o, "die_diameter", num(v->die));
  json_object_set_new(o, "bed_height", num(v->bed));
  json_object_set_new(o, "indenter_diameter", num(v->ind));
  json_object_set_new(o, "h_over_r", num(v->hr));
  json_object_set_new(o, "seed", json_integer((json_int_t)(v->seed ? v->seed : 1)));
  json_object_set_new(o, "ran", json_boolean(v->ran));
  json_object_set_new(o, "status", json_integer(v->rc));
  json_object_set_new(o, "status_name", json_string(code_name(v->rc)));
  json_object_set_new(o, "status_text", json_string(dem_strerror(v->rc)));
  json_object_set_new(o, "message", json_string(v->msg));
  json_object_set_new(o, "category", json_string(v->category ? v->category : "?"));
  json_object_set_new(o, "particles", json_integer((json_int_t)v->n));
  json_object_set_new(o, "dt", num(v->dt));
  json_object_set_new(o, "steps", json_integer(v->steps));
  json_object_set_new(o, "sim_time", num(v->sim_t));
  json_object_set_new(o, "stage_sim_time",
                      json_pack("{s:o,s:o,s:o,s:o}", "settle", num(v->t_stage[0]), "consolidate",
                                num(v->t_stage[1]), "unload", num(v->t_stage[2]), "indent",
                                num(v->t_stage[3])));
  json_object_set_new(o, "wall_s", num(v->wall_s));
  json_object_set_new(o, "cpu_s", num(v->cpu_s));
  json_object_set_new(o, "H_mean", num(v->H_mean));
  json_object_set_new(o, "H_se", num(v->H_se));
  json_object_set_new(o, "H_sd", num(v->H_sd));
  json_object_set_new(o, "H_n", json_integer((json_int_t)v->H_n));
  json_object_set_new(o, "H_tau", num(v->tau));
  json_object_set_new(o, "H_se_reliable", json_boolean(v->H_reliable));
  json_object_set_new(o, "dev_ref_se", num(v->dev_ref_se));
  json_object_set_new(o, "z", num(v->z));
  json_object_set_new(o, "within", json_boolean(v->within));
  json_object_set_new(o, "pair", v->pair ? json_string(v->pair) : json_null());
  json_object_set_new(o, "z_pair", num(v->z_pair));
  json_object_set_new(o, "within_pair", json_boolean(v->within_pair));
  json_object_set_new(o, "max_overlap_frac", num(v->max_ovl));
  json_object_set_new(o, "max_overlap_frac_indent", num(v->max_ovl_indent));
  json_object_set_new(o, "ke_peak_indent", num(v->ke_peak));
  json_object_set_new(o, "phi", num(v->phi));
  if (!v->ran) { /* skipped (budget, --only): nothing was measured, not zeros */
    static const char *const measured[] = {
        "status", "status_name", "status_text", "particles", "dt", "steps", "sim_time",
        "stage_sim_time", "wall_s", "cpu_s", "H_mean", "H_se", "H_sd", "H_n", "H_tau",
        "H_se_reliable", "dev_ref_se", "z", "within", "z_pair", "within_pair",
        "max_overlap_frac", "max_overlap_frac_indent", "ke_peak_indent", "phi"};
    for (size_t i = 0; i < sizeof measured / sizeof *measured; i++)
      json_object_set_new(o, measured[i], json_null());
  }
  return o;
}

static int write_csv(const char *path, const variant *vs, int nv) {
  FILE *f = fopen(path, "w");
  if (!f) return -1;
  fprintf(f,
          "name,group,stiffness_scale,gamma_star,strain_rate,dt_factor,die_diameter,"
          "bed_height,indenter_diameter,h_over_r,status_name,category,particles,dt,steps,"
          "sim_time,wall_s,cpu_s,H_mean,H_se,H_n,H_tau,dev_ref_se,z,within,max_overlap_frac,"
          "max_overlap_frac_indent,ke_peak_indent,phi,pair,z_pair\n");
  for (int i = 0; i < nv; i++) {
    const variant *v = &vs[i];
    if (!v->ran) { /* skipped: the settings, the category, and empty measurements */
      fprintf(f, "%s,%s,%g,%g,%.6g,%g,%g,%g,%g,%g,,%s,,,,,,,,,,,,,,,,,,%s,\n", v->name, v->group,
              v->scale, v->gstar, rate_of(v->gstar), v->dtf, v->die, v->bed, v->ind, v->hr,
              v->category ? v->category : "skipped", v->pair ? v->pair : "");
      continue;
    }
    fprintf(f,
            "%s,%s,%g,%g,%.6g,%g,%g,%g,%g,%g,%s,%s,%zu,%.4g,%ld,%.5g,%.2f,%.2f,%.6g,%.4g,%zu,"
            "%.3g,%.3g,%.3g,%d,%.4g,%.4g,%.4g,%.4g,%s,%.3g\n",
            v->name, v->group, v->scale, v->gstar, rate_of(v->gstar), v->dtf, v->die, v->bed,
            v->ind, v->hr, code_name(v->rc), v->category, v->n, v->dt, v->steps, v->sim_t,
            v->wall_s, v->cpu_s, v->H_mean, v->H_se, v->H_n, v->tau, v->dev_ref_se, v->z,
            v->within, v->max_ovl, v->max_ovl_indent, v->ke_peak, v->phi,
            v->pair ? v->pair : "", v->z_pair);
  }
  return fclose(f);
}

static json_t *machine_json(int threads) {
  json_t *m = json_object();
  struct utsname u;
  if (uname(&u) == 0) {
    json_object_set_new(m, "system", json_string(u.sysname));
    json_object_set_new(m, "release", json_string(u.release));
    json_object_set_new(m, "machine", json_string(u.machine));
  }
  json_object_set_new(m, "threads", json_integer(threads));
  double la[3];
  FILE *f = fopen("/proc/loadavg", "r");
  if (f && fscanf(f, "%lf %lf %lf", &la[0], &la[1], &la[2]) == 3)
    json_object_set_new(m, "loadavg_at_end", json_pack("[f,f,f]", la[0], la[1], la[2]));
  if (f) fclose(f);
  return m;
}

static int run_gnuplot(const char *gp) {
  char cmd[600];
  snprintf(cmd, sizeof cmd, "gnuplot '%s' > /dev/null 2>&1", gp);
  return system(cmd);
}

/* Speed chart: H with error bars against wall time (log x), one series per group, the
 * reference band H_ref +- se_ref. */
static void speed_chart(const char *dir, const variant *vs, int nv, const variant *ref) {
  char gp[400], png[400], dat[400];
  snprintf(gp, sizeof gp, "%s/study_speed.gp", dir);
  snprintf(png, sizeof png, "%s/study_speed.png", dir);
  snprintf(dat, sizeof dat, "%s/study_speed.dat", dir);
  FILE *d = fopen(dat, "w");
  if (!d) return;
  static const char *const groups[] = {"reference", "stiffness", "rate", "dt", "die",
                                       "candidate"};
  for (int g = 0; g < 6; g++) {
    fprintf(d, "# %s\n", groups[g]);
    for (int i = 0; i < nv; i++)
      if (strcmp(vs[i].group, groups[g]) == 0 && isfinite(vs[i].H_mean))
        fprintf(d, "%g %g %g \"%s\"\n", vs[i].cpu_s, vs[i].H_mean / 1e3, vs[i].H_se / 1e3,
                vs[i].name);
    /* the reference is part of every one-at-a-time series */
    if (g > 0 && g < 5 && isfinite(ref->H_mean))
      fprintf(d, "%g %g %g \"\"\n", ref->cpu_s, ref->H_mean / 1e3, ref->H_se / 1e3);
    fprintf(d, "\n\n");
  }
  fclose(d);
  FILE *f = fopen(gp, "w");
  if (!f) return;
  fprintf(f,
          "set terminal pngcairo size 900,600 font ',10' noenhanced\nset output '%s'\n"
          "set logscale x\nset xlabel 'CPU time per variant (s, fill to the end of the "
          "indentation; 1 thread)'\n"
          "set ylabel 'plateau hardness H (kPa), mean over h/r window +- SE'\n"
          "set key outside right top\nset grid\n"
          "set title 'Speed vs accuracy: ball indentation (each variant prepares its own bed)'\n"
          "Href=%g; se=%g\n"
          "set object 1 rect from graph 0, first Href-se to graph 1, first Href+se "
          "fc rgb '#dddddd' fs solid 0.6 noborder behind\n"
          "plot '%s' index 1 u 1:2:3 w yerrorbars lw 1.5 pt 7 t 'stiffness scale', \\\n"
          " '' index 1 u 1:2:4 w labels offset 0,1 font ',7' notitle, \\\n"
          " '' index 2 u 1:2:3 w yerrorbars lw 1.5 pt 5 t 'gamma*', \\\n"
          " '' index 2 u 1:2:4 w labels offset 0,1 font ',7' notitle, \\\n"
          " '' index 3 u 1:2:3 w yerrorbars lw 1.5 pt 9 t 'dt factor', \\\n"
          " '' index 3 u 1:2:4 w labels offset 0,-1 font ',7' notitle, \\\n"
          " '' index 4 u 1:2:3 w yerrorbars lw 1.5 pt 11 t 'die diameter', \\\n"
          " '' index 4 u 1:2:4 w labels offset 0,-1 font ',7' notitle, \\\n"
          " '' index 5 u 1:2:3 w yerrorbars lw 2 pt 13 ps 1.5 t 'candidate', \\\n"
          " '' index 0 u 1:2:3 w yerrorbars lw 2 pt 3 ps 2 lc rgb 'black' t 'reference "
          "(band: +- SE)'\n",
          png, ref->H_mean / 1e3, ref->H_se / 1e3, dat);
  fclose(f);
  run_gnuplot(gp);
}

static void stability_chart(const char *dir, const variant *vs, int nv) {
  char gp[400], png[400], dat[400];
  snprintf(gp, sizeof gp, "%s/study_stability.gp", dir);
  snprintf(png, sizeof png, "%s/study_stability.png", dir);
  snprintf(dat, sizeof dat, "%s/study_stability.dat", dir);
  FILE *d = fopen(dat, "w");
  if (!d) return;
  for (int pass = 0; pass < 2; pass++) {
    fprintf(d, "# %s\n", pass ? "rate line" : "grid");
    for (int i = 0; i < nv; i++) {
      const variant *v = &vs[i];
      if ((strcmp(v->group, "rate-line") == 0) != pass) continue;
      fprintf(d, "%g %g %g %d \"%s\" %g %g\n", v->dtf, v->scale, v->gstar,
              category_index(v->category), v->category, v->max_ovl,
              isfinite(v->z) ? v->z : 0.0);
    }
    fprintf(d, "\n\n");
  }
  fclose(d);
  FILE *f = fopen(gp, "w");
  if (!f) return;
  fprintf(f,
          "set terminal pngcairo size 1000,460 font ',10'\nset output '%s'\n"
          "set multiplot layout 1,2\nset grid\nset key off\n"
          "set palette defined (0 '#2ca02c', 1 '#ffbf00', 2 '#ff7f0e', 3 '#9467bd', "
          "4 '#d62728', 5 '#aaaaaa')\nset cbrange [-0.5:5.5]\n"
          "set cbtics ('ok' 0, 'overlap>0.05r' 1, 'biased' 2, 'failed' 3, 'breakdown' 4, "
          "'skipped' 5)\nunset colorbox\n"
          "set logscale xy\nset xlabel 'dt\\_factor'\nset ylabel 'stiffness\\_scale'\n"
          "set xrange [0.1:5]\nset yrange [0.0005:0.3]\n"
          "set title 'gamma* = 0.1: category (label: max overlap / r)'\n"
          "plot '%s' index 0 u 1:2:4 w p pt 5 ps 4 lc palette, \\\n"
          " '' index 0 u 1:2:(sprintf('%%s\\n%%.3f', stringcolumn(5), $6)) w labels "
          "font ',7' offset 0,2.2\n"
          "unset logscale y\nset yrange [-0.5:5.5]\nset xrange [0.05:5]\n"
          "set ytics ('ok' 0, 'overlap>0.05r' 1, 'biased' 2, 'failed' 3, 'breakdown' 4, "
          "'skipped' 5)\n"
          "set xlabel 'gamma*'\nset ylabel ''\n"
          "set title 'rate line (default stiffness, dt): label z vs reference'\n"
          "plot '%s' index 1 u 3:4:4 w p pt 5 ps 4 lc palette, \\\n"
          " '' index 1 u 3:4:(sprintf('z=%%.1f', $7)) w labels font ',7' offset 0,1.5\n"
          "unset multiplot\n",
          png, dat, dat);
  fclose(f);
  run_gnuplot(gp);
}

/* ---- the studies ------------------------------------------------------------------------- */

static void progress_line(const variant *v, int i, int nv, double elapsed) {
  fprintf(stderr,
          "[%2d/%d %6.0fs] %-14s scale %-6g g* %-5g dtf %-5g die %-3g: %-14s n %zu "
          "wall %.1fs H %.4g +- %.3g Pa ovl %.3f\n",
          i + 1, nv, elapsed, v->name, v->scale, v->gstar, v->dtf, v->die, code_name(v->rc),
          v->n, v->wall_s, v->H_mean, v->H_se, v->max_ovl);
}

typedef struct opts {
  int study; /* 0 speed, 1 stability */
  const char *out;
  double budget;
  int threads, json, quick;
  const char *only; /* comma-separated variant names (the reference always runs) */
} opts;

static int listed(const char *list, const char *name) {
  size_t n = strlen(name);
  for (const char *p = list; p && *p; p = strchr(p, ',') ? strchr(p, ',') + 1 : NULL)
    if (strncmp(p, name, n) == 0 && (p[n] == ',' || p[n] == '\0')) return 1;
  return 0;
}

/* Runs vs[0..nv) (vs[iref] first); skips what does not start within the budget. */
static void run_all(variant *vs, int nv, int iref, const opts *o, double t0, double lo) {
  const double deadline = o->budget > 0 ? t0 + 1.25 * o->budget : 0.0;
  for (int k = -1; k < nv; k++) {
    int i = k < 0 ? iref : k;
    if (k >= 0 && i == iref) continue;
    double el = now_wall() - t0;
    if (o->budget > 0 && el > o->budget && i != iref) continue;
    if (o->only && i != iref && !listed(o->only, vs[i].name)) continue;
    run_variant(&vs[i], o->threads, i == iref ? 0.0 : deadline, lo);
    progress_line(&vs[i], i, nv, now_wall() - t0);
  }
}

static json_t *finish(variant *vs, int nv, int iref, const char *study, const opts *o,
                      double t0, double lo) {
  for (int i = 0; i < nv; i++) compare(&vs[i], &vs[iref], vs, nv);
  for (int i = 0; i < nv; i++) categorise(&vs[i]);
  json_t *root = json_object();
  json_object_set_new(root, "study", json_string(study));
  json_object_set_new(root, "machine", machine_json(o->threads));
  json_object_set_new(root, "budget_s", num(o->budget));
  json_object_set_new(root, "wall_total_s", num(now_wall() - t0));
  json_object_set_new(root, "window", json_pack("[f,s]", lo, "h_over_r of the variant"));
  json_object_set_new(root, "z_level", num(Z_LEVEL));
  json_object_set_new(root, "overlap_limit", num(OVERLAP_LIMIT));
  json_object_set_new(root, "own_bed_per_variant", json_true());
  json_object_set_new(root, "reference", json_string(vs[iref].name));
  json_t *arr = json_array();
  for (int i = 0; i < nv; i++) json_array_append_new(arr, variant_json(&vs[i]));
  json_object_set_new(root, "variants", arr);
  return root;
}

static int write_outputs(const char *dir, const char *stem, json_t *root, const variant *vs,
                         int nv) {
  char p[400];
  snprintf(p, sizeof p, "%s/%s.csv", dir, stem);
  if (write_csv(p, vs, nv)) {
    fprintf(stderr, "dem-bench-scene: cannot write %s: %s\n", p, strerror(errno));
    return -1;
  }
  snprintf(p, sizeof p, "%s/%s.json", dir, stem);
  if (json_dump_file(root, p, JSON_INDENT(1) | JSON_REAL_PRECISION(6))) {
    fprintf(stderr, "dem-bench-scene: cannot write %s\n", p);
    return -1;
  }
  return 0;
}

/* The cheapest passing value per group (by wall time) and the candidate built from them. */
static json_t *speed_conclusion(const variant *vs, int nv, const variant *ref, variant *cand) {
  json_t *c = json_object();
  static const char *const groups[] = {"stiffness", "rate", "dt", "die"};
  *cand = *ref;
  snprintf(cand->name, sizeof cand->name, "candidate");
  cand->group = "candidate";
  for (int g = 0; g < 4; g++) {
    const variant *best = ref;
    for (int i = 0; i < nv; i++) {
      const variant *v = &vs[i];
      if (strcmp(v->group, groups[g]) || !v->ran || v->rc || !v->within || v->pair) continue;
      if (v->cpu_s < best->cpu_s) best = v; /* CPU: the wall clock of a shared machine
                                              varies with the other jobs */
    }
    json_object_set_new(c, groups[g], json_string(best->name));
    if (g == 0) cand->scale = best->scale;
    if (g == 1) cand->gstar = best->gstar;
    if (g == 2) cand->dtf = best->dtf;
    if (g == 3) cand->die = best->die;
  }
  return c;
}

static int study_speed(const opts *o) {
  variant vs[MAXV];
  int nv = 0;
  const double lo = 0.1;
  /* the small scene: die 10 d, bed 6 d, sphere 6 d, h/r 0.3 (docs/validation-study.md) */
  double die = 10, bed = 6, ind = 6, hr = 0.3;
  /* the reference: x0.1 stiffness at gamma* 0.05, the thesis' dt factor 0.2 */
  double s_ref = 0.1, g_ref = 0.05, dt_ref = 0.2;
  if (o->quick) die = 6, bed = 4, ind = 3, hr = 0.3, s_ref = 0.01, g_ref = 0.5, dt_ref = 0.4;
  set_v(&vs[nv++], "reference", "reference", s_ref, g_ref, dt_ref, die, bed, ind, hr);
  if (o->quick) {
    set_v(&vs[nv++], "scale0.003", "stiffness", 0.003, g_ref, dt_ref, die, bed, ind, hr);
  } else {
    /* in order of importance: the budget skips the tail */
    set_v(&vs[nv++], "scale0.01", "stiffness", 0.01, g_ref, dt_ref, die, bed, ind, hr);
    set_v(&vs[nv++], "scale0.003", "stiffness", 0.003, g_ref, dt_ref, die, bed, ind, hr);
    set_v(&vs[nv++], "g*0.1", "rate", s_ref, 0.1, dt_ref, die, bed, ind, hr);
    set_v(&vs[nv++], "g*0.2", "rate", s_ref, 0.2, dt_ref, die, bed, ind, hr);
    set_v(&vs[nv++], "g*0.5", "rate", s_ref, 0.5, dt_ref, die, bed, ind, hr);
    set_v(&vs[nv++], "dtf0.4", "dt", s_ref, g_ref, 0.4, die, bed, ind, hr);
    set_v(&vs[nv++], "dtf0.8", "dt", s_ref, g_ref, 0.8, die, bed, ind, hr);
    set_v(&vs[nv++], "die8", "die", s_ref, g_ref, dt_ref, 8, bed, ind, hr);
    /* the combination the one-at-a-time results suggest for the harness (docs) */
    set_v(&vs[nv++], "combo_s0.01_g*0.1_dtf0.4", "candidate", 0.01, 0.1, 0.4, die, bed, ind,
          hr);
    /* dem-validate's own default scene (x0.01, gamma* 0.1, dt 0.2, validate/cases.c): its
       parts agreed one at a time, the combination itself must be measured */
    set_v(&vs[nv++], "default_s0.01_g*0.1", "candidate", 0.01, 0.1, dt_ref, die, bed, ind, hr);
    /* the tables' stiffness: x1 against x0.1 at gamma* 0.2 (cheap) and at the reference's
       gamma* 0.05 (~3x the reference's steps), so that a stiffness x rate interaction can
       be told from a stiffness bias */
    set_v(&vs[nv], "scale1_g*0.2", "stiffness", 1.0, 0.2, dt_ref, die, bed, ind, hr);
    vs[nv++].pair = "g*0.2";
    set_v(&vs[nv++], "scale1", "stiffness", 1.0, g_ref, dt_ref, die, bed, ind, hr);
    set_v(&vs[nv++], "die12", "die", s_ref, g_ref, dt_ref, 12, bed, ind, hr);
    set_v(&vs[nv++], "dtf0.1", "dt", s_ref, g_ref, 0.1, die, bed, ind, hr);
  }
  double t0 = now_wall();
  run_all(vs, nv, 0, o, t0, lo);
  for (int i = 0; i < nv; i++) compare(&vs[i], &vs[0], vs, nv);
  variant cand;
  json_t *concl = speed_conclusion(vs, nv, &vs[0], &cand);
  int same_as_ref = cand.scale == vs[0].scale && cand.gstar == vs[0].gstar &&
                    cand.dtf == vs[0].dtf && cand.die == vs[0].die;
  if (!o->quick && !same_as_ref && nv < MAXV &&
      (o->budget <= 0 || now_wall() - t0 <= o->budget)) {
    vs[nv] = cand;
    run_variant(&vs[nv], o->threads, o->budget > 0 ? t0 + 1.25 * o->budget : 0.0, lo);
    progress_line(&vs[nv], nv, nv + 1, now_wall() - t0);
    nv++;
  }
  json_t *root = finish(vs, nv, 0, "speed", o, t0, lo);
  json_object_set_new(concl, "candidate_run", json_boolean(strcmp(vs[nv - 1].group,
                                                                  "candidate") == 0));
  if (strcmp(vs[nv - 1].group, "candidate") == 0) {
    json_object_set_new(concl, "candidate_within", json_boolean(vs[nv - 1].within));
    json_object_set_new(concl, "candidate_z", num(vs[nv - 1].z));
    json_object_set_new(concl, "candidate_speedup_cpu", num(vs[0].cpu_s / vs[nv - 1].cpu_s));
  }
  json_object_set_new(root, "conclusion", concl);
  int rc = write_outputs(o->out, "study_speed", root, vs, nv);
  if (!rc && !o->quick) speed_chart(o->out, vs, nv, &vs[0]);
  if (o->json) json_dumpf(root, stdout, JSON_INDENT(1) | JSON_REAL_PRECISION(6)), puts("");
  json_decref(root);
  if (rc) return EXIT_RUN_;
  return vs[0].rc || !isfinite(vs[0].H_mean) ? EXIT_RUN_ : EXIT_OK_;
}

static int study_stability(const opts *o) {
  variant vs[MAXV];
  int nv = 0;
  const double lo = 0.1;
  double die = 8, bed = 5, ind = 4, hr = 0.3;
  static const double dts[] = {0.2, 0.5, 1.0, 2.0, 3.0};
  static const double scales[] = {0.001, 0.01, 0.1};
  static const double rates[] = {0.5, 1.0, 2.0, 3.0};
  const double g_grid = 0.1;
  char name[48];
  /* the grid's most faithful point first: the comparison reference */
  if (o->quick) {
    die = 6, bed = 4, ind = 3;
    set_v(&vs[nv++], "s0.01_dtf0.4", "grid", 0.01, 0.5, 0.4, die, bed, ind, hr);
    set_v(&vs[nv++], "s0.001_dtf0.4", "grid", 0.001, 0.5, 0.4, die, bed, ind, hr);
  } else {
    set_v(&vs[nv++], "s0.1_dtf0.2", "grid", 0.1, g_grid, 0.2, die, bed, ind, hr);
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 5; b++) {
        if (a == 2 && b == 0) continue;
        snprintf(name, sizeof name, "s%g_dtf%g", scales[a], dts[b]);
        set_v(&vs[nv++], name, "grid", scales[a], g_grid, dts[b], die, bed, ind, hr);
      }
    for (int r = 0; r < 4; r++) {
      snprintf(name, sizeof name, "rate_g*%g", rates[r]);
      set_v(&vs[nv++], name, "rate-line", 0.01, rates[r], 0.2, die, bed, ind, hr);
    }
  }
  double t0 = now_wall();
  run_all(vs, nv, 0, o, t0, lo);
  json_t *root = finish(vs, nv, 0, "stability", o, t0, lo);
  int rc = write_outputs(o->out, "study_stability", root, vs, nv);
  if (!rc && !o->quick) stability_chart(o->out, vs, nv);
  if (o->json) json_dumpf(root, stdout, JSON_INDENT(1) | JSON_REAL_PRECISION(6)), puts("");
  json_decref(root);
  if (rc) return EXIT_RUN_;
  return vs[0].rc || !isfinite(vs[0].H_mean) ? EXIT_RUN_ : EXIT_OK_;
}

/* Replicate beds (fill seeds) at the tables' stiffness (x1), the speed study's reference
 * (x0.1) and x0.01, on the speed scene: the bed-to-bed spread of the plateau mean against
 * the within-run standard error, and the stiffness effect judged from the spread of
 * replicates (dem_replicates_mean, dem_compare_means_t with k - 1 degrees of freedom). Every
 * group starts at seed 1, so the study stands on its own (seed 1 of x0.1 and x1 repeat the
 * speed study's `reference` and `scale1`, bit-identical on one thread). */
#define NSCALE_ 3
static int study_replicates(const opts *o) {
  variant vs[MAXV];
  int nv = 0;
  const double lo = 0.1;
  double die = 10, bed = 6, ind = 6, hr = 0.3, g = 0.05, dtf = 0.2;
  /* beds per group, cheapest group first (the budget skips the tail): x0.01, x0.1, x1 */
  static const double scales[NSCALE_] = {0.01, 0.1, 1.0};
  static const char *const gname[NSCALE_] = {"x0.01", "x0.1", "x1"};
  int kbeds[NSCALE_] = {5, 5, 5};
  if (o->quick) die = 6, bed = 4, ind = 3, g = 0.5, dtf = 0.4, kbeds[0] = kbeds[1] = 2,
                kbeds[2] = 0;
  char name[48];
  for (int a = 0; a < NSCALE_; a++)
    for (int k = 1; k <= kbeds[a]; k++) {
      snprintf(name, sizeof name, "s%g_seed%d", scales[a], k);
      set_v(&vs[nv], name, gname[a], scales[a], g, dtf, die, bed, ind, hr);
      vs[nv++].seed = (unsigned long)k;
    }
  double t0 = now_wall();
  run_all(vs, nv, 0, o, t0, lo);
  json_t *root = finish(vs, nv, 0, "replicates", o, t0, lo);
  json_t *grp = json_object();
  double m[NSCALE_], se[NSCALE_], nu[NSCALE_];
  for (int a = 0; a < NSCALE_; a++) {
    double means[MAXV], wse = 0.0;
    size_t k = 0;
    m[a] = se[a] = NAN, nu[a] = 1.0;
    for (int i = 0; i < nv; i++)
      if (vs[i].scale == scales[a] && vs[i].ran && !vs[i].rc && isfinite(vs[i].H_mean)) {
        means[k++] = vs[i].H_mean;
        wse += vs[i].H_se * vs[i].H_se;
      }
    json_t *gj = json_object();
    json_object_set_new(gj, "stiffness_scale", num(scales[a]));
    json_object_set_new(gj, "beds", json_integer((json_int_t)k));
    dem_err e;
    if (k >= 2 && dem_replicates_mean(k, means, &m[a], &se[a], &e) == DEM_OK) {
      nu[a] = (double)k - 1.0;
      json_object_set_new(gj, "H_mean", num(m[a]));
      json_object_set_new(gj, "H_se_replicates", num(se[a]));
      json_object_set_new(gj, "H_sd_between_beds", num(se[a] * sqrt((double)k)));
      json_object_set_new(gj, "H_se_within_rms", num(sqrt(wse / (double)k)));
    }
    json_object_set_new(grp, gname[a], gj);
  }
  /* each scaled group against the tables' stiffness and x0.01 against x0.1 (Welch t) */
  static const int pairs[3][2] = {{0, 1}, {1, 2}, {0, 2}};
  for (int p = 0; p < 3; p++) {
    int i = pairs[p][0], j = pairs[p][1];
    dem_comparison cmp;
    dem_err e;
    if (!isfinite(m[i]) || !isfinite(m[j]) ||
        dem_compare_means_t(m[i], se[i], nu[i], m[j], se[j], nu[j], 0.05, DEM_TEST_TWO_SIDED,
                            &cmp, &e) != DEM_OK)
      continue;
    json_t *c = json_object();
    json_object_set_new(c, "diff", num(cmp.diff));
    json_object_set_new(c, "se", num(cmp.se));
    json_object_set_new(c, "t", num(cmp.z));
    json_object_set_new(c, "t_crit", num(cmp.z_crit));
    json_object_set_new(c, "p", num(cmp.p));
    json_object_set_new(c, "different", json_boolean(cmp.different));
    char key[32];
    snprintf(key, sizeof key, "%s_vs_%s", gname[i], gname[j]);
    json_object_set_new(grp, key, c);
  }
  json_object_set_new(root, "groups", grp);
  int rc = write_outputs(o->out, "study_replicates", root, vs, nv);
  if (o->json) json_dumpf(root, stdout, JSON_INDENT(1) | JSON_REAL_PRECISION(6)), puts("");
  json_decref(root);
  if (rc) return EXIT_RUN_;
  return vs[0].rc || !isfinite(vs[0].H_mean) ? EXIT_RUN_ : EXIT_OK_;
}

static void usage(FILE *f) {
  fprintf(f,
          "usage: dem-bench-scene --study speed|stability|replicates [--out DIR]\n"
          "                       [--budget SECONDS]\n"
          "                       [--threads N] [--json] [--quick] [--only NAME,...]\n"
          "  Speed-versus-accuracy study or stability map of the ball-indentation scene\n"
          "  (docs/validation-study.md). Writes DIR/study_<study>.{csv,json,gp,png}\n"
          "  (default DIR bench-out); --json also prints the JSON summary on stdout;\n"
          "  --budget: variants not started within SECONDS are skipped (default 1200);\n"
          "  --quick: 2 tiny variants (smoke test, seconds);\n"
          "  --only: run the reference and the named variants only (names: see the CSV).\n");
}

int main(int argc, char **argv) {
  opts o = {-1, "bench-out", 1200.0, 1, 0, 0, NULL};
  static const struct option lo[] = {{"study", required_argument, 0, 's'},
                                     {"out", required_argument, 0, 'o'},
                                     {"budget", required_argument, 0, 'b'},
                                     {"threads", required_argument, 0, 't'},
                                     {"json", no_argument, 0, 'j'},
                                     {"quick", no_argument, 0, 'q'},
                                     {"only", required_argument, 0, 'n'},
                                     {"help", no_argument, 0, 'h'},
                                     {0, 0, 0, 0}};
  int ch;
  char *end;
  opterr = 0;
  while ((ch = getopt_long(argc, argv, "", lo, NULL)) != -1) {
    switch (ch) {
      case 's':
        if (strcmp(optarg, "speed") == 0) o.study = 0;
        else if (strcmp(optarg, "stability") == 0) o.study = 1;
        else if (strcmp(optarg, "replicates") == 0) o.study = 2;
        else {
          fprintf(stderr,
                  "dem-bench-scene: --study = '%s' (allowed: speed, stability, replicates)\n",
                  optarg);
          return EXIT_USAGE_;
        }
        break;
      case 'o': o.out = optarg; break;
      case 'b':
        o.budget = strtod(optarg, &end);
        if (*end || !(o.budget >= 0 && o.budget <= 1e6)) {
          fprintf(stderr, "dem-bench-scene: --budget = '%s' s (allowed [0, 1e6]; 0: none)\n",
                  optarg);
          return EXIT_USAGE_;
        }
        break;
      case 't':
        o.threads = (int)strtol(optarg, &end, 10);
        if (*end || o.threads < 1 || o.threads > 256) {
          fprintf(stderr, "dem-bench-scene: --threads = '%s' (allowed [1, 256])\n", optarg);
          return EXIT_USAGE_;
        }
        break;
      case 'j': o.json = 1; break;
      case 'q': o.quick = g_quick = 1; break;
      case 'n': o.only = optarg; break;
      case 'h': usage(stdout); return EXIT_OK_;
      default:
        fprintf(stderr, "dem-bench-scene: unknown option or missing value: %s\n",
                argv[optind - 1]);
        usage(stderr);
        return EXIT_USAGE_;
    }
  }
  if (optind < argc) {
    fprintf(stderr, "dem-bench-scene: unexpected operand '%s'\n", argv[optind]);
    return EXIT_USAGE_;
  }
  if (o.study < 0) {
    fprintf(stderr, "dem-bench-scene: --study speed|stability is required\n");
    usage(stderr);
    return EXIT_USAGE_;
  }
  dem_err err = {0};
  if (dem_mkdirs(o.out, &err)) {
    fprintf(stderr, "dem-bench-scene: --out %s: %s\n", o.out, err.msg);
    return EXIT_RUN_;
  }
  return o.study == 0 ? study_speed(&o) : o.study == 1 ? study_stability(&o)
                                                      : study_replicates(&o);
}
