/* dem/analysis.h — analysis of ball indentation: hardness, contact depth, plateau statistics,
 * stress tensor and solids fraction in bins, dimensionless strain rate.
 *
 * Pure functions over plain arrays, independent of the engine. Vectors are interleaved,
 * x[3*i + k] for k = 0, 1, 2 (the engine's layout); z (k = 2) is vertical, up. The indenter
 * moves in -z. Units: SI throughout (m, N, Pa, s). docs/analysis.md derives every formula and
 * states the estimators and their assumptions.
 *
 * Sources: thesis = Pasha 2013 (../shared/seeds/000_*.txt): hardness eqs 2.7-2.9 and the
 * contact depth of 2.3.5, dimensionless penetration 5.5, stress 5.1 / A4.2 (Bagi 1996),
 * hydrostatic 5.2 and deviatoric 5.3 stress, bins of Figs 5.8 / 5.13 / 5.18, solids fraction
 * of Fig 6.4, dimensionless strain rate 5.4 / 7.1.
 *
 * Closed formulas return a double (NaN outside their domain, stated per function); array
 * routines return a dem_status and write a message naming the field, value and range.
 */
#ifndef DEM_ANALYSIS_H
#define DEM_ANALYSIS_H

#include <stddef.h>

#include "dem/error.h"

/* ---- hardness (thesis 2.7-2.9, 5.5) ---------------------------------------------------- */

/* Projected contact area of a sphere of diameter D pressed to depth h (m^2), thesis 2.9:
 * A = pi (D h - h^2) for 0 <= h <= D/2; beyond D/2 the projection is the full circle
 * pi D^2 / 4 (the formula would shrink again). NaN if D <= 0, h < 0 or non-finite. */
double dem_indent_area(double D, double h);

/* Hardness H = F / A(h) (Pa), thesis 2.7 with 2.9. NaN if h <= 0, D <= 0 or non-finite. */
double dem_hardness(double F, double D, double h);

/* Sensitivity of H to the depth origin at fixed force: -d ln H / d h = (D - 2h) / (D h - h^2)
 * (1/m) for 0 < h < D/2 (0 beyond). A surface error dz shifts H by about -dz times this
 * (relative): docs/analysis.md. NaN outside the domain. */
double dem_hardness_origin_sensitivity(double D, double h);

/* A loading curve: h[i] = z_surface - z_tip[i] (m, depth below the bed surface, see
 * dem_bed_surface), F[i] the indenter force (N, > 0 pushing the bed). Writes H[i] (Pa; NaN
 * where h[i] <= 0: no area yet) and, if hd != NULL, the dimensionless penetration
 * hd[i] = h[i] / (D/2) (thesis 5.5). DEM_ERANGE for D <= 0, DEM_ENONFINITE for a NaN input. */
int dem_hardness_curve(size_t n, const double *F, const double *h, double D, double *H,
                       double *hd, dem_err *err);

/* ---- bed surface under the indenter ---------------------------------------------------- */

/* The surface height from the particles under the indenter footprint (docs/analysis.md):
 * square columns of side `cell` (a grid with one column centred on the axis (x, y) =
 * (ax, ay)) whose centres lie within r_foot of the axis; each occupied column's top is
 * max(z_i + r_i) over the particles whose centres lie in the column (also those outside the
 * circle: a column cut by it keeps its real top). The surface z is the mean of the column
 * tops; sd is their spread (the bed's roughness, the uncertainty of the depth origin of a
 * single point of contact) and se = sd / sqrt(ncol) the standard error of z. */
typedef struct dem_surface {
  double z;          /* m, mean column top: the surface used for h */
  double sd;         /* m, standard deviation of the column tops */
  double se;         /* m, standard error of z */
  double z_pct;      /* m, the requested percentile of the column tops */
  double z_max;      /* m, the highest particle top (the first-contact height) */
  size_t ncol;       /* occupied columns */
  size_t nparticles; /* particles whose centres lie in the footprint */
} dem_surface;

