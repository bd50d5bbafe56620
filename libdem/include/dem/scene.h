/* dem/scene.h — the ball-indentation scene (thesis 5.1, 6.1, 7.1): fill a cylindrical die
 * with the thesis' size distribution, settle under gravity, consolidate with a servo piston
 * at constant strain rate to the pre-consolidation stress, unload, indent at constant
 * velocity to a given h/r, optionally unload the indenter. See docs/scene.md.
 *
 * Lengths of the geometry (die diameter, bed height, indenter diameter) are given in mean
 * particle diameters d; everything else is SI. A scene is an opaque handle: create from a
 * config, then run the stages one by one (tests) or all at once; the time series is a
 * dem_table (dem/table.h).
 */
#ifndef DEM_SCENE_H
#define DEM_SCENE_H

#include "dem/analysis.h"
#include "dem/engine.h"
#include "dem/error.h"
#include "dem/params.h"
#include "dem/table.h"

typedef enum { DEM_SCENE_PASHA = 0, DEM_SCENE_HERTZ_JKR = 1 } dem_scene_materials;
/* Their names (config key `materials`, dem-validate --materials), indexed by the enum, NULL
 * after the last: "pasha-simplified", "hertz-jkr". */
extern const char *const dem_scene_materials_names[];
typedef enum { DEM_SCENE_PSD_T61 = 0, DEM_SCENE_PSD_T51 = 1 } dem_scene_psd;
typedef enum {
  DEM_INDENTER_SPHERE = 0,
  DEM_INDENTER_CYLINDER = 1, /* flat-ended */
  DEM_INDENTER_CUBE = 2
} dem_indenter_shape;

typedef struct dem_scene_config {
  /* materials: the chapter 6/7 set (pasha-simplified, Tables 6.2/6.3) or the chapter 5 set
   * (jkr-modified particle-particle + Hertz particle-wall, Tables 5.2/5.3). The three
   * parameter sets hold the physics-notes keys of each interaction (defaults from the
   * tables, filled by dem_scene_config_defaults; a caller may overwrite keys). */
  dem_scene_materials materials;
  dem_params pp;          /* particle-particle: law coefficients + mu, mu_r, kt */
  dem_params pw;          /* particle-die and particle-piston */
  dem_params pi;          /* particle-indenter */
  double rho;             /* kg/m^3, particle density */
  double rho_wall;        /* kg/m^3, geometries (only for the record: walls are rigid) */
  /* bed */
  double d_mean;          /* m, mean particle diameter (1 mm) */
  dem_scene_psd psd;      /* number distribution of Table 6.1 or 5.1 */
  double die_diameter;    /* d, die diameter (thesis 39-45 d; default 20 d) */
  double bed_height;      /* d, target settled bed height (thesis 13-50 d; default 12 d) */
  double phi_est;         /* -, solids fraction assumed to size the particle count (0.58) */
  long n_particles;       /* > 0 overrides the count from bed_height */
  double fill_fraction;   /* -, solids fraction of the random fill volume (0.30) */
  unsigned long seed;     /* GSL mt19937 seed */
  /* settling */
  double settle_ke;       /* stop when the kinetic energy per particle < settle_ke x
                             m_mean g d_mean (1e-4: a mean particle moving ~1.4 mm/s) */
  double settle_min_time; /* s, at least this long (the fall time) */
  double settle_max_time; /* s, give up (error) after this */
  /* consolidation */
  double sigma_pre;       /* Pa, pre-consolidation stress (10 kPa) */
  double strain_rate;     /* 1/s, piston speed / bed height (1 1/s in the thesis) */
  double servo_band;      /* -, constant speed up to sigma_pre, then the servo, whose set
                             point stays within F (1 +- servo_band) (0.1) */
  double servo_steps;     /* servo time constant for the stiffest possible bed, in steps of
                             the reference step 0.2 sqrt(m_min / k_max) at every dt_factor
                             (4; see docs/scene.md) */
  double hold_time;       /* s, hold at sigma_pre with the servo before unloading */
  double hold_tol;        /* -, the stress must be within this of sigma_pre (0.02) */
  /* indentation */
  dem_indenter_shape shape;
  double indenter_diameter; /* d, sphere/cylinder diameter or cube side (16 d) */
  double indenter_length; /* d, flat cylinder's length behind its face (0: its diameter);
                             the cube is a cube (length = side) */
  double indent_rate;     /* 1/s, indenter speed / bed height (defaults to strain_rate) */
  double h_over_r;        /* -, stop at this dimensionless penetration h/r (0.5) */
  int unload;             /* 1: withdraw the indenter at the same speed after h_over_r */
  /* numerics */
  double dt_factor;       /* dt = dt_factor sqrt(m_min / k_max) (thesis 4.29-4.31; 0.2) */
  double stiffness_scale; /* multiplies every stiffness (ke, kp, kcp, kt, kn; E for Hertz
                             and JKR): 1 = the tables; < 1 speeds a run up (dt ~ k^-1/2) */
  double skin;            /* d, neighbour skin (0.1) */
  int threads;
  double sample_interval; /* s, time-series row interval (0: 200 rows per stage) */
  /* output */
  int output_stress;      /* 1 (default): the stress columns bin_p, bin_q, bin_phi, base_p
                             and the footprint columns indenter_contacts, contact_radius
                             of the time series (one contact export per row, see
                             dem_scene_series); 0: those columns are NaN */
} dem_scene_config;

