/* dist.c — the plan of an invocation and its distribution over MPI ranks.
 *
 * The cases are deterministic in what they ask for: running them with h->plan set lists
 * every bed and run (vh_bed_get / vh_run_get record the request and return a placeholder
 * that the cases see as unavailable). The plan is then carried out in two phases, each
 * balanced over the ranks by estimated cost (longest first onto the least loaded rank, the
 * same assignment on every rank):
 *   1. the beds, each prepared once into beds_dir (a bed already there is reused);
 *   2. the runs, each into the run cache (cache.c) in beds_dir.
 * Every rank then has nothing left to compute, and rank 0 evaluates the cases in order from
 * the beds and the cache, exactly as a one-process invocation would (the same runs, the same
 * order, the same report). Independent runs are what is distributed; every run keeps its
 * --threads OpenMP threads, so ranks x threads should not exceed the cores.
 *
 * Between the phases the ranks wait in a barrier that sleeps (MPI_Ibarrier + MPI_Test every
 * 50 ms): a busy-polling MPI_Barrier would take a core from the ranks still computing.
 * Without MPI (not built with it, or not started by mpirun) there is one rank and the plan is
 * used only by --plan, which prints it.
 *
 * Cost estimates (s, for the order and the --plan table only; measured on the 2-core Xeon of
 * docs/validation.md with 2 threads, x1.9 for one thread: the 20 d bed in the 45 d die at x0.01 454 s, the 16 d
 * sphere to h/r 0.5 at gamma* 0.1 195 s): a bed costs ~ die^2 bed sqrt(k) (particles x steps
 * of fill, settle and consolidation, dt ~ 1/sqrt(k)); a run costs particles x steps ~
 * die^2 bed x (h/r D/2) / (gamma* bed dt) = die^2 D h/r sqrt(k) / (gamma* dt_scale).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#ifdef VH_HAVE_MPI
#include <mpi.h>
#endif

#include "vh.h"

static double bed_cost(const vh_bed *b) {
  return 454.0 * (b->die * b->die * b->bed) / (45.0 * 45.0 * 20.0) * sqrt(b->kscale / 0.01);
}

static double run_cost(const vh *h, const vh_bed *b, const vh_indent *in) {
  return 195.0 * (b->die * b->die) / (45.0 * 45.0) * (in->D / 16.0) * (h->tier->h_end / 0.5) *
         (0.1 / in->gamma_star) * sqrt(b->kscale / 0.01) / in->dt_scale;
}

static void wait_all(const vh *h) {
#ifdef VH_HAVE_MPI
  if (h->nranks > 1) {
    MPI_Request rq;
    int done = 0;
    MPI_Ibarrier(MPI_COMM_WORLD, &rq);
    const struct timespec ts = {0, 50000000L};
    while (MPI_Test(&rq, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS && !done) nanosleep(&ts, NULL);
  }
#else
  (void)h;
#endif
}

/* Longest processing time first: owner[i] for costs[0..n). */
static void assign(const double *cost, int n, int nranks, int *owner) {
  int *ord = malloc((size_t)(n > 0 ? n : 1) * sizeof *ord);
  double load[256] = {0};
  if (!ord) {
    for (int i = 0; i < n; i++) owner[i] = i % nranks;
    return;
  }
  for (int i = 0; i < n; i++) ord[i] = i;
  for (int i = 1; i < n; i++) /* insertion sort by cost, descending; stable */
    for (int j = i; j > 0 && cost[ord[j]] > cost[ord[j - 1]]; j--) {
      int t = ord[j];
      ord[j] = ord[j - 1];
      ord[j - 1] = t;
    }
  for (int k = 0; k < n; k++) {
    int best = 0;
    for (int r = 1; r < nranks && r < 256; r++)
      if (load[r] < load[best]) best = r;
    owner[ord[k]] = best;
    load[best] += cost[ord[k]];
  }
  free(ord);
}

/* The largest load of the assignment: the estimated wall time of a phase on nranks ranks. */
static double makespan(const double *cost, int n, int nranks) {
  int *own = malloc((size_t)(n > 0 ? n : 1) * sizeof *own);
  double load[256] = {0}, m = 0;
  if (!own) return NAN;
  assign(cost, n, nranks, own);
  for (int i = 0; i < n; i++) load[own[i]] += cost[i];
  for (int r = 0; r < nranks && r < 256; r++) m = fmax(m, load[r]);
  free(own);
  return m;
}

