/* Scene checkpoints (dem_scene_save / dem_scene_restore, dem/scene.h): a bed saved after
 * unloading and restored indents bit-for-bit like the run that was never stopped; one bed
 * serves two different indenters; an interrupted indentation resumes bit-for-bit; the
 * override may not change the bed; damaged files and plain engine checkpoints are refused
 * with messages naming the file. The bed is the small one of check_scene.c (die 8 d, bed
 * 5 d, stiffness x 0.01), built once in an unchecked fixture (in the parent process). */
#include <check.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "dem/checkpoint.h"
#include "dem/scene.h"

static char dir[256], bed_file[300];
static dem_table *ref;      /* the uninterrupted run's series after the indentation */
static long ref_rows0;      /* rows at the save point */

static void small(dem_scene_config *c) {
  dem_scene_config_defaults(c, DEM_SCENE_PASHA);
  c->die_diameter = 8.0;
  c->bed_height = 5.0;
  c->indenter_diameter = 3.0;
  c->fill_fraction = 0.33;
  c->hold_time = 1e-3;
  c->stiffness_scale = 0.01;
  c->strain_rate = 10.0;
  c->settle_min_time = 0.005;
  c->h_over_r = 0.3;
  c->threads = 1;
  c->seed = 7;
}

static dem_table *copy_table(const dem_table *t) {
  static const char *const names[] = {"c0",  "c1",  "c2",  "c3",  "c4",  "c5",  "c6",  "c7",
                                      "c8",  "c9",  "c10", "c11", "c12", "c13", "c14", "c15",
                                      "c16", "c17", "c18", "c19", "c20", "c21", "c22", "c23",
                                      "c24", "c25", "c26", "c27", "c28", "c29", "c30", "c31"};
  dem_err err;
  int nc = dem_table_ncols(t);
  dem_table *c = dem_table_create(nc, names, NULL, &err);
  double row[DEM_TABLE_MAX_COLS];
  for (long r = 0; r < dem_table_nrows(t); r++) {
    for (int q = 0; q < nc; q++) row[q] = dem_table_get(t, r, q);
    dem_table_append(c, row, &err);
  }
  return c;
}

/* Build the bed once: fill .. unload, save, then indent on (the uninterrupted reference). */
static void bed_setup(void) {
  snprintf(dir, sizeof dir, "check_scene_restart.%ld", (long)getpid());
  snprintf(bed_file, sizeof bed_file, "%s_unloaded.h5", dir);
  dem_scene_config c;
  small(&c);
  dem_err err;
  dem_scene *sc = dem_scene_create(&c, NULL, &err);
  int rc = sc ? DEM_OK : err.code;
  if (!rc) rc = dem_scene_fill(sc, &err);
  if (!rc) rc = dem_scene_settle(sc, &err);
  if (!rc) rc = dem_scene_consolidate(sc, &err);
  if (!rc) rc = dem_scene_unload(sc, &err);
  if (!rc) rc = dem_scene_save(sc, bed_file, &err);
  if (!rc) ref_rows0 = dem_table_nrows(dem_scene_series(sc));
  if (!rc) rc = dem_scene_indent(sc, &err);
  if (rc) {
    fprintf(stderr, "bed setup failed: %s\n", err.msg);
    exit(EXIT_FAILURE);
  }
  ref = copy_table(dem_scene_series(sc));
  dem_scene_info in;
  dem_scene_get_info(sc, &in);
  printf("reference: %zu particles, %ld rows at the save, %ld after indenting to %g m "
         "(force %g N)\n",
         in.n, ref_rows0, dem_table_nrows(ref), in.depth, in.indenter_force);
  dem_scene_free(sc);
}

static void bed_teardown(void) {
  remove(bed_file);
  dem_table_free(ref);
}

