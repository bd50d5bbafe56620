/* cases.c — the eleven thesis conclusions (thesis 5.3, 6.4, 7.4, 8.1; physics notes "Ball
 * indentation") as checks whose statistic and pass criterion are fixed here, before any run.
 *
 * Conventions of every check:
 * - H is the plateau mean of the hardness over the tier's h/r window (0.2-0.5), with the
 *   standard error that allows for the correlation of the series (dem_plateau_stats);
 *   "sd" is the standard deviation of H over the window (the fluctuation bars of the
 *   thesis' Figs 5.17, 6.x, 7.3).
 * - "A > B beyond the fluctuation": one-sided z-test of the two plateau means at level
 *   h->level (0.05) with se = sqrt(se_A^2 + se_B^2).
 * - "A and B agree": the two-sided z-test does not find a difference at level / (number of
 *   pairs compared) (Bonferroni, so that comparing many runs does not manufacture a
 *   difference).
 * - Runs on different beds are independent; runs on the same bed share the bed (common
 *   random numbers), which makes a test of their difference conservative.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "vh.h"

const char *vh_status_name(vh_status s) {
  static const char *n[] = {"PASS", "FAIL", "ERROR", "N/A"};
  return n[s];
}

int vh_greater(const vh *h, const dem_series_stats *a, const dem_series_stats *b,
               dem_comparison *c) {
  dem_err e = {0};
  return dem_compare_means(a->mean, a->se, b->mean, b->se, h->level, DEM_TEST_GREATER, c, &e);
}

int vh_agree(const vh *h, const dem_series_stats *a, const dem_series_stats *b,
             dem_comparison *c) {
  dem_err e = {0};
  return dem_compare_means(a->mean, a->se, b->mean, b->se, h->level, DEM_TEST_TWO_SIDED, c,
                           &e);
}

static vh_check *check(vh_case_result *r, const char *what, const char *statistic,
                       const char *thesis) {
  if (r->nchecks == VH_MAX_CHECKS) return &r->checks[VH_MAX_CHECKS - 1];
  vh_check *c = &r->checks[r->nchecks++];
  memset(c, 0, sizeof *c);
  snprintf(c->what, sizeof c->what, "%s", what);
  snprintf(c->statistic, sizeof c->statistic, "%s", statistic);
  snprintf(c->thesis, sizeof c->thesis, "%s", thesis);
  c->status = VH_NA;
  return c;
}

/* Run (or reuse) an indentation for the case; label and x name it in the case's figures
 * (x: the varied parameter of the trend figure, NAN if none). */
static int add_run_x(vh *h, vh_case_result *r, const vh_bed *b, const vh_indent *in,
                     const char *label, double x, dem_err *err) {
  int i = vh_run_get(h, b, in, err);
  if (i < 0) return -1;
  if (r->nruns < VH_MAX_CASE_RUNS) {
    snprintf(r->labels[r->nruns], sizeof r->labels[0], "%.39s", label);
    r->x[r->nruns] = x;
    r->runs[r->nruns++] = i;
  }
  return i;
}

static int ok(const vh *h, int i) {
  return i >= 0 && h->runs[i].status == DEM_OK && isfinite(h->runs[i].sH.mean) &&
         h->runs[i].sH.se > 0;
}

/* Any failed run makes the case ERROR; the checks that could not be evaluated stay N/A. */
static vh_status pass(int cond) { return cond ? VH_PASS : VH_FAIL; }

static void kpa(char *b, size_t n, const dem_series_stats *s) {
  snprintf(b, n, "%.2f +- %.2f kPa (sd %.2f)", s->mean / 1e3, s->se / 1e3, s->sd / 1e3);
}

/* ---- replicate beds ----------------------------------------------------------------- *
 * A criterion read off one run (the plateau's slope, the dynamic bin's 90 % point, the solids
 * fraction under an indenter) swings from bed to bed at thesis scale as much as between the
 * runs it compares (docs/validation.md, "the servo without its dashpots"). The cases that
 * judge such criteria (1, 4, 6, and 3's wall confinement on the shallow bed) therefore
 * make their runs on each of the tier's replicate
 * beds (seeds 1..k, vh_bed_ref) and judge:
 * - a scalar statistic (a relative slope, an h/r, a deviation in sd) by its mean over the
 *   beds; a slope relative to a mean as mean slope / mean value (the trend of the mean curve);
 * - a difference of two runs on the same bed by the paired test over the beds
 *   (dem_compare_paired: the runs' own errors and z, or, if Cochran's Q finds the difference
 *   varying between beds beyond those errors, its spread and Student's t of k - 1 dof).
 * With one replicate (quick, smoke) this is the single-bed criterion unchanged. */
#define VH_MAX_REPLICATES 4

static int nreplicates(const vh *h) {
  int k = h->tier->replicates;
  return k < 1 ? 1 : k > VH_MAX_REPLICATES ? VH_MAX_REPLICATES : k;
}

/* The indentation `in` on every replicate bed of height `bed` [d] (0: the tier's reference
 * bed; another height in its die and at its speed, at_height); idx[j] its run on replicate j.
 * The first replicate's run is labelled `label`, the others "label, seed s". Returns the
 * count or -1. */
static int on_replicates(vh *h, vh_case_result *r, const vh_indent *in, double bed,
                         const char *label, int *idx, dem_err *err);

/* The replicates j < k whose runs idx[j * nper + cols[o]] (o < nc; cols NULL: every run of
 * replicate j, o < nper) all succeeded, in use[]. Returns their number. */
static int usable(const vh *h, const int *idx, int k, int nper, const int *cols, int nc,
                  int *use) {
  if (!cols) nc = nper;
  int n = 0;
  for (int j = 0; j < k; j++) {
    int all = 1;
    for (int o = 0; o < nc; o++)
      if (!ok(h, idx[j * nper + (cols ? cols[o] : o)])) all = 0;
    if (all) use[n++] = j;
  }
  return n;
}

/* "; mean over k replicate beds" (or "over n of k") after the values printed; "" for k = 1. */
static void reps_note(char *buf, size_t len, int n, int k) {
  if (k <= 1) buf[0] = 0;
  else if (n == k) snprintf(buf, len, "; mean over %d replicate beds", k);
  else snprintf(buf, len, "; mean over %d of %d replicate beds", n, k);
}

/* Appends bed j's value x to the list "; per bed a b ..." in buf (nothing with one replicate). */
static void per_bed(char *buf, size_t len, int j, int k, int prec, double x) {
  size_t m = strlen(buf);
  if (k > 1 && m < len) snprintf(buf + m, len - m, "%s%.*f", j ? " " : "; per bed ", prec, x);
}

/* A bed of another height than the reference, and the indentation on it: a bed deeper than
 * the reference is consolidated and indented at the reference bed's speed in m/s, not at
 * the tier's gamma* (vh_gamma_star_of_bed): with gamma_dot = v / h_bed the same gamma*
 * moves the piston and the indenter 1.5-2.5x faster on the 30 and 50 d beds than the speed
 * the speed-versus-accuracy study validated on the 20 d bed, and those beds then read high
 * because of the speed (diagnostics of 2026-12-01/02, docs/validation.md). The thesis ran
 * every bed at gamma* 0.01, quasi-static whatever the depth. */
