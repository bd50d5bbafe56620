/* dem-validate — runs the thesis' ball-indentation conclusions as checks (docs/validation.md).
 *
 *   dem-validate [--tier quick|medium|full|smoke] [--case NAME[,NAME...]] [--out DIR] [--beds DIR]
 *                [--threads N] [--level A] [--json] [--list] [--quiet] [--baseline FILE]
 *                [--plan] [--no-run-cache] [--budget S] [--materials SET]
 *                [--dt-factor F] [--stiffness-scale K] [--replicates N]
 *   mpirun -n R dem-validate ...   beds and runs distributed over R ranks (validate/dist.c)
 *
 * Writes DIR/report.md, DIR/report.html, DIR/summary.json, PNG figures and DIR/data/; prints
 * one line per case (PASS/FAIL with the numbers), or with --json the summary object on
 * stdout. Progress goes to stderr. Exit status: 0 every case passed (or had nothing to
 * check), 3 a criterion failed, 4 a criterion that passed in the --baseline file failed,
 * 1 a run or the report failed, 2 usage error.
 */
#include <errno.h>
#include <getopt.h>
#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>

#ifdef VH_HAVE_MPI
#include <mpi.h>
#endif

#include "cli_common.h"
#include "dem/table.h"
#include "vh.h"

static const char *prog = "dem-validate";

static void usage(FILE *f) {
  fprintf(f,
          "usage: %s [--tier quick|medium|full|smoke] [--case NAME[,NAME...]] [--out DIR] [--beds DIR]\n"
          "          [--threads N] [--level A] [--json] [--list] [--quiet] [--baseline FILE]\n"
          "          [--plan] [--no-run-cache] [--budget S] [--materials SET]\n"
          "          [--dt-factor F] [--stiffness-scale K] [--replicates N]\n"
          "       mpirun -n R %s ...   (independent beds and runs on R ranks)\n"
          "  --tier     quick (default: geometry scaled ~0.6, cases 1-3, minutes), medium (the\n"
          "             same geometry, all eleven cases, ~30 min), full (thesis scale, all\n"
          "             eleven cases, hours) or smoke (tests only)\n"
          "  --case     run only these cases (see --list), at the tier's scale\n"
          "  --out      report folder, created with its parents (default validation-<tier>)\n"
          "  --beds     folder of prepared beds, reused across invocations (default OUT/beds)\n"
          "  --threads  OpenMP threads per run (default 2)\n"
          "  --level    significance level of every test (default 0.05)\n"
          "  --json     print the summary object on stdout\n"
          "  --list     name the cases and exit\n"
          "  --quiet    no progress lines (stage, simulated time, ETA every 30 s) on stderr\n"
          "  --baseline FILE  a summary.json of an earlier run: exit 4 if a criterion that\n"
          "             passed there fails now (regression check for CI)\n"
          "  --plan     list the beds and runs the cases need, which of them are already in\n"
          "             the --beds folder, and an estimate of the rest; compute nothing\n"
          "  --no-run-cache  do not reuse runs kept in the --beds folder (they are kept\n"
          "             there after every run, keyed by bed, indenter and a hash of the\n"
          "             sources and build a run depends on, not the report's)\n"
          "  --budget S make the beds and runs case by case, the case that lacks the least\n"
          "             first, and start none whose estimate (scaled by how long the ones\n"
          "             made so far took) would end more than S seconds after the start; the\n"
          "             criteria that need what was not made are N/A, and a later invocation\n"
          "             over the same --beds goes on (with --plan: prints that order)\n"
          "  --materials pasha-simplified (default: chapters 6/7, Tables 6.1-6.3, every case)\n"
          "             or hertz-jkr (chapter 5's cohesive glass beads, Tables 5.1-5.3: the\n"
          "             materials of the thesis' runs behind cases 1-4, which are the only\n"
          "             cases it runs)\n"
          "  --replicates N  replicate beds (seeds 1..N, N <= 4) on which the cases whose\n"
          "             criteria swing from bed to bed (plateau, penetration-depth,\n"
          "             indenter-shape, indenter-size's wall confinement on the shallow bed,\n"
          "             strain-rate on its rate bed) make their runs and are judged over the\n"
          "             beds;\n"
          "             and from which cases 2, 8, 9 estimate the bed-to-bed spread (default:\n"
          "             the tier's: 1 quick and smoke, 2 medium and full)\n",
          prog, prog);
}

