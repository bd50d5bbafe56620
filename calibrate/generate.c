/* Generated reference curves: a curve target with `reference_law` gets its reference from a
 * normal impact of that law at `v_impact` (dem_impact_run with a trace), e.g. the
 * `thornton-ning` force-overlap curves at 2, 5 and 10 m/s of issue 4. The rate-independent
 * force f_el is kept (the calibrated law is driven quasi-statically along the same overlap
 * path), subsampled to about `samples` points evenly spaced in path length, always keeping
 * the largest overlap and the last point. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cal.h"

int cal_generate_reference(const cal_config *c, cal_target *t, dem_err *err) {
  (void)c;
#ifndef CAL_HAVE_IMPACT
  (void)t;
  return dem_err_set(err, DEM_EUNSUPPORTED,
                     "generated curves need the impact solver (dem/impact.h, `impact` branch), "
                     "not merged yet");
#else
  const dem_law *law = dem_contact_law_find(t->gen_law);
  if (!law) return dem_err_set(err, DEM_ENOTFOUND, "unknown law '%s'", t->gen_law);
  dem_impact_scene sc;
  int rc = dem_impact_setup(&sc, law, &t->gen_set, t->pair ? DEM_TARGET_PAIR : DEM_TARGET_WALL, err);
  if (rc) return rc;
  dem_impact_opts o = c->impact;
  FILE *tr = tmpfile();
  if (!tr) return dem_err_set(err, DEM_EIO, "cannot create a temporary file");
  o.trace = tr;
  o.trace_every = 1;
  dem_impact_result res;
  rc = dem_impact_run(&sc, &o, t->gen_v, &res, err);
  if (rc) {
    fclose(tr);
    return rc;
  }
  rewind(tr);
  long cap = 1 << 16, n = 0;
  double *a = malloc(sizeof(double) * (size_t)cap), *f = malloc(sizeof(double) * (size_t)cap);
  char line[512];
  if (!fgets(line, sizeof line, tr)) line[0] = '\0'; /* header */
  while (a && f && fgets(line, sizeof line, tr)) {
    double tt, al, ad, ft, fe, fd;
    if (sscanf(line, "%lf,%lf,%lf,%lf,%lf,%lf", &tt, &al, &ad, &ft, &fe, &fd) != 6) continue;
    if (n == cap) {
      cap *= 2;
      double *na = realloc(a, sizeof(double) * (size_t)cap), *nf = NULL;
      if (na) a = na;
      if (na) nf = realloc(f, sizeof(double) * (size_t)cap);
      if (!na || !nf) {
        free(na ? a : NULL);
        a = NULL;
        break;
      }
      f = nf;
    }
    a[n] = al;
    f[n++] = fe;
  }
  fclose(tr);
  if (!a || !f) {
    free(a);
    free(f);
    return dem_err_set(err, DEM_ENOMEM, "out of memory");
  }
  if (n < 2) {
    free(a);
    free(f);
    return dem_err_set(err, DEM_EINVAL, "the %s impact at %g m/s gave %ld trace rows", t->gen_law,
                       t->gen_v, n);
  }
  /* subsample evenly in path length (|d alpha|), keeping the turning point */
  double len = 0.0;
  long kmax = 0;
  for (long k = 1; k < n; k++) {
    len += fabs(a[k] - a[k - 1]);
    if (a[k] > a[kmax]) kmax = k;
  }
  int want = t->gen_samples;
  t->x = malloc(sizeof(double) * (size_t)(want + 3));
  t->y = malloc(sizeof(double) * (size_t)(want + 3));
  if (!t->x || !t->y) {
    free(a);
    free(f);
    return dem_err_set(err, DEM_ENOMEM, "out of memory");
  }
  int m = 0;
  double s = 0.0, next = 0.0, ds = len / want;
  for (long k = 0; k < n && m < want + 2; k++) {
    if (k > 0) s += fabs(a[k] - a[k - 1]);
    if (k == 0 || k == kmax || k == n - 1 || s >= next) {
      t->x[m] = a[k];
      t->y[m++] = f[k];
      while (next <= s) next += ds;
    }
  }
  t->n = m;
  free(a);
  free(f);
  return DEM_OK;
#endif
}
