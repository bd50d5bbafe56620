/* dem-bench-contact: cost of one force evaluation, per law of the registry, and of one
 * tangential step and one rolling torque.
 *
 * Every law of dem_contact_law_count() is set up from the first parameter set of the table
 * below that it accepts (a law added later runs without changing this file as long as one
 * set covers its coefficients; otherwise it is skipped with the set-up error). The sets hold
 * every key of the physics notes at two scales:
 *   "afl-wall"  the reference case: ammonium fluorescein R = 2.45 um on a wall of the same
 *               material (thesis Table 4.1/4.2; paper Table 1/5);
 *   "bulk-mm"   the bulk simulations of thesis chapters 6-7 (Table 6.2/6.3), d = 1 mm.
 *
 * Workload: NC contacts (default 4096), each with its own history block, each walking the
 * same realistic overlap cycle (approach, loading to alpha_max, partial unloading to
 * 0.5 alpha_max, reloading to 0.8 alpha_max, unloading into tension to -0.5 alpha_max where
 * adhesive contacts break, then a fresh contact) at its own phase, so consecutive
 * evaluations touch different history blocks as in the bulk engine. alpha_max is the
 * linear-spring estimate v sqrt(m* / k_ref(v)) at v = 2 m/s; alpha_dot follows the path at
 * up to 2 m/s. Every force returned is summed into a checksum that is printed, so no
 * evaluation can be discarded; the laws are called through the table's function pointer
 * (as the engine does). A "baseline" row runs the same harness with a trivial force
 * function: subtract it for the cost of the law itself.
 *
 * Timing: CLOCK_MONOTONIC; each measurement repeats whole sweeps until --time seconds have
 * passed; the best and the median of --repeats measurements are reported.
 */
#include <getopt.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dem/contact.h"
#include "dem/material.h"
#include "dem/params.h"
#include "dem/tangential.h"

typedef struct {
  const char *key;
  double value;
} kv;

typedef struct {
  const char *name;
  double R, rho; /* particle; the contact is particle-wall: R* = R, m* = m */
  const kv *keys;
} param_set;

/* Reference case: thesis Table 4.1 (R, rho, E, nu, Gamma, py), Table 4.2 (ke, kp, kc = kcp,
 * f0p), f0 = 8/9 * 1.5 pi Gamma R* (physics notes), Luding ke_max = 1500 N/m and
 * phi_f = 0.02 (thesis 4.1.5, Fig 4.23), kt = ke * 2(1-nu)/(2-nu) (paper eq 22). */
static const kv afl_keys[] = {
    {"E", 1.2e9},    {"nu", 0.3},     {"gamma", 0.2},  {"py", 35.3e6},   {"kn", 1500.0},
    {"ke", 1500.0},  {"kp", 210.0},   {"kc", 20.0},    {"kcp", 20.0},    {"f0", 2.0525e-6},
    {"f0p", 4.0e-6}, {"ke_max", 1500.0}, {"phi_f", 0.02}, {"kt", 1235.3}, {"e", 0.9},
    {"mu", 0.3},     {"mu_r", 0.01},  {NULL, 0.0}};
/* Bulk: thesis Table 6.2/6.3 (ke = 1 MN/m, kp = 0.1 MN/m, kcp = 0.01 MN/m, kt = ke,
 * Gamma = 2 J/m^2, mu = 0.15, mu_r = 0.01, e = 0.5); E, nu, rho, py: an assumed glass-like
 * particle (the thesis' bulk runs are linear and give no modulus). */
static const kv bulk_keys[] = {
    {"E", 5e7},      {"nu", 0.3},     {"gamma", 2.0},  {"py", 5e7},      {"kn", 1e6},
    {"ke", 1e6},     {"kp", 1e5},     {"kc", 1e4},     {"kcp", 1e4},     {"f0", 6.2832e-3},
    {"f0p", 6.2832e-3}, {"ke_max", 1e6}, {"phi_f", 0.05}, {"kt", 1e6},     {"e", 0.5},
    {"mu", 0.15},    {"mu_r", 0.01},  {NULL, 0.0}};
