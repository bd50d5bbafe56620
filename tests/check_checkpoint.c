/* Engine checkpoints (dem/checkpoint.h): restart equality with a plastic-adhesive law, a
 * servo piston and walls, for 1 and 2 threads; rejection of missing, truncated and
 * corrupted files; interruption at a step boundary. */
#define _GNU_SOURCE /* memmem */
#include <check.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <unistd.h>

#include "dem/checkpoint.h"
#include "dem/contact.h"
#include "dem/engine.h"
#include "dem/params.h"
#include "dem/tangential.h"

#define L_BOX 6e-3 /* m, column of the settled bed */

/* A column of the peers' settled bed (d = 1 mm) in a box of side L_BOX with a servo piston
 * coming down from above; pasha-simplified (plastic, adhesive) with Mindlin friction and
 * rolling resistance, so that contact histories carry state. */
static dem_sim *bed(int nthreads) {
  dem_err err = {0};
  dem_sim *s = dem_sim_create(&err);
  ck_assert_ptr_nonnull(s);
  int mat, wmat;
  ck_assert_int_eq(dem_sim_add_material(s, 2500.0, &mat, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_add_material(s, 7800.0, &wmat, &err), DEM_OK);
  dem_params ps;
  dem_params_init(&ps);
  dem_params_set(&ps, "ke", 1e5, "test", NULL);
  dem_params_set(&ps, "kp", 2e4, "test", NULL);
  dem_params_set(&ps, "kcp", 2e3, "test", NULL);
  dem_params_set(&ps, "f0", 2e-5, "test", NULL);
  dem_params_set(&ps, "e", 0.5, "test", NULL);
  dem_params_set(&ps, "E", 5e7, "test", NULL);
  dem_params_set(&ps, "nu", 0.3, "test", NULL);
  dem_params_set(&ps, "mu", 0.3, "test", NULL);
  dem_params_set(&ps, "mu_r", 0.05, "test", NULL);
  dem_contact ct;
  dem_tangential tg;
  dem_rolling rl;
  ck_assert_int_eq(dem_contact_setup(&ct, dem_contact_law_find("pasha-simplified"), &ps, &err),
                   DEM_OK);
  ck_assert_int_eq(dem_tangential_setup(&tg, DEM_TANGENTIAL_MINDLIN, &ps, &err), DEM_OK);
  ck_assert_int_eq(dem_rolling_setup(&rl, &ps, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_interaction(s, mat, mat, &ct, &tg, &rl, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_interaction(s, mat, wmat, &ct, &tg, &rl, &err), DEM_OK);
  FILE *fp = fopen(DEM_SOURCE_DIR "/../shared/bench/dense20k.csv", "r");
  ck_assert_ptr_nonnull(fp);
  char line[256];
  double ztop = 0.0;
  while (fgets(line, sizeof line, fp)) {
    double x[4];
    if (sscanf(line, "%lf,%lf,%lf,%lf", &x[0], &x[1], &x[2], &x[3]) != 4) continue;
    if (x[0] + x[3] > L_BOX || x[1] + x[3] > L_BOX || x[2] > 5e-3) continue;
    double v[3] = {0.0, 0.0, -0.02}; /* something to do from the first step */
    ck_assert_int_eq(dem_sim_add_particle(s, x, v, x[3], mat, &err), DEM_OK);
    if (x[2] + x[3] > ztop) ztop = x[2] + x[3];
  }
  fclose(fp);
  for (int w = 0; w < 5; w++) {
    dem_wall_spec ws = {DEM_WALL_PLANE, {0, 0, 0}, {0, 0, 0}, 0, {0, 0, 0}, wmat};
    ws.n[w / 2] = w % 2 ? -1.0 : 1.0;
    if (w % 2) ws.p[w / 2] = L_BOX;
    ck_assert_int_eq(dem_sim_add_wall(s, &ws, NULL, &err), DEM_OK);
  }
  int piston;
  dem_wall_spec pw = {DEM_WALL_PLANE, {0, 0, ztop + 2e-5}, {0, 0, -1}, 0, {0, 0, 0}, wmat};
  ck_assert_int_eq(dem_sim_add_wall(s, &pw, &piston, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_wall_servo(s, piston, 1e4 * L_BOX * L_BOX, 0.5, 0.1, &err),
                   DEM_OK);
  dem_sim_set_gravity(s, (double[3]){0, 0, -9.81});
  ck_assert_int_eq(dem_sim_set_dt(s, 5e-7, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_set_skin(s, 5e-5, &err), DEM_OK);
  dem_sim_set_sort_interval(s, 2); /* re-sort often: the stored order must carry over */
  if (dem_sim_set_threads(s, nthreads, &err) != DEM_OK) {
    dem_sim_free(s);
    return NULL;
  }
  return s;
}

/* Bit-identical states (same particle order: the sorts happened at the same builds). */
static void assert_same(dem_sim *a, dem_sim *b) {
  dem_particles *p = dem_sim_particles(a), *q = dem_sim_particles(b);
  ck_assert_uint_eq(p->n, q->n);
  size_t n = p->n;
  ck_assert_int_eq(memcmp(p->id, q->id, n * sizeof *p->id), 0);
  ck_assert_int_eq(memcmp(p->x, q->x, 3 * n * sizeof(double)), 0);
  ck_assert_int_eq(memcmp(p->v, q->v, 3 * n * sizeof(double)), 0);
  ck_assert_int_eq(memcmp(p->omega, q->omega, 3 * n * sizeof(double)), 0);
  ck_assert_int_eq(memcmp(p->f, q->f, 3 * n * sizeof(double)), 0);
  ck_assert_int_eq(memcmp(p->torque, q->torque, 3 * n * sizeof(double)), 0);
  for (int w = 0; w < 6; w++) {
    dem_wall_spec wa, wb;
    double fa[3], fb[3], ta[3], tb[3], ka, kb;
    ck_assert_int_eq(dem_sim_wall(a, w, &wa), DEM_OK);
    ck_assert_int_eq(dem_sim_wall(b, w, &wb), DEM_OK);
    ck_assert_int_eq(memcmp(wa.p, wb.p, sizeof wa.p), 0);
    ck_assert_int_eq(memcmp(wa.v, wb.v, sizeof wa.v), 0);
    dem_sim_wall_load(a, w, fa, ta, &ka);
    dem_sim_wall_load(b, w, fb, tb, &kb);
    ck_assert_int_eq(memcmp(fa, fb, sizeof fa), 0);
    ck_assert_int_eq(memcmp(ta, tb, sizeof ta), 0);
    ck_assert_int_eq(memcmp(&ka, &kb, sizeof ka), 0);
    dem_sim_wall_load_rate_independent(a, w, fa); /* the servo's input (version 3) */
    dem_sim_wall_load_rate_independent(b, w, fb);
    ck_assert_int_eq(memcmp(fa, fb, sizeof fa), 0);
  }
  dem_sim_stats sa, sb;
  dem_sim_get_stats(a, &sa);
  dem_sim_get_stats(b, &sb);
  ck_assert_int_eq(sa.steps, sb.steps);
  /* the clock is t_base + (steps - steps_base) dt: equal however the runs were split */
  ck_assert_msg(sa.time == sb.time, "time %.17g vs %.17g", sa.time, sb.time);
  ck_assert_int_eq(sa.rebuilds, sb.rebuilds);
  ck_assert_int_eq(sa.sorts, sb.sorts);
  ck_assert_uint_eq(sa.contacts, sb.contacts);
}

static void tmp_path(char *buf, size_t n, const char *tag) {
  snprintf(buf, n, "%s/check_checkpoint_%ld_%s.h5", DEM_BINARY_DIR, (long)getpid(), tag);
}

/* N steps, checkpoint, M more == restart from the checkpoint + M, for 1 and 2 threads; and
 * the uninterrupted N + M (writing a checkpoint does not disturb the run). */
START_TEST(test_restart_equal) {
  const int nt = _i + 1;
  const long N = 1500, M = 1500;
  dem_err err = {0};
  dem_sim *a = bed(nt);
  if (!a) return; /* no OpenMP */
  dem_sim *c = bed(nt);
  ck_assert_int_eq(dem_sim_run(a, N, &err), DEM_OK);
  char path[512];
  tmp_path(path, sizeof path, nt == 1 ? "eq1" : "eq2");
  const char blob[] = "stage=consolidate\0rng-bytes\x01\x02\x03";
  ck_assert_int_eq(dem_sim_checkpoint_write(a, path, blob, sizeof blob, &err), DEM_OK);
  /* histories matter: some pairs carry a live plastic/adhesive state */
  {
    dem_sim_stats st;
    dem_sim_get_stats(a, &st);
    ck_assert_msg(st.contacts > dem_sim_particles(a)->n / 2, "contacts %zu of %zu particles",
                  st.contacts, dem_sim_particles(a)->n);
  }
  ck_assert_int_eq(dem_sim_run(a, M, &err), DEM_OK);
  void *ub = NULL;
  size_t ulen = 0;
  dem_sim *b = dem_sim_checkpoint_read(path, &ub, &ulen, &err);
  ck_assert_msg(b != NULL, "%s", err.msg);
  ck_assert_uint_eq(ulen, sizeof blob);
  ck_assert_int_eq(memcmp(ub, blob, ulen), 0);
  free(ub);
  ck_assert_int_eq(dem_sim_set_threads(b, nt, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_run(b, M, &err), DEM_OK);
  assert_same(a, b);
  ck_assert_int_eq(dem_sim_run(c, N + M, &err), DEM_OK);
  assert_same(a, c);
  {
    dem_sim_stats st;
    dem_sim_get_stats(a, &st);
    ck_assert_msg(st.rebuilds > 3 && st.sorts > 1, "rebuilds %ld sorts %ld", st.rebuilds,
                  st.sorts);
    dem_wall_spec pw;
    dem_sim_wall(a, 5, &pw);
    ck_assert_msg(pw.v[2] != 0.0, "the servo moves the piston");
  }
  remove(path);
  dem_sim_free(a);
  dem_sim_free(b);
  dem_sim_free(c);
}
END_TEST

static unsigned char *slurp(const char *path, size_t *n) {
  FILE *f = fopen(path, "rb");
  ck_assert_ptr_nonnull(f);
  fseek(f, 0, SEEK_END);
  long len = ftell(f);
  fseek(f, 0, SEEK_SET);
  unsigned char *b = malloc((size_t)len);
  ck_assert_uint_eq(fread(b, 1, (size_t)len, f), (size_t)len);
  fclose(f);
  *n = (size_t)len;
  return b;
}

static void spit(const char *path, const unsigned char *b, size_t n) {
  FILE *f = fopen(path, "wb");
  ck_assert_ptr_nonnull(f);
  ck_assert_uint_eq(fwrite(b, 1, n, f), n);
  fclose(f);
}

START_TEST(test_rejects_bad_files) {
  dem_err err = {0};
  dem_sim *a = bed(1);
  ck_assert_int_eq(dem_sim_run(a, 200, &err), DEM_OK);
  char path[512], bad[512];
  tmp_path(path, sizeof path, "good");
  tmp_path(bad, sizeof bad, "bad");
  ck_assert_int_eq(dem_sim_checkpoint_write(a, path, NULL, 0, &err), DEM_OK);
  size_t n;
  unsigned char *b = slurp(path, &n);

  /* missing file */
  remove(bad);
  ck_assert_ptr_null(dem_sim_checkpoint_read(bad, NULL, NULL, &err));
  ck_assert_int_eq(err.code, DEM_EIO);
  ck_assert_ptr_nonnull(strstr(err.msg, bad));

  /* truncated */
  spit(bad, b, n / 2);
  ck_assert_ptr_null(dem_sim_checkpoint_read(bad, NULL, NULL, &err));
  ck_assert_int_ne(err.code, DEM_OK);
  ck_assert_ptr_nonnull(strstr(err.msg, bad));
  fprintf(stderr, "truncated: %s\n", err.msg);

  /* one flipped bit in the particle positions */
  const dem_particles *p = dem_sim_particles(a);
  unsigned char *at = memmem(b, n, p->x + 3 * (p->n / 2), sizeof(double));
  ck_assert_ptr_nonnull(at);
  at[3] ^= 0x10;
  spit(bad, b, n);
  at[3] ^= 0x10;
  ck_assert_ptr_null(dem_sim_checkpoint_read(bad, NULL, NULL, &err));
  ck_assert_int_eq(err.code, DEM_EPARSE);
  ck_assert_ptr_nonnull(strstr(err.msg, "checksum"));
  ck_assert_ptr_nonnull(strstr(err.msg, bad));
  fprintf(stderr, "flipped: %s\n", err.msg);

  /* a law this build does not know */
  at = memmem(b, n, "pasha-simplified", 16);
  ck_assert_ptr_nonnull(at);
  at[15] = 'X';
  spit(bad, b, n);
  at[15] = 'd';
  ck_assert_ptr_null(dem_sim_checkpoint_read(bad, NULL, NULL, &err));
  ck_assert_int_eq(err.code, DEM_ENOTFOUND);
  ck_assert_ptr_nonnull(strstr(err.msg, "pasha-simplifieX"));
  fprintf(stderr, "law: %s\n", err.msg);

  /* an HDF5 file that is not a checkpoint of ours (format tag) */
  at = memmem(b, n, "dem-checkpoint", 14);
  ck_assert_ptr_nonnull(at);
  at[0] = 'x';
  spit(bad, b, n);
  at[0] = 'd';
  ck_assert_ptr_null(dem_sim_checkpoint_read(bad, NULL, NULL, &err));
  ck_assert_int_eq(err.code, DEM_EPARSE);
  ck_assert_ptr_nonnull(strstr(err.msg, "format tag"));

  /* a file of the previous format version (1: walls without length and angle): the int32
   * version follows the 16-byte format tag in the file's raw data */
  at = memmem(b, n, "dem-checkpoint", 14);
  ck_assert_ptr_nonnull(at);
  int32_t v;
  memcpy(&v, at + 16, 4);
  ck_assert_int_eq(v, DEM_CHECKPOINT_VERSION);
  v = 1;
  memcpy(at + 16, &v, 4);
  spit(bad, b, n);
  v = DEM_CHECKPOINT_VERSION;
  memcpy(at + 16, &v, 4);
  ck_assert_ptr_null(dem_sim_checkpoint_read(bad, NULL, NULL, &err));
  ck_assert_int_eq(err.code, DEM_EUNSUPPORTED);
  ck_assert_ptr_nonnull(strstr(err.msg, "version 1"));
  ck_assert_ptr_nonnull(strstr(err.msg, "older build"));
  ck_assert_ptr_nonnull(strstr(err.msg, bad));
  fprintf(stderr, "old version: %s\n", err.msg);

  /* garbage */
  memset(b, 0x5a, n < 4096 ? n : 4096);
  spit(bad, b, n);
  ck_assert_ptr_null(dem_sim_checkpoint_read(bad, NULL, NULL, &err));
  ck_assert_int_eq(err.code, DEM_EIO);

  /* the good file still reads */
  dem_sim *c = dem_sim_checkpoint_read(path, NULL, NULL, &err);
  ck_assert_msg(c != NULL, "%s", err.msg);
  dem_sim_free(c);
  /* unwritable destination: an error, no file left behind */
  ck_assert_int_eq(dem_sim_checkpoint_write(a, "/nonexistent-dir/x.h5", NULL, 0, &err), DEM_EIO);
  free(b);
  remove(path);
  remove(bad);
  dem_sim_free(a);
}
END_TEST


/* Every wall kind survives a checkpoint: a floor, two side planes and the three indenters
 * (sphere, flat-ended cylinder, cube; thesis 6.2.2), each met by a sphere falling under
 * gravity, with the indenters moving down. N steps, checkpoint, M more == restart + M. */
START_TEST(test_restart_indenters) {
  dem_err err = {0};
  dem_sim *s[2];
  for (int k = 0; k < 2; k++) {
    s[k] = dem_sim_create(&err);
    ck_assert_ptr_nonnull(s[k]);
    int mat;
    ck_assert_int_eq(dem_sim_add_material(s[k], 2500.0, &mat, &err), DEM_OK);
    dem_params ps;
    dem_params_init(&ps);
    dem_params_set(&ps, "E", 1e8, "test", NULL);
    dem_params_set(&ps, "nu", 0.3, "test", NULL);
    dem_params_set(&ps, "e", 0.5, "test", NULL);
    dem_params_set(&ps, "mu", 0.3, "test", NULL);
    dem_contact ct;
    dem_tangential tg;
    ck_assert_int_eq(dem_contact_setup(&ct, &dem_law_hertz, &ps, &err), DEM_OK);
    ck_assert_int_eq(dem_tangential_setup(&tg, DEM_TANGENTIAL_MINDLIN, &ps, &err), DEM_OK);
    ck_assert_int_eq(dem_sim_set_interaction(s[k], mat, mat, &ct, &tg, NULL, &err), DEM_OK);
    const dem_wall_kind kinds[6] = {DEM_WALL_PLANE,  DEM_WALL_PLANE,    DEM_WALL_PLANE,
                                    DEM_WALL_SPHERE, DEM_WALL_FLATCYL,  DEM_WALL_BOX};
    for (int w = 0; w < 6; w++) {
      dem_wall_spec ws;
      memset(&ws, 0, sizeof ws);
      ws.kind = kinds[w];
      ws.material = mat;
      if (w == 0) ws.n[2] = 1.0; /* floor */
      if (w == 1) ws.n[0] = 1.0; /* x = 0 */
      if (w == 2) {              /* x = 0.04 */
        ws.n[0] = -1.0;
        ws.p[0] = 0.04;
      }
      if (w >= 3) { /* indenters at x = 0.008, 0.02, 0.032, lowest point at z = 1.2 mm, facing down */
        ws.p[0] = 0.008 + 0.012 * (w - 3);
        ws.p[1] = 0.01;
        ws.radius = 2.5e-3;
        ws.p[2] = (w == 3) ? 1.2e-3 + ws.radius : 1.2e-3; /* sphere: p is the centre */
        ws.n[2] = -1.0;
        ws.v[2] = -0.01;
        if (w >= 4) ws.length = 2.0 * ws.radius; /* closed cylinder, a real cube */
        if (w == 5) ws.angle = 0.3;               /* turned about its axis */
      }
      ck_assert_int_eq(dem_sim_add_wall(s[k], &ws, NULL, &err), DEM_OK);
    }
    for (int i = 0; i < 3; i++) { /* on the floor under each indenter, and under its rim */
      double x[3] = {0.008 + 0.012 * i + 4e-4 * i, 0.01 + 3e-4, 5e-4}, v[3] = {0, 0, 0};
      ck_assert_int_eq(dem_sim_add_particle(s[k], x, v, 5e-4, mat, &err), DEM_OK);
      double xf[3] = {x[0] + 2.6e-3, x[1], 5e-4};
      ck_assert_int_eq(dem_sim_add_particle(s[k], xf, v, 5e-4, mat, &err), DEM_OK);
    }
    const double g[3] = {0.0, 0.0, -9.81};
    dem_sim_set_gravity(s[k], g);
    ck_assert_int_eq(dem_sim_set_dt(s[k], 1e-6, &err), DEM_OK);
    ck_assert_int_eq(dem_sim_set_skin(s[k], 1e-4, &err), DEM_OK);
  }
  const long N = 20000, M = 10000; /* indenters reach the particles after ~18 ms */
  ck_assert_int_eq(dem_sim_run(s[0], N, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_run(s[1], N + M, &err), DEM_OK);
  char path[512];
  tmp_path(path, sizeof path, "indenters");
  ck_assert_int_eq(dem_sim_checkpoint_write(s[0], path, NULL, 0, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_run(s[0], M, &err), DEM_OK);
  void *ub = NULL;
  size_t ulen = 0;
  dem_sim *b = dem_sim_checkpoint_read(path, &ub, &ulen, &err);
  ck_assert_msg(b != NULL, "%s", err.msg);
  free(ub);
  for (int w = 3; w < 6; w++) {
    dem_wall_spec wa, wb;
    dem_sim_wall(s[0], w, &wa);
    dem_sim_wall(b, w, &wb);
    ck_assert_int_eq(wb.kind, wa.kind);
    ck_assert_double_eq(wb.radius, wa.radius);
    ck_assert_double_eq(wb.length, wa.length);
    ck_assert_double_eq(wb.angle, wa.angle);
  }
  ck_assert_int_eq(dem_sim_run(b, M, &err), DEM_OK);
  assert_same(s[0], b);
  assert_same(s[0], s[1]);
  /* the indenters did meet the particles: every indenter has done work */
  for (int w = 3; w < 6; w++) {
    double f[3], t[3], work;
    dem_sim_wall_load(s[0], w, f, t, &work);
    ck_assert_msg(work != 0.0, "indenter %d never touched a particle", w);
  }
  remove(path);
  dem_sim_free(s[0]);
  dem_sim_free(s[1]);
  dem_sim_free(b);
}
END_TEST

static volatile sig_atomic_t stop_flag = 0;
static void on_alarm(int sig) {
  (void)sig;
  stop_flag = 1;
}

/* An interrupt (here a timer signal) stops the run at a step boundary; checkpoint, restart,
 * run the remaining steps: the same end state as the run that was never interrupted. */
START_TEST(test_interrupt) {
  const long K = 6000;
  dem_err err = {0};
  dem_sim *a = bed(1), *c = bed(1);
  dem_sim_set_interrupt_flag(a, &stop_flag);
  /* set on entry: no step taken */
  stop_flag = 1;
  ck_assert_int_eq(dem_sim_run(a, 10, &err), DEM_EINTERRUPTED);
  dem_sim_stats st;
  dem_sim_get_stats(a, &st);
  ck_assert_int_eq(st.steps, 0);
  stop_flag = 0;
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_alarm;
  sigaction(SIGALRM, &sa, NULL);
  struct itimerval it = {{0, 0}, {0, 20000}}; /* 20 ms */
  setitimer(ITIMER_REAL, &it, NULL);
  int rc = dem_sim_run(a, K, &err);
  ck_assert_int_eq(rc, DEM_EINTERRUPTED);
  ck_assert_ptr_nonnull(strstr(err.msg, "interrupted"));
  dem_sim_get_stats(a, &st);
  ck_assert_msg(st.steps > 0 && st.steps < K, "steps %ld", st.steps);
  fprintf(stderr, "interrupted after %ld steps: %s\n", st.steps, err.msg);
  char path[512];
  tmp_path(path, sizeof path, "intr");
  ck_assert_int_eq(dem_sim_checkpoint_write(a, path, NULL, 0, &err), DEM_OK);
  dem_sim_free(a);
  stop_flag = 0;
  dem_sim *b = dem_sim_checkpoint_read(path, NULL, NULL, &err);
  ck_assert_msg(b != NULL, "%s", err.msg);
  ck_assert_int_eq(dem_sim_run(b, K - st.steps, &err), DEM_OK);
  ck_assert_int_eq(dem_sim_run(c, K, &err), DEM_OK);
  assert_same(b, c);
  ck_assert_int_eq(dem_sim_last_good_step(c), K / 100 * 100);
  remove(path);
  dem_sim_free(b);
  dem_sim_free(c);
}
END_TEST

static Suite *suite(void) {
  Suite *s = suite_create("checkpoint");
  TCase *tc = tcase_create("core");
  tcase_set_timeout(tc, 120);
  tcase_add_loop_test(tc, test_restart_equal, 0, 2);
  tcase_add_test(tc, test_rejects_bad_files);
  tcase_add_test(tc, test_restart_indenters);
  tcase_add_test(tc, test_interrupt);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) {
  SRunner *sr = srunner_create(suite());
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
