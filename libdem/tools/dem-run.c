/* dem-run — the ball-indentation scene from one libconfig file (docs/scene.md).
 *
 *   dem-run CONFIG [--out DIR] [--threads N] [--restart CHECKPOINT]
 *
 * Writes DIR/series.h5 and DIR/series.csv (time series), DIR/snap_*.h5 + DIR/snapshots.xmf
 * (particle snapshots every output.snapshot_interval s of simulated time), a progress
 * line on stderr (\r on a terminal, one line per update otherwise), and a scene checkpoint
 * DIR/checkpoint_<stage>.h5 at the end of every stage (filled, settled, consolidated,
 * unloaded, indented). --restart continues from a scene checkpoint; the config file's
 * indentation fields, indenter coefficients, threads and sampling override the stored
 * ones (dem_scene_restore). SIGINT/SIGTERM stop at the next step boundary and write
 * DIR/checkpoint_interrupted.h5. Exit 0 ok, 2 usage or configuration error (file:line:
 * field = value (allowed ...)) or an unusable --restart file, 1 run failure (a breakdown
 * also writes DIR/checkpoint_broken.h5 and names the last good checkpoint), 130 / 143
 * interrupted by SIGINT / SIGTERM (state saved).
 */
#include <errno.h>
#include <libconfig.h>
#include <math.h>
#include <signal.h>
#include <time.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli_common.h"
#include "dem/checkpoint.h"
#include "dem/scene.h"
#include "dem/table.h"

static const char *prog = "dem-run";

typedef struct out_state {
  const char *dir;
  int count, cap;
  double *times;
  size_t *n;
  int tty;
} out_state;

static int snap(dem_sim *s, const char *stage, double t, void *user, dem_err *err) {
  out_state *o = user;
  if (o->count == o->cap) {
    int c = o->cap ? 2 * o->cap : 64;
    double *tt = realloc(o->times, (size_t)c * sizeof *tt);
    if (tt) o->times = tt;
    size_t *nn = realloc(o->n, (size_t)c * sizeof *nn);
    if (nn) o->n = nn;
    if (!tt || !nn) return dem_err_set(err, DEM_ENOMEM, "snapshots: out of memory");
    o->cap = c;
  }
  int rc = dem_scene_write_snapshot(s, o->dir, o->count, t, stage, err);
  if (rc) return rc;
  o->times[o->count] = t;
  o->n[o->count] = dem_sim_particles(s)->n;
  o->count++;
  return dem_scene_write_xdmf(o->dir, o->count, o->times, o->n, err);
}

static void progress(const char *stage, double t, double frac, double eta, void *user) {
  out_state *o = user;
  char f[32] = "", e[32] = "";
  if (frac >= 0) snprintf(f, sizeof f, " %5.1f%%", 100.0 * frac);
  if (eta >= 0) snprintf(e, sizeof e, " ETA %.0f s", eta);
  fprintf(stderr, "%s%-11s t = %.5f s%s%s%s", o->tty ? "\r" : "", stage, t, f, e,
          o->tty ? "    " : "\n");
  fflush(stderr);
}

/* libconfig lookups with messages naming file:line, field, value, range. */
typedef struct cfgctx {
  const char *file;
  dem_err *err;
} cfgctx;

static int num(cfgctx *cx, config_setting_t *g, const char *key, double lo, double hi,
               const char *unit, double *out) {
  config_setting_t *s = g ? config_setting_get_member(g, key) : NULL;
  if (!s) return DEM_OK;
  const char *path = config_setting_name(g) ? config_setting_name(g) : "";
  int t = config_setting_type(s);
  if (t != CONFIG_TYPE_FLOAT && t != CONFIG_TYPE_INT && t != CONFIG_TYPE_INT64 &&
      t != CONFIG_TYPE_BOOL)
    return dem_err_set(cx->err, DEM_EINVAL, "%s:%d: %s%s%s is not a number", cx->file,
                       config_setting_source_line(s), path, *path ? "." : "", key);
  double v = t == CONFIG_TYPE_FLOAT ? config_setting_get_float(s)
             : t == CONFIG_TYPE_BOOL ? (double)config_setting_get_bool(s)
                                     : (double)config_setting_get_int64(s);
  if (!(v >= lo && v <= hi))
    return dem_err_set(cx->err, DEM_ERANGE, "%s:%d: %s%s%s = %g %s (allowed [%g, %g])",
                       cx->file, config_setting_source_line(s), path, *path ? "." : "", key, v,
                       unit, lo, hi);
  *out = v;
  return DEM_OK;
}