int vh_distribute(vh *h, vh_cases_fn run_cases, void *user, int print_plan, dem_err *err) {
  h->plan = 1;
  run_cases(h, user);
  h->plan = 0;
  const int nb = h->nbeds, nr = h->nruns;
  vh_bed *beds = calloc((size_t)nb + 1, sizeof *beds);
  vh_indent *inds = calloc((size_t)nr + 1, sizeof *inds);
  int *rbed = calloc((size_t)nr + 1, sizeof *rbed), *owner = calloc((size_t)(nb + nr) + 1,
                                                                     sizeof *owner);
  double *cost = calloc((size_t)(nb + nr) + 1, sizeof *cost);
  if (!beds || !inds || !rbed || !owner || !cost) {
    free(beds), free(inds), free(rbed), free(owner), free(cost);
    return dem_err_set(err, DEM_ENOMEM, "dem-validate: out of memory");
  }
  /* the constants are for 2 threads; one thread is 1.9x slower (docs/benchmarks.md); beyond
   * 2 threads the scaling is not measured here and the 2-thread costs are used */
  const double tf = h->threads == 1 ? 1.9 : 1.0;
  for (int i = 0; i < nb; i++) {
    beds[i] = h->beds[i];
    cost[i] = tf * bed_cost(&beds[i]);
  }
  for (int j = 0; j < nr; j++) {
    inds[j] = h->runs[j].ind;
    rbed[j] = h->runs[j].bed;
    cost[nb + j] = tf * run_cost(h, &beds[rbed[j]], &inds[j]);
  }
  vh_reset(h);

  if (print_plan) {
    /* what this invocation would do, and what is already in beds_dir */
    double todo = 0, total = 0;
    printf("plan of --tier %s: %d beds, %d runs (folder %s)\n", h->tier->name, nb, nr,
           h->beds_dir);
    for (int i = 0; i < nb; i++) {
      int have = access(beds[i].path, R_OK) == 0;
      double prep = vh_bed_info_load(&beds[i]);
      printf("  bed %2d  %-62s %s", i, strrchr(beds[i].path, '/') + 1,
             have ? "prepared" : "to prepare");
      if (have && isfinite(prep)) printf(" (%.0f s)", prep);
      else if (!have) printf(" (est. %.0f s)", cost[i]);
      printf("\n");
      total += cost[i];
      if (!have) todo += cost[i];
    }
    for (int j = 0; j < nr; j++) {
      const vh_bed *b = &beds[rbed[j]];
      char bn[256], cp[700];
      snprintf(bn, sizeof bn, "%s", strrchr(b->path, '/') + 1);
      bn[strlen(bn) - 3] = '\0'; /* ".h5" */
      vh_cache_path(h, bn, &inds[j], cp, sizeof cp);
      vh_run r;
      memset(&r, 0, sizeof r);
      int have = access(b->path, R_OK) == 0 && vh_cache_load(h, cp, b->path, &r) == 0;
      printf("  run %2d  bed %2d  %-52s %s", j, rbed[j], strrchr(cp, '/') + 5,
             have ? "cached" : "to run");
      if (have) printf(" (%.0f s)", r.wall_s);
      else printf(" (est. %.0f s)", cost[nb + j]);
      printf("\n");
      vh_run_release(&r);
      total += cost[nb + j];
      if (!have) todo += cost[nb + j];
    }
    printf("estimated cost: %.0f s of which %.0f s not yet done (one process, %d threads; the "
           "constants are from a 2-core Xeon with 2 threads, see validate/dist.c%s)\n", total,
           todo, h->threads, h->threads > 2 ? "; used as they are for more threads" : "");
    printf("estimated wall time of everything from scratch on R ranks of %d threads (beds, then "
           "runs, longest first; R x %d cores):", h->threads, h->threads);
    for (int R = 1; R <= 16; R *= 2)
      printf(" R=%d %.0f s%s", R, makespan(cost, nb, R) + makespan(cost + nb, nr, R),
             R < 16 ? "," : "\n");
    free(beds), free(inds), free(rbed), free(owner), free(cost);
    return DEM_OK;
  }

  /* phase 1: beds */
  assign(cost, nb, h->nranks, owner);
  int nfail = 0;
  for (int i = 0; i < nb; i++) {
    if (owner[i] != h->rank) continue;
    dem_err e = {0};
    if (vh_bed_get(h, &beds[i], &e) < 0) {
      vh_log(h, "rank %d: bed %d failed: %s", h->rank, i, e.msg);
      nfail++;
    }
  }
  wait_all(h);
  vh_reset(h);
  /* phase 2: runs (vh_run_get writes each into the cache) */
  assign(cost + nb, nr, h->nranks, owner + nb);
  for (int j = 0; j < nr; j++) {
    if (owner[nb + j] != h->rank) continue;
    dem_err e = {0};
    int k = vh_run_get(h, &beds[rbed[j]], &inds[j], &e);
    if (k < 0 || h->runs[k].status != DEM_OK) nfail++;
  }
  wait_all(h);
  vh_reset(h);
  free(beds), free(inds), free(rbed), free(owner), free(cost);
  if (nfail)
    vh_log(h, "rank %d: %d of its beds or runs failed (the cases report them)", h->rank, nfail);
  return DEM_OK;
}