/* Defaults of the given material set (thesis tables) and the small quick bed. */
void dem_scene_config_defaults(dem_scene_config *c, dem_scene_materials m);
/* Range checks of every field; messages name the field, value and allowed range. */
int dem_scene_config_check(const dem_scene_config *c, dem_err *err);

/* Progress and snapshots: called by the stages (may be NULL). stage: "settle",
 * "consolidate", "unload" (the piston retracting until it loses the bed), "relax" (the
 * unload stage's wait for the bed to come to rest; snapshots name it "unload"), "indent",
 * "withdraw". frac in [0, 1] or < 0 if unknown; eta in s of wall clock for the stage, < 0 if
 * unknown. */
typedef struct dem_scene_hooks {
  void (*progress)(const char *stage, double t, double frac, double eta, void *user);
  double progress_interval;  /* s of wall clock between progress calls */
  int (*snapshot)(dem_sim *s, const char *stage, double t, void *user, dem_err *err);
  double snapshot_interval;  /* s of simulated time (0: none) */
  void *user;
} dem_scene_hooks;

typedef struct dem_scene dem_scene;

typedef struct dem_scene_info {
  size_t n;               /* particles */
  double dt;              /* s */
  double die_radius;      /* m */
  double mean_d, sd_d;    /* m, number mean and standard deviation of the generated sizes */
  double table_mean, table_sd; /* m, of the requested distribution */
  double bed_top;         /* m, bed height: mean of the highest particle tops (see docs) */
  double phi;             /* -, solids fraction of the bed below bed_top (after settling) */
  double surface;         /* m, bed surface for the indentation (first indenter contact) */
  double piston_stress;   /* Pa, last */
  double indenter_force;  /* N, last (axial, > 0 resisting penetration) */
  double depth;           /* m, last penetration depth from the surface */
  double v_piston, v_indenter; /* m/s */
} dem_scene_info;

dem_scene *dem_scene_create(const dem_scene_config *c, const dem_scene_hooks *h, dem_err *err);
void dem_scene_free(dem_scene *sc);
int dem_scene_fill(dem_scene *sc, dem_err *err);
int dem_scene_settle(dem_scene *sc, dem_err *err);
int dem_scene_consolidate(dem_scene *sc, dem_err *err); /* load to sigma_pre and hold */
int dem_scene_unload(dem_scene *sc, dem_err *err);      /* piston back to zero load, away;
                                                           the bed left at rest (docs/scene.md) */
