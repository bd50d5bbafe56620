/* vh_run.h — dem-validate's tiers, beds and indentation runs: everything a run's numbers
 * depend on (validate/run.c). Private to validate/.
 *
 * This header, run.c, libdem and the CMakeLists are the inputs of the run cache's code id
 * (validate/code_id.cmake): an edit here makes every kept run anew. The cases, their
 * criteria and the report (vh.h) are deliberately not, so that changing how runs are
 * judged or shown reuses hours of thesis-scale runs. Keep report-only fields out of here.
 *
 * Vocabulary
 *   bed     a filled, settled, consolidated (10 kPa) and unloaded die, prepared once and
 *           saved as a scene checkpoint (dem_scene_save); every indentation on it restores
 *           the checkpoint (dem_scene_restore), so variants of the indenter start from the
 *           identical bed.
 *   run     one indentation of a bed to h/r_end with one indenter.
 *   tier    the scale of every case: quick (reduced geometry, CI) or full (thesis scale as
 *           far as the budget allows); the geometry is in mean particle diameters d.
 */
#ifndef VH_RUN_H
#define VH_RUN_H

#include <stddef.h>
#include <stdio.h>

#include "dem/analysis.h"
#include "dem/error.h"
#include "dem/scene.h"

#define G_ACC 9.81   /* m/s^2 */
#define D_MEAN 1e-3  /* m, thesis mean diameter */

#define VH_MAX_RUNS 96
#define VH_MAX_BEDS 24
#define VH_MAX_CASES 16

/* The scale of a tier (lengths in d, rates as gamma* = gamma_dot sqrt(d/g)). */
typedef struct vh_tier {
  const char *name;
  double die;              /* d, die diameter */
  double bed;              /* d, reference bed height */
  double indenter;         /* d, reference indenter diameter */
  double gamma_star;       /* reference dimensionless strain rate of every stage */
  double stiffness_scale;  /* multiplies every stiffness of Tables 6.2/6.3 */
  double rate_stiffness_scale; /* the same for the beds of cases 10 and 11 (high rates) */
  double dt_factor;        /* dt = dt_factor sqrt(m_min / k_max) */
  double fill_fraction;    /* solids fraction of the random fill */
  double h_end;            /* h/r at which an indentation stops */
  double plateau_lo, plateau_hi; /* h/r window of the plateau statistics */
  double early_lo, early_hi;     /* h/r window of the "early" hardness */
  /* case 2 and 3 geometry */
  int nbeds;               /* bed heights of case 2 */
  double beds[4];          /* d */
  double bed_indenter;     /* d, indenter of case 2 (13 d in the thesis) */
  int nsizes;              /* indenter sizes of case 3 */
  double sizes[6];         /* d */
  double stable_from;      /* d, sizes >= this count as "large" in case 3 */
  double wall_indenter;    /* d, the very large indenter of case 3 on the shallow bed */
  double shallow_die;      /* d, die of the beds shallower than the reference (case 2's
                              shallowest bed and case 3's wall-confinement runs): the thesis'
                              13 mm bed is in a 39 mm die (Figs 5.2-5.11), its 20-50 mm beds
                              in the 45 mm die (Figs 5.12-5.19); 0: the tier's die */
  int replicates;          /* reference beds with different seeds (>= 1) */
  int cases_mask;          /* bit i: case i + 1 runs in this tier */
} vh_tier;

const vh_tier *vh_tier_find(const char *name);

/* A bed: what a prepared bed depends on. */
typedef struct vh_bed {
  double bed;          /* d */
  double die;          /* d */
  unsigned long seed;
  double mu;           /* inter-particle sliding friction */
  double gamma;        /* J/m^2, inter-particle interface energy */
  double kscale;       /* multiplies every stiffness of Tables 6.2/6.3 (stiffness_scale) */
  double gamma_star;   /* rate of its consolidation and unloading (piston speed = gamma_dot x
                          bed top): the tier's, lower for a bed deeper than the reference
                          (vh_gamma_star_of_bed) */
  /* filled in when prepared */
  int ready;
  int skipped;         /* 1: not prepared, over the --budget (dist.c); its runs are skipped */
  char path[512];      /* scene checkpoint */
  double wall_s;       /* s, wall time of this invocation (preparation or restore) */
  double prep_s;       /* s, wall time of the preparation (NaN: unknown, made elsewhere) */
  size_t n;            /* particles */
  double phi, bed_top; /* -, m after unloading */
  double dt;           /* s */
  double rho;          /* kg/m^3, particle density of the bed's materials */
  unsigned cases;      /* plan: bit k set if the k-th selected case needs the bed (dist.c) */
} vh_bed;

/* An indentation on a bed. */
typedef struct vh_indent {
  dem_indenter_shape shape;
  double D;            /* d, diameter (cube: side) */
  double gamma_star;   /* indentation rate */
  double kn_scale;     /* multiplies the particle-indenter stiffness kn, kt */
  double mu_ind;       /* particle-indenter sliding friction */
  double dt_scale;     /* multiplies the bed's time step (1: the tier's dt_factor) */
} vh_indent;

