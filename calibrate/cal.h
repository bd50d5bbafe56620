/* calibrate/cal.h — the calibration program's internal interface (not part of libdem).
 *
 * A calibration fits the free coefficients of one contact law to reference targets:
 *   curve        force-overlap curves (alpha in m, f in N), driven quasi-statically along the
 *                reference's own overlap path through dem_contact_path; compared point by
 *                point, on a common overlap grid per branch, or by summary points
 *                (f_max, alpha_p, pull-off force);
 *   sticking     critical sticking velocities v_stick (m/s) versus particle radius R (m),
 *                dem_impact_sticking per radius;
 *   restitution  e(v) curves: dem_impact_run per impact velocity v (m/s).
 *
 * Residuals: r_i = sqrt(w_t) (model_i - ref_i) / norm_i with norm_i = |ref_i| for sticking and
 * restitution (relative errors) and norm = max |f_ref| of the curve for force curves (the
 * force passes through zero, so a point-wise relative error would explode). The objective is
 * S = sum r_i^2. The reported `relative_error` of a point is (model - ref) / norm (unweighted).
 *
 * The optimiser works in scaled coordinates u: u = log10(x) for scale "log", u = x for
 * "linear"; bounds are clamped in u.
 */
#ifndef CAL_H
#define CAL_H

#include <signal.h>
#include <stdio.h>

#include "dem/contact.h"
#include "dem/error.h"
#include "dem/impact.h"
#include "dem/params.h"

#define CAL_NAME_LEN 64
#define CAL_PATH_LEN 1024
#define CAL_MAX_FREE 16
#define CAL_MAX_TARGETS 32

/* ---- config (config.c) ------------------------------------------------------------------ */

typedef enum { CAL_SCALE_LINEAR = 0, CAL_SCALE_LOG = 1 } cal_scale;
typedef enum { CAL_T_CURVE = 0, CAL_T_STICKING = 1, CAL_T_RESTITUTION = 2 } cal_ttype;
typedef enum { CAL_CURVE_POINTS = 0, CAL_CURVE_GRID = 1, CAL_CURVE_SUMMARY = 2 } cal_cmode;

typedef struct cal_free {
  char name[DEM_KEY_LEN];
  double lo, hi;   /* bounds, physical units */
  double start;    /* physical; NAN = centre of the scaled box */
  cal_scale scale;
  int line;        /* config line, for messages */
} cal_free;

typedef struct cal_target {
  char name[CAL_NAME_LEN];
  cal_ttype type;
  double weight;
  int line;
  char file[CAL_PATH_LEN]; /* resolved path, "" if the data are inline */
  int n;                   /* reference points as read */
  double *x, *y;           /* curve: alpha, f; sticking: R, v_stick; restitution: v, e */
  cal_cmode mode;          /* curves only */
  int grid;                /* points per branch for CAL_CURVE_GRID */
  dem_params over;         /* per-target parameter overrides (e.g. R for a curve) */
  int pair;                /* impact/curve geometry: 0 wall, 1 equal sphere */
  double v_lo, v_hi, tol;  /* sticking search bracket (m/s) and relative tolerance */
  /* derived by cal_targets_prepare: the points actually compared */
  int nres;
  double *xr, *yr;         /* abscissa and reference value of each compared point */
  int *branch;             /* curves: branch index of each compared point (-1 summary) */
  double norm;             /* curves: max |f_ref| */
  int off;                 /* offset of this target's residuals in the full vector */
} cal_target;

typedef struct cal_opt_settings {
  char global[32];  /* NLopt name, "" = none (multistart or local only) */
  char local[32];   /* NLopt name or "auto" (BOBYQA; SBPLX if a sticking target exists) */
  int maxeval_global, maxeval_local;
  int multistart;   /* > 0: that many local starts instead of the global stage */
  double xtol_rel, ftol_rel;
  double fd_step;   /* Jacobian step as a fraction of the scaled range */
  double penalty;   /* objective of a failed evaluation */
  int line_global, line_local; /* config lines of the algorithm names */
} cal_opt_settings;