/* Every row of t equals ref's bit for bit (NaN == NaN), same row count. */
static void same_series(const dem_table *t, const char *what) {
  ck_assert_msg(dem_table_nrows(t) == dem_table_nrows(ref), "%s: %ld rows, reference %ld", what,
                dem_table_nrows(t), dem_table_nrows(ref));
  for (long r = 0; r < dem_table_nrows(t); r++)
    for (int q = 0; q < dem_table_ncols(t); q++) {
      double a = dem_table_get(t, r, q), b = dem_table_get(ref, r, q);
      ck_assert_msg(a == b || (isnan(a) && isnan(b)), "%s: row %ld col %d: %.17g vs %.17g",
                    what, r, q, a, b);
    }
}

/* (a) restore after unloading, indent: the whole series (history + indentation) equals the
 * uninterrupted run's, and the restored scene reports the stage reached. */
START_TEST(test_bit_identical) {
  dem_err err;
  dem_scene *sc = dem_scene_restore(bed_file, NULL, NULL, &err);
  ck_assert_msg(sc != NULL, "%s", err.msg);
  ck_assert_int_eq(dem_scene_get_stage(sc), DEM_SCENE_STAGE_UNLOADED);
  ck_assert_int_eq(dem_table_nrows(dem_scene_series(sc)), ref_rows0);
  /* the stages done are skipped: run continues with the indentation */
  int rc = dem_scene_run(sc, &err);
  ck_assert_msg(rc == DEM_OK, "%s", err.msg);
  ck_assert_int_eq(dem_scene_get_stage(sc), DEM_SCENE_STAGE_INDENTED);
  same_series(dem_scene_series(sc), "restored");
  printf("restored run: %ld rows equal bit for bit\n", dem_table_nrows(dem_scene_series(sc)));
  dem_scene_free(sc);
}
END_TEST

/* (b) one bed, two indenters (a 2 d flat cylinder 1.5 d long and a 2.5 d cube, closed
 * bodies, at h/r 0.4): both start
 * from the identical bed (same particle state at restore, same history rows) and give a
 * valid indentation (surface found, h/r reached, final force positive). */
START_TEST(test_two_indenters) {
  dem_scene_config c;
  small(&c);
  dem_err err;
  dem_scene *s[2];
  for (int k = 0; k < 2; k++) {
    c.shape = k ? DEM_INDENTER_CUBE : DEM_INDENTER_CYLINDER;
    c.indenter_diameter = k ? 2.5 : 2.0;
    c.h_over_r = 0.4;
    c.indenter_length = k ? 0.0 : 1.5; /* the cylinder 1.5 d long; the cube is a cube */
    s[k] = dem_scene_restore(bed_file, &c, NULL, &err);
    ck_assert_msg(s[k] != NULL, "%s", err.msg);
  }
  dem_particles *p0 = dem_sim_particles(dem_scene_sim(s[0]));
  dem_particles *p1 = dem_sim_particles(dem_scene_sim(s[1]));
  ck_assert_uint_eq(p0->n, p1->n);
  ck_assert(memcmp(p0->x, p1->x, 3 * p0->n * sizeof(double)) == 0);
  ck_assert(memcmp(p0->v, p1->v, 3 * p0->n * sizeof(double)) == 0);
  for (int k = 0; k < 2; k++) {
    int rc = dem_scene_indent(s[k], &err);
    ck_assert_msg(rc == DEM_OK, "%s", err.msg);
    dem_scene_info in;
    dem_scene_get_info(s[k], &in);
    const dem_table *t = dem_scene_series(s[k]);
    for (long r = 0; r < ref_rows0; r++)
      for (int q = 0; q < dem_table_ncols(t); q++) {
        double a = dem_table_get(t, r, q), b = dem_table_get(ref, r, q);
        ck_assert(a == b || (isnan(a) && isnan(b)));
      }
    double r_ind = 0.5 * (k ? 2.5 : 2.0) * c.d_mean;
    printf("%s %g d: surface %.5g m, depth %.4g m (h/r %.3f), force %.4g N\n",
           k ? "cube" : "cylinder", k ? 2.5 : 2.0, in.surface, in.depth, in.depth / r_ind,
           in.indenter_force);
    ck_assert(isfinite(in.surface));
    ck_assert_msg(in.depth >= 0.4 * r_ind, "depth %g < 0.4 r", in.depth);
    ck_assert_msg(in.indenter_force > 0.0, "force %g", in.indenter_force);
    /* closed bodies: the indenter is the wall added last (base, die, piston, indenter) */
    dem_wall_spec w;
    ck_assert_int_eq(dem_sim_wall(dem_scene_sim(s[k]), 3, &w), DEM_OK);
    ck_assert_int_eq(w.kind, k ? DEM_WALL_BOX : DEM_WALL_FLATCYL);
    ck_assert_double_eq_tol(w.length, k ? 2.5e-3 : 1.5e-3, 1e-15);
  }
  dem_scene_free(s[0]);
  dem_scene_free(s[1]);
}
END_TEST

