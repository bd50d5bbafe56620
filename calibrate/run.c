/* A calibration end to end: prepare the targets, open the evaluation cache and the trace,
 * optimise, evaluate the statistics at the optimum, write the output folder and the plots.
 * SIGINT/SIGTERM ask the optimiser to stop after the evaluation in progress; every
 * evaluation made so far is already in the cache, so `--resume` continues from there. */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cal.h"
#include "dem/table.h"

static volatile sig_atomic_t stop_requested = 0;

static void on_signal(int sig) {
  (void)sig;
  stop_requested = 1;
}

void cal_install_signal_handlers(void) {
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
}

int cal_run(cal_config *c, const cal_run_opts *o, cal_result *res, cal_stats *st,
            dem_err *err) {
  char outdir[CAL_PATH_LEN], path[CAL_PATH_LEN + 32], trace_tmp[CAL_PATH_LEN];
  if (o->outdir)
    snprintf(outdir, sizeof outdir, "%s", o->outdir);
  else
    snprintf(outdir, sizeof outdir, "out/calibrate/%s", c->name);
  int rc = dem_mkdirs(outdir, err);
  if (rc) return rc;
  cal_problem p;
  memset(&p, 0, sizeof p);
  memset(res, 0, sizeof *res);
  memset(st, 0, sizeof *st);
  p.cfg = c;
  if ((rc = cal_targets_prepare(c, &p.nres, err))) return rc;
  p.model = calloc((size_t)p.nres, sizeof(double));
  p.resid = calloc((size_t)p.nres, sizeof(double));
  if (!p.model || !p.resid) {
    rc = dem_err_set(err, DEM_ENOMEM, "out of memory");
    goto done;
  }
  snprintf(path, sizeof path, "%s/eval_cache.txt", outdir);
  p.cache = cal_cache_open(path, c->hash, c->nfree, o->resume, err);
  if (!p.cache) {
    rc = err ? err->code : DEM_EIO;
    goto done;
  }
  p.trace = cal_tmp_open(outdir, "trace.csv", trace_tmp, sizeof trace_tmp, err);
  if (!p.trace) {
    rc = err ? err->code : DEM_EIO;
    goto done;
  }
  fprintf(p.trace, "eval,stage,cached,objective,best");
  for (int i = 0; i < c->nfree; i++) fprintf(p.trace, ",%s", c->fr[i].name);
  fputc('\n', p.trace);
  snprintf(path, sizeof path, "%s/failures.log", outdir);
  p.failures = fopen(path, "w");
  stop_requested = 0;
  p.stop = &stop_requested;
  p.stop_after = o->stop_after;
  p.maxeval_total = c->opt.multistart ? c->opt.multistart * c->opt.maxeval_local
                                      : c->opt.maxeval_global + c->opt.maxeval_local;
  p.t0 = cal_now();
  p.best_f = INFINITY;
  if (!o->quiet) p.progress = cal_progress_stderr;

  rc = cal_optimise(&p, res, err);
  if (!o->quiet) cal_progress_end();
  if (rc) goto done;
  if ((rc = cal_statistics(&p, res->u, st, err))) goto done;
  dem_err e = {0};
  if (cal_residuals(&p, res->u, p.resid, p.model, &e)) {
    rc = dem_err_set(err, e.code, "the model fails at the optimum: %s", e.msg);
    goto done;
  }
  double wall = cal_now() - p.t0;
  rc = cal_commit(p.trace, trace_tmp, err);
  p.trace = NULL;
  if (rc) goto done;
  if ((rc = cal_write_outputs(&p, res, st, outdir, wall, err))) goto done;
  if (o->plots) {
    dem_err pe = {0};
    if (cal_write_plots(&p, res, outdir, &pe)) fprintf(stderr, "dem-calibrate: warning: %s\n", pe.msg);
  }
  if (o->json && (rc = cal_write_json(&p, res, st, stdout, err))) goto done;
done:
  res->nevals = p.nevals;
  res->ncached = p.ncached;
  res->nfailed = p.nfailed;
  res->mean_relative_error = rc ? NAN : cal_mean_relative_error(&p);
  if (p.trace) fclose(p.trace); /* the incomplete trace stays as trace.csv.tmp */
  if (p.failures) {
    long size = ftell(p.failures);
    fclose(p.failures);
    if (size == 0) remove(path);
  }
  cal_cache_close(p.cache);
  free(p.model);
  free(p.resid);
  free(p.tr);
  return rc;
}
