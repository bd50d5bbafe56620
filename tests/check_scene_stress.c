/* Contact export (dem_sim_contacts), the scene's contact view and stresses (thesis 5.1-5.3,
 * Fig 5.18): the exported forces are the ones the force loop applied (per-particle sums,
 * torques, wall loads), a single loaded pair between two walls gives the analytic stress, a
 * bed held at 10 kPa under the piston reads about 10 kPa in a bin, and the stress columns of
 * the time series are finite where defined and NaN elsewhere. Tolerances stated per check. */
#include <check.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dem/analysis.h"
#include "dem/scene.h"

#define RELTOL(a, b, t) ck_assert_double_eq_tol((a), (b), (t) * fabs(b))

/* Worst relative errors of the export against the engine's own totals. */
typedef struct identity {
  double force;   /* max_i |sum_c F_c + m g - f_i| / (sum_c |F_c| + m |g|) */
  double torque;  /* the same for sum_c (x_c - x_i) x F_c against torque_i (no rolling) */
  double wall;    /* max_w |sum_c -F_c - load_w| / sum_c |F_c| */
  size_t pairs, walls;
} identity;

static void check_identity(dem_sim *s, const double g[3], identity *id) {
  dem_err err;
  dem_sim_contact *buf = NULL;
  size_t cap = 0, n = 0;
  int rc = dem_sim_contacts(s, &buf, &cap, &n, &err);
  ck_assert_msg(rc == DEM_OK, "%s", err.msg);
  const dem_particles *p = dem_sim_particles(s);
  double *acc = calloc(3 * p->n, sizeof *acc), *tq = calloc(3 * p->n, sizeof *tq);
  double *mag = calloc(p->n, sizeof *mag);
  double wl[DEM_ENGINE_MAX_WALLS][3] = {{0}}, wm[DEM_ENGINE_MAX_WALLS] = {0};
  ck_assert(acc && tq && mag);
  memset(id, 0, sizeof *id);
  for (size_t k = 0; k < n; k++) {
    const dem_sim_contact *c = buf + k;
    double fm = sqrt(c->f[0] * c->f[0] + c->f[1] * c->f[1] + c->f[2] * c->f[2]);
    size_t who[2] = {c->i, c->j};
    double sg[2] = {1.0, -1.0};
    for (int e = 0; e < (c->wall < 0 ? 2 : 1); e++) {
      size_t i = who[e];
      const double *x = p->x + 3 * i;
      double b[3] = {c->point[0] - x[0], c->point[1] - x[1], c->point[2] - x[2]};
      double F[3] = {sg[e] * c->f[0], sg[e] * c->f[1], sg[e] * c->f[2]};
      acc[3 * i] += F[0], acc[3 * i + 1] += F[1], acc[3 * i + 2] += F[2];
      tq[3 * i] += b[1] * F[2] - b[2] * F[1];
      tq[3 * i + 1] += b[2] * F[0] - b[0] * F[2];
      tq[3 * i + 2] += b[0] * F[1] - b[1] * F[0];
      mag[i] += fm;
    }
    if (c->wall >= 0) {
      for (int a = 0; a < 3; a++) wl[c->wall][a] -= c->f[a];
      wm[c->wall] += fm;
      id->walls++;
    } else {
      id->pairs++;
    }
  }
  const double gm = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  for (size_t i = 0; i < p->n; i++) {
    double sc = mag[i] + p->mass[i] * gm, e2 = 0.0, t2 = 0.0;
    for (int a = 0; a < 3; a++) {
      double d = acc[3 * i + a] + p->mass[i] * g[a] - p->f[3 * i + a];
      e2 += d * d;
      double dt = tq[3 * i + a] - p->torque[3 * i + a];
      t2 += dt * dt;
    }
    if (sc > 0) id->force = fmax(id->force, sqrt(e2) / sc);
    if (mag[i] > 0) id->torque = fmax(id->torque, sqrt(t2) / (mag[i] * p->radius[i]));
  }
  for (int w = 0; w < DEM_ENGINE_MAX_WALLS; w++) {
    double f[3];
    if (dem_sim_wall_load(s, w, f, NULL, NULL) != DEM_OK || wm[w] == 0.0) continue;
    double d = sqrt((wl[w][0] - f[0]) * (wl[w][0] - f[0]) + (wl[w][1] - f[1]) * (wl[w][1] - f[1]) +
                    (wl[w][2] - f[2]) * (wl[w][2] - f[2]));
    id->wall = fmax(id->wall, d / wm[w]);
  }
  dem_sim_stats st;
  dem_sim_get_stats(s, &st);
  ck_assert_uint_eq(id->pairs, st.contacts);
  ck_assert_uint_eq(id->walls, st.wall_contacts);
  free(acc), free(tq), free(mag), free(buf);
}

