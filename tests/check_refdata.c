/* Reference data module tests: every committed reference file loads and its SOURCE.md is
 * complete; transcribed values equal the printed tables; the sources' own derived numbers
 * are reproduced from the transcribed ones; every loader and validator error is provoked on
 * purpose and names file and line. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "dem/error.h"
#include "dem/refdata.h"

#define REFDIR DEM_SOURCE_DIR "/reference_data"

/* ---- helpers ----------------------------------------------------------------------- */

/* Load REFDIR/case/file, requiring the given columns; fail the test with the message. */
static dem_reftable *load_req(const char *file, const dem_refcol *req, int nreq) {
  char path[DEM_REFDATA_PATH_LEN];
  snprintf(path, sizeof path, "%s/%s", REFDIR, file);
  dem_err err = {0};
  dem_reftable *t = dem_refdata_load(path, req, nreq, &err);
  ck_assert_msg(t != NULL, "%s", err.msg);
  return t;
}

/* Value of column `name` in the first row whose column `key` equals kval. */
static double lookup(const dem_reftable *t, const char *key, double kval, const char *name) {
  int ck = dem_refdata_column(t, key), cv = dem_refdata_column(t, name);
  ck_assert_int_ge(ck, 0);
  ck_assert_int_ge(cv, 0);
  for (int r = 0; r < t->nrows; r++)
    if (dem_refdata_value(t, r, ck) == kval) return dem_refdata_value(t, r, cv);
  ck_abort_msg("%s: no row with %s = %g", t->path, key, kval);
  return NAN;
}

static double col0(const dem_reftable *t, const char *name, int row) {
  int c = dem_refdata_column(t, name);
  ck_assert_msg(c >= 0, "%s: no column %s", t->path, name);
  return dem_refdata_value(t, row, c);
}

/* A scratch folder per test (Check forks, so tests do not share it). */
static char scratch[256];

static void make_scratch(void) {
  snprintf(scratch, sizeof scratch, "%s/refdata-test-XXXXXX", P_tmpdir);
  ck_assert_ptr_nonnull(mkdtemp(scratch));
}

static void write_file(const char *name, const char *text) {
  char path[512];
  snprintf(path, sizeof path, "%s/%s", scratch, name);
  FILE *f = fopen(path, "wb");
  ck_assert_ptr_nonnull(f);
  fputs(text, f);
  fclose(f);
}

static void remove_scratch(void) {
  char cmd[600];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", scratch);
  if (strstr(scratch, "refdata-test-")) ck_assert_int_eq(system(cmd), 0);
}

/* Load scratch/name expecting failure with `code` and a message containing `where`
 * ("name:line:") and `what`. */
static void expect_fail(const char *name, const char *text, const dem_refcol *req, int nreq,
                        int code, int line, const char *what) {
  write_file(name, text);
  char path[512], where[600];
  snprintf(path, sizeof path, "%s/%s", scratch, name);
  snprintf(where, sizeof where, "%s:%d: ", path, line);
  dem_err err = {0};
  dem_reftable *t = dem_refdata_load(path, req, nreq, &err);
  ck_assert_msg(t == NULL, "%s: loaded although malformed", name);
  ck_assert_int_eq(err.code, code);
  ck_assert_msg(strstr(err.msg, where) != NULL, "'%s' does not name '%s'", err.msg, where);
  ck_assert_msg(strstr(err.msg, what) != NULL, "'%s' does not mention '%s'", err.msg, what);
}

/* ---- every committed folder ---------------------------------------------------------- */

typedef struct walk {
  int folders, files, rows;
} walk;

static int check_one(const char *dir, const char *name, void *ud) {
  walk *w = ud;
  dem_err err = {0};
  int nf = 0, nr = 0;
  int rc = dem_refdata_check_folder(dir, &nf, &nr, &err);
  ck_assert_msg(rc == DEM_OK, "%s: %s", name, err.msg);
  w->folders++;
  w->files += nf;
  w->rows += nr;
  return 0;
}

START_TEST(test_all_folders) {
  walk w = {0};
  dem_err err = {0};
  ck_assert_int_eq(dem_refdata_foreach_folder(REFDIR, check_one, &w, &err), DEM_OK);
  /* The nine cases of reference_data/README.md; more may be added, none may vanish. */
  ck_assert_int_ge(w.folders, 9);
  ck_assert_int_ge(w.files, 42);
  ck_assert_int_ge(w.rows, 120);
}
END_TEST

