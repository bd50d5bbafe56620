/* dem-bench: throughput of the 3-D engine on the peers' dense-bed scene.
 *
 *   dem-bench [--particles N] [--steps N] [--threads N] [--json] [--file CSV] [--checksum]
 *
 * Scene (issue 5, identical to the LAMMPS / LIGGGHTS / Yade runs): the 20,000 settled
 * spheres of ../shared/bench/dense20k.csv (d = 1 mm, rho = 2500 kg/m^3) in a 0.03 x 0.03 m
 * box (plane walls at x = 0, 0.03 and y = 0, 0.03, floor z = 0), gravity 9.81 m/s^2 along
 * -z, Hertz with E = 1e8 Pa, nu = 0.3, restitution 0.5, history-based (Mindlin) tangential
 * friction mu = 0.3, dt = 1.5e-6 s, neighbour skin 0.1 mm.
 * --particles N: the file is tiled k x k in x and y (box k * 0.03 m) with k the smallest
 * integer giving at least N spheres, and the N lowest spheres (in z) are kept.
 * --checksum: also print a 64-bit FNV-1a hash of the final positions, velocities and angular
 * velocities in particle-id order (equal hashes: bit-identical results, e.g. before and
 * after an optimisation).
 * The time is the engine's own loop timer (dem_sim_run, including its neighbour builds and
 * the first force evaluation, excluding reading the file and setting up).
 */
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "dem/contact.h"
#include "dem/engine.h"
#include "dem/material.h"
#include "dem/params.h"
#include "dem/tangential.h"
#include "cli_common.h"

#ifndef DEM_SHARED_DIR
#define DEM_SHARED_DIR "../shared"
#endif

typedef struct sphere {
  double x[3], r;
} sphere;

static int cmp_z(const void *a, const void *b) {
  const sphere *p = a, *q = b;
  if (p->x[2] < q->x[2]) return -1;
  if (p->x[2] > q->x[2]) return 1;
  return p < q ? -1 : (p > q);
}

static sphere *read_csv(const char *path, size_t *n) {
  FILE *fp = fopen(path, "r");
  if (!fp) return NULL;
  size_t cap = 1024, k = 0;
  sphere *s = malloc(cap * sizeof *s);
  char line[512];
  while (s && fgets(line, sizeof line, fp)) {
    if (line[0] == '#' || line[0] == 'x' || line[0] == '\n') continue;
    sphere q;
    if (sscanf(line, "%lf,%lf,%lf,%lf", &q.x[0], &q.x[1], &q.x[2], &q.r) != 4) continue;
    if (k == cap) {
      sphere *t = realloc(s, 2 * cap * sizeof *s);
      if (!t) {
        free(s);
        s = NULL;
        break;
      }
      s = t;
      cap *= 2;
    }
    s[k++] = q;
  }
  fclose(fp);
  *n = k;
  return s;
}

/* FNV-1a over the bytes of x, v, omega of each particle in id order. */
static unsigned long long state_hash(const dem_particles *p) {
  unsigned long long h = 1469598103934665603ull;
  size_t *at = malloc((p->n ? p->n : 1) * sizeof *at);
  if (!at) return 0;
  for (size_t i = 0; i < p->n; i++) at[p->id[i] < p->n ? p->id[i] : 0] = i;
  for (size_t k = 0; k < p->n; k++) {
    const double *src[3] = {p->x + 3 * at[k], p->v + 3 * at[k], p->omega + 3 * at[k]};
    for (int a = 0; a < 3; a++) {
      const unsigned char *c = (const unsigned char *)src[a];
      for (size_t b = 0; b < 3 * sizeof(double); b++) h = (h ^ c[b]) * 1099511628211ull;
    }
  }
  free(at);
  return h;
}

static void usage(FILE *f) {
  fprintf(f, "usage: dem-bench [--particles N] [--steps N] [--threads N] [--json] [--file CSV]\n"
             "                 [--checksum]\n"
             "  the dense-bed throughput benchmark of issue 5 (default 20000 particles,\n"
             "  1000 steps, 1 thread); prints particle-steps per second\n");
}

static int fail(const char *what, const dem_err *e) {
  fprintf(stderr, "dem-bench: %s: %s\n", what, e->msg[0] ? e->msg : dem_strerror(e->code));
  return 1;
}

