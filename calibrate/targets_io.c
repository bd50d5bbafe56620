/* Glue from target files to the project's CSV loader (dem/refdata.h, the `refdata` branch).
 * Until that loader is merged, target data must be given inline in the config. */
#include <stdlib.h>

#include "targets_io.h"

#ifdef CAL_HAVE_REFDATA
#include "dem/refdata.h"
#endif

int cal_target_read_file(const char *path, const char *xcol, const char *ycol, double **x,
                         double **y, int *n, dem_err *err) {
  *x = *y = NULL;
  *n = 0;
#ifdef CAL_HAVE_REFDATA
  dem_refcol req[2] = {{xcol, NULL}, {ycol, NULL}};
  dem_reftable *t = dem_refdata_load(path, req, 2, err);
  if (!t) return err ? err->code : DEM_EPARSE;
  *x = malloc(sizeof(double) * (size_t)t->nrows);
  *y = malloc(sizeof(double) * (size_t)t->nrows);
  int rc = (!*x || !*y) ? dem_err_set(err, DEM_ENOMEM, "out of memory") : DEM_OK;
  if (!rc) rc = dem_refdata_column_si(t, xcol, *x, err);
  if (!rc) rc = dem_refdata_column_si(t, ycol, *y, err);
  if (!rc) *n = t->nrows;
  dem_refdata_free(t);
  if (rc) {
    free(*x);
    free(*y);
    *x = *y = NULL;
  }
  return rc;
#else
  (void)xcol;
  (void)ycol;
  return dem_err_set(err, DEM_EUNSUPPORTED,
                     "cannot read '%s': target files need the CSV loader dem/refdata.h, which "
                     "is not merged yet; give the data inline",
                     path);
#endif
}
