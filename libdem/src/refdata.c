/* Reference data tables and their SOURCE.md (dem/refdata.h). */
#include "dem/refdata.h"

#include <assert.h>
#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* ---- units ------------------------------------------------------------------------- */

static const struct {
  const char *unit;
  double si;
} units[] = {
    {"-", 1.0},      {"%", 0.01},      {"m", 1.0},       {"mm", 1e-3},     {"um", 1e-6},
    {"nm", 1e-9},    {"kg", 1.0},      {"kg/m^3", 1.0},  {"s", 1.0},       {"ms", 1e-3},
    {"us", 1e-6},    {"1/s", 1.0},     {"m/s", 1.0},     {"mm/s", 1e-3},   {"N", 1.0},
    {"mN", 1e-3},    {"uN", 1e-6},     {"nN", 1e-9},     {"N/m", 1.0},     {"kN/m", 1e3},
    {"MN/m", 1e6},   {"Pa", 1.0},      {"kPa", 1e3},     {"MPa", 1e6},     {"GPa", 1e9},
    {"J", 1.0},      {"J/m^2", 1.0},   {"mJ/m^2", 1e-3},
};

int dem_refdata_unit_scale(const char *unit, double *scale) {
  for (size_t i = 0; i < sizeof units / sizeof units[0]; i++)
    if (strcmp(units[i].unit, unit) == 0) {
      if (scale) *scale = units[i].si;
      return DEM_OK;
    }
  return DEM_ENOTFOUND;
}

/* ---- small helpers ----------------------------------------------------------------- */

/* Read a whole file into a NUL-terminated buffer. */
static char *slurp(const char *path, dem_err *err) {
  FILE *f = fopen(path, "rb");
  if (!f) {
    dem_err_set(err, DEM_EIO, "%s: cannot open: %s", path, strerror(errno));
    return NULL;
  }
  size_t cap = 4096, len = 0;
  char *buf = malloc(cap);
  while (buf) {
    size_t got = fread(buf + len, 1, cap - len - 1, f);
    len += got;
    if (len + 1 < cap) break;
    char *nb = realloc(buf, cap * 2);
    if (!nb) {
      free(buf);
      buf = NULL;
      break;
    }
    buf = nb;
    cap *= 2;
  }
  int bad = ferror(f);
  fclose(f);
  if (!buf) {
    dem_err_set(err, DEM_ENOMEM, "%s: out of memory while reading", path);
    return NULL;
  }
  if (bad) {
    free(buf);
    dem_err_set(err, DEM_EIO, "%s: read error", path);
    return NULL;
  }
  buf[len] = '\0';
  if (strlen(buf) != len) {
    free(buf);
    dem_err_set(err, DEM_EPARSE, "%s: contains a NUL byte (not a text file)", path);
    return NULL;
  }
  return buf;
}

/* Next line of *cursor (split in place at '\n', a trailing '\r' removed); NULL at the end.
 * A final newline does not start another (empty) line. */
static char *next_line(char **cursor) {
  char *s = *cursor;
  if (!s || *s == '\0') return NULL;
  char *nl = strchr(s, '\n');
  if (nl) {
    *nl = '\0';
    *cursor = nl + 1;
  } else {
    *cursor = s + strlen(s);
  }
  size_t n = strlen(s);
  if (n && s[n - 1] == '\r') s[n - 1] = '\0';
  return s;
}

/* Trim blanks at both ends, in place. */
static char *trim(char *s) {
  while (*s == ' ' || *s == '\t') s++;
  size_t n = strlen(s);
  while (n && (s[n - 1] == ' ' || s[n - 1] == '\t')) s[--n] = '\0';
  return s;
}

static int count_fields(const char *s) {
  int n = 1;
  for (; *s; s++)
    if (*s == ',') n++;
  return n;
}

/* Split s at commas into at most nmax trimmed fields; returns the number found. */
static int split(char *s, char **fields, int nmax) {
  int n = 0;
  char *p = s;
  while (n < nmax) {
    char *c = strchr(p, ',');
    if (c) *c = '\0';
    fields[n++] = trim(p);
    if (!c) break;
    p = c + 1;
  }
  return n;
}