/* Regressions against a baseline summary.json (--baseline): every criterion that passed
 * there must pass now (matched by case name and criterion text). Returns the number of
 * regressions (printed), or -1 with err set if the file cannot be read. */
static int regressions(const char *file, const vh_case_result *res, int nres, dem_err *err) {
  json_error_t je;
  json_t *root = json_load_file(file, 0, &je);
  if (!root) {
    dem_err_set(err, DEM_EIO, "--baseline %s:%d: %s", file, je.line, je.text);
    return -1;
  }
  int nreg = 0, ncmp = 0;
  json_t *cases = json_object_get(root, "cases"), *c;
  size_t i;
  json_array_foreach(cases, i, c) {
    const char *name = json_string_value(json_object_get(c, "name"));
    json_t *checks = json_object_get(c, "checks"), *k;
    size_t j;
    json_array_foreach(checks, j, k) {
      const char *what = json_string_value(json_object_get(k, "criterion"));
      const char *st = json_string_value(json_object_get(k, "status"));
      if (!name || !what || !st || strcmp(st, "PASS") != 0) continue;
      for (int r = 0; r < nres; r++) {
        if (strcmp(res[r].name, name) != 0) continue;
        for (int q = 0; q < res[r].nchecks; q++) {
          if (strcmp(res[r].checks[q].what, what) != 0) continue;
          ncmp++;
          if (res[r].checks[q].status != VH_PASS) {
            fprintf(stderr, "%s: regression: %s: \"%s\" passed in %s, now %s (%s)\n", prog,
                    name, what, file, vh_status_name(res[r].checks[q].status),
                    res[r].checks[q].ours);
            nreg++;
          }
        }
      }
    }
  }
  json_decref(root);
  fprintf(stderr, "%s: %d criteria that passed in %s compared, %d regressions\n", prog, ncmp,
          file, nreg);
  return nreg;
}

static int selected(const char *list, const char *name) {
  if (!list) return -1;
  size_t n = strlen(name);
  for (const char *p = list; *p;) {
    const char *e = strchr(p, ',');
    size_t m = e ? (size_t)(e - p) : strlen(p);
    if (m == n && strncmp(p, name, n) == 0) return 1;
    p += m + (e ? 1 : 0);
  }
  return 0;
}

typedef struct loop_ctx {
  const char *cases;     /* --case list or NULL */
  vh_case_result *res;
  int nres;
  int json;
  int any_fail, any_err;
} loop_ctx;

/* The selected cases in order. With h->plan set they only list their beds and runs (dist.c):
 * nothing is printed and no report is written. */
static int run_cases(vh *h, void *user) {
  loop_ctx *L = user;
  const vh_tier *t = h->tier;
  FILE *o = L->json ? stderr : stdout;
  for (int i = 0; i < vh_ncases; i++) {
    int sel = selected(L->cases, vh_cases[i].name);
    int mask = t->cases_mask & (h->materials == DEM_SCENE_HERTZ_JKR ? VH_CHAPTER5_CASES : ~0);
    if (sel == 0 || (sel < 0 && !(mask & (1 << i)))) continue;
    vh_case_result *r = &L->res[L->nres++];
    memset(r, 0, sizeof *r);
    h->cur_case = L->nres - 1;
    if (h->cur_case < VH_MAX_CASES) h->case_names[h->cur_case] = vh_cases[i].name;
    h->ncases = L->nres;
    r->name = vh_cases[i].name;
    r->title = vh_cases[i].title;
    r->source = vh_cases[i].source;
    if (!h->plan) vh_log(h, "case %s: %s", r->name, r->title);
    double t0 = vh_now();
    int nb0 = h->nbeds, nr0 = h->nruns;
    dem_err e = {0};
    if (vh_cases[i].run(h, r, &e)) {
      r->status = VH_ERROR;
      snprintf(r->note, sizeof r->note, "setup error: %.380s", e.msg);
    }
    r->wall_s = vh_now() - t0;
    if (h->plan) continue;
    /* the cost of what this case was first to need, when it was made (cached or not) */
    r->cost_s = 0;
    for (int k = nb0; k < h->nbeds; k++)
      if (!h->beds[k].skipped)
        r->cost_s += isfinite(h->beds[k].prep_s) ? h->beds[k].prep_s : h->beds[k].wall_s;
    for (int k = nr0; k < h->nruns; k++) r->cost_s += h->runs[k].wall_s;
    for (int k = 0; k < r->nchecks; k++)
      fprintf(o, "%-20s %-5s %s: %s (thesis: %s)\n", r->name,
              vh_status_name(r->checks[k].status), r->checks[k].what,
              r->checks[k].ours[0] ? r->checks[k].ours : "-", r->checks[k].thesis);
    fprintf(o, "%-20s %s (%.0f s; made in %.0f s)\n", r->name, vh_status_name(r->status),
            r->wall_s, r->cost_s);
    fflush(stdout);
    if (r->status == VH_FAIL) L->any_fail = 1;
    if (r->status == VH_ERROR) L->any_err = 1;
    /* the report so far after every case: a long run interrupted later keeps its results */
    dem_err e2 = {0};
    if (vh_report_write(h, L->res, L->nres, vh_now() - h->t0, &e2)) cli_error(prog, &e2);
  }
  h->cur_case = -1;
  return DEM_OK;
}

