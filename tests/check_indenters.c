/* Indenter walls (sphere, flat-ended cylinder, cube): penetration depths, normals and R*
 * against hand-computed values for every region (face, rim/edge, side, corner, inside),
 * and a particle pressed by a moving indenter: the load on the indenter equals the force on
 * the particle, and the work done equals the integral of force x velocity.
 * Tolerance: 1e-12 m on depths (closed-form geometry, round-off only). */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dem/engine.h"

#define TOL 1e-12

static void expect(const dem_wall_spec *w, double x0, double x1, double x2, double r,
                   double alpha, double n0, double n1, double n2, double rfac) {
  double x[3] = {x0, x1, x2}, n[3], rf;
  double a = dem_wall_penetration(w, x, r, n, &rf);
  ck_assert_msg(fabs(a - alpha) < TOL, "alpha %.15g expected %.15g at (%g,%g,%g)", a, alpha, x0,
                x1, x2);
  ck_assert_msg(fabs(n[0] - n0) < 1e-12 && fabs(n[1] - n1) < 1e-12 && fabs(n[2] - n2) < 1e-12,
                "normal (%g,%g,%g) expected (%g,%g,%g)", n[0], n[1], n[2], n0, n1, n2);
  ck_assert_msg(fabs(rf - rfac) < 1e-12, "rfac %.15g expected %.15g", rf, rfac);
}

START_TEST(test_sphere) {
  /* sphere of radius 8 mm at (1, 2, 3) mm; particle r = 0.5 mm */
  dem_wall_spec w = {DEM_WALL_SPHERE, {1e-3, 2e-3, 3e-3}, {0, 0, -1}, 8e-3, {0, 0, 0}, 0};
  const double r = 5e-4, Rs = 8e-3, rf = Rs / (Rs + r);
  /* below the sphere, gap 0.1 mm: alpha = -1e-4 */
  expect(&w, 1e-3, 2e-3, 3e-3 - Rs - r - 1e-4, r, -1e-4, 0, 0, -1, rf);
  /* along (3,4,0)/5, overlapping by 0.2 mm */
  double l = Rs + r - 2e-4;
  expect(&w, 1e-3 + 0.6 * l, 2e-3 + 0.8 * l, 3e-3, r, 2e-4, 0.6, 0.8, 0, rf);
}
END_TEST

START_TEST(test_flatcyl) {
  /* face centre at the origin, face normal -z (indenter moving down), radius 8 mm
   * (body occupies z >= 0, semi-infinite) */
  dem_wall_spec w = {DEM_WALL_FLATCYL, {0, 0, 0}, {0, 0, -1}, 8e-3, {0, 0, 0}, 0};
  const double r = 5e-4, Rc = 8e-3, rs = sqrt(Rc / (Rc + r));
  /* flat face: under the face, 0.3 mm overlap */
  expect(&w, 3e-3, -2e-3, -(r - 3e-4), r, 3e-4, 0, 0, -1, 1.0);
  /* rim edge: beyond the rim diagonally, distance 0.4 mm at 45 degrees in the (x, -z) plane */
  double s = 0.4e-3 / sqrt(2.0);
  expect(&w, Rc + s, 0, -s, r, r - 0.4e-3, 1 / sqrt(2.0), 0, -1 / sqrt(2.0), 1.0);
  /* side: at mid-height along +y, 0.1 mm overlap */
  expect(&w, 0, Rc + r - 1e-4, 10e-3, r, 1e-4, 0, 1, 0, rs);
  /* high up the side (semi-infinite body): still the side */
  expect(&w, -(Rc + r - 2e-4), 0, 0.5, r, 2e-4, -1, 0, 0, rs);
  /* centre inside, 0.6 mm above the face: pushed out through the face */
  expect(&w, 1e-3, 0, 0.6e-3, r, r + 0.6e-3, 0, 0, -1, 1.0);
  /* far away: negative */
  expect(&w, 0, 0, -5e-3, r, r - 5e-3, 0, 0, -1, 1.0);
}
END_TEST