static int is_identifier(const char *s) {
  if (!(isalpha((unsigned char)*s) || *s == '_')) return 0;
  for (s++; *s; s++)
    if (!(isalnum((unsigned char)*s) || *s == '_')) return 0;
  return 1;
}

/* Parse one header field "name [unit]" into t's column c. */
static int parse_header_field(dem_reftable *t, int c, char *field, dem_err *err) {
  const char *path = t->path;
  char *open = strchr(field, '[');
  char *close = open ? strchr(open, ']') : NULL;
  if (!open || !close || close[1] != '\0') {
    char *end = NULL;
    errno = 0;
    (void)strtod(field, &end);
    if (*field && end && *end == '\0')
      return dem_err_set(err, DEM_EPARSE,
                         "%s:1: missing header line: column %d holds the number '%s', "
                         "expected 'name [unit]'",
                         path, c + 1, field);
    return dem_err_set(err, DEM_EPARSE,
                       "%s:1: column %d header '%s' is not of the form 'name [unit]'", path,
                       c + 1, field);
  }
  *open = '\0';
  *close = '\0';
  char *name = trim(field), *unit = trim(open + 1);
  if (!is_identifier(name) || strlen(name) >= DEM_REFDATA_NAME_LEN)
    return dem_err_set(err, DEM_EPARSE,
                       "%s:1: column %d name '%s' must be an identifier of 1 to %d "
                       "characters ([A-Za-z_][A-Za-z0-9_]*)",
                       path, c + 1, name, DEM_REFDATA_NAME_LEN - 1);
  if (dem_refdata_unit_scale(unit, NULL) != DEM_OK || strlen(unit) >= DEM_REFDATA_UNIT_LEN)
    return dem_err_set(err, DEM_EPARSE,
                       "%s:1: column '%s' has unknown unit '[%s]' (write units in ASCII, e.g. "
                       "[um], [uN], [kg/m^3], [-]; see dem_refdata_unit_scale)",
                       path, name, unit);
  for (int k = 0; k < c; k++)
    if (strcmp(t->names[k], name) == 0)
      return dem_err_set(err, DEM_EPARSE, "%s:1: column '%s' appears twice (columns %d and %d)",
                         path, name, k + 1, c + 1);
  memcpy(t->names[c], name, strlen(name) + 1);
  memcpy(t->units[c], unit, strlen(unit) + 1);
  return DEM_OK;
}

/* Parse one numeric field at (line, col). */
static int parse_value(const dem_reftable *t, int line, int c, const char *text, double *v,
                       dem_err *err) {
  if (*text == '\0')
    return dem_err_set(err, DEM_EPARSE, "%s:%d: column '%s' [%s]: empty field", t->path, line,
                       t->names[c], t->units[c]);
  char *end = NULL;
  errno = 0;
  double x = strtod(text, &end);
  if (end == text || *end != '\0')
    return dem_err_set(err, DEM_EPARSE, "%s:%d: column '%s' [%s]: '%s' is not a number",
                       t->path, line, t->names[c], t->units[c], text);
  if (!isfinite(x) || (errno == ERANGE && fabs(x) == HUGE_VAL))
    return dem_err_set(err, DEM_ENONFINITE,
                       "%s:%d: column '%s' [%s]: '%s' is not a finite number", t->path, line,
                       t->names[c], t->units[c], text);
  *v = x;
  return DEM_OK;
}

/* ---- tables ------------------------------------------------------------------------ */

void dem_refdata_free(dem_reftable *t) {
  if (!t) return;
  free(t->names);
  free(t->units);
  free(t->data);
  free(t);
}