static void at_height(const vh *h, vh_bed *b, vh_indent *in, double bed) {
  b->bed = bed;
  /* The thesis' shallow bed (13 mm) is in a 39 mm die, its deeper beds in the 45 mm die
   * (Figs 5.2-5.11 against 5.12-5.19): the tier's shallow_die. */
  if (bed < h->tier->bed && h->tier->shallow_die > 0) b->die = h->tier->shallow_die;
  b->gamma_star = in->gamma_star = vh_gamma_star_of_bed(h, bed);
}

/* The bed-to-bed spread of the plateau mean: for runs on different beds the within-run
 * standard error misses the variation between beds of the same parameters. Estimated from the
 * reference indentation on the tier's replicate beds (seeds 1..k) as
 * s_bed^2 = max(0, var(means) - mean(se^2)); 0 with one replicate (then stated in the note).
 * Applied to the cross-bed tests of cases 2, 8 and 9 as se' = sqrt(se^2 + s_bed^2). */
static double bed_spread(vh *h, vh_case_result *r, double bed, double D, dem_err *err) {
  const int k = h->tier->replicates;
  if (k < 2) {
    snprintf(r->note, sizeof r->note, "One bed per parameter set: the bed-to-bed spread is "
                                      "not estimated in this tier (within-run errors only).");
    return 0.0;
  }
  double m[8], se2 = 0, mean = 0;
  int n = 0;
  for (int i = 0; i < k && i < 8; i++) {
    vh_bed b = vh_bed_ref(h, i);
    vh_indent in = vh_indent_ref(h);
    at_height(h, &b, &in, bed);
    in.D = D;
    int j = vh_run_get(h, &b, &in, err);
    if (j < 0 || !ok(h, j)) continue;
    m[n++] = h->runs[j].sH.mean;
    se2 += h->runs[j].sH.se * h->runs[j].sH.se;
    mean += h->runs[j].sH.mean;
  }
  *err = (dem_err){0};
  if (n < 2) return 0.0;
  mean /= n;
  double var = 0;
  for (int i = 0; i < n; i++) var += (m[i] - mean) * (m[i] - mean) / (n - 1);
  double s = sqrt(fmax(0.0, var - se2 / n));
  snprintf(r->note, sizeof r->note, "Bed-to-bed spread of the plateau mean from %d replicate "
                                    "beds (%g d, indenter %g d): %.2f kPa, added in quadrature "
                                    "to the standard error of every cross-bed comparison.",
           n, bed, D, s / 1e3);
  return s;
}

static double s_bed_cur = 0.0; /* the spread applied by greater/agree_all (0 within a bed) */

static dem_series_stats widened(const dem_series_stats *s) {
  dem_series_stats w = *s;
  w.se = sqrt(s->se * s->se + s_bed_cur * s_bed_cur);
  return w;
}

/* One-sided "a > b" as a check. */
static void greater(vh *h, vh_check *c, int ia, int ib, const char *na, const char *nb) {
  if (!ok(h, ia) || !ok(h, ib)) return;
  dem_comparison z;
  dem_series_stats a = widened(&h->runs[ia].sH), b = widened(&h->runs[ib].sH);
  if (vh_greater(h, &a, &b, &z)) return;
  snprintf(c->ours, sizeof c->ours, "H(%s) %.2f, H(%s) %.2f kPa; z = %.2f (crit %.2f), p = %.3g",
           na, h->runs[ia].sH.mean / 1e3, nb, h->runs[ib].sH.mean / 1e3, z.z, z.z_crit, z.p);
  c->status = pass(z.different);
}

/* "t" for a paired test judged by the spread between beds, else "z". */
static const char *zt(const dem_comparison *z) { return isinf(z->nu) ? "z" : "t"; }

/* Pairwise agreement of the plateau means of the runs in columns 0..nc of idx (nper runs per
 * replicate bed, beds use[0..n)), by the paired two-sided test over the beds at level / pairs
 * (Bonferroni). With one bed it is the z-test of the two runs (dem_compare_paired, k = 1).
 * The standard errors are widened by s_bed_cur, which is 0 but in the cross-bed comparisons
 * of cases 2 and 8 (one run per bed, through agree_all). The pair printed is the one
 * furthest beyond its critical value (z and t pairs can mix). */
static void agree_paired(vh *h, vh_check *c, const int *idx, int nper, const int *use, int n,
                         int k, int nc, const char *const *names) {
  if (n == 0) return;
  const int npairs = nc * (nc - 1) / 2;
  int all = 1;
  double worst_r = -1.0;
  dem_comparison worst = {0};
  char wname[64] = "";
  for (int a = 0; a < nc; a++)
    for (int b = a + 1; b < nc; b++) {
      double ma[VH_MAX_REPLICATES], sa[VH_MAX_REPLICATES], mb[VH_MAX_REPLICATES],
          sb[VH_MAX_REPLICATES];
      for (int j = 0; j < n; j++) {
        const dem_series_stats x = widened(&h->runs[idx[use[j] * nper + a]].sH),
                               y = widened(&h->runs[idx[use[j] * nper + b]].sH);
        ma[j] = x.mean, sa[j] = x.se, mb[j] = y.mean, sb[j] = y.se;
      }
      dem_comparison z;
      dem_err e = {0};
      if (dem_compare_paired((size_t)n, ma, sa, mb, sb, h->level / npairs, DEM_TEST_TWO_SIDED,
                             &z, NULL, &e))
        return;
      double rr = fabs(z.z) / z.z_crit;
      if (rr > worst_r) {
        worst_r = rr, worst = z;
        snprintf(wname, sizeof wname, "%s vs %s", names[a], names[b]);
      }
      if (z.different) all = 0;
    }
  char buf[160] = "", rn[64];
  size_t m = 0;
  for (int a = 0; a < nc && m < sizeof buf - 24; a++) {
    double mean = 0.0;
    for (int j = 0; j < n; j++) mean += h->runs[idx[use[j] * nper + a]].sH.mean / n;
    m += (size_t)snprintf(buf + m, sizeof buf - m, "%s%s %.2f", a ? ", " : "", names[a],
                          mean / 1e3);
  }
  reps_note(rn, sizeof rn, n, k);
  char dof[24] = "";
  if (!isinf(worst.nu)) snprintf(dof, sizeof dof, " on %.0f dof", worst.nu);
  /* the precisions keep the worst case within c->ours (-Wformat-truncation) */
  snprintf(c->ours, sizeof c->ours, "H [kPa]: %.80s; max |%s| = %.2f (%.24s), crit %.2f%.12s%.40s",
           buf, zt(&worst), fabs(worst.z), wname, worst.z_crit, dof, rn);
  c->status = pass(all);
}

/* Pairwise agreement of the plateau means of runs idx[0..n), one run each, on one bed or on
 * different beds (Bonferroni): agree_paired with one "bed" of n runs. */
static void agree_all(vh *h, vh_check *c, const int *idx, int n, const char *const *names) {
  int use[1];
  if (usable(h, idx, 1, n, NULL, 0, use) == 1) agree_paired(h, c, idx, n, use, 1, 1, n, names);
}

