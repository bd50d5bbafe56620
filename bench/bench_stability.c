/* dem-bench-stability: time-step stability of the plastic and adhesive laws in a normal
 * impact (issue 3, "Stability where methods fail").
 *
 * For every law of the registry with the DEM_LAW_PLASTIC or DEM_LAW_ADHESIVE flag (laws added
 * later are picked up automatically), at the reference case of the physics notes and impact
 * velocities 2, 5 and 10 m/s, the velocity-Verlet impact (dem_impact_run) is repeated with the
 * dt factor (of the Rayleigh step, thesis eq 3.1) on a log grid from 0.001 upwards (8 points
 * per decade) until the solver reports breakdown. Per law and velocity it records:
 *   - e_ref, alpha_max,ref: the GSL rk8pd reference integration (rtol 1e-10);
 *   - f_1%: the largest grid factor up to which every grid factor gives e within 1 % of e_ref
 *     (relative) and the same sticking outcome; where the reference sticks (e_ref = 0) the
 *     criterion is alpha_max within 1 % instead;
 *   - the first factor at which the solver reports breakdown, with its code (DEM_EUNSTABLE,
 *     DEM_ERUNAWAY, DEM_ENONFINITE) and message, and the largest error of e seen below it
 *     (numbers the solver returned without detecting anything);
 *   - the wall time of one impact at every factor (CLOCK_MONOTONIC around repeated runs for at
 *     least --time seconds, the whole dem_impact_run).
 *
 * Parameter set (the job script scripts/jobs/10-single-contact.sh and docs/impact.md): the
 * particle R = 2.45 um, rho = 1350 kg/m^3, E = 1.2 GPa, nu = 0.3 on a silicon wall (E = 182 GPa,
 * nu = 0.3), Gamma = 0.2 J/m^2, p_y = 35.3 MPa (thesis Table 4.1); ke = kn = 1500, kp = 210,
 * kc = kcp = 20 N/m, f0 = 2.1 uN, f0p = 4.0 uN (thesis Table 4.2); Luding ke_max = 1500 N/m,
 * phi_f = 0.02 (thesis 4.1.5); no viscous damping (e = 1). A law receives the keys of this pool
 * that are among its coefficients, except `nan`, whose k_el, k_p and k_cl come from its own
 * correlations (eqs 52, 38; k_p = k_el; physics notes: "when no loading data exist"): the
 * thesis' Table 4.2 stiffnesses are fits of the thesis' law to Thornton-Ning's curves, and
 * with them `nan` sticks at 2, 5 and 10 m/s (docs/contact-laws.md).
 *
 * Usage: dem-bench-stability [--out DIR] [--time S] [--law ID]   (default DIR bench-out)
 * Writes DIR/bench_stability.csv (every run), DIR/bench_stability_summary.csv,
 * DIR/bench_stability.md (the summary as a markdown table), DIR/bench_stability.gp and, with
 * gnuplot, DIR/bench_stability.png. Runs in about 15 s on the 2-core machine.
 */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dem/impact.h"
#include "dem/material.h"
#include "dem/table.h"

#define NV 3
static const double vels[NV] = {2.0, 5.0, 10.0}; /* m/s, physics notes */

typedef struct {
  const char *key;
  double value;
} kv;

/* The reference pool (see the header comment). */
static const kv pool[] = {
    {"E", 1.2e9},     {"nu", 0.3},      {"wall_E", 182e9}, {"wall_nu", 0.3}, {"gamma", 0.2},
    {"py", 35.3e6},   {"kn", 1500.0},   {"ke", 1500.0},    {"kp", 210.0},    {"kc", 20.0},
    {"kcp", 20.0},    {"f0", 2.1e-6},   {"f0p", 4.0e-6},   {"ke_max", 1500.0}, {"phi_f", 0.02},
    {"e", 1.0},       {NULL, 0.0}};
static const double R_PART = 2.45e-6, RHO_PART = 1350.0;