static int check_required(const dem_reftable *t, const dem_refcol *req, int nreq,
                          dem_err *err) {
  if (!req) nreq = 0;
  for (int i = 0; i < nreq; i++) {
    int c = dem_refdata_column(t, req[i].name);
    if (c < 0) {
      char have[256] = "";
      size_t used = 0;
      for (int k = 0; k < t->ncols && used + 1 < sizeof have; k++) {
        int w = snprintf(have + used, sizeof have - used, "%s%s", k ? ", " : "", t->names[k]);
        if (w < 0) break;
        used += (size_t)w;
      }
      return dem_err_set(err, DEM_EMISSING, "%s:1: required column '%s' is missing (has: %s)",
                         t->path, req[i].name, have);
    }
    if (req[i].unit && strcmp(req[i].unit, t->units[c]) != 0)
      return dem_err_set(err, DEM_EINVAL, "%s:1: column '%s' has unit [%s], expected [%s]",
                         t->path, req[i].name, t->units[c], req[i].unit);
  }
  return DEM_OK;
}

dem_reftable *dem_refdata_load(const char *path, const dem_refcol *required, int nrequired,
                               dem_err *err) {
  if (!path || strlen(path) >= DEM_REFDATA_PATH_LEN) {
    dem_err_set(err, DEM_EINVAL, "reference file path missing or longer than %d characters",
                DEM_REFDATA_PATH_LEN - 1);
    return NULL;
  }
  char *buf = slurp(path, err);
  if (!buf) return NULL;
  dem_reftable *t = calloc(1, sizeof *t);
  char **fields = NULL;
  int rc = DEM_OK;
  if (!t) {
    rc = dem_err_set(err, DEM_ENOMEM, "%s: out of memory", path);
    goto done;
  }
  memcpy(t->path, path, strlen(path) + 1);

  char *cursor = buf;
  char *line = next_line(&cursor);
  if (!line || *trim(line) == '\0') {
    rc = dem_err_set(err, DEM_EPARSE, "%s:1: missing header line (%s)", path,
                     line ? "first line is empty" : "file is empty");
    goto done;
  }
  t->ncols = count_fields(line);
  t->names = calloc((size_t)t->ncols, sizeof *t->names);
  t->units = calloc((size_t)t->ncols, sizeof *t->units);
  fields = calloc((size_t)t->ncols, sizeof *fields);
  if (!t->names || !t->units || !fields) {
    rc = dem_err_set(err, DEM_ENOMEM, "%s: out of memory", path);
    goto done;
  }
  split(line, fields, t->ncols);
  for (int c = 0; c < t->ncols && rc == DEM_OK; c++)
    rc = parse_header_field(t, c, fields[c], err);
  if (rc) goto done;

  size_t cap = 16;
  t->data = malloc(cap * (size_t)t->ncols * sizeof *t->data);
  if (!t->data) {
    rc = dem_err_set(err, DEM_ENOMEM, "%s: out of memory", path);
    goto done;
  }
  int lineno = 1;
  while ((line = next_line(&cursor)) != NULL) {
    lineno++;
    if (*trim(line) == '\0') {
      rc = dem_err_set(err, DEM_EPARSE, "%s:%d: empty line (expected %d fields)", path, lineno,
                       t->ncols);
      goto done;
    }
    int n = count_fields(line);
    if (n != t->ncols) {
      rc = dem_err_set(err, DEM_EPARSE, "%s:%d: row has %d fields, the header has %d", path,
                       lineno, n, t->ncols);
      goto done;
    }
    if ((size_t)t->nrows == cap) {
      double *nd = realloc(t->data, 2 * cap * (size_t)t->ncols * sizeof *nd);
      if (!nd) {
        rc = dem_err_set(err, DEM_ENOMEM, "%s: out of memory", path);
        goto done;
      }
      t->data = nd;
      cap *= 2;
    }
    split(line, fields, t->ncols);
    double *row = t->data + (size_t)t->nrows * (size_t)t->ncols;
    for (int c = 0; c < t->ncols; c++) {
      rc = parse_value(t, lineno, c, fields[c], &row[c], err);
      if (rc) goto done;
    }
    t->nrows++;
  }
  if (t->nrows == 0) {
    rc = dem_err_set(err, DEM_EMISSING, "%s:2: no data rows after the header", path);
    goto done;
  }
  rc = check_required(t, required, nrequired, err);

done:
  free(fields);
  free(buf);
  if (rc) {
    dem_refdata_free(t);
    return NULL;
  }
  return t;
}