/* x [3n] centres, radius [n]; r_foot > 0 (m); cell > 0 (m), or 0 for twice the mean radius
 * of the particles whose centres lie within r_foot (one particle diameter; nparticles
 * counts them, z_max is the highest of their tops); pct in [0, 100] (e.g. 90).
 * DEM_ERANGE for bad arguments, DEM_EINVAL if no particle lies in the footprint,
 * DEM_ENOMEM. */
int dem_bed_surface(size_t n, const double *x, const double *radius, double ax, double ay,
                    double r_foot, double cell, double pct, dem_surface *out, dem_err *err);

/* ---- the footprint of the contacts on the indenter (sink-in / pile-up) ----------------- */

/* Eq. 2.9 takes the projected contact area at depth h to be the cap's cross-section at the
 * undisturbed surface, pi a(h)^2 with a(h)^2 = D h - h^2. The bed may sink in around the
 * indenter (the real footprint is smaller) or pile up (larger). The footprint read off the
 * contacts themselves tests that assumption (docs/analysis.md, section 2b):
 *   a_c^2 = 2 sum(w_k rho_k^2) / sum(w_k)
 * over the contacts with w_k > 0, rho_k the distance of contact k from the indenter axis,
 * w_k the vertical load it puts on the indenter (N). For a uniform vertical pressure over a
 * disk of radius a, which a uniform normal pressure on a sphere gives (p dS cos(theta) =
 * p dA_projected), the load-weighted mean of rho^2 is a^2 / 2, so a_c = a and
 * F / (pi a_c^2) is that pressure. A pressure that falls towards the rim reads smaller:
 * Hertz's p ~ sqrt(1 - rho^2/a^2) gives a_c = sqrt(4/5) a = 0.894 a. Contacts in tension
 * (w_k <= 0, adhesion) carry no pressure and are left out. */
typedef struct dem_footprint {
  double a;       /* m, a_c above; NaN if no contact has w > 0 */
  double rho_max; /* m, the outermost contact with w > 0 (NaN if none) */
  double w;       /* N, sum of the positive loads */
  size_t n;       /* contacts with w > 0 */
} dem_footprint;

/* point [3n] contact points (m), w [n] loads (N), (ax, ay) the indenter axis (m).
 * DEM_EINVAL for NULL arrays with n > 0 or a NULL out, DEM_ENONFINITE for a NaN or inf
 * input. No contact with w > 0 is not an error (a, rho_max NaN, n 0). */
int dem_indent_footprint(size_t n, const double *point, const double *w, double ax, double ay,
                         dem_footprint *out, dem_err *err);

/* ---- contact depth from the initial unloading (thesis 2.3.5) --------------------------- */

typedef enum {
  DEM_UNLOAD_LINEAR = 0, /* least-squares line F = a + S h through the fitted points */
  DEM_UNLOAD_POWER       /* F = alpha (h - h_f)^m (Oliver & Pharr 1992), S = dF/dh at h_max */
} dem_unload_fit;

/* Default fitted fractions: points of the unloading branch with F >= (1 - frac) F_max. */
#define DEM_UNLOAD_FRAC_LINEAR 0.2
#define DEM_UNLOAD_FRAC_POWER 0.5

typedef struct dem_unload {
  double h_max; /* m, depth at the start of unloading (first point of the branch) */
  double F_max; /* N, force there */
  double S;     /* N/m, unloading stiffness: slope of the tangent at the start */
  double S_se;  /* N/m, standard error of S (linear fit; NaN for the power fit) */
  double h_c;   /* m, contact depth: the tangent through (h_max, F_max) meets F = 0 */
  double H;     /* Pa, F_max / A(h_c) */
  double h_f;   /* m, power fit: the final depth of the fitted curve; NaN for linear */
  double m;     /* power fit: the exponent; 1 for linear */
  size_t nfit;  /* points fitted */
} dem_unload;