static int word(cfgctx *cx, config_setting_t *g, const char *key, const char *const *words,
                int *out) {
  config_setting_t *s = g ? config_setting_get_member(g, key) : NULL;
  if (!s) return DEM_OK;
  const char *v = config_setting_get_string(s);
  for (int k = 0; v && words[k]; k++)
    if (!strcmp(v, words[k])) {
      *out = k;
      return DEM_OK;
    }
  char allowed[256] = "";
  for (int k = 0; words[k]; k++) {
    strncat(allowed, k ? ", " : "", sizeof allowed - strlen(allowed) - 1);
    strncat(allowed, words[k], sizeof allowed - strlen(allowed) - 1);
  }
  return dem_err_set(cx->err, DEM_EINVAL, "%s:%d: %s = \"%s\" (allowed: %s)", cx->file,
                     config_setting_source_line(s), key, v ? v : "(not a string)", allowed);
}

/* A group of law coefficients (physics-notes keys) into a parameter set. */
static int coeffs(cfgctx *cx, config_setting_t *g, dem_params *ps) {
  if (!g) return DEM_OK;
  for (int k = 0; k < config_setting_length(g); k++) {
    config_setting_t *s = config_setting_get_elem(g, (unsigned)k);
    int t = config_setting_type(s);
    char origin[DEM_ORIGIN_LEN];
    snprintf(origin, sizeof origin, "%s:%d", cx->file, config_setting_source_line(s));
    if (t != CONFIG_TYPE_FLOAT && t != CONFIG_TYPE_INT && t != CONFIG_TYPE_INT64)
      return dem_err_set(cx->err, DEM_EINVAL, "%s: %s.%s is not a number", origin,
                         config_setting_name(g), config_setting_name(s));
    double v = t == CONFIG_TYPE_FLOAT ? config_setting_get_float(s)
                                      : (double)config_setting_get_int64(s);
    int rc = dem_params_set(ps, config_setting_name(s), v, origin, cx->err);
    if (rc) return rc;
  }
  return DEM_OK;
}