int dem_refdata_column(const dem_reftable *t, const char *name) {
  for (int c = 0; c < t->ncols; c++)
    if (strcmp(t->names[c], name) == 0) return c;
  return -1;
}

double dem_refdata_value(const dem_reftable *t, int row, int col) {
  assert(row >= 0 && row < t->nrows && col >= 0 && col < t->ncols);
  return t->data[(size_t)row * (size_t)t->ncols + (size_t)col];
}

int dem_refdata_column_si(const dem_reftable *t, const char *name, double *out, dem_err *err) {
  int c = dem_refdata_column(t, name);
  if (c < 0) return dem_err_set(err, DEM_EMISSING, "%s: no column '%s'", t->path, name);
  double s = 1.0;
  if (dem_refdata_unit_scale(t->units[c], &s) != DEM_OK) /* cannot happen after load */
    return dem_err_set(err, DEM_EINVAL, "%s: column '%s' has unknown unit [%s]", t->path, name,
                       t->units[c]);
  for (int r = 0; r < t->nrows; r++) out[r] = s * dem_refdata_value(t, r, c);
  return DEM_OK;
}

/* ---- folders ----------------------------------------------------------------------- */

typedef struct namelist {
  char **v;
  int n, cap;
} namelist;

static void namelist_free(namelist *l) {
  for (int i = 0; i < l->n; i++) free(l->v[i]);
  free(l->v);
  l->v = NULL;
  l->n = l->cap = 0;
}

