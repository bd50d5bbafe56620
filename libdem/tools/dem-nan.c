/* dem-nan: the characteristic impact velocities of the improved linear law (second seed,
 * section 4) over a range of yield pressures p_y — the data of the paper's Fig 9 — computed
 * with the library's correlation functions (dem/nan.h), never re-derived here:
 *   V_s   adhesive sticking velocity, eq (73)            dem_nan_vs
 *   V_y0  yield velocity without adhesion, eq (74)       dem_nan_vy0
 *   V_y^2 yield velocity with adhesion, eq (75), signed  dem_nan_vy2 (< 0: adhesion-induced
 *         yield, the shaded zone of Fig 9)
 *   V_ys  plastic adhesive sticking velocity, eqs (77)-(79)   dem_nan_vys
 *   p_y,crit eq (80) (dem_nan_py_crit) and CY eq (81) (dem_nan_cy).
 * k_el = pi R* p_y (eq 52) and k_p = k_el as the paper does for Fig 9, unless `ke`/`kp` are
 * given; k_el/k_cl from eq (38) unless `kc` is given. Impact on a wall (m* = particle mass,
 * R* = R) or, with --pair, on an equal sphere (R* = R/2, m* = m/2). No damping (e0 = 1).
 *
 * Usage: dem-nan --set R=... --set rho=... --set E=... --set nu=... [--set wall_E=...]
 *                [--set wall_nu=...] --set gamma=... --py P1:P2:N [--wall|--pair]
 *                [--out FILE.csv|FILE.h5] [--json]
 * Exit status: 0 success, 2 usage error, 1 run failure.
 */
#include <getopt.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "dem/material.h"
#include "dem/nan.h"
#include "dem/table.h"

static const char *prog = "dem-nan";

static void usage(FILE *out) {
  fprintf(out,
          "Usage: dem-nan --set key=value... --py P1:P2:N [--wall | --pair]\n"
          "               [--out FILE.csv|FILE.h5] [--json]\n"
          "Characteristic velocities of the improved linear law (second seed, eqs 73-81)\n"
          "over N yield pressures log-spaced from P1 to P2 (Pa): the data of its Fig 9.\n"
          "\n"
          "  --set key=value  R (m), rho (kg/m^3), E (Pa), nu, gamma (J/m^2) required;\n"
          "                   wall_E, wall_nu (default: the particle's; 1e30 = rigid);\n"
          "                   ke (k_el, default pi R* p_y, eq 52), kp (default k_el),\n"
          "                   kc (k_cl, default eq 38)\n"
          "  --py P1:P2:N     yield pressures, Pa (0 < P1 < P2, 2 <= N <= 100000)\n"
          "  --wall | --pair  impact on a wall (default) or on an equal sphere\n"
          "  --out FILE       table (.h5/.hdf5 -> HDF5, else CSV; default CSV on stdout):\n"
          "                   py, V_s, V_y0, V_y (sign of V_y^2 times sqrt|V_y^2|), V_ys, f_y,\n"
          "                   f_0, k_el, CY\n"
          "  --json           a JSON summary (V_s, p_y,crit, the p_y where V_ys reaches V_s)\n"
          "  --help, --version\n"
          "Exit status: 0 success, 2 usage error, 1 run failure.\n");
}

enum { OPT_SET = 256, OPT_PY, OPT_OUT, OPT_JSON, OPT_WALL, OPT_PAIR, OPT_HELP, OPT_VERSION };

static const struct option long_opts[] = {
    {"set", required_argument, NULL, OPT_SET}, {"py", required_argument, NULL, OPT_PY},
    {"out", required_argument, NULL, OPT_OUT}, {"json", no_argument, NULL, OPT_JSON},
    {"wall", no_argument, NULL, OPT_WALL},     {"pair", no_argument, NULL, OPT_PAIR},
    {"help", no_argument, NULL, OPT_HELP},     {"version", no_argument, NULL, OPT_VERSION},
    {NULL, 0, NULL, 0}};

static const char *const known[] = {"R",  "rho", "E",  "nu", "wall_E", "wall_nu",
                                    "gamma", "ke", "kp", "kc", NULL};

