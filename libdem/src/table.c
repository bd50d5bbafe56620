/* Tables of named columns with units, written to CSV or HDF5 (dem/table.h). */
#include "dem/table.h"

#include <errno.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define NAME_LEN 64
#define ATTR_MAX 32
#define ATTR_LEN 512

struct dem_table {
  int ncol;
  char name[DEM_TABLE_MAX_COLS][NAME_LEN];
  char unit[DEM_TABLE_MAX_COLS][NAME_LEN];
  long nrow, cap;
  double *v; /* row-major */
  int nattr;
  char akey[ATTR_MAX][NAME_LEN];
  char aval[ATTR_MAX][ATTR_LEN];
};

static int bad_name(const char *s) {
  size_t n = strlen(s);
  if (n == 0 || n >= NAME_LEN) return 1;
  for (; *s; s++)
    if (*s == ',' || *s == '/' || *s == '"' || *s == ' ' || *s == '\t' || *s == '\n' ||
        *s == '\r')
      return 1;
  return 0;
}

dem_table *dem_table_create(int ncol, const char *const *names, const char *const *units,
                            dem_err *err) {
  if (ncol < 1 || ncol > DEM_TABLE_MAX_COLS || !names) {
    dem_err_set(err, DEM_EINVAL, "table: %d columns (allowed 1 to %d)", ncol, DEM_TABLE_MAX_COLS);
    return NULL;
  }
  for (int j = 0; j < ncol; j++) {
    if (!names[j] || bad_name(names[j])) {
      dem_err_set(err, DEM_EINVAL,
                  "table: column %d name '%s' must have 1 to %d characters and no , / \" or "
                  "blanks",
                  j, names[j] ? names[j] : "(null)", NAME_LEN - 1);
      return NULL;
    }
    for (int i = 0; i < j; i++)
      if (strcmp(names[i], names[j]) == 0) {
        dem_err_set(err, DEM_EINVAL, "table: column name '%s' appears twice", names[j]);
        return NULL;
      }
  }
  dem_table *t = calloc(1, sizeof *t);
  if (!t) {
    dem_err_set(err, DEM_ENOMEM, "table: out of memory");
    return NULL;
  }
  t->ncol = ncol;
  for (int j = 0; j < ncol; j++) {
    snprintf(t->name[j], NAME_LEN, "%s", names[j]);
    snprintf(t->unit[j], NAME_LEN, "%s", (units && units[j]) ? units[j] : "-");
  }
  return t;
}

void dem_table_free(dem_table *t) {
  if (!t) return;
  free(t->v);
  free(t);
}

int dem_table_append(dem_table *t, const double *row, dem_err *err) {
  if (!t || !row) return dem_err_set(err, DEM_EINVAL, "table: NULL argument");
  if (t->nrow == t->cap) {
    long cap = t->cap ? 2 * t->cap : 256;
    double *v = realloc(t->v, sizeof(double) * (size_t)cap * (size_t)t->ncol);
    if (!v) return dem_err_set(err, DEM_ENOMEM, "table: out of memory at %ld rows", t->nrow);
    t->v = v;
    t->cap = cap;
  }
  memcpy(t->v + t->nrow * t->ncol, row, sizeof(double) * (size_t)t->ncol);
  t->nrow++;
  return DEM_OK;
}

int dem_table_set_attr(dem_table *t, const char *key, const char *value, dem_err *err) {
  if (!t || !key || !value) return dem_err_set(err, DEM_EINVAL, "table: NULL argument");
  if (bad_name(key))
    return dem_err_set(err, DEM_EINVAL, "table: attribute name '%s' is not allowed", key);
  if (strlen(value) >= ATTR_LEN || strchr(value, '\n'))
    return dem_err_set(err, DEM_EINVAL,
                       "table: attribute '%s' must be one line of fewer than %d characters", key,
                       ATTR_LEN);
  int i = 0;
  while (i < t->nattr && strcmp(t->akey[i], key) != 0) i++;
  if (i == t->nattr) {
    if (t->nattr == ATTR_MAX)
      return dem_err_set(err, DEM_ERANGE, "table: more than %d attributes", ATTR_MAX);
    t->nattr++;
  }
  snprintf(t->akey[i], NAME_LEN, "%s", key);
  snprintf(t->aval[i], ATTR_LEN, "%s", value);
  return DEM_OK;
}

