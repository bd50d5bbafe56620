/* dem/table.h — small tables of named columns with units, written to CSV or HDF5.
 *
 * A table is an opaque handle (create / append / write / free). Writing always goes to a
 * temporary file next to the target, renamed over it only when complete: an error never
 * leaves a half-written file and never destroys a file written before.
 *
 * CSV:  "# key: value" lines for the attributes, then one header line "name [unit],...",
 *       then the rows (%.12g).
 * HDF5: one 1-D double dataset per column, named by the column, with a string attribute
 *       "unit"; the table's attributes as string attributes of the root group.
 * HDF5 types stay inside table.c.
 */
#ifndef DEM_TABLE_H
#define DEM_TABLE_H

#include "dem/error.h"

#define DEM_TABLE_MAX_COLS 32

typedef struct dem_table dem_table;

/* ncol names and units (units may be NULL: all "-"). Names: 1-63 characters, none of
 * , / " or whitespace. NULL on failure (message in err). */
dem_table *dem_table_create(int ncol, const char *const *names, const char *const *units,
                            dem_err *err);
void dem_table_free(dem_table *t);
/* Append one row of ncol values (non-finite values are written as nan/inf). */
int dem_table_append(dem_table *t, const double *row, dem_err *err);
/* A text attribute (metadata: law, parameters, command). Overwrites a key already set. */
int dem_table_set_attr(dem_table *t, const char *key, const char *value, dem_err *err);
long dem_table_nrows(const dem_table *t);
int dem_table_ncols(const dem_table *t);
/* Index of the column named `name`, or -1 if there is none (consumers find columns by name,
 * so that columns appended later do not break them). */
int dem_table_col(const dem_table *t, const char *name);
/* Value at (row, col); NAN outside the table. */
double dem_table_get(const dem_table *t, long row, int col);

int dem_table_write_csv(const dem_table *t, const char *path, dem_err *err);
int dem_table_write_hdf5(const dem_table *t, const char *path, dem_err *err);
/* By extension: .h5 / .hdf5 -> HDF5, anything else -> CSV. */
int dem_table_write(const dem_table *t, const char *path, dem_err *err);

/* mkdir -p: create dir and every missing parent (mode 0777 less the umask). DEM_OK when dir
 * ends up an existing, writable folder; DEM_EIO naming the level that failed and why
 * ("cannot create the folder 'a/b': Not a directory"); DEM_EINVAL for an empty path or one
 * of DEM_PATH_MAX characters or more. The one folder-making routine of every program. */
#define DEM_PATH_MAX 4096
int dem_mkdirs(const char *dir, dem_err *err);

#endif
