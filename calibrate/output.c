/* The output folder of a calibration. Every file is written to "<name>.tmp" and renamed
 * when complete, so an interrupted run never leaves a half-written result:
 *
 *   best_params.txt        key=value lines (free and fixed), usable with --set
 *   residuals_<target>.csv x, reference, model, residual, relative_error per compared point
 *   trace.csv              every evaluation (written while running as trace.csv.tmp)
 *   summary.txt            human-readable: values, standard errors, 95% intervals,
 *                          correlations, identifiability warning, residual table, timing
 *   results.h5             the same in HDF5
 *   failures.log           evaluations the model could not complete (if any)
 *   eval_cache.txt         the evaluation cache (cache.c)
 */
#include <errno.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <time.h>

#include "cal.h"

FILE *cal_tmp_open(const char *dir, const char *name, char *tmp, size_t n, dem_err *err) {
  snprintf(tmp, n, "%s/%s.tmp", dir, name);
  FILE *f = fopen(tmp, "w");
  if (!f) dem_err_set(err, DEM_EIO, "cannot write '%s': %s", tmp, strerror(errno));
  return f;
}

int cal_commit(FILE *f, const char *tmp, dem_err *err) {
  int bad = ferror(f);
  if (fclose(f) != 0 || bad) return dem_err_set(err, DEM_EIO, "error writing '%s'", tmp);
  char final[CAL_PATH_LEN];
  size_t len = strlen(tmp);
  snprintf(final, sizeof final, "%.*s", (int)(len - 4), tmp);
  if (rename(tmp, final) != 0)
    return dem_err_set(err, DEM_EIO, "cannot rename '%s': %s", tmp, strerror(errno));
  return DEM_OK;
}

static const char *unit_of(const cal_config *c, const char *key) {
  for (int i = 0; i < c->law->ncoef; i++)
    if (strcmp(c->law->coef[i].key, key) == 0) return c->law->coef[i].unit;
  if (!strcmp(key, "R")) return "m";
  if (!strcmp(key, "rho")) return "kg/m^3";
  if (!strcmp(key, "E")) return "Pa";
  return "-";
}

double cal_mean_relative_error(const cal_problem *p) {
  double *norm = malloc(sizeof(double) * (size_t)p->nres), s = 0.0;
  if (!norm) return NAN;
  cal_residual_norms(p->cfg, norm);
  for (int i = 0; i < p->cfg->ntargets; i++) {
    const cal_target *t = &p->cfg->t[i];
    for (int k = 0; k < t->nres; k++)
      s += fabs((p->model[t->off + k] - t->yr[k]) / norm[t->off + k]);
  }
  free(norm);
  return s / p->nres;
}

static const char *type_name(const cal_target *t) {
  static const char *const n[] = {"curve", "sticking", "restitution", "unloading"};
  return n[t->type];
}

static const char *xname(const cal_target *t) {
  if (t->type == CAL_T_UNLOADING) return "alpha_max_m";
  if (t->type == CAL_T_STICKING) return "R_m";
  if (t->type == CAL_T_RESTITUTION) return "v_impact_m/s";
  return t->mode == CAL_CURVE_SUMMARY ? "quantity(0=f_max_N,1=alpha_p_m,2=f_pulloff_N)"
                                      : "alpha_m";
}

static const char *yname(const cal_target *t) {
  if (t->type == CAL_T_UNLOADING) return "f_max_N|alpha_p_m|f_pulloff_N";
  if (t->type == CAL_T_STICKING) return "v_stick_m/s";
  if (t->type == CAL_T_RESTITUTION) return "e";
  return t->mode == CAL_CURVE_SUMMARY ? "value" : "f_N";
}