long dem_table_nrows(const dem_table *t) { return t ? t->nrow : 0; }
int dem_table_ncols(const dem_table *t) { return t ? t->ncol : 0; }

int dem_table_col(const dem_table *t, const char *name) {
  for (int c = 0; t && name && c < t->ncol; c++)
    if (strcmp(t->name[c], name) == 0) return c;
  return -1;
}

double dem_table_get(const dem_table *t, long row, int col) {
  if (!t || row < 0 || row >= t->nrow || col < 0 || col >= t->ncol) return NAN;
  return t->v[row * t->ncol + col];
}

static void tmp_name(const char *path, char *buf, size_t n) {
  snprintf(buf, n, "%s.tmp%ld", path, (long)getpid());
}

static int commit(const char *tmp, const char *path, dem_err *err) {
  if (rename(tmp, path) != 0) {
    int e = errno;
    remove(tmp);
    return dem_err_set(err, DEM_EIO, "%s: cannot rename the finished temporary file: %s", path,
                       strerror(e));
  }
  return DEM_OK;
}

int dem_table_write_csv(const dem_table *t, const char *path, dem_err *err) {
  if (!t || !path) return dem_err_set(err, DEM_EINVAL, "table: NULL argument");
  char tmp[4096];
  tmp_name(path, tmp, sizeof tmp);
  FILE *f = fopen(tmp, "w");
  if (!f) return dem_err_set(err, DEM_EIO, "%s: cannot open for writing: %s", tmp, strerror(errno));
  for (int i = 0; i < t->nattr; i++) fprintf(f, "# %s: %s\n", t->akey[i], t->aval[i]);
  for (int j = 0; j < t->ncol; j++)
    fprintf(f, "%s%s [%s]", j ? "," : "", t->name[j], t->unit[j]);
  fputc('\n', f);
  for (long r = 0; r < t->nrow; r++) {
    const double *row = t->v + r * t->ncol;
    for (int j = 0; j < t->ncol; j++) fprintf(f, "%s%.12g", j ? "," : "", row[j]);
    fputc('\n', f);
  }
  int bad = ferror(f);
  if (fclose(f) != 0) bad = 1;
  if (bad) {
    remove(tmp);
    return dem_err_set(err, DEM_EIO, "%s: write error", path);
  }
  return commit(tmp, path, err);
}

/* A string attribute on an HDF5 object. */
static int h5_attr_str(hid_t obj, const char *key, const char *val) {
  hid_t type = H5Tcopy(H5T_C_S1);
  if (type < 0) return -1;
  H5Tset_size(type, strlen(val) + 1);
  H5Tset_strpad(type, H5T_STR_NULLTERM);
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t a = space >= 0 ? H5Acreate2(obj, key, type, space, H5P_DEFAULT, H5P_DEFAULT) : -1;
  herr_t rc = a >= 0 ? H5Awrite(a, type, val) : -1;
  if (a >= 0) H5Aclose(a);
  if (space >= 0) H5Sclose(space);
  H5Tclose(type);
  return rc < 0 ? -1 : 0;
}