/* (e) an indentation interrupted at an arbitrary step (the engine's interrupt flag, set by
 * a timer thread), saved, restored and finished equals the uninterrupted run. */
static volatile sig_atomic_t flag;
static void *trip(void *arg) {
  struct timespec ts = {0, (long)(*(double *)arg * 1e9)};
  nanosleep(&ts, NULL);
  flag = 1;
  return NULL;
}
START_TEST(test_interrupted) {
  dem_err err;
  dem_scene *sc = dem_scene_restore(bed_file, NULL, NULL, &err);
  ck_assert_msg(sc != NULL, "%s", err.msg);
  flag = 0;
  dem_sim_set_interrupt_flag(dem_scene_sim(sc), &flag);
  pthread_t th;
  double delay = 0.3 + 0.2 * _i; /* s of wall clock: well inside the indentation */
  pthread_create(&th, NULL, trip, &delay);
  int rc = dem_scene_run(sc, &err);
  pthread_join(th, NULL);
  ck_assert_msg(rc == DEM_EINTERRUPTED, "expected an interruption, got %d: %s", rc, err.msg);
  dem_sim_stats st;
  dem_sim_get_stats(dem_scene_sim(sc), &st);
  char path[320];
  snprintf(path, sizeof path, "%s_intr%d.h5", dir, _i);
  rc = dem_scene_save(sc, path, &err);
  ck_assert_msg(rc == DEM_OK, "%s", err.msg);
  dem_scene_free(sc);
  sc = dem_scene_restore(path, NULL, NULL, &err);
  ck_assert_msg(sc != NULL, "%s", err.msg);
  ck_assert_int_eq(dem_scene_get_stage(sc), DEM_SCENE_STAGE_UNLOADED);
  rc = dem_scene_run(sc, &err);
  ck_assert_msg(rc == DEM_OK, "%s", err.msg);
  same_series(dem_scene_series(sc), "interrupted and resumed");
  printf("interrupted at step %ld (t = %g s), resumed: equal bit for bit\n", st.steps, st.time);
  /* an interrupted indentation may not change its indenter */
  dem_scene_config c;
  small(&c);
  c.indenter_diameter = 2.0;
  ck_assert_ptr_null(dem_scene_restore(path, &c, NULL, &err));
  ck_assert_msg(err.code == DEM_EINVAL && strstr(err.msg, "indenter_diameter") &&
                    strstr(err.msg, "already begun"),
                "%s", err.msg);
  remove(path);
  dem_scene_free(sc);
}
END_TEST