/* Spearman rank correlation of x and y (n <= 16, no ties expected). */
static double spearman(const double *x, const double *y, int n) {
  double rx[16], ry[16];
  for (int i = 0; i < n; i++) {
    rx[i] = ry[i] = 1;
    for (int j = 0; j < n; j++) {
      if (x[j] < x[i]) rx[i]++;
      if (y[j] < y[i]) ry[i]++;
    }
  }
  double d2 = 0;
  for (int i = 0; i < n; i++) d2 += (rx[i] - ry[i]) * (rx[i] - ry[i]);
  return 1.0 - 6.0 * d2 / (n * ((double)n * n - 1.0));
}

/* A run not made because of the --budget is not an error: its criteria stay N/A, and so
 * does the case unless a criterion it could evaluate failed (a partly evaluated case is
 * not called PASS). */
static void finish(vh *h, vh_case_result *r) {
  int err = 0, fail = 0, any = 0, skipped = 0;
  s_bed_cur = 0.0;
  for (int i = 0; i < r->nruns; i++) {
    const vh_run *u = &h->runs[r->runs[i]];
    if (u->skipped) skipped++;
    else if (u->status != DEM_OK) err = 1;
  }
  for (int i = 0; i < r->nchecks; i++) {
    if (r->checks[i].status == VH_FAIL) fail = 1;
    if (r->checks[i].status != VH_NA) any = 1;
  }
  r->status = err ? VH_ERROR : fail ? VH_FAIL : skipped ? VH_NA : any ? VH_PASS : VH_NA;
  if (skipped) {
    size_t len = strlen(r->note);
    snprintf(r->note + len, sizeof r->note - len,
             "%s%d of its %d runs not made (over the --budget): the criteria that need them "
             "are N/A, and so is the case unless a criterion fails.", len ? " " : "", skipped,
             r->nruns);
  }
}

static void names_D(char names[][24], const double *D, int n, const char *fmt) {
  for (int i = 0; i < n; i++) snprintf(names[i], 24, fmt, D[i]);
}

static int on_replicates(vh *h, vh_case_result *r, const vh_indent *in, double bed,
                         const char *label, int *idx, dem_err *err) {
  const int k = nreplicates(h);
  for (int j = 0; j < k; j++) {
    vh_bed b = vh_bed_ref(h, j);
    vh_indent x = *in;
    if (bed > 0) at_height(h, &b, &x, bed);
    char lab[40];
    if (j == 0) snprintf(lab, sizeof lab, "%.39s", label);
    else snprintf(lab, sizeof lab, "%.28s, seed %lu", label, b.seed);
    if ((idx[j] = add_run_x(h, r, &b, &x, lab, NAN, err)) < 0) return -1;
  }
  return k;
}

/* The paired one-sided test "a > b" over n replicate beds: sa[j], sb[j] the two runs'
 * statistics on bed j. */
static int paired_greater(const vh *h, const dem_series_stats *const *sa,
                          const dem_series_stats *const *sb, int n, dem_comparison *z) {
  double a[VH_MAX_REPLICATES], sea[VH_MAX_REPLICATES], b[VH_MAX_REPLICATES],
      seb[VH_MAX_REPLICATES];
  for (int j = 0; j < n; j++) {
    a[j] = sa[j]->mean, sea[j] = sa[j]->se;
    b[j] = sb[j]->mean, seb[j] = sb[j]->se;
  }
  dem_err e = {0};
  return dem_compare_paired((size_t)n, a, sea, b, seb, h->level, DEM_TEST_GREATER, z, NULL,
                            &e);
}

/* ---- 1. plateau ------------------------------------------------------------------------ */

static int c_plateau(vh *h, vh_case_result *r, dem_err *err) {
  vh_indent in = vh_indent_ref(h);
  char lab[40];
  snprintf(lab, sizeof lab, "sphere %g d", in.D);
  int idx[VH_MAX_REPLICATES], use[VH_MAX_REPLICATES];
  int k = on_replicates(h, r, &in, 0, lab, idx, err);
  if (k < 0) return err->code;
  int n = usable(h, idx, k, 1, NULL, 0, use);
  const vh_tier *t = h->tier;
  const double win = t->plateau_hi - t->plateau_lo;
  char rn[64], what[200];
  reps_note(rn, sizeof rn, n, k);
  snprintf(what, sizeof what,
           "H early (h/r %.2f-%.2f) exceeds the plateau H (h/r %.2f-%.2f) beyond the "
           "fluctuation", t->early_lo, t->early_hi, t->plateau_lo, t->plateau_hi);
  vh_check *c = check(r, what, k > 1 ? "paired over the replicate beds, one-sided, level 0.05"
                                     : "z, one-sided, level 0.05",
                      "H falls from high early values to a plateau (Figs 5.3-5.6, 5.12)");
  const dem_series_stats *se[VH_MAX_REPLICATES], *sh[VH_MAX_REPLICATES];
  int early_ok = n > 0;
  double mE = 0, mH = 0, slope = 0, mp = 0, pslope = 0;
  for (int j = 0; j < n; j++) {
    const vh_run *u = &h->runs[idx[use[j]]];
    se[j] = &u->sEarly, sh[j] = &u->sH;
    if (!isfinite(u->sEarly.mean) || !(u->sEarly.se > 0)) early_ok = 0;
    mE += u->sEarly.mean / n, mH += u->sH.mean / n, slope += u->sH.slope / n;
  }
  dem_comparison z;
  if (early_ok && !paired_greater(h, se, sh, n, &z)) {
    snprintf(c->ours, sizeof c->ours, "early %.2f, plateau %.2f kPa; %s = %.2f (crit %.2f)%s",
             mE / 1e3, mH / 1e3, zt(&z), z.z, z.z_crit, rn);
    c->status = pass(z.different);
  }
  c = check(r, "the plateau is flat: the fitted change of H across the window is below 20% "
               "of its mean",
            "|slope| x window / mean", "H stabilises beyond h/r ~ 0.35-0.4 (5.2)");
  if (n > 0) {
    double rel = fabs(slope) * win / mH;
    char s1[80];
    if (k == 1) kpa(s1, sizeof s1, &h->runs[idx[0]].sH);
    else {
      snprintf(s1, sizeof s1, "%.2f kPa", mH / 1e3);
      for (int j = 0; j < n; j++)
        per_bed(s1, sizeof s1, j, k, 3,
                fabs(h->runs[idx[use[j]]].sH.slope) * win / h->runs[idx[use[j]]].sH.mean);
    }
    snprintf(c->ours, sizeof c->ours, "%.3f (slope %.2f kPa per unit h/r; H %s%s)", rel,
             slope / 1e3, s1, rn);
    c->status = pass(rel < 0.2);
  }
  c = check(r, "the dynamic-bin hydrostatic stress stops rising: its fitted change across the "
               "plateau window is below 20% of its mean",
            "|slope| x window / mean", "rises up to h/r ~ 0.1, then constant (Fig 5.19)");
  int stress_ok = n > 0;
  for (int j = 0; j < n; j++) {
    const vh_run *u = &h->runs[idx[use[j]]];
    if (!u->have_stress || !isfinite(u->sp.mean) || !(u->sp.mean > 0)) stress_ok = 0;
    else mp += u->sp.mean / n, pslope += u->sp.slope / n;
  }
  if (stress_ok) {
    double rel = fabs(pslope) * win / mp;
    char s1[64] = "";
    for (int j = 0; j < n; j++)
      per_bed(s1, sizeof s1, j, k, 3,
              fabs(h->runs[idx[use[j]]].sp.slope) * win / h->runs[idx[use[j]]].sp.mean);
    snprintf(c->ours, sizeof c->ours, "%.3f (bin p %.2f kPa, slope %.2f kPa per unit h/r%s%s)",
             rel, mp / 1e3, pslope / 1e3, s1, rn);
    c->status = pass(rel < 0.2);
  }
  finish(h, r);
  return DEM_OK;
}