/* ---- transcribed values, checked against the printed tables ------------------------- */

START_TEST(test_spot_nan_paper) {
  /* Nan et al. Table 6, row "Wall et al. (1990)", columns R = 2.45 and 1.29 um. */
  const dem_refcol mreq[] = {{"R", "um"}, {"v_s_jkr", "m/s"}, {"v_stick", "m/s"}};
  dem_reftable *t = load_req("nan_wall1990_sticking/measured.csv", mreq, 3);
  ck_assert_int_eq(t->nrows, 4);
  ck_assert_double_eq(lookup(t, "R", 2.45, "v_stick"), 1.96);
  ck_assert_double_eq(lookup(t, "R", 1.29, "v_stick"), 4.63);
  ck_assert_double_eq(lookup(t, "R", 3.445, "v_s_jkr"), 0.49); /* row V_s */
  dem_refdata_free(t);

  /* Table 6, row "p_y = 30 MPa, e0 = 0.81", R = 1.72 um: 3.16 m/s; mean error 7.5 %. */
  const dem_refcol oreq[] = {{"py", "MPa"}, {"e0", "-"}, {"R", "um"}, {"v_stick", "m/s"}};
  t = load_req("nan_wall1990_sticking/model.csv", oreq, 4);
  ck_assert_int_eq(t->nrows, 12);
  ck_assert_double_eq(dem_refdata_value(t, 10, 3), 3.16);
  ck_assert_double_eq(dem_refdata_value(t, 10, 1), 0.81);
  dem_refdata_free(t);
  const dem_refcol ereq[] = {{"py", "MPa"}, {"e0", "-"}, {"mean_rel_err", "%"}};
  t = load_req("nan_wall1990_sticking/model_error.csv", ereq, 3);
  ck_assert_double_eq(lookup(t, "e0", 0.81, "mean_rel_err"), 7.5);
  dem_refdata_free(t);

  /* Table 2, Ning column: f_max of the first curve 42.4 uN, alpha_p 177.3 nm; k_e of the
   * third curve 639 N/m; f_cp of the second printed -6.1 uN (stored as magnitude). */
  const dem_refcol ureq[] = {{"curve", "-"},     {"f_max", "uN"},     {"alpha_max", "nm"},
                             {"alpha_p", "nm"},  {"f_pulloff", "uN"}, {"ke", "N/m"}};
  t = load_req("nan_ning1995_unloading/unloading.csv", ureq, 6);
  ck_assert_double_eq(lookup(t, "curve", 1, "f_max"), 42.4);
  ck_assert_double_eq(lookup(t, "curve", 1, "alpha_p"), 177.3);
  ck_assert_double_eq(lookup(t, "curve", 3, "ke"), 639);
  ck_assert_double_eq(lookup(t, "curve", 2, "f_pulloff"), 6.1);
  dem_refdata_free(t);

  /* Table 2, Du et al. column: f_max 8584.4 uN, k_e 4.2x10^5 N/m (curve 1). */
  t = load_req("nan_du2007_unloading/unloading.csv", ureq, 6);
  ck_assert_double_eq(lookup(t, "curve", 1, "f_max"), 8584.4);
  ck_assert_double_eq(lookup(t, "curve", 1, "ke"), 4.2e5);
  dem_refdata_free(t);

  /* Table 1: Ning p_y = 35.3 MPa; Du et al. p_y = 5.52x10^3 MPa. Table 3 Ning k_el 283. */
  const dem_refcol preq[] = {{"py", "MPa"}, {"R", "um"}};
  t = load_req("nan_ning1995_unloading/properties.csv", preq, 2);
  ck_assert_double_eq(col0(t, "py", 0), 35.3);
  dem_refdata_free(t);
  t = load_req("nan_du2007_unloading/properties.csv", preq, 2);
  ck_assert_double_eq(col0(t, "py", 0), 5.52e3);
  dem_refdata_free(t);
  const dem_refcol yreq[] = {{"ke_law_eq", "-"}, {"kel", "N/m"}};
  t = load_req("nan_ning1995_unloading/yield_point.csv", yreq, 2);
  ck_assert_double_eq(lookup(t, "ke_law_eq", 44, "kel"), 283);
  dem_refdata_free(t);
}
END_TEST

