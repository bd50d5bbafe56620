/* dem-bench-impact: accuracy against cost of the velocity-Verlet impact integrator.
 *
 * For the linear (kn = 1500 N/m, thesis Table 4.2 ke) and Hertz (ammonium fluorescein on
 * silicon, thesis Table 4.1) impacts at 2 m/s of the reference particle (R = 2.45 um,
 * rho = 1350 kg/m^3), sweeps the dt factor from 0.001 upwards (log grid, 8 per decade) and
 * records |e - e_reference| and |t_c/t_c,ref - 1| against the wall time of one impact;
 * e_reference comes from the GSL rk8pd reference integrator at rtol 1e-12. The sweep goes on
 * past 0.5 until the integrator reports breakdown (DEM_EUNSTABLE / DEM_ERUNAWAY), which is
 * marked. Time step rules: Hertz Rayleigh (E, nu known), linear mass-spring sqrt(m* / k).
 *
 * Usage: dem-bench-impact [OUT_DIR]   (default bench-out). Writes OUT_DIR/bench_impact.csv,
 * OUT_DIR/bench_impact.gp and, if gnuplot is installed, OUT_DIR/bench_impact.png and
 * OUT_DIR/bench_impact_dt.png. Runs in well under a minute.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dem/impact.h"
#include "dem/table.h"

typedef struct {
  const char *name;
  const char *law;
  const char *sets[8];
  int rule;
} bench_case;

static const bench_case cases[] = {
    {"linear-e0.5", "linear", {"kn=1500", "e=0.5", NULL}, DEM_DT_MASS_SPRING},
    {"hertz-e0.5", "hertz", {"E=1.2e9", "nu=0.3", "wall_E=182e9", "wall_nu=0.3", "e=0.5", NULL},
     DEM_DT_RAYLEIGH},
    {"hertz-e1", "hertz", {"E=1.2e9", "nu=0.3", "wall_E=182e9", "wall_nu=0.3", "e=1", NULL},
     DEM_DT_RAYLEIGH},
};

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(int argc, char **argv) {
  const char *dir = argc > 1 ? argv[1] : "bench-out";
  dem_err merr = {0};
  if (dem_mkdirs(dir, &merr)) {
    fprintf(stderr, "dem-bench-impact: %s\n", merr.msg);
    return 1;
  }
  char path[4096], tmp[4200];
  snprintf(path, sizeof path, "%s/bench_impact.csv", dir);
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  FILE *csv = fopen(tmp, "w");
  if (!csv) {
    fprintf(stderr, "dem-bench-impact: cannot write %s\n", tmp);
    return 1;
  }
  fprintf(csv, "# v_impact = 2 m/s; R = 2.45e-6 m; rho = 1350 kg/m^3; Verlet with predicted "
               "damping velocity; reference rk8pd rtol 1e-12\n");
  fprintf(csv, "case,dt_factor,dt [s],steps,wall_per_impact [s],abs_err_e,rel_err_tc,status\n");
  const double v = 2.0;
  double unstable[3] = {NAN, NAN, NAN}, last_ok[3] = {NAN, NAN, NAN};
  for (int c = 0; c < 3; c++) {
    dem_params ps;
    dem_params_init(&ps);
    dem_err err = {0};
    dem_params_set(&ps, "R", 2.45e-6, "bench", &err);
    dem_params_set(&ps, "rho", 1350.0, "bench", &err);
    for (int i = 0; cases[c].sets[i]; i++)
      dem_params_parse_assignment(&ps, cases[c].sets[i], "bench", &err);
    dem_impact_scene sc;
    if (dem_impact_setup(&sc, dem_contact_law_find(cases[c].law), &ps, DEM_TARGET_WALL, &err)) {
      fprintf(stderr, "dem-bench-impact: %s: %s\n", cases[c].name, err.msg);
      return 1;
    }
    dem_impact_opts o;
    dem_impact_opts_default(&o);
    o.integrator = DEM_INTEGRATOR_REFERENCE;
    o.rtol = 1e-12;
    dem_impact_result ref, r;
    if (dem_impact_run(&sc, &o, v, &ref, &err)) {
      fprintf(stderr, "dem-bench-impact: reference %s: %s\n", cases[c].name, err.msg);
      return 1;
    }
    o.integrator = DEM_INTEGRATOR_VERLET;
    o.dt_rule = (dem_dt_rule)cases[c].rule;
    for (int k = 0; k <= 40; k++) {
      double f = 0.001 * pow(10.0, k / 8.0);
      o.dt_factor = f;
      int rc = dem_impact_run(&sc, &o, v, &r, &err);
      if (rc) {
        fprintf(csv, "%s,%.6g,%.6g,0,nan,nan,nan,%s\n", cases[c].name, f,
                dem_impact_dt(&sc, &o, v), rc == DEM_ERUNAWAY ? "runaway" : "unstable");
        unstable[c] = f;
        printf("%-12s dt factor %.4g: %s (%s)\n", cases[c].name, f, dem_strerror(rc), err.msg);
        break;
      }
      /* Time enough repetitions for ~20 ms. */
      long reps = 0;
      double t0 = now(), t1;
      do {
        dem_impact_run(&sc, &o, v, &r, NULL);
        reps++;
        t1 = now();
      } while (t1 - t0 < 0.02);
      double per = (t1 - t0) / (double)reps;
      double ee = fabs(r.e - ref.e), et = fabs(r.t_contact / ref.t_contact - 1.0);
      fprintf(csv, "%s,%.6g,%.6g,%ld,%.6g,%.6g,%.6g,ok\n", cases[c].name, f, r.dt, r.steps, per,
              ee, et);
      last_ok[c] = f;
      printf("%-12s dt factor %-8.4g steps %-7ld %9.3f us/impact  |e-e_ref| %.3e  "
             "|tc/tc_ref-1| %.3e\n",
             cases[c].name, f, r.steps, per * 1e6, ee, et);
    }
  }
  if (fclose(csv) != 0 || rename(tmp, path) != 0) {
    fprintf(stderr, "dem-bench-impact: cannot write %s\n", path);
    return 1;
  }
  /* gnuplot script: error vs wall time, and error vs dt factor with the breakdown marked. */
  char gp[4096];
  snprintf(gp, sizeof gp, "%s/bench_impact.gp", dir);
  FILE *g = fopen(gp, "w");
  if (!g) return 1;
  fprintf(g,
          "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 900,640 "
          "font ',11' } else { set terminal png size 900,640 }\n"
          "set datafile separator ','\nset logscale xy\nset grid\nset key top right\n"
          "f = '%s'\n",
          path);
  fprintf(g, "set output '%s/bench_impact.png'\n"
             "set title 'Impact at 2 m/s, velocity Verlet: accuracy vs cost (2.45 um particle)'\n"
             "set xlabel 'wall time per impact (us)'\nset ylabel '|e - e_{reference}|'\n"
             "set format y '10^{%%L}'\n",
          dir);
  fprintf(g, "plot ");
  for (int c = 0; c < 3; c++)
    fprintf(g,
            "%sf using (strcol(8) eq 'ok' && strcol(1) eq '%s' ? $5*1e6 : NaN):($6 > 0 ? $6 : 1e-16) "
            "with linespoints lw 2 pt %d title '%s (unstable at dt factor %.3g)'",
            c ? ", " : "", cases[c].name, 5 + 2 * c, cases[c].name, unstable[c]);
  fprintf(g, "\nset output '%s/bench_impact_dt.png'\n"
             "set title 'Impact at 2 m/s: error vs dt factor; dashed: breakdown detected'\n"
             "set xlabel 'dt factor (Rayleigh for Hertz, sqrt(m*/k) for linear)'\n"
             "set key bottom right\n",
          dir);
  for (int c = 0; c < 3; c++)
    if (isfinite(unstable[c]))
      fprintf(g, "set arrow %d from %g, graph 0 to %g, graph 1 nohead dt 2 lc %d\n", c + 1,
              unstable[c], unstable[c], c + 1);
  fprintf(g, "plot ");
  for (int c = 0; c < 3; c++)
    fprintf(g,
            "%sf using (strcol(1) eq '%s' && strcol(8) eq 'ok' ? $2 : NaN):($6 > 0 ? $6 : 1e-16) "
            "with linespoints lw 2 lc %d pt %d title '%s |e - e_{ref}|'",
            c ? ", " : "", cases[c].name, c + 1, 5 + 2 * c, cases[c].name);
  fprintf(g, "\n");
  fclose(g);
  char cmd[8400];
  snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>/dev/null", gp);
  if (system(cmd) != 0)
    printf("dem-bench-impact: gnuplot not available or failed; CSV and script in %s\n", dir);
  for (int c = 0; c < 3; c++)
    printf("%-12s last stable dt factor %.4g, breakdown detected at %.4g\n", cases[c].name,
           last_ok[c], unstable[c]);
  printf("dem-bench-impact: wrote %s\n", path);
  return 0;
}
