/* dem-impact: normal impact of a sphere on a wall (or an equal sphere) through any contact
 * law: one impact, an e(v) sweep, or the critical sticking velocity. See --help and
 * docs/impact.md. Exit status: 0 success, 2 usage error, 1 run failure. */
#include <getopt.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli_common.h"
#include "dem/impact.h"
#include "dem/table.h"

static const char *prog = "dem-impact";

static void usage(FILE *out) {
  fprintf(out,
          "Usage: dem-impact --law ID [--set key=value]... [--config FILE]\n"
          "                  (--velocity V | --sticking [--v-min V --v-max V] | --sweep V1:V2:N)\n"
          "                  [options]\n"
          "Normal impact of a sphere on a flat wall (default) or on an equal sphere, integrated\n"
          "as one degree of freedom through the contact law ID. SI units throughout.\n"
          "\n"
          "Scene and law:\n"
          "  --law ID              contact law (see --list-laws)\n"
          "  --set key=value       particle (R, rho, E, nu) or law coefficient; repeatable\n"
          "  --config FILE         libconfig file: law, velocity, sticking, v_min, v_max, target,\n"
          "                        dt_factor, dt_rule, integrator, rtol, clip_tensile and a group\n"
          "                        params { R = 2.45e-6; ... }; flags and --set override it\n"
          "  --wall | --pair       target: flat wall (R* = R, m* = m) or equal sphere (R/2, m/2)\n"
          "What to compute:\n"
          "  --velocity V          one impact at V m/s, (0, 1e4]\n"
          "  --sticking            critical sticking velocity by bracketing and bisection\n"
          "  --v-min V, --v-max V  its search interval (default 1e-3 .. 100 m/s)\n"
          "  --tol T               its relative tolerance (default 1e-4)\n"
          "  --sweep V1:V2:N       N impacts, velocities log-spaced from V1 to V2 (e(v) table)\n"
          "Integration:\n"
          "  --integrator verlet|reference   velocity Verlet (default) or GSL rk8pd reference\n"
          "  --dt-factor F         time step = F x rule step (default 0.01), (0, 100]\n"
          "  --dt-rule rayleigh|mass-spring  Rayleigh (thesis 3.1, needs E and nu; default when\n"
          "                        they are given) or sqrt(m*/k) (thesis 4.29-4.31)\n"
          "  --rtol R              reference integrator relative tolerance (default 1e-10)\n"
          "  --clip-tensile        no tensile total force (non-adhesive laws): the contact ends\n"
          "                        when the force reaches zero\n"
          "  --t-max-factor N      give up (stuck) after N half periods (default 200)\n"
          "Output:\n"
          "  --json                one JSON object on stdout\n"
          "  --trace FILE          force-overlap trace CSV of a single impact\n"
          "  --trace-every N       every N-th step in the trace (default 1)\n"
          "  --out FILE            sweep table, .csv or .h5 (default: CSV on stdout)\n"
          "  --list-laws           every law with its coefficients, units, ranges, defaults\n"
          "  --help, --version\n"
          "Exit status: 0 success, 2 usage error, 1 run failure (instability, I/O).\n");
}

enum {
  OPT_SET = 256, OPT_CONFIG, OPT_VEL, OPT_STICK, OPT_VMIN, OPT_VMAX, OPT_TOL, OPT_SWEEP,
  OPT_WALL, OPT_PAIR, OPT_DTF, OPT_DTR, OPT_INTEG, OPT_RTOL, OPT_CLIP, OPT_TMAX, OPT_JSON,
  OPT_TRACE, OPT_TEVERY, OPT_OUT, OPT_LIST, OPT_HELP, OPT_VERSION, OPT_LAW
};

static const struct option long_opts[] = {
    {"law", required_argument, NULL, OPT_LAW},
    {"set", required_argument, NULL, OPT_SET},
    {"config", required_argument, NULL, OPT_CONFIG},
    {"velocity", required_argument, NULL, OPT_VEL},
    {"sticking", no_argument, NULL, OPT_STICK},
    {"v-min", required_argument, NULL, OPT_VMIN},
    {"v-max", required_argument, NULL, OPT_VMAX},
    {"tol", required_argument, NULL, OPT_TOL},
    {"sweep", required_argument, NULL, OPT_SWEEP},
    {"wall", no_argument, NULL, OPT_WALL},
    {"pair", no_argument, NULL, OPT_PAIR},
    {"dt-factor", required_argument, NULL, OPT_DTF},
    {"dt-rule", required_argument, NULL, OPT_DTR},
    {"integrator", required_argument, NULL, OPT_INTEG},
    {"rtol", required_argument, NULL, OPT_RTOL},
    {"clip-tensile", no_argument, NULL, OPT_CLIP},
    {"t-max-factor", required_argument, NULL, OPT_TMAX},
    {"json", no_argument, NULL, OPT_JSON},
    {"trace", required_argument, NULL, OPT_TRACE},
    {"trace-every", required_argument, NULL, OPT_TEVERY},
    {"out", required_argument, NULL, OPT_OUT},
    {"list-laws", no_argument, NULL, OPT_LIST},
    {"help", no_argument, NULL, OPT_HELP},
    {"version", no_argument, NULL, OPT_VERSION},
    {NULL, 0, NULL, 0}};

