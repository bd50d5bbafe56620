/* The 3-D engine: impacts against closed forms, conservation laws, the neighbour list
 * against brute force, history carry-over, wall geometry, breakdown detection and
 * reproducibility with threads. */
#include <check.h>
#include <stdio.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "dem/contact.h"
#include "dem/engine.h"
#include "dem/material.h"
#include "dem/params.h"
#include "dem/tangential.h"
#include "dem/impact.h"

static const double RHO = 2500.0, E_MOD = 1e8, NU = 0.3;

/* A simulation with one material and `law` (hertz or linear) between everything. */
static dem_sim *make_sim(const char *law, double e, double kn, int *mat) {
  dem_err err = {0};
  dem_sim *s = dem_sim_create(&err);
  ck_assert_ptr_nonnull(s);
  ck_assert_int_eq(dem_sim_add_material(s, RHO, mat, &err), DEM_OK);
  dem_params ps;
  dem_params_init(&ps);
  dem_params_set(&ps, "E", E_MOD, "test", &err);
  dem_params_set(&ps, "nu", NU, "test", &err);
  dem_params_set(&ps, "e", e, "test", &err);
  if (kn > 0) dem_params_set(&ps, "kn", kn, "test", &err);
  dem_contact ct;
  const dem_law *l = dem_contact_law_find(law);
  ck_assert_ptr_nonnull(l);
  ck_assert_int_eq(dem_contact_setup(&ct, l, &ps, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_interaction(s, *mat, *mat, &ct, NULL, NULL, &err), DEM_OK);
  return s;
}

static size_t find_id(const dem_particles *p, uint32_t id) {
  for (size_t i = 0; i < p->n; i++)
    if (p->id[i] == id) return i;
  ck_abort_msg("particle id %u not found", (unsigned)id);
  return 0;
}

static double urand(unsigned *st) {
  *st = *st * 1103515245u + 12345u;
  return ((*st >> 8) & 0xffffff) / 16777216.0;
}

/* Head-on impact of two unequal spheres: maximum overlap against Hertz's closed form
 * alpha_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5), and the restitution of the law. */
static void head_on(double e, double *amax_out, double *amax_ref, double *e_out) {
  int mat;
  dem_sim *s = make_sim("hertz", e, 0, &mat);
  dem_err err = {0};
  const double r1 = 4.385e-4, r2 = 6.17e-4, v = 0.731;
  const double x1[3] = {0, 0, 0}, x2[3] = {r1 + r2 + 1e-6, 2e-7, -1e-7};
  /* collide along the line of centres */
  double d[3] = {x2[0] - x1[0], x2[1] - x1[1], x2[2] - x1[2]};
  double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  double v1[3], v2[3];
  for (int k = 0; k < 3; k++) {
    v1[k] = 0.5 * v * d[k] / dl;
    v2[k] = -0.5 * v * d[k] / dl;
  }
  ck_assert_int_eq(dem_sim_add_particle(s, x1, v1, r1, mat, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_add_particle(s, x2, v2, r2, mat, &err), DEM_OK);
  double Rs = dem_reduced_radius(r1, r2);
  double m1 = dem_sphere_mass(r1, RHO), m2 = dem_sphere_mass(r2, RHO);
  double ms = dem_reduced_mass(m1, m2), Es = dem_reduced_modulus(E_MOD, NU, E_MOD, NU);
  *amax_ref = pow(15.0 * ms * v * v / (16.0 * Es * sqrt(Rs)), 0.4);
  double tc = 2.87 * pow(ms * ms / (Rs * Es * Es * v), 0.2); /* Hertz contact time */
  ck_assert_int_eq(dem_sim_set_dt(s, tc / 4000.0, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_skin(s, 1e-5, &err), DEM_OK);
  dem_particles *p = dem_sim_particles(s);
  double amax = 0.0, vrel_end = 0.0;
  for (int step = 0; step < 20000; step++) {
    ck_assert_int_eq(dem_sim_run(s, 1, &err), DEM_OK);
    size_t a = find_id(p, 0), b = find_id(p, 1);
    double dd[3], vv[3];
    for (int k = 0; k < 3; k++) {
      dd[k] = p->x[3 * b + k] - p->x[3 * a + k];
      vv[k] = p->v[3 * b + k] - p->v[3 * a + k];
    }
    double dist = sqrt(dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2]);
    double al = r1 + r2 - dist;
    if (al > amax) amax = al;
    if (amax > 0 && al < -1e-7) {
      vrel_end = (vv[0] * dd[0] + vv[1] * dd[1] + vv[2] * dd[2]) / dist;
      break;
    }
  }
  *amax_out = amax;
  *e_out = vrel_end / v;
  dem_sim_free(s);
}

START_TEST(test_head_on_hertz) {
  double amax, aref, e;
  head_on(1.0, &amax, &aref, &e);
  /* dt = t_c / 4000: the sampled maximum is within (pi/4000)^2 of the true one; the
   * integration error of velocity Verlet is O(dt^2). 1e-4 relative. */
  ck_assert_double_eq_tol(amax / aref, 1.0, 1e-4);
  ck_assert_double_eq_tol(e, 1.0, 1e-4);
  head_on(0.5, &amax, &aref, &e);
  /* damping acts on half-step velocities: O(dt) error in e; 2e-3 at t_c / 4000 */
  ck_assert_double_eq_tol(e, 0.5, 2e-3);
  ck_assert(amax < aref);
}
END_TEST

static void momentum(const dem_particles *p, double P[3], double L[3]) {
  for (int k = 0; k < 3; k++) P[k] = L[k] = 0.0;
  for (size_t i = 0; i < p->n; i++) {
    const double *x = p->x + 3 * i, *v = p->v + 3 * i, *w = p->omega + 3 * i;
    double m = p->mass[i];
    for (int k = 0; k < 3; k++) P[k] += m * v[k];
    L[0] += m * (x[1] * v[2] - x[2] * v[1]) + p->inertia[i] * w[0];
    L[1] += m * (x[2] * v[0] - x[0] * v[2]) + p->inertia[i] * w[1];
    L[2] += m * (x[0] * v[1] - x[1] * v[0]) + p->inertia[i] * w[2];
  }
}

START_TEST(test_oblique_momentum) {
  int mat;
  dem_sim *s = make_sim("hertz", 0.5, 0, &mat);
  dem_err err = {0};
  const double r1 = 5e-4, r2 = 3.7e-4;
  const double x1[3] = {0, 0, 0}, x2[3] = {1.5e-3, 4.1e-4, 1.3e-4};
  const double v1[3] = {0.9, 0.05, -0.02}, v2[3] = {-0.4, 0.0, 0.03};
  dem_sim_add_particle(s, x1, v1, r1, mat, &err);
  dem_sim_add_particle(s, x2, v2, r2, mat, &err);
  dem_sim_set_dt(s, 2e-8, &err);
  dem_sim_set_skin(s, 5e-5, &err);
  dem_particles *p = dem_sim_particles(s);
  double P0[3], L0[3], P1[3], L1[3];
  momentum(p, P0, L0);
  ck_assert_int_eq(dem_sim_run(s, 100000, &err), DEM_OK);
  dem_sim_stats st;
  dem_sim_get_stats(s, &st);
  momentum(p, P1, L1);
  /* they did collide: the relative velocity changed */
  size_t a = find_id(p, 0);
  ck_assert(fabs(p->v[3 * a] - 0.9) > 0.1);
  double Pn = sqrt(P0[0] * P0[0] + P0[1] * P0[1] + P0[2] * P0[2]);
  for (int k = 0; k < 3; k++) ck_assert_double_eq_tol(P1[k], P0[k], 1e-12 * Pn);
  /* angular momentum about the origin (no tangential force: spins stay 0) */
  double Ln = sqrt(L0[0] * L0[0] + L0[1] * L0[1] + L0[2] * L0[2]);
  for (int k = 0; k < 3; k++) ck_assert_double_eq_tol(L1[k], L0[k], 1e-9 * Ln);
  dem_sim_free(s);
}
END_TEST

/* Elastic energy of the Hertz contacts (brute force): 8/15 E* sqrt(R*) alpha^(5/2). */
static double hertz_energy(dem_sim *s, double box) {
  const dem_particles *p = dem_sim_particles(s);
  double Es = dem_reduced_modulus(E_MOD, NU, E_MOD, NU), U = 0.0;
  for (size_t i = 0; i < p->n; i++) {
    for (size_t j = i + 1; j < p->n; j++) {
      double d2 = 0;
      for (int k = 0; k < 3; k++) d2 += pow(p->x[3 * i + k] - p->x[3 * j + k], 2);
      double al = p->radius[i] + p->radius[j] - sqrt(d2);
      if (al > 0)
        U += 8.0 / 15.0 * Es * sqrt(dem_reduced_radius(p->radius[i], p->radius[j])) *
             pow(al, 2.5);
    }
    for (int k = 0; k < 3; k++) {
      double lo = p->radius[i] - p->x[3 * i + k], hi = p->x[3 * i + k] + p->radius[i] - box;
      if (lo > 0) U += 8.0 / 15.0 * Es * sqrt(p->radius[i]) * pow(lo, 2.5);
      if (hi > 0) U += 8.0 / 15.0 * Es * sqrt(p->radius[i]) * pow(hi, 2.5);
    }
  }
  return U;
}

static void add_box(dem_sim *s, double box, int mat) {
  dem_err err = {0};
  for (int k = 0; k < 3; k++) {
    dem_wall_spec lo = {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 0}, 0, {0, 0, 0}, mat};
    dem_wall_spec hi = lo;
    lo.n[k] = 1.0;
    hi.p[k] = box;
    hi.n[k] = -1.0;
    ck_assert_int_eq(dem_sim_add_wall(s, &lo, NULL, &err), DEM_OK);
    ck_assert_int_eq(dem_sim_add_wall(s, &hi, NULL, &err), DEM_OK);
  }
}

/* A gas of polydisperse spheres in a box of walls, random velocities, no gravity. */
static dem_sim *gas(int n, double box, unsigned seed, const char *law, double e, int *mat) {
  dem_sim *s = make_sim(law, e, 0, mat);
  dem_err err = {0};
  unsigned st = seed;
  int placed = 0;
  while (placed < n) {
    double r = 2.5e-4 * (1.0 + urand(&st)), x[3], v[3];
    for (int k = 0; k < 3; k++) {
      x[k] = r + (box - 2 * r) * urand(&st);
      v[k] = 0.5 * (2 * urand(&st) - 1);
    }
    const dem_particles *p = dem_sim_particles(s);
    int ok = 1;
    for (size_t i = 0; i < p->n && ok; i++) {
      double d2 = 0;
      for (int k = 0; k < 3; k++) d2 += pow(p->x[3 * i + k] - x[k], 2);
      ok = sqrt(d2) > p->radius[i] + r;
    }
    if (!ok) continue;
    ck_assert_int_eq(dem_sim_add_particle(s, x, v, r, *mat, &err), DEM_OK);
    placed++;
  }
  add_box(s, box, *mat);
  return s;
}

START_TEST(test_energy_conservation) {
  int mat;
  const double box = 4e-3;
  dem_sim *s = gas(40, box, 7u, "hertz", 1.0, &mat);
  dem_err err = {0};
  /* contact time at v ~ 1 m/s for r = 0.25 mm is ~ 2e-6 s: dt = 2e-8 gives ~100 steps */
  dem_sim_set_dt(s, 2e-8, &err);
  dem_sim_set_skin(s, 5e-5, &err);
  double E0 = dem_sim_kinetic_energy(s) + hertz_energy(s, box);
  long collisions = 0;
  double worst = 0.0;
  for (int seg = 0; seg < 20; seg++) {
    ck_assert_int_eq(dem_sim_run(s, 5000, &err), DEM_OK);
    dem_sim_stats st;
    dem_sim_get_stats(s, &st);
    collisions += (long)(st.contacts + st.wall_contacts);
    double E = dem_sim_kinetic_energy(s) + hertz_energy(s, box);
    double rel = fabs(E - E0) / E0;
    worst = rel > worst ? rel : worst;
  }
  /* ~ 40 particles crossing a 4 mm box at 0.5 m/s for 2 ms: several hundred collisions.
   * Velocity Verlet conserves energy to O(dt^2) within a contact and exactly between
   * contacts; 1e-4 relative over 1e5 steps. */
  ck_assert_msg(worst < 1e-4, "energy drift %g", worst);
  dem_sim_stats st;
  dem_sim_get_stats(s, &st);
  ck_assert(st.rebuilds > 5);
  (void)collisions;
  dem_sim_free(s);
}
END_TEST

START_TEST(test_free_flight) {
  int mat;
  dem_sim *s = make_sim("hertz", 0.5, 0, &mat);
  dem_err err = {0};
  const double g[3] = {0.3, -1.1, -9.81};
  dem_sim_set_gravity(s, g);
  unsigned st = 3u;
  for (int i = 0; i < 30; i++) {
    double x[3] = {i * 3e-3, urand(&st) * 1e-3, urand(&st) * 1e-3};
    double v[3] = {urand(&st) - 0.5, urand(&st) - 0.5, urand(&st) - 0.5};
    dem_sim_add_particle(s, x, v, 4e-4 + 1e-4 * urand(&st), mat, &err);
  }
  dem_sim_set_dt(s, 1e-5, &err);
  dem_sim_set_skin(s, 1e-4, &err);
  dem_particles *p = dem_sim_particles(s);
  double P0[3], L0[3], P1[3], L1[3];
  momentum(p, P0, L0);
  double M = 0;
  for (size_t i = 0; i < p->n; i++) M += p->mass[i];
  ck_assert_int_eq(dem_sim_run(s, 1000, &err), DEM_OK);
  momentum(p, P1, L1);
  double T = 1000 * 1e-5;
  for (int k = 0; k < 3; k++) ck_assert_double_eq_tol(P1[k], P0[k] + M * g[k] * T, 1e-12);
  dem_sim_set_gravity(s, (double[3]){0, 0, 0});
  momentum(p, P0, L0);
  ck_assert_int_eq(dem_sim_run(s, 1000, &err), DEM_OK);
  momentum(p, P1, L1);
  for (int k = 0; k < 3; k++) {
    ck_assert_double_eq_tol(P1[k], P0[k], 1e-15);
    ck_assert_double_eq_tol(L1[k], L0[k], 1e-15);
  }
  dem_sim_free(s);
}
END_TEST

typedef struct idpair {
  uint32_t a, b;
} idpair;

static int cmp_pair(const void *x, const void *y) {
  const idpair *p = x, *q = y;
  if (p->a != q->a) return p->a < q->a ? -1 : 1;
  return (p->b > q->b) - (p->b < q->b);
}

/* The list's pairs by particle id, sorted. */
static size_t list_pairs(dem_sim *s, idpair **out) {
  const dem_particles *p = dem_sim_particles(s);
  size_t np = dem_sim_neighbour_pairs(s, NULL, 0);
  uint32_t *raw = malloc(2 * (np + 1) * sizeof *raw);
  dem_sim_neighbour_pairs(s, raw, np);
  idpair *l = malloc((np + 1) * sizeof *l);
  for (size_t k = 0; k < np; k++) {
    uint32_t a = p->id[raw[2 * k]], b = p->id[raw[2 * k + 1]];
    l[k].a = a < b ? a : b;
    l[k].b = a < b ? b : a;
  }
  free(raw);
  qsort(l, np, sizeof *l, cmp_pair);
  *out = l;
  return np;
}

/* Brute force: pairs with distance < r_i + r_j + cut_extra. */
static size_t brute_pairs(dem_sim *s, double extra, idpair **out) {
  const dem_particles *p = dem_sim_particles(s);
  size_t cap = 1024, m = 0;
  idpair *l = malloc(cap * sizeof *l);
  for (size_t i = 0; i < p->n; i++)
    for (size_t j = i + 1; j < p->n; j++) {
      double d2 = 0;
      for (int k = 0; k < 3; k++) d2 += pow(p->x[3 * i + k] - p->x[3 * j + k], 2);
      double c = p->radius[i] + p->radius[j] + extra;
      if (d2 < c * c) {
        if (m == cap) l = realloc(l, (cap *= 2) * sizeof *l);
        uint32_t a = p->id[i], b = p->id[j];
        l[m].a = a < b ? a : b;
        l[m].b = a < b ? b : a;
        m++;
      }
    }
  qsort(l, m, sizeof *l, cmp_pair);
  *out = l;
  return m;
}

START_TEST(test_neighbour_brute_force) {
  int mat;
  const double box = 5e-3, skin = 1.3e-4;
  dem_sim *s = gas(300, box, 11u + (unsigned)_i, "hertz", 1.0, &mat);
  dem_err err = {0};
  dem_sim_set_dt(s, 4e-8, &err);
  dem_sim_set_skin(s, skin, &err);
  dem_sim_set_sort_interval(s, 2);
  for (int round = 0; round < 6; round++) {
    /* right after a build: exactly the pairs within r_i + r_j + skin */
    ck_assert_int_eq(dem_sim_build_neighbours(s, &err), DEM_OK);
    idpair *L, *B;
    size_t nl = list_pairs(s, &L), nb = brute_pairs(s, skin, &B);
    ck_assert_uint_eq(nl, nb);
    ck_assert_int_eq(memcmp(L, B, nl * sizeof *L), 0);
    free(L);
    free(B);
    /* after running (the engine rebuilds on its own): every pair in contact is listed */
    ck_assert_int_eq(dem_sim_run(s, 5000, &err), DEM_OK);
    nl = list_pairs(s, &L);
    nb = brute_pairs(s, 0.0, &B);
    for (size_t k = 0; k < nb; k++)
      ck_assert_ptr_nonnull(bsearch(B + k, L, nl, sizeof *L, cmp_pair));
    free(L);
    free(B);
  }
  dem_sim_stats st;
  dem_sim_get_stats(s, &st);
  ck_assert_int_ge(st.rebuilds, 10);
  ck_assert(st.sorts > 2);
  dem_sim_free(s);
}
END_TEST

/* Sentinels written into every history block follow their pair through a rebuild with
 * spatial re-ordering. */
START_TEST(test_history_survives_rebuild) {
  int mat;
  const double box = 4e-3, skin = 2e-4;
  dem_sim *s = gas(200, box, 5u, "hertz", 1.0, &mat);
  dem_err err = {0};
  dem_sim_set_skin(s, skin, &err);
  dem_sim_set_sort_interval(s, 1);
  ck_assert_int_eq(dem_sim_build_neighbours(s, &err), DEM_OK);
  dem_particles *p = dem_sim_particles(s);
  int nh = dem_sim_history_size(s);
  ck_assert_int_ge(nh, 4);
  size_t np = dem_sim_neighbour_pairs(s, NULL, 0);
  ck_assert(np > 50);
  uint32_t *raw = malloc(2 * np * sizeof *raw);
  dem_sim_neighbour_pairs(s, raw, np);
  for (size_t k = 0; k < np; k++) {
    double *h = dem_sim_pair_history(s, raw[2 * k], raw[2 * k + 1]);
    ck_assert_ptr_nonnull(h);
    uint32_t a = p->id[raw[2 * k]], b = p->id[raw[2 * k + 1]];
    uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
    for (int q = 0; q < nh; q++) h[q] = 1.0 + lo * 1000.0 + hi + 0.125 * q;
  }
  /* shift everything: cells change, the sort permutes the particles */
  uint32_t *ids = malloc(2 * np * sizeof *ids);
  for (size_t k = 0; k < 2 * np; k++) ids[k] = p->id[raw[k]];
  for (size_t i = 0; i < p->n; i++) p->x[3 * i] += 0.37 * skin * (1 + (p->id[i] % 3)) / 3.0;
  dem_sim_invalidate(s);
  ck_assert_int_eq(dem_sim_build_neighbours(s, &err), DEM_OK);
  dem_sim_stats st;
  dem_sim_get_stats(s, &st);
  ck_assert_int_ge(st.sorts, 2);
  size_t found = 0;
  for (size_t k = 0; k < np; k++) {
    size_t i = find_id(p, ids[2 * k]), j = find_id(p, ids[2 * k + 1]);
    double *h = dem_sim_pair_history(s, i, j);
    if (!h) continue; /* the pair moved out of range */
    found++;
    uint32_t lo = ids[2 * k] < ids[2 * k + 1] ? ids[2 * k] : ids[2 * k + 1];
    uint32_t hi = ids[2 * k] < ids[2 * k + 1] ? ids[2 * k + 1] : ids[2 * k];
    for (int q = 0; q < nh; q++) ck_assert_double_eq(h[q], 1.0 + lo * 1000.0 + hi + 0.125 * q);
  }
  ck_assert(found > np * 9 / 10);
  /* a new pair starts from a zero block */
  size_t np2 = dem_sim_neighbour_pairs(s, NULL, 0);
  uint32_t *raw2 = malloc(2 * np2 * sizeof *raw2);
  dem_sim_neighbour_pairs(s, raw2, np2);
  for (size_t k = 0; k < np2; k++) {
    double *h = dem_sim_pair_history(s, raw2[2 * k], raw2[2 * k + 1]);
    if (h[0] == 0.0)
      for (int q = 0; q < nh; q++) ck_assert_double_eq(h[q], 0.0);
  }
  free(raw);
  free(raw2);
  free(ids);
  dem_sim_free(s);
}
END_TEST

/* One particle against one wall: the force is Hertz at the analytic penetration depth along
 * the analytic normal, and the wall gets the reaction. */
static void wall_case(const dem_wall_spec *w, const double x[3], double r, double alpha,
                      const double n[3], double Rstar) {
  int mat;
  dem_sim *s = make_sim("hertz", 1.0, 0, &mat);
  dem_err err = {0};
  dem_wall_spec ws = *w;
  ws.material = mat;
  ck_assert_int_eq(dem_sim_add_wall(s, &ws, NULL, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_add_particle(s, x, NULL, r, mat, &err), DEM_OK);
  dem_sim_set_dt(s, 1e-9, &err);
  ck_assert_int_eq(dem_sim_run(s, 0, &err), DEM_OK);
  const dem_particles *p = dem_sim_particles(s);
  double Es = dem_reduced_modulus(E_MOD, NU, E_MOD, NU);
  double fref = 4.0 / 3.0 * Es * sqrt(Rstar) * pow(alpha, 1.5);
  double wf[3];
  dem_sim_wall_load(s, 0, wf, NULL, NULL);
  for (int k = 0; k < 3; k++) {
    ck_assert_double_eq_tol(p->f[k], fref * n[k], 1e-9 * fref);
    ck_assert_double_eq_tol(wf[k], -fref * n[k], 1e-9 * fref);
  }
  dem_sim_free(s);
}

START_TEST(test_walls) {
  const double r = 4.1e-4;
  /* plane through (1,2,3) mm with a tilted normal */
  double nn[3] = {0.3, -0.5, 0.8}, l = sqrt(0.09 + 0.25 + 0.64);
  for (int k = 0; k < 3; k++) nn[k] /= l;
  dem_wall_spec pl = {DEM_WALL_PLANE, {1e-3, 2e-3, 3e-3}, {0.3, -0.5, 0.8}, 0, {0, 0, 0}, 0};
  double d = r - 2.3e-6, x[3];
  for (int k = 0; k < 3; k++) x[k] = pl.p[k] + d * nn[k] + (k == 0 ? 1e-3 : 0) * 0;
  wall_case(&pl, x, r, 2.3e-6, nn, r);
  /* inside of a die: axis along z through (0.5, -0.2, 0) mm, radius 10 mm */
  dem_wall_spec cy = {DEM_WALL_CYLINDER, {5e-4, -2e-4, 0}, {0, 0, 2}, 1e-2, {0, 0, 0}, 0};
  double phi = 0.7, rho = 1e-2 - r + 3.1e-6;
  double xc[3] = {5e-4 + rho * cos(phi), -2e-4 + rho * sin(phi), 1.7e-3};
  double nc[3] = {-cos(phi), -sin(phi), 0};
  wall_case(&cy, xc, r, 3.1e-6, nc, r * 1e-2 / (1e-2 - r));
  /* disc (piston) facing -z at z = 5 mm, radius 3 mm: face contact ... */
  dem_wall_spec dc = {DEM_WALL_DISC, {0, 0, 5e-3}, {0, 0, -1}, 3e-3, {0, 0, 0}, 0};
  double xd[3] = {1e-3, -1.5e-3, 5e-3 - r + 1.9e-6};
  wall_case(&dc, xd, r, 1.9e-6, (double[3]){0, 0, -1}, r);
  /* ... and rim contact beyond its edge */
  double e[3] = {cos(0.3), sin(0.3), 0}, q[3] = {3e-3 * e[0], 3e-3 * e[1], 5e-3};
  double dir[3] = {e[0] * 0.6, e[1] * 0.6, -0.8};
  double xr[3];
  for (int k = 0; k < 3; k++) xr[k] = q[k] + (r - 2.7e-6) * dir[k];
  wall_case(&dc, xr, r, 2.7e-6, dir, r);
  /* out of reach: no force */
  {
    int mat;
    dem_sim *s = make_sim("hertz", 1.0, 0, &mat);
    dem_err err = {0};
    dem_wall_spec w = cy;
    w.material = mat;
    dem_sim_add_wall(s, &w, NULL, &err);
    double xo[3] = {5e-4 + 1e-2 - r - 1e-6, -2e-4, 0};
    dem_sim_add_particle(s, xo, NULL, r, mat, &err);
    dem_sim_set_dt(s, 1e-9, &err);
    ck_assert_int_eq(dem_sim_run(s, 0, &err), DEM_OK);
    ck_assert_double_eq(dem_sim_particles(s)->f[0], 0.0);
    dem_sim_free(s);
  }
}
END_TEST

/* A settled-ish block of spheres under gravity in a box, for the thread tests. */
static dem_sim *block_law(int nthreads, const char *law, double kn) {
  int mat;
  dem_sim *s = make_sim(law, 0.5, kn, &mat);
  dem_err err = {0};
  /* the bottom 3000 spheres of the peers' settled bed (d = 1 mm, box 30 x 30 mm) */
  const double box = 30e-3;
  FILE *fp = fopen(DEM_SOURCE_DIR "/../shared/bench/dense20k.csv", "r");
  ck_assert_ptr_nonnull(fp);
  char line[256];
  int n = 0;
  while (n < 3000 && fgets(line, sizeof line, fp)) {
    double x[4];
    if (sscanf(line, "%lf,%lf,%lf,%lf", &x[0], &x[1], &x[2], &x[3]) != 4) continue;
    ck_assert_int_eq(dem_sim_add_particle(s, x, NULL, x[3], mat, &err), DEM_OK);
    n++;
  }
  fclose(fp);
  for (int w = 0; w < 5; w++) {
    dem_wall_spec ws = {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 0}, 0, {0, 0, 0}, mat};
    ws.n[w / 2] = w % 2 ? -1.0 : 1.0;
    if (w % 2) ws.p[w / 2] = box;
    ck_assert_int_eq(dem_sim_add_wall(s, &ws, NULL, &err), DEM_OK);
  }
  dem_sim_set_gravity(s, (double[3]){0, 0, -9.81});
  dem_sim_set_dt(s, 1.5e-6, &err);
  dem_sim_set_skin(s, 1e-4, &err);
  if (dem_sim_set_threads(s, nthreads, &err) != DEM_OK) {
    dem_sim_free(s);
    return NULL;
  }
  return s;
}

static dem_sim *block(int nthreads) { return block_law(nthreads, "hertz", 0); }

static void sorted_state(dem_sim *s, double *out) {
  const dem_particles *p = dem_sim_particles(s);
  for (size_t i = 0; i < p->n; i++)
    for (int k = 0; k < 3; k++) {
      out[6 * p->id[i] + k] = p->x[3 * i + k];
      out[6 * p->id[i] + 3 + k] = p->v[3 * i + k];
    }
}

START_TEST(test_threads_reproducible) {
  dem_err err = {0};
  dem_sim *a = block(2), *b = block(2), *c = block(1);
  if (!a) { /* built without OpenMP */
    dem_sim_free(c);
    return;
  }
  ck_assert_int_eq(dem_sim_run(a, 3000, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_run(b, 3000, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_run(c, 3000, &err), DEM_OK);
  size_t n = dem_sim_particles(a)->n;
  double *sa = malloc(6 * n * sizeof *sa), *sb = malloc(6 * n * sizeof *sb),
         *sc = malloc(6 * n * sizeof *sc);
  sorted_state(a, sa);
  sorted_state(b, sb);
  sorted_state(c, sc);
  /* same thread count: bit-identical */
  ck_assert_int_eq(memcmp(sa, sb, 6 * n * sizeof *sa), 0);
  /* other thread count: round-off only (a short run of a dense bed: differences of order
   * 1e-16 grow slowly; positions within 1e-12 m, velocities within 1e-9 m/s) */
  for (size_t i = 0; i < n; i++)
    for (int k = 0; k < 3; k++) {
      ck_assert_double_eq_tol(sa[6 * i + k], sc[6 * i + k], 1e-12);
      ck_assert_double_eq_tol(sa[6 * i + 3 + k], sc[6 * i + 3 + k], 1e-9);
    }
  dem_sim_stats st;
  dem_sim_get_stats(a, &st);
  ck_assert_msg(st.contacts > n / 2, "contacts %zu", st.contacts); /* a dense bed */
  free(sa);
  free(sb);
  free(sc);
  dem_sim_free(a);
  dem_sim_free(b);
  dem_sim_free(c);
}
END_TEST

/* The runaway message names the contact (run.c, overlap_error). Oracle: an undamped linear
 * spring (e = 1) conserves energy, so when the overlap alpha first exceeds the limit the
 * approach speed is sqrt(v0^2 - k alpha^2 / m*) and the normal force k alpha; m* = m/2 for
 * two equal spheres, m against a fixed wall. The stop comes within one step of the limit,
 * so alpha is read back from the engine (stats) rather than assumed. */
static void runaway_case(int wall) {
  dem_err err = {0};
  int mat;
  const double k = 1e3, r = 5e-4, v0 = 1.0, m = dem_sphere_mass(r, RHO);
  const double ms = wall ? m : 0.5 * m, tc = sqrt(ms / k);
  dem_sim *s = make_sim("linear", 1.0, k, &mat);
  if (wall) {
    dem_wall_spec fl = {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 1}, 0, {0, 0, 0}, mat};
    ck_assert_int_eq(dem_sim_add_wall(s, &fl, NULL, &err), DEM_OK);
    ck_assert_int_eq(dem_sim_add_particle(s, (double[3]){0, 0, r + 1e-6},
                                          (double[3]){0, 0, -v0}, r, mat, &err), DEM_OK);
  } else {
    ck_assert_int_eq(dem_sim_add_particle(s, (double[3]){-r - 1e-6, 0, 0},
                                          (double[3]){0.5 * v0, 0, 0}, r, mat, &err), DEM_OK);
    ck_assert_int_eq(dem_sim_add_particle(s, (double[3]){r + 1e-6, 0, 0},
                                          (double[3]){-0.5 * v0, 0, 0}, r, mat, &err), DEM_OK);
  }
  ck_assert_int_eq(dem_sim_set_skin(s, 0.2 * r, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_dt(s, 0.002 * tc, &err), DEM_OK);
  dem_breakdown bd;
  dem_breakdown_defaults(&bd);
  bd.max_overlap_frac = 0.02; /* the undamped peak is v0 tc = 0.05 r (pair), 0.07 r (wall) */
  ck_assert_int_eq(dem_sim_set_breakdown(s, &bd, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_run(s, 100000, &err), DEM_ERUNAWAY);
  dem_sim_stats st;
  dem_sim_get_stats(s, &st);
  const double alpha = st.max_overlap_frac * r;
  ck_assert(alpha > 0.02 * r && alpha < 0.021 * r);
  const char *b = strstr(err.msg, " between particle ");
  ck_assert_msg(b != NULL, "%s", err.msg);
  if (wall) ck_assert_msg(strstr(err.msg, "and wall 0 (plane)") != NULL, "%s", err.msg);
  else ck_assert_msg(strstr(err.msg, "between particle 1 ") != NULL ||
                     strstr(err.msg, "between particle 0 ") != NULL, "%s", err.msg);
  if (!wall) ck_assert_msg(strstr(err.msg, "and particle ") != NULL, "%s", err.msg);
  double fn = 0.0, vn = 0.0;
  const char *f = strstr(err.msg, "normal force "), *a = strstr(err.msg, "approach speed ");
  ck_assert_msg(f && a, "%s", err.msg);
  ck_assert_int_eq(sscanf(f, "normal force %lf N", &fn), 1);
  ck_assert_int_eq(sscanf(a, "approach speed %lf m/s", &vn), 1);
  ck_assert_msg(strstr(err.msg, "1 contact above the limit") != NULL, "%s", err.msg);
  /* the message prints 3 significant digits: 0.5 % */
  ck_assert_msg(fabs(fn - k * alpha) < 5e-3 * k * alpha, "fn %g, k alpha %g", fn, k * alpha);
  const double ve = sqrt(v0 * v0 - k * alpha * alpha / ms);
  ck_assert_msg(fabs(vn - ve) < 5e-3 * ve, "vn %g, expected %g (%s)", vn, ve, err.msg);
  dem_sim_free(s);
}

START_TEST(test_runaway_names_contact) {
  runaway_case(0);
  runaway_case(1);
}
END_TEST

/* peak_overlap_frac keeps the largest overlap of every step: a head-on undamped linear
 * collision peaks at alpha_max = v0 sqrt(m* / k) (energy balance) and is over when the
 * spheres separate, where max_overlap_frac is back to 0; the reset starts it again. */
START_TEST(test_peak_overlap) {
  dem_err err = {0};
  int mat;
  const double k = 1e3, r = 5e-4, v0 = 1.0, ms = 0.5 * dem_sphere_mass(r, RHO);
  const double tc = sqrt(ms / k);
  dem_sim *s = make_sim("linear", 1.0, k, &mat);
  ck_assert_int_eq(dem_sim_add_particle(s, (double[3]){-r - 1e-6, 0, 0},
                                        (double[3]){0.5 * v0, 0, 0}, r, mat, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_add_particle(s, (double[3]){r + 1e-6, 0, 0},
                                        (double[3]){-0.5 * v0, 0, 0}, r, mat, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_skin(s, 0.2 * r, &err), DEM_OK);
  const double dt = 0.002 * tc;
  ck_assert_int_eq(dem_sim_set_dt(s, dt, &err), DEM_OK);
  /* contact lasts pi tc; run to twice that after the 1e-6 m approach */
  const long steps = (long)((2e-6 / v0 + 2.0 * M_PI * tc) / dt);
  ck_assert_int_eq(dem_sim_run(s, steps, &err), DEM_OK);
  dem_sim_stats st;
  dem_sim_get_stats(s, &st);
  ck_assert_double_eq(st.max_overlap_frac, 0.0);
  const double want = v0 * tc / r; /* 0.051 */
  /* sampled once per step: the peak is missed by at most (omega dt)^2 / 8 relative */
  ck_assert_msg(fabs(st.peak_overlap_frac - want) < 1e-4 * want, "peak %.6g, want %.6g",
                st.peak_overlap_frac, want);
  dem_sim_reset_peak_overlap(s);
  dem_sim_get_stats(s, &st);
  ck_assert_double_eq(st.peak_overlap_frac, 0.0);
  dem_sim_free(s);
}
END_TEST

START_TEST(test_breakdown) {
  dem_err err = {0};
  /* NaN velocity */
  {
    dem_sim *s = block(1);
    dem_sim_particles(s)->v[3 * 17 + 1] = NAN;
    int rc = dem_sim_run(s, 500, &err);
    ck_assert_int_eq(rc, DEM_ENONFINITE);
    dem_sim_free(s);
  }
  /* time step far too large: runaway overlap */
  {
    dem_sim *s = block(1);
    dem_sim_set_dt(s, 2e-4, &err);
    int rc = dem_sim_run(s, 2000, &err);
    ck_assert_int_eq(rc, DEM_ERUNAWAY);
    ck_assert(strstr(err.msg, "overlap") != NULL);
    dem_sim_free(s);
  }
  /* unstable but the overlap check disabled: kinetic energy growth. A sphere squeezed
   * between two linear-spring planes (1e-5 m overlap each), no gravity, dt = 3/omega with
   * omega = sqrt(2k/m) > 2/omega: velocity Verlet amplifies the oscillation by 6.85 per step
   * while both contacts stay closed. */
  {
    int mat;
    dem_sim *s = make_sim("linear", 1.0, 1e3, &mat);
    const double r = 5e-4, g = 0.0, m = dem_sphere_mass(r, RHO), k = 2e3;
    dem_wall_spec fl = {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 1}, 0, {0, 0, 0}, mat};
    dem_wall_spec ce = {DEM_WALL_PLANE, {0, 0, 2 * r - 2e-5}, {0, 0, -1}, 0, {0, 0, 0}, mat};
    ck_assert_int_eq(dem_sim_add_wall(s, &fl, NULL, &err), DEM_OK);
    ck_assert_int_eq(dem_sim_add_wall(s, &ce, NULL, &err), DEM_OK);
    const double x[3] = {0, 0, r - 1e-5 + 1e-12};
    ck_assert_int_eq(dem_sim_add_particle(s, x, NULL, r, mat, &err), DEM_OK);
    dem_sim_set_gravity(s, (double[3]){0, 0, -g});
    dem_sim_set_dt(s, 3.0 / sqrt(k / m), &err);
    dem_breakdown bd;
    dem_breakdown_defaults(&bd);
    bd.max_overlap_frac = 1e30;
    bd.check_interval = 1;
    bd.ke_strikes = 5;
    ck_assert_int_eq(dem_sim_set_breakdown(s, &bd, &err), DEM_OK);
    memset(&err, 0, sizeof err);
    int rc = dem_sim_run(s, 100, &err);
    ck_assert_msg(rc == DEM_EUNSTABLE, "rc %d: %s", rc, err.msg);
    ck_assert(strstr(err.msg, "kinetic energy") != NULL);
    dem_sim_free(s);
  }
  /* a stable step on a resting sphere under strong gravity: not flagged */
  {
    int mat;
    dem_sim *s = make_sim("linear", 1.0, 1e3, &mat);
    const double r = 5e-4, g = 1e4, m = dem_sphere_mass(r, RHO), k = 1e3;
    dem_wall_spec fl = {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 1}, 0, {0, 0, 0}, mat};
    dem_sim_add_wall(s, &fl, NULL, &err);
    const double x[3] = {0, 0, r - m * g / k + 1e-7};
    dem_sim_add_particle(s, x, NULL, r, mat, &err);
    dem_sim_set_gravity(s, (double[3]){0, 0, -g});
    dem_sim_set_dt(s, 0.1 / sqrt(k / m), &err);
    /* default thresholds: the check interval (100 steps) spans several oscillation
     * periods (63 steps at omega dt = 0.1), so the exchange between elastic and kinetic
     * energy averages out */
    ck_assert_int_eq(dem_sim_run(s, 5000, &err), DEM_OK);
    dem_sim_free(s);
  }
  /* energy leaving through a retreating wall is no gain: a sphere squeezed between two
   * frictionless planes (1e-5 m overlap each) slides along them at a constant 1 mm/s while
   * both planes back off at 0.1 mm/s. Its kinetic energy (6.5e-13 J) does not change; per
   * check interval the released elastic energy does ~7e-10 J of work on the planes. The
   * balance without the contacts' elastic energy read that as an unexplained gain of
   * ~1000 x the kinetic energy, and a consolidated bed under the retreating servo piston
   * (docs/validation-study.md, dt factor 0.1) was stopped as unstable. */
  {
    int mat;
    dem_sim *s = make_sim("linear", 1.0, 1e3, &mat);
    const double r = 5e-4, m = dem_sphere_mass(r, RHO), k = 1e3, vw = 1e-4, u = 1e-3;
    dem_wall_spec fl = {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 1}, 0, {0, 0, -vw}, mat};
    dem_wall_spec ce = {DEM_WALL_PLANE, {0, 0, 2 * r - 2e-5}, {0, 0, -1}, 0, {0, 0, vw}, mat};
    ck_assert_int_eq(dem_sim_add_wall(s, &fl, NULL, &err), DEM_OK);
    ck_assert_int_eq(dem_sim_add_wall(s, &ce, NULL, &err), DEM_OK);
    const double x[3] = {0, 0, r - 1e-5}, v[3] = {u, 0, 0};
    ck_assert_int_eq(dem_sim_add_particle(s, x, v, r, mat, &err), DEM_OK);
    dem_sim_set_gravity(s, (double[3]){0, 0, 0});
    dem_sim_set_dt(s, 0.1 / sqrt(k / m), &err);
    memset(&err, 0, sizeof err);
    int rc = dem_sim_run(s, 2000, &err); /* 20 check intervals; the planes back off 0.7 um */
    ck_assert_msg(rc == DEM_OK, "rc %d: %s", rc, err.msg);
    ck_assert_double_eq_tol(dem_sim_kinetic_energy(s), 0.5 * m * u * u, 1e-6 * m * u * u);
    dem_sim_free(s);
  }
  /* a stable run is not flagged */
  {
    dem_sim *s = block(1);
    ck_assert_int_eq(dem_sim_run(s, 2000, &err), DEM_OK);
    dem_sim_free(s);
  }
}
END_TEST

START_TEST(test_errors) {
  dem_err err = {0};
  dem_sim *s = dem_sim_create(&err);
  int m;
  ck_assert_int_eq(dem_sim_add_material(s, -1.0, &m, &err), DEM_ERANGE);
  ck_assert(strstr(err.msg, "rho") != NULL);
  ck_assert_int_eq(dem_sim_add_material(s, 2500.0, &m, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_add_particle(s, (double[3]){0, 0, 0}, NULL, -1e-3, m, &err),
                   DEM_ERANGE);
  ck_assert_int_eq(dem_sim_add_particle(s, (double[3]){0, 0, 0}, NULL, 1e-3, 3, &err),
                   DEM_ERANGE);
  ck_assert_int_eq(dem_sim_add_particle(s, (double[3]){0, 0, 0}, NULL, 1e-3, m, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_run(s, 1, &err), DEM_EMISSING); /* no dt */
  ck_assert_int_eq(dem_sim_set_dt(s, 0.0, &err), DEM_ERANGE);
  ck_assert_int_eq(dem_sim_set_dt(s, 1e-6, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_run(s, 1, &err), DEM_EMISSING); /* no interaction */
  ck_assert(strstr(err.msg, "interaction") != NULL);
  ck_assert_int_eq(dem_sim_set_skin(s, -1.0, &err), DEM_ERANGE);
  ck_assert_int_eq(dem_sim_set_threads(s, 0, &err), DEM_ERANGE);
  dem_wall_spec w = {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 0}, 0, {0, 0, 0}, m};
  ck_assert_int_eq(dem_sim_add_wall(s, &w, NULL, &err), DEM_EINVAL);
  w.kind = DEM_WALL_CYLINDER;
  w.n[2] = 1;
  ck_assert_int_eq(dem_sim_add_wall(s, &w, NULL, &err), DEM_ERANGE);
  dem_sim_free(s);
}
END_TEST

/* Hertz + Mindlin friction (mu) + rolling resistance (mu_r), restitution e. */
static dem_sim *make_sim_friction(double e, double mu, double mu_r, int *mat) {
  dem_err err = {0};
  dem_sim *s = dem_sim_create(&err);
  ck_assert_int_eq(dem_sim_add_material(s, RHO, mat, &err), DEM_OK);
  dem_params ps;
  dem_params_init(&ps);
  dem_params_set(&ps, "E", E_MOD, "test", &err);
  dem_params_set(&ps, "nu", NU, "test", &err);
  dem_params_set(&ps, "e", e, "test", &err);
  dem_params_set(&ps, "mu", mu, "test", &err);
  dem_params_set(&ps, "mu_r", mu_r, "test", &err);
  dem_contact ct;
  dem_tangential tg;
  dem_rolling rl;
  ck_assert_int_eq(dem_contact_setup(&ct, dem_contact_law_find("hertz"), &ps, &err), DEM_OK);
  ck_assert_int_eq(dem_tangential_setup(&tg, DEM_TANGENTIAL_MINDLIN, &ps, &err), DEM_OK);
  ck_assert_int_eq(dem_rolling_setup(&rl, &ps, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_interaction(s, *mat, *mat, &ct, &tg, &rl, &err), DEM_OK);
  return s;
}

/* Oblique impact with friction and spin: linear and angular momentum (orbital + spin) are
 * conserved to round-off (the contact point is shared by both spheres). */
START_TEST(test_oblique_friction) {
  int mat;
  dem_sim *s = make_sim_friction(0.5, 0.3, 0.0, &mat);
  dem_err err = {0};
  const double r1 = 5e-4, r2 = 3.7e-4;
  const double x1[3] = {0, 0, 0}, x2[3] = {1.5e-3, 4.1e-4, 1.3e-4};
  const double v1[3] = {0.9, 0.05, -0.02}, v2[3] = {-0.4, 0.0, 0.03};
  dem_sim_add_particle(s, x1, v1, r1, mat, &err);
  dem_sim_add_particle(s, x2, v2, r2, mat, &err);
  dem_sim_set_dt(s, 2e-8, &err);
  dem_sim_set_skin(s, 5e-5, &err);
  dem_particles *p = dem_sim_particles(s);
  double P0[3], L0[3], P1[3], L1[3];
  momentum(p, P0, L0);
  ck_assert_int_eq(dem_sim_run(s, 100000, &err), DEM_OK);
  momentum(p, P1, L1);
  double Pn = sqrt(P0[0] * P0[0] + P0[1] * P0[1] + P0[2] * P0[2]);
  for (int k = 0; k < 3; k++) ck_assert_double_eq_tol(P1[k], P0[k], 1e-12 * Pn);
  /* friction made them spin */
  size_t a = find_id(p, 0);
  double w = sqrt(pow(p->omega[3 * a], 2) + pow(p->omega[3 * a + 1], 2) + pow(p->omega[3 * a + 2], 2));
  ck_assert(w > 10.0);
  double Ln = sqrt(L0[0] * L0[0] + L0[1] * L0[1] + L0[2] * L0[2]);
  for (int k = 0; k < 3; k++) ck_assert_double_eq_tol(L1[k], L0[k], 1e-9 * Ln);
  dem_sim_free(s);
}
END_TEST

/* A sphere launched sliding (v0, no spin) on a floor: Coulomb friction turns sliding into
 * rolling at v = 5/7 v0, omega r = v (rigid-body result for a solid sphere), reached after
 * t = 2 v0 / (7 mu g). With rolling resistance mu_r the rolling sphere then decelerates at
 * 5/7 mu_r g. */
static void rolling_case(double mu_r, double *v_end, double *w_end, double *v_mid) {
  int mat;
  dem_sim *s = make_sim_friction(0.5, 0.3, mu_r, &mat);
  dem_err err = {0};
  const double r = 5e-4, g = 9.81, v0 = 0.1;
  double m = dem_sphere_mass(r, RHO), Es = dem_reduced_modulus(E_MOD, NU, E_MOD, NU);
  double aeq = pow(m * g / (4.0 / 3.0 * Es * sqrt(r)), 2.0 / 3.0);
  const double x[3] = {0, 0, r - aeq}, v[3] = {v0, 0, 0};
  dem_sim_add_particle(s, x, v, r, mat, &err);
  dem_wall_spec fl = {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 1}, 0, {0, 0, 0}, mat};
  dem_sim_add_wall(s, &fl, NULL, &err);
  dem_sim_set_gravity(s, (double[3]){0, 0, -g});
  dem_sim_set_dt(s, 1e-6, &err);
  dem_sim_set_skin(s, 1e-4, &err);
  /* rolling starts at 2 v0 / (7 mu g) = 9.7 ms */
  ck_assert_int_eq(dem_sim_run(s, 12000, &err), DEM_OK);
  dem_particles *p = dem_sim_particles(s);
  *v_mid = p->v[0];
  ck_assert_int_eq(dem_sim_run(s, 20000, &err), DEM_OK);
  *v_end = p->v[0];
  *w_end = p->omega[1] * r;
  dem_sim_free(s);
}

START_TEST(test_sliding_to_rolling) {
  double v, wr, vm;
  rolling_case(0.0, &v, &wr, &vm);
  /* 1%: the tangential spring's elastic oscillation and the Hertz bounce at the start */
  ck_assert_double_eq_tol(v, 0.1 * 5.0 / 7.0, 1e-2 * 0.1);
  ck_assert_double_eq_tol(wr, v, 1e-2 * v);
  double v2, wr2, vm2;
  rolling_case(0.01, &v2, &wr2, &vm2);
  /* deceleration 5/7 mu_r g over the last 20 ms: 1.4 mm/s; 25% (regularised torque) */
  double decel = (vm2 - v2) / 0.02;
  ck_assert_double_eq_tol(decel, 5.0 / 7.0 * 0.01 * 9.81, 0.25 * 5.0 / 7.0 * 0.01 * 9.81);
  ck_assert_double_eq_tol(wr2, v2, 2e-2 * v2);
}
END_TEST


/* Every law of the registry: two equal spheres colliding head-on in the engine against the
 * one-degree-of-freedom impact solver (dem/impact.h, target "pair", velocity Verlet with the
 * same step): restitution and maximum overlap. Parameter sets as in bench/bench_contact.c:
 * the reference case (ammonium fluorescein, thesis Tables 4.1/4.2) and the bulk set (thesis
 * Tables 6.2/6.3, d = 1 mm); the first one the law accepts is used. */
typedef struct {
  const char *key;
  double value;
} law_kv;
static const law_kv afl_set[] = {
    {"E", 1.2e9},    {"nu", 0.3},     {"gamma", 0.2},  {"py", 35.3e6},   {"kn", 1500.0},
    {"ke", 1500.0},  {"kp", 210.0},   {"kc", 20.0},    {"kcp", 20.0},    {"f0", 2.0525e-6},
    {"f0p", 4.0e-6}, {"ke_max", 1500.0}, {"phi_f", 0.02}, {"e", 0.9},    {NULL, 0.0}};
static const law_kv bulk_set[] = {
    {"E", 5e7},      {"nu", 0.3},     {"gamma", 2.0},  {"py", 5e7},      {"kn", 1e6},
    {"ke", 1e6},     {"kp", 1e5},     {"kc", 1e4},     {"kcp", 1e4},     {"f0", 6.2832e-3},
    {"f0p", 6.2832e-3}, {"ke_max", 1e6}, {"phi_f", 0.05}, {"e", 0.5},    {NULL, 0.0}};

/* The law's own keys of a set, plus the scene keys of the impact solver. */
static void law_params(const dem_law *law, const law_kv *set, double R, double rho,
                       dem_params *ps) {
  dem_params_init(ps);
  dem_params_set(ps, "R", R, "set", NULL);
  dem_params_set(ps, "rho", rho, "set", NULL);
  for (const law_kv *k = set; k->key; k++)
    if (dem_contact_law_has_coef(law, k->key) || !strcmp(k->key, "E") || !strcmp(k->key, "nu"))
      dem_params_set(ps, k->key, k->value, "set", NULL);
}

START_TEST(test_every_law_head_on) {
  const dem_law *law = dem_contact_law_at(_i);
  const law_kv *sets[2] = {afl_set, bulk_set};
  const double Rs[2] = {2.45e-6, 0.5e-3}, rhos[2] = {1350.0, 2500.0}, vs[2] = {5.0, 0.5};
  dem_params ps;
  dem_impact_scene sc;
  dem_contact ct;
  int k = 0;
  for (; k < 2; k++) {
    law_params(law, sets[k], Rs[k], rhos[k], &ps);
    if (dem_contact_setup(&ct, law, &ps, NULL) == DEM_OK &&
        dem_impact_setup(&sc, law, &ps, DEM_TARGET_PAIR, NULL) == DEM_OK)
      break;
  }
  ck_assert_msg(k < 2, "law '%s' accepts neither parameter set", law->name);
  const double R = Rs[k];
  double v = vs[k];
  dem_impact_opts o;
  dem_impact_opts_default(&o);
  dem_impact_result res;
  dem_err err = {0};
  /* faster until it rebounds (adhesive laws stick below their sticking velocity) */
  for (int tries = 0; tries < 4; tries++, v *= 2.0) {
    ck_assert_int_eq(dem_impact_run(&sc, &o, v, &res, &err), DEM_OK);
    if (!res.stuck) break;
  }
  if (getenv("DEM_TEST_VERBOSE"))
    fprintf(stderr, "%-18s set %d  e %.4f  alpha_max %.4g  stuck %d  steps %ld\n", law->name, k,
            res.e, res.alpha_max, res.stuck, res.steps);
  /* the engine: two spheres of radius R approaching at v */
  dem_sim *s = dem_sim_create(&err);
  int mat;
  dem_sim_add_material(s, rhos[k], &mat, &err);
  ck_assert_int_eq(dem_sim_set_interaction(s, mat, mat, &ct, NULL, NULL, &err), DEM_OK);
  const double x1[3] = {0, 0, 0}, x2[3] = {2 * R + 0.5 * v * res.dt, 0, 0};
  const double v1[3] = {0.5 * v, 0, 0}, v2[3] = {-0.5 * v, 0, 0};
  dem_sim_add_particle(s, x1, v1, R, mat, &err);
  dem_sim_add_particle(s, x2, v2, R, mat, &err);
  dem_sim_set_dt(s, res.dt, &err);
  dem_sim_set_skin(s, 0.2 * R, &err);
  dem_particles *p = dem_sim_particles(s);
  if (res.stuck) { /* sticks at every velocity tried: the engine's pair stays together too */
    dem_breakdown bd;
    dem_breakdown_defaults(&bd);
    bd.max_overlap_frac = 1.0;
    dem_sim_set_breakdown(s, &bd, &err);
    ck_assert_int_eq(dem_sim_run(s, res.steps, &err), DEM_OK);
    dem_sim_stats st;
    dem_sim_get_stats(s, &st);
    ck_assert_msg(st.contacts == 1, "law %s: impact solver sticks, the engine's pair does not",
                  law->name);
    dem_sim_free(s);
    return;
  }
  double amax = 0.0, vout = 0.0;
  long limit = 20 * res.steps + 1000;
  for (long step = 0; step < limit; step++) {
    ck_assert_int_eq(dem_sim_run(s, 1, &err), DEM_OK);
    size_t a = find_id(p, 0), b = find_id(p, 1);
    double al = 2 * R - (p->x[3 * b] - p->x[3 * a]);
    amax = al > amax ? al : amax;
    dem_sim_stats st;
    dem_sim_get_stats(s, &st);
    if (amax > 0 && al < 0 && st.contacts == 0) {
      vout = p->v[3 * b] - p->v[3 * a];
      break;
    }
  }
  /* same integrator, same step: agreement to the end-of-contact detection (one step) */
  ck_assert_msg(fabs(vout / v - res.e) < 2e-3, "law %s: e engine %g, impact %g", law->name,
                vout / v, res.e);
  ck_assert_msg(fabs(amax / res.alpha_max - 1.0) < 1e-3, "law %s: alpha_max engine %g, impact %g",
                law->name, amax, res.alpha_max);
  dem_sim_free(s);
}
END_TEST


/* Servo piston: a column cut from the settled bed (8 x 8 mm, spheres clear of the new side
 * walls; Hertz-Mindlin, mu = 0.3 — without friction the column keeps compacting), a plane
 * piston from above (gain 0.05 m/(s N), v_max 0.05 m/s) driven to a target force of
 * 10 kPa x area; the force on
 * the piston, averaged over the last 2000 steps, is within 2% of the target, and no single
 * step is off by more than 10%. */
START_TEST(test_servo) {
  int mat;
  dem_sim *s = make_sim_friction(0.5, 0.3, 0.0, &mat);
  dem_err err = {0};
  const double L = 8e-3;
  FILE *fp = fopen(DEM_SOURCE_DIR "/../shared/bench/dense20k.csv", "r");
  ck_assert_ptr_nonnull(fp);
  char line[256];
  double ztop = 0.0;
  while (fgets(line, sizeof line, fp)) {
    double x[4];
    if (sscanf(line, "%lf,%lf,%lf,%lf", &x[0], &x[1], &x[2], &x[3]) != 4) continue;
    if (x[0] + x[3] > L || x[1] + x[3] > L || x[2] > 8e-3) continue;
    ck_assert_int_eq(dem_sim_add_particle(s, x, NULL, x[3], mat, &err), DEM_OK);
    if (x[2] + x[3] > ztop) ztop = x[2] + x[3];
  }
  fclose(fp);
  for (int w = 0; w < 5; w++) {
    dem_wall_spec ws = {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 0}, 0, {0, 0, 0}, mat};
    ws.n[w / 2] = w % 2 ? -1.0 : 1.0;
    if (w % 2) ws.p[w / 2] = L;
    ck_assert_int_eq(dem_sim_add_wall(s, &ws, NULL, &err), DEM_OK);
  }
  int piston;
  dem_wall_spec pw = {DEM_WALL_PLANE, {0, 0, ztop + 5e-5}, {0, 0, -1}, 0, {0, 0, 0}, mat};
  ck_assert_int_eq(dem_sim_add_wall(s, &pw, &piston, &err), DEM_OK);
  const double target = 1e4 * L * L; /* N */
  ck_assert_int_eq(dem_sim_set_wall_servo(s, piston, target, 0.05, 0.05, &err), DEM_OK);
  dem_sim_set_gravity(s, (double[3]){0, 0, -9.81});
  dem_sim_set_dt(s, 1.5e-6, &err);
  dem_sim_set_skin(s, 1e-4, &err);
  /* 60 ms: approach, compaction, and the column's slips: under the held load it rearranges
   * now and then (the load falls 2-4 % for ~3-6 ms and the servo brings it back: at 37-42
   * ms since the servo reads the rate-independent load, at 48-54 ms before; both runs hold
   * the target to 1e-4 from 57 ms on: a copy of this test run to 90 ms against both engines,
   * 2026-12-03); the window
   * (until 2026-12-03 after 36 ms) must not depend on when a slip comes. */
  ck_assert_int_eq(dem_sim_run(s, 40000, &err), DEM_OK);
  double sum = 0.0, worst = 0.0, sumr = 0.0;
  for (int k = 0; k < 2000; k++) {
    ck_assert_int_eq(dem_sim_run(s, 1, &err), DEM_OK);
    double f[3], fr[3];
    dem_sim_wall_load(s, piston, f, NULL, NULL);
    dem_sim_wall_load_rate_independent(s, piston, fr);
    sumr += fr[2];
    sum += f[2];
    double dev = fabs(f[2] / target - 1.0);
    worst = dev > worst ? dev : worst;
  }
  if (getenv("DEM_TEST_VERBOSE"))
    fprintf(stderr, "servo: n = %zu, mean %g N (ri %g), target %g N, worst step %g\n",
            dem_sim_particles(s)->n, sum / 2000, sumr / 2000, target, worst);
  ck_assert_double_eq_tol(sum / 2000, target, 0.02 * target);
  ck_assert_double_eq_tol(sumr / 2000, target, 0.02 * target); /* what the servo reads */
  ck_assert(worst < 0.1);
  dem_sim_free(s);
}
END_TEST


/* The servo reads the rate-independent wall load (dem_sim_wall_load_rate_independent), not
 * the dashpots: one sphere (d = 1 mm, 2500 kg/m^3) on a base under a servo piston, linear
 * law kn = 1000 N/m, e = 0.3 (dashpot c = 2 zeta sqrt(m kn) = 0.026 N s/m against a wall),
 * target 0.1 N, v_max 0.5 m/s, dt = 0.2 sqrt(m / kn). At gain 100 m/(s N), gain c = 2.6 and
 * gain kn dt = 0.72: a servo reading the whole load fed the piston's own speed back through
 * c (v_(n+1) ~ -gain c v_n) and chattered at +-v_max for good, the piston load stuck at
 * 0.08 or 0.11 N (from gain ~30 on; 2026-12-03, docs/scene.md); reading the rate-independent
 * load it settles on the target. While the piston moves, the total load differs from the
 * rate-independent one by the dashpot force; at rest they agree. */
START_TEST(test_servo_dashpot) {
  dem_err err = {0};
  dem_sim *s = dem_sim_create(&err);
  int mat;
  ck_assert_int_eq(dem_sim_add_material(s, 2500.0, &mat, &err), DEM_OK);
  dem_params ps;
  dem_params_init(&ps);
  dem_params_set(&ps, "kn", 1e3, "test", &err);
  dem_params_set(&ps, "e", 0.3, "test", &err);
  dem_contact ct;
  ck_assert_int_eq(dem_contact_setup(&ct, dem_contact_law_find("linear"), &ps, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_interaction(s, mat, mat, &ct, NULL, NULL, &err), DEM_OK);
  const double r = 5e-4, m = 2500.0 * 4.0 / 3.0 * M_PI * r * r * r, F = 0.1, gain = 100.0;
  ck_assert_int_eq(dem_sim_add_particle(s, (double[3]){0, 0, r}, NULL, r, mat, &err), DEM_OK);
  dem_wall_spec base = {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 1}, 0, {0, 0, 0}, mat};
  ck_assert_int_eq(dem_sim_add_wall(s, &base, NULL, &err), DEM_OK);
  int piston;
  dem_wall_spec pw = {DEM_WALL_PLANE, {0, 0, 2 * r + 1e-6}, {0, 0, -1}, 0, {0, 0, 0}, mat};
  ck_assert_int_eq(dem_sim_add_wall(s, &pw, &piston, &err), DEM_OK);
  dem_sim_set_gravity(s, (double[3]){0, 0, -9.81});
  ck_assert_int_eq(dem_sim_set_dt(s, 0.2 * sqrt(m / 1e3), &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_wall_servo(s, piston, F, gain, 0.5, &err), DEM_OK);
  double dmax = 0.0; /* N, largest |total - rate-independent| while the piston moves */
  for (int k = 0; k < 200; k++) {
    ck_assert_int_eq(dem_sim_run(s, 1, &err), DEM_OK);
    double f[3], fr[3];
    dem_sim_wall_load(s, piston, f, NULL, NULL);
    ck_assert_int_eq(dem_sim_wall_load_rate_independent(s, piston, fr), DEM_OK);
    dmax = fmax(dmax, fabs(f[2] - fr[2]));
  }
  ck_assert_msg(dmax > 1e-3 * F, "the dashpots load the moving piston (%g N)", dmax);
  ck_assert_int_eq(dem_sim_run(s, 3800, &err), DEM_OK);
  double f[3], fr[3];
  dem_wall_spec w;
  dem_sim_wall_load(s, piston, f, NULL, NULL);
  dem_sim_wall_load_rate_independent(s, piston, fr);
  dem_sim_wall(s, piston, &w);
  if (getenv("DEM_TEST_VERBOSE"))
    fprintf(stderr, "servo dashpot: load %.9g N (rate-independent %.9g), v %g m/s, max |dashpot| "
            "%g N\n", f[2], fr[2], w.v[2], dmax);
  ck_assert_double_eq_tol(fr[2], F, 1e-9 * F);
  ck_assert_double_eq_tol(f[2], F, 1e-9 * F);
  ck_assert(fabs(w.v[2]) < 1e-9);
  ck_assert_int_eq(dem_sim_wall_load_rate_independent(s, 2, fr), DEM_ERANGE);
  dem_sim_free(s);
}
END_TEST

static Suite *suite(void) {
  Suite *s = suite_create("engine");
  TCase *tc = tcase_create("engine");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, test_head_on_hertz);
  tcase_add_test(tc, test_oblique_momentum);
  tcase_add_test(tc, test_energy_conservation);
  tcase_add_test(tc, test_free_flight);
  tcase_add_loop_test(tc, test_neighbour_brute_force, 0, 3);
  tcase_add_test(tc, test_history_survives_rebuild);
  tcase_add_test(tc, test_walls);
  tcase_add_test(tc, test_threads_reproducible);
  tcase_add_test(tc, test_breakdown);
  tcase_add_test(tc, test_runaway_names_contact);
  tcase_add_test(tc, test_peak_overlap);
  tcase_add_test(tc, test_servo);
  tcase_add_test(tc, test_servo_dashpot);
  tcase_add_test(tc, test_errors);
  tcase_add_test(tc, test_oblique_friction);
  tcase_add_loop_test(tc, test_every_law_head_on, 0, dem_contact_law_count());
  tcase_add_test(tc, test_sliding_to_rolling);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) {
  SRunner *sr = srunner_create(suite());
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