static int own_correlation(const char *law, const char *key) {
  return strcmp(law, "nan") == 0 &&
         (strcmp(key, "ke") == 0 || strcmp(key, "kp") == 0 || strcmp(key, "kc") == 0);
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

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The law's scene from the pool; returns the dem_impact_setup status. */
static int law_scene(const dem_law *law, dem_impact_scene *sc, char *keys, size_t nkeys,
                     dem_err *err) {
  dem_params ps;
  dem_params_init(&ps);
  dem_params_set(&ps, "R", R_PART, "bench", NULL);
  dem_params_set(&ps, "rho", RHO_PART, "bench", NULL);
  size_t used = 0;
  keys[0] = '\0';
  for (const kv *k = pool; k->key; k++) {
    int scene = strcmp(k->key, "E") == 0 || strcmp(k->key, "nu") == 0;
    if (!scene && !dem_contact_law_has_coef(law, k->key)) continue;
    if (own_correlation(law->name, k->key)) continue;
    dem_params_set(&ps, k->key, k->value, "bench", NULL);
    if (used + 40 < nkeys)
      used += (size_t)snprintf(keys + used, nkeys - used, "%s%s=%g", used ? " " : "", k->key,
                               k->value);
  }
  return dem_impact_setup(sc, law, &ps, DEM_TARGET_WALL, err);
}

typedef struct {
  const char *law;
  double v, e_ref, amax_ref, f1, f1_ms, fbreak, fbreak_ms, max_err_below, us_001;
  int stuck_ref, code;
  char msg[DEM_ERRMSG_LEN + 32];
} summary;

static void usage(FILE *f) {
  fprintf(f, "usage: dem-bench-stability [--out DIR] [--time S] [--law ID]\n"
             "  Time-step factor at which e(v) departs by 1%% from the reference integrator,\n"
             "  and where the impact solver detects breakdown, for every plastic or adhesive\n"
             "  law at 2, 5 and 10 m/s (reference case of the physics notes).\n"
             "  --out DIR   output directory (default bench-out)\n"
             "  --time S    seconds of repeated impacts per timing point (default 0.02)\n"
             "  --law ID    only this law\n");
}

int main(int argc, char **argv) {
  const char *dir = "bench-out", *only = NULL;
  double tmin = 0.02;
  static const struct option opts[] = {{"out", required_argument, NULL, 'o'},
                                       {"time", required_argument, NULL, 't'},
                                       {"law", required_argument, NULL, 'l'},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  int o;
  while ((o = getopt_long(argc, argv, "o:t:l:h", opts, NULL)) != -1) {
    switch (o) {
      case 'o': dir = optarg; break;
      case 't': tmin = atof(optarg); break;
      case 'l': only = optarg; break;
      case 'h': usage(stdout); return 0;
      default: usage(stderr); return 2;
    }
  }
  if (optind < argc || !(tmin >= 0.0 && tmin <= 10.0)) {
    usage(stderr);
    return 2;
  }
  if (only && !dem_contact_law_find(only)) {
    fprintf(stderr, "dem-bench-stability: unknown law '%s'\n", only);
    return 2;
  }
  dem_err merr = {0};
  if (dem_mkdirs(dir, &merr)) {
    fprintf(stderr, "dem-bench-stability: %s\n", merr.msg);
    return 1;
  }
  char path[4096], tmp[4200];
  snprintf(path, sizeof path, "%s/bench_stability.csv", dir);
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  FILE *csv = fopen(tmp, "w");
  if (!csv) {
    fprintf(stderr, "dem-bench-stability: cannot write %s\n", tmp);
    return 1;
  }
  const double t_ray = dem_dt_rayleigh(R_PART, RHO_PART, 1.2e9, 0.3);
  fprintf(csv, "# particle R = %g m, rho = %g kg/m^3, wall; velocity Verlet, dt = factor x "
               "Rayleigh step %.6g s; reference: GSL rk8pd rtol 1e-10\n",
          R_PART, RHO_PART, t_ray);
  fprintf(csv, "law,v_impact [m/s],dt_factor,dt [s],dt_over_tscale,steps,wall_per_impact [s],"
               "e,e_ref,rel_err_e,alpha_max [m],rel_err_alpha_max,stuck,status\n");

  summary sums[64 * NV];
  int ns = 0;
  for (int li = 0; li < dem_contact_law_count(); li++) {
    const dem_law *law = dem_contact_law_at(li);
    if (!(law->flags & (DEM_LAW_PLASTIC | DEM_LAW_ADHESIVE))) continue;
    if (only && strcmp(only, law->name) != 0) continue;
    dem_impact_scene sc;
    dem_err err = {0};
    char keys[1024];
    if (law_scene(law, &sc, keys, sizeof keys, &err)) {
      printf("%-18s skipped: %s\n", law->name, err.msg);
      continue;
    }
    printf("%-18s %s\n", law->name, keys);
    for (int iv = 0; iv < NV && ns < 64 * NV; iv++) {
      const double v = vels[iv];
      summary *s = &sums[ns++];
      memset(s, 0, sizeof *s);
      s->law = law->name;
      s->v = v;
      s->f1 = s->f1_ms = s->fbreak = s->fbreak_ms = s->us_001 = NAN;
      dem_impact_opts op;
      dem_impact_opts_default(&op);
      op.integrator = DEM_INTEGRATOR_REFERENCE;
      op.rtol = 1e-10;
      dem_impact_result ref, r;
      if (dem_impact_run(&sc, &op, v, &ref, &err)) {
        printf("  v = %g: reference failed: %s\n", v, err.msg);
        s->code = -1;
        snprintf(s->msg, sizeof s->msg, "reference: %s", err.msg);
        continue;
      }
      s->e_ref = ref.e;
      s->amax_ref = ref.alpha_max;
      s->stuck_ref = ref.stuck;
      const double tscale = dem_dt_sdof(sc.geom.m, dem_contact_kref(&sc.law, &sc.geom, v));
      op.integrator = DEM_INTEGRATOR_VERLET;
      op.dt_rule = DEM_DT_RAYLEIGH;
      int departed = 0;
      for (int k = 0; k <= 40; k++) {
        const double f = 0.001 * pow(10.0, k / 8.0);
        op.dt_factor = f;
        const double dt = dem_impact_dt(&sc, &op, v);
        int rc = dem_impact_run(&sc, &op, v, &r, &err);
        if (rc) {
          s->fbreak = f;
          s->fbreak_ms = dt / tscale;
          s->code = rc;
          snprintf(s->msg, sizeof s->msg, "%s", err.msg);
          fprintf(csv, "%s,%g,%.6g,%.6g,%.6g,0,nan,nan,%.12g,nan,nan,nan,0,%s\n", law->name, v,
                  f, dt, dt / tscale, ref.e, code_name(rc));
          break;
        }
        long reps = 0;
        double t0 = now(), t1 = t0;
        if (tmin > 0.0) do {
            dem_impact_run(&sc, &op, v, &r, NULL);
            reps++;
            t1 = now();
          } while (t1 - t0 < tmin);
        const double per = reps ? (t1 - t0) / (double)reps : NAN;
        const double ee = ref.e > 0.0 ? fabs(r.e - ref.e) / ref.e : fabs(r.e - ref.e);
        const double ea = fabs(r.alpha_max / ref.alpha_max - 1.0);
        const double crit = ref.stuck ? ea : ee;
        if (!departed && (crit > 0.01 || r.stuck != ref.stuck)) departed = 1;
        if (!departed) {
          s->f1 = f;
          s->f1_ms = dt / tscale;
        }
        /* A flipped sticking outcome counts as a 100 % error. */
        const double err_here = r.stuck != ref.stuck ? fmax(crit, 1.0) : crit;
        if (err_here > s->max_err_below) s->max_err_below = err_here;
        if (fabs(f - 0.01) < 1e-9) s->us_001 = per * 1e6;
        fprintf(csv, "%s,%g,%.6g,%.6g,%.6g,%ld,%.6g,%.12g,%.12g,%.6g,%.12g,%.6g,%d,ok\n",
                law->name, v, f, dt, dt / tscale, r.steps, per, r.e, ref.e, ee, r.alpha_max, ea,
                r.stuck);
      }
      printf("  v = %4.1f m/s  e_ref %.5f%s  1%% up to factor %-7.3g (%.3g sqrt(m*/k))  "
             "breakdown at %-7.3g (%.3g sqrt(m*/k)): %s\n    %s\n",
             v, ref.e, ref.stuck ? " (stuck)" : "", s->f1, s->f1_ms, s->fbreak, s->fbreak_ms,
             code_name(s->code), s->msg);
    }
  }
  if (fclose(csv) != 0 || rename(tmp, path) != 0) {
    fprintf(stderr, "dem-bench-stability: cannot write %s\n", path);
    return 1;
  }

  /* Summary: CSV and markdown. */
  char sp[4096], mp[4096];
  snprintf(sp, sizeof sp, "%s/bench_stability_summary.csv", dir);
  snprintf(mp, sizeof mp, "%s/bench_stability.md", dir);
  FILE *sf = fopen(sp, "w"), *mf = fopen(mp, "w");
  if (!sf || !mf) {
    fprintf(stderr, "dem-bench-stability: cannot write %s or %s\n", sp, mp);
    return 1;
  }
  fprintf(sf, "law,v_impact [m/s],e_ref,stuck_ref,alpha_max_ref [m],f_1pct,f_1pct_tscale,"
              "f_break,f_break_tscale,max_rel_err_below_break,us_per_impact_at_0.01,code,"
              "message\n");
  fprintf(mf, "| law | v (m/s) | e_ref | 1 %% up to dt factor (x T_R) | same in sqrt(m*/k_ref) "
              "| breakdown at (x T_R) | same in sqrt(m*/k_ref) | largest error of e below it "
              "| how | us/impact at 0.01 |\n|---|---|---|---|---|---|---|---|---|---|\n");
  for (int i = 0; i < ns; i++) {
    const summary *s = &sums[i];
    char msg[DEM_ERRMSG_LEN + 32];
    snprintf(msg, sizeof msg, "%s", s->msg);
    for (char *c = msg; *c; c++)
      if (*c == '"') *c = '\'';
    fprintf(sf, "%s,%g,%.6g,%d,%.6g,%.4g,%.4g,%.4g,%.4g,%.3g,%.4g,%s,\"%s\"\n", s->law, s->v,
            s->e_ref, s->stuck_ref, s->amax_ref, s->f1, s->f1_ms, s->fbreak, s->fbreak_ms,
            s->max_err_below, s->us_001, code_name(s->code), msg);
    fprintf(mf, "| %s | %g | %.4f%s | %.3g | %.3g | %.3g | %.3g | %.3g%s | %s | %.3g |\n", s->law,
            s->v, s->e_ref, s->stuck_ref ? " (stuck)" : "", s->f1, s->f1_ms, s->fbreak,
            s->fbreak_ms, s->max_err_below * 100.0, " %", code_name(s->code), s->us_001);
  }
  fprintf(mf, "\nT_R = %.4g s (Rayleigh step of the particle, thesis eq 3.1). Messages:\n\n",
          t_ray);
  for (int i = 0; i < ns; i++)
    fprintf(mf, "- %s, %g m/s: `%s`\n", sums[i].law, sums[i].v, sums[i].msg);
  fclose(sf);
  fclose(mf);

  /* gnuplot: relative error of e (alpha_max where the reference sticks) against the dt
   * factor, one panel per velocity, one line per law; breakdown marked. */
  char gp[4096];
  snprintf(gp, sizeof gp, "%s/bench_stability.gp", dir);
  FILE *g = fopen(gp, "w");
  if (!g) return 1;
  fprintf(g,
          "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1500,560 "
          "font ',11' } else { set terminal png size 1500,560 }\n"
          "set output '%s/bench_stability.png'\n"
          "set datafile separator ','\nset logscale xy\nset grid\nset key bottom right font ',9'\n"
          "set format y '10^{%%L}'\nset xrange [0.001:10]\nset yrange [1e-9:300]\n"
          "f = '%s'\nset multiplot layout 1,3 title 'Impact of the 2.45 um particle on "
          "silicon, velocity Verlet: relative error of e (of alpha\\_max where it sticks) vs "
          "time step; x = breakdown detected'\n",
          dir, path);
  static const char *const colors[10] = {"#9400d3", "#009e73", "#56b4e9", "#e69f00", "#2e8b57",
                                         "#e51e10", "#0072b2", "#808080", "#a0522d", "#ff69b4"};
  for (int iv = 0; iv < NV; iv++) {
    fprintf(g, "set title 'v = %g m/s'\nset xlabel 'dt factor (x Rayleigh step %.3g ns)'\n"
               "set ylabel 'relative error'\n",
            vels[iv], t_ray * 1e9);
    fprintf(g, "plot 0.01 with lines dt 2 lc rgb 'gray30' title '1 %%'");
    int pt = 0;
    for (int i = 0; i < ns; i++) {
      if (sums[i].v != vels[iv]) continue;
      const char *col = sums[i].stuck_ref ? "$12" : "$10";
      /* thornton-ning, the nonlinear reference law, in black */
      const char *lc = strcmp(sums[i].law, "thornton-ning") == 0 ? "#000000" : colors[pt % 10];
      fprintf(g,
              ", f using (strcol(1) eq '%s' && $2 == %g && strcol(14) eq 'ok' ? $3 : NaN):"
              "(%s > 1e-9 ? %s : 1e-9) with linespoints lw 2 pt %d lc rgb '%s' title '%s%s'",
              sums[i].law, vels[iv], col, col, 4 + pt, lc, sums[i].law,
              sums[i].stuck_ref ? " (sticks: alpha\\_max)" : "");
      if (isfinite(sums[i].fbreak))
        fprintf(g, ", '+' using (%g):(%g) every ::0::0 with points pt 2 ps 2 lw 2 lc rgb '%s' "
                   "notitle",
                sums[i].fbreak, 2.0 * pow(1.7, pt), lc);
      pt++;
    }
    fprintf(g, "\n");
  }
  fprintf(g, "unset multiplot\n");
  fclose(g);
  char cmd[8400];
  snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", gp);
  if (system("command -v gnuplot > /dev/null 2>&1") == 0 && system(cmd) != 0)
    fprintf(stderr, "dem-bench-stability: gnuplot failed on %s\n", gp);
  printf("results: %s, %s, %s, %s/bench_stability.png\n", path, sp, mp, dir);
  return 0;
}