START_TEST(test_spot_thesis) {
  /* Thesis Table 4.2: k_e 1500, k_p 210, k_cp 20 N/m, 8/9 f_ce 2.1 uN, f_0p 4.0 uN. */
  const dem_refcol sreq[] = {
      {"ke", "N/m"}, {"kp", "N/m"}, {"kcp", "N/m"}, {"f0", "uN"}, {"f0p", "uN"}};
  dem_reftable *t = load_req("pasha2013_ning_impact/stiffness.csv", sreq, 5);
  ck_assert_int_eq(t->nrows, 1);
  ck_assert_double_eq(col0(t, "ke", 0), 1500);
  ck_assert_double_eq(col0(t, "kp", 0), 210);
  ck_assert_double_eq(col0(t, "kcp", 0), 20);
  ck_assert_double_eq(col0(t, "f0", 0), 2.1);
  ck_assert_double_eq(col0(t, "f0p", 0), 4.0);
  double si;
  ck_assert_int_eq(dem_refdata_column_si(t, "f0p", &si, NULL), DEM_OK);
  ck_assert_double_eq_tol(si, 4.0e-6, 1e-18);
  dem_refdata_free(t);

  /* Thesis Table 4.1: wall E printed 182 GPa. */
  const dem_refcol wreq[] = {{"E", "GPa"}};
  t = load_req("pasha2013_ning_impact/wall.csv", wreq, 1);
  ck_assert_double_eq(col0(t, "E", 0), 182);
  dem_refdata_free(t);

  /* Table 6.2: particle k_e = 1 MN/m -> 1e6 N/m in SI; Table 6.3: Gamma 2.00 J/m^2,
   * rolling friction 0.01 (particle-particle). */
  const dem_refcol kreq[] = {{"ke", "MN/m"}, {"kp", "MN/m"}, {"kcp", "MN/m"}};
  t = load_req("pasha2013_ch6_indentation/particles.csv", kreq, 3);
  ck_assert_int_eq(dem_refdata_column_si(t, "kcp", &si, NULL), DEM_OK);
  ck_assert_double_eq_tol(si, 1e4, 1e-9);
  dem_refdata_free(t);
  const dem_refcol ireq[] = {{"pair", "-"}, {"gamma", "J/m^2"}, {"mu_r", "-"}};
  t = load_req("pasha2013_ch6_indentation/interactions.csv", ireq, 3);
  ck_assert_double_eq(lookup(t, "pair", 1, "gamma"), 2.0);
  ck_assert_double_eq(lookup(t, "pair", 1, "mu_r"), 0.01);
  dem_refdata_free(t);

  /* Table 5.1, first row 0.59 mm / 0.33 %; Table 5.2 Material 1 E = 55 GPa. */
  const dem_refcol dreq[] = {{"d", "mm"}, {"number_freq", "%"}};
  t = load_req("pasha2013_ch5_indentation/size.csv", dreq, 2);
  ck_assert_double_eq(lookup(t, "d", 0.59, "number_freq"), 0.33);
  dem_refdata_free(t);
  const dem_refcol mreq[] = {{"material", "-"}, {"E", "GPa"}};
  t = load_req("pasha2013_ch5_indentation/materials.csv", mreq, 2);
  ck_assert_double_eq(lookup(t, "material", 1, "E"), 55);
  dem_refdata_free(t);

  /* Section 5.2: hardness ~8 kPa (13 mm bed) vs ~6 kPa (20-50 mm beds), 13 mm indenter. */
  const dem_refcol hreq[] = {
      {"h_bed", "mm"}, {"d_die", "mm"}, {"D_indenter", "mm"}, {"H_plateau", "kPa"}};
  t = load_req("pasha2013_ch5_indentation/hardness.csv", hreq, 4);
  int n13 = 0;
  for (int r = 0; r < t->nrows; r++) {
    if (dem_refdata_value(t, r, 2) != 13) continue;
    double hb = dem_refdata_value(t, r, 0), H = dem_refdata_value(t, r, 3);
    ck_assert_double_eq(H, hb == 13 ? 8 : 6);
    n13++;
  }
  ck_assert_int_eq(n13, 4); /* beds of 13, 20, 30 and 50 mm */
  dem_refdata_free(t);

  /* Section 7.2: gamma* = 0.0115, 0.2297, 0.4594, 2.2969. */
  const dem_refcol greq[] = {{"gamma_star", "-"}};
  t = load_req("pasha2013_ch7_strain_rate/strain_rates.csv", greq, 1);
  ck_assert_int_eq(t->nrows, 4);
  ck_assert_double_eq(dem_refdata_value(t, 3, 0), 2.2969);
  dem_refdata_free(t);
}
END_TEST