/* The unloading branch h[0..n), F[0..n) starts at the reversal point (h[0] = h_max, use
 * dem_unload_start on a whole cycle) and runs with decreasing depth. Fits the points with
 * F >= (1 - frac) F[0], frac in (0, 1], at least 3 of them (power fit: with F > 0), with
 * `method`, and sets h_c = h_max - F_max / S, H = F_max / A(h_c) (thesis 2.7, 2.9).
 * DEM_ERANGE (frac, D, F_max <= 0, too few points), DEM_EPHYSICS (S <= 0 or h_c outside
 * [0, h_max]: no tangent to extrapolate), DEM_ENONFINITE. */
int dem_unload_analyse(size_t n, const double *h, const double *F, double D,
                       dem_unload_fit method, double frac, dem_unload *out, dem_err *err);

/* Index of the reversal point of a load-unload cycle: the first maximum of h. */
size_t dem_unload_start(size_t n, const double *h);

/* ---- statistics of a fluctuating series ------------------------------------------------ */

typedef enum {
  DEM_SE_IAT = 0, /* integrated autocorrelation time, Sokal's automatic window */
  DEM_SE_BATCH    /* non-overlapping batch means */
} dem_se_method;

typedef struct dem_stats_opts {
  dem_se_method method; /* default DEM_SE_IAT */
  double c_window;      /* IAT: smallest window W with W >= c tau(W); 0 = default 6 */
  size_t nbatch;        /* batch means: number of batches; 0 = default 20 */
} dem_stats_opts;       /* zero-initialised = defaults */

typedef struct dem_series_stats {
  size_t n;        /* samples used */
  double mean;     /* sample mean */
  double sd;       /* sample standard deviation (n - 1) */
  double se;       /* standard error of the mean allowing for correlation */
  double se_naive; /* sd / sqrt(n), as if the samples were independent */
  double tau;      /* integrated autocorrelation time, samples (var(mean) = 2 tau sd^2 / n;
                      1/2 for independent samples) */
  double n_eff;    /* effective sample size n / (2 tau) */
  size_t window;   /* IAT: lags summed; batch means: batch length */
  int reliable;    /* 1 if the window condition held within n / 4 lags (IAT) or the batch
                      length is at least 10 tau (batch means), else 0: se is a lower bound */
  double cv;       /* coefficient of variation sd / |mean| (NaN if mean == 0) */
  double slope;    /* least-squares slope dy/dx (gsl_fit_linear), per unit of x */
  double slope_se;       /* its standard error assuming independent residuals */
  double slope_se_corr;  /* the same times sqrt(2 tau) of the residuals */
  double intercept;      /* y at x = 0 of the fitted line */
  double lo, hi;         /* the x window (plateau: h/r) */
} dem_series_stats;

/* Statistics of y[0..n) (n >= 4) with abscissa x (NULL: the sample index). Samples are
 * assumed equally spaced (constant output interval); correlation is counted in samples.
 * DEM_ERANGE (n < 4, bad options), DEM_ENONFINITE (a NaN/inf sample), DEM_ENOMEM. */
int dem_series_analyse(size_t n, const double *x, const double *y,
                       const dem_stats_opts *opts, dem_series_stats *out, dem_err *err);

/* Plateau statistics: the samples with lo <= hd[i] <= hi (h/r window) of y (e.g. H), the
 * slope per unit of h/r. DEM_ERANGE if lo >= hi or fewer than 4 samples in the window. */
int dem_plateau_stats(size_t n, const double *hd, const double *y, double lo, double hi,
                      const dem_stats_opts *opts, dem_series_stats *out, dem_err *err);

typedef enum {
  DEM_TEST_TWO_SIDED = 0, /* mean1 != mean2 */
  DEM_TEST_GREATER,       /* mean1 > mean2 */
  DEM_TEST_LESS           /* mean1 < mean2 */
} dem_alternative;

