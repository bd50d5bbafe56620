/* Private state of the ball-indentation scene (libdem/src/scene/). Not installed. */
#ifndef DEM_SCENE_INTERNAL_H
#define DEM_SCENE_INTERNAL_H

#include "dem/scene.h"

struct dem_scene {
  dem_scene_config cfg;
  dem_scene_hooks hooks;
  dem_sim *sim;
  dem_table *series;
  int mat_p, mat_w, mat_i;   /* particle, die/piston, indenter materials */
  int w_base, w_die, w_piston, w_ind; /* wall indices (w_ind -1 until the indent stage) */
  double die_radius;         /* m */
  double fill_top;           /* m, top of the random fill volume */
  double mean_d, sd_d;       /* m, of the generated sizes */
  double dt;                 /* s */
  double k_max;              /* N/m, largest contact stiffness */
  long since_row;            /* steps since the last row */
  double m_mean;             /* kg */
  double bed_top, phi;       /* m, -: after settling / consolidation */
  double surface;            /* m, first indenter contact (NAN before) */
  double v_piston, v_ind;    /* m/s */
  double ind_r;              /* m, indenter radius (half side for a cube) */
  int stage;                 /* the series' stage code */
  double next_snap;          /* s */
  double last_progress;      /* s of wall clock */
  double stage_wall0;        /* s of wall clock at the stage start */
  int reached;               /* dem_scene_stage: the last stage completed */
  /* The stage in progress, kept here (not in locals) so that a stage interrupted by the
   * engine's interrupt flag continues exactly where it stopped, also from a checkpoint
   * (restart.c). sub: 0 not begun, then a stage-specific phase >= 1. */
  int sub;
  double t0, t_max;          /* s: stage start (simulated), give-up duration */
  double t_rest;             /* s, unload relax: simulated time since which the bed has been
                                at rest as a whole (< 0: not at rest) */
  double z_half, f_half;     /* consolidation: piston z (m) and force (N) at half load */
  double t_in, f_set, gain;  /* servo: band entry time (s), set point (N), gain (m/(N s)) */
  double ki;                 /* servo: integral rate, fraction of the error per sample (-) */
  int resume;                /* 1: an advance was interrupted; finish it first */
  long pending;              /* steps left of the interrupted advance */
  /* contacts and stresses (stress.c) */
  dem_sim_contact *cbuf;     /* engine contact export */
  size_t ccap;
  size_t cn;                 /* records in cbuf after the last export */
  double *fp_buf;            /* indenter contacts' points [3] and loads [1] (footprint) */
  size_t fp_cap;
  size_t *v_part;            /* dem_contact_view arrays: every pair twice, walls once */
  double *v_point, *v_force;
  size_t vcap;
};

/* scene.c: the three interactions from cfg.pp/pw/pi (stiffness_scale applied), setting
 * sc->k_max and sc->dt (the engine's dt too); the time-series table. */
int scene_interactions(dem_scene *sc, dem_err *err);
/* scene.c: the consolidation servo's gain (m/(N s)) from k_max and the reference step. */
double scene_servo_gain(const dem_scene *sc);
/* scene.c: the servo's integral rate (-, per sample) from the loading stiffness between the
 * half-load point (z_half m, f_half N) and the switch (z1 m, f1 N). */
double scene_servo_ki(const dem_scene *sc, double z_half, double f_half, double z1, double f1);
dem_table *scene_series_create(dem_err *err);

int scene_fill(dem_scene *sc, dem_err *err);
/* stress.c: the columns of a row read off the contacts (bin_p, bin_q, bin_phi, base_p,
 * indenter_contacts, contact_radius; NaN where not defined) and the buffers' release. */
#define SCENE_NCONTACT 6
/* columns of the time series before indenter_contacts and contact_radius were appended
 * (checkpoints written until 2026-12-07; restart.c reads them with those two NaN) */
#define SCENE_NSERIES_V3 16
#define SCENE_NSERIES 18 /* now: SCENE_NSERIES_V3 + indenter_contacts, contact_radius */
int scene_stress_row(dem_scene *sc, double out[SCENE_NCONTACT], dem_err *err);
void scene_stress_free(dem_scene *sc);
void scene_psd_moments(dem_scene_psd psd, double d_mean, double *mean, double *sd);

#endif