/* (c) the override may not change the bed: seed, a particle coefficient, the stress. */
START_TEST(test_override_forbidden) {
  dem_err err;
  dem_scene_config c;
  small(&c);
  c.seed = 8;
  ck_assert_ptr_null(dem_scene_restore(bed_file, &c, NULL, &err));
  ck_assert_int_eq(err.code, DEM_EINVAL);
  ck_assert_msg(strstr(err.msg, "seed") && strstr(err.msg, bed_file), "%s", err.msg);
  small(&c);
  dem_params_set(&c.pp, "ke", 2e6, "test", &err);
  ck_assert_ptr_null(dem_scene_restore(bed_file, &c, NULL, &err));
  ck_assert_int_eq(err.code, DEM_EINVAL);
  ck_assert_msg(strstr(err.msg, "pp.ke") != NULL, "%s", err.msg);
  small(&c);
  c.sigma_pre = 2e4;
  ck_assert_ptr_null(dem_scene_restore(bed_file, &c, NULL, &err));
  ck_assert_msg(err.code == DEM_EINVAL && strstr(err.msg, "sigma_pre"), "%s", err.msg);
  /* allowed: the indentation, the indenter coefficients, threads, the hold limits */
  small(&c);
  c.h_over_r = 0.2;
  c.hold_tol = 0.05;
  c.threads = 2;
  dem_params_set(&c.pi, "kn", 4e6, "test", &err);
  dem_scene *sc = dem_scene_restore(bed_file, &c, NULL, &err);
#ifdef _OPENMP
  ck_assert_msg(sc != NULL, "%s", err.msg);
  dem_scene_free(sc);
#else
  (void)sc;
#endif
  /* an allowed field out of its range: the range error, naming the file */
  small(&c);
  c.h_over_r = 5.0;
  ck_assert_ptr_null(dem_scene_restore(bed_file, &c, NULL, &err));
  ck_assert_msg(err.code == DEM_ERANGE && strstr(err.msg, "h_over_r"), "%s", err.msg);
  /* stage order on a fresh scene */
  small(&c);
  sc = dem_scene_create(&c, NULL, &err);
  ck_assert_int_eq(dem_scene_get_stage(sc), DEM_SCENE_STAGE_NONE);
  ck_assert_int_eq(dem_scene_indent(sc, &err), DEM_EINVAL);
  ck_assert_msg(strstr(err.msg, "fill") != NULL, "%s", err.msg);
  dem_scene_free(sc);
}
END_TEST

static void copy_file(const char *from, const char *to, long keep) {
  FILE *a = fopen(from, "rb"), *b = fopen(to, "wb");
  ck_assert(a && b);
  char buf[65536];
  size_t n;
  long total = 0;
  while ((n = fread(buf, 1, sizeof buf, a)) > 0) {
    if (keep >= 0 && total + (long)n > keep) n = (size_t)(keep - total);
    fwrite(buf, 1, n, b);
    total += (long)n;
    if (keep >= 0 && total >= keep) break;
  }
  fclose(a);
  fclose(b);
}

static long file_size(const char *path) {
  FILE *f = fopen(path, "rb");
  ck_assert(f);
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fclose(f);
  return n;
}