typedef struct dem_comparison {
  double diff;   /* mean1 - mean2 */
  double se;     /* sqrt(se1^2 + se2^2) */
  double z;      /* diff / se */
  double p;      /* p-value of z under the alternative (normal approximation) */
  double level;  /* the significance level used */
  double nu;     /* degrees of freedom of the test (INFINITY: the z-test; else z is a t) */
  double z_crit; /* |z| (two-sided) or signed z beyond which the difference counts */
  int different; /* 1: different beyond the fluctuation at `level`, else 0 ("agree") */
} dem_comparison;

/* z-test of two independent means with standard errors se1, se2 (> 0; from
 * dem_series_analyse). level in (0, 0.5), e.g. 0.05. DEM_ERANGE / DEM_ENONFINITE. */
int dem_compare_means(double mean1, double se1, double mean2, double se2, double level,
                      dem_alternative alt, dem_comparison *out, dem_err *err);

/* The same with Student's t and Welch-Satterthwaite degrees of freedom
 * nu = (se1^2 + se2^2)^2 / (se1^4 / nu1 + se2^4 / nu2), for few effective samples or few
 * replicate beds: nu_i = k_i - 1 for the mean of k_i replicates, ~ n_eff - 1 for one series.
 * nu1, nu2 >= 1 (INFINITY: that side's se is exact); both infinite gives the z-test. z and
 * z_crit are then t and t_crit. */
int dem_compare_means_t(double mean1, double se1, double nu1, double mean2, double se2,
                        double nu2, double level, dem_alternative alt, dem_comparison *out,
                        dem_err *err);

/* Replicates (beds with different seeds): the mean of k >= 2 replicate plateau means and its
 * standard error from their spread, sd / sqrt(k) (degrees of freedom k - 1). */
int dem_replicates_mean(size_t k, const double *means, double *mean, double *se, dem_err *err);

/* Paired comparison over k >= 1 replicate beds: on bed i the two runs a_i, b_i (means with
 * standard errors se_a[i], se_b[i] > 0) share the bed, so the test is on the differences
 * d_i = a_i - b_i (variance s_i^2 = se_a[i]^2 + se_b[i]^2) and their mean dbar. Whether d
 * varies between beds beyond the runs' own errors is decided by Cochran's heterogeneity
 * statistic Q = sum (d_i - d_w)^2 / s_i^2 (d_w the inverse-variance weighted mean), chi^2
 * with k - 1 dof if the beds share one true difference, at the same `level`:
 * - not heterogeneous: se = sqrt(sum s_i^2) / k and the z-test;
 * - heterogeneous: se = sd(d_i) / sqrt(k) and Student's t with k - 1 dof (the paired t-test;
 *   with two beds t_0.95 = 6.31), so a difference whose sign swings between beds is not
 *   called a difference.
 * (Choosing the spread whenever it exceeds the runs' errors would use t_1 a third of the
 * time for two beds with no bed effect at all: Q > 1 has probability 0.32 under chi^2_1.)
 * k = 1 is dem_compare_means(a_0, se_a[0], b_0, se_b[0]). out->diff = dbar, out->se = se,
 * out->nu = INFINITY (z) or k - 1 (t); *q (if not NULL) = Q (0 for k = 1).
 * DEM_ERANGE (k = 0, se <= 0, level), DEM_ENONFINITE. */
int dem_compare_paired(size_t k, const double *a, const double *se_a, const double *b,
                       const double *se_b, double level, dem_alternative alt,
                       dem_comparison *out, double *q, dem_err *err);

/* ---- measurement volumes --------------------------------------------------------------- */

/* An axis-aligned cuboid [lo, hi] (m). */
typedef struct dem_box {
  double lo[3], hi[3];
} dem_box;

/* The bin size of thesis Figs 5.8, 5.13, 5.18: 5.2 x 5.2 x 4.2 mm. */
#define DEM_BIN_DX 5.2e-3
#define DEM_BIN_DY 5.2e-3
#define DEM_BIN_DZ 4.2e-3

/* The cuboid of the given size (m) centred at c. */
dem_box dem_box_centred(const double c[3], const double size[3]);

/* The dynamic bin of Fig 5.18: size (m; NULL: 5.2 x 5.2 x 4.2 mm) centred on the indenter
 * axis, its top face `gap` (m, >= 0; 0 in the thesis' schematic) below the indenter's lowest
 * point tip[3]. It moves with the indenter. */