/* ---- the sources' derived numbers, recomputed from the transcribed ones -------------- */

START_TEST(test_derived_unloading) {
  /* Eq. (50): k_e = f_max/(alpha_max - alpha_p); the printed k_e are within 3.1 % (the
   * paper rounds its digitised values; see SOURCE.md). Eq. (51): mean of the two secant
   * loading slopes = k_p (printed 217 and 1.8e5 N/m, to their 3 and 2 digits). */
  const char *cases[] = {"nan_ning1995_unloading", "nan_du2007_unloading"};
  const double kp_printed[] = {217, 1.8e5}, kp_tol[] = {0.005, 0.01};
  for (int k = 0; k < 2; k++) {
    char file[128];
    snprintf(file, sizeof file, "%s/unloading.csv", cases[k]);
    const dem_refcol req[] = {{"f_max", "uN"}, {"alpha_max", "nm"}, {"alpha_p", "nm"},
                              {"ke", "N/m"}};
    dem_reftable *t = load_req(file, req, 4);
    ck_assert_int_eq(t->nrows, 3);
    double f[3], am[3], ap[3], ke[3];
    ck_assert_int_eq(dem_refdata_column_si(t, "f_max", f, NULL), DEM_OK);
    ck_assert_int_eq(dem_refdata_column_si(t, "alpha_max", am, NULL), DEM_OK);
    ck_assert_int_eq(dem_refdata_column_si(t, "alpha_p", ap, NULL), DEM_OK);
    ck_assert_int_eq(dem_refdata_column_si(t, "ke", ke, NULL), DEM_OK);
    for (int i = 0; i < 3; i++) {
      double k50 = f[i] / (am[i] - ap[i]);
      ck_assert_msg(fabs(k50 / ke[i] - 1) < 0.035, "%s curve %d: eq 50 %g vs %g", cases[k], i,
                    k50, ke[i]);
    }
    double kp = 0.5 * ((f[0] - f[1]) / (am[0] - am[1]) + (f[1] - f[2]) / (am[1] - am[2]));
    ck_assert_msg(fabs(kp / kp_printed[k] - 1) < kp_tol[k], "%s: eq 51 k_p %g", cases[k], kp);
    dem_refdata_free(t);
  }
}
END_TEST

START_TEST(test_derived_properties) {
  /* Table 1: pi R* p_y (R* = R for a wall) = 272 and 6.94e4 N/m. */
  const char *files[] = {"nan_ning1995_unloading/properties.csv",
                         "nan_du2007_unloading/properties.csv"};
  for (int k = 0; k < 2; k++) {
    const dem_refcol req[] = {{"R", "um"}, {"py", "MPa"}, {"pi_Rs_py", "N/m"}};
    dem_reftable *t = load_req(files[k], req, 3);
    double R, py, printed;
    dem_refdata_column_si(t, "R", &R, NULL);
    dem_refdata_column_si(t, "py", &py, NULL);
    dem_refdata_column_si(t, "pi_Rs_py", &printed, NULL);
    ck_assert_double_le(fabs(M_PI * R * py / printed - 1), 0.002);
    dem_refdata_free(t);
  }
  /* Thesis Table 4.2: 8/9 f_ce = 8/9 x 1.5 pi Gamma R* = 2.05 uN, printed 2.1 (Table 4.1:
   * Gamma = 0.2 J/m^2, R = 2.45 um). */
  const dem_refcol preq[] = {{"R", "um"}, {"gamma", "J/m^2"}};
  dem_reftable *p = load_req("pasha2013_ning_impact/particle.csv", preq, 2);
  double R, G;
  dem_refdata_column_si(p, "R", &R, NULL);
  dem_refdata_column_si(p, "gamma", &G, NULL);
  dem_refdata_free(p);
  ck_assert_double_eq_tol(8.0 / 9.0 * 1.5 * M_PI * G * R, 2.1e-6, 0.05e-6);
}
END_TEST