static const param_set sets[] = {
    {"afl-wall", 2.45e-6, 1350.0, afl_keys},
    {"bulk-mm", 0.5e-3, 2500.0, bulk_keys},
};
#define NSETS ((int)(sizeof sets / sizeof sets[0]))

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int fill_params(const param_set *s, dem_params *ps) {
  dem_params_init(ps);
  for (const kv *k = s->keys; k->key; k++)
    if (dem_params_set(ps, k->key, k->value, s->name, NULL)) return -1;
  return 0;
}

/* The overlap cycle: NP points of (alpha, alpha_dot). */
typedef struct {
  int np;
  double *a, *ad;
} path;

static void path_build(path *p, double amax, double v) {
  /* Turning points in units of alpha_max, and the share of points of each leg. */
  static const double tp[] = {-0.1, 1.0, 0.5, 0.8, -0.5};
  static const int legs[] = {400, 150, 150, 300};
  p->np = 1000;
  p->a = malloc(sizeof(double) * (size_t)p->np);
  p->ad = malloc(sizeof(double) * (size_t)p->np);
  int k = 0;
  double da_max = 0.0;
  for (int l = 0; l < 4; l++) {
    double a0 = tp[l] * amax, a1 = tp[l + 1] * amax;
    for (int i = 0; i < legs[l]; i++, k++) {
      /* Smooth (half-cosine) legs: the rate vanishes at turning points, as in an impact. */
      double s = 0.5 * (1.0 - cos(M_PI * (i + 0.5) / legs[l]));
      p->a[k] = a0 + (a1 - a0) * s;
      p->ad[k] = (a1 - a0) * 0.5 * M_PI * sin(M_PI * (i + 0.5) / legs[l]) / legs[l];
      if (fabs(p->ad[k]) > da_max) da_max = fabs(p->ad[k]);
    }
  }
  /* Scale the per-point rate to at most v (m/s). */
  for (int i = 0; i < p->np; i++) p->ad[i] *= v / da_max;
}

static void path_free(path *p) {
  free(p->a);
  free(p->ad);
}

/* The benchmarked loop: nsweep sweeps over nc contacts. */
typedef struct {
  const dem_contact *ct;
  dem_law_force_fn force;
  const double *c;
  dem_geom g;
  int nc, nhist;
  double *hist;       /* nc * nhist */
  const double *fresh;/* a freshly initialised block */
  int *phase;
  const path *p;
  int step;
} normal_bench;

static double normal_sweeps(normal_bench *b, int nsweep) {
  double sum = 0.0;
  const int np = b->p->np, nh = b->nhist;
  for (int s = 0; s < nsweep; s++, b->step++) {
    for (int c = 0; c < b->nc; c++) {
      int i = (b->step + b->phase[c]) % np;
      double *h = b->hist + (size_t)c * (size_t)nh;
      if (i == 0) memcpy(h, b->fresh, sizeof(double) * (size_t)nh);
      dem_normal out;
      b->force(b->c, &b->g, h, b->p->a[i], b->p->ad[i], &out);
      sum += out.f + out.f_adh;
    }
  }
  return sum;
}

/* Baseline: the same harness with a trivial force (in another function, via a pointer). */
static void trivial_force(const double *c, const dem_geom *g, double *hist, double alpha,
                          double alpha_dot, dem_normal *out) {
  (void)g;
  out->f = c[0] * alpha + hist[0];
  out->f_adh = alpha_dot;
}

typedef struct {
  double best, median, checksum;
  long evals;
} timing;

static int cmp_double(const void *x, const void *y) {
  double a = *(const double *)x, b = *(const double *)y;
  return (a > b) - (a < b);
}

/* Time fn(ctx, nsweep) repeatedly: per-evaluation ns = elapsed / (nsweep * per_sweep). */
typedef double (*sweep_fn)(void *ctx, int nsweep);

static timing measure(sweep_fn fn, void *ctx, int per_sweep, double tmin, int reps) {
  timing t = {0};
  double ns[32];
  if (reps > 32) reps = 32;
  fn(ctx, 2); /* warm-up */
  for (int r = 0; r < reps; r++) {
    long n = 0;
    double t0 = now(), el = 0.0;
    while (el < tmin) {
      t.checksum += fn(ctx, 16);
      n += 16;
      el = now() - t0;
    }
    ns[r] = el * 1e9 / ((double)n * per_sweep);
    t.evals += n * per_sweep;
  }
  qsort(ns, (size_t)reps, sizeof ns[0], cmp_double);
  t.best = ns[0];
  t.median = ns[reps / 2];
  return t;
}