dem_box dem_dynamic_bin(const double tip[3], const double size[3], double gap);

/* Volume of the box (m^3). */
double dem_box_volume(const dem_box *b);

/* Regular grid of nx * ny * nz bins of size cell[3] from origin (the lo corner of bin 0);
 * bin (i, j, k) has index (k ny + j) nx + i. */
typedef struct dem_grid {
  double origin[3]; /* m */
  double cell[3];   /* m */
  size_t nx, ny, nz;
} dem_grid;

/* The static bins of thesis Figs 5.8 / 5.13: 5 columns in x, 1 in y, nz rows of
 * 5.2 x 5.2 x 4.2 mm, centred on the die axis (ax, ay), bottom at z_base (nz = 3 for the
 * 13 mm bed, 4 for the 20 mm bed of Fig 5.13). */
dem_grid dem_grid_thesis(double ax, double ay, double z_base, size_t nz);

/* The box of bin `index` of the grid. */
dem_box dem_grid_box(const dem_grid *g, size_t index);

/* ---- stress (thesis 5.1, A4.2; Bagi 1996) ---------------------------------------------- */

/* Contacts as seen from particles: for contact record c, particle[c] is the particle index,
 * point[3c..] the contact point (m) and force[3c..] the force on that particle (N). A pair
 * contact appears twice (once per particle, opposite forces), a wall contact once. */
typedef struct dem_contact_view {
  size_t n;               /* records */
  const size_t *particle; /* [n] */
  const double *point;    /* m [3n] */
  const double *force;    /* N [3n] */
} dem_contact_view;

/* sigma_ij = -(1/V) sum over records whose particle centre x[3p..] lies in the box (lo <= x
 * < hi) of (x^c - x^p)_i F_j (thesis 5.1 / A4.2): compression positive, as the thesis plots
 * it. sigma[3 i + j], Pa. V = `volume` if > 0 (e.g. the bin minus the indenter, see
 * dem_box_free_volume), else the box volume. *nparticles (may be NULL) counts the distinct
 * particles that contributed. DEM_ERANGE for a particle index >= np. */
int dem_stress_box(const dem_contact_view *c, size_t np, const double *x, const dem_box *b,
                   double volume, double sigma[9], size_t *nparticles, dem_err *err);

/* The same for every bin of a grid in one pass: sigma[9 * index + 3 i + j], each bin's
 * volume the cell volume. */
int dem_stress_grid(const dem_contact_view *c, size_t np, const double *x, const dem_grid *g,
                    double *sigma, dem_err *err);

/* Hydrostatic stress (sxx + syy + szz) / 3, thesis 5.2. Pa. */
double dem_stress_hydrostatic(const double s[9]);
/* Deviatoric stress as the thesis defines it (5.3), from the normal components only:
 * sqrt(((sxx - syy)^2 + (sxx - szz)^2 + (syy - szz)^2) / 6). Pa. */
double dem_stress_deviatoric(const double s[9]);
/* sqrt(J2) of the symmetric part: 5.3 plus (sxy^2 + syz^2 + szx^2); equal to 5.3 when the
 * shear components vanish, frame-independent. Pa. */
double dem_stress_sqrt_j2(const double s[9]);
/* Relative asymmetry |s - s^T| / |s| (Frobenius norms; 0 for a zero tensor). */
double dem_stress_asymmetry(const double s[9]);

/* ---- solids fraction (Fig 6.4) --------------------------------------------------------- */

/* Volume of the intersection of the sphere (centre c, radius R) with the box (m^3): exact
 * disc-rectangle cross-section areas integrated over z by Gauss-Legendre quadrature between
 * the kinks of the integrand (relative error ~1e-13, docs/analysis.md). 0 if R <= 0. */
double dem_sphere_box_volume(const double c[3], double R, const dem_box *b);