START_TEST(test_derived_wall_errors) {
  /* Table 6: the printed mean relative errors (12.5, 9.4, 7.5 %) are the means of
   * |V_model - V_Wall| / V_Wall over the four radii, to the printed 0.1 %. */
  const dem_refcol mreq[] = {{"R", "um"}, {"v_stick", "m/s"}};
  dem_reftable *meas = load_req("nan_wall1990_sticking/measured.csv", mreq, 2);
  dem_reftable *mod = load_req("nan_wall1990_sticking/model.csv", NULL, 0);
  dem_reftable *err = load_req("nan_wall1990_sticking/model_error.csv", NULL, 0);
  for (int e = 0; e < err->nrows; e++) {
    double py = dem_refdata_value(err, e, 0), e0 = dem_refdata_value(err, e, 1);
    double sum = 0;
    int n = 0;
    for (int r = 0; r < mod->nrows; r++) {
      if (dem_refdata_value(mod, r, 0) != py || dem_refdata_value(mod, r, 1) != e0) continue;
      double vw = lookup(meas, "R", dem_refdata_value(mod, r, 2), "v_stick");
      sum += fabs(dem_refdata_value(mod, r, 3) - vw) / vw;
      n++;
    }
    ck_assert_int_eq(n, 4);
    ck_assert_double_eq_tol(100 * sum / n, dem_refdata_value(err, e, 2), 0.05 + 1e-9);
  }
  /* V_s of eq. (73) scales as R^(-5/6): the printed values follow to their 2 digits. */
  const dem_refcol sreq[] = {{"R", "um"}, {"v_s_jkr", "m/s"}};
  dem_reftable *vs = load_req("nan_wall1990_sticking/measured.csv", sreq, 2);
  double v245 = lookup(vs, "R", 2.45, "v_s_jkr");
  for (int r = 0; r < vs->nrows; r++) {
    double R = dem_refdata_value(vs, r, 0), v = dem_refdata_value(vs, r, 1);
    ck_assert_double_le(fabs(v245 * pow(2.45 / R, 5.0 / 6.0) / v - 1), 0.015);
  }
  dem_refdata_free(vs);
  dem_refdata_free(meas);
  dem_refdata_free(mod);
  dem_refdata_free(err);
}
END_TEST

START_TEST(test_derived_size_distributions) {
  /* Tables 4.4, 5.1, 6.1 (seven bins, see SOURCE.md): frequencies sum to 100 % within the
   * printed rounding, number-mean diameter 1 mm within 0.2 %. */
  const char *files[] = {"pasha2013_ch4_compression/size.csv",
                         "pasha2013_ch5_indentation/size.csv",
                         "pasha2013_ch6_indentation/size.csv"};
  for (int k = 0; k < 3; k++) {
    const dem_refcol req[] = {{"d", "mm"}, {"number_freq", "%"}};
    dem_reftable *t = load_req(files[k], req, 2);
    double s = 0, m = 0;
    for (int r = 0; r < t->nrows; r++) {
      s += dem_refdata_value(t, r, 1);
      m += dem_refdata_value(t, r, 0) * dem_refdata_value(t, r, 1);
    }
    ck_assert_msg(fabs(s - 100) <= 0.015, "%s: frequencies sum to %g", files[k], s);
    ck_assert_double_le(fabs(m / s - 1.0), 0.002);
    dem_refdata_free(t);
  }
}
END_TEST

/* ---- units ------------------------------------------------------------------------- */

START_TEST(test_units) {
  double s = 0;
  ck_assert_int_eq(dem_refdata_unit_scale("uN", &s), DEM_OK);
  ck_assert_double_eq(s, 1e-6);
  ck_assert_int_eq(dem_refdata_unit_scale("mJ/m^2", &s), DEM_OK);
  ck_assert_double_eq(s, 1e-3);
  ck_assert_int_eq(dem_refdata_unit_scale("%", &s), DEM_OK);
  ck_assert_double_eq(s, 0.01);
  ck_assert_int_eq(dem_refdata_unit_scale("-", &s), DEM_OK);
  ck_assert_double_eq(s, 1.0);
  ck_assert_int_eq(dem_refdata_unit_scale("µm", &s), DEM_ENOTFOUND); /* ASCII only */
  ck_assert_int_eq(dem_refdata_unit_scale("furlong", NULL), DEM_ENOTFOUND);
}
END_TEST

