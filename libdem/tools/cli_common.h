/* cli_common.h — what the dem-* programs share: exit codes, number parsing with messages
 * naming the flag, the libconfig configuration file, --set, --list-laws, --version.
 *
 * Conventions of every dem-* program: exit 0 on success, 2 on a usage error (bad flag, bad
 * value, bad configuration file), 1 when the run itself fails (instability, I/O error).
 * Command-line flags override the configuration file; --set overrides its params group.
 */
#ifndef DEM_CLI_COMMON_H
#define DEM_CLI_COMMON_H

#include <stdio.h>

#include "dem/contact.h"
#include "dem/error.h"
#include "dem/params.h"

enum { CLI_EXIT_OK = 0, CLI_EXIT_RUN = 1, CLI_EXIT_USAGE = 2 };

#define CLI_PATH_MAX 256

/* Values a configuration file may give (unset: NAN, -1 or ""). */
typedef struct cli_config {
  char law[64];
  double velocity;           /* m/s */
  int sticking;              /* 0/1, -1 unset */
  double v_min, v_max;       /* m/s */
  int target;                /* 0 wall, 1 pair, -1 unset */
  double dt_factor;
  int dt_rule;               /* 0 rayleigh, 1 mass-spring, -1 unset */
  int integrator;            /* 0 verlet, 1 reference, -1 unset */
  double rtol;
  int clip_tensile;          /* -1 unset */
  int npath;                 /* turning points, 0 unset */
  double path[CLI_PATH_MAX]; /* m */
  double step;               /* m */
} cli_config;

void cli_config_init(cli_config *c);
/* Read a libconfig file: top-level law, velocity, sticking, v_min, v_max, target
 * ("wall"|"pair"), dt_factor, dt_rule ("rayleigh"|"mass-spring"), integrator
 * ("verlet"|"reference"), rtol, clip_tensile, path (list of overlaps), step, and a group
 * params { key = value; ... } whose values go to ps with origin "file:line". Errors name
 * file:line, the field and what is allowed. */
int cli_config_load(const char *path, cli_config *c, dem_params *ps, dem_err *err);

/* A number given to a flag, in [lo, hi]; the message names the flag, value and range. */
int cli_parse_double(const char *flag, const char *text, double lo, double hi, double *out,
                     dem_err *err);
/* "a,b,c" -> values (at most max). */
int cli_parse_list(const char *flag, const char *text, double *out, int max, int *n,
                   dem_err *err);
/* --set key=value (origin "--set"). */
int cli_parse_set(dem_params *ps, const char *text, dem_err *err);
/* Keyword -> index in a NULL-terminated list, or an error naming flag and allowed words. */
int cli_parse_word(const char *flag, const char *text, const char *const *words, int *out,
                   dem_err *err);

/* The law named by id, or an error listing the known ids. */
const dem_law *cli_find_law(const char *id, dem_err *err);
/* Every law with its coefficients, units, ranges and defaults. */
void cli_list_laws(FILE *out);
void cli_print_version(const char *prog);
/* Warns on stderr when `threads` OpenMP threads would share the cores with other work (other
 * runnable threads now, from /proc/loadavg, + threads > online cores): libgomp's spinning
 * barriers, several per time step, then slow a run by 5-40x (measured in CI). Returns 1 if it
 * warned. */
int cli_warn_contention(const char *prog, int threads);
/* "prog: message" on stderr. */
void cli_error(const char *prog, const dem_err *err);
/* The error of getopt_long's '?' return: a missing or unexpected value (optopt set) or an
 * unknown option. Always returns DEM_EINVAL. */
int cli_getopt_error(char *const *argv, dem_err *err);
/* DEM_EINVAL naming the first operand if any is left after the options, else DEM_OK. */
int cli_no_operands(int argc, char *const *argv, dem_err *err);

#endif