/* The bin volume not occupied by a spherical indenter (centre c, radius R): for the stress of
 * bins the indenter has entered (thesis 5.2 text to Figs 5.9-5.11). m^3. */
double dem_box_free_volume(const dem_box *b, const double c[3], double R);

/* Solids fraction phi = (sum of sphere volumes inside the box) / V, V = `volume` if > 0 else
 * the box volume. x [3n], radius [n]. DEM_ERANGE / DEM_ENONFINITE. */
int dem_solids_fraction(size_t n, const double *x, const double *radius, const dem_box *b,
                        double volume, double *phi, dem_err *err);

/* ---- dimensionless strain rate (thesis 5.4 / 7.1) -------------------------------------- */

/* gamma* = gamma_dot sqrt(d / g): gamma_dot (1/s), d mean particle diameter (m), g (m/s^2).
 * NaN if d <= 0 or g <= 0. */
double dem_gamma_star(double gamma_dot, double d, double g);

/* The project's strain rate of indentation: gamma_dot = v / h_bed (1/s), the indenter speed
 * over the bed height, the way the thesis defines the rate of the consolidating piston
 * (docs/analysis.md). NaN if h_bed <= 0. */
double dem_indent_strain_rate(double v, double h_bed);

/* ---- rate dependence of the hardness: the dynamic-pressure fit ------------------------- */

/* H(v) = H0 + beta rho_b v^2 (docs/analysis.md, "Rate dependence"): the hardness measured at
 * indenter speed v (m/s) as a quasi-static part H0 (Pa) plus beta times the bed's dynamic
 * pressure rho_b v^2 (Pa), rho_b = particle density x solids fraction (kg/m^3). The
 * momentum the indenter gives the material ahead of it each second, per unit projected
 * area, is of order rho_b v^2 (the inertial "Poncelet" term of granular impact drag), so
 * beta is a dimensionless drag coefficient.
 *
 * Weighted least squares of H_i against x_i = rho_b v_i^2 with weights 1 / se_i^2
 * (gsl_fit_wlinear), se_i the standard error of H_i. chi2 = sum ((H_i - H0 - beta x_i) /
 * se_i)^2 with dof = n - 2; p = P(chi^2_dof >= chi2) (NaN if dof = 0). The standard errors
 * are those of the weights, scaled by `scale` = sqrt(chi2 / dof) when that exceeds 1 (the
 * points scatter more than their own errors allow: the Particle Data Group's scale
 * factor), else scale = 1. */
typedef struct dem_rate_fit {
  double H0, H0_se;     /* Pa */
  double beta, beta_se; /* - */
  double cov;           /* Pa, covariance of H0 and beta (scaled like the errors) */
  double chi2;          /* - */
  int dof;              /* n - 2 */
  double p;             /* goodness of fit */
  double scale;         /* >= 1, applied to H0_se and beta_se */
} dem_rate_fit;

/* n >= 2 runs: speeds v[i] (m/s, >= 0), hardness H[i] (Pa), its standard error se[i] (Pa,
 * > 0), the bed's rho_b (kg/m^3, > 0). DEM_ERANGE for n < 2, se <= 0, v < 0, rho_b <= 0 or
 * fewer than two distinct speeds; DEM_ENONFINITE for a NaN or infinite input. */
int dem_rate_fit_dynamic(size_t n, const double *v, const double *H, const double *se,
                         double rho_b, dem_rate_fit *out, dem_err *err);

/* The speed (m/s) at which the fitted dynamic part reaches `frac` of the quasi-static
 * hardness, beta rho_b v^2 = frac H0: v = sqrt(frac H0 / (beta rho_b)). If se != NULL, its
 * standard error by first-order propagation of H0_se, beta_se and cov:
 * se / v = (1/2) sqrt((H0_se / H0)^2 + (beta_se / beta)^2 - 2 cov / (H0 beta)).
 * NaN (and se NaN) unless H0, beta, rho_b and frac are all > 0. */
double dem_rate_onset_speed(const dem_rate_fit *f, double rho_b, double frac, double *se);

#endif