/* ---- loader errors, provoked --------------------------------------------------------- */

START_TEST(test_load_good_scratch) {
  make_scratch();
  /* CRLF line ends, blanks around fields, no final newline, e-notation: all accepted. */
  write_file("ok.csv", "R [um] , f_max [uN]\r\n2.385, 4.2e1\r\n 1.72 ,-3.5");
  char path[512];
  snprintf(path, sizeof path, "%s/ok.csv", scratch);
  dem_err err = {0};
  const dem_refcol req[] = {{"f_max", "uN"}, {"R", NULL}};
  dem_reftable *t = dem_refdata_load(path, req, 2, &err);
  ck_assert_msg(t != NULL, "%s", err.msg);
  ck_assert_int_eq(t->ncols, 2);
  ck_assert_int_eq(t->nrows, 2);
  ck_assert_str_eq(t->names[1], "f_max");
  ck_assert_str_eq(t->units[0], "um");
  ck_assert_double_eq(dem_refdata_value(t, 0, 1), 42.0);
  ck_assert_double_eq(dem_refdata_value(t, 1, 1), -3.5);
  ck_assert_int_eq(dem_refdata_column(t, "absent"), -1);
  double si[2];
  ck_assert_int_eq(dem_refdata_column_si(t, "R", si, &err), DEM_OK);
  ck_assert_double_eq_tol(si[0], 2.385e-6, 1e-20);
  ck_assert_int_eq(dem_refdata_column_si(t, "absent", si, &err), DEM_EMISSING);
  ck_assert_ptr_nonnull(strstr(err.msg, "absent"));
  dem_refdata_free(t);
  dem_refdata_free(NULL);
  remove_scratch();
}
END_TEST

START_TEST(test_load_errors) {
  make_scratch();
  const dem_refcol req[] = {{"v_stick", "m/s"}};
  /* Missing header: the first line holds numbers. */
  expect_fail("noheader.csv", "2.45,1.96\n1.72,3.25\n", NULL, 0, DEM_EPARSE, 1, "'2.45'");
  /* Empty file and empty first line. */
  expect_fail("empty.csv", "", NULL, 0, DEM_EPARSE, 1, "missing header");
  expect_fail("blankhead.csv", "\nR [um]\n1\n", NULL, 0, DEM_EPARSE, 1, "missing header");
  /* A header field without a unit, with a bad name, with an unknown unit, twice. */
  expect_fail("nounit.csv", "R [um],v_stick\n1,2\n", NULL, 0, DEM_EPARSE, 1, "'v_stick'");
  expect_fail("badname.csv", "2R [um]\n1\n", NULL, 0, DEM_EPARSE, 1, "'2R'");
  expect_fail("unknownunit.csv", "R [furlong]\n1\n", NULL, 0, DEM_EPARSE, 1, "[furlong]");
  expect_fail("dupcol.csv", "R [um],R [um]\n1,2\n", NULL, 0, DEM_EPARSE, 1, "twice");
  /* Ragged rows: too few and too many fields on line 3. */
  expect_fail("short.csv", "R [um],v [m/s]\n1,2\n3\n", NULL, 0, DEM_EPARSE, 3, "1 fields");
  expect_fail("long.csv", "R [um],v [m/s]\n1,2\n3,4,5\n", NULL, 0, DEM_EPARSE, 3, "3 fields");
  /* Non-finite numbers: NaN, infinity, overflow. The column is named. */
  expect_fail("nan.csv", "R [um],v [m/s]\n1,2\n3,NaN\n", NULL, 0, DEM_ENONFINITE, 3,
              "column 'v' [m/s]: 'NaN'");
  expect_fail("inf.csv", "R [um],v [m/s]\n-inf,2\n", NULL, 0, DEM_ENONFINITE, 2, "'-inf'");
  expect_fail("huge.csv", "R [um],v [m/s]\n1,1e999\n", NULL, 0, DEM_ENONFINITE, 2, "'1e999'");
  /* Text in a number, a trailing unit, a placeholder dash, an empty field. */
  expect_fail("text.csv", "R [um],v [m/s]\n1,2\n2.45,fast\n", NULL, 0, DEM_EPARSE, 3,
              "column 'v' [m/s]: 'fast' is not a number");
  expect_fail("suffix.csv", "R [um],v [m/s]\n2.45um,1\n", NULL, 0, DEM_EPARSE, 2, "'2.45um'");
  expect_fail("dash.csv", "R [um],v [m/s]\n1,-\n", NULL, 0, DEM_EPARSE, 2, "'-'");
  expect_fail("emptyfield.csv", "R [um],v [m/s]\n1,\n", NULL, 0, DEM_EPARSE, 2,
              "empty field");
  /* An empty line inside the data, and no data at all. */
  expect_fail("gap.csv", "R [um]\n1\n\n2\n", NULL, 0, DEM_EPARSE, 3, "empty line");
  expect_fail("nodata.csv", "R [um]\n", NULL, 0, DEM_EMISSING, 2, "no data rows");
  /* A required column missing; present with the wrong unit. */
  expect_fail("missingcol.csv", "R [um],v_s [m/s]\n1,2\n", req, 1, DEM_EMISSING, 1,
              "'v_stick' is missing");
  expect_fail("wrongunit.csv", "R [um],v_stick [mm/s]\n1,2\n", req, 1, DEM_EINVAL, 1,
              "unit [mm/s], expected [m/s]");

  /* A file that does not exist: DEM_EIO naming the path; NULL err is allowed. */
  dem_err err = {0};
  char path[512];
  snprintf(path, sizeof path, "%s/absent.csv", scratch);
  ck_assert_ptr_null(dem_refdata_load(path, NULL, 0, &err));
  ck_assert_int_eq(err.code, DEM_EIO);
  ck_assert_ptr_nonnull(strstr(err.msg, "absent.csv"));
  ck_assert_ptr_null(dem_refdata_load(path, NULL, 0, NULL));
  remove_scratch();
}
END_TEST

