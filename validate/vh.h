/* vh.h — the validation harness (dem-validate): the thesis' operating-window conclusions
 * as cases with criteria fixed before the run, their distribution and the report.
 * Private to validate/. See docs/validation.md. The beds and runs are in vh_run.h.
 *
 *   case    one thesis conclusion: a set of runs, statistics and a PASS/FAIL criterion.
 */
#ifndef VH_H
#define VH_H

#include "vh_run.h"

#define VH_MAX_CHECKS 8
#define VH_MAX_CASE_RUNS 24 /* case 10: six rates on four replicate beds */
/* Cases 1-4 (bits 0-3) reproduce chapter 5, whose runs used its own materials (hertz-jkr) */
#define VH_CHAPTER5_CASES 0xf
/* Case 10's reading of the rate rise (not a criterion): the rate at which the dynamic part
 * beta rho_b v^2 reaches this fraction of H0 (dem_rate_onset_speed; docs/analysis.md). */
#define VH_RATE_ONSET_FRACTION 0.1

typedef enum { VH_PASS = 0, VH_FAIL = 1, VH_ERROR = 2, VH_NA = 3 } vh_status;
const char *vh_status_name(vh_status s);

/* One sub-criterion of a case. */
typedef struct vh_check {
  char what[200];      /* the criterion in words, fixed before the run */
  char statistic[120]; /* the statistic, e.g. "z (one-sided, 0.05)" */
  char ours[200];      /* our value(s) */
  char thesis[160];    /* the thesis' value or statement */
  vh_status status;
} vh_check;

typedef struct vh_case_result {
  const char *name;
  const char *title;
  const char *source;    /* thesis sections / figures */
  vh_status status;      /* FAIL if any check fails, ERROR if a run failed, NA if none */
  int nchecks;
  vh_check checks[VH_MAX_CHECKS];
  int nruns;
  int runs[VH_MAX_CASE_RUNS]; /* indices into the harness' runs */
  double wall_s;         /* wall time spent on this case's new beds and runs */
  double cost_s;         /* wall time its beds and runs took when they were made (the
                            ones no earlier case used), cached or not */
  char labels[VH_MAX_CASE_RUNS][40]; /* per run, for the figures */
  double x[VH_MAX_CASE_RUNS];         /* the varied parameter (NAN: none) */
  const char *xlabel;    /* its name and unit, for the trend figure (NULL: no trend) */
  int logx;
  char plots[5][96];     /* PNG files written for this case ("" if none) */
  char note[400];
  /* case 10 only, not a criterion: H = H0 + beta rho_b v^2 over its rates
   * on every replicate bed together (dem_rate_fit_dynamic); has_rate_fit 0 if fewer than
   * 3 runs succeeded */
  int has_rate_fit;
  dem_rate_fit rate_fit;
  int rate_fit_beds;     /* replicate beds whose runs entered the fit */
  double rho_b;          /* kg/m^3, particle density x the solids fraction (beds' mean) */
  double onset_v, onset_v_se; /* m/s, where beta rho_b v^2 = 0.1 H0 (dem_rate_onset_speed) */
  double onset_gamma_star, onset_gamma_star_se; /* the same as gamma* (the beds' mean
                                                    gamma* per m/s) */
} vh_case_result;

typedef struct vh_case {
  const char *name;
  const char *title;
  const char *source;
  int (*run)(vh *h, vh_case_result *r, dem_err *err);
} vh_case;

extern const vh_case vh_cases[];
extern const int vh_ncases;

/* Distribution (dist.c): list every bed and run of the selected cases (h->plan), then
 * prepare the beds and make the runs on the MPI ranks (longest first), each into beds_dir;
 * afterwards rank 0 evaluates the cases from the cache. With h->budget > 0 every rank makes
 * its items cheapest first and skips those whose estimate would end past the budget.
 * Returns DEM_OK or an error. */
typedef int (*vh_cases_fn)(vh *h, void *user);
int vh_distribute(vh *h, vh_cases_fn run_cases, void *user, int print_plan, dem_err *err);

/* Tests on plateau means (independent runs: z-test on the combined standard error). */
int vh_greater(const vh *h, const dem_series_stats *a, const dem_series_stats *b,
               dem_comparison *c);
int vh_agree(const vh *h, const dem_series_stats *a, const dem_series_stats *b,
             dem_comparison *c);

/* Report: the case table, figures, report.md, report.html and summary.json in h->out. */
int vh_plot_runs(const vh *h, const char *png, const char *title, const int *runs, int nruns,
                 const char *const *labels, int column, dem_err *err);
int vh_plot_trend(const vh *h, const char *png, const char *title, const char *xlabel,
                  const double *x, const int *runs, int nruns, int logx, dem_err *err);
int vh_report_write(const vh *h, const vh_case_result *res, int nres, double wall_s,
                    dem_err *err);
int vh_json_print(const vh *h, const vh_case_result *res, int nres, double wall_s, FILE *f);

#endif