static double normal_fn(void *ctx, int n) { return normal_sweeps((normal_bench *)ctx, n); }

/* Tangential and rolling: per contact a spring, a slowly turning normal and a tangential
 * velocity that makes a share of the contacts slide. */
typedef struct {
  dem_tangential t;
  dem_rolling r;
  int nc, step;
  double *xi, *n, *vt, *w;
  double R, m, alpha, fn, fadh, dt, weps;
} tang_bench;

static double tang_fn(void *ctx, int nsweep) {
  tang_bench *b = (tang_bench *)ctx;
  double sum = 0.0;
  for (int s = 0; s < nsweep; s++, b->step++) {
    /* The velocity reverses every 64 steps so that springs load, unload and slide. */
    const double sg = ((b->step >> 6) & 1) ? -1.0 : 1.0;
    for (int c = 0; c < b->nc; c++) {
      double *n = b->n + 3 * c, v[3], ft[3];
      for (int i = 0; i < 3; i++) v[i] = sg * b->vt[3 * c + i];
      sum += dem_tangential_force(&b->t, b->xi + 3 * c, n, v, b->dt, b->R, b->alpha, b->m,
                                  b->fn, b->fadh, ft);
      sum += ft[0] + ft[1] + ft[2];
    }
  }
  return sum;
}

static double roll_fn(void *ctx, int nsweep) {
  tang_bench *b = (tang_bench *)ctx;
  double sum = 0.0;
  for (int s = 0; s < nsweep; s++, b->step++) {
    double scale = 1.0 + 1e-3 * (b->step & 7);
    for (int c = 0; c < b->nc; c++) {
      double w[3] = {b->w[3 * c] * scale, b->w[3 * c + 1], b->w[3 * c + 2]}, M[3];
      dem_rolling_torque(&b->r, w, b->fn, b->R, b->weps, M);
      sum += M[0] + M[1] + M[2];
    }
  }
  return sum;
}

/* A small deterministic generator (no dependence on libc's rand). */
static double urand(unsigned long long *s) {
  *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(*s >> 11) * (1.0 / 9007199254740992.0);
}

static void usage(FILE *f) {
  fprintf(f,
          "usage: dem-bench-contact [--json] [--contacts N] [--time S] [--repeats R] "
          "[--law ID]\n"
          "  Nanoseconds per normal-force evaluation for every law of the registry, per\n"
          "  tangential step and per rolling torque.\n"
          "  --json         one JSON object on stdout instead of the table\n"
          "  --contacts N   contacts (history blocks) per sweep, default 4096\n"
          "  --time S       seconds per measurement, default 0.1\n"
          "  --repeats R    measurements per row (best and median reported), default 5\n"
          "  --law ID       only this law (and the tangential/rolling rows)\n");
}

static void cpu_model(char *buf, size_t n) {
  snprintf(buf, n, "unknown");
  FILE *f = fopen("/proc/cpuinfo", "r");
  if (!f) return;
  char line[512];
  while (fgets(line, sizeof line, f))
    if (strncmp(line, "model name", 10) == 0) {
      char *c = strchr(line, ':');
      if (c) {
        c += 2;
        c[strcspn(c, "\n")] = '\0';
        snprintf(buf, n, "%s", c);
      }
      break;
    }
  fclose(f);
}

