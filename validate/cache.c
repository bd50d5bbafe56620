/* cache.c — runs kept across invocations, next to the beds (--beds DIR).
 *
 * A run is an indentation of one bed with one indenter; its result is the raw loading series
 * (h/r, H, bin p, q, phi, base p, F, and the footprint a_c, Hc, indenter contacts per sample)
 * and a few scalars. The statistics are not
 * stored: they are recomputed from the series on load, so a cached run serves any plateau
 * window. A cached run is used only if all of these match what this invocation would run:
 *   - the key: the bed's name (every parameter a bed depends on) and every indentation
 *     parameter (shape, D, gamma*, kn scale, indenter mu, dt scale, h/r at the end, sampling);
 *   - the bed file: its size and modification time when the run was made (a bed prepared
 *     anew invalidates its runs);
 *   - the code: VH_CODE_ID, a hash of every source file a run's numbers depend on (libdem,
 *     validate/run.c and vh_run.h, the CMakeLists that set the options), the compiler and its
 *     version, the build type and flags, and the GSL and HDF5 versions
 *     (validate/code_id.cmake). A change to the report, the criteria, the plan or the CLI
 *     keeps the runs; a change to the physics or the run set-up makes them anew. (Until
 *     2026-12-06 it was a hash of the executable, so every rebuild ran everything again.)
 *     Runs are bit-identical for the same code and thread count; the thread count is
 *     recorded, not matched (another count gives the same physics to rounding).
 * Anything else (a missing, truncated or foreign file) is a cache miss, never an error: the
 * run is computed and the file replaced. Files are written to a temporary name and renamed,
 * so an interrupted invocation leaves no half-written entry.
 * Format: text, "# key value" header lines, then one row of %.17g numbers per sample.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "vh_run.h"
#include "vh_code_id.h" /* VH_CODE_ID, generated at build time by validate/code_id.cmake */

/* format 2 (2026-12-07): the footprint columns a_c, Hc, indenter contacts appended */
#define CACHE_MAGIC "# dem-validate run cache, format 2"

const char *vh_code_id(void) { return VH_CODE_ID; }

static int bed_stamp(const char *path, char *buf, size_t len) {
  struct stat st;
  if (stat(path, &st)) return -1;
  snprintf(buf, len, "%lld.%09ld:%lld", (long long)st.st_mtim.tv_sec, (long)st.st_mtim.tv_nsec,
           (long long)st.st_size);
  return 0;
}

void vh_cache_path(const vh *h, const char *bed_name, const vh_indent *in, char *buf,
                   size_t len) {
  static const char *shp[] = {"sphere", "cylinder", "cube"};
  int s = (int)in->shape;
  snprintf(buf, len, "%.300s/run_%.160s__%s%g_g%g_kn%g_mui%g_dts%g_h%g.dat", h->beds_dir,
           bed_name, (s >= 0 && s < 3) ? shp[s] : "shape", in->D, in->gamma_star, in->kn_scale,
           in->mu_ind, in->dt_scale, h->tier->h_end);
}

/* The series columns, in file order. */
static double **columns(vh_run *r, int k) {
  double **c[] = {&r->hr, &r->H, &r->bin_p, &r->bin_q, &r->bin_phi,
                  &r->base_p, &r->F, &r->ac, &r->Hc, &r->nind};
  return c[k];
}
#define NCOLS 10