START_TEST(test_box) {
  /* cube of side 16 mm: leading face centred at the origin, normal -z, edges along x and y;
   * body occupies -8..8 mm in x and y, z >= 0 (semi-infinite prism) */
  dem_wall_spec w = {DEM_WALL_BOX, {0, 0, 0}, {0, 0, -1}, 8e-3, {0, 0, 0}, 0};
  const double r = 5e-4, a = 8e-3;
  /* face */
  expect(&w, 2e-3, 3e-3, -(r - 1e-4), r, 1e-4, 0, 0, -1, 1.0);
  /* side face x = +a */
  expect(&w, a + r - 2e-4, 1e-3, 5e-3, r, 2e-4, 1, 0, 0, 1.0);
  /* edge between the leading face and x = +a: at 45 degrees, distance 0.3 mm */
  double s = 0.3e-3 / sqrt(2.0);
  expect(&w, a + s, 0, -s, r, r - 0.3e-3, 1 / sqrt(2.0), 0, -1 / sqrt(2.0), 1.0);
  /* corner (+a, -a, 0): along (1,-1,-1)/sqrt3, distance 0.45 mm */
  double c = 0.45e-3 / sqrt(3.0), q = 1 / sqrt(3.0);
  expect(&w, a + c, -a - c, -c, r, r - 0.45e-3, q, -q, -q, 1.0);
  /* inside, nearest to the face x = -a (0.2 mm in) */
  expect(&w, -a + 0.2e-3, 0, 8e-3, r, r + 0.2e-3, -1, 0, 0, 1.0);
  /* high up a side face: still that face (semi-infinite prism) */
  expect(&w, 1e-3, -(a + r - 3e-4), 0.2, r, 3e-4, 0, -1, 0, 1.0);
}
END_TEST

/* Closed flat cylinder (length 16 mm behind the face, as dem_scene makes it: length = the
 * diameter): the back face, back rim, side near the back, inside near the back, and a
 * point high above that the semi-infinite body would still touch through its side. */
START_TEST(test_flatcyl_closed) {
  dem_wall_spec w = {DEM_WALL_FLATCYL, {0, 0, 0}, {0, 0, -1}, 8e-3, {0, 0, 0}, 0};
  const double r = 5e-4, Rc = 8e-3, L = 16e-3, rs = sqrt(Rc / (Rc + r));
  w.length = L; /* body: 0 <= z <= 16 mm, back face at z = L with outward normal +z */
  /* back face: 0.25 mm overlap */
  expect(&w, 2e-3, -1e-3, L + r - 2.5e-4, r, 2.5e-4, 0, 0, 1, 1.0);
  /* back rim: at 45 degrees in the (radial (0.6, 0.8), +z) plane, distance 0.35 mm */
  double s = 0.35e-3 / sqrt(2.0), h = 1 / sqrt(2.0);
  expect(&w, 0.6 * (Rc + s), 0.8 * (Rc + s), L + s, r, r - 0.35e-3, 0.6 * h, 0.8 * h, h, 1.0);
  /* the side just below the back rim (1 mm): still the side */
  expect(&w, 0, -(Rc + r - 1e-4), L - 1e-3, r, 1e-4, 0, -1, 0, rs);
  /* centre inside, 0.3 mm below the back face: pushed out through the back */
  expect(&w, 1e-3, 0, L - 0.3e-3, r, r + 0.3e-3, 0, 0, 1, 1.0);
  /* centre inside, 0.3 mm above the front face: through the front as before */
  expect(&w, 1e-3, 0, 0.3e-3, r, r + 0.3e-3, 0, 0, -1, 1.0);
  /* high above: the semi-infinite body's side contact is gone; the back rim is the nearest
   * point (distance sqrt(0.3^2 + 484^2) mm), far out of contact */
  double dx = r - 2e-4, dz = 0.5 - L, dd = sqrt(dx * dx + dz * dz);
  expect(&w, -(Rc + r - 2e-4), 0, 0.5, r, r - dd, -dx / dd, 0, dz / dd, 1.0);
  /* above the back face on the axis, 5 mm away */
  expect(&w, 0, 0, L + 5e-3, r, r - 5e-3, 0, 0, 1, 1.0);
  /* the same point without a length (semi-infinite): inside, nearest the side */
  w.length = 0.0;
  expect(&w, 0, -(Rc - 1e-3), L - 0.3e-3, r, r + 1e-3, 0, -1, 0, rs);
}
END_TEST

/* A real cube (side 16 mm = 2 radius, length 16 mm): back face, back edges, back corner,
 * inside near the back; then turned by 30 degrees about its axis: side face, front corner
 * and a point that the unturned cube would contain. */