typedef struct cal_config {
  char path[CAL_PATH_LEN]; /* the config file */
  char dir[CAL_PATH_LEN];  /* its folder: relative target paths resolve against it */
  char name[CAL_NAME_LEN];
  const dem_law *law;
  unsigned long seed;
  int nfree;
  cal_free fr[CAL_MAX_FREE];
  dem_params fixed;        /* fixed law coefficients and scene keys */
  int ntargets;
  cal_target t[CAL_MAX_TARGETS];
  cal_opt_settings opt;
  dem_impact_opts impact;  /* options of impact targets */
  int path_steps;          /* steps of the overlap path per unit branch (curves) */
  unsigned long long hash; /* of the config text, keys the evaluation cache */
} cal_config;

/* Read and validate a config; every error names "file:line: field". */
int cal_config_load(cal_config *c, const char *path, dem_err *err);
void cal_config_free(cal_config *c);
/* Parse a config given as text (tests); `path` is used for messages and relative paths. */
int cal_config_load_string(cal_config *c, const char *text, const char *path, dem_err *err);

/* ---- parameter transforms (transform.c) ------------------------------------------------- */

double cal_to_scaled(const cal_free *f, double x);
double cal_from_scaled(const cal_free *f, double u);
void cal_scaled_bounds(const cal_free *f, double *ulo, double *uhi);
/* u (scaled, clamped to the box) -> physical values; fills ps = fixed + free. */
int cal_params_from_scaled(const cal_config *c, const double *u, double *x, dem_params *ps,
                           dem_err *err);

/* ---- targets and the model (targets.c, model.c) ----------------------------------------- */

/* Derive the compared points of every target and their offsets; returns the total count. */
int cal_targets_prepare(cal_config *c, int *nres, dem_err *err);
/* Evaluate the model at physical parameters ps: model[nres] values at the compared points.
 * Targets and their points run in parallel (OpenMP); the result does not depend on the
 * number of threads. */
int cal_model_eval(const cal_config *c, const dem_params *ps, double *model, dem_err *err);
/* Model force-overlap rows along the path of a curve target (for plots): arrays of *n rows
 * (malloc'd, caller frees). */
int cal_model_curve(const cal_config *c, const cal_target *t, const dem_params *ps,
                    double **alpha, double **f, int *n, dem_err *err);

/* ---- objective (objective.c) ------------------------------------------------------------ */

typedef struct cal_problem cal_problem;
typedef void (*cal_progress_fn)(const cal_problem *p, void *user);

struct cal_problem {
  cal_config *cfg;
  int nres;
  double *model, *resid;   /* scratch of the last evaluation */
  struct cal_cache *cache; /* may be NULL */
  FILE *trace;             /* objective trace rows, may be NULL */
  FILE *failures;          /* failed evaluations, may be NULL */
  int stage;               /* 0 global, 1 local, 2 statistics */
  long nevals, ncached, nfailed;
  double best_f;
  double best_u[CAL_MAX_FREE];
  int maxeval_total;
  double t0;               /* wall clock at start, s */
  volatile sig_atomic_t *stop; /* set by a signal handler */
  long stop_after;         /* > 0: behave as if interrupted after this many evaluations */
  cal_progress_fn progress;
  void *progress_user;
  double *tr;              /* in-memory trace: rows of (stage, S, best S, x_0..x_{p-1}) */
  long tr_n, tr_cap;
};

/* Residual vector at physical params (no cache). Returns DEM_OK or the failure. */
int cal_residuals(cal_problem *p, const double *u, double *resid, double *model, dem_err *err);
/* The objective at scaled u: cached, traced, penalised on failure; never NaN. */
double cal_objective(cal_problem *p, const double *u);
void cal_residual_norms(const cal_config *c, double *norm_of_point);

/* ---- evaluation cache (cache.c) --------------------------------------------------------- */