int dem_scene_indent(dem_scene *sc, dem_err *err);      /* indent (and unload if asked) */
int dem_scene_run(dem_scene *sc, dem_err *err);         /* all of the above */

dem_sim *dem_scene_sim(dem_scene *sc);
/* The time series: t [s], stage [0 settle, 1 consolidate, 2 unload, 3 indent, 4 withdraw],
 * piston_z [m], piston_stress [Pa], indenter_z [m], depth [m], h_over_r [-],
 * indenter_force [N], hardness [Pa], kinetic_energy [J], contacts [-], wall_contacts [-],
 * then the stresses of the bed (thesis 5.1-5.3; NaN if config.output_stress is 0):
 *   bin_p [Pa]   hydrostatic stress (5.2, compression positive) in the dynamic bin of Fig
 *                5.18: 5.2 x 5.2 x 4.2 mm scaled by d_mean / 1 mm, centred on the axis, top
 *                face at the indenter tip (dem_dynamic_bin with gap 0), volume minus the
 *                indenter's part (dem_box_free_volume); stages 3 and 4 only, NaN before;
 *   bin_q [Pa]   deviatoric stress (5.3) in the same bin; stages 3 and 4;
 *   bin_phi [-]  solids fraction of the same bin (Fig 6.4); stages 3 and 4;
 *   base_p [Pa]  hydrostatic stress in a bin of the same size on the axis at the base
 *                (bottom face at z = 0); every stage;
 * then the footprint of the indenter's contacts (dem_indent_footprint; the same switch;
 * stages 3 and 4, NaN before; since 2026-12-07, NaN in the rows of a restored older bed):
 *   indenter_contacts [-]  particles touching the indenter;
 *   contact_radius [m]     a_c = sqrt(2 sum(w rho^2) / sum(w)), w the vertical load of a
 *                contact on the indenter, rho its distance from the axis: the radius of the
 *                loaded footprint (a uniform pressure over a disk of radius a gives a); NaN
 *                while nothing presses. indenter_force / (pi a_c^2) is the mean pressure on
 *                the footprint, to compare with hardness (eq. 2.9's pi (D h - h^2)). */
const dem_table *dem_scene_series(const dem_scene *sc);
void dem_scene_get_info(const dem_scene *sc, dem_scene_info *info);
/* The discrete size distribution: diameters (in d) and number fractions of a table. */
int dem_scene_psd_table(dem_scene_psd psd, const double **dd, const double **frac);
/* Projected contact area of the indenter at depth h (m^2): sphere pi (D h - h^2) up to
 * h = D/2, then pi D^2/4 (thesis 2.7-2.9); flat cylinder pi D^2/4; cube D^2. */
double dem_scene_indent_area(dem_indenter_shape shape, double D, double h);