START_TEST(test_box_closed) {
  dem_wall_spec w = {DEM_WALL_BOX, {0, 0, 0}, {0, 0, -1}, 8e-3, {0, 0, 0}, 0};
  const double r = 5e-4, a = 8e-3, L = 16e-3;
  w.length = L; /* body: |x|, |y| <= 8 mm, 0 <= z <= 16 mm */
  expect(&w, 2e-3, 3e-3, L + r - 1e-4, r, 1e-4, 0, 0, 1, 1.0);      /* back face */
  double s = 0.3e-3 / sqrt(2.0), h = 1 / sqrt(2.0);
  expect(&w, -a - s, 1e-3, L + s, r, r - 0.3e-3, -h, 0, h, 1.0);     /* back edge at x = -a */
  expect(&w, 2e-3, a + s, L + s, r, r - 0.3e-3, 0, h, h, 1.0);       /* back edge at y = +a */
  double c = 0.45e-3 / sqrt(3.0), q = 1 / sqrt(3.0);
  expect(&w, a + c, a + c, L + c, r, r - 0.45e-3, q, q, q, 1.0);     /* back corner (+a,+a,L) */
  expect(&w, -a - c, a + c, L + c, r, r - 0.45e-3, -q, q, q, 1.0);   /* back corner (-a,+a,L) */
  expect(&w, 0, 1e-3, L - 0.2e-3, r, r + 0.2e-3, 0, 0, 1, 1.0);      /* inside, near the back */
  expect(&w, 0, 1e-3, 0.2e-3, r, r + 0.2e-3, 0, 0, -1, 1.0);         /* inside, near the front */
  /* turned by 30 degrees: e1' = cos e1 + sin e2 with e1 = x, e2 = n x e1 = -y */
  w.angle = M_PI / 6.0;
  const double cs = cos(w.angle), sn = sin(w.angle);
  const double e1[3] = {cs, -sn, 0}, e2[3] = {-sn, -cs, 0};
  double x[3];
  /* side face +e1': 0.2 mm overlap at l2 = 1 mm, halfway up */
  for (int k = 0; k < 3; k++) x[k] = (a + r - 2e-4) * e1[k] + 1e-3 * e2[k];
  expect(&w, x[0], x[1], 5e-3, r, 2e-4, e1[0], e1[1], e1[2], 1.0);
  /* front corner (+a e1' + a e2', z = 0): along (e1' + e2' - z)/sqrt3 */
  for (int k = 0; k < 3; k++) x[k] = (a + c) * (e1[k] + e2[k]);
  expect(&w, x[0], x[1], -c, r, r - 0.45e-3, q * (e1[0] + e2[0]), q * (e1[1] + e2[1]), -q, 1.0);
  /* (0.99 a, 0.99 a): inside the unturned cube, outside the turned one beyond -e2'
   * (l2 = 0.99 a (-sin - cos) = -1.352 a): no contact */
  double l2 = 0.99 * a * (-sn - cs), dist = -l2 - a;
  expect(&w, 0.99 * a, 0.99 * a, 5e-3, r, r - dist, -e2[0], -e2[1], -e2[2], 1.0);
  /* a negative or non-finite length and a non-finite angle are rejected */
  dem_err err;
  dem_sim *sim = dem_sim_create(&err);
  int m;
  dem_sim_add_material(sim, 1000.0, &m, &err);
  w.material = m;
  w.length = -1e-3;
  ck_assert_int_eq(dem_sim_add_wall(sim, &w, NULL, &err), DEM_ERANGE);
  ck_assert_msg(strstr(err.msg, "length") != NULL, "%s", err.msg);
  w.length = INFINITY;
  ck_assert_int_eq(dem_sim_add_wall(sim, &w, NULL, &err), DEM_ERANGE);
  w.length = L;
  w.angle = NAN;
  ck_assert_int_eq(dem_sim_add_wall(sim, &w, NULL, &err), DEM_ERANGE);
  ck_assert_msg(strstr(err.msg, "angle") != NULL, "%s", err.msg);
  w.angle = 0.5;
  ck_assert_int_eq(dem_sim_add_wall(sim, &w, NULL, &err), DEM_OK);
  dem_sim_free(sim);
}
END_TEST

/* A sphere indenter moving down at constant velocity onto a particle resting on a floor:
 * the force on the indenter balances the contact force, the work is the integral of
 * F . v dt, and each shape is accepted by dem_sim_add_wall. */
