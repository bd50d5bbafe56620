/* Glue from target files to the project's CSV loader (dem/refdata.h, the `refdata` branch).
 * Until that loader is merged, target data must be given inline in the config. */
#include <stdlib.h>

#include "targets_io.h"

#ifdef CAL_HAVE_REFDATA
#include "dem/refdata.h"
#endif

int cal_target_read_file(const char *path, const char *const *cols, int ncol, double **out,
                         int *n, dem_err *err) {
  *n = 0;
  for (int k = 0; k < ncol; k++) out[k] = NULL;
#ifdef CAL_HAVE_REFDATA
  dem_refcol req[4] = {{NULL, NULL}, {NULL, NULL}, {NULL, NULL}, {NULL, NULL}};
  if (ncol > 4) return dem_err_set(err, DEM_EINVAL, "at most 4 columns");
  for (int k = 0; k < ncol; k++) {
    req[k].name = cols[k];
    req[k].unit = NULL;
  }
  dem_reftable *t = dem_refdata_load(path, req, ncol, err);
  if (!t) return err ? err->code : DEM_EPARSE;
  int rc = DEM_OK;
  for (int k = 0; k < ncol && !rc; k++) {
    out[k] = malloc(sizeof(double) * (size_t)t->nrows);
    if (!out[k])
      rc = dem_err_set(err, DEM_ENOMEM, "out of memory");
    else
      rc = dem_refdata_column_si(t, cols[k], out[k], err);
  }
  if (!rc) *n = t->nrows;
  dem_refdata_free(t);
  if (rc)
    for (int k = 0; k < ncol; k++) {
      free(out[k]);
      out[k] = NULL;
    }
  return rc;
#else
  (void)cols;
  (void)ncol;
  return dem_err_set(err, DEM_EUNSUPPORTED,
                     "cannot read '%s': target files need the CSV loader dem/refdata.h, which "
                     "is not merged yet; give the data inline",
                     path);
#endif
}