/* ---- 2. bed height --------------------------------------------------------------------- */
static int c_bed(vh *h, vh_case_result *r, dem_err *err) {
  r->xlabel = "bed height [d]";
  r->logx = 0;
  const vh_tier *t = h->tier;
  int idx[4];
  double die[4];
  char nm[4][24];
  const char *names[4];
  for (int k = 0; k < t->nbeds; k++) {
    vh_bed b = vh_bed_ref(h, 0);
    vh_indent in = vh_indent_ref(h);
    at_height(h, &b, &in, t->beds[k]);
    die[k] = b.die;
    in.D = t->bed_indenter;
    snprintf(nm[k], sizeof nm[k], "%g d", t->beds[k]);
    names[k] = nm[k];
    char lab[40];
    snprintf(lab, sizeof lab, "bed %g d", t->beds[k]);
    if ((idx[k] = add_run_x(h, r, &b, &in, lab, t->beds[k], err)) < 0) return err->code;
  }
  s_bed_cur = bed_spread(h, r, t->bed, t->bed_indenter, err);
  char what[200];
  snprintf(what, sizeof what, "H of the %g d bed (%g d die) exceeds H of the %g d bed (%g d "
                              "die; indenter %g d)",
           t->beds[0], die[0], t->beds[1], die[1], t->bed_indenter);
  vh_check *c = check(r, what, "z, one-sided, level 0.05",
                      "13 mm bed ~8 kPa vs ~6 kPa at 20-50 mm (Fig 5.12)");
  greater(h, c, idx[0], idx[1], nm[0], nm[1]);
  if (t->nbeds >= 3) {
    c = check(r, "the beds of 20 d and more agree pairwise", "z, two-sided, Bonferroni",
              "20, 30 and 50 mm give the same ~6 kPa (Fig 5.12)");
    agree_all(h, c, idx + 1, t->nbeds - 1, names + 1);
  }
  s_bed_cur = 0.0;
  c = check(r, "the indentation raises the stress near the base of the deeper beds by less "
               "than 10% of H, and by more on the shallowest bed",
            "(base p at the plateau - before contact) / H",
            "near the base stresses notable for 13 mm, negligible for 20 mm (Figs 5.10, 5.14)");
  int have = 1;
  double rel[4];
  for (int k = 0; k < t->nbeds; k++) {
    vh_run *u = &h->runs[idx[k]];
    if (!ok(h, idx[k]) || !u->have_stress || !isfinite(u->base_p0)) {
      have = 0;
      break;
    }
    double s = 0;
    size_t m = 0;
    for (size_t i = 0; i < u->n; i++)
      if (u->hr[i] >= t->plateau_lo && u->hr[i] <= t->plateau_hi && isfinite(u->base_p[i]))
        s += u->base_p[i], m++;
    rel[k] = m ? (s / (double)m - u->base_p0) / u->sH.mean : NAN;
    if (!isfinite(rel[k])) have = 0;
  }
  if (have) {
    int deep_ok = 1;
    size_t m = 0;
    for (int k = 0; k < t->nbeds; k++) {
      m += (size_t)snprintf(c->ours + m, sizeof c->ours - m, "%s%s %.3f", k ? ", " : "", nm[k],
                            rel[k]);
      if (k > 0 && !(rel[k] < 0.1 && rel[k] < rel[0])) deep_ok = 0;
    }
    c->status = pass(deep_ok);
  }
  finish(h, r);
  return DEM_OK;
}

/* ---- 3. indenter size ------------------------------------------------------------------ */
static int c_size(vh *h, vh_case_result *r, dem_err *err) {
  r->xlabel = "indenter diameter D [d]";
  r->logx = 0;
  const vh_tier *t = h->tier;
  int idx[6];
  char nm[6][24];
  const char *names[6];
  names_D(nm, t->sizes, t->nsizes, "%g d");
  for (int k = 0; k < t->nsizes; k++) {
    vh_bed b = vh_bed_ref(h, 0);
    vh_indent in = vh_indent_ref(h);
    in.D = t->sizes[k];
    char lab[40];
    snprintf(lab, sizeof lab, "D %g d", in.D);
    if ((idx[k] = add_run_x(h, r, &b, &in, lab, in.D, err)) < 0) return err->code;
    names[k] = nm[k];
  }
  int all = 1;
  double sd[6];
  for (int k = 0; k < t->nsizes; k++) {
    if (!ok(h, idx[k])) all = 0;
    else sd[k] = h->runs[idx[k]].sH.sd;
  }
  char what[200];
  snprintf(what, sizeof what, "the fluctuation sd(H) falls with D: Spearman rho(D, sd) <= -0.6 "
                              "on the %g d bed", t->bed);
  vh_check *c = check(r, what, "Spearman rank correlation", "fluctuation grows as D shrinks "
                                                            "(Figs 5.15-5.17)");
  if (all) {
    double rho = spearman(t->sizes, sd, t->nsizes);
    size_t m = 0;
    m += (size_t)snprintf(c->ours, sizeof c->ours, "rho = %.2f; sd [kPa]:", rho);
    for (int k = 0; k < t->nsizes && m < sizeof c->ours; k++)
      m += (size_t)snprintf(c->ours + m, sizeof c->ours - m, " %s %.2f", nm[k], sd[k] / 1e3);
    c->status = pass(rho <= -0.6);
  }
  snprintf(what, sizeof what, "indenters of %g d and more agree pairwise (stable)",
           t->stable_from);
  c = check(r, what, "z, two-sided, Bonferroni", "16-22 d stable at ~6 kPa (Fig 5.15)");
  int k0 = 0;
  while (k0 < t->nsizes && t->sizes[k0] < t->stable_from) k0++;
  if (t->nsizes - k0 >= 2) agree_all(h, c, idx + k0, t->nsizes - k0, names + k0);
  else {
    snprintf(c->ours, sizeof c->ours, "only one size >= %g d in this tier", t->stable_from);
  }
  /* Very large indenter on the shallow bed (wall confinement, Fig 5.6): both balls on each
   * replicate shallow bed, the difference judged by the paired test over the beds. One bed
   * read the 25 d ball 1.5 standard errors below the 13 d ball at thesis scale and 3.5 in the
   * quick tier (docs/validation.md): a same-bed difference of ~10 % is as large as a bed's
   * swing, the situation the replicates of cases 1, 4 and 6 are for. */
  vh_indent in = vh_indent_ref(h);
  const double shallow = t->beds[0];
  int iw[2][VH_MAX_REPLICATES], k = 0;
  const double Dw[2] = {t->bed_indenter, t->wall_indenter};
  char lab[40];
  for (int o = 0; o < 2; o++) {
    in.D = Dw[o];
    snprintf(lab, sizeof lab, "bed %g d, D %g d", shallow, in.D);
    if ((k = on_replicates(h, r, &in, shallow, lab, iw[o], err)) < 0) return err->code;
  }
  vh_bed b = vh_bed_ref(h, 0);
  at_height(h, &b, &in, shallow);
  snprintf(what, sizeof what, "on the %g d bed in the %g d die, the %g d indenter reads higher "
                              "than the %g d one (wall confinement)",
           shallow, b.die, t->wall_indenter, t->bed_indenter);
  c = check(r, what, k > 1 ? "paired over the replicate beds, one-sided, level 0.05"
                           : "z, one-sided, level 0.05",
            "22-25 mm on the 13 mm bed ~10 kPa vs ~8 kPa (Fig 5.6)");
  int comb[2 * VH_MAX_REPLICATES], use[VH_MAX_REPLICATES];
  for (int j = 0; j < k; j++) comb[2 * j] = iw[0][j], comb[2 * j + 1] = iw[1][j];
  int n = usable(h, comb, k, 2, NULL, 0, use);
  const dem_series_stats *sw[VH_MAX_REPLICATES], *sr[VH_MAX_REPLICATES];
  double mw = 0, mr = 0;
  char rn[64], pb[96] = "";
  reps_note(rn, sizeof rn, n, k);
  for (int j = 0; j < n; j++) {
    sw[j] = &h->runs[iw[1][use[j]]].sH, sr[j] = &h->runs[iw[0][use[j]]].sH;
    mw += sw[j]->mean / n, mr += sr[j]->mean / n;
    per_bed(pb, sizeof pb, j, k, 2, (sw[j]->mean - sr[j]->mean) / 1e3);
  }
  dem_comparison z;
  if (n > 0 && !paired_greater(h, sw, sr, n, &z)) {
    /* pb and rn fit in ours; the length is kept so that a truncation is visible to GCC's
     * -Wformat-truncation as intended, not an oversight. */
    int len = snprintf(c->ours, sizeof c->ours, "H(%g d) %.2f, H(%g d) %.2f kPa; %s = %.2f "
                                                "(crit %.2f), p = %.3g%s%s%s",
                       t->wall_indenter, mw / 1e3, t->bed_indenter, mr / 1e3, zt(&z), z.z,
                       z.z_crit, z.p, pb, k > 1 ? " kPa difference" : "", rn);
    (void)len;
    c->status = pass(z.different);
  }
  finish(h, r);
  return DEM_OK;
}

