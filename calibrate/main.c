/* dem-calibrate: fit contact-law coefficients to reference data with NLopt.
 *
 *   dem-calibrate CONFIG [--out DIR] [--resume] [--json] [--quiet] [--no-plots]
 *   dem-calibrate --builtin NAME [...]     a built-in case (calibrate/builtin/NAME.cfg)
 *   dem-calibrate --list-builtins | --help | --version
 *
 * Exit status: 0 success, 1 bad input or a failed run, 2 usage, 130 interrupted (resume
 * with --resume). See docs/calibration.md. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cal.h"

#ifndef DEM_SOURCE_DIR
#define DEM_SOURCE_DIR "."
#endif

static const char *builtin_dir(void) {
  const char *env = getenv("DEM_CALIBRATE_BUILTIN_DIR");
  return env && *env ? env : DEM_SOURCE_DIR "/calibrate/builtin";
}

static void usage(FILE *f) {
  fprintf(f,
          "usage: dem-calibrate CONFIG [--out DIR] [--resume] [--json] [--quiet] [--no-plots]\n"
          "       dem-calibrate --builtin NAME [--out DIR] [--resume] [--json] ...\n"
          "       dem-calibrate --list-builtins | --help | --version\n\n"
          "Fits the free coefficients of a contact law to reference force-overlap curves,\n"
          "critical sticking velocities and e(v) curves (NLopt: global stage + local polish).\n\n"
          "  CONFIG           libconfig file: law, free parameters (bounds, log/linear scale),\n"
          "                   fixed parameters, targets with weights, optimiser, seed\n"
          "  --out DIR        output folder (default out/calibrate/<name>)\n"
          "  --resume         reuse the evaluation cache of an interrupted run in DIR\n"
          "  --json           print one JSON object: parameters, objective, residuals\n"
          "                   (each with relative_error), mean_relative_error\n"
          "  --quiet          no progress line\n"
          "  --no-plots       skip the gnuplot PNGs\n"
          "  --stop-after N   (testing) stop after N evaluations as if interrupted\n"
          "  --builtin NAME   run calibrate/builtin/NAME.cfg; --list-builtins lists them\n\n"
          "Exit status: 0 ok, 1 bad input or failed run, 2 usage, 130 interrupted.\n"
          "Documentation: docs/calibration.md.\n");
}

static int cmp_str(const void *a, const void *b) {
  return strcmp(*(const char *const *)a, *(const char *const *)b);
}

static int list_builtins(void) {
  DIR *d = opendir(builtin_dir());
  if (!d) {
    fprintf(stderr, "dem-calibrate: cannot open %s\n", builtin_dir());
    return 1;
  }
  char *names[256];
  int n = 0;
  struct dirent *e;
  while ((e = readdir(d)) && n < 256) {
    size_t l = strlen(e->d_name);
    if (l > 4 && strcmp(e->d_name + l - 4, ".cfg") == 0) names[n++] = strndup(e->d_name, l - 4);
  }
  closedir(d);
  qsort(names, (size_t)n, sizeof names[0], cmp_str);
  for (int i = 0; i < n; i++) {
    char path[CAL_PATH_LEN], line[256] = "";
    snprintf(path, sizeof path, "%s/%s.cfg", builtin_dir(), names[i]);
    FILE *f = fopen(path, "r");
    if (f) {
      /* the first comment line describes the case */
      while (fgets(line, sizeof line, f))
        if (line[0] == '#' || (line[0] == '/' && line[1] == '/')) break;
      fclose(f);
    }
    char *txt = line + strspn(line, "#/ ");
    txt[strcspn(txt, "\n")] = '\0';
    printf("%-28s %s\n", names[i], txt);
    free(names[i]);
  }
  return 0;
}

int main(int argc, char **argv) {
  const char *config = NULL, *builtin = NULL;
  cal_run_opts o = {NULL, 0, 0, 0, 1, 0};
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      usage(stdout);
      return 0;
    } else if (!strcmp(a, "--version")) {
      printf("dem-calibrate %s\n", DEM_VERSION);
      return 0;
    } else if (!strcmp(a, "--list-builtins")) {
      return list_builtins();
    } else if (!strcmp(a, "--builtin") && i + 1 < argc) {
      builtin = argv[++i];
    } else if (!strcmp(a, "--out") && i + 1 < argc) {
      o.outdir = argv[++i];
    } else if (!strcmp(a, "--resume")) {
      o.resume = 1;
    } else if (!strcmp(a, "--json")) {
      o.json = 1;
    } else if (!strcmp(a, "--quiet")) {
      o.quiet = 1;
    } else if (!strcmp(a, "--stop-after") && i + 1 < argc) {
      o.stop_after = atol(argv[++i]); /* testing the interrupt/resume path */
    } else if (!strcmp(a, "--no-plots")) {
      o.plots = 0;
    } else if (a[0] == '-') {
      fprintf(stderr, "dem-calibrate: unknown or incomplete option '%s'\n", a);
      usage(stderr);
      return 2;
    } else if (!config) {
      config = a;
    } else {
      fprintf(stderr, "dem-calibrate: more than one config file ('%s', '%s')\n", config, a);
      return 2;
    }
  }
  char bpath[CAL_PATH_LEN];
  if (builtin) {
    if (config) {
      fprintf(stderr, "dem-calibrate: give either CONFIG or --builtin NAME\n");
      return 2;
    }
    if (strchr(builtin, '/')) {
      fprintf(stderr, "dem-calibrate: built-in names have no '/' (see --list-builtins)\n");
      return 2;
    }
    snprintf(bpath, sizeof bpath, "%s/%s.cfg", builtin_dir(), builtin);
    config = bpath;
  }
  if (!config) {
    usage(stderr);
    return 2;
  }
  static cal_config c; /* large: keep it off the stack */
  dem_err err = {0};
  if (cal_config_load(&c, config, &err)) {
    fprintf(stderr, "dem-calibrate: %s\n", err.msg);
    if (builtin) fprintf(stderr, "dem-calibrate: (see --list-builtins)\n");
    return 1;
  }
  cal_install_signal_handlers();
  cal_result res;
  cal_stats st;
  int rc = cal_run(&c, &o, &res, &st, &err);
  cal_config_free(&c);
  if (rc == DEM_EINTERRUPTED) {
    fprintf(stderr,
            "dem-calibrate: interrupted after %ld evaluations; every evaluation is in the cache: "
            "rerun with --resume to continue\n",
            res.nevals);
    return 130;
  }
  if (rc) {
    fprintf(stderr, "dem-calibrate: %s\n", err.msg);
    return 1;
  }
  if (!o.json)
    fprintf(stderr, "dem-calibrate: %s done: S = %.6g, mean |relative error| %.4g, %ld evaluations%s%s\n",
            c.name, res.f, res.mean_relative_error, res.nevals, st.warning[0] ? "\nwarning: " : "",
            st.warning);
  return 0;
}
