/* dem-contact: drive a prescribed overlap path (load, unload, reload) through a contact law
 * and write the force-overlap table (CSV or HDF5). See --help and docs/impact.md.
 * Exit status: 0 success, 2 usage error, 1 run failure. */
#include <getopt.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "dem/impact.h"
#include "dem/table.h"

static const char *prog = "dem-contact";

static void usage(FILE *out) {
  fprintf(out,
          "Usage: dem-contact --law ID [--set key=value]... [--config FILE]\n"
          "                   --path a0,a1,a2,... --step DA [--out FILE.csv|FILE.h5] [--json]\n"
          "Quasi-static force-overlap curve (alpha_dot = 0) of the contact law ID along the\n"
          "overlaps a0 -> a1 -> a2 ... (m), each leg cut into equal steps of at most DA (m).\n"
          "\n"
          "  --law ID           contact law (see --list-laws)\n"
          "  --set key=value    particle (R required; rho, E, nu) or law coefficient; repeatable\n"
          "  --config FILE      libconfig file: law, path = [...], step, target, params { ... }\n"
          "  --wall | --pair    reduced radius R* = R (default) or R/2 (equal spheres)\n"
          "  --path LIST        turning points, comma-separated, m\n"
          "  --step DA          largest overlap step, m\n"
          "  --out FILE         table: .h5/.hdf5 -> HDF5, anything else CSV (default: CSV on\n"
          "                     stdout); columns alpha, f, f_el, k, f_adh, contact\n"
          "  --json             one JSON summary object on stdout\n"
          "  --list-laws, --help, --version\n"
          "Exit status: 0 success, 2 usage error, 1 run failure (I/O).\n");
}

enum { OPT_LAW = 256, OPT_SET, OPT_CONFIG, OPT_PATH, OPT_STEP, OPT_OUT, OPT_JSON, OPT_WALL,
       OPT_PAIR, OPT_LIST, OPT_HELP, OPT_VERSION };

static const struct option long_opts[] = {
    {"law", required_argument, NULL, OPT_LAW},   {"set", required_argument, NULL, OPT_SET},
    {"config", required_argument, NULL, OPT_CONFIG},
    {"path", required_argument, NULL, OPT_PATH}, {"step", required_argument, NULL, OPT_STEP},
    {"out", required_argument, NULL, OPT_OUT},   {"json", no_argument, NULL, OPT_JSON},
    {"wall", no_argument, NULL, OPT_WALL},       {"pair", no_argument, NULL, OPT_PAIR},
    {"list-laws", no_argument, NULL, OPT_LIST},  {"help", no_argument, NULL, OPT_HELP},
    {"version", no_argument, NULL, OPT_VERSION}, {NULL, 0, NULL, 0}};

typedef struct {
  dem_table *t;
  int failed;
  double f_max, f_min, a_max, a_min;
} rows_ctx;

static void on_row(double alpha, const dem_normal *n, void *user) {
  rows_ctx *c = user;
  double row[6] = {alpha, n->f, n->f_el, n->k, n->f_adh, (double)n->contact};
  if (dem_table_append(c->t, row, NULL)) c->failed = 1;
  if (n->f > c->f_max) c->f_max = n->f;
  if (n->f < c->f_min) c->f_min = n->f;
  if (alpha > c->a_max) c->a_max = alpha;
  if (alpha < c->a_min) c->a_min = alpha;
}

static int usage_error(const dem_err *e) {
  cli_error(prog, e);
  fprintf(stderr, "Try '%s --help'.\n", prog);
  return CLI_EXIT_USAGE;
}

static json_t *jnum(double v) { return isfinite(v) ? json_real(v) : json_null(); }