static int load(const char *file, dem_scene_config *c, double *snap_dt, dem_err *err) {
  config_t cf;
  config_init(&cf);
  int rc = DEM_OK;
  if (!config_read_file(&cf, file)) {
    rc = dem_err_set(err, DEM_EINVAL, "%s:%d: %s", config_error_file(&cf) ? config_error_file(&cf) : file,
                     config_error_line(&cf), config_error_text(&cf));
    config_destroy(&cf);
    return rc;
  }
  cfgctx cx = {file, err};
  config_setting_t *root = config_root_setting(&cf);
  int m = 0;
  if ((rc = word(&cx, root, "materials", dem_scene_materials_names, &m))) goto out;
  dem_scene_config_defaults(c, (dem_scene_materials)m);
  config_setting_t *bed = config_setting_get_member(root, "bed");
  config_setting_t *st = config_setting_get_member(root, "settle");
  config_setting_t *co = config_setting_get_member(root, "consolidate");
  config_setting_t *in = config_setting_get_member(root, "indent");
  config_setting_t *nu = config_setting_get_member(root, "numerics");
  config_setting_t *ou = config_setting_get_member(root, "output");
  static const char *const psds[] = {"table6.1", "table5.1", NULL};
  static const char *const shapes[] = {"sphere", "cylinder", "cube", NULL};
  int psd = (int)c->psd, shape = 0;
  double seed = (double)c->seed, np = 0, unload = 0, thr = 1, ostress = c->output_stress;
  if ((rc = word(&cx, bed, "psd", psds, &psd)) ||
      (rc = num(&cx, bed, "d_mean", 1e-7, 1.0, "m", &c->d_mean)) ||
      (rc = num(&cx, bed, "die_diameter", 3, 1000, "d", &c->die_diameter)) ||
      (rc = num(&cx, bed, "bed_height", 1, 1000, "d", &c->bed_height)) ||
      (rc = num(&cx, bed, "phi_est", 0.05, 0.74, "-", &c->phi_est)) ||
      (rc = num(&cx, bed, "n_particles", 0, 1e8, "", &np)) ||
      (rc = num(&cx, bed, "fill_fraction", 0.01, 0.38, "-", &c->fill_fraction)) ||
      (rc = num(&cx, bed, "seed", 0, 4294967295.0, "", &seed)) ||
      (rc = num(&cx, bed, "rho", 1, 1e5, "kg/m^3", &c->rho)) ||
      (rc = num(&cx, st, "ke_per_particle", 1e-12, 1, "x m g d", &c->settle_ke)) ||
      (rc = num(&cx, st, "min_time", 0, 100, "s", &c->settle_min_time)) ||
      (rc = num(&cx, st, "max_time", 0, 100, "s", &c->settle_max_time)) ||
      (rc = num(&cx, co, "stress", 1, 1e9, "Pa", &c->sigma_pre)) ||
      (rc = num(&cx, co, "strain_rate", 1e-4, 1e4, "1/s", &c->strain_rate)) ||
      (rc = num(&cx, co, "servo_band", 1e-3, 1, "-", &c->servo_band)) ||
      (rc = num(&cx, co, "servo_steps", 2, 1e6, "steps", &c->servo_steps)) ||
      (rc = num(&cx, co, "hold_time", 0, 100, "s", &c->hold_time)) ||
      (rc = num(&cx, co, "hold_tol", 1e-4, 0.5, "-", &c->hold_tol)) ||
      (rc = word(&cx, in, "shape", shapes, &shape)) ||
      (rc = num(&cx, in, "diameter", 0.5, 1000, "d", &c->indenter_diameter)) ||
      (rc = num(&cx, in, "length", 0, 1000, "d", &c->indenter_length)) ||
      (rc = num(&cx, in, "strain_rate", 0, 1e4, "1/s", &c->indent_rate)) ||
      (rc = num(&cx, in, "h_over_r", 0.01, 2, "-", &c->h_over_r)) ||
      (rc = num(&cx, in, "unload", 0, 1, "", &unload)) ||
      (rc = num(&cx, nu, "dt_factor", 1e-4, 1, "-", &c->dt_factor)) ||
      (rc = num(&cx, nu, "stiffness_scale", 1e-6, 1, "-", &c->stiffness_scale)) ||
      (rc = num(&cx, nu, "skin", 0, 2, "d", &c->skin)) ||
      (rc = num(&cx, nu, "threads", 1, 64, "", &thr)) ||
      (rc = num(&cx, ou, "sample_interval", 0, 10, "s", &c->sample_interval)) ||
      (rc = num(&cx, ou, "snapshot_interval", 0, 1e3, "s", snap_dt)) ||
      (rc = num(&cx, ou, "stress", 0, 1, "(true/false)", &ostress)) ||
      (rc = coeffs(&cx, config_setting_get_member(root, "particle"), &c->pp)) ||
      (rc = coeffs(&cx, config_setting_get_member(root, "wall"), &c->pw)) ||
      (rc = coeffs(&cx, config_setting_get_member(root, "indenter"), &c->pi)))
    goto out;
  c->psd = (dem_scene_psd)psd;
  c->shape = (dem_indenter_shape)shape;
  c->seed = (unsigned long)seed;
  c->n_particles = (long)np;
  c->unload = unload != 0;
  c->threads = (int)thr;
  c->output_stress = ostress != 0;
out:
  config_destroy(&cf);
  return rc;
}

static void usage(FILE *f) {
  fprintf(f, "usage: %s CONFIG [--out DIR] [--threads N] [--restart CHECKPOINT]\n"
             "  Runs fill, settle, consolidate, unload, indent (docs/scene.md), writing\n"
             "  DIR/checkpoint_<stage>.h5 after each stage. --restart continues from a\n"
             "  checkpoint (the config's indentation fields apply to a bed not yet indented).\n"
             "  SIGINT/SIGTERM write DIR/checkpoint_interrupted.h5 (exit 130/143).\n", prog);
}

/* SIGINT/SIGTERM: the engine's interrupt flag (polled once per step); a second signal more
 * than a second after the first gets the default action (kills). Within that second it is
 * taken as the same request: `timeout`, batch schedulers and a terminal deliver one request
 * to the process and again to its process group, which used to kill the run before it could
 * write its checkpoint (CTest cli_dem-run_sigterm failed so, now and then, under load). */