/* (d) damaged files and checkpoints without (or with a wrong) scene state. */
START_TEST(test_bad_files) {
  dem_err err;
  char path[320];
  snprintf(path, sizeof path, "%s_bad.h5", dir);
  /* missing */
  ck_assert_ptr_null(dem_scene_restore("no-such-checkpoint.h5", NULL, NULL, &err));
  ck_assert_msg(err.code == DEM_EIO && strstr(err.msg, "no-such-checkpoint.h5"), "%s", err.msg);
  /* truncated to half */
  copy_file(bed_file, path, file_size(bed_file) / 2);
  ck_assert_ptr_null(dem_scene_restore(path, NULL, NULL, &err));
  ck_assert_msg(err.code == DEM_EIO && strstr(err.msg, path), "%s", err.msg);
  /* one byte flipped in the last quarter (the data): checksum or HDF5 error */
  copy_file(bed_file, path, -1);
  FILE *f = fopen(path, "r+b");
  long at = file_size(bed_file) * 3 / 4;
  fseek(f, at, SEEK_SET);
  int ch = fgetc(f);
  fseek(f, at, SEEK_SET);
  fputc(ch ^ 0x5a, f);
  fclose(f);
  ck_assert_ptr_null(dem_scene_restore(path, NULL, NULL, &err));
  ck_assert_msg((err.code == DEM_EPARSE || err.code == DEM_EIO) && strstr(err.msg, path), "%s",
                err.msg);
  printf("flipped byte: %s\n", err.msg);
  /* a plain engine checkpoint (no blob), and one with a foreign blob */
  void *blob = NULL;
  size_t blen = 0;
  dem_sim *s = dem_sim_checkpoint_read(bed_file, &blob, &blen, &err);
  ck_assert_msg(s != NULL, "%s", err.msg);
  ck_assert_int_eq(dem_sim_checkpoint_write(s, path, NULL, 0, &err), DEM_OK);
  ck_assert_ptr_null(dem_scene_restore(path, NULL, NULL, &err));
  ck_assert_msg(err.code == DEM_EINVAL && strstr(err.msg, "without a scene state") &&
                    strstr(err.msg, path),
                "%s", err.msg);
  ck_assert_int_eq(dem_sim_checkpoint_write(s, path, "stage=settle", 12, &err), DEM_OK);
  ck_assert_ptr_null(dem_scene_restore(path, NULL, NULL, &err));
  ck_assert_msg(err.code == DEM_EINVAL && strstr(err.msg, "without a scene state"), "%s",
                err.msg);
  /* the scene blob cut short (its own length check), and another blob version */
  ck_assert_int_eq(dem_sim_checkpoint_write(s, path, blob, blen - 9, &err), DEM_OK);
  ck_assert_ptr_null(dem_scene_restore(path, NULL, NULL, &err));
  ck_assert_msg(err.code == DEM_EPARSE && strstr(err.msg, "truncated"), "%s", err.msg);
  ((unsigned char *)blob)[16] ^= 0x7;
  ck_assert_int_eq(dem_sim_checkpoint_write(s, path, blob, blen, &err), DEM_OK);
  ck_assert_ptr_null(dem_scene_restore(path, NULL, NULL, &err));
  ck_assert_msg(err.code == DEM_EUNSUPPORTED && strstr(err.msg, "version"), "%s", err.msg);
  free(blob);
  dem_sim_free(s);
  remove(path);
}
END_TEST

/* (f) a bed written before the footprint columns (16 columns, 2026-12-07): its blob is
 * rebuilt here with the series cut to its first 16 columns; the restore reads it with the
 * two new columns NaN, the first 16 unchanged, and indents on to the reference's
 * indentation bit for bit (the footprint columns of the indentation rows are measured). A
 * 15-column series is refused with a message naming the file. Blob layout: restart.c. */
static size_t old_blob(const unsigned char *b, size_t len, int keep, unsigned char *out) {
  size_t at = 32, o = 32;
  memcpy(out, b, 32);
  int64_t nc = 0, nr = 0;
  while (at < len) {
    const size_t nl = b[at];
    char name[256];
    memcpy(name, b + at + 1, nl);
    name[nl] = 0;
    const unsigned char type = b[at + 1 + nl];
    uint64_t cnt;
    memcpy(&cnt, b + at + 2 + nl, 8);
    const size_t head = 10 + nl, body = (size_t)cnt * (type == 2 ? 1 : 8);
    if (!strcmp(name, "series_ncols")) memcpy(&nc, b + at + head, 8);
    if (!strcmp(name, "series_nrows")) memcpy(&nr, b + at + head, 8);
    if (!strcmp(name, "series_ncols")) {
      const int64_t k = keep;
      memcpy(out + o, b + at, head);
      memcpy(out + o + head, &k, 8);
      o += head + 8;
    } else if (!strcmp(name, "series")) {
      const uint64_t c2 = (uint64_t)nr * (uint64_t)keep;
      memcpy(out + o, b + at, head);
      memcpy(out + o + 2 + nl, &c2, 8);
      o += head;
      for (int64_t r = 0; r < nr; r++) {
        memcpy(out + o, b + at + head + 8 * (size_t)(r * nc), 8 * (size_t)keep);
        o += 8 * (size_t)keep;
      }
    } else {
      memcpy(out + o, b + at, head + body);
      o += head + body;
    }
    at += head + body;
  }
  const uint64_t total = o;
  memcpy(out + 24, &total, 8);
  return o;
}

