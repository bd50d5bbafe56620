/* calibrate/curve.h — helpers on sampled force-overlap curves (targets.c). */
#ifndef CAL_CURVE_H
#define CAL_CURVE_H

/* Label each point with the index of its monotone run (branch) of the overlap sequence;
 * a turning point ends one run and starts the next. Returns the number of runs. */
int cal_runs(const double *a, int n, int *run);
/* +1 if the sequence first increases, -1 if it first decreases, 0 if constant. */
int cal_first_direction(const double *a, int n);
/* f at overlap x on run r, linearly interpolated (clamped at the run's ends). */
double cal_interp_run(const double *a, const double *f, const int *run, int n, int r, double x);
/* f_max, alpha_p, pull-off force of a curve; has[q] says which exist. */
void cal_curve_summary(const double *a, const double *f, int n, double out[3], int has[3]);

#endif