static int finish(vh *h, vh_case_result *res, int code) {
  vh_reset(h);
  free(res);
  free(h);
#ifdef VH_HAVE_MPI
  int inited = 0;
  MPI_Initialized(&inited);
  if (inited) MPI_Finalize();
#endif
  return code;
}

/* MPI only when started by a launcher (mpirun sets these): a plain invocation stays a plain
 * process, even in a build with MPI. */
static int launched_by_mpi(void) {
  return getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMIX_RANK") || getenv("PMI_RANK") ||
         getenv("PMI_SIZE");
}

int main(int argc, char **argv) {
  static struct option opts[] = {{"tier", required_argument, 0, 't'},
                                 {"case", required_argument, 0, 'c'},
                                 {"out", required_argument, 0, 'o'},
                                 {"beds", required_argument, 0, 'b'},
                                 {"threads", required_argument, 0, 'j'},
                                 {"level", required_argument, 0, 'a'},
                                 {"json", no_argument, 0, 'J'},
                                 {"list", no_argument, 0, 'l'},
                                 {"verbose", no_argument, 0, 'v'},
                                 {"quiet", no_argument, 0, 'q'},
                                 {"baseline", required_argument, 0, 'B'},
                                 {"plan", no_argument, 0, 'P'},
                                 {"no-run-cache", no_argument, 0, 'N'},
                                 {"budget", required_argument, 0, 'T'},
                                 {"materials", required_argument, 0, 'M'},
                                 {"dt-factor", required_argument, 0, 'D'},
                                 {"stiffness-scale", required_argument, 0, 'K'},
                                 {"replicates", required_argument, 0, 'R'},
                                 {"help", no_argument, 0, 'h'},
                                 {"version", no_argument, 0, 'V'},
                                 {0, 0, 0, 0}};
  const char *tier = "quick", *cases = NULL, *out = NULL, *beds = NULL, *baseline = NULL;
  dem_scene_materials materials = DEM_SCENE_PASHA;
  double threads = 2, level = 0.05, budget = 0, dt_factor = 0, kscale = 0, replicates = 0;
  int json = 0, list = 0, verbose = 0, plan_only = 0, no_cache = 0, o;
  dem_err err = {0};
  opterr = 0;
  while ((o = getopt_long(argc, argv, ":", opts, NULL)) != -1) {
    switch (o) {
    case 't': tier = optarg; break;
    case 'c': cases = optarg; break;
    case 'o': out = optarg; break;
    case 'b': beds = optarg; break;
    case 'j':
      if (cli_parse_double("--threads", optarg, 1, 64, &threads, &err)) goto usage_error;
      break;
    case 'a':
      if (cli_parse_double("--level", optarg, 1e-6, 0.5, &level, &err)) goto usage_error;
      break;
    case 'J': json = 1; break;
    case 'l': list = 1; break;
    case 'v': verbose = 1; break;
    case 'q': verbose = -1; break;
    case 'B': baseline = optarg; break;
    case 'P': plan_only = 1; break;
    case 'N': no_cache = 1; break;
    case 'T':
      if (cli_parse_double("--budget", optarg, 1, 1e7, &budget, &err)) goto usage_error;
      break;
    case 'M': {
      int k = 0;
      while (dem_scene_materials_names[k] && strcmp(optarg, dem_scene_materials_names[k])) k++;
      if (!dem_scene_materials_names[k]) {
        dem_err_set(&err, DEM_EINVAL, "--materials %s: unknown (allowed: %s, %s)", optarg,
                    dem_scene_materials_names[0], dem_scene_materials_names[1]);
        goto usage_error;
      }
      materials = (dem_scene_materials)k;
      break;
    }
    case 'D':
      if (cli_parse_double("--dt-factor", optarg, 0.01, 1, &dt_factor, &err)) goto usage_error;
      break;
    case 'K':
      if (cli_parse_double("--stiffness-scale", optarg, 1e-3, 1, &kscale, &err))
        goto usage_error;
      break;
    case 'R':
      if (cli_parse_double("--replicates", optarg, 1, 4, &replicates, &err)) goto usage_error;
      if (replicates != floor(replicates)) {
        dem_err_set(&err, DEM_ERANGE, "--replicates: %s is not a whole number (allowed: 1-4)",
                    optarg);
        goto usage_error;
      }
      break;
    case 'h': usage(stdout); return CLI_EXIT_OK;
    case 'V': cli_print_version(prog); return CLI_EXIT_OK;
    default: cli_getopt_error(argv, &err); goto usage_error;
    }
  }
  if (cli_no_operands(argc, argv, &err)) goto usage_error;
  if (budget > 0 && no_cache) {
    dem_err_set(&err, DEM_EINVAL, "--budget with --no-run-cache: a budgeted invocation "
                                  "evaluates the cases from the run cache; drop one of them");
    goto usage_error;
  }
  if (list) {
    for (int i = 0; i < vh_ncases; i++)
      printf("%-20s %s (%s)\n", vh_cases[i].name, vh_cases[i].title, vh_cases[i].source);
    return CLI_EXIT_OK;
  }
  const vh_tier *t = vh_tier_find(tier);
  if (!t) {
    dem_err_set(&err, DEM_EINVAL, "--tier %s: unknown (allowed: quick, medium, full, smoke)", tier);
    goto usage_error;
  }
  if (cases)
    for (const char *p = cases; *p;) {
      const char *e = strchr(p, ',');
      size_t m = e ? (size_t)(e - p) : strlen(p);
      int found = 0;
      for (int i = 0; i < vh_ncases; i++)
        if (strlen(vh_cases[i].name) == m && strncmp(vh_cases[i].name, p, m) == 0) found = 1;
      if (!found) {
        char names[400];
        size_t k = 0;
        names[0] = '\0';
        for (int i = 0; i < vh_ncases && k < sizeof names; i++)
          k += (size_t)snprintf(names + k, sizeof names - k, "%s%s", i ? ", " : "",
                                vh_cases[i].name);
        dem_err_set(&err, DEM_EINVAL, "--case %.*s: unknown case (allowed: %s)", (int)m, p,
                    names);
        goto usage_error;
      }
      for (int i = 0; i < vh_ncases; i++)
        if (strlen(vh_cases[i].name) == m && strncmp(vh_cases[i].name, p, m) == 0 &&
            materials == DEM_SCENE_HERTZ_JKR && !(VH_CHAPTER5_CASES & (1 << i))) {
          dem_err_set(&err, DEM_EINVAL, "--case %.*s with --materials hertz-jkr: the thesis "
                      "ran it with the chapter 6/7 materials (pasha-simplified); hertz-jkr "
                      "takes the chapter 5 cases only (plateau, bed-height, indenter-size, "
                      "penetration-depth)", (int)m, p);
          goto usage_error;
        }
      p += m + (e ? 1 : 0);
    }

  vh *h = calloc(1, sizeof *h);
  vh_case_result *res = calloc((size_t)vh_ncases, sizeof *res);
  if (!h || !res) {
    fprintf(stderr, "%s: out of memory\n", prog);
    return CLI_EXIT_RUN;
  }
  h->tier = t;
  if (dt_factor > 0 || kscale > 0 || replicates > 0) {
    /* the tier's table entry with the numerics the user chose; beds and runs carry dt and
       the stiffness scale in their names (run.c), so they never mix with the tier's own */
    h->tier_own = *t;
    int n = 0;
    if (dt_factor > 0) {
      h->tier_own.dt_factor = dt_factor;
      n += snprintf(h->overrides + n, sizeof h->overrides - (size_t)n, "--dt-factor %g",
                    dt_factor);
    }
    if (kscale > 0) {
      h->tier_own.stiffness_scale = h->tier_own.rate_stiffness_scale = kscale;
      n += snprintf(h->overrides + n, sizeof h->overrides - (size_t)n, "%s--stiffness-scale %g",
                    n ? " " : "", kscale);
    }
    if (replicates > 0) {
      h->tier_own.replicates = (int)replicates;
      snprintf(h->overrides + n, sizeof h->overrides - (size_t)n, "%s--replicates %d",
               n ? " " : "", (int)replicates);
    }
    h->tier = &h->tier_own;
  }
  h->materials = materials;
  h->cases_arg = cases;
  h->threads = (int)threads;
  h->nranks = 1;
  h->use_cache = !no_cache;
  h->budget = budget;
  if (launched_by_mpi()) {
#ifdef VH_HAVE_MPI
    int provided;
    if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
      fprintf(stderr, "%s: MPI_Init_thread failed\n", prog);
      return CLI_EXIT_RUN;
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &h->rank);
    MPI_Comm_size(MPI_COMM_WORLD, &h->nranks);
    if (h->nranks > 1 && no_cache) {
      fprintf(stderr, "%s: --no-run-cache: the ranks hand their runs over through the run "
                      "cache; not allowed with %d MPI ranks\n", prog, h->nranks);
      return finish(h, res, CLI_EXIT_USAGE);
    }
#else
    fprintf(stderr, "%s: started by an MPI launcher, but this build has no MPI (Open MPI's "
                    "libopenmpi-dev was not found by CMake): running as one process\n", prog);
#endif
  }
  cli_warn_contention(prog, h->threads);
  h->level = level;
  h->verbose = verbose;
  h->t0 = vh_now();
  if (out) snprintf(h->out, sizeof h->out, "%s", out);
  else snprintf(h->out, sizeof h->out, "validation-%s", t->name);
  if (beds) snprintf(h->beds_dir, sizeof h->beds_dir, "%s", beds);
  else snprintf(h->beds_dir, sizeof h->beds_dir, "%.500s/beds", h->out);
  if (dem_mkdirs(h->out, &err)) {
    fprintf(stderr, "%s: --out %s: %s\n", prog, h->out, err.msg);
    return CLI_EXIT_RUN;
  }

  loop_ctx L = {cases, res, 0, json, 0, 0};
  if (plan_only || h->nranks > 1 || h->budget > 0) {
    /* list every bed and run, then (MPI) compute them on all ranks into beds_dir */
    if (vh_distribute(h, run_cases, &L, plan_only, &err)) {
      cli_error(prog, &err);
      return finish(h, res, CLI_EXIT_RUN);
    }
    memset(res, 0, (size_t)vh_ncases * sizeof *res);
    L.nres = 0;
    if (plan_only || h->rank != 0) return finish(h, res, CLI_EXIT_OK);
    /* after a --budget, what was not made stays not made (N/A), not made now */
    h->cache_only = h->budget > 0;
    vh_log(h, "rank 0: %s; evaluating the cases", h->budget > 0 ? "the budget is spent or "
           "everything is made" : "every bed and run is computed");
  }
  run_cases(h, &L);
  int nres = L.nres, any_fail = L.any_fail, any_err = L.any_err;
  double wall = vh_now() - h->t0;
  if (vh_report_write(h, res, nres, wall, &err)) {
    cli_error(prog, &err);
    any_err = 1;
  } else {
    vh_log(h, "report: %s/report.md, %s/report.html, %s/summary.json (%.0f s)", h->out, h->out,
           h->out, wall);
  }
  if (json) vh_json_print(h, res, nres, wall, stdout);
  int nreg = 0;
  if (baseline && (nreg = regressions(baseline, res, nres, &err)) < 0) {
    cli_error(prog, &err);
    any_err = 1;
  }
  return finish(h, res, any_err ? CLI_EXIT_RUN : nreg > 0 ? 4 : any_fail ? 3 : CLI_EXIT_OK);

usage_error:
  cli_error(prog, &err);
  usage(stderr);
  return CLI_EXIT_USAGE;
}