/* ---- SOURCE.md and folder validator errors ------------------------------------------ */

static const char *good_source =
    "# Title\n\n## Citation\nA. Author, 2013.\n## Location\nTable 1.\n## Files\n"
    "- `a.csv`: the data.\n## Units\num\n## Transcription\nBy hand.\n## Tolerance\n1 %.\n";

static void expect_source_fail(const char *source, int code, const char *what) {
  write_file("SOURCE.md", source);
  dem_err err = {0};
  ck_assert_int_eq(dem_refdata_check_source(scratch, &err), code);
  ck_assert_msg(strstr(err.msg, "SOURCE.md") != NULL, "'%s' does not name SOURCE.md", err.msg);
  ck_assert_msg(strstr(err.msg, what) != NULL, "'%s' does not mention '%s'", err.msg, what);
}

START_TEST(test_source_errors) {
  make_scratch();
  write_file("a.csv", "R [um]\n1\n");
  write_file("SOURCE.md", good_source);
  dem_err err = {0};
  int nf = -1, nr = -1;
  ck_assert_int_eq(dem_refdata_check_folder(scratch, &nf, &nr, &err), DEM_OK);
  ck_assert_int_eq(nf, 1);
  ck_assert_int_eq(nr, 1);

  /* Each required section missing in turn. */
  const char *sections[] = {"Citation", "Location", "Files", "Units", "Transcription",
                            "Tolerance"};
  for (int k = 0; k < 6; k++) {
    char text[1024], head[64];
    snprintf(text, sizeof text, "%s", good_source);
    snprintf(head, sizeof head, "## %s\n", sections[k]);
    char *at = strstr(text, head);
    ck_assert_ptr_nonnull(at);
    at[2] = '#'; /* "## X" -> "###X": no longer a required heading */
    expect_source_fail(text, DEM_EMISSING, sections[k]);
  }
  /* An empty section is reported with its line. */
  expect_source_fail("# T\n## Citation\nx\n## Location\nx\n## Files\na.csv\n## Units\n\n"
                     "## Transcription\nx\n## Tolerance\nx\n",
                     DEM_EMISSING, "SOURCE.md:8: section '## Units' is empty");
  /* No title; a repeated section; a CSV file not described. */
  expect_source_fail(good_source + 9, DEM_EPARSE, "title");
  char twice[1024];
  snprintf(twice, sizeof twice, "%s## Units\nagain\n", good_source);
  expect_source_fail(twice, DEM_EPARSE, "repeats");
  write_file("SOURCE.md", good_source);
  write_file("b.csv", "R [um]\n1\n");
  expect_source_fail(good_source, DEM_EMISSING, "'b.csv' is not described");

  /* The folder check reports a bad data file with its line. */
  char src[1024];
  snprintf(src, sizeof src, "%s\nAlso `b.csv`.\n", good_source);
  write_file("SOURCE.md", src);
  write_file("b.csv", "R [um]\n1\nx\n");
  ck_assert_int_eq(dem_refdata_check_folder(scratch, NULL, NULL, &err), DEM_EPARSE);
  ck_assert_ptr_nonnull(strstr(err.msg, "b.csv:3: "));
  ck_assert_int_eq(dem_refdata_check_folder(scratch, NULL, NULL, NULL), DEM_EPARSE);

  /* No SOURCE.md at all; a folder without data files. */
  char path[512];
  snprintf(path, sizeof path, "%s/SOURCE.md", scratch);
  ck_assert_int_eq(unlink(path), 0);
  ck_assert_int_eq(dem_refdata_check_folder(scratch, NULL, NULL, &err), DEM_EIO);
  ck_assert_ptr_nonnull(strstr(err.msg, "SOURCE.md"));
  remove_scratch();

  make_scratch();
  write_file("SOURCE.md", good_source);
  ck_assert_int_eq(dem_refdata_check_folder(scratch, NULL, NULL, &err), DEM_EMISSING);
  ck_assert_ptr_nonnull(strstr(err.msg, "no .csv"));
  remove_scratch();
}
END_TEST