static volatile sig_atomic_t intr_flag = 0, intr_sig = 0;
static struct timespec intr_t0;
static void on_signal(int sig) {
  struct timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now); /* async-signal-safe (POSIX) */
  if (!intr_flag) {
    intr_t0 = now;
    intr_sig = sig;
    intr_flag = 1;
    return;
  }
  double dt = (double)(now.tv_sec - intr_t0.tv_sec) +
              1e-9 * (double)(now.tv_nsec - intr_t0.tv_nsec);
  if (dt > 1.0) {
    signal(sig, SIG_DFL);
    raise(sig);
  }
}

/* A restart into a directory with snapshots: keep the index entries up to the restored
 * time t (snapshots.xmf, written by dem_scene_write_xdmf), so that numbering continues and
 * the index covers the whole run. */
static void snapshots_resume(out_state *o, double t) {
  char path[1024], line[512];
  snprintf(path, sizeof path, "%s/snapshots.xmf", o->dir);
  FILE *f = fopen(path, "r");
  if (!f) return;
  double tk = NAN;
  while (fgets(line, sizeof line, f)) {
    const char *a = strstr(line, "<Time Value=\""), *b = strstr(line, "NumberOfElements=\"");
    if (a) tk = strtod(a + 13, NULL);
    if (b && !isnan(tk)) {
      if (!(tk <= t)) break;
      if (o->count == o->cap) {
        int c = o->cap ? 2 * o->cap : 64;
        double *tt = realloc(o->times, (size_t)c * sizeof *tt);
        if (tt) o->times = tt;
        size_t *nn = realloc(o->n, (size_t)c * sizeof *nn);
        if (nn) o->n = nn;
        if (!tt || !nn) break;
        o->cap = c;
      }
      o->times[o->count] = tk;
      o->n[o->count] = (size_t)strtoul(b + 18, NULL, 10);
      o->count++;
      tk = NAN;
    }
  }
  fclose(f);
}

static const char *const ck_names[] = {"filled", "settled", "consolidated", "unloaded",
                                       "indented"};