/* The result of a run. Arrays hold the loading samples with h > 0 (from the bed surface). */
typedef struct vh_run {
  char label[128];
  int bed;             /* index into the harness' beds */
  vh_indent ind;
  int status;          /* DEM_OK or the error */
  char error[640];
  int cached;          /* 1: loaded from the run cache (cache.c), not run by this invocation */
  int skipped;         /* 1: not made, over the --budget (dist.c): its criteria are N/A */
  int threads;         /* OpenMP threads of the run that made it */
  double v;            /* m/s, indenter speed: gamma_dot(gamma*) x the bed top (docs/scene.md;
                          NaN for a bed not prepared) */
  double wall_s;       /* s, wall time of the run (when it was made) */
  long steps;
  double dt;           /* s */
  double surface;      /* m, bed surface under the footprint (dem_bed_surface) */
  double surface_sd;   /* m, roughness of the footprint */
  double peak_overlap; /* the largest overlap / smaller radius of any contact at any step
                          of the run (dem_sim_stats.peak_overlap_frac) */
  size_t n;
  double *hr, *H, *bin_p, *bin_q, *bin_phi, *base_p, *F; /* [n] */
  /* the footprint of the indenter's contacts (scene columns contact_radius and
     indenter_contacts, dem_indent_footprint; NaN where not measured): a_c [m], the mean
     pressure on it Hc = F / (pi a_c^2) [Pa], and the contacts [-] */
  double *ac, *Hc, *nind; /* [n] */
  double base_p0;      /* Pa, base stress at the first contact */
  /* statistics over the plateau window (H; stresses if available) */
  dem_series_stats sH, sp, sq, sphi;
  dem_series_stats sHc;    /* Hc over the plateau window (NaN mean if not measured) */
  dem_series_stats sfoot;  /* a_c^2 / a(h)^2 over the plateau window, a(h)^2 = D h - h^2 of
                              eq. 2.9 (spheres): < 1 sink-in, > 1 pile-up */
  int have_stress;
  dem_series_stats sEarly; /* H over the early window */
  unsigned cases;      /* plan: bit k set if the k-th selected case needs the run (dist.c) */
} vh_run;

typedef struct vh {
  const vh_tier *tier;   /* the tier's table entry, or tier_own when overridden */
  vh_tier tier_own;      /* the tier with --dt-factor / --stiffness-scale / --replicates */
  char overrides[128];   /* those options as given ("" if none), for the report */
  const char *cases_arg; /* --case as given (NULL: the tier's cases), for the report */
  dem_scene_materials materials; /* pasha-simplified (chapters 6/7, every case; default) or
                                    hertz-jkr (chapter 5's glass beads, cases 1-4 only) */
  char out[512];
  char beds_dir[512];
  int threads;
  double level;          /* significance level of every test (0.05) */
  int verbose;
  int nbeds;
  vh_bed beds[VH_MAX_BEDS];
  int nruns;
  vh_run runs[VH_MAX_RUNS];
  double t0;             /* wall clock at the start */
  int plan;              /* 1: cases only list their beds and runs (nothing is prepared) */
  int rank, nranks;      /* MPI rank and size (0, 1 without MPI) */
  int use_cache;         /* runs are kept in and reused from beds_dir (cache.c) */
  double budget;         /* s, --budget: wall time from t0 after which no bed or run is
                            started (0: none; dist.c) */
  int cache_only;        /* 1: a bed or run not in beds_dir is skipped, not made (the
                            evaluation after a --budget invocation) */
  int cur_case;          /* index of the selected case being run (-1: none); the plan
                            records which cases need each bed and run (--budget order) */
  int ncases;            /* selected cases so far, and their names */
  const char *case_names[VH_MAX_CASES];
} vh;

double vh_now(void);
void vh_log(const vh *h, const char *fmt, ...);

/* The reference bed and indenter of the tier (replicate k >= 0 changes the seed). */
vh_bed vh_bed_ref(const vh *h, int replicate);
/* The reference bed at the tier's stiffness scale for high rates (cases 10, 11). */
vh_bed vh_bed_rate(const vh *h);
vh_indent vh_indent_ref(const vh *h);
/* gamma* of the consolidation and indentation of a bed of height bed [d]: the tier's, or
 * for a bed deeper than the reference the tier's x reference / bed, so that no bed is
 * pressed faster in m/s than the reference bed, whose speed the speed-versus-accuracy study
 * validated (docs/validation.md, "Bed height"). */
double vh_gamma_star_of_bed(const vh *h, double bed);
/* Index of the bed (prepared on first use), or -1 with err set. */
int vh_bed_get(vh *h, const vh_bed *spec, dem_err *err);
/* Index of the run (run on first use; identical runs are shared between cases). A failed
 * run is returned with status != DEM_OK (the case reports ERROR). -1 only on setup errors. */
int vh_run_get(vh *h, const vh_bed *bed, const vh_indent *ind, dem_err *err);

/* Run cache (cache.c): runs kept across invocations in beds_dir. */
const char *vh_code_id(void); /* hash of what a run depends on (validate/code_id.cmake) */
void vh_cache_path(const vh *h, const char *bed_name, const vh_indent *in, char *buf,
                   size_t len);
/* 0 and r filled (series, scalars, status, cached = 1) on a hit; -1 on a miss. */
int vh_cache_load(const vh *h, const char *path, const char *bed_path, vh_run *r);
int vh_cache_save(const vh *h, const char *path, const char *bed_path, const vh_run *r,
                  dem_err *err);
void vh_bed_info_save(const vh_bed *b, int threads);
double vh_bed_info_load(const vh_bed *b);
/* a_c^2 / a(h)^2 of sample i, a(h)^2 = D h - h^2 (eq. 2.9): < 1 the bed sinks in around the
 * ball, > 1 it piles up; NaN for other shapes or where a_c is not measured. */
double vh_footprint_ratio(const vh_run *r, size_t i);
/* Free the series of one run (pointers set to NULL, n = 0). */
void vh_run_release(vh_run *r);
/* Free the series of every run and forget the beds and runs (after a plan). */
void vh_reset(vh *h);

#endif