static int cmp_names(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Entries of dir that are directories (want_dirs) or regular files ending in ".csv". */
static int list_dir(const char *dir, int want_dirs, namelist *out, dem_err *err) {
  DIR *d = opendir(dir);
  if (!d) return dem_err_set(err, DEM_EIO, "%s: cannot open folder: %s", dir, strerror(errno));
  struct dirent *e;
  int rc = DEM_OK;
  while ((e = readdir(d)) != NULL) {
    if (e->d_name[0] == '.') continue;
    char full[DEM_REFDATA_PATH_LEN];
    if (snprintf(full, sizeof full, "%s/%s", dir, e->d_name) >= (int)sizeof full) continue;
    struct stat st;
    if (stat(full, &st) != 0) continue;
    size_t len = strlen(e->d_name);
    int keep = want_dirs ? S_ISDIR(st.st_mode)
                         : (S_ISREG(st.st_mode) && len > 4 &&
                            strcmp(e->d_name + len - 4, ".csv") == 0);
    if (!keep) continue;
    if (out->n == out->cap) {
      int nc = out->cap ? 2 * out->cap : 16;
      char **nv = realloc(out->v, (size_t)nc * sizeof *nv);
      if (!nv) {
        rc = dem_err_set(err, DEM_ENOMEM, "%s: out of memory", dir);
        break;
      }
      out->v = nv;
      out->cap = nc;
    }
    out->v[out->n] = malloc(len + 1);
    if (!out->v[out->n]) {
      rc = dem_err_set(err, DEM_ENOMEM, "%s: out of memory", dir);
      break;
    }
    memcpy(out->v[out->n++], e->d_name, len + 1);
  }
  closedir(d);
  if (rc) {
    namelist_free(out);
    return rc;
  }
  if (out->n > 1) qsort(out->v, (size_t)out->n, sizeof *out->v, cmp_names);
  return DEM_OK;
}

int dem_refdata_foreach_folder(const char *root, dem_refdata_folder_fn fn, void *ud,
                               dem_err *err) {
  namelist l = {0};
  int rc = list_dir(root, 1, &l, err);
  if (rc) return rc;
  for (int i = 0; i < l.n && rc == 0; i++) {
    char dir[DEM_REFDATA_PATH_LEN];
    snprintf(dir, sizeof dir, "%s/%s", root, l.v[i]);
    rc = fn(dir, l.v[i], ud);
  }
  namelist_free(&l);
  return rc;
}

static const char *const source_sections[] = {"Citation", "Location",      "Files",
                                              "Units",    "Transcription", "Tolerance"};
#define NSECTIONS ((int)(sizeof source_sections / sizeof source_sections[0]))

int dem_refdata_check_source(const char *dir, dem_err *err_out) {
  dem_err local = {0};
  dem_err *err = err_out ? err_out : &local;
  char path[DEM_REFDATA_PATH_LEN];
  if (snprintf(path, sizeof path, "%s/SOURCE.md", dir) >= (int)sizeof path)
    return dem_err_set(err, DEM_EINVAL, "%s: path too long", dir);
  char *buf = slurp(path, err);
  if (!buf) return err->code;
  char *text = strdup(buf); /* unsplit copy, to look for the file names */
  if (!text) {
    free(buf);
    return dem_err_set(err, DEM_ENOMEM, "%s: out of memory", path);
  }
  int line_of[NSECTIONS] = {0}, body[NSECTIONS] = {0};
  int title = 0, lineno = 0, cur = -1, rc = DEM_OK;
  char *cursor = buf, *line;
  while ((line = next_line(&cursor)) != NULL) {
    lineno++;
    if (strncmp(line, "# ", 2) == 0) {
      title = 1;
      cur = -1;
    } else if (strncmp(line, "## ", 3) == 0) {
      cur = -1;
      const char *h = trim(line + 3);
      for (int k = 0; k < NSECTIONS; k++)
        if (strcmp(h, source_sections[k]) == 0) {
          if (line_of[k]) {
            rc = dem_err_set(err, DEM_EPARSE, "%s:%d: section '## %s' repeats line %d", path,
                             lineno, h, line_of[k]);
            goto done;
          }
          line_of[k] = lineno;
          cur = k;
        }
    } else if (cur >= 0 && *trim(line) != '\0') {
      body[cur] = 1;
    }
  }
  if (!title) {
    rc = dem_err_set(err, DEM_EPARSE, "%s:1: missing '# ' title line", path);
    goto done;
  }
  for (int k = 0; k < NSECTIONS; k++) {
    if (!line_of[k]) {
      rc = dem_err_set(err, DEM_EMISSING, "%s: missing section '## %s'", path,
                       source_sections[k]);
      goto done;
    }
    if (!body[k]) {
      rc = dem_err_set(err, DEM_EMISSING, "%s:%d: section '## %s' is empty", path, line_of[k],
                       source_sections[k]);
      goto done;
    }
  }
  namelist csv = {0};
  rc = list_dir(dir, 0, &csv, err);
  if (rc) goto done;
  for (int i = 0; i < csv.n && rc == DEM_OK; i++)
    if (!strstr(text, csv.v[i]))
      rc = dem_err_set(err, DEM_EMISSING, "%s: data file '%s' is not described", path,
                       csv.v[i]);
  namelist_free(&csv);
done:
  free(text);
  free(buf);
  return rc;
}

int dem_refdata_check_folder(const char *dir, int *nfiles, int *nrows, dem_err *err_out) {
  dem_err local = {0};
  dem_err *err = err_out ? err_out : &local;
  int rc = dem_refdata_check_source(dir, err);
  if (rc) return rc;
  namelist csv = {0};
  rc = list_dir(dir, 0, &csv, err);
  if (rc) return rc;
  if (csv.n == 0) rc = dem_err_set(err, DEM_EMISSING, "%s: no .csv data file", dir);
  int rows = 0;
  for (int i = 0; i < csv.n && rc == DEM_OK; i++) {
    char path[DEM_REFDATA_PATH_LEN];
    if (snprintf(path, sizeof path, "%s/%s", dir, csv.v[i]) >= (int)sizeof path) {
      rc = dem_err_set(err, DEM_EINVAL, "%s/%s: path too long", dir, csv.v[i]);
      break;
    }
    dem_reftable *t = dem_refdata_load(path, NULL, 0, err);
    if (!t) {
      rc = err->code ? err->code : DEM_EPARSE;
      break;
    }
    rows += t->nrows;
    dem_refdata_free(t);
  }
  if (rc == DEM_OK) {
    if (nfiles) *nfiles = csv.n;
    if (nrows) *nrows = rows;
  }
  namelist_free(&csv);
  return rc;
}