START_TEST(test_older_series) {
  dem_err err;
  char path[320];
  snprintf(path, sizeof path, "%s_v16.h5", dir);
  void *blob = NULL;
  size_t blen = 0;
  dem_sim *s = dem_sim_checkpoint_read(bed_file, &blob, &blen, &err);
  ck_assert_msg(s != NULL, "%s", err.msg);
  unsigned char *nb = malloc(blen);
  size_t nlen = old_blob(blob, blen, 16, nb);
  ck_assert_uint_lt(nlen, blen);
  ck_assert_int_eq(dem_sim_checkpoint_write(s, path, nb, nlen, &err), DEM_OK);
  dem_scene *sc = dem_scene_restore(path, NULL, NULL, &err);
  ck_assert_msg(sc != NULL, "%s", err.msg);
  const dem_table *t = dem_scene_series(sc);
  ck_assert_int_eq(dem_table_ncols(t), 18);
  ck_assert_int_eq(dem_table_nrows(t), ref_rows0);
  for (long r = 0; r < ref_rows0; r++) {
    for (int q = 0; q < 16; q++) {
      double a = dem_table_get(t, r, q), b = dem_table_get(ref, r, q);
      ck_assert_msg(a == b || (isnan(a) && isnan(b)), "row %ld col %d", r, q);
    }
    ck_assert(isnan(dem_table_get(t, r, 16)) && isnan(dem_table_get(t, r, 17)));
  }
  ck_assert_int_eq(dem_scene_run(sc, &err), DEM_OK);
  ck_assert_int_eq(dem_table_nrows(t), dem_table_nrows(ref));
  long pressing = 0;
  for (long r = ref_rows0; r < dem_table_nrows(t); r++) {
    for (int q = 0; q < 18; q++) {
      double a = dem_table_get(t, r, q), b = dem_table_get(ref, r, q);
      ck_assert_msg(a == b || (isnan(a) && isnan(b)), "row %ld col %d", r, q);
    }
    pressing += isfinite(dem_table_get(t, r, 17));
  }
  ck_assert_msg(pressing > 0, "no indentation row with a footprint");
  dem_scene_free(sc);
  /* 15 columns: refused */
  nlen = old_blob(blob, blen, 15, nb);
  ck_assert_int_eq(dem_sim_checkpoint_write(s, path, nb, nlen, &err), DEM_OK);
  ck_assert_ptr_null(dem_scene_restore(path, NULL, NULL, &err));
  ck_assert_msg(err.code == DEM_EPARSE && strstr(err.msg, "15 columns") && strstr(err.msg, path),
                "%s", err.msg);
  printf("older series: %ld rows restored with the footprint columns NaN; 15 columns: %s\n",
         ref_rows0, err.msg);
  free(nb);
  free(blob);
  dem_sim_free(s);
  remove(path);
}
END_TEST

int main(void) {
  Suite *su = suite_create("scene_restart");
  TCase *tc = tcase_create("restart");
  tcase_set_timeout(tc, 300);
  tcase_add_unchecked_fixture(tc, bed_setup, bed_teardown);
  tcase_add_test(tc, test_override_forbidden);
  tcase_add_test(tc, test_bad_files);
  tcase_add_test(tc, test_older_series);
  tcase_add_test(tc, test_bit_identical);
  tcase_add_test(tc, test_two_indenters);
  tcase_add_loop_test(tc, test_interrupted, 0, 1); /* one interruption: the suite < 60 s */
  suite_add_tcase(su, tc);
  SRunner *sr = srunner_create(su);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