static json_t *jnum(double v) { return isfinite(v) ? json_real(v) : json_null(); }

static void result_json(json_t *o, const dem_impact_result *r) {
  json_object_set_new(o, "v_impact", jnum(r->v_impact));
  json_object_set_new(o, "e", jnum(r->e));
  json_object_set_new(o, "alpha_max", jnum(r->alpha_max));
  json_object_set_new(o, "alpha_p", jnum(r->alpha_p));
  json_object_set_new(o, "f_max", jnum(r->f_max));
  json_object_set_new(o, "f_pulloff", jnum(r->f_pulloff));
  json_object_set_new(o, "t_contact", jnum(r->t_contact));
  json_object_set_new(o, "stuck", json_boolean(r->stuck));
  json_object_set_new(o, "v_rebound", jnum(r->v_rebound));
  json_object_set_new(o, "w_damp", jnum(r->w_damp));
  json_object_set_new(o, "dt", jnum(r->dt));
  json_object_set_new(o, "steps", json_integer(r->steps));
}

static int print_json(json_t *o) {
  char *s = json_dumps(o, JSON_COMPACT | JSON_REAL_PRECISION(12));
  json_decref(o);
  if (!s) return CLI_EXIT_RUN;
  puts(s);
  free(s);
  return CLI_EXIT_OK;
}

static void result_text(const dem_impact_result *r) {
  printf("v_impact  = %.10g m/s\n", r->v_impact);
  printf("e         = %.10g\n", r->e);
  printf("v_rebound = %.10g m/s\n", r->v_rebound);
  printf("alpha_max = %.10g m\n", r->alpha_max);
  printf("alpha_p   = %.10g m\n", r->alpha_p);
  printf("f_max     = %.10g N\n", r->f_max);
  printf("f_pulloff = %.10g N\n", r->f_pulloff);
  printf("t_contact = %.10g s\n", r->t_contact);
  printf("stuck     = %s\n", r->stuck ? "true" : "false");
  printf("w_damp    = %.10g J\n", r->w_damp);
  printf("dt        = %.6g s (%ld steps)\n", r->dt, r->steps);
}

static int usage_error(const dem_err *e) {
  cli_error(prog, e);
  fprintf(stderr, "Try '%s --help'.\n", prog);
  return CLI_EXIT_USAGE;
}