/* ---- 4. minimum penetration depth ------------------------------------------------------ */
/* The h/r at which the rise of the dynamic-bin hydrostatic stress over its value at the
 * surface (the bed keeps a residual stress from its consolidation), as a running mean of 5
 * samples, first reaches 90% of its plateau rise; NaN if it never does or does not rise.
 * *p0: the value at the surface. */
static double hr90_of(const vh_run *u, double *p0) {
  *p0 = NAN;
  for (size_t k = 0; k < u->n && !isfinite(*p0); k++)
    if (isfinite(u->bin_p[k])) *p0 = u->bin_p[k];
  if (!isfinite(*p0) || !(u->sp.mean > *p0)) return NAN;
  double rise = u->sp.mean - *p0;
  for (size_t k = 4; k < u->n; k++) {
    double s = 0;
    int m = 0;
    for (size_t j = k - 4; j <= k; j++)
      if (isfinite(u->bin_p[j])) s += u->bin_p[j], m++;
    if (m && s / m - *p0 >= 0.9 * rise) return u->hr[k - 2];
  }
  return NAN;
}

/* (mean H over h/r 0.1-0.2 - plateau mean) / plateau sd; NaN without samples there. *H01:
 * that mean. */
static double dev01_of(const vh_run *u, double *H01) {
  double s = 0;
  int m = 0;
  for (size_t k = 0; k < u->n; k++)
    if (u->hr[k] >= 0.1 && u->hr[k] <= 0.2) s += u->H[k], m++;
  *H01 = m ? s / m : NAN;
  return m ? (*H01 - u->sH.mean) / u->sH.sd : NAN;
}

static int c_depth(vh *h, vh_case_result *r, dem_err *err) {
  vh_indent in = vh_indent_ref(h);
  char lab[40];
  snprintf(lab, sizeof lab, "sphere %g d", in.D);
  int idx[VH_MAX_REPLICATES], use[VH_MAX_REPLICATES];
  int k = on_replicates(h, r, &in, 0, lab, idx, err);
  if (k < 0) return err->code;
  int n = usable(h, idx, k, 1, NULL, 0, use);
  char rn[64];
  reps_note(rn, sizeof rn, n, k);
  vh_check *c = check(r, "the rise of the dynamic-bin hydrostatic stress over its value at the "
                         "surface (running mean of 5 samples) first reaches 90% of its plateau "
                         "rise at h/r in [0.05, 0.2]",
                      "h/r at 90% of the plateau rise", "about 0.1 (Fig 5.19)");
  int have = n > 0;
  for (int j = 0; j < n; j++)
    if (!h->runs[idx[use[j]]].have_stress) have = 0;
  if (have) {
    double hr90 = 0, p0m = 0, pm = 0;
    char per[64] = "";
    for (int j = 0; j < n; j++) {
      const vh_run *u = &h->runs[idx[use[j]]];
      double p0, x = hr90_of(u, &p0);
      hr90 += x / n, p0m += p0 / n, pm += u->sp.mean / n;
      per_bed(per, sizeof per, j, k, 3, x);
    }
    if (isfinite(p0m) && pm > p0m)
      snprintf(c->ours, sizeof c->ours, "h/r = %.3f (bin p %.2f kPa at the surface, plateau "
                                        "%.2f kPa%s%s)",
               hr90, p0m / 1e3, pm / 1e3, per, rn);
    else
      snprintf(c->ours, sizeof c->ours, "no rise: bin p %.2f kPa at the surface, plateau %.2f "
                                        "kPa%s",
               p0m / 1e3, pm / 1e3, rn);
    c->status = pass(hr90 >= 0.05 && hr90 <= 0.2);
  }
  c = check(r, "H at h/r 0.1-0.2 is within 2 sd of the plateau (plastic flow initiated)",
            "(mean H(0.1-0.2) - plateau) / sd", "the plateau starts near h/r = 0.1-0.4 (5.2)");
  if (n > 0) {
    double dev = 0, H01 = 0, Hm = 0;
    char per[64] = "";
    for (int j = 0; j < n; j++) {
      const vh_run *u = &h->runs[idx[use[j]]];
      double hj, x = dev01_of(u, &hj);
      dev += x / n, H01 += hj / n, Hm += u->sH.mean / n;
      per_bed(per, sizeof per, j, k, 2, x);
    }
    if (isfinite(dev)) {
      snprintf(c->ours, sizeof c->ours, "%.2f (H(0.1-0.2) %.2f kPa, plateau %.2f kPa%s%s)", dev,
               H01 / 1e3, Hm / 1e3, per, rn);
      c->status = pass(fabs(dev) <= 2.0);
    }
  }
  finish(h, r);
  return DEM_OK;
}