static int write_residual_tables(cal_problem *p, const char *dir, const double *norm,
                                 dem_err *err) {
  for (int i = 0; i < p->cfg->ntargets; i++) {
    const cal_target *t = &p->cfg->t[i];
    char name[CAL_NAME_LEN + 32], tmp[CAL_PATH_LEN];
    snprintf(name, sizeof name, "residuals_%s.csv", t->name);
    FILE *f = cal_tmp_open(dir, name, tmp, sizeof tmp, err);
    if (!f) return err ? err->code : DEM_EIO;
    fprintf(f, "%s,reference_%s,model_%s,weighted_residual,relative_error\n", xname(t),
            yname(t), yname(t));
    for (int k = 0; k < t->nres; k++) {
      int q = t->off + k;
      fprintf(f, "%.10g,%.10g,%.10g,%.6g,%.6g\n", t->xr[k], t->yr[k], p->model[q], p->resid[q],
              (p->model[q] - t->yr[k]) / norm[q]);
    }
    int rc = cal_commit(f, tmp, err);
    if (rc) return rc;
  }
  return DEM_OK;
}

static void machine(char *buf, size_t n) {
  struct utsname u;
  if (uname(&u) == 0)
    snprintf(buf, n, "%s %s %s", u.nodename, u.sysname, u.machine);
  else
    snprintf(buf, n, "unknown");
}

static int write_summary(cal_problem *p, const cal_result *r, const cal_stats *st,
                         const char *dir, double wall_s, const double *norm, dem_err *err) {
  const cal_config *c = p->cfg;
  char tmp[CAL_PATH_LEN], host[256];
  FILE *f = cal_tmp_open(dir, "summary.txt", tmp, sizeof tmp, err);
  if (!f) return err ? err->code : DEM_EIO;
  machine(host, sizeof host);
  fprintf(f, "dem-calibrate %s: %s\n", DEM_VERSION, c->name);
  fprintf(f, "config      %s\n", c->path);
  fprintf(f, "law         %s (%s; %s)\n", c->law->name, c->law->title, c->law->source);
  fprintf(f, "seed        %lu\n", c->seed);
  fprintf(f, "optimiser   %s%s%s, maxeval %d + %d%s\n", c->opt.multistart ? "multistart " : "",
          c->opt.multistart ? "" : (c->opt.global[0] ? c->opt.global : "(no global stage)"),
          " -> local", c->opt.maxeval_global, c->opt.maxeval_local,
          r->interrupted ? " (INTERRUPTED)" : "");
  fprintf(f, "nlopt       global result %d, local result %d\n", r->nlopt_global, r->nlopt_local);
  fprintf(f, "evaluations %ld (%ld from the cache, %ld failed)\n", p->nevals, p->ncached,
          p->nfailed);
  fprintf(f, "objective   S = %.10g (sum of squared weighted normalised residuals, %d points)\n",
          r->f, p->nres);
  fprintf(f, "mean |relative error| %.6g\n", cal_mean_relative_error(p));
  fprintf(f, "wall time   %.3f s on %s\n\n", wall_s, host);
  fprintf(f, "%-10s %-14s %-12s %-14s %-27s %-8s %s\n", "parameter", "value", "unit",
          "std error", "95% interval", "scale", "bounds");
  for (int i = 0; i < c->nfree; i++) {
    const cal_free *fr = &c->fr[i];
    char ci[64];
    snprintf(ci, sizeof ci, "[%.6g, %.6g]", st->lo95[i], st->hi95[i]);
    fprintf(f, "%-10s %-14.8g %-12s %-14.4g %-27s %-8s [%g, %g]\n", fr->name, r->x[i],
            unit_of(c, fr->name), st->ok ? st->se_x[i] : NAN, st->ok ? ci : "-",
            fr->scale == CAL_SCALE_LOG ? "log" : "linear", fr->lo, fr->hi);
  }
  fprintf(f, "\nfixed:");
  for (int i = 0; i < c->fixed.n; i++)
    fprintf(f, " %s=%g", c->fixed.p[i].key, c->fixed.p[i].value);
  fprintf(f, "\n\n");
  if (st->ok) {
    fprintf(f, "residual variance s^2 = %.6g; singular values of J:", st->s2);
    for (int j = 0; j < c->nfree; j++) fprintf(f, " %.4g", st->sv[j]);
    fprintf(f, " (condition %.4g)\ncorrelation matrix:\n%-10s", st->cond, "");
    for (int j = 0; j < c->nfree; j++) fprintf(f, " %9s", c->fr[j].name);
    fputc('\n', f);
    for (int a = 0; a < c->nfree; a++) {
      fprintf(f, "%-10s", c->fr[a].name);
      for (int b = 0; b < c->nfree; b++) fprintf(f, " %9.4f", st->corr[a * c->nfree + b]);
      fputc('\n', f);
    }
  }
  fprintf(f, "\nidentifiability: %s\n\n", st->warning[0] ? st->warning : "all parameters identifiable");
  fprintf(f, "residuals (relative_error = (model - reference) / norm; curves: norm = max |f_ref|)\n");
  for (int i = 0; i < c->ntargets; i++) {
    const cal_target *t = &c->t[i];
    double s = 0, mx = 0;
    for (int k = 0; k < t->nres; k++) {
      double e = fabs((p->model[t->off + k] - t->yr[k]) / norm[t->off + k]);
      s += e;
      if (e > mx) mx = e;
    }
    fprintf(f, "  target %-20s %-11s weight %-6g points %-5d mean |rel err| %.4g  max %.4g\n",
            t->name, type_name(t),
            t->weight, t->nres, s / t->nres, mx);
    if (t->type != CAL_T_CURVE || t->mode == CAL_CURVE_SUMMARY)
      for (int k = 0; k < t->nres; k++)
        fprintf(f, "    %-14.6g reference %-14.6g model %-14.6g relative error %+.4f\n",
                t->xr[k], t->yr[k], p->model[t->off + k],
                (p->model[t->off + k] - t->yr[k]) / norm[t->off + k]);
  }
  return cal_commit(f, tmp, err);
}