int main(int argc, char **argv) {
  dem_params ps;
  dem_params_init(&ps);
  dem_err err = {0};
  cli_config fl; /* from flags */
  cli_config_init(&fl);
  const char *config = NULL, *trace = NULL, *out = NULL, *sweep = NULL;
  double tol = 1e-4, tmax = NAN, v;
  int json = 0, trace_every = 1;
  static const char *const w_rule[] = {"rayleigh", "mass-spring", NULL};
  static const char *const w_integ[] = {"verlet", "reference", NULL};
  int c, rc = DEM_OK;
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
    case OPT_VEL:
      rc = cli_parse_double("--velocity", optarg, -INFINITY, INFINITY, &fl.velocity, &err);
      if (!rc && !(fl.velocity > 0.0 && fl.velocity <= 1e4))
        rc = dem_err_set(&err, DEM_ERANGE,
                         "--velocity: %g m/s is outside the allowed range (0, 1e4] m/s",
                         fl.velocity);
      break;
    case OPT_STICK:
      fl.sticking = 1;
      break;
    case OPT_VMIN:
      rc = cli_parse_double("--v-min", optarg, 1e-9, 1e4, &fl.v_min, &err);
      break;
    case OPT_VMAX:
      rc = cli_parse_double("--v-max", optarg, 1e-9, 1e4, &fl.v_max, &err);
      break;
    case OPT_TOL:
      rc = cli_parse_double("--tol", optarg, 1e-12, 0.1, &tol, &err);
      break;
    case OPT_SWEEP:
      sweep = optarg;
      break;
    case OPT_WALL:
      fl.target = 0;
      break;
    case OPT_PAIR:
      fl.target = 1;
      break;
    case OPT_DTF:
      rc = cli_parse_double("--dt-factor", optarg, 1e-6, 100.0, &fl.dt_factor, &err);
      break;
    case OPT_DTR:
      rc = cli_parse_word("--dt-rule", optarg, w_rule, &fl.dt_rule, &err);
      break;
    case OPT_INTEG:
      rc = cli_parse_word("--integrator", optarg, w_integ, &fl.integrator, &err);
      break;
    case OPT_RTOL:
      rc = cli_parse_double("--rtol", optarg, 1e-14, 1e-3, &fl.rtol, &err);
      break;
    case OPT_CLIP:
      fl.clip_tensile = 1;
      break;
    case OPT_TMAX:
      rc = cli_parse_double("--t-max-factor", optarg, 1.0, 1e7, &tmax, &err);
      break;
    case OPT_JSON:
      json = 1;
      break;
    case OPT_TRACE:
      trace = optarg;
      break;
    case OPT_TEVERY:
      rc = cli_parse_double("--trace-every", optarg, 1, 1e9, &v, &err);
      trace_every = (int)v;
      break;
    case OPT_OUT:
      out = optarg;
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

  /* Configuration file under the flags. */
  cli_config cf;
  cli_config_init(&cf);
  if (config && (rc = cli_config_load(config, &cf, &ps, &err))) return usage_error(&err);
  if (!fl.law[0]) memcpy(fl.law, cf.law, sizeof fl.law);
#define MERGE_D(f) if (isnan(fl.f)) fl.f = cf.f
#define MERGE_I(f) if (fl.f < 0) fl.f = cf.f
  /* What to compute: a mode given by a flag replaces the file's mode. */
  if (isnan(fl.velocity) && fl.sticking != 1 && !sweep) {
    MERGE_D(velocity);
    MERGE_I(sticking);
  }
  MERGE_D(v_min); MERGE_D(v_max); MERGE_D(dt_factor); MERGE_D(rtol);
  MERGE_I(target); MERGE_I(dt_rule); MERGE_I(integrator); MERGE_I(clip_tensile);
  if (!fl.law[0]) {
    dem_err_set(&err, DEM_EMISSING, "--law is required (see --list-laws)");
    return usage_error(&err);
  }
  const dem_law *law = cli_find_law(fl.law, &err);
  if (!law) return usage_error(&err);
  int modes = (!isnan(fl.velocity)) + (fl.sticking == 1) + (sweep != NULL);
  if (modes != 1) {
    dem_err_set(&err, DEM_EINVAL,
                "give exactly one of --velocity V, --sticking or --sweep V1:V2:N (got %d)", modes);
    return usage_error(&err);
  }
  double sw_lo = 0, sw_hi = 0;
  int sw_n = 0;
  if (sweep) {
    char extra;
    if (sscanf(sweep, "%lf:%lf:%d%c", &sw_lo, &sw_hi, &sw_n, &extra) != 3 || !(sw_lo > 0) ||
        !(sw_hi >= sw_lo) || sw_hi > 1e4 || sw_n < 1 || sw_n > 100000) {
      dem_err_set(&err, DEM_EINVAL,
                  "--sweep: '%s' must be V1:V2:N with 0 < V1 <= V2 <= 1e4 m/s and 1 <= N <= "
                  "100000",
                  sweep);
      return usage_error(&err);
    }
  }
  if (trace && isnan(fl.velocity)) {
    dem_err_set(&err, DEM_EINVAL, "--trace: only with --velocity (a single impact)");
    return usage_error(&err);
  }

  dem_impact_scene sc;
  if ((rc = dem_impact_setup(&sc, law, &ps, fl.target == 1 ? DEM_TARGET_PAIR : DEM_TARGET_WALL,
                             &err)))
    return usage_error(&err);
  dem_impact_opts o;
  dem_impact_opts_default(&o);
  if (!isnan(fl.dt_factor)) o.dt_factor = fl.dt_factor;
  if (fl.dt_rule >= 0) o.dt_rule = fl.dt_rule ? DEM_DT_MASS_SPRING : DEM_DT_RAYLEIGH;
  if (fl.dt_rule == 0 && (isnan(sc.E) || isnan(sc.nu))) {
    dem_err_set(&err, DEM_EMISSING, "--dt-rule rayleigh needs the particle's E and nu (--set)");
    return usage_error(&err);
  }
  if (fl.integrator >= 0)
    o.integrator = fl.integrator ? DEM_INTEGRATOR_REFERENCE : DEM_INTEGRATOR_VERLET;
  if (!isnan(fl.rtol)) o.rtol = fl.rtol;
  if (fl.clip_tensile > 0) o.clip_tensile = 1;
  if (!isnan(tmax)) o.t_max_factor = tmax;
  o.trace_every = trace_every;

  if (fl.sticking == 1) {
    double lo = isnan(fl.v_min) ? 1e-3 : fl.v_min, hi = isnan(fl.v_max) ? 100.0 : fl.v_max, vs;
    rc = dem_impact_sticking(&sc, &o, lo, hi, tol, &vs, &err);
    if (rc) {
      cli_error(prog, &err);
      return CLI_EXIT_RUN;
    }
    if (json) {
      json_t *j = json_object();
      json_object_set_new(j, "law", json_string(law->name));
      json_object_set_new(j, "v_stick", jnum(vs));
      json_object_set_new(j, "v_min", jnum(lo));
      json_object_set_new(j, "v_max", jnum(hi));
      json_object_set_new(j, "tol", jnum(tol));
      return print_json(j);
    }
    printf("v_stick = %.10g m/s\n", vs);
    return CLI_EXIT_OK;
  }

  if (sweep) {
    const char *names[] = {"v_impact", "e", "alpha_max", "alpha_p", "f_max", "f_pulloff",
                           "t_contact", "stuck"};
    const char *units[] = {"m/s", "-", "m", "m", "N", "N", "s", "-"};
    dem_table *t = dem_table_create(8, names, units, &err);
    if (!t) return cli_error(prog, &err), CLI_EXIT_RUN;
    dem_table_set_attr(t, "law", law->name, NULL);
    json_t *arr = json ? json_array() : NULL;
    for (int i = 0; i < sw_n; i++) {
      double vi = sw_n == 1 ? sw_lo : sw_lo * pow(sw_hi / sw_lo, (double)i / (sw_n - 1));
      dem_impact_result r;
      if ((rc = dem_impact_run(&sc, &o, vi, &r, &err))) {
        cli_error(prog, &err);
        dem_table_free(t);
        json_decref(arr);
        return CLI_EXIT_RUN;
      }
      double row[8] = {r.v_impact, r.e, r.alpha_max, r.alpha_p, r.f_max, r.f_pulloff,
                       r.t_contact, (double)r.stuck};
      dem_table_append(t, row, NULL);
      if (arr) {
        json_t *jo = json_object();
        result_json(jo, &r);
        json_array_append_new(arr, jo);
      }
    }
    int code = CLI_EXIT_OK;
    if (out && (rc = dem_table_write(t, out, &err))) {
      cli_error(prog, &err);
      code = CLI_EXIT_RUN;
    } else if (!out && !json) {
      for (int j = 0; j < 8; j++) printf("%s%s [%s]", j ? "," : "", names[j], units[j]);
      putchar('\n');
      for (long r = 0; r < dem_table_nrows(t); r++)
        for (int j = 0; j < 8; j++) printf("%.12g%c", dem_table_get(t, r, j), j == 7 ? '\n' : ',');
    }
    dem_table_free(t);
    if (arr) {
      json_t *j = json_object();
      json_object_set_new(j, "law", json_string(law->name));
      json_object_set_new(j, "sweep", arr);
      if (code == CLI_EXIT_OK) return print_json(j);
      json_decref(j);
    }
    return code;
  }

  /* One impact. */
  char tmp[4200] = "";
  if (trace) {
    snprintf(tmp, sizeof tmp, "%s.tmp%ld", trace, (long)getpid());
    o.trace = fopen(tmp, "w");
    if (!o.trace) {
      dem_err_set(&err, DEM_EIO, "--trace: cannot write '%s'", trace);
      cli_error(prog, &err);
      return CLI_EXIT_RUN;
    }
  }
  dem_impact_result r;
  rc = dem_impact_run(&sc, &o, fl.velocity, &r, &err);
  if (o.trace) {
    int bad = ferror(o.trace);
    if (fclose(o.trace) != 0) bad = 1;
    if (rc || bad || rename(tmp, trace) != 0) {
      remove(tmp);
      if (!rc) {
        dem_err_set(&err, DEM_EIO, "--trace: cannot write '%s'", trace);
        rc = DEM_EIO;
      }
    }
  }
  if (rc) {
    cli_error(prog, &err);
    return CLI_EXIT_RUN;
  }
  if (json) {
    json_t *j = json_object();
    json_object_set_new(j, "law", json_string(law->name));
    json_object_set_new(j, "integrator",
                        json_string(o.integrator == DEM_INTEGRATOR_REFERENCE ? "reference"
                                                                             : "verlet"));
    result_json(j, &r);
    return print_json(j);
  }
  result_text(&r);
  return CLI_EXIT_OK;
}