static int need(const dem_params *ps, const char *key, double *v, dem_err *err) {
  if (!dem_params_get(ps, key, v))
    return dem_err_set(err, DEM_EMISSING, "missing --set %s=...", key);
  if (!isfinite(*v) || !(*v > 0.0) )
    return dem_err_set(err, DEM_ERANGE, "%s%s = %g must be finite and > 0",
                       dem_params_origin(ps, key), key, *v);
  return DEM_OK;
}

int main(int argc, char **argv) {
  dem_params ps;
  dem_params_init(&ps);
  dem_err err = {0};
  const char *out = NULL;
  int json = 0, pair = 0, n = 0;
  double p1 = NAN, p2 = NAN;
  int o;
  while ((o = getopt_long(argc, argv, "", long_opts, NULL)) != -1) {
    switch (o) {
      case OPT_SET:
        if (cli_parse_set(&ps, optarg, &err)) goto usage_error;
        break;
      case OPT_PY: {
        char a[64], b[64];
        int nn = 0;
        if (sscanf(optarg, "%63[^:]:%63[^:]:%d", a, b, &nn) != 3 ||
            cli_parse_double("--py P1", a, 1e-300, 1e15, &p1, &err) ||
            cli_parse_double("--py P2", b, 1e-300, 1e15, &p2, &err) || !(p2 > p1) || nn < 2 ||
            nn > 100000) {
          if (!err.code)
            dem_err_set(&err, DEM_ERANGE,
                        "--py '%s': need P1:P2:N with 0 < P1 < P2 (Pa) and 2 <= N <= 100000",
                        optarg);
          goto usage_error;
        }
        n = nn;
        break;
      }
      case OPT_OUT: out = optarg; break;
      case OPT_JSON: json = 1; break;
      case OPT_WALL: pair = 0; break;
      case OPT_PAIR: pair = 1; break;
      case OPT_HELP: usage(stdout); return CLI_EXIT_OK;
      case OPT_VERSION: cli_print_version(prog); return CLI_EXIT_OK;
      default: usage(stderr); return CLI_EXIT_USAGE;
    }
  }
  if (optind < argc) {
    dem_err_set(&err, DEM_EINVAL, "unexpected argument '%s'", argv[optind]);
    goto usage_error;
  }
  if (n == 0) {
    dem_err_set(&err, DEM_EMISSING, "--py P1:P2:N is required");
    goto usage_error;
  }
  for (int i = 0; i < ps.n; i++) {
    int ok = 0;
    for (int k = 0; known[k]; k++) ok |= strcmp(ps.p[i].key, known[k]) == 0;
    if (!ok) {
      dem_err_set(&err, DEM_ENOTFOUND,
                  "%sunknown key '%s' (known: R, rho, E, nu, wall_E, wall_nu, gamma, ke, kp, kc)",
                  dem_params_origin(&ps, ps.p[i].key), ps.p[i].key);
      goto usage_error;
    }
  }
  double R, rho, E, nu, gamma;
  if (need(&ps, "R", &R, &err) || need(&ps, "rho", &rho, &err) || need(&ps, "E", &E, &err) ||
      need(&ps, "gamma", &gamma, &err))
    goto usage_error;
  if (!dem_params_get(&ps, "nu", &nu) || !(nu > -1.0 && nu <= 0.5)) {
    dem_err_set(&err, DEM_ERANGE, "--set nu=... is required, in (-1, 0.5]");
    goto usage_error;
  }
  double wE = dem_params_get_or(&ps, "wall_E", E), wnu = dem_params_get_or(&ps, "wall_nu", nu);
  const double Es = dem_reduced_modulus(E, nu, wE, wnu);
  const double Rs = pair ? 0.5 * R : R, m = dem_sphere_mass(R, rho) * (pair ? 0.5 : 1.0);
  const double kel_in = dem_params_get_or(&ps, "ke", -1.0), kp_in = dem_params_get_or(&ps, "kp", -1.0);
  const double kc_in = dem_params_get_or(&ps, "kc", -1.0);

  static const char *const names[] = {"py", "V_s", "V_y0", "V_y", "V_ys", "f_y", "f_0", "k_el",
                                      "CY"};
  static const char *const units[] = {"Pa", "m/s", "m/s", "m/s", "m/s", "N", "N", "N/m", "-"};
  dem_table *t = dem_table_create(9, names, units, &err);
  if (!t) goto run_error;
  const double vs = dem_nan_vs(Rs, Es, gamma, m), pyc = dem_nan_py_crit(Rs, Es, gamma);
  double py_vs = NAN; /* the smallest p_y of the grid where V_ys = V_s */
  for (int i = 0; i < n; i++) {
    double py = p1 * pow(p2 / p1, (double)i / (n - 1));
    dem_nan_input in = {Rs, Es, gamma, py, kel_in, kp_in, -1.0, 46, 59};
    if (kc_in > 0.0) in.kel_kcl = (kel_in > 0.0 ? kel_in : dem_nan_kel_py(Rs, py)) / kc_in;
    dem_nan_coeffs k;
    double vys = NAN;
    if (dem_nan_coeffs_init(&k, &in, &err) == DEM_OK) {
      if (dem_nan_vys(&k, m, &vys, NULL, &err)) goto run_error;
      double vy2 = dem_nan_vy2(&k, m);
      double row[9] = {py, vs, dem_nan_vy0(&k, m), copysign(sqrt(fabs(vy2)), vy2), vys, k.fy,
                       k.f0, k.kel, dem_nan_cy(Rs, Es, gamma, py)};
      if (dem_table_append(t, row, &err)) goto run_error;
      if (isnan(py_vs) && vys <= vs * (1.0 + 1e-12)) py_vs = py;
    } else {
      /* The model with its own correlations cannot be evaluated here (e.g. eq 38 gives
       * k_el/k_cl <= 0 at small p_y): a row of NaN keeps the grid, the message goes to
       * stderr once. */
      static int told = 0;
      if (!told) fprintf(stderr, "%s: p_y = %g Pa: %s (row left as nan)\n", prog, py, err.msg);
      told = 1;
      double row[9] = {py, vs, NAN, NAN, NAN, NAN, NAN, NAN, dem_nan_cy(Rs, Es, gamma, py)};
      if (dem_table_append(t, row, &err)) goto run_error;
    }
  }
  char buf[512];
  snprintf(buf, sizeof buf, "R = %g m, rho = %g kg/m^3, E* = %g Pa, gamma = %g J/m^2, %s", R,
           rho, Es, gamma, pair ? "pair" : "wall");
  dem_table_set_attr(t, "params", buf, NULL);
  snprintf(buf, sizeof buf, "%.10g", pyc);
  dem_table_set_attr(t, "py_crit [Pa] (eq 80)", buf, NULL);
  snprintf(buf, sizeof buf, "%.10g", vs);
  dem_table_set_attr(t, "V_s [m/s] (eq 73)", buf, NULL);
  if (out) {
    if (dem_table_write(t, out, &err)) goto run_error;
  } else if (!json) {
    printf("# py_crit [Pa] (eq 80): %.10g\n# V_s [m/s] (eq 73): %.10g\n", pyc, vs);
    for (int c = 0; c < 9; c++) printf("%s%s [%s]", c ? "," : "", names[c], units[c]);
    printf("\n");
    for (long r = 0; r < dem_table_nrows(t); r++)
      for (int c = 0; c < 9; c++) printf("%.10g%s", dem_table_get(t, r, c), c < 8 ? "," : "\n");
  }
  if (json) {
    json_t *j = json_object();
    json_object_set_new(j, "V_s", json_real(vs));
    json_object_set_new(j, "py_crit", json_real(pyc));
    json_object_set_new(j, "py_vys_equals_vs", isnan(py_vs) ? json_null() : json_real(py_vs));
    json_object_set_new(j, "E_star", json_real(Es));
    json_object_set_new(j, "m_star", json_real(m));
    json_object_set_new(j, "R_star", json_real(Rs));
    json_object_set_new(j, "rows", json_integer(dem_table_nrows(t)));
    char *s = json_dumps(j, JSON_INDENT(2) | JSON_REAL_PRECISION(10));
    if (s) puts(s);
    free(s);
    json_decref(j);
  }
  dem_table_free(t);
  return CLI_EXIT_OK;
run_error:
  dem_table_free(t);
  cli_error(prog, &err);
  return CLI_EXIT_RUN;
usage_error:
  cli_error(prog, &err);
  fprintf(stderr, "(%s --help for usage)\n", prog);
  return CLI_EXIT_USAGE;
}