/* Engine level, Hertz between particles (the inline fast path) with Mindlin friction and
 * damping, a box of plane walls, and a sphere indenter pressed into the bed, no rolling
 * resistance (so the torques are contact torques only). The bed is dropped and pressed
 * while still moving: damping, sliding and sticking contacts are all present. Tolerance
 * 1e-9 relative: the exported forces are re-evaluated from the same state, up to the
 * rounding of the recovered half-step velocities (~1e-16 relative) and of summation order. */
START_TEST(test_export_engine) {
  dem_err err;
  dem_sim *s = dem_sim_create(&err);
  ck_assert_ptr_nonnull(s);
  int mp, mw;
  ck_assert_int_eq(dem_sim_add_material(s, 2500.0, &mp, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_add_material(s, 7800.0, &mw, &err), DEM_OK);
  dem_params ps;
  dem_params_init(&ps);
  dem_params_set(&ps, "E", 1e7, "test", &err);
  dem_params_set(&ps, "nu", 0.3, "test", &err);
  dem_params_set(&ps, "e", 0.5, "test", &err);
  dem_params_set(&ps, "mu", 0.3, "test", &err);
  dem_contact ct;
  dem_tangential tg;
  ck_assert_int_eq(dem_contact_setup(&ct, dem_contact_law_find("hertz"), &ps, &err), DEM_OK);
  ck_assert_int_eq(dem_tangential_setup(&tg, DEM_TANGENTIAL_MINDLIN, &ps, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_interaction(s, mp, mp, &ct, &tg, NULL, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_interaction(s, mp, mw, &ct, &tg, NULL, &err), DEM_OK);
  const double r = 5e-4, L = 6e-3;
  unsigned long seed = 12345;
  for (int ix = 0; ix < 5; ix++)
    for (int iy = 0; iy < 5; iy++)
      for (int iz = 0; iz < 8; iz++) {
        seed = seed * 6364136223846793005ul + 1442695040888963407ul;
        double jit = ((double)(seed >> 33) / 2147483648.0 - 0.5) * 0.2 * r;
        double x[3] = {-L / 2 + 1.2 * r * (2 * ix + 1) + jit, -L / 2 + 1.2 * r * (2 * iy + 1) - jit,
                       1.2 * r * (2 * iz + 1)};
        double rr = r * (0.8 + 0.2 * ((ix + iy + iz) % 3) / 2.0);
        ck_assert_int_eq(dem_sim_add_particle(s, x, NULL, rr, mp, &err), DEM_OK);
      }
  dem_wall_spec walls[5] = {
      {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 1}, 0, {0, 0, 0}, mw},
      {DEM_WALL_PLANE, {-L / 2, 0, 0}, {1, 0, 0}, 0, {0, 0, 0}, mw},
      {DEM_WALL_PLANE, {L / 2, 0, 0}, {-1, 0, 0}, 0, {0, 0, 0}, mw},
      {DEM_WALL_PLANE, {0, -L / 2, 0}, {0, 1, 0}, 0, {0, 0, 0}, mw},
      {DEM_WALL_PLANE, {0, L / 2, 0}, {0, -1, 0}, 0, {0, 0, 0}, mw}};
  for (int w = 0; w < 5; w++) ck_assert_int_eq(dem_sim_add_wall(s, &walls[w], NULL, &err), DEM_OK);
  const double g[3] = {0, 0, -9.81};
  dem_sim_set_gravity(s, g);
  ck_assert_int_eq(dem_sim_set_dt(s, 2e-6, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_skin(s, 1e-4, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_run(s, 25000, &err), DEM_OK); /* 50 ms: piling up, still moving */
  identity id;
  check_identity(s, g, &id);
  printf("engine, settling: %zu pairs, %zu wall contacts, force %.2e torque %.2e wall %.2e\n",
         id.pairs, id.walls, id.force, id.torque, id.wall);
  ck_assert_uint_gt(id.pairs, 100);
  ck_assert_msg(id.force < 1e-9 && id.torque < 1e-9 && id.wall < 1e-9, "identity");
  /* a sphere indenter (servo to 0.5 N, so that its velocity changes after every
   * evaluation) pressing on the bed */
  double top = 0.0;
  const double R = 2e-3;
  const dem_particles *p = dem_sim_particles(s);
  for (size_t i = 0; i < p->n; i++)
    if (hypot(p->x[3 * i], p->x[3 * i + 1]) < R) top = fmax(top, p->x[3 * i + 2] + p->radius[i]);
  dem_wall_spec ind = {DEM_WALL_SPHERE, {0, 0, top + R + 1e-5}, {0, 0, -1}, R, {0, 0, -0.05}, mw};
  int wi;
  ck_assert_int_eq(dem_sim_add_wall(s, &ind, &wi, &err), DEM_OK);
  double f[3] = {0, 0, 0};
  for (int k = 0; k < 60 && f[2] <= 0.0; k++) { /* down at 5 cm/s until it touches */
    ck_assert_int_eq(dem_sim_run(s, 500, &err), DEM_OK);
    dem_sim_wall_load(s, wi, f, NULL, NULL);
  }
  ck_assert_int_eq(dem_sim_set_wall_servo(s, wi, 0.5, 0.05, 0.05, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_run(s, 3000, &err), DEM_OK);
  check_identity(s, g, &id);
  dem_sim_wall_load(s, wi, f, NULL, NULL);
  printf("engine, indenter: load %.3g N, %zu pairs, %zu wall contacts, force %.2e torque %.2e "
         "wall %.2e\n", f[2], id.pairs, id.walls, id.force, id.torque, id.wall);
  ck_assert_msg(f[2] > 0.0, "indenter in contact");
  ck_assert_msg(id.force < 1e-9 && id.torque < 1e-9 && id.wall < 1e-9, "identity");
  /* not current after a wall moved; dem_sim_run(s, 0) evaluates (no kick) */
  double dp[3] = {0, 0, 1e-5};
  ck_assert_int_eq(dem_sim_move_wall(s, wi, dp, &err), DEM_OK);
  dem_sim_contact *buf = NULL;
  size_t cap = 0, n = 0;
  ck_assert_int_eq(dem_sim_contacts(s, &buf, &cap, &n, &err), DEM_EINVAL);
  free(buf);
  ck_assert_int_eq(dem_sim_run(s, 0, &err), DEM_OK);
  check_identity(s, g, &id);
  ck_assert_msg(id.force < 1e-9 && id.torque < 1e-9 && id.wall < 1e-9, "identity after run(0)");
  dem_sim_free(s);
}
END_TEST

/* The engine's contacts as a dem_contact_view (pairs twice, walls once). */
static void to_view(const dem_sim_contact *c, size_t n, size_t *part, double *pt, double *fo,
                    dem_contact_view *v) {
  size_t m = 0;
  for (size_t k = 0; k < n; k++) {
    part[m] = c[k].i;
    memcpy(pt + 3 * m, c[k].point, 3 * sizeof(double));
    memcpy(fo + 3 * m, c[k].f, 3 * sizeof(double));
    m++;
    if (c[k].wall < 0) {
      part[m] = c[k].j;
      memcpy(pt + 3 * m, c[k].point, 3 * sizeof(double));
      for (int a = 0; a < 3; a++) fo[3 * m + a] = -c[k].f[a];
      m++;
    }
  }
  v->n = m;
  v->particle = part;
  v->point = pt;
  v->force = fo;
}

/* Two equal spheres (radius r) stacked on the axis between a base plane and a top plane,
 * every overlap alpha, no gravity, at rest, linear law kn: every contact carries F = kn alpha.
 * Bottom particle: base contact at its wall point z = 0, branch -(r - alpha) e_z, force +F;
 * pair contact in the middle of the overlap, branch +(r - alpha/2) e_z, force -F. So a box
 * around both gives sigma_zz = F (4r - 3 alpha) / V = F H / V (H the wall gap), the other
 * components 0; a box around the bottom one alone gives F (2r - 3 alpha/2) / V. 1e-12. */
START_TEST(test_pair_analytic) {
  dem_err err;
  dem_sim *s = dem_sim_create(&err);
  int m;
  ck_assert_int_eq(dem_sim_add_material(s, 2500.0, &m, &err), DEM_OK);
  dem_params ps;
  dem_params_init(&ps);
  dem_params_set(&ps, "kn", 1e5, "test", &err);
  dem_contact ct;
  ck_assert_int_eq(dem_contact_setup(&ct, dem_contact_law_find("linear"), &ps, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_interaction(s, m, m, &ct, NULL, NULL, &err), DEM_OK);
  const double r = 1e-3, al = 1e-5, F = 1e5 * al, H = 4 * r - 3 * al;
  double x1[3] = {0, 0, r - al}, x2[3] = {0, 0, 3 * r - 2 * al};
  ck_assert_int_eq(dem_sim_add_particle(s, x1, NULL, r, m, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_add_particle(s, x2, NULL, r, m, &err), DEM_OK);
  dem_wall_spec base = {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 1}, 0, {0, 0, 0}, m};
  dem_wall_spec top = {DEM_WALL_PLANE, {0, 0, H}, {0, 0, -1}, 0, {0, 0, 0}, m};
  ck_assert_int_eq(dem_sim_add_wall(s, &base, NULL, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_add_wall(s, &top, NULL, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_dt(s, 1e-6, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_run(s, 0, &err), DEM_OK);
  dem_sim_contact *buf = NULL;
  size_t cap = 0, n = 0;
  ck_assert_int_eq(dem_sim_contacts(s, &buf, &cap, &n, &err), DEM_OK);
  ck_assert_uint_eq(n, 3);
  size_t part[6];
  double pt[18], fo[18];
  dem_contact_view v;
  to_view(buf, n, part, pt, fo, &v);
  ck_assert_uint_eq(v.n, 4);
  const dem_particles *p = dem_sim_particles(s);
  const double a = 2e-3;
  dem_box both = {{-a, -a, -a}, {a, a, 5 * r}}, low = {{-a, -a, -a}, {a, a, 2 * r - al}};
  double sig[9];
  size_t np;
  ck_assert_int_eq(dem_stress_box(&v, p->n, p->x, &both, 0.0, sig, &np, &err), DEM_OK);
  double V = dem_box_volume(&both), want = F * H / V;
  printf("pair: sigma_zz %.12g Pa, analytic %.12g Pa\n", sig[8], want);
  ck_assert_uint_eq(np, 2);
  ck_assert_double_eq_tol(sig[8], want, 1e-12 * want);
  for (int k = 0; k < 8; k++) ck_assert_double_eq_tol(sig[k], 0.0, 1e-12 * want);
  ck_assert_int_eq(dem_stress_box(&v, p->n, p->x, &low, 0.0, sig, &np, &err), DEM_OK);
  want = F * (2 * r - 1.5 * al) / dem_box_volume(&low);
  ck_assert_uint_eq(np, 1);
  ck_assert_double_eq_tol(sig[8], want, 1e-12 * want);
  free(buf);
  dem_sim_free(s);
}
END_TEST

static void small(dem_scene_config *c) {
  dem_scene_config_defaults(c, DEM_SCENE_PASHA);
  c->die_diameter = 8.0;
  c->bed_height = 6.0;
  c->indenter_diameter = 3.0;
  c->fill_fraction = 0.33;
  c->hold_time = 1e-3;
  c->stiffness_scale = 0.01; /* dt x10: the suite must stay short */
  c->strain_rate = 10.0;     /* gamma* = 0.1, quasi-static by Tardos' 0.15 (thesis 5.1.3) */
  c->settle_min_time = 0.005;
  c->threads = 1;
  c->seed = 7;
  c->h_over_r = 0.4;
}

/* The scene pipeline on a small bed: the export identity under the servo piston and under
 * the indenter, the bin under the piston at 10 kPa, the stress columns. */
START_TEST(test_scene) {
  dem_scene_config c;
  small(&c);
  dem_err err;
  dem_scene *sc = dem_scene_create(&c, NULL, &err);
  ck_assert_msg(sc != NULL, "%s", err.msg);
  int rc;
  ck_assert_int_eq(dem_scene_fill(sc, &err), DEM_OK);
  rc = dem_scene_settle(sc, &err);
  ck_assert_msg(rc == DEM_OK, "%s", err.msg);
  rc = dem_scene_consolidate(sc, &err);
  ck_assert_msg(rc == DEM_OK, "%s", err.msg);
  dem_sim *s = dem_scene_sim(sc);
  const double g[3] = {0, 0, -9.81};
  identity id;
  check_identity(s, g, &id);
  printf("scene, consolidated: %zu pairs, %zu wall contacts, force %.2e wall %.2e\n", id.pairs,
         id.walls, id.force, id.wall);
  /* pasha-simplified with adhesion, linear friction, rolling resistance (torques not
   * compared), servo piston: 1e-9 as above */
  ck_assert_msg(id.force < 1e-9 && id.wall < 1e-9, "identity");
  /* the view: pairs twice with opposite forces at one point, walls once */
  dem_contact_view v;
  ck_assert_int_eq(dem_scene_contacts(sc, &v, &err), DEM_OK);
  ck_assert_uint_eq(v.n, 2 * id.pairs + id.walls);
  for (size_t k = 0; k + 1 < 2 * id.pairs; k += 2)
    for (int a = 0; a < 3; a++) {
      ck_assert(v.force[3 * k + a] == -v.force[3 * k + 3 + a]);
      ck_assert(v.point[3 * k + a] == v.point[3 * k + 3 + a]);
    }
  /* A bin under the piston at sigma_pre = 10 kPa: the middle column of the static grid, one
   * row from the base (5.2 x 5.2 x 4.2 d in a bed of ~6 d under a piston over the whole 8 d
   * die). The die and piston are frictionless here (Table 6.3: mu = 0 particle-wall), so
   * without wall friction sigma_zz is the piston stress plus the weight above (rho g h phi
   * ~ 100 Pa, 1%). Tolerance [0.6, 1.4] sigma_pre: the bin counts particles by their centre,
   * so the volume its ~100 particles own differs from V by a surface layer of about d/2 on
   * each face (~ +-25% for a 4-5 d bin), and the servo holds 2%. Hydrostatic > 0. */
  dem_grid grid;
  double sg[5 * 9];
  ck_assert_int_eq(dem_scene_stress_grid(sc, 1, sg, &grid, &err), DEM_OK);
  const double *m = sg + 9 * 2;
  double p = dem_stress_hydrostatic(m);
  dem_scene_info in;
  dem_scene_get_info(sc, &in);
  printf("scene, bin under the piston: szz %.0f sxx %.0f syy %.0f p %.0f q %.0f Pa (piston "
         "%.0f Pa), bed %.2f mm\n", m[8], m[0], m[4], p, dem_stress_deviatoric(m),
         in.piston_stress, 1e3 * in.bed_top);
  ck_assert_msg(p > 0.0, "hydrostatic %g", p);
  ck_assert_msg(m[8] > 0.6 * c.sigma_pre && m[8] < 1.4 * c.sigma_pre, "szz %g", m[8]);
  ck_assert_double_eq_tol(grid.cell[0], 5.2e-3, 1e-15);
  rc = dem_scene_unload(sc, &err);
  ck_assert_msg(rc == DEM_OK, "%s", err.msg);
  /* the piston was moved away: dem_scene_contacts evaluates the forces first */
  ck_assert_int_eq(dem_scene_contacts(sc, &v, &err), DEM_OK);
  const dem_table *t = dem_scene_series(sc);
  long r0 = dem_table_nrows(t);
  rc = dem_scene_indent(sc, &err);
  ck_assert_msg(rc == DEM_OK, "%s", err.msg);
  check_identity(s, g, &id);
  printf("scene, indented: %zu pairs, %zu wall contacts, force %.2e wall %.2e\n", id.pairs,
         id.walls, id.force, id.wall);
  ck_assert_msg(id.force < 1e-9 && id.wall < 1e-9, "identity");
  /* columns: 12..15 = bin_p, bin_q, bin_phi, base_p, 16..17 indenter_contacts,
   * contact_radius */
  ck_assert_int_eq(dem_table_ncols(t), 18);
  long nr = dem_table_nrows(t);
  for (long k = 0; k < r0; k++) {
    ck_assert(isnan(dem_table_get(t, k, 12)) && isnan(dem_table_get(t, k, 13)) &&
              isnan(dem_table_get(t, k, 14)));
    ck_assert(isfinite(dem_table_get(t, k, 15)));
    ck_assert(isnan(dem_table_get(t, k, 16)) && isnan(dem_table_get(t, k, 17)));
  }
  long k0 = -1;
  for (long k = r0; k < nr; k++) {
    for (int col = 12; col < 16; col++) ck_assert(isfinite(dem_table_get(t, k, col)));
    if (k0 < 0 && dem_table_get(t, k, 5) > 0.0) k0 = k;
  }
  ck_assert_msg(k0 >= 0 && nr - k0 >= 8, "too few rows in contact");
  /* bin_p increases during the first part of the penetration: the mean over the second
   * quarter of the rows in contact exceeds the mean over the rows before contact (the bin
   * then only carries the bed's weight, ~ rho g h phi ~ 50 Pa), and the solids fraction is
   * a packing fraction */
  long q = (nr - k0) / 4;
  double before = 0, early = 0;
  for (long k = r0; k < k0; k++) before += dem_table_get(t, k, 12);
  before /= (double)(k0 > r0 ? k0 - r0 : 1);
  for (long k = k0 + q; k < k0 + 2 * q; k++) early += dem_table_get(t, k, 12);
  early /= (double)q;
  printf("scene, bin_p: %.0f Pa before contact, %.0f Pa (2nd quarter), last %.0f Pa, "
         "bin_q last %.0f Pa, bin_phi last %.3f, base_p last %.0f Pa\n", before, early,
         dem_table_get(t, nr - 1, 12), dem_table_get(t, nr - 1, 13),
         dem_table_get(t, nr - 1, 14), dem_table_get(t, nr - 1, 15));
  ck_assert_msg(early > before, "bin_p before %g, early %g", before, early);
  /* The footprint columns of the last row against the contacts the engine exports: the
   * test finds the indenter as the wall whose contact points lie on the indenter's sphere
   * (centre = tip + r, column 4 the tip) and recomputes count and a_c from them (sign: the
   * indenter pushes the particles down, a pressing contact's force on i has f_z < 0). */
  {
    dem_sim_contact *cb = NULL;
    size_t cap = 0, nc = 0;
    ck_assert_int_eq(dem_sim_contacts(s, &cb, &cap, &nc, &err), DEM_OK);
    const double zi = dem_table_get(t, nr - 1, 4) + 0.5 * c.indenter_diameter * c.d_mean;
    const double ri = 0.5 * c.indenter_diameter * c.d_mean;
    double sw = 0, swr2 = 0;
    size_t ni = 0;
    int wi = -1;
    for (size_t k = 0; k < nc; k++) {
      const double *pk = cb[k].point;
      const double dist = sqrt(pk[0] * pk[0] + pk[1] * pk[1] + (pk[2] - zi) * (pk[2] - zi));
      if (cb[k].wall < 0 || fabs(dist - ri) > 1e-9 * ri) continue;
      if (wi < 0) wi = cb[k].wall;
      ck_assert_int_eq(cb[k].wall, wi);
    }
    for (size_t k = 0; k < nc; k++) {
      if (cb[k].wall != wi) continue;
      ni++;
      const double w = -cb[k].f[2], *pk = cb[k].point;
      if (w > 0) sw += w, swr2 += w * (pk[0] * pk[0] + pk[1] * pk[1]);
    }
    free(cb);
    const double a_last = dem_table_get(t, nr - 1, 17);
    printf("scene, footprint: %zu indenter contacts, a_c %.3f d (eq. 2.9: %.3f d at h %.3f d)\n",
           ni, a_last / c.d_mean,
           sqrt(dem_scene_indent_area(c.shape, ri * 2, dem_table_get(t, nr - 1, 5)) / M_PI) /
               c.d_mean,
           dem_table_get(t, nr - 1, 5) / c.d_mean);
    ck_assert_msg(wi >= 0 && ni > 0, "no indenter contact at the end");
    ck_assert_double_eq(dem_table_get(t, nr - 1, 16), (double)ni);
    RELTOL(a_last, sqrt(2.0 * swr2 / sw), 1e-12);
    /* the load-weighted radius lies inside the outermost contact's reach */
    ck_assert_msg(a_last > 0 && a_last <= sqrt(2.0) * ri, "a_c %g", a_last);
  }
  for (long k = r0; k < nr; k++) {
    double phi = dem_table_get(t, k, 14);
    ck_assert_msg(phi > 0.2 && phi < 0.74, "bin_phi %g", phi);
  }
  dem_scene_free(sc);
}
END_TEST

/* output_stress = 0: the columns are NaN. */
START_TEST(test_switch) {
  dem_scene_config c;
  small(&c);
  c.output_stress = 0;
  c.settle_min_time = 0.001;
  c.settle_max_time = 0.002;
  dem_err err;
  dem_scene *sc = dem_scene_create(&c, NULL, &err);
  ck_assert_ptr_nonnull(sc);
  ck_assert_int_eq(dem_scene_fill(sc, &err), DEM_OK);
  dem_scene_settle(sc, &err); /* gives up after 2 ms: the rows are enough */
  const dem_table *t = dem_scene_series(sc);
  ck_assert_int_gt(dem_table_nrows(t), 3);
  for (long k = 0; k < dem_table_nrows(t); k++)
    for (int col = 12; col < 18; col++) ck_assert(isnan(dem_table_get(t, k, col)));
  c.output_stress = 2;
  ck_assert_int_eq(dem_scene_config_check(&c, &err), DEM_ERANGE);
  dem_scene_free(sc);
}
END_TEST

int main(void) {
  Suite *su = suite_create("scene_stress");
  TCase *tc = tcase_create("core");
  tcase_set_timeout(tc, 300);
  tcase_add_test(tc, test_pair_analytic);
  tcase_add_test(tc, test_export_engine);
  tcase_add_test(tc, test_switch);
  tcase_add_test(tc, test_scene);
  suite_add_tcase(su, tc);
  SRunner *sr = srunner_create(su);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
