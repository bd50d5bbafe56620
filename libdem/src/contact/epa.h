/* epa.h — private to libdem: the compiled-coefficient and history layouts of the linear
 * elasto-plastic-adhesive laws `luding`, `pasha` and `pasha-simplified`, and the geometry of
 * their unloading curves, shared by the law files (libdem/src/contact/) and the closed-form
 * energy balances (libdem/src/energy_pasha.c). Not installed, not public.
 *
 * Conventions as in dem/contact.h: alpha > 0 compression, F > 0 repulsive, SI units.
 * All pull-off forces below (f_cp, f0, f0p, f_ce) are MAGNITUDES (> 0); the thesis writes
 * some of them tensile-negative (eq 4.17).
 */
#ifndef DEM_SRC_CONTACT_EPA_H
#define DEM_SRC_CONTACT_EPA_H

/* The unloading curve that starts at alpha_max (one plastic loading episode). */
typedef struct dem_epa_unload {
  double ke;       /* N/m, unloading (elastic) stiffness used */
  double alpha_0;  /* m, where the plastic loading line crosses F = 0 */
  double alpha_max;/* m */
  double f_max;    /* N, force at alpha_max on the loading line */
  double alpha_p;  /* m, where the unloading line crosses F = 0 (permanent overlap) */
  double alpha_cp; /* m, pull-off point: the most tensile force on unloading */
  double f_cp;     /* N, > 0: pull-off force magnitude */
  double alpha_fp; /* m, where the contact breaks on unloading */
  double alpha_fe; /* m, luding only: unloading line at F = -f0 (thesis App. III) */
} dem_epa_unload;

/* ---- luding ------------------------------------------------------------------------- */
enum {
  DEM_LUD_KP,     /* N/m, plastic loading stiffness k_p (Luding's k_1) */
  DEM_LUD_KEMAX,  /* N/m, maximum elastic stiffness \hat k_e (Luding's \hat k_2) */
  DEM_LUD_KC,     /* N/m, adhesive stiffness k_c */
  DEM_LUD_ASTAR,  /* -, alpha* / R* = 2 phi_f ke_max / (ke_max - kp), eq (3.71) */
  DEM_LUD_F0,     /* N, constant adhesive force at first contact f_0 (>= 0) */
  DEM_LUD_CAPPED, /* 1: ke = ke_max for alpha_max >= alpha* (Luding); 0: uncapped */
  DEM_LUD_ETA,    /* -, damping constant eta(e) */
  DEM_LUD_NCOEF
};
enum { DEM_LUD_H_STATE, DEM_LUD_H_AMAX, DEM_LUD_H_K2, DEM_LUD_H_D0, DEM_LUD_NHIST };
/* Branch states (hist[0]); 0 = no contact (fresh, or broken: Luding forgets everything). */
enum { DEM_LUD_PLASTIC = 1, DEM_LUD_ELASTIC = 2, DEM_LUD_ADHESIVE = 3 };

/* k_e(alpha_max), eq (3.74), capped at ke_max for alpha_max >= alpha* if c says so. */
double dem_luding_ke(const double *c, double R, double alpha_max);
/* Unloading from alpha_max (reached on the plastic line) down to breakage at alpha = 0. */
void dem_luding_unload(const double *c, double R, double alpha_max, dem_epa_unload *u);

/* ---- pasha (full law, thesis 4.1-4.11) ---------------------------------------------- */
enum {
  DEM_PAS_KE,    /* N/m, elastic stiffness k_e (initial linear-JKR part and unloading) */
  DEM_PAS_KP,    /* N/m, plastic stiffness k_p */
  DEM_PAS_FCE_R, /* N/m, f_ce / R* = 1.5 pi Gamma, eq (4.1) */
  DEM_PAS_PIG,   /* N/m, pi Gamma */
  DEM_PAS_KEMAX, /* N/m, \hat k_e of eq (4.23); 0: constant k_e */
  DEM_PAS_ETA,   /* -, damping constant eta(e) */
  DEM_PAS_NCOEF
};
enum {
  DEM_PAS_H_STATE,
  DEM_PAS_H_AMAX,
  DEM_PAS_H_KEU, /* N/m, unloading stiffness of the current unloading line */
  DEM_PAS_H_AP,
  DEM_PAS_H_ACP,
  DEM_PAS_H_AFP,
  DEM_PAS_H_FCP,
  DEM_PAS_NHIST
};
/* 1: in contact, never yielded (linear JKR, A-B-alpha_0); 2: yielded, in contact;
 * 3: yielded, separated (the plastic memory is kept; re-contact at alpha_fp). */
enum { DEM_PAS_ELASTIC = 1, DEM_PAS_PLASTIC = 2, DEM_PAS_BROKEN = 3 };

/* Unloading stiffness after plastic loading to alpha_max: k_e, or eq (4.23) if k_e max > 0. */
double dem_pasha_ke_unload(const double *c, double R, double alpha_max);
/* Unloading from alpha_max > alpha_0: eqs (4.4)-(4.11), App. I. */
void dem_pasha_unload(const double *c, double R, double alpha_max, dem_epa_unload *u);

/* ---- pasha-simplified (thesis 4.1.4-4.1.5, Fig 4.20) -------------------------------- */
enum {
  DEM_PSS_KE,    /* N/m, constant unloading stiffness (0 if KEMAX is used) */
  DEM_PSS_KP,    /* N/m */
  DEM_PSS_KCP,   /* N/m, slope of the pull-off locus (4.17) */
  DEM_PSS_F0,    /* N, initial adhesive force; < 0: 8/9 * 1.5 pi Gamma R* */
  DEM_PSS_F0P,   /* N, intercept of the locus (4.17); < 0: = f0 */
  DEM_PSS_FCE_R, /* N/m, 1.5 pi Gamma; < 0: Gamma not given (f_ce = 9/8 f0) */
  DEM_PSS_KEMAX, /* N/m, \hat k_e of eq (4.23); 0: constant k_e */
  DEM_PSS_ETA,
  DEM_PSS_NCOEF
};
enum {
  DEM_PSS_H_STATE,
  DEM_PSS_H_AMAX,
  DEM_PSS_H_KEU,
  DEM_PSS_H_AP,
  DEM_PSS_H_ACP,
  DEM_PSS_H_AFP,
  DEM_PSS_NHIST
};
/* 1: in contact (any branch); 2: separated with plastic memory (re-contact at alpha_fp). */
enum { DEM_PSS_CONTACT = 1, DEM_PSS_BROKEN = 2 };

/* The forces of this contact geometry: f0, f0p and f_ce (N, magnitudes). */
void dem_pashas_forces(const double *c, double R, double *f0, double *f0p, double *fce);
double dem_pashas_ke_unload(const double *c, double R, double alpha_max);
void dem_pashas_unload(const double *c, double R, double alpha_max, dem_epa_unload *u);

/* Eq (4.23): k_e = k_p + (r/R*)^2 (\hat k_e - k_p), r^2 = 2 R* a - a^2 (4.21); a is clamped
 * to R* (the cap area is largest there; beyond it the formula would make k_e fall). */
double dem_epa_ke_load_dependent(double kp, double ke_max, double R, double alpha_max);

#endif