/* ---- checkpoints of a scene and reuse of a prepared bed (issue 5) ---------------------
 * A scene checkpoint is an engine checkpoint (dem/checkpoint.h) whose caller blob holds the
 * scene state: the config, the stage reached, the bed measurements, the surface, the state
 * of a stage in progress and the time series so far (libdem/src/scene/restart.c).
 * dem_scene_save writes it (temporary file + rename) at any step boundary: between stages,
 * or after a stage returned DEM_EINTERRUPTED (the engine's interrupt flag, see
 * dem_sim_set_interrupt_flag on dem_scene_sim): an interrupted stage keeps its progress in
 * the scene and continues exactly where it stopped when called again, in the same process
 * or after a restore. dem_scene_restore reads it back into a new scene that continues
 * bit-identically (same thread count) with the stored config; the stage functions of the
 * stages already completed return DEM_OK at once (dem_scene_run continues with the next
 * one), a stage whose predecessor is not complete is DEM_EINVAL.
 * `override` (may be NULL) replaces the config of the stages not yet run; only the
 * indentation fields (shape, indenter_diameter, indenter_length, indent_rate, h_over_r,
 * unload), dt_factor (the time-step study of thesis 7.3; dt is recomputed) and the
 * particle-indenter parameters `pi` (all only while the indentation has not begun),
 * threads, sample_interval, output_stress and the limits settle_ke, settle_min_time,
 * settle_max_time,
 * hold_time, hold_tol may differ from the stored config (anything else: DEM_EINVAL naming
 * the field, the stored and the given value). New `pi` coefficients re-create the
 * particle-indenter interaction (stiffness_scale applied) and re-derive k_max and dt from
 * the three interactions (dt changes only if the indenter becomes the stiffest contact).
 * This is how one consolidated bed serves many indentations.
 * Errors of restore name the file: DEM_EIO / DEM_EPARSE / DEM_EUNSUPPORTED of the engine
 * checkpoint (missing, truncated, corrupted, other version), DEM_EINVAL for an engine
 * checkpoint without a scene state, DEM_EPARSE for a scene state cut short or missing a
 * field, DEM_EUNSUPPORTED for another scene-state version. */
typedef enum {
  DEM_SCENE_STAGE_NONE = -1, /* created, not filled */
  DEM_SCENE_STAGE_FILLED = 0,
  DEM_SCENE_STAGE_SETTLED = 1,
  DEM_SCENE_STAGE_CONSOLIDATED = 2,
  DEM_SCENE_STAGE_UNLOADED = 3,
  DEM_SCENE_STAGE_INDENTED = 4
} dem_scene_stage;
int dem_scene_save(const dem_scene *sc, const char *path, dem_err *err);
dem_scene *dem_scene_restore(const char *path, const dem_scene_config *override,
                             const dem_scene_hooks *h, dem_err *err);
/* The last stage completed. dem_scene_run continues from it. */
dem_scene_stage dem_scene_get_stage(const dem_scene *sc);

/* ---- stresses of the bed (thesis 5.1-5.3, App. IV; dem/analysis.h) -------------------
 * Contact view of the current state for dem_stress_box / dem_stress_grid: every
 * particle-particle contact twice and every particle-wall (incl. indenter) contact once,
 * contact points and forces of the last force evaluation. The arrays belong to the scene
 * and stay valid until the next stage runs or the scene is freed. */
int dem_scene_contacts(dem_scene *sc, dem_contact_view *view, dem_err *err);
/* The static bins of Figs 5.8 / 5.13: dem_grid_thesis (5 columns in x, 1 in y, nz rows of
 * 5.2 x 5.2 x 4.2 mm, scaled by d_mean / 1 mm) centred on the die axis, bottom at the base
 * z = 0; sigma[9 * index + 3 i + j] (Pa, compression positive, nz * 5 * 9 doubles) from
 * dem_stress_grid over dem_scene_contacts, each bin's volume its cell volume (a bin the
 * indenter has entered, or one reaching beyond the die wall, is not corrected: use
 * dem_stress_box with dem_box_free_volume for those). *grid_out (may be NULL) receives the
 * grid. nz >= 1 (DEM_ERANGE). Invalidates the arrays of an earlier dem_scene_contacts. */
int dem_scene_stress_grid(dem_scene *sc, size_t nz, double *sigma, dem_grid *grid_out,
                          dem_err *err);

/* Snapshot DIR/snap_<index>.h5 (x, v, omega, radius, id; attributes time, stage) and the
 * XDMF index DIR/snapshots.xmf over snapshots 0..count-1 (times, particle counts); both
 * written to a temporary file and renamed. */
int dem_scene_write_snapshot(dem_sim *s, const char *dir, int index, double t,
                             const char *stage, dem_err *err);
int dem_scene_write_xdmf(const char *dir, int count, const double *times, const size_t *n,
                         dem_err *err);

#endif