int dem_table_write_hdf5(const dem_table *t, const char *path, dem_err *err) {
  if (!t || !path) return dem_err_set(err, DEM_EINVAL, "table: NULL argument");
  char tmp[4096];
  tmp_name(path, tmp, sizeof tmp);
  /* Silence HDF5's own error printing: the library reports through dem_err. */
  H5E_auto2_t old_fn;
  void *old_data;
  H5Eget_auto2(H5E_DEFAULT, &old_fn, &old_data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  int rc = DEM_OK;
  double *col = malloc(sizeof(double) * (size_t)(t->nrow > 0 ? t->nrow : 1));
  hid_t file = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (!col || file < 0) {
    rc = dem_err_set(err, col ? DEM_EIO : DEM_ENOMEM, "%s: cannot create HDF5 file", tmp);
    goto done;
  }
  for (int i = 0; i < t->nattr; i++)
    if (h5_attr_str(file, t->akey[i], t->aval[i]) < 0) {
      rc = dem_err_set(err, DEM_EIO, "%s: cannot write attribute '%s'", tmp, t->akey[i]);
      goto done;
    }
  hsize_t dims[1] = {(hsize_t)t->nrow};
  for (int j = 0; j < t->ncol; j++) {
    for (long r = 0; r < t->nrow; r++) col[r] = t->v[r * t->ncol + j];
    hid_t space = H5Screate_simple(1, dims, NULL);
    hid_t ds = space >= 0 ? H5Dcreate2(file, t->name[j], H5T_NATIVE_DOUBLE, space, H5P_DEFAULT,
                                       H5P_DEFAULT, H5P_DEFAULT)
                          : -1;
    herr_t w = ds >= 0 ? H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, col) : -1;
    int a = ds >= 0 ? h5_attr_str(ds, "unit", t->unit[j]) : -1;
    if (ds >= 0) H5Dclose(ds);
    if (space >= 0) H5Sclose(space);
    if (w < 0 || a < 0) {
      rc = dem_err_set(err, DEM_EIO, "%s: cannot write column '%s'", tmp, t->name[j]);
      goto done;
    }
  }
done:
  if (file >= 0 && H5Fclose(file) < 0 && rc == DEM_OK)
    rc = dem_err_set(err, DEM_EIO, "%s: cannot close HDF5 file", tmp);
  H5Eset_auto2(H5E_DEFAULT, old_fn, old_data);
  free(col);
  if (rc != DEM_OK) {
    remove(tmp);
    return rc;
  }
  return commit(tmp, path, err);
}

static int ends_with(const char *s, const char *suffix) {
  size_t n = strlen(s), m = strlen(suffix);
  return n >= m && strcmp(s + n - m, suffix) == 0;
}

int dem_table_write(const dem_table *t, const char *path, dem_err *err) {
  if (!path) return dem_err_set(err, DEM_EINVAL, "table: NULL path");
  if (ends_with(path, ".h5") || ends_with(path, ".hdf5")) return dem_table_write_hdf5(t, path, err);
  return dem_table_write_csv(t, path, err);
}

/* Each level is made in turn; EEXIST is fine at any level (a parent that is a file is caught
 * by the next level's ENOTDIR, the last level by the stat below). */
int dem_mkdirs(const char *dir, dem_err *err) {
  if (!dir || !*dir) return dem_err_set(err, DEM_EINVAL, "an empty folder name");
  size_t n = strlen(dir);
  if (n >= DEM_PATH_MAX)
    return dem_err_set(err, DEM_EINVAL, "a folder name of %zu characters (allowed up to %d)", n,
                       DEM_PATH_MAX - 1);
  char buf[DEM_PATH_MAX];
  memcpy(buf, dir, n + 1);
  for (char *p = buf + 1;; p++) {
    char ch = *p;
    if (ch == '/' || ch == '\0') {
      *p = '\0';
      if (mkdir(buf, 0777) != 0 && errno != EEXIST)
        return dem_err_set(err, DEM_EIO, "cannot create the folder '%s': %s", buf,
                           strerror(errno));
      *p = ch;
    }
    if (ch == '\0') break;
  }
  struct stat st;
  if (stat(buf, &st) != 0)
    return dem_err_set(err, DEM_EIO, "cannot create the folder '%s': %s", buf, strerror(errno));
  if (!S_ISDIR(st.st_mode))
    return dem_err_set(err, DEM_EIO, "cannot create the folder '%s': %s", buf,
                       strerror(ENOTDIR));
  if (access(buf, W_OK) != 0)
    return dem_err_set(err, DEM_EIO, "the folder '%s' is not writable: %s", buf,
                       strerror(errno));
  return DEM_OK;
}