int vh_cache_load(const vh *h, const char *path, const char *bed_path, vh_run *r) {
  FILE *f = fopen(path, "r");
  if (!f) return -1;
  char line[1024], want_code[64], want_bed[96], code[64] = "", bed[96] = "";
  snprintf(want_code, sizeof want_code, "%s", vh_code_id());
  if (bed_stamp(bed_path, want_bed, sizeof want_bed)) {
    fclose(f);
    return -1;
  }
  long n = -1;
  int status = -1, have_stress = 0, ok = 0;
  if (!fgets(line, sizeof line, f) || strncmp(line, CACHE_MAGIC, strlen(CACHE_MAGIC)) != 0)
    goto miss;
  while (fgets(line, sizeof line, f)) {
    if (line[0] != '#') break;
    char key[32], *val = line + 2;
    if (sscanf(line, "# %31s", key) != 1) continue;
    val += strlen(key);
    while (*val == ' ') val++;
    val[strcspn(val, "\n")] = '\0';
    if (!strcmp(key, "code")) snprintf(code, sizeof code, "%s", val);
    else if (!strcmp(key, "bed_file")) snprintf(bed, sizeof bed, "%s", val);
    else if (!strcmp(key, "status")) status = atoi(val);
    else if (!strcmp(key, "error")) snprintf(r->error, sizeof r->error, "%s", val);
    else if (!strcmp(key, "wall_s")) r->wall_s = strtod(val, NULL);
    else if (!strcmp(key, "threads")) r->threads = atoi(val);
    else if (!strcmp(key, "steps")) r->steps = strtol(val, NULL, 10);
    else if (!strcmp(key, "dt")) r->dt = strtod(val, NULL);
    else if (!strcmp(key, "surface")) r->surface = strtod(val, NULL);
    else if (!strcmp(key, "surface_sd")) r->surface_sd = strtod(val, NULL);
    else if (!strcmp(key, "peak_overlap")) r->peak_overlap = strtod(val, NULL);
    else if (!strcmp(key, "base_p0")) r->base_p0 = strtod(val, NULL);
    else if (!strcmp(key, "have_stress")) have_stress = atoi(val);
    else if (!strcmp(key, "samples")) n = strtol(val, NULL, 10);
  }
  if (strcmp(code, want_code) || strcmp(bed, want_bed) || status < 0 || n < 0 || n > 10000000)
    goto miss;
  for (int k = 0; k < NCOLS; k++) {
    *columns(r, k) = calloc((size_t)n + 1, sizeof(double));
    if (!*columns(r, k)) goto miss;
  }
  /* `line` holds the first data row (or EOF was reached with n == 0) */
  for (long i = 0; i < n; i++) {
    if (i > 0 && !fgets(line, sizeof line, f)) goto miss;
    char *p = line, *e;
    for (int k = 0; k < NCOLS; k++) {
      double v = strtod(p, &e);
      if (e == p) goto miss;
      (*columns(r, k))[i] = v;
      p = e;
    }
  }
  r->n = (size_t)n;
  r->status = status;
  r->have_stress = have_stress;
  r->cached = 1;
  ok = 1;
miss:
  fclose(f);
  if (!ok) {
    vh_run_release(r);
    r->error[0] = '\0';
    return -1;
  }
  return 0;
}

int vh_cache_save(const vh *h, const char *path, const char *bed_path, const vh_run *r,
                  dem_err *err) {
  char stamp[96], tmp[600];
  if (bed_stamp(bed_path, stamp, sizeof stamp))
    return dem_err_set(err, DEM_EIO, "%s: %s", bed_path, strerror(errno));
  snprintf(tmp, sizeof tmp, "%s.tmp%ld", path, (long)getpid());
  FILE *f = fopen(tmp, "w");
  if (!f) return dem_err_set(err, DEM_EIO, "%s: %s", tmp, strerror(errno));
  fprintf(f, "%s\n# code %s\n# bed_file %s\n# label %s\n# status %d\n", CACHE_MAGIC,
          vh_code_id(), stamp, r->label, r->status);
  if (r->error[0]) fprintf(f, "# error %s\n", r->error);
  fprintf(f, "# wall_s %.17g\n# threads %d\n# steps %ld\n# dt %.17g\n# surface %.17g\n"
          "# surface_sd %.17g\n# peak_overlap %.17g\n# base_p0 %.17g\n# have_stress %d\n"
          "# samples %zu\n", r->wall_s, h->threads, r->steps, r->dt, r->surface,
          r->surface_sd, r->peak_overlap, r->base_p0, r->have_stress, r->n);
  fprintf(f, "# columns h/r H[Pa] bin_p[Pa] bin_q[Pa] bin_phi base_p[Pa] F[N] a_c[m] Hc[Pa] "
             "indenter_contacts\n");
  vh_run *rw = (vh_run *)r; /* columns() names the arrays; nothing is written through it */
  for (size_t i = 0; i < r->n; i++)
    for (int k = 0; k < NCOLS; k++)
      fprintf(f, "%.17g%c", (*columns(rw, k))[i], k + 1 < NCOLS ? ' ' : '\n');
  int bad = ferror(f);
  if (fclose(f) || bad || rename(tmp, path)) {
    int e = errno;
    remove(tmp);
    return dem_err_set(err, DEM_EIO, "%s: cannot write the run cache (%s)", path, strerror(e));
  }
  return DEM_OK;
}

/* The preparation wall time of a bed, kept next to its checkpoint (BED.h5.info), so that the
 * cost of a case can be reported when its bed was prepared by an earlier invocation. */
void vh_bed_info_save(const vh_bed *b, int threads) {
  char p[600], tmp[620];
  snprintf(p, sizeof p, "%s.info", b->path);
  snprintf(tmp, sizeof tmp, "%s.tmp%ld", p, (long)getpid());
  FILE *f = fopen(tmp, "w");
  if (!f) return;
  fprintf(f, "prep_wall_s %.17g\nthreads %d\n", b->prep_s, threads); /* exact: summary.json */
  if (fclose(f) || rename(tmp, p)) remove(tmp);
}

double vh_bed_info_load(const vh_bed *b) {
  char p[600];
  snprintf(p, sizeof p, "%s.info", b->path);
  FILE *f = fopen(p, "r");
  double s = NAN;
  if (!f) return s;
  if (fscanf(f, "prep_wall_s %lf", &s) != 1) s = NAN;
  fclose(f);
  return s;
}
