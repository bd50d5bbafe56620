/* calibrate/targets_io.h — reading a target's two columns from a reference-data file.
 * The file format and its validation (columns, units, finite numbers, file:line errors)
 * belong to the project's CSV loader, dem/refdata.h; this is only the glue to it. */
#ifndef CAL_TARGETS_IO_H
#define CAL_TARGETS_IO_H

#include "dem/error.h"

/* The ncol named columns of the file as malloc'd arrays out[0..ncol-1] of *n values each,
 * converted to SI units. */
int cal_target_read_file(const char *path, const char *const *cols, int ncol, double **out,
                         int *n, dem_err *err);

#endif
