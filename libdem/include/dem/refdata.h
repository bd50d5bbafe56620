/* dem/refdata.h — reference data tables (reference_data/CASE/NAME.csv) and their SOURCE.md.
 *
 * A reference file is a plain CSV table of numbers (no quoting, no comments):
 *
 *     R [um],v_s_jkr [m/s],v_stick [m/s]        <- header: one `name [unit]` per column
 *     3.445,0.49,1.18                           <- rows: the same number of fields,
 *     2.45,0.66,1.96                               every field a finite C floating literal
 *
 * Column names are C identifiers ([A-Za-z_][A-Za-z0-9_]*); the unit is written in ASCII
 * ("um", "uN", "kg/m^3", "J/m^2", "-" for dimensionless) and must be one that
 * dem_refdata_unit_scale() knows, so every value can be converted to SI. Values are stored
 * in the units of the header (the units of the printed source table, so that a transcription
 * can be checked against the source by eye); convert with dem_refdata_column_si().
 * The convention is described for humans in reference_data/README.md.
 *
 * Every case folder also holds a SOURCE.md with a `# ` title and the sections
 * `## Citation`, `## Location`, `## Files`, `## Units`, `## Transcription`, `## Tolerance`
 * (each non-empty), and names every CSV file of the folder.
 *
 * Errors name the file and line (and the column and the offending text); nothing is printed.
 */
#ifndef DEM_REFDATA_H
#define DEM_REFDATA_H

#include "dem/error.h"

#define DEM_REFDATA_NAME_LEN 48 /* longest column name + 1 */
#define DEM_REFDATA_UNIT_LEN 16 /* longest unit + 1 */
#define DEM_REFDATA_PATH_LEN 512

/* A column a caller requires: name and unit exactly as in the header (unit NULL: any). */
typedef struct dem_refcol {
  const char *name;
  const char *unit;
} dem_refcol;

/* A loaded table. data is row-major: value of row r, column c = data[r * ncols + c],
 * in the unit of the column's header. */
typedef struct dem_reftable {
  char path[DEM_REFDATA_PATH_LEN];
  int ncols, nrows;
  char (*names)[DEM_REFDATA_NAME_LEN];
  char (*units)[DEM_REFDATA_UNIT_LEN];
  double *data;
} dem_reftable;

/* Load and validate a reference CSV file: header present and well-formed, known units,
 * unique names, at least one row, every row with as many fields as the header, every
 * field a finite number, and each of the `nrequired` columns in `required` present with its
 * unit. Returns NULL on failure with err set (DEM_EIO, DEM_EPARSE, DEM_ENONFINITE,
 * DEM_EMISSING, DEM_EINVAL or DEM_ENOMEM); the message starts with "path:line: ". */
dem_reftable *dem_refdata_load(const char *path, const dem_refcol *required, int nrequired,
                               dem_err *err);
void dem_refdata_free(dem_reftable *t);

/* Index of a column, or -1. */
int dem_refdata_column(const dem_reftable *t, const char *name);
/* Value at (row, col) in the header's unit; no bounds check beyond an assert. */
double dem_refdata_value(const dem_reftable *t, int row, int col);
/* Copy the nrows values of column `name` into out[], converted to SI. */
int dem_refdata_column_si(const dem_reftable *t, const char *name, double *out, dem_err *err);

/* SI factor of a unit ("uN" -> 1e-6, "%" -> 0.01, "-" -> 1). DEM_OK, or DEM_ENOTFOUND. */
int dem_refdata_unit_scale(const char *unit, double *scale);

/* Check dir/SOURCE.md: title, the required sections (non-empty), every dir/ *.csv named. */
int dem_refdata_check_source(const char *dir, dem_err *err);
/* Check a case folder: SOURCE.md, then load every *.csv (at least one). On success the
 * number of CSV files and of data rows are returned through nfiles/nrows (may be NULL). */
int dem_refdata_check_folder(const char *dir, int *nfiles, int *nrows, dem_err *err);

/* Call fn(path_of_folder, folder_name, ud) for every sub-folder of root (names not starting
 * with '.'), in alphabetical order. A non-zero return of fn stops the walk and is returned.
 * Returns DEM_EIO (with err) if root cannot be read. */
typedef int (*dem_refdata_folder_fn)(const char *dir, const char *name, void *ud);
int dem_refdata_foreach_folder(const char *root, dem_refdata_folder_fn fn, void *ud,
                               dem_err *err);

#endif
