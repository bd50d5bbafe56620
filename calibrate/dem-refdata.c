/* dem-refdata: check the reference data tree (reference_data/CASE/{SOURCE.md,*.csv}).
 *
 *   dem-refdata --check DIR     validate every case folder of DIR; one line per folder and a
 *                               summary; exit status 1 if any folder fails, 2 on bad usage.
 *   dem-refdata --show FILE     load one CSV and print its columns (name, unit, SI factor)
 *                               and rows.
 */
#include <stdio.h>
#include <string.h>

#include "dem/error.h"
#include "dem/refdata.h"

typedef struct tally {
  int folders, failed, files, rows;
} tally;

static int check_one(const char *dir, const char *name, void *ud) {
  tally *t = ud;
  dem_err err = {0};
  int nfiles = 0, nrows = 0;
  t->folders++;
  if (dem_refdata_check_folder(dir, &nfiles, &nrows, &err) != DEM_OK) {
    t->failed++;
    printf("FAIL  %-32s %s\n", name, err.msg);
  } else {
    t->files += nfiles;
    t->rows += nrows;
    printf("ok    %-32s %d file%s, %d row%s\n", name, nfiles, nfiles == 1 ? "" : "s", nrows,
           nrows == 1 ? "" : "s");
  }
  return 0; /* keep going: report every folder */
}

static int check(const char *root) {
  tally t = {0};
  dem_err err = {0};
  if (dem_refdata_foreach_folder(root, check_one, &t, &err) != DEM_OK) {
    fprintf(stderr, "dem-refdata: %s\n", err.msg);
    return 1;
  }
  if (t.folders == 0) {
    fprintf(stderr, "dem-refdata: %s: no case folders\n", root);
    return 1;
  }
  printf("%d folder%s, %d failed; %d data files, %d rows checked\n", t.folders,
         t.folders == 1 ? "" : "s", t.failed, t.files, t.rows);
  return t.failed ? 1 : 0;
}

static int show(const char *path) {
  dem_err err = {0};
  dem_reftable *t = dem_refdata_load(path, NULL, 0, &err);
  if (!t) {
    fprintf(stderr, "dem-refdata: %s\n", err.msg);
    return 1;
  }
  printf("%s: %d columns, %d rows\n", t->path, t->ncols, t->nrows);
  for (int c = 0; c < t->ncols; c++) {
    double s = 1.0;
    dem_refdata_unit_scale(t->units[c], &s);
    printf("  %-28s [%s]  x %g -> SI\n", t->names[c], t->units[c], s);
  }
  for (int r = 0; r < t->nrows; r++) {
    for (int c = 0; c < t->ncols; c++)
      printf("%s%.10g", c ? "," : "", dem_refdata_value(t, r, c));
    printf("\n");
  }
  dem_refdata_free(t);
  return 0;
}

static void usage(FILE *f) {
  fprintf(f,
          "usage: dem-refdata --check DIR   validate every case folder of DIR\n"
          "       dem-refdata --show FILE   print one reference CSV with its units\n");
}

int main(int argc, char **argv) {
  if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
    usage(stdout);
    return 0;
  }
  if (argc == 3 && strcmp(argv[1], "--check") == 0) return check(argv[2]);
  if (argc == 3 && strcmp(argv[1], "--show") == 0) return show(argv[2]);
  usage(stderr);
  return 2;
}
