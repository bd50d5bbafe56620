/* PNG plots with gnuplot (pngcairo): for each curve target the fitted force-overlap curve
 * over the reference points (fit_<target>.png), for sticking targets V_crit versus radius
 * with the reference points (vcrit_<target>.png), for restitution targets e(v)
 * (restitution_<target>.png), and the objective trace (trace.png). The plotted data go to
 * plot_<...>.dat next to them. Each PNG is drawn to a .tmp file and renamed. A missing
 * gnuplot is reported, not fatal. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cal.h"

static int gnuplot(const char *dir, const char *png, const char *script, dem_err *err) {
  char sp[CAL_PATH_LEN], cmd[3 * CAL_PATH_LEN], tmp[CAL_PATH_LEN], fin[CAL_PATH_LEN];
  snprintf(sp, sizeof sp, "%s/%s.gp", dir, png);
  snprintf(tmp, sizeof tmp, "%s/%s.tmp", dir, png);
  snprintf(fin, sizeof fin, "%s/%s", dir, png);
  FILE *f = fopen(sp, "w");
  if (!f) return dem_err_set(err, DEM_EIO, "cannot write '%s'", sp);
  fprintf(f, "set terminal pngcairo size 900,640 noenhanced\nset output '%s'\n%s", tmp, script);
  fclose(f);
  snprintf(cmd, sizeof cmd, "gnuplot '%s' >/dev/null 2>&1", sp);
  int st = system(cmd);
  remove(sp);
  if (st != 0) {
    remove(tmp);
    return dem_err_set(err, DEM_EIO, "gnuplot failed for %s (is gnuplot installed?)", png);
  }
  return rename(tmp, fin) == 0 ? DEM_OK : dem_err_set(err, DEM_EIO, "cannot rename '%s'", tmp);
}

static int curve_plot(cal_problem *p, const cal_target *t, const dem_params *ps,
                      const char *dir, dem_err *err) {
  double *a = NULL, *f = NULL;
  int n = 0;
  int rc = cal_model_curve(p->cfg, t, ps, &a, &f, &n, err);
  if (rc) return rc;
  char dat[CAL_PATH_LEN], png[CAL_NAME_LEN + 16], script[4096];
  snprintf(dat, sizeof dat, "%s/plot_%s.dat", dir, t->name);
  FILE *o = fopen(dat, "w");
  if (!o) {
    free(a);
    free(f);
    return dem_err_set(err, DEM_EIO, "cannot write '%s'", dat);
  }
  fprintf(o, "# reference: alpha_m f_N\n");
  for (int k = 0; k < t->n; k++) fprintf(o, "%.10g %.10g\n", t->x[k], t->y[k]);
  fprintf(o, "\n\n# model: alpha_m f_N\n");
  int stride = n > 4000 ? n / 4000 : 1;
  for (int k = 0; k < n; k += stride) fprintf(o, "%.10g %.10g\n", a[k], f[k]);
  fclose(o);
  free(a);
  free(f);
  snprintf(png, sizeof png, "fit_%s.png", t->name);
  snprintf(script, sizeof script,
           "set title '%s: law %s fitted to %s'\nset xlabel 'overlap alpha (um)'\n"
           "set ylabel 'normal force (uN)'\nset grid\nset key top left\n"
           "plot '%s' index 0 using ($1*1e6):($2*1e6) with points pt 7 ps 0.6 title 'reference', "
           "'' index 1 using ($1*1e6):($2*1e6) with lines lw 2 title 'fitted %s'\n",
           p->cfg->name, p->cfg->law->name, t->name, dat, p->cfg->law->name);
  return gnuplot(dir, png, script, err);
}

static int point_plot(cal_problem *p, const cal_target *t, const char *dir, dem_err *err) {
  char dat[CAL_PATH_LEN], png[CAL_NAME_LEN + 24], script[4096];
  int stick = t->type == CAL_T_STICKING;
  if (t->type == CAL_T_UNLOADING) {
    snprintf(dat, sizeof dat, "%s/plot_%s.dat", dir, t->name);
    FILE *o = fopen(dat, "w");
    if (!o) return dem_err_set(err, DEM_EIO, "cannot write '%s'", dat);
    fprintf(o, "# alpha_max_m quantity(0 f_max, 1 alpha_p, 2 f_pulloff) reference model\n");
    for (int k = 0; k < t->nres; k++)
      fprintf(o, "%.10g %d %.10g %.10g\n", t->xr[k], k % 3, t->yr[k], p->model[t->off + k]);
    fclose(o);
    snprintf(png, sizeof png, "unloading_%s.png", t->name);
    snprintf(script, sizeof script,
             "set title '%s: load-unload summary points, law %s (model / reference)'\n"
             "set xlabel 'alpha_max (nm)'\nset ylabel 'model / reference'\nset grid\n"
             "set yrange [0:*]\n"
             "plot '%s' using ($1*1e9):($2==0?$4/$3:1/0) with linespoints pt 7 ps 1.5 title 'f_max', "
             "'' using ($1*1e9):($2==1?$4/$3:1/0) with linespoints pt 5 ps 1.5 title 'alpha_p', "
             "'' using ($1*1e9):($2==2?$4/$3:1/0) with linespoints pt 9 ps 1.5 title 'pull-off', "
             "1 with lines lc rgb 'black' notitle\n",
             p->cfg->name, p->cfg->law->name, dat);
    return gnuplot(dir, png, script, err);
  }
  snprintf(dat, sizeof dat, "%s/plot_%s.dat", dir, t->name);
  FILE *o = fopen(dat, "w");
  if (!o) return dem_err_set(err, DEM_EIO, "cannot write '%s'", dat);
  fprintf(o, "# %s reference model\n", stick ? "R_m v_stick_m/s" : "v_m/s e");
  for (int k = 0; k < t->nres; k++)
    fprintf(o, "%.10g %.10g %.10g\n", t->xr[k], t->yr[k], p->model[t->off + k]);
  fclose(o);
  snprintf(png, sizeof png, "%s_%s.png", stick ? "vcrit" : "restitution", t->name);
  if (stick)
    snprintf(script, sizeof script,
             "set title '%s: critical sticking velocity, law %s'\nset xlabel 'radius R (um)'\n"
             "set ylabel 'V_crit (m/s)'\nset grid\nset logscale y\n"
             "plot '%s' using ($1*1e6):2 with points pt 7 ps 1.5 title 'reference', "
             "'' using ($1*1e6):3 with linespoints pt 6 lw 2 title 'fitted'\n",
             p->cfg->name, p->cfg->law->name, dat);
  else
    snprintf(script, sizeof script,
             "set title '%s: coefficient of restitution, law %s'\nset xlabel 'impact velocity (m/s)'\n"
             "set ylabel 'e'\nset grid\n"
             "plot '%s' using 1:2 with points pt 7 ps 1.5 title 'reference', "
             "'' using 1:3 with linespoints pt 6 lw 2 title 'fitted'\n",
             p->cfg->name, p->cfg->law->name, dat);
  return gnuplot(dir, png, script, err);
}

static int trace_plot(cal_problem *p, const char *dir, dem_err *err) {
  char dat[CAL_PATH_LEN], script[4096];
  snprintf(dat, sizeof dat, "%s/plot_trace.dat", dir);
  FILE *o = fopen(dat, "w");
  if (!o) return dem_err_set(err, DEM_EIO, "cannot write '%s'", dat);
  int w = 3 + p->cfg->nfree;
  fprintf(o, "# eval stage S best_S\n");
  for (long k = 0; k < p->tr_n; k++)
    fprintf(o, "%ld %g %.10g %.10g\n", k + 1, p->tr[k * w], p->tr[k * w + 1], p->tr[k * w + 2]);
  fclose(o);
  snprintf(script, sizeof script,
           "set title '%s: objective trace'\nset xlabel 'evaluation'\nset ylabel 'S'\n"
           "set logscale y\nset grid\n"
           "plot '%s' using 1:($3>0?$3:1/0) with points pt 7 ps 0.4 title 'S (evaluated)', "
           "'' using 1:($4>0?$4:1/0) with lines lw 2 title 'best so far'\n",
           p->cfg->name, dat);
  return gnuplot(dir, "trace.png", script, err);
}

int cal_write_plots(cal_problem *p, const cal_result *r, const char *dir, dem_err *err) {
  dem_params ps;
  int rc = cal_params_from_scaled(p->cfg, r->u, NULL, &ps, err);
  for (int i = 0; !rc && i < p->cfg->ntargets; i++) {
    const cal_target *t = &p->cfg->t[i];
    rc = t->type == CAL_T_CURVE ? curve_plot(p, t, &ps, dir, err) : point_plot(p, t, dir, err);
  }
  if (!rc) rc = trace_plot(p, dir, err);
  return rc;
}