int main(int argc, char **argv) {
  int json = 0, nc = 4096, reps = 5;
  double tmin = 0.1;
  const char *only = NULL;
  static const struct option opts[] = {{"json", no_argument, NULL, 'j'},
                                       {"contacts", required_argument, NULL, 'n'},
                                       {"time", required_argument, NULL, 't'},
                                       {"repeats", required_argument, NULL, 'r'},
                                       {"law", required_argument, NULL, 'l'},
                                       {"help", no_argument, NULL, 'h'},
                                       {NULL, 0, NULL, 0}};
  int o;
  while ((o = getopt_long(argc, argv, "jn:t:r:l:h", opts, NULL)) != -1) {
    switch (o) {
      case 'j': json = 1; break;
      case 'n': nc = atoi(optarg); break;
      case 't': tmin = atof(optarg); break;
      case 'r': reps = atoi(optarg); break;
      case 'l': only = optarg; break;
      case 'h': usage(stdout); return 0;
      default: usage(stderr); return 2;
    }
  }
  if (nc < 1 || nc > 1 << 22 || !(tmin > 0.0 && tmin < 60.0) || reps < 1 || reps > 32) {
    fprintf(stderr, "dem-bench-contact: need 1 <= contacts <= 4194304, 0 < time < 60, "
                    "1 <= repeats <= 32\n");
    return 2;
  }
  if (only && !dem_contact_law_find(only)) {
    fprintf(stderr, "dem-bench-contact: unknown law '%s'\n", only);
    return 2;
  }
  char cpu[256];
  cpu_model(cpu, sizeof cpu);
  json_t *root = json_object(), *rows = json_array(), *skipped = json_array();
  json_object_set_new(root, "benchmark", json_string("contact"));
  json_object_set_new(root, "cpu", json_string(cpu));
  json_object_set_new(root, "compiler", json_string(__VERSION__));
  json_object_set_new(root, "contacts", json_integer(nc));
  json_object_set_new(root, "repeats", json_integer(reps));
  json_object_set_new(root, "time_per_measurement_s", json_real(tmin));
  if (!json) {
    printf("# dem-bench-contact: %s, %s; %d contacts, best/median of %d x %.2f s\n", cpu,
           __VERSION__, nc, reps, tmin);
    printf("%-16s %-9s %10s %10s %14s  %s\n", "row", "set", "ns_best", "ns_median", "evals",
           "checksum");
  }
  unsigned long long seed = 0x2385ULL;
  int *phase = malloc(sizeof(int) * (size_t)nc);
  double *hist = malloc(sizeof(double) * (size_t)nc * DEM_LAW_NHIST_MAX);
  if (!phase || !hist) return 1;
  for (int c = 0; c < nc; c++) phase[c] = (int)(urand(&seed) * 1000.0);

  /* Each law, with the first parameter set it accepts; the baseline first. */
  for (int li = -1; li < dem_contact_law_count(); li++) {
    const dem_law *law = li < 0 ? NULL : dem_contact_law_at(li);
    if (law && only && strcmp(law->name, only) != 0) continue;
    dem_contact ct;
    dem_err err = {0};
    int si = 0;
    dem_params ps;
    if (law) {
      for (si = 0; si < NSETS; si++) {
        if (fill_params(&sets[si], &ps)) continue;
        if (dem_contact_setup(&ct, law, &ps, &err) == DEM_OK) break;
      }
      if (si == NSETS) {
        if (!json) printf("%-16s skipped: %s\n", law->name, err.msg);
        json_t *sk = json_object();
        json_object_set_new(sk, "law", json_string(law->name));
        json_object_set_new(sk, "reason", json_string(err.msg));
        json_array_append_new(skipped, sk);
        continue;
      }
    }
    const param_set *set = &sets[si];
    double m = dem_sphere_mass(set->R, set->rho);
    dem_geom g = {set->R, m};
    double fresh[DEM_LAW_NHIST_MAX] = {0};
    int nh = 1;
    double amax;
    if (law) {
      nh = law->nhist;
      if (dem_contact_init(&ct, &g, fresh, &err)) {
        if (!json) printf("%-16s skipped: %s\n", law->name, err.msg);
        json_t *sk = json_object();
        json_object_set_new(sk, "law", json_string(law->name));
        json_object_set_new(sk, "reason", json_string(err.msg));
        json_array_append_new(skipped, sk);
        continue;
      }
      amax = 2.0 * sqrt(m / dem_contact_kref(&ct, &g, 2.0));
    } else {
      amax = 2.0 * sqrt(m / 1500.0);
    }
    path p;
    path_build(&p, amax, 2.0);
    for (int c = 0; c < nc; c++) memcpy(hist + (size_t)c * nh, fresh, sizeof(double) * nh);
    static const double one = 1500.0;
    normal_bench b = {law ? &ct : NULL, law ? law->force : trivial_force, law ? ct.c : &one,
                      g, nc, nh, hist, fresh, phase, &p, 0};
    timing t = measure(normal_fn, &b, nc, tmin, reps);
    path_free(&p);
    const char *name = law ? law->name : "baseline";
    if (!json)
      printf("%-16s %-9s %10.2f %10.2f %14ld  %.6e\n", name, law ? set->name : "-", t.best,
             t.median, t.evals, t.checksum);
    json_t *row = json_object();
    json_object_set_new(row, "name", json_string(name));
    json_object_set_new(row, "kind", json_string(law ? "normal" : "baseline"));
    json_object_set_new(row, "param_set", json_string(law ? set->name : "-"));
    json_object_set_new(row, "alpha_max", json_real(amax));
    json_object_set_new(row, "ns_best", json_real(t.best));
    json_object_set_new(row, "ns_median", json_real(t.median));
    json_object_set_new(row, "evals", json_integer(t.evals));
    json_object_set_new(row, "checksum", json_real(t.checksum));
    json_array_append_new(rows, row);
  }

  /* Tangential (linear, Mindlin; damping on) and rolling, at the reference case. */
  tang_bench tb = {0};
  tb.nc = nc;
  tb.xi = calloc((size_t)nc * 3, sizeof(double));
  tb.n = malloc(sizeof(double) * (size_t)nc * 3);
  tb.vt = malloc(sizeof(double) * (size_t)nc * 3);
  tb.w = malloc(sizeof(double) * (size_t)nc * 3);
  if (!tb.xi || !tb.n || !tb.vt || !tb.w) return 1;
  tb.R = sets[0].R;
  tb.m = dem_sphere_mass(sets[0].R, sets[0].rho);
  tb.alpha = 1.5e-8;
  tb.fn = 2.2e-5;  /* ke * alpha */
  tb.fadh = 4e-6;
  tb.dt = 1e-10;
  for (int c = 0; c < nc; c++) {
    double a[3] = {urand(&seed) - 0.5, urand(&seed) - 0.5, urand(&seed) - 0.5};
    double l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int i = 0; i < 3; i++) {
      tb.n[3 * c + i] = a[i] / l;
      /* 0-2 m/s: with k_t ~ 1e3 N/m and F_lim ~ 8 uN a share of the contacts slides. */
      tb.vt[3 * c + i] = 2.0 * urand(&seed);
      tb.w[3 * c + i] = (urand(&seed) - 0.5) * (c % 8 ? 1e4 : 1e-6);
    }
  }
  const char *tnames[] = {"tangential-lin", "tangential-mdl", "rolling"};
  for (int k = 0; k < 3; k++) {
    dem_params ps;
    fill_params(&sets[0], &ps);
    dem_err err = {0};
    int rc = k == 2 ? dem_rolling_setup(&tb.r, &ps, &err)
                    : dem_tangential_setup(&tb.t, k ? DEM_TANGENTIAL_MINDLIN
                                                    : DEM_TANGENTIAL_LINEAR,
                                           &ps, &err);
    if (rc) {
      fprintf(stderr, "dem-bench-contact: %s\n", err.msg);
      return 1;
    }
    tb.weps = dem_rolling_omega_eps(tb.r.mu_r, tb.fn, tb.R, 0.4 * tb.m * tb.R * tb.R, tb.dt);
    memset(tb.xi, 0, sizeof(double) * (size_t)nc * 3);
    tb.step = 0;
    timing t = measure(k == 2 ? roll_fn : tang_fn, &tb, nc, tmin, reps);
    if (!json)
      printf("%-16s %-9s %10.2f %10.2f %14ld  %.6e\n", tnames[k], sets[0].name, t.best,
             t.median, t.evals, t.checksum);
    json_t *row = json_object();
    json_object_set_new(row, "name", json_string(tnames[k]));
    json_object_set_new(row, "kind", json_string(k == 2 ? "rolling" : "tangential"));
    json_object_set_new(row, "param_set", json_string(sets[0].name));
    json_object_set_new(row, "ns_best", json_real(t.best));
    json_object_set_new(row, "ns_median", json_real(t.median));
    json_object_set_new(row, "evals", json_integer(t.evals));
    json_object_set_new(row, "checksum", json_real(t.checksum));
    json_array_append_new(rows, row);
  }
  json_object_set_new(root, "results", rows);
  json_object_set_new(root, "skipped", skipped);
  if (json) {
    char *s = json_dumps(root, JSON_INDENT(2) | JSON_REAL_PRECISION(6));
    if (s) puts(s);
    free(s);
  }
  json_decref(root);
  free(phase);
  free(hist);
  free(tb.xi);
  free(tb.n);
  free(tb.vt);
  free(tb.w);
  return 0;
}