int main(int argc, char **argv) {
  long nwant = 20000, steps = 1000;
  int threads = 1, json = 0, checksum = 0;
  const char *file = DEM_SHARED_DIR "/bench/dense20k.csv";
  for (int a = 1; a < argc; a++) {
    const char *s = argv[a];
    dem_err pe = {0};
    double val = 0.0;
    if (!strcmp(s, "--particles") && a + 1 < argc) {
      if (cli_parse_double(s, argv[++a], 1, 5e7, &val, &pe)) return cli_error("dem-bench", &pe), 2;
      nwant = (long)val;
    } else if (!strcmp(s, "--steps") && a + 1 < argc) {
      if (cli_parse_double(s, argv[++a], 1, 1e9, &val, &pe)) return cli_error("dem-bench", &pe), 2;
      steps = (long)val;
    } else if (!strcmp(s, "--threads") && a + 1 < argc) {
      if (cli_parse_double(s, argv[++a], 1, 64, &val, &pe)) return cli_error("dem-bench", &pe), 2;
      threads = (int)val;
    } else if (!strcmp(s, "--file") && a + 1 < argc) {
      file = argv[++a];
    } else if (!strcmp(s, "--checksum")) {
      checksum = 1;
    } else if (!strcmp(s, "--json")) {
      json = 1;
    } else if (!strcmp(s, "--version")) {
      cli_print_version("dem-bench");
      return 0;
    } else if (!strcmp(s, "--help") || !strcmp(s, "-h")) {
      usage(stdout);
      return 0;
    } else {
      usage(stderr);
      return 2;
    }
  }
  size_t nfile = 0;
  sphere *src = read_csv(file, &nfile);
  if (!src || nfile == 0) {
    fprintf(stderr, "dem-bench: cannot read spheres from %s\n", file);
    free(src);
    return 1;
  }
  const double L = 0.03; /* m, box side of the file */
  int k = 1;
  while ((size_t)k * k * nfile < (size_t)nwant) k++;
  size_t ntot = (size_t)k * k * nfile;
  sphere *all = malloc(ntot * sizeof *all);
  if (!all) return 1;
  size_t m = 0;
  for (int ty = 0; ty < k; ty++)
    for (int tx = 0; tx < k; tx++)
      for (size_t i = 0; i < nfile; i++, m++) {
        all[m] = src[i];
        all[m].x[0] += tx * L;
        all[m].x[1] += ty * L;
      }
  free(src);
  if ((size_t)nwant < ntot) qsort(all, ntot, sizeof *all, cmp_z);
  size_t n = (size_t)nwant < ntot ? (size_t)nwant : ntot;
  double box = k * L;

  dem_err e = {0};
  dem_sim *sim = dem_sim_create(&e);
  if (!sim) return fail("create", &e);
  int mat_p, mat_w;
  dem_params ps;
  dem_params_init(&ps);
  dem_params_set(&ps, "E", 1e8, "bench", &e);
  dem_params_set(&ps, "nu", 0.3, "bench", &e);
  dem_params_set(&ps, "e", 0.5, "bench", &e);
  dem_params_set(&ps, "mu", 0.3, "bench", &e);
  dem_contact ct;
  const dem_law *hz = dem_contact_law_find("hertz");
  if (!hz) {
    fprintf(stderr, "dem-bench: law 'hertz' is not in this build\n");
    return 1;
  }
  if (dem_contact_setup(&ct, hz, &ps, &e)) return fail("hertz", &e);
  dem_tangential tg;
  int have_tangential = 1;
  if (dem_sim_add_material(sim, 2500.0, &mat_p, &e) ||
      dem_sim_add_material(sim, 2500.0, &mat_w, &e))
    return fail("material", &e);
  int trc = dem_tangential_setup(&tg, DEM_TANGENTIAL_MINDLIN, &ps, &e);
  if (trc || dem_sim_set_interaction(sim, mat_p, mat_p, &ct, &tg, NULL, &e) ||
      dem_sim_set_interaction(sim, mat_p, mat_w, &ct, &tg, NULL, &e)) {
    have_tangential = 0;
    fprintf(stderr, "dem-bench: WARNING: tangential friction unavailable (%s); timing the "
                    "normal force only\n", e.msg);
    memset(&e, 0, sizeof e);
    if (dem_sim_set_interaction(sim, mat_p, mat_p, &ct, NULL, NULL, &e) ||
        dem_sim_set_interaction(sim, mat_p, mat_w, &ct, NULL, NULL, &e))
      return fail("interaction", &e);
  }
  if (dem_sim_reserve(sim, n, &e)) return fail("reserve", &e);
  for (size_t i = 0; i < n; i++)
    if (dem_sim_add_particle(sim, all[i].x, NULL, all[i].r, mat_p, &e))
      return fail("particle", &e);
  free(all);
  const dem_wall_spec walls[5] = {
      {DEM_WALL_PLANE, {0, 0, 0}, {1, 0, 0}, 0, {0, 0, 0}, 0},
      {DEM_WALL_PLANE, {box, 0, 0}, {-1, 0, 0}, 0, {0, 0, 0}, 0},
      {DEM_WALL_PLANE, {0, 0, 0}, {0, 1, 0}, 0, {0, 0, 0}, 0},
      {DEM_WALL_PLANE, {0, box, 0}, {0, -1, 0}, 0, {0, 0, 0}, 0},
      {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 1}, 0, {0, 0, 0}, 0},
  };
  for (int w = 0; w < 5; w++) {
    dem_wall_spec ws = walls[w];
    ws.material = mat_w;
    if (dem_sim_add_wall(sim, &ws, NULL, &e)) return fail("wall", &e);
  }
  const double g[3] = {0.0, 0.0, -9.81};
  dem_sim_set_gravity(sim, g);
  if (dem_sim_set_dt(sim, 1.5e-6, &e) || dem_sim_set_skin(sim, 1e-4, &e) ||
      dem_sim_set_threads(sim, threads, &e))
    return fail("settings", &e);
  struct rusage ru0, ru;
  getrusage(RUSAGE_SELF, &ru0);
  if (dem_sim_run(sim, steps, &e)) return fail("run", &e);
  getrusage(RUSAGE_SELF, &ru);
  double cpu = (double)(ru.ru_utime.tv_sec - ru0.ru_utime.tv_sec) +
               1e-6 * (double)(ru.ru_utime.tv_usec - ru0.ru_utime.tv_usec) +
               (double)(ru.ru_stime.tv_sec - ru0.ru_stime.tv_sec) +
               1e-6 * (double)(ru.ru_stime.tv_usec - ru0.ru_stime.tv_usec);
  dem_sim_stats st;
  dem_sim_get_stats(sim, &st);
  double pss = (double)n * (double)steps / st.loop_seconds;
  double cpp = (double)(2 * st.contacts + st.wall_contacts) / (double)n;
  if (json) {
    json_t *o = json_object();
    json_object_set_new(o, "particles", json_integer((json_int_t)n));
    json_object_set_new(o, "steps", json_integer(steps));
    json_object_set_new(o, "threads", json_integer(threads));
    json_object_set_new(o, "seconds", json_real(st.loop_seconds));
    json_object_set_new(o, "particle_steps_per_s", json_real(pss));
    json_object_set_new(o, "peak_rss_kb", json_integer(ru.ru_maxrss));
    json_object_set_new(o, "cpu_seconds", json_real(cpu));
    json_object_set_new(o, "contacts_per_particle", json_real(cpp));
    json_object_set_new(o, "rebuilds", json_integer(st.rebuilds));
    json_object_set_new(o, "tangential", json_boolean(have_tangential));
    if (checksum) {
      char hx[32];
      snprintf(hx, sizeof hx, "%016llx", state_hash(dem_sim_particles(sim)));
      json_object_set_new(o, "checksum", json_string(hx));
    }
    char *txt = json_dumps(o, JSON_COMPACT | JSON_REAL_PRECISION(6));
    if (txt) puts(txt);
    free(txt);
    json_decref(o);
  } else {
    printf("particles %zu  steps %ld  threads %d  box %.3g m\n", n, steps, threads, box);
    printf("loop time %.3f s  rebuilds %ld  sorts %ld  pairs %zu  contacts/particle %.2f\n",
           st.loop_seconds, st.rebuilds, st.sorts, st.pairs, cpp);
    printf("contacts %zu  wall contacts %zu  spilled reactions %zu\n", st.contacts,
           st.wall_contacts, st.spills);
    printf("tangential friction: %s\n", have_tangential ? "on (Mindlin, mu = 0.3)" : "OFF");
    printf("peak RSS %ld kB  engine memory %.1f MB\n", ru.ru_maxrss, st.bytes / 1048576.0);
    printf("cpu time %.3f s (all threads; %.4g particle-steps per cpu-second)\n", cpu,
           (double)n * (double)steps / cpu);
    if (checksum) printf("state checksum %016llx\n", state_hash(dem_sim_particles(sim)));
    printf("%.4g particle-steps/s\n", pss);
  }
  dem_sim_free(sim);
  return 0;
}