/* ---- 5. indenter stiffness ------------------------------------------------------------- */
static int c_stiff(vh *h, vh_case_result *r, dem_err *err) {
  r->xlabel = "indenter stiffness kn [N/m] (Table 6.2 scale)";
  r->logx = 1;
  static const double ks[] = {0.01, 0.1, 1.0};
  int idx[3];
  char nm[3][24];
  const char *names[3];
  for (int k = 0; k < 3; k++) {
    vh_bed b = vh_bed_ref(h, 0);
    vh_indent in = vh_indent_ref(h);
    in.kn_scale = ks[k];
    snprintf(nm[k], sizeof nm[k], "kn x%g", ks[k]);
    if ((idx[k] = add_run_x(h, r, &b, &in, nm[k], 8e6 * ks[k], err)) < 0) return err->code;
    names[k] = nm[k];
  }
  vh_check *c = check(r, "H agrees over two decades of indenter stiffness (x0.01, x0.1, x1 of "
                         "Table 6.2's 8 MN/m)",
                      "z, two-sided, Bonferroni", "hardly any effect (Fig 6.1)");
  agree_all(h, c, idx, 3, names);
  finish(h, r);
  return DEM_OK;
}

/* ---- 6. indenter shape ----------------------------------------------------------------- */
static int c_shape(vh *h, vh_case_result *r, dem_err *err) {
  static const char *sn[] = {"sphere", "flat cylinder", "cube"};
  int idx[3][VH_MAX_REPLICATES], k = 0;
  for (int o = 0; o < 3; o++) {
    vh_indent in = vh_indent_ref(h);
    in.shape = (dem_indenter_shape)o;
    if ((k = on_replicates(h, r, &in, 0, sn[o], idx[o], err)) < 0) return err->code;
  }
  int comb[3 * VH_MAX_REPLICATES], use[VH_MAX_REPLICATES];
  for (int j = 0; j < k; j++)
    for (int o = 0; o < 3; o++) comb[3 * j + o] = idx[o][j];
  int n = usable(h, comb, k, 3, NULL, 0, use);
  char rn[64];
  reps_note(rn, sizeof rn, n, k);
  /* Per usable bed: the runs' H and solids-fraction statistics, by shape. */
  const dem_series_stats *H[3][VH_MAX_REPLICATES], *phi[3][VH_MAX_REPLICATES];
  double mH[3] = {0, 0, 0}, mphi[3] = {0, 0, 0};
  int have_phi = n > 0;
  for (int o = 0; o < 3; o++)
    for (int j = 0; j < n; j++) {
      const vh_run *u = &h->runs[idx[o][use[j]]];
      H[o][j] = &u->sH, phi[o][j] = &u->sphi;
      mH[o] += u->sH.mean / n, mphi[o] += u->sphi.mean / n;
      if (!isfinite(u->sphi.mean) || !(u->sphi.se > 0)) have_phi = 0;
    }
  const char *stat = k > 1 ? "paired over the replicate beds, one-sided, level 0.05"
                           : "z, one-sided, level 0.05";
  static const char *const whats[] = {NULL, "the flat cylinder reads higher than the sphere",
                                      "the cube reads higher than the sphere"};
  static const char *const short_n[] = {"sphere", "cylinder", "cube"};
  for (int o = 1; o < 3; o++) {
    vh_check *c = check(r, whats[o], stat, "markedly higher (Fig 6.2)");
    dem_comparison z;
    if (n > 0 && !paired_greater(h, H[o], H[0], n, &z)) {
      snprintf(c->ours, sizeof c->ours, "H(%s) %.2f, H(sphere) %.2f kPa; %s = %.2f (crit %.2f), "
                                        "p = %.3g%s",
               short_n[o], mH[o] / 1e3, mH[0] / 1e3, zt(&z), z.z, z.z_crit, z.p, rn);
      c->status = pass(z.different);
    }
  }
  vh_check *c = check(r, "the solids fraction of the dynamic bin is higher under the cylinder "
                         "and the cube than under the sphere",
                      k > 1 ? "paired over the replicate beds, one-sided, level 0.05 (each)"
                            : "z, one-sided, level 0.05 (each)",
                      "local densification (Fig 6.5)");
  dem_comparison z1, z2;
  if (have_phi && !paired_greater(h, phi[1], phi[0], n, &z1) &&
      !paired_greater(h, phi[2], phi[0], n, &z2)) {
    snprintf(c->ours, sizeof c->ours, "phi sphere %.4f, cylinder %.4f (%s %.2f, crit %.2f), "
                                      "cube %.4f (%s %.2f, crit %.2f)%s",
             mphi[0], mphi[1], zt(&z1), z1.z, z1.z_crit, mphi[2], zt(&z2), z2.z, z2.z_crit, rn);
    c->status = pass(z1.different && z2.different);
  }
  finish(h, r);
  return DEM_OK;
}

/* ---- 7. indenter friction -------------------------------------------------------------- */
static int c_ifric(vh *h, vh_case_result *r, dem_err *err) {
  r->xlabel = "indenter sliding friction mu";
  r->logx = 0;
  static const double mus[] = {0.0, 0.1, 0.3, 0.5};
  int idx[4];
  for (int k = 0; k < 4; k++) {
    vh_bed b = vh_bed_ref(h, 0);
    vh_indent in = vh_indent_ref(h);
    in.mu_ind = mus[k];
    char lab[40];
    snprintf(lab, sizeof lab, "indenter mu %g", mus[k]);
    if ((idx[k] = add_run_x(h, r, &b, &in, lab, mus[k], err)) < 0) return err->code;
  }
  vh_check *c = check(r, "H with indenter friction (mean over mu 0.1, 0.3, 0.5) exceeds H "
                         "without",
                      "z, one-sided, level 0.05", "a general, slight increase, notable from "
                                                  "0 to 0.1 (Fig 6.6)");
  int have = 1;
  for (int k = 0; k < 4; k++)
    if (!ok(h, idx[k])) have = 0;
  double rise = NAN;
  if (have) {
    dem_series_stats pool = h->runs[idx[1]].sH;
    double m = 0, v = 0;
    for (int k = 1; k < 4; k++) {
      m += h->runs[idx[k]].sH.mean / 3.0;
      v += h->runs[idx[k]].sH.se * h->runs[idx[k]].sH.se / 9.0;
    }
    pool.mean = m;
    pool.se = sqrt(v);
    dem_comparison z;
    vh_greater(h, &pool, &h->runs[idx[0]].sH, &z);
    rise = (m - h->runs[idx[0]].sH.mean) / h->runs[idx[0]].sH.mean;
    snprintf(c->ours, sizeof c->ours,
             "H [kPa]: mu 0 %.2f, 0.1 %.2f, 0.3 %.2f, 0.5 %.2f; z = %.2f (crit %.2f)",
             h->runs[idx[0]].sH.mean / 1e3, h->runs[idx[1]].sH.mean / 1e3,
             h->runs[idx[2]].sH.mean / 1e3, h->runs[idx[3]].sH.mean / 1e3, z.z, z.z_crit);
    c->status = pass(z.different);
  }
  c = check(r, "the rise is slight: below 30% of H without friction", "relative rise",
            "slight (6.4)");
  if (have) {
    snprintf(c->ours, sizeof c->ours, "%.3f", rise);
    c->status = pass(rise < 0.3);
  }
  finish(h, r);
  return DEM_OK;
}