static void h5_attr_d(hid_t loc, const char *name, double v) {
  hid_t sp = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(loc, name, H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, H5T_NATIVE_DOUBLE, &v);
  H5Aclose(a);
  H5Sclose(sp);
}

static void h5_attr_s(hid_t loc, const char *name, const char *v) {
  hid_t sp = H5Screate(H5S_SCALAR), ty = H5Tcopy(H5T_C_S1);
  H5Tset_size(ty, strlen(v) + 1);
  hid_t a = H5Acreate2(loc, name, ty, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, ty, v);
  H5Aclose(a);
  H5Tclose(ty);
  H5Sclose(sp);
}

static void h5_ds(hid_t loc, const char *name, int rank, const hsize_t *dims, const double *d) {
  hid_t sp = H5Screate_simple(rank, dims, NULL);
  hid_t ds = H5Dcreate2(loc, name, H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d);
  H5Dclose(ds);
  H5Sclose(sp);
}

static int write_h5(cal_problem *p, const cal_result *r, const cal_stats *st, const char *dir,
                    double wall_s, const double *norm, dem_err *err) {
  const cal_config *c = p->cfg;
  char tmp[CAL_PATH_LEN], fin[CAL_PATH_LEN];
  snprintf(tmp, sizeof tmp, "%s/results.h5.tmp", dir);
  snprintf(fin, sizeof fin, "%s/results.h5", dir);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (f < 0) return dem_err_set(err, DEM_EIO, "cannot create '%s'", tmp);
  h5_attr_s(f, "name", c->name);
  h5_attr_s(f, "law", c->law->name);
  h5_attr_s(f, "config", c->path);
  h5_attr_d(f, "seed", (double)c->seed);
  h5_attr_d(f, "objective", r->f);
  h5_attr_d(f, "mean_relative_error", cal_mean_relative_error(p));
  h5_attr_d(f, "evaluations", (double)p->nevals);
  h5_attr_d(f, "wall_time_s", wall_s);
  h5_attr_s(f, "identifiability_warning", st->warning);
  hid_t g = H5Gcreate2(f, "parameters", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  for (int i = 0; i < c->nfree; i++) {
    hid_t q = H5Gcreate2(g, c->fr[i].name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    h5_attr_d(q, "value", r->x[i]);
    h5_attr_s(q, "unit", unit_of(c, c->fr[i].name));
    h5_attr_d(q, "std_error", st->ok ? st->se_x[i] : NAN);
    h5_attr_d(q, "ci95_lo", st->ok ? st->lo95[i] : NAN);
    h5_attr_d(q, "ci95_hi", st->ok ? st->hi95[i] : NAN);
    h5_attr_d(q, "min", c->fr[i].lo);
    h5_attr_d(q, "max", c->fr[i].hi);
    h5_attr_s(q, "scale", c->fr[i].scale == CAL_SCALE_LOG ? "log" : "linear");
    H5Gclose(q);
  }
  H5Gclose(g);
  hsize_t pp[2] = {(hsize_t)c->nfree, (hsize_t)c->nfree};
  if (st->ok) {
    h5_ds(f, "correlation", 2, pp, st->corr);
    h5_ds(f, "covariance_scaled", 2, pp, st->cov_u);
  }
  if (p->tr_n > 0) {
    hsize_t td[2] = {(hsize_t)p->tr_n, (hsize_t)(3 + c->nfree)};
    h5_ds(f, "trace", 2, td, p->tr);
  }
  g = H5Gcreate2(f, "targets", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  for (int i = 0; i < c->ntargets; i++) {
    const cal_target *t = &c->t[i];
    hid_t q = H5Gcreate2(g, t->name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    hsize_t n = (hsize_t)t->nres;
    double *re = malloc(sizeof(double) * n);
    if (re) {
      for (hsize_t k = 0; k < n; k++)
        re[k] = (p->model[t->off + k] - t->yr[k]) / norm[t->off + k];
      h5_ds(q, "x", 1, &n, t->xr);
      h5_ds(q, "reference", 1, &n, t->yr);
      h5_ds(q, "model", 1, &n, p->model + t->off);
      h5_ds(q, "relative_error", 1, &n, re);
      free(re);
    }
    h5_attr_s(q, "x_name", xname(t));
    h5_attr_s(q, "y_name", yname(t));
    h5_attr_d(q, "weight", t->weight);
    H5Gclose(q);
  }
  H5Gclose(g);
  if (H5Fclose(f) < 0) return dem_err_set(err, DEM_EIO, "error writing '%s'", tmp);
  if (rename(tmp, fin) != 0)
    return dem_err_set(err, DEM_EIO, "cannot rename '%s': %s", tmp, strerror(errno));
  return DEM_OK;
}

int cal_write_outputs(cal_problem *p, const cal_result *r, const cal_stats *st,
                      const char *dir, double wall_s, dem_err *err) {
  const cal_config *c = p->cfg;
  double *norm = malloc(sizeof(double) * (size_t)p->nres);
  if (!norm) return dem_err_set(err, DEM_ENOMEM, "out of memory");
  cal_residual_norms(c, norm);
  char tmp[CAL_PATH_LEN];
  int rc = DEM_OK;
  FILE *f = cal_tmp_open(dir, "best_params.txt", tmp, sizeof tmp, err);
  if (!f) rc = err ? err->code : DEM_EIO;
  if (!rc) {
    fprintf(f, "# %s: law %s, objective %.10g\n", c->name, c->law->name, r->f);
    for (int i = 0; i < c->nfree; i++) fprintf(f, "%s=%.10g\n", c->fr[i].name, r->x[i]);
    for (int i = 0; i < c->fixed.n; i++)
      fprintf(f, "%s=%.10g\n", c->fixed.p[i].key, c->fixed.p[i].value);
    rc = cal_commit(f, tmp, err);
  }
  if (!rc) rc = write_residual_tables(p, dir, norm, err);
  if (!rc) rc = write_summary(p, r, st, dir, wall_s, norm, err);
  if (!rc) rc = write_h5(p, r, st, dir, wall_s, norm, err);
  free(norm);
  return rc;
}
