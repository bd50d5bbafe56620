/* The evaluation cache: an append-only text file, one line per evaluation,
 *
 *   <u_0> ... <u_{d-1}> <S> <checksum>
 *
 * with the scaled parameters and the objective as C99 hexadecimal floats (%a: exact), and an
 * FNV-1a checksum of the rest of the line. The first line names the format, the config hash
 * and the dimension. Each line is flushed as soon as the evaluation ends, so a SIGINT, a
 * SIGTERM or a kill -9 loses at most the evaluation in progress; on --resume a truncated or
 * damaged last line is dropped (and cut off the file before appending). Keys are the exact
 * bit patterns of u: the optimiser, being deterministic, asks for the same vectors again and
 * gets the same answers, so a resumed run retraces the interrupted one and reaches the same
 * optimum with fewer new evaluations. */
#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cal.h"

#define CACHE_MAGIC "# dem-calibrate evaluation cache v1"

typedef struct entry {
  double u[CAL_MAX_FREE];
  double f;
  int used;
} entry;

struct cal_cache {
  FILE *f;
  int dim;
  entry *tab;
  long cap, n;
};

static uint64_t fnv_bytes(uint64_t h, const void *p, size_t n) {
  const unsigned char *b = p;
  for (size_t i = 0; i < n; i++) {
    h ^= b[i];
    h *= 1099511628211ULL;
  }
  return h;
}

static uint64_t key_hash(const double *u, int dim) {
  return fnv_bytes(1469598103934665603ULL, u, sizeof(double) * (size_t)dim);
}

static int insert(cal_cache *cc, const double *u, double f);

static int grow(cal_cache *cc) {
  long ncap = cc->cap ? 2 * cc->cap : 1024;
  entry *old = cc->tab;
  long ocap = cc->cap;
  cc->tab = calloc((size_t)ncap, sizeof(entry));
  if (!cc->tab) {
    cc->tab = old;
    return DEM_ENOMEM;
  }
  cc->cap = ncap;
  cc->n = 0;
  for (long i = 0; i < ocap; i++)
    if (old[i].used) insert(cc, old[i].u, old[i].f);
  free(old);
  return DEM_OK;
}

static int insert(cal_cache *cc, const double *u, double f) {
  if (2 * (cc->n + 1) > cc->cap && grow(cc)) return DEM_ENOMEM;
  size_t bytes = sizeof(double) * (size_t)cc->dim;
  long i = (long)(key_hash(u, cc->dim) & (uint64_t)(cc->cap - 1));
  while (cc->tab[i].used) {
    if (memcmp(cc->tab[i].u, u, bytes) == 0) {
      cc->tab[i].f = f;
      return DEM_OK;
    }
    i = (i + 1) & (cc->cap - 1);
  }
  memcpy(cc->tab[i].u, u, bytes);
  cc->tab[i].f = f;
  cc->tab[i].used = 1;
  cc->n++;
  return DEM_OK;
}

int cal_cache_lookup(const cal_cache *cc, const double *u, double *f) {
  if (!cc->cap) return 0;
  size_t bytes = sizeof(double) * (size_t)cc->dim;
  long i = (long)(key_hash(u, cc->dim) & (uint64_t)(cc->cap - 1));
  while (cc->tab[i].used) {
    if (memcmp(cc->tab[i].u, u, bytes) == 0) {
      *f = cc->tab[i].f;
      return 1;
    }
    i = (i + 1) & (cc->cap - 1);
  }
  return 0;
}

/* Parse one complete line (without its newline); 1 if valid. */
static int parse_line(const char *line, int dim, double *u, double *f) {
  const char *last = strrchr(line, ' ');
  if (!last) return 0;
  char *end;
  uint64_t sum = strtoull(last + 1, &end, 16);
  if (end == last + 1 || *end) return 0;
  if (fnv_bytes(1469598103934665603ULL, line, (size_t)(last - line)) != sum) return 0;
  const char *p = line;
  for (int i = 0; i <= dim; i++) {
    double v = strtod(p, &end);
    if (end == p) return 0;
    if (i < dim)
      u[i] = v;
    else
      *f = v;
    p = end;
  }
  return p == last;
}

cal_cache *cal_cache_open(const char *path, unsigned long long hash, int dim, int resume,
                          dem_err *err) {
  cal_cache *cc = calloc(1, sizeof *cc);
  if (!cc) {
    dem_err_set(err, DEM_ENOMEM, "out of memory");
    return NULL;
  }
  cc->dim = dim;
  char header[128];
  snprintf(header, sizeof header, CACHE_MAGIC " hash=%016llx dim=%d", hash, dim);
  long keep = 0; /* bytes of the file that are complete, valid lines */
  FILE *in = resume ? fopen(path, "rb") : NULL;
  if (in) {
    char *line = NULL;
    size_t cap = 0;
    ssize_t len;
    long pos = 0, lineno = 0;
    while ((len = getline(&line, &cap, in)) > 0) {
      lineno++;
      int complete = line[len - 1] == '\n';
      if (!complete) break; /* the truncated last line of an interrupted run */
      line[len - 1] = '\0';
      if (lineno == 1) {
        if (strcmp(line, header) != 0) {
          dem_err_set(err, DEM_EINVAL,
                      "%s: this cache belongs to a different calibration (header '%s', "
                      "expected '%s'); remove it or run without --resume",
                      path, line, header);
          free(line);
          fclose(in);
          free(cc);
          return NULL;
        }
      } else {
        double u[CAL_MAX_FREE], f = 0.0;
        if (!parse_line(line, dim, u, &f)) break; /* damaged: keep what precedes it */
        if (insert(cc, u, f)) {
          dem_err_set(err, DEM_ENOMEM, "out of memory");
          free(line);
          fclose(in);
          cal_cache_close(cc);
          return NULL;
        }
      }
      pos += (long)len;
      keep = pos;
    }
    free(line);
    fclose(in);
    if (truncate(path, keep) != 0) {
      dem_err_set(err, DEM_EIO, "%s: cannot truncate: %s", path, strerror(errno));
      cal_cache_close(cc);
      return NULL;
    }
  }
  cc->f = fopen(path, keep > 0 ? "ab" : "wb");
  if (!cc->f) {
    dem_err_set(err, DEM_EIO, "%s: cannot open the evaluation cache: %s", path, strerror(errno));
    cal_cache_close(cc);
    return NULL;
  }
  if (keep == 0) {
    fprintf(cc->f, "%s\n", header);
    fflush(cc->f);
  }
  return cc;
}

int cal_cache_store(cal_cache *cc, const double *u, double f) {
  char line[64 * (CAL_MAX_FREE + 2)];
  size_t used = 0;
  for (int i = 0; i < cc->dim; i++)
    used += (size_t)snprintf(line + used, sizeof line - used, "%s%a", i ? " " : "", u[i]);
  used += (size_t)snprintf(line + used, sizeof line - used, " %a", f);
  uint64_t sum = fnv_bytes(1469598103934665603ULL, line, used);
  fprintf(cc->f, "%s %016" PRIx64 "\n", line, sum);
  fflush(cc->f);
  return insert(cc, u, f);
}

long cal_cache_size(const cal_cache *cc) { return cc ? cc->n : 0; }

void cal_cache_close(cal_cache *cc) {
  if (!cc) return;
  if (cc->f) fclose(cc->f);
  free(cc->tab);
  free(cc);
}