START_TEST(test_moving_indenter) {
  static const dem_wall_kind kinds[3] = {DEM_WALL_SPHERE, DEM_WALL_FLATCYL, DEM_WALL_BOX};
  dem_err err;
  dem_sim *s = dem_sim_create(&err);
  ck_assert_ptr_nonnull(s);
  int mat, wm;
  ck_assert_int_eq(dem_sim_add_material(s, 2500.0, &mat, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_add_material(s, 7800.0, &wm, &err), DEM_OK);
  dem_params ps;
  dem_params_init(&ps);
  dem_params_set(&ps, "kn", 1e5, "test", &err);
  dem_params_set(&ps, "e", 0.5, "test", &err);
  dem_contact ct;
  ck_assert_int_eq(dem_contact_setup(&ct, dem_contact_law_find("linear"), &ps, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_interaction(s, mat, mat, &ct, NULL, NULL, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_interaction(s, mat, wm, &ct, NULL, NULL, &err), DEM_OK);
  const double r = 5e-4;
  double x[3] = {0, 0, r};
  ck_assert_int_eq(dem_sim_add_particle(s, x, NULL, r, mat, &err), DEM_OK);
  dem_wall_spec fl = {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 1}, 0, {0, 0, 0}, wm};
  ck_assert_int_eq(dem_sim_add_wall(s, &fl, NULL, &err), DEM_OK);
  int kind = kinds[_i];
  dem_wall_spec in = {kind, {0, 0, 2 * r + 1e-6}, {0, 0, -1}, 4e-3, {0, 0, -0.01}, wm};
  if (kind == DEM_WALL_SPHERE) in.p[2] += 4e-3;
  int wi;
  ck_assert_int_eq(dem_sim_add_wall(s, &in, &wi, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_dt(s, 1e-7, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_skin(s, 1e-4, &err), DEM_OK);
  double work_expect = 0.0, f[3], t[3], work;
  /* the gap of 1e-6 m closes after 1000 steps of 1e-9 m; then 1400 steps of loading */
  for (int k = 0; k < 2400; k++) {
    ck_assert_int_eq(dem_sim_run(s, 1, &err), DEM_OK);
    dem_sim_wall_load(s, wi, f, t, &work);
    work_expect += -f[2] * -0.01 * 1e-7; /* force on the particle = -f, wall velocity -0.01 */
  }
  dem_sim_wall_load(s, wi, f, t, &work);
  ck_assert_msg(f[2] > 0.0, "indenter pushed up by the particle: f_z = %g", f[2]);
  ck_assert_msg(fabs(f[0]) < 1e-12 * f[2] + 1e-15 && fabs(f[1]) < 1e-12 * f[2] + 1e-15,
                "axial contact: no lateral load (%g, %g)", f[0], f[1]);
  dem_particles *p = dem_sim_particles(s);
  ck_assert_msg(p->x[2] < r, "particle pressed into the floor");
  ck_assert_msg(work > 0.0 && fabs(work - work_expect) < 1e-9 * work,
                "work %.12g J, integral of F.v dt %.12g J", work, work_expect);
  /* a bad radius is rejected */
  dem_wall_spec bad = in;
  bad.radius = 0.0;
  ck_assert_int_eq(dem_sim_add_wall(s, &bad, NULL, &err), DEM_ERANGE);
  dem_sim_free(s);
}
END_TEST

/* dem_sim_move_wall translates without work and rejects bad input. */
START_TEST(test_move_wall) {
  dem_err err;
  dem_sim *s = dem_sim_create(&err);
  int m;
  dem_sim_add_material(s, 1000.0, &m, &err);
  dem_wall_spec w = {DEM_WALL_SPHERE, {0, 0, 0}, {0, 0, -1}, 1e-3, {0, 0, 0}, m};
  int wi;
  ck_assert_int_eq(dem_sim_add_wall(s, &w, &wi, &err), DEM_OK);
  double dp[3] = {1e-3, 0, -2e-3};
  ck_assert_int_eq(dem_sim_move_wall(s, wi, dp, &err), DEM_OK);
  dem_wall_spec o;
  dem_sim_wall(s, wi, &o);
  ck_assert(fabs(o.p[0] - 1e-3) < TOL && fabs(o.p[2] + 2e-3) < TOL);
  ck_assert_int_eq(dem_sim_move_wall(s, 3, dp, &err), DEM_ERANGE);
  dp[1] = NAN;
  ck_assert_int_eq(dem_sim_move_wall(s, wi, dp, &err), DEM_ENONFINITE);
  dem_sim_free(s);
}
END_TEST

int main(void) {
  Suite *su = suite_create("indenters");
  TCase *tc = tcase_create("geometry");
  tcase_add_test(tc, test_sphere);
  tcase_add_test(tc, test_flatcyl);
  tcase_add_test(tc, test_box);
  tcase_add_test(tc, test_flatcyl_closed);
  tcase_add_test(tc, test_box_closed);
  tcase_add_loop_test(tc, test_moving_indenter, 0, 3);
  tcase_add_test(tc, test_move_wall);
  suite_add_tcase(su, tc);
  SRunner *sr = srunner_create(su);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