static int count_folder(const char *dir, const char *name, void *ud) {
  (void)dir;
  char *order = ud;
  strcat(order, name);
  strcat(order, ";");
  return strcmp(name, "b") == 0 ? 7 : 0; /* stop at "b" with a user code */
}

START_TEST(test_foreach_folder) {
  make_scratch();
  char path[512];
  const char *names[] = {"c", "a", "b", ".hidden"};
  for (int k = 0; k < 4; k++) {
    snprintf(path, sizeof path, "%s/%s", scratch, names[k]);
    ck_assert_int_eq(mkdir(path, 0700), 0);
  }
  write_file("file.csv", "R [um]\n1\n"); /* not a folder: skipped */
  char order[64] = "";
  dem_err err = {0};
  ck_assert_int_eq(dem_refdata_foreach_folder(scratch, count_folder, order, &err), 7);
  ck_assert_str_eq(order, "a;b;");
  remove_scratch();
  ck_assert_int_eq(dem_refdata_foreach_folder("/nonexistent-refdata-dir", count_folder, order,
                                              &err),
                   DEM_EIO);
  ck_assert_ptr_nonnull(strstr(err.msg, "/nonexistent-refdata-dir"));
}
END_TEST

static Suite *refdata_suite(void) {
  Suite *s = suite_create("refdata");
  TCase *tc = tcase_create("committed");
  tcase_add_test(tc, test_all_folders);
  tcase_add_test(tc, test_spot_nan_paper);
  tcase_add_test(tc, test_spot_thesis);
  suite_add_tcase(s, tc);
  tc = tcase_create("derived");
  tcase_add_test(tc, test_derived_unloading);
  tcase_add_test(tc, test_derived_properties);
  tcase_add_test(tc, test_derived_wall_errors);
  tcase_add_test(tc, test_derived_size_distributions);
  suite_add_tcase(s, tc);
  tc = tcase_create("loader");
  tcase_add_test(tc, test_units);
  tcase_add_test(tc, test_load_good_scratch);
  tcase_add_test(tc, test_load_errors);
  suite_add_tcase(s, tc);
  tc = tcase_create("validator");
  tcase_add_test(tc, test_source_errors);
  tcase_add_test(tc, test_foreach_folder);
  suite_add_tcase(s, tc);
  return s;
}

int main(void) {
  SRunner *sr = srunner_create(refdata_suite());
  srunner_run_all(sr, CK_ENV);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
