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
 * used by --plan, which prints it, and by --budget.
 *
 * --budget S (seconds of wall time from the start): every rank makes its items case by case,
 * the case that lacks the least (estimated) first (budget_order), and starts an item only if
 * its estimate, scaled by measured / estimated over the items it has made so far, ends
 * within S; the rest are skipped. One rank makes a case's beds and then its runs before the
 * next case; several ranks keep the two phases (a run may need a bed another rank makes).
 * Rank 0 then evaluates the cases from the cache only (h->cache_only): a skipped run is a
 * placeholder whose criteria are N/A (cases.c), so a time-limited invocation reports every
 * criterion it could decide, and the next invocation over the same --beds folder goes on
 * from what this one made.
 *
 * Cost estimates (s, for the order, --budget and the --plan table only), measured on the
 * 2-core AMD EPYC VM of docs/validation.md with 2 threads, x1.9 for one thread.
 * A bed costs ~ die^2 bed^1.5 sqrt(k) x 0.2 / dt_factor: particles ~ die^2 bed, and the
 * simulated time of its stages grows with the depth (the fill falls from higher, settling
 * ~ bed^0.5; the piston travels further at the same speed, consolidation ~ bed; the deep beds'
 * hold and relax last longer), dt ~ 1/sqrt(k). The constant is the 20 d bed in the 45 d die
 * at x0.01, 1100 s (1050 s on 2026-12-03, 1108 and 1128 s on 2026-12-06: settle 417 s,
 * consolidate 225 s, unload and relax 466 s); the exponent 1.5 fits the other beds of the
 * current program within 20 % (measured / estimated: 13 d bed in the 39 d die 413 s, 0.95;
 * 30 d 2108 s, 1.04; 50 d 3992 s, 0.92; quick tier 12 d in the 20 d die 100 s, 0.99; 8 d in
 * the 17.3 d die 33 s, 0.80), where the bed-linear die^2 bed of before read 0.51-1.45 on
 * them with the same constant (the 50 d bed's 3992 s against 2750).
 * A run costs particles x steps ~ die^2 bed x (h/r D/2) / (gamma* bed dt) = die^2 D h/r
 * sqrt(k) / (gamma* dt_scale) x 0.2 / dt_factor, the 16 d sphere to h/r 0.5 at gamma* 0.1 on
 * that bed 246 s (the 13 d sphere: 13 d bed 154 s against 150, 20 d 204-217 against 200,
 * 30 d 374 against 300, 50 d 484 against 500: 0.150-0.158 us per particle-step, the 30 d
 * run's 0.182 the outlier). History: before the servo's remedy (2026-12-03 morning) 1936 and 285 s
 * (consolidate 952 s); until then 454 and 195 s (a 2-core Xeon VM, 2026-12-01), which
 * predated the bed's relax phase and the longer hold of the consolidation without overshoot
 * and underestimated the full tier ~2.5-4x (docs/validation.md).
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

static double bed_cost(const vh *h, const vh_bed *b) {
  return 1100.0 * (b->die * b->die) / (45.0 * 45.0) * pow(b->bed / 20.0, 1.5) *
         sqrt(b->kscale / 0.01) * (0.2 / h->tier->dt_factor);
}

static double run_cost(const vh *h, const vh_bed *b, const vh_indent *in) {
  return 246.0 * (b->die * b->die) / (45.0 * 45.0) * (in->D / 16.0) * (h->tier->h_end / 0.5) *
         (0.1 / in->gamma_star) * sqrt(b->kscale / 0.01) * (0.2 / h->tier->dt_factor) / in->dt_scale;
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

/* ord[0..n) = 0..n-1 sorted by cost, descending (desc) or ascending; stable. */
static void sort_by_cost(const double *cost, int n, int desc, int *ord) {
  for (int i = 0; i < n; i++) ord[i] = i;
  for (int i = 1; i < n; i++) /* insertion sort: n is a few tens */
    for (int j = i; j > 0 && (desc ? cost[ord[j]] > cost[ord[j - 1]]
                                   : cost[ord[j]] < cost[ord[j - 1]]); j--) {
      int t = ord[j];
      ord[j] = ord[j - 1];
      ord[j - 1] = t;
    }
}

/* Longest processing time first: owner[i] for costs[0..n). */
static void assign(const double *cost, int n, int nranks, int *owner) {
  int *ord = malloc((size_t)(n > 0 ? n : 1) * sizeof *ord);
  double load[256] = {0};
  if (!ord) {
    for (int i = 0; i < n; i++) owner[i] = i % nranks;
    return;
  }
  sort_by_cost(cost, n, 1, ord);
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

/* The cache file of a run on a listed bed. */
static void run_cache_path(const vh *h, const vh_bed *b, const vh_indent *in, char *cp,
                           size_t len) {
  char bn[256];
  snprintf(bn, sizeof bn, "%s", strrchr(b->path, '/') + 1);
  bn[strlen(bn) - 3] = '\0'; /* ".h5" */
  vh_cache_path(h, bn, in, cp, len);
}

/* 1 if the run is in the cache (with its wall time), 0 if not. */
static int run_cached(const vh *h, const vh_bed *b, const vh_indent *in, char *cp, size_t len,
                      double *wall_s) {
  run_cache_path(h, b, in, cp, len);
  vh_run r;
  memset(&r, 0, sizeof r);
  int have = access(b->path, R_OK) == 0 && vh_cache_load(h, cp, b->path, &r) == 0;
  *wall_s = have ? r.wall_s : NAN;
  vh_run_release(&r);
  return have;
}

/* --budget: the estimates are scaled by what the items made so far by this rank in this
 * invocation took against their estimates (1 before the first), so a slower or faster
 * machine than the one of the constants is learnt from the first item. An item is started
 * only if its scaled estimate ends within the budget; a started item runs to its end. */
typedef struct budget_acc {
  double est, spent; /* s, summed over the items made (not the ones found made) */
} budget_acc;

static int budget_fits(const vh *h, const budget_acc *a, double cost, double *end) {
  const double ratio = a->est > 0 ? a->spent / a->est : 1.0;
  *end = (vh_now() - h->t0) + ratio * cost;
  return *end <= h->budget;
}

static void budget_skip(const vh *h, const char *what, int i, double cost, double end) {
  vh_log(h, "rank %d: %s %d not made: its estimate (%.0f s, scaled) would end at %.0f s, past "
         "the --budget of %.0f s", h->rank, what, i, cost, end, h->budget);
}

/* --budget: the order in which the items (0..nb-1 beds, nb..nb+nr-1 runs) are made. A case
 * is decided only when every run it needs is made (a part-made case is N/A, cases.c), so the
 * cases are taken by the estimated cost of what each still lacks, cheapest first, and what a
 * chosen case lacks then counts as made for the cases after it (greedy: the most cases
 * decided within the time); within a case its beds come first, then its runs, each cheapest
 * first. Items already made (done) come first and cost nothing. (Every item cheapest first
 * regardless of its cases, the order of 721286c, spreads the budget over the cheap runs of
 * every case: at thesis scale the gamma* 0.1 run that every criterion of case 10 needs came
 * last.) cord[0..*ncord) receives the case order, cinc[] what each case added (s, estimated)
 * and cfirst[] where its items start in ord (cfirst[*ncord] = the end). */
static void budget_order(int nb, int nr, const double *cost, const unsigned *mask,
                         const int *done, int ncases, int *ord, int *cord, double *cinc,
                         int *cfirst, int *ncord) {
  const int n = nb + nr;
  int taken[VH_MAX_BEDS + VH_MAX_RUNS] = {0}, chosen[32] = {0}, m = 0, nc = 0;
  if (ncases > 32) ncases = 32;
  for (int i = 0; i < n; i++)
    if (done[i]) taken[i] = 1, ord[m++] = i;
  for (;;) {
    int best = -1;
    double bc = INFINITY;
    for (int c = 0; c < ncases; c++) {
      if (chosen[c]) continue;
      double sum = 0;
      for (int i = 0; i < n; i++)
        if (!taken[i] && (mask[i] >> c & 1u)) sum += cost[i];
      if (sum < bc) bc = sum, best = c; /* ties: the earlier case */
    }
    /* best == -1 after the last case: what no case claimed (nothing, as every bed and run
     * is asked for by a case) is taken by the same loop with every item eligible */
    if (best >= 0) chosen[best] = 1, cord[nc] = best, cinc[nc] = bc, cfirst[nc++] = m;
    for (int part = 0; part < 2; part++) { /* beds, then runs */
      for (;;) {
        int k = -1;
        for (int i = part ? nb : 0; i < (part ? n : nb); i++)
          if (!taken[i] && (best < 0 || (mask[i] >> best & 1u)) && (k < 0 || cost[i] < cost[k]))
            k = i;
        if (k < 0) break;
        taken[k] = 1, ord[m++] = k;
      }
    }
    if (best < 0) break;
  }
  cfirst[nc] = m;
  *ncord = nc;
}

int vh_distribute(vh *h, vh_cases_fn run_cases, void *user, int print_plan, dem_err *err) {
  h->plan = 1;
  run_cases(h, user);
  h->plan = 0;
  const int nb = h->nbeds, nr = h->nruns, n = nb + nr;
  vh_bed *beds = calloc((size_t)nb + 1, sizeof *beds);
  vh_indent *inds = calloc((size_t)nr + 1, sizeof *inds);
  int *rbed = calloc((size_t)nr + 1, sizeof *rbed), *owner = calloc((size_t)n + 1, sizeof *owner);
  int *done = calloc((size_t)n + 1, sizeof *done), *ord = calloc((size_t)n + 1, sizeof *ord);
  double *cost = calloc((size_t)n + 1, sizeof *cost), *rwall = calloc((size_t)nr + 1,
                                                                       sizeof *rwall);
  unsigned *mask = calloc((size_t)n + 1, sizeof *mask);
  int cord[32], cfirst[33], ncord = 0;
  double cinc[32];
  int rc = DEM_OK;
  if (!beds || !inds || !rbed || !owner || !done || !ord || !cost || !rwall || !mask) {
    rc = dem_err_set(err, DEM_ENOMEM, "dem-validate: out of memory");
    goto out;
  }
  /* the constants are for 2 threads; one thread is 1.9x slower (docs/benchmarks.md); beyond
   * 2 threads the scaling is not measured here and the 2-thread costs are used */
  const double tf = h->threads == 1 ? 1.9 : 1.0;
  for (int i = 0; i < nb; i++) {
    beds[i] = h->beds[i];
    cost[i] = tf * bed_cost(h, &beds[i]);
    mask[i] = beds[i].cases;
  }
  for (int j = 0; j < nr; j++) {
    inds[j] = h->runs[j].ind;
    rbed[j] = h->runs[j].bed;
    cost[nb + j] = tf * run_cost(h, &beds[rbed[j]], &inds[j]);
    mask[nb + j] = h->runs[j].cases;
  }
  vh_reset(h);
  /* what is already made: a bed in beds_dir, a run in the cache (read only when it matters) */
  for (int i = 0; i < nb; i++) done[i] = access(beds[i].path, R_OK) == 0;
  for (int j = 0; j < nr; j++) {
    char cp[700];
    rwall[j] = NAN;
    if (print_plan || h->budget > 0)
      done[nb + j] = run_cached(h, &beds[rbed[j]], &inds[j], cp, sizeof cp, &rwall[j]);
  }
  if (h->budget > 0)
    budget_order(nb, nr, cost, mask, done, h->ncases, ord, cord, cinc, cfirst, &ncord);
  else
    for (int i = 0; i < n; i++) ord[i] = i;

  if (print_plan) {
    /* what this invocation would do, and what is already in beds_dir */
    double todo = 0, total = 0;
    printf("plan of --tier %s: %d beds, %d runs (folder %s)\n", h->tier->name, nb, nr,
           h->beds_dir);
    for (int i = 0; i < nb; i++) {
      double prep = vh_bed_info_load(&beds[i]);
      printf("  bed %2d  %-62s %s", i, strrchr(beds[i].path, '/') + 1,
             done[i] ? "prepared" : "to prepare");
      if (done[i] && isfinite(prep)) printf(" (%.0f s)", prep);
      else if (!done[i]) printf(" (est. %.0f s)", cost[i]);
      printf("\n");
      total += cost[i];
      if (!done[i]) todo += cost[i];
    }
    for (int j = 0; j < nr; j++) {
      char cp[700];
      run_cache_path(h, &beds[rbed[j]], &inds[j], cp, sizeof cp);
      printf("  run %2d  bed %2d  %-52s %s", j, rbed[j], strrchr(cp, '/') + 5,
             done[nb + j] ? "cached" : "to run");
      if (done[nb + j]) printf(" (%.0f s)", rwall[j]);
      else printf(" (est. %.0f s)", cost[nb + j]);
      printf("\n");
      total += cost[nb + j];
      if (!done[nb + j]) todo += cost[nb + j];
    }
    printf("estimated cost: %.0f s of which %.0f s not yet done (one process, %d threads; the "
           "constants are from a 2-core AMD EPYC VM with 2 threads, see validate/dist.c%s)\n", total,
           todo, h->threads, h->threads > 2 ? "; used as they are for more threads" : "");
    printf("estimated wall time of everything from scratch on R ranks of %d threads (beds, then "
           "runs, longest first; R x %d cores):", h->threads, h->threads);
    for (int R = 1; R <= 16; R *= 2)
      printf(" R=%d %.0f s%s", R, makespan(cost, nb, R) + makespan(cost + nb, nr, R),
             R < 16 ? "," : "\n");
    if (h->budget > 0) {
      printf("order under --budget %.0f (cases by what each lacks, cheapest first; within a "
             "case beds, then runs, cheapest first):\n", h->budget);
      for (int c = 0; c < ncord; c++) {
        printf("  %d. %s (+%.0f s est.):", c + 1,
               cord[c] < VH_MAX_CASES && h->case_names[cord[c]] ? h->case_names[cord[c]] : "?",
               cinc[c]);
        if (cfirst[c] == cfirst[c + 1]) printf(" nothing to make");
        for (int k = cfirst[c]; k < cfirst[c + 1]; k++)
          printf(" %s %d%s", ord[k] < nb ? "bed" : "run", ord[k] < nb ? ord[k] : ord[k] - nb,
                 k + 1 < cfirst[c + 1] ? "," : "");
        printf("\n");
      }
    }
    goto out;
  }
  if (h->budget > 0 && h->rank == 0) {
    char line[1024];
    size_t len = 0;
    for (int c = 0; c < ncord && len < sizeof line; c++)
      len += (size_t)snprintf(line + len, sizeof line - len, "%s%s (+%.0f s est.)",
                              c ? ", " : "", cord[c] < VH_MAX_CASES && h->case_names[cord[c]]
                                                 ? h->case_names[cord[c]] : "?", cinc[c]);
    vh_log(h, "--budget %.0f s: the cases in the order of what each lacks: %s", h->budget,
           ncord ? line : "(none)");
  }

  /* Each rank makes its items (the balanced assignment) in the plan order, or with a --budget
   * in the order above. One rank makes them in one pass (a case's beds, then its runs);
   * several ranks make the beds, wait for one another, then make the runs. */
  budget_acc acc = {0, 0};
  int nfail = 0, nskip = 0;
  assign(cost, nb, h->nranks, owner);
  assign(cost + nb, nr, h->nranks, owner + nb);
  const int passes = h->nranks > 1 ? 2 : 1;
  for (int pass = 0; pass < passes; pass++) {
    for (int k = 0; k < n; k++) {
      const int i = ord[k];
      if (passes == 2 && (i < nb) != (pass == 0)) continue;
      if (owner[i] != h->rank) continue;
      const int have = done[i];
      double end;
      dem_err e = {0};
      const double t0 = vh_now();
      if (i < nb) { /* a bed */
        if (h->budget > 0 && !have && !budget_fits(h, &acc, cost[i], &end)) {
          budget_skip(h, "bed", i, cost[i], end);
          nskip++;
          continue;
        }
        if (vh_bed_get(h, &beds[i], &e) < 0) {
          vh_log(h, "rank %d: bed %d failed: %s", h->rank, i, e.msg);
          nfail++;
        } else if (!have) {
          acc.est += cost[i];
          acc.spent += vh_now() - t0;
        }
        continue;
      }
      const int j = i - nb; /* a run */
      if (h->budget > 0 && !have) {
        if (access(beds[rbed[j]].path, R_OK) != 0) { /* its bed was skipped, or failed */
          vh_log(h, "rank %d: run %d not made: its bed was not prepared", h->rank, j);
          nskip++;
          continue;
        }
        if (!budget_fits(h, &acc, cost[i], &end)) {
          budget_skip(h, "run", j, cost[i], end);
          nskip++;
          continue;
        }
      }
      int r = vh_run_get(h, &beds[rbed[j]], &inds[j], &e);
      if (r < 0 || h->runs[r].status != DEM_OK) nfail++;
      if (!have) {
        acc.est += cost[i];
        acc.spent += vh_now() - t0;
      }
    }
    wait_all(h);
    vh_reset(h);
  }
  if (nfail)
    vh_log(h, "rank %d: %d of its beds or runs failed (the cases report them)", h->rank, nfail);
  if (nskip)
    vh_log(h, "rank %d: %d of its beds and runs not made within the --budget (the cases report "
           "their criteria as N/A)", h->rank, nskip);
out:
  free(beds), free(inds), free(rbed), free(owner), free(done), free(ord), free(cost);
  free(rwall), free(mask);
  return rc;
}