/* ---- 8. inter-particle friction -------------------------------------------------------- */
static int c_pfric(vh *h, vh_case_result *r, dem_err *err) {
  r->xlabel = "inter-particle sliding friction mu";
  r->logx = 0;
  static const double mus[] = {0.05, 0.15, 0.3, 0.5};
  int idx[4];
  for (int k = 0; k < 4; k++) {
    vh_bed b = vh_bed_ref(h, 0);
    b.mu = mus[k];
    vh_indent in = vh_indent_ref(h);
    char lab[40];
    snprintf(lab, sizeof lab, "particle mu %g", mus[k]);
    if ((idx[k] = add_run_x(h, r, &b, &in, lab, mus[k], err)) < 0) return err->code;
  }
  s_bed_cur = bed_spread(h, r, h->tier->bed, h->tier->indenter, err);
  vh_check *c = check(r, "H rises with inter-particle friction: H(0.3) > H(0.05)",
                      "z, one-sided, level 0.05", "rising (Fig 6.7)");
  greater(h, c, idx[2], idx[0], "mu 0.3", "mu 0.05");
  c = check(r, "H saturates: H(0.5) and H(0.3) agree", "z, two-sided, level 0.05",
            "0.3 and 0.5 alike (Fig 6.7)");
  const char *nm[] = {"mu 0.3", "mu 0.5"};
  agree_all(h, c, idx + 2, 2, nm);
  s_bed_cur = 0.0;
  finish(h, r);
  return DEM_OK;
}

/* ---- 9. surface energy ----------------------------------------------------------------- */
static int c_gamma(vh *h, vh_case_result *r, dem_err *err) {
  r->xlabel = "interface energy Gamma [J/m^2]";
  r->logx = 0;
  static const double gs[] = {0.5, 2.0, 5.0};
  int idx[3];
  for (int k = 0; k < 3; k++) {
    vh_bed b = vh_bed_ref(h, 0);
    b.gamma = gs[k];
    vh_indent in = vh_indent_ref(h);
    char lab[40];
    snprintf(lab, sizeof lab, "Gamma %g J/m^2", gs[k]);
    if ((idx[k] = add_run_x(h, r, &b, &in, lab, gs[k], err)) < 0) return err->code;
  }
  s_bed_cur = bed_spread(h, r, h->tier->bed, h->tier->indenter, err);
  vh_check *c = check(r, "H rises with the interface energy: H(5) > H(2) > H(0.5) J/m^2",
                      "z, one-sided, level 0.05 (each step)", "rising (Fig 6.8)");
  if (ok(h, idx[0]) && ok(h, idx[1]) && ok(h, idx[2])) {
    dem_comparison z1, z2;
    dem_series_stats w0 = widened(&h->runs[idx[0]].sH), w1 = widened(&h->runs[idx[1]].sH),
                     w2 = widened(&h->runs[idx[2]].sH);
    vh_greater(h, &w1, &w0, &z1);
    vh_greater(h, &w2, &w1, &z2);
    s_bed_cur = 0.0;
    snprintf(c->ours, sizeof c->ours, "H [kPa]: %.2f, %.2f, %.2f; z = %.2f, %.2f (crit %.2f)",
             h->runs[idx[0]].sH.mean / 1e3, h->runs[idx[1]].sH.mean / 1e3,
             h->runs[idx[2]].sH.mean / 1e3, z1.z, z2.z, z1.z_crit);
    c->status = pass(z1.different && z2.different);
  }
  finish(h, r);
  return DEM_OK;
}

/* ---- 10. strain rate ------------------------------------------------------------------- */
static const double rates[] = {0.03, 0.1, 0.23, 0.46, 1.0, 2.3};
#define VH_NRATES 6
/* Case 10's reading of the rise, not a criterion (the thesis states none): H = H0 + beta
 * rho_b v^2 over the rates that ran, on every replicate bed together (dem_rate_fit_dynamic,
 * docs/analysis.md "Rate dependence"; rho_b and gamma* per m/s are the beds' means; the
 * scatter between beds enters through the fit's scale factor sqrt(chi2/dof)): the
 * quasi-static hardness, the dynamic-pressure coefficient and the speed and gamma* at which
 * the dynamic part reaches VH_RATE_ONSET_FRACTION of H0. Needs 3 runs (one degree of freedom
 * left to judge the fit). */
static void rate_fit(const vh *h, vh_case_result *r, const int *idx, int n) {
  double v[VH_NRATES * VH_MAX_REPLICATES], H[VH_NRATES * VH_MAX_REPLICATES],
      se[VH_NRATES * VH_MAX_REPLICATES];
  int m = 0, nb = 0, seen[VH_MAX_REPLICATES];
  double rho_b = 0.0, g_per_v = 0.0;
  for (int k = 0; k < n && m < VH_NRATES * VH_MAX_REPLICATES; k++) {
    if (!ok(h, idx[k])) continue;
    const vh_run *u = &h->runs[idx[k]];
    if (!(isfinite(u->v) && u->sH.se > 0.0)) continue;
    int known = 0;
    for (int j = 0; j < nb; j++) known |= seen[j] == u->bed;
    if (!known && nb < VH_MAX_REPLICATES) {
      const vh_bed *b = &h->beds[u->bed];
      seen[nb++] = u->bed;
      rho_b += b->rho * b->phi;
      /* gamma* is proportional to v on one bed */
      g_per_v += dem_gamma_star(dem_indent_strain_rate(1.0, b->bed_top), D_MEAN, G_ACC);
    }
    v[m] = u->v, H[m] = u->sH.mean, se[m] = u->sH.se, m++;
  }
  if (m < 3) return;
  r->rho_b = rho_b / nb;
  r->rate_fit_beds = nb;
  g_per_v /= nb;
  dem_err e = {0};
  if (dem_rate_fit_dynamic((size_t)m, v, H, se, r->rho_b, &r->rate_fit, &e)) {
    vh_log(h, "warning: case %s: the rate fit: %s", r->name, e.msg);
    return;
  }
  r->has_rate_fit = 1;
  r->onset_v =
      dem_rate_onset_speed(&r->rate_fit, r->rho_b, VH_RATE_ONSET_FRACTION, &r->onset_v_se);
  r->onset_gamma_star = g_per_v * r->onset_v;
  r->onset_gamma_star_se = g_per_v * r->onset_v_se;
}

/* The rate sweep on every replicate of the rate bed (seeds 1..k; the flatness the thesis
 * reports is judged over the beds, since the slowest rate's reading varied from nothing to
 * +40 % between four x0.3 beds: docs/validation.md, "The slowest rate of case 10 on more
 * beds"); idx[j * VH_NRATES + o] is rate o on bed j. */