typedef struct cal_cache cal_cache;
/* Open the cache file; resume = 0 starts afresh, 1 loads the existing entries (a truncated
 * last line is dropped). A cache written by a different config is an error. */
cal_cache *cal_cache_open(const char *path, unsigned long long hash, int dim, int resume,
                          dem_err *err);
int cal_cache_lookup(const cal_cache *cc, const double *u, double *f);
int cal_cache_store(cal_cache *cc, const double *u, double f);
long cal_cache_size(const cal_cache *cc);
void cal_cache_close(cal_cache *cc);

/* ---- optimiser (optimise.c) ------------------------------------------------------------- */

typedef struct cal_result {
  double u[CAL_MAX_FREE], x[CAL_MAX_FREE];
  double f;
  int nlopt_global, nlopt_local; /* nlopt_result codes */
  int interrupted;
  long nevals, ncached, nfailed; /* evaluations asked for, answered by the cache, failed */
  double mean_relative_error;
} cal_result;

int cal_optimise(cal_problem *p, cal_result *res, dem_err *err);

/* ---- statistics (stats.c) --------------------------------------------------------------- */

typedef struct cal_stats {
  int ok;                        /* 0: Jacobian unavailable */
  int n, p;                      /* residuals, parameters */
  double s2;                     /* residual variance S / (n - p) */
  double se_u[CAL_MAX_FREE];     /* standard errors in scaled coordinates */
  double se_x[CAL_MAX_FREE];     /* in physical units (delta method) */
  double lo95[CAL_MAX_FREE], hi95[CAL_MAX_FREE]; /* 95% interval, physical */
  double corr[CAL_MAX_FREE * CAL_MAX_FREE];
  double cov_u[CAL_MAX_FREE * CAL_MAX_FREE];
  double sv[CAL_MAX_FREE];       /* singular values of J */
  double cond;
  char warning[1024];            /* "" if every parameter is identifiable */
} cal_stats;

int cal_statistics(cal_problem *p, const double *u, cal_stats *st, dem_err *err);

/* ---- output (output.c, plots.c, json.c) ------------------------------------------------- */

int cal_mkdirs(const char *dir, dem_err *err);
/* Open dir/name.tmp for writing; cal_commit renames it to dir/name. */
FILE *cal_tmp_open(const char *dir, const char *name, char *tmp, size_t n, dem_err *err);
int cal_commit(FILE *f, const char *tmp, dem_err *err);
int cal_write_outputs(cal_problem *p, const cal_result *r, const cal_stats *st,
                      const char *outdir, double wall_s, dem_err *err);
int cal_write_plots(cal_problem *p, const cal_result *r, const char *outdir, dem_err *err);
/* The --json object on `out`. */
int cal_write_json(cal_problem *p, const cal_result *r, const cal_stats *st, FILE *out,
                   dem_err *err);
double cal_mean_relative_error(const cal_problem *p);

/* ---- progress (progress.c) -------------------------------------------------------------- */

void cal_progress_stderr(const cal_problem *p, void *user);
void cal_progress_end(void);
double cal_now(void);

/* ---- a whole run (run.c) ---------------------------------------------------------------- */

typedef struct cal_run_opts {
  const char *outdir; /* NULL: out/calibrate/<name> */
  int resume;
  int json;
  int quiet;          /* no progress line */
  int plots;          /* 1: write PNG plots (needs gnuplot) */
  long stop_after;    /* testing: stop as if interrupted after this many evaluations */
} cal_run_opts;

/* Run a loaded calibration end to end; fills res and st. Returns DEM_EINTERRUPTED if a
 * signal stopped it (the cache keeps every evaluation made). */
int cal_run(cal_config *c, const cal_run_opts *o, cal_result *res, cal_stats *st,
            dem_err *err);
/* Install SIGINT/SIGTERM handlers that ask a running calibration to stop. */
void cal_install_signal_handlers(void);

#endif