int main(int argc, char **argv) {
  const char *cfgfile = NULL, *dir = ".", *restart = NULL;
  int threads = 0;
  dem_err err;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help")) {
      usage(stdout);
      return CLI_EXIT_OK;
    } else if (!strcmp(argv[i], "--version")) {
      cli_print_version(prog);
      return CLI_EXIT_OK;
    } else if (!strcmp(argv[i], "--out") && i + 1 < argc) {
      dir = argv[++i];
    } else if (!strcmp(argv[i], "--restart") && i + 1 < argc) {
      restart = argv[++i];
    } else if (!strcmp(argv[i], "--threads") && i + 1 < argc) {
      double t;
      if (cli_parse_double("--threads", argv[++i], 1, 64, &t, &err)) {
        cli_error(prog, &err);
        return CLI_EXIT_USAGE;
      }
      threads = (int)t;
    } else if (argv[i][0] != '-' && !cfgfile) {
      cfgfile = argv[i];
    } else {
      usage(stderr);
      return CLI_EXIT_USAGE;
    }
  }
  if (!cfgfile) {
    usage(stderr);
    return CLI_EXIT_USAGE;
  }
  dem_scene_config c;
  double snap_dt = 0.0;
  if (load(cfgfile, &c, &snap_dt, &err) || dem_scene_config_check(&c, &err)) {
    cli_error(prog, &err);
    return CLI_EXIT_USAGE;
  }
  if (threads > 0) c.threads = threads;
  cli_warn_contention(prog, c.threads);
  if (dem_mkdirs(dir, &err)) {
    cli_error(prog, &err);
    return CLI_EXIT_RUN;
  }
  out_state o = {dir, 0, 0, NULL, NULL, isatty(2)};
  dem_scene_hooks h = {progress, o.tty ? 0.5 : 10.0, snap, snap_dt, &o};
  dem_scene *sc = restart ? dem_scene_restore(restart, &c, &h, &err)
                          : dem_scene_create(&c, &h, &err);
  if (!sc) {
    cli_error(prog, &err);
    if (restart)
      fprintf(stderr, "%s: --restart needs a checkpoint written by dem-run "
                      "(DIR/checkpoint_<stage>.h5) and the config it was run with\n", prog);
    return CLI_EXIT_USAGE;
  }
  char last_ck[1024] = "", path[1024];
  if (restart) {
    dem_sim_stats st;
    dem_sim_get_stats(dem_scene_sim(sc), &st);
    snapshots_resume(&o, st.time);
    int k = (int)dem_scene_get_stage(sc);
    fprintf(stderr, "%s: restarted from %s: stage %s completed, t = %.6g s\n", prog, restart,
            k >= 0 ? ck_names[k] : "(none)", st.time);
    snprintf(last_ck, sizeof last_ck, "%s", restart);
  }
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
  dem_sim_set_interrupt_flag(dem_scene_sim(sc), &intr_flag);
  int (*const stage_fn[])(dem_scene *, dem_err *) = {dem_scene_fill, dem_scene_settle,
                                                     dem_scene_consolidate, dem_scene_unload,
                                                     dem_scene_indent};
  int rc = DEM_OK;
  for (int k = 0; k < 5 && !rc; k++) {
    if ((int)dem_scene_get_stage(sc) >= k) continue;
    if ((rc = stage_fn[k](sc, &err))) break;
    snprintf(path, sizeof path, "%s/checkpoint_%s.h5", dir, ck_names[k]);
    if ((rc = dem_scene_save(sc, path, &err))) break;
    snprintf(last_ck, sizeof last_ck, "%s", path);
  }
  if (o.tty) fputc('\n', stderr);
  int status = rc ? CLI_EXIT_RUN : CLI_EXIT_OK;
  dem_err e2;
  if (rc == DEM_EINTERRUPTED) {
    /* a clean step boundary: save and say how to go on */
    int sig = intr_sig ? (int)intr_sig : SIGINT;
    status = 128 + sig;
    snprintf(path, sizeof path, "%s/checkpoint_interrupted.h5", dir);
    if (dem_scene_save(sc, path, &e2)) {
      cli_error(prog, &e2);
      status = CLI_EXIT_RUN;
    } else {
      fprintf(stderr, "%s: interrupted by %s; state saved to %s\n%s: resume with: %s %s --out "
                      "%s --restart %s\n",
              prog, sig == SIGTERM ? "SIGTERM" : "SIGINT", path, prog, prog, cfgfile, dir,
              path);
    }
  } else if (rc == DEM_ENONFINITE || rc == DEM_EUNSTABLE || rc == DEM_ERUNAWAY) {
    /* the state in memory is broken: keep it for diagnosis, point to the last good one */
    cli_error(prog, &err);
    snprintf(path, sizeof path, "%s/checkpoint_broken.h5", dir);
    if (dem_scene_save(sc, path, &e2) == DEM_OK)
      fprintf(stderr, "%s: the broken state is in %s (for diagnosis only)\n", prog, path);
    if (*last_ck)
      fprintf(stderr, "%s: the last good checkpoint is %s: restart with %s %s --out %s "
                      "--restart %s\n",
              prog, last_ck, prog, cfgfile, dir, last_ck);
    else
      fprintf(stderr, "%s: no stage was completed: no checkpoint to restart from\n", prog);
  } else if (rc) {
    cli_error(prog, &err);
    if (*last_ck) fprintf(stderr, "%s: the last checkpoint is %s\n", prog, last_ck);
  }
  snprintf(path, sizeof path, "%s/series.h5", dir);
  int wr = dem_table_write(dem_scene_series(sc), path, &e2);
  snprintf(path, sizeof path, "%s/series.csv", dir);
  if (!wr) wr = dem_table_write(dem_scene_series(sc), path, &e2);
  dem_scene_info in;
  dem_scene_get_info(sc, &in);
  if (!rc) {
    /* the peak overlap covers this invocation (since creation or --restart): for a
     * restarted indentation, the bed's own overlaps and the indentation's */
    dem_sim_stats st;
    dem_sim_get_stats(dem_scene_sim(sc), &st);
    printf("particles %zu, dt %.3g s, bed after unloading %.4g m (phi %.3f), surface %.4g m, "
           "depth %.4g m, indenter force %.4g N, peak overlap %.4f of the smaller radius\n",
           in.n, in.dt, in.bed_top, in.phi, in.surface, in.depth, in.indenter_force,
           st.peak_overlap_frac);
  }
  dem_scene_free(sc);
  free(o.times);
  free(o.n);
  if (wr) {
    cli_error(prog, &e2);
    if (!status) status = CLI_EXIT_RUN;
  }
  return status;
}