static int c_rate(vh *h, vh_case_result *r, dem_err *err) {
  r->xlabel = "gamma* = gamma_dot (d/g)^0.5";
  r->logx = 1;
  const int k = nreplicates(h);
  int idx[VH_NRATES * VH_MAX_REPLICATES], use[VH_MAX_REPLICATES];
  for (int j = 0; j < k; j++)
    for (int o = 0; o < VH_NRATES; o++) {
      vh_bed b = vh_bed_rate(h);
      b.seed = vh_bed_ref(h, j).seed; /* replicate j of the rate bed */
      vh_indent in = vh_indent_ref(h);
      in.gamma_star = rates[o];
      char lab[40];
      if (j == 0) snprintf(lab, sizeof lab, "gamma* %g", rates[o]);
      else snprintf(lab, sizeof lab, "gamma* %g, seed %lu", rates[o], b.seed);
      /* the trend figure shows the first bed (as cases 1, 4 and 6 do) */
      int i = add_run_x(h, r, &b, &in, lab, j ? NAN : rates[o], err);
      if ((idx[j * VH_NRATES + o] = i) < 0) return err->code;
    }
  const char *nm[] = {"0.03", "0.1", "0.23", "0.46"};
  static const int flat[] = {0, 1, 2, 3}, sdc[] = {1, 3, 4}, rise[] = {5, 1};
  char rn[64];
  vh_check *c = check(r, "H is independent of gamma* up to 0.46: the four rates agree pairwise",
                      k > 1 ? "paired over the replicate beds, two-sided, Bonferroni"
                            : "z, two-sided, Bonferroni",
                      "constant up to gamma* ~ 1 (Figs 7.3, 7.4)");
  int n = usable(h, idx, k, VH_NRATES, flat, 4, use);
  agree_paired(h, c, idx, VH_NRATES, use, n, k, 4, nm);
  c = check(r, "the fluctuation grows from about 0.5: sd(H) at gamma* 0.46 and 1 exceeds sd(H) "
               "at 0.1",
            k > 1 ? "ratio of the sd(H) means over the replicate beds" : "sd ratio",
            "fluctuations increase from gamma* = 0.5 (7.4)");
  if ((n = usable(h, idx, k, VH_NRATES, sdc, 3, use)) > 0) {
    double s1 = 0, s3 = 0, s4 = 0;
    char pb[80] = "";
    for (int j = 0; j < n; j++) {
      const int *q = &idx[use[j] * VH_NRATES];
      s1 += h->runs[q[1]].sH.sd / n, s3 += h->runs[q[3]].sH.sd / n, s4 += h->runs[q[4]].sH.sd / n;
      size_t m = strlen(pb);
      const double sd1 = h->runs[q[1]].sH.sd;
      snprintf(pb + m, sizeof pb - m, "%s%.2f/%.2f", j ? " " : "; per bed (0.46/1.0) ",
               h->runs[q[3]].sH.sd / sd1, h->runs[q[4]].sH.sd / sd1);
    }
    if (k == 1) pb[0] = 0;
    reps_note(rn, sizeof rn, n, k);
    snprintf(c->ours, sizeof c->ours, "sd ratios %.2f (0.46), %.2f (1.0)%s%s", s3 / s1, s4 / s1,
             pb, rn);
    c->status = pass(s3 > s1 && s4 > s1);
  }
  /* A rise by a factor 3-10 (docs/validation.md) is judged on every bed by itself, not by the
   * paired test: the rise scales with each bed's hardness, so the beds' differences vary
   * beyond their errors and the paired test falls back to Student's t on k - 1 dof (6.31
   * for two beds), which a rise of 3x on one bed and 10x on the other can fail. "Rises on
   * every bed", each by the one-sided z-test at the level, is an intersection-union test:
   * its level is the level of each test, with no correction. */
  c = check(r, "H rises above gamma* = 1: H(2.3) > H(0.1)",
            k > 1 ? "z, one-sided, level 0.05, on every replicate bed"
                  : "z, one-sided, level 0.05",
            "stresses rise above gamma* ~ 1, hardness most (7.2)");
  if ((n = usable(h, idx, k, VH_NRATES, rise, 2, use)) > 0) {
    double ma = 0, mb = 0, zmin = INFINITY, crit = NAN, pmax = 0;
    int all = 1;
    char pb[80] = "";
    for (int j = 0; j < n; j++) {
      const dem_series_stats *sa = &h->runs[idx[use[j] * VH_NRATES + 5]].sH,
                             *sb = &h->runs[idx[use[j] * VH_NRATES + 1]].sH;
      dem_comparison z;
      if (vh_greater(h, sa, sb, &z)) {
        all = -1;
        break;
      }
      ma += sa->mean / n, mb += sb->mean / n;
      if (z.z < zmin) zmin = z.z, crit = z.z_crit, pmax = z.p;
      if (!z.different) all = 0;
      per_bed(pb, sizeof pb, j, k, 2, z.z);
    }
    if (all >= 0) {
      reps_note(rn, sizeof rn, n, k);
      snprintf(c->ours, sizeof c->ours, "H(2.3) %.2f, H(0.1) %.2f kPa; z = %.2f (crit %.2f), "
                                        "p = %.3g%s%.50s%.40s",
               ma / 1e3, mb / 1e3, zmin, crit, pmax, k > 1 ? " (the least of the beds)" : "",
               pb, rn);
      c->status = pass(all);
    }
  }
  rate_fit(h, r, idx, VH_NRATES * k);
  finish(h, r);
  return DEM_OK;
}

/* ---- 11. time step --------------------------------------------------------------------- */
static int c_dt(vh *h, vh_case_result *r, dem_err *err) {
  r->xlabel = "time-step factor zeta";
  r->logx = 1;
  static const double zs[] = {0.01, 0.1, 1.0};
  int idx[3];
  char nm[3][24];
  const char *names[3];
  for (int k = 0; k < 3; k++) {
    vh_bed b = vh_bed_rate(h);
    vh_indent in = vh_indent_ref(h);
    in.gamma_star = 2.3;
    in.dt_scale = zs[k];
    snprintf(nm[k], sizeof nm[k], "zeta %g", zs[k]);
    if ((idx[k] = add_run_x(h, r, &b, &in, nm[k], zs[k], err)) < 0) return err->code;
    names[k] = nm[k];
  }
  vh_check *c = check(r, "at gamma* = 2.3, H agrees for time-step factors 0.01, 0.1 and 1 "
                         "(times the tier's step)",
                      "z, two-sided, Bonferroni", "no effect beyond the fluctuation (Fig 7.5)");
  agree_all(h, c, idx, 3, names);
  finish(h, r);
  return DEM_OK;
}

const vh_case vh_cases[] = {
    {"plateau", "Hardness plateau and the dynamic-bin stress", "thesis 5.2, Figs 5.3-5.6, 5.19",
     c_plateau},
    {"bed-height", "Bed height (thesis 13-50 d)", "thesis 5.2, Figs 5.12-5.14", c_bed},
    {"indenter-size", "Indenter size (thesis 7-22 d)", "thesis 5.2, Figs 5.6, 5.15-5.17", c_size},
    {"penetration-depth", "Minimum penetration depth", "thesis 5.2, Fig 5.19", c_depth},
    {"indenter-stiffness", "Indenter stiffness", "thesis 6.2.1, Fig 6.1", c_stiff},
    {"indenter-shape", "Indenter shape: sphere, flat cylinder, cube",
     "thesis 6.2.2, Figs 6.2-6.5", c_shape},
    {"indenter-friction", "Indenter friction", "thesis 6.2.3, Fig 6.6", c_ifric},
    {"particle-friction", "Inter-particle friction", "thesis 6.3.1, Fig 6.7", c_pfric},
    {"surface-energy", "Inter-particle interface energy", "thesis 6.3.2, Fig 6.8", c_gamma},
    {"strain-rate", "Strain rate gamma* 0.03-2.3", "thesis 7.2, Figs 7.1-7.4", c_rate},
    {"time-step", "Time-step factor at gamma* = 2.3", "thesis 7.3, Fig 7.5", c_dt},
};
const int vh_ncases = (int)(sizeof vh_cases / sizeof vh_cases[0]);