int main(int argc, char **argv) {
  dem_params ps;
  dem_params_init(&ps);
  dem_err err = {0};
  cli_config fl;
  cli_config_init(&fl);
  const char *config = NULL, *out = NULL;
  int json = 0, c, rc = DEM_OK;
  opterr = 0;
  while ((c = getopt_long(argc, argv, "", long_opts, NULL)) != -1) {
    switch (c) {
    case OPT_LAW:
      snprintf(fl.law, sizeof fl.law, "%s", optarg);
      break;
    case OPT_SET:
      rc = cli_parse_set(&ps, optarg, &err);
      break;
    case OPT_CONFIG:
      config = optarg;
      break;
    case OPT_PATH:
      rc = cli_parse_list("--path", optarg, fl.path, CLI_PATH_MAX, &fl.npath, &err);
      break;
    case OPT_STEP:
      rc = cli_parse_double("--step", optarg, 1e-18, 1.0, &fl.step, &err);
      break;
    case OPT_OUT:
      out = optarg;
      break;
    case OPT_JSON:
      json = 1;
      break;
    case OPT_WALL:
      fl.target = 0;
      break;
    case OPT_PAIR:
      fl.target = 1;
      break;
    case OPT_LIST:
      cli_list_laws(stdout);
      return CLI_EXIT_OK;
    case OPT_HELP:
      usage(stdout);
      return CLI_EXIT_OK;
    case OPT_VERSION:
      cli_print_version(prog);
      return CLI_EXIT_OK;
    default:
      cli_getopt_error(argv, &err);
      return usage_error(&err);
    }
    if (rc) return usage_error(&err);
  }
  if (cli_no_operands(argc, argv, &err)) return usage_error(&err);
  cli_config cf;
  cli_config_init(&cf);
  if (config && (rc = cli_config_load(config, &cf, &ps, &err))) return usage_error(&err);
  if (!fl.law[0]) memcpy(fl.law, cf.law, sizeof fl.law);
  if (fl.npath == 0) {
    fl.npath = cf.npath;
    memcpy(fl.path, cf.path, sizeof fl.path);
  }
  if (isnan(fl.step)) fl.step = cf.step;
  if (fl.target < 0) fl.target = cf.target;
  if (!fl.law[0]) {
    dem_err_set(&err, DEM_EMISSING, "--law is required (see --list-laws)");
    return usage_error(&err);
  }
  const dem_law *law = cli_find_law(fl.law, &err);
  if (!law) return usage_error(&err);
  if (fl.npath < 1) {
    dem_err_set(&err, DEM_EMISSING, "--path a0,a1,... is required (overlaps in m)");
    return usage_error(&err);
  }
  if (isnan(fl.step)) {
    dem_err_set(&err, DEM_EMISSING, "--step DA is required (m, > 0)");
    return usage_error(&err);
  }
  /* The density only enters damping, which is zero on a quasi-static path. */
  if (!dem_params_find(&ps, "rho")) dem_params_set(&ps, "rho", 1000.0, "default", NULL);
  dem_impact_scene sc;
  if ((rc = dem_impact_setup(&sc, law, &ps, fl.target == 1 ? DEM_TARGET_PAIR : DEM_TARGET_WALL,
                             &err)))
    return usage_error(&err);

  const char *names[] = {"alpha", "f", "f_el", "k", "f_adh", "contact"};
  const char *units[] = {"m", "N", "N", "N/m", "N", "-"};
  rows_ctx ctx = {dem_table_create(6, names, units, &err), 0, -INFINITY, INFINITY, -INFINITY,
                  INFINITY};
  if (!ctx.t) return cli_error(prog, &err), CLI_EXIT_RUN;
  dem_table_set_attr(ctx.t, "law", law->name, NULL);
  char buf[512];
  size_t used = 0;
  for (int i = 0; i < ps.n && used < sizeof buf - 40; i++)
    used += (size_t)snprintf(buf + used, sizeof buf - used, "%s%s=%.10g", i ? " " : "",
                             ps.p[i].key, ps.p[i].value);
  dem_table_set_attr(ctx.t, "params", buf, NULL);
  rc = dem_contact_path(&sc.law, &sc.geom, fl.path, fl.npath, fl.step, on_row, &ctx, &err);
  if (rc) {
    dem_table_free(ctx.t);
    return usage_error(&err); /* path errors are bad input */
  }
  if (ctx.failed) {
    dem_table_free(ctx.t);
    dem_err_set(&err, DEM_ENOMEM, "out of memory for the table");
    cli_error(prog, &err);
    return CLI_EXIT_RUN;
  }
  int code = CLI_EXIT_OK;
  if (out) {
    if ((rc = dem_table_write(ctx.t, out, &err))) {
      cli_error(prog, &err);
      code = CLI_EXIT_RUN;
    }
  } else if (!json) {
    for (int j = 0; j < 6; j++) printf("%s%s [%s]", j ? "," : "", names[j], units[j]);
    putchar('\n');
    for (long r = 0; r < dem_table_nrows(ctx.t); r++)
      for (int j = 0; j < 6; j++) printf("%.12g%c", dem_table_get(ctx.t, r, j), j == 5 ? '\n' : ',');
  }
  if (json && code == CLI_EXIT_OK) {
    json_t *o = json_object();
    json_object_set_new(o, "law", json_string(law->name));
    json_object_set_new(o, "points", json_integer(dem_table_nrows(ctx.t)));
    json_object_set_new(o, "alpha_min", jnum(ctx.a_min));
    json_object_set_new(o, "alpha_max", jnum(ctx.a_max));
    json_object_set_new(o, "f_max", jnum(ctx.f_max));
    json_object_set_new(o, "f_min", jnum(ctx.f_min));
    json_object_set_new(o, "out", out ? json_string(out) : json_null());
    char *s = json_dumps(o, JSON_COMPACT | JSON_REAL_PRECISION(12));
    json_decref(o);
    if (s) {
      puts(s);
      free(s);
    } else {
      code = CLI_EXIT_RUN;
    }
  }
  dem_table_free(ctx.t);
  return code;
}
