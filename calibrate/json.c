/* The --json summary (jansson): one object with the best parameters, the objective, one
 * `residuals` entry per compared point with its `relative_error`, and `mean_relative_error`.
 * Non-finite numbers (e.g. a standard error without statistics) are written as null. */
#include <jansson.h>
#include <math.h>
#include <stdlib.h>

#include "cal.h"

static json_t *num(double v) { return isfinite(v) ? json_real(v) : json_null(); }

int cal_write_json(cal_problem *p, const cal_result *r, const cal_stats *st, FILE *out,
                   dem_err *err) {
  const cal_config *c = p->cfg;
  double *norm = malloc(sizeof(double) * (size_t)p->nres);
  if (!norm) return dem_err_set(err, DEM_ENOMEM, "out of memory");
  cal_residual_norms(c, norm);
  json_t *o = json_object(), *par = json_object(), *se = json_object(), *ci = json_object();
  json_t *res = json_array();
  json_object_set_new(o, "name", json_string(c->name));
  json_object_set_new(o, "law", json_string(c->law->name));
  for (int i = 0; i < c->nfree; i++) {
    json_object_set_new(par, c->fr[i].name, num(r->x[i]));
    json_object_set_new(se, c->fr[i].name, num(st->ok ? st->se_x[i] : NAN));
    json_t *iv = json_array();
    json_array_append_new(iv, num(st->ok ? st->lo95[i] : NAN));
    json_array_append_new(iv, num(st->ok ? st->hi95[i] : NAN));
    json_object_set_new(ci, c->fr[i].name, iv);
  }
  json_object_set_new(o, "parameters", par);
  json_object_set_new(o, "standard_errors", se);
  json_object_set_new(o, "ci95", ci);
  json_object_set_new(o, "objective", num(r->f));
  for (int i = 0; i < c->ntargets; i++) {
    const cal_target *t = &c->t[i];
    for (int k = 0; k < t->nres; k++) {
      int q = t->off + k;
      json_t *e = json_object();
      json_object_set_new(e, "target", json_string(t->name));
      json_object_set_new(e, "x", num(t->xr[k]));
      json_object_set_new(e, "reference", num(t->yr[k]));
      json_object_set_new(e, "model", num(p->model[q]));
      json_object_set_new(e, "relative_error", num((p->model[q] - t->yr[k]) / norm[q]));
      json_array_append_new(res, e);
    }
  }
  json_object_set_new(o, "residuals", res);
  json_object_set_new(o, "mean_relative_error", num(cal_mean_relative_error(p)));
  json_object_set_new(o, "evaluations", json_integer(p->nevals));
  json_object_set_new(o, "cached_evaluations", json_integer(p->ncached));
  json_object_set_new(o, "failed_evaluations", json_integer(p->nfailed));
  json_object_set_new(o, "interrupted", json_boolean(r->interrupted));
  json_object_set_new(o, "identifiability_warning", json_string(st->warning));
  free(norm);
  int rc = json_dumpf(o, out, JSON_INDENT(2) | JSON_REAL_PRECISION(12) | JSON_PRESERVE_ORDER);
  fputc('\n', out);
  json_decref(o);
  return rc ? dem_err_set(err, DEM_EIO, "cannot write the JSON summary") : DEM_OK;
}
