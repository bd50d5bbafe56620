/* Closed-form energy balances of a normal impact for `pasha`, `pasha-simplified` and
 * `luding` (dem/energy.h; thesis 4.1.3, 4.1.5, Appendices II and III).
 *
 * Areas under the piecewise-linear curves (x = alpha_max - alpha_0, F_max = k_p x):
 *   W_p + W_e - |W_lt|:  pasha  1/2 k_p x^2 - 1/2 k_e alpha_0^2            (A2.4, A2.7)
 *                        others 1/2 k_p x^2 - 1/2 k_p alpha_0^2            (A3.4, A3.5)
 *   W_e  = 1/2 F_max (alpha_max - alpha_p)                                 (A2.11, A3.7)
 *   |W_ad|: pasha       1/2 f_cp/9 (-3 a_cp - 14 a_fp + 9 a_c0 + 8 a_p)    (A2.14)
 *                       = 137/162 f_cp^2 / k_e  (any a_c0 on the line 4.4)
 *           simplified  1/2 f_cp (alpha_p - alpha_fp)                      (A3.8)
 *           luding      1/2 f_0 alpha_p + 1/2 f_cp alpha_fe                (A3.10)
 * Note A2.12 prints W_e = 1/2 k_e (alpha_max - alpha_0)(alpha_max - alpha_p); with A2.3 it is
 * k_p, as A2.15 (= 4.16) uses.
 */
#include <math.h>

#include "contact/epa.h"
#include "dem/energy.h"

enum { LAW_NONE, LAW_PASHA, LAW_SIMPLIFIED, LAW_LUDING };

static int law_kind(const dem_law *law) {
  if (law == &dem_law_pasha) return LAW_PASHA;
  if (law == &dem_law_pasha_simplified) return LAW_SIMPLIFIED;
  if (law == &dem_law_luding) return LAW_LUDING;
  return LAW_NONE;
}

int dem_energy_has_law(const dem_law *law) { return law && law_kind(law) != LAW_NONE; }

static int unsupported(const dem_contact *ct, dem_err *err) {
  return dem_err_set(err, DEM_EUNSUPPORTED,
                     "no closed-form energy balance for law '%s' (have: luding, pasha, "
                     "pasha-simplified)",
                     ct->law ? ct->law->name : "(none)");
}

/* Unloading geometry and m v_i^2 (J x 2) of an impact reaching alpha_max. */
static void geometry(int kind, const double *c, const dem_geom *g, double amax,
                     dem_epa_unload *u, double *mvi2) {
  switch (kind) {
    case LAW_PASHA: {
      dem_pasha_unload(c, g->R, amax, u);
      double x = amax - u->alpha_0, a0 = u->alpha_0;
      *mvi2 = c[DEM_PAS_KP] * x * x - c[DEM_PAS_KE] * a0 * a0; /* (4.13) */
      break;
    }
    case LAW_SIMPLIFIED:
      dem_pashas_unload(c, g->R, amax, u);
      *mvi2 = c[DEM_PSS_KP] * (amax * amax - 2.0 * u->alpha_0 * amax); /* (4.18) */
      break;
    default:
      dem_luding_unload(c, g->R, amax, u);
      *mvi2 = c[DEM_LUD_KP] * (amax * amax - 2.0 * u->alpha_0 * amax); /* (4.18) */
      break;
  }
}

/* m v_r^2 = 2 (W_e - |W_ad|) and the two works. */
static double rebound(int kind, const double *c, const dem_epa_unload *u, double *we,
                      double *wad) {
  *we = 0.5 * u->f_max * (u->alpha_max - u->alpha_p);
  if (kind == LAW_PASHA) {
    double ac0 = u->alpha_p - 8.0 / 9.0 * u->f_cp / u->ke;
    *wad = 0.5 * u->f_cp / 9.0 *
           (-3.0 * u->alpha_cp - 14.0 * u->alpha_fp + 9.0 * ac0 + 8.0 * u->alpha_p);
  } else if (kind == LAW_SIMPLIFIED) {
    *wad = 0.5 * u->f_cp * (u->alpha_p - u->alpha_fp);
  } else {
    *wad = 0.5 * c[DEM_LUD_F0] * u->alpha_p + 0.5 * u->f_cp * u->alpha_fe;
  }
  return 2.0 * (*we - *wad);
}

static void fill(int kind, const double *c, const dem_geom *g, double amax, double mvi2,
                 const dem_epa_unload *u, dem_energy_point *p) {
  double we, wad, mvr2 = rebound(kind, c, u, &we, &wad);
  p->alpha_max = amax;
  p->v_impact = sqrt(mvi2 / g->m);
  p->stuck = !(mvr2 > 0.0);
  p->v_rebound = p->stuck ? 0.0 : sqrt(mvr2 / g->m);
  p->e = p->v_rebound / p->v_impact;
  p->alpha_0 = u->alpha_0;
  p->alpha_p = u->alpha_p;
  p->alpha_cp = u->alpha_cp;
  p->alpha_fp = kind == LAW_LUDING ? 0.0 : u->alpha_fp;
  p->f_max = u->f_max;
  p->f_pulloff = u->f_cp;
  p->k_e = u->ke;
  p->w_in = 0.5 * mvi2;
  p->w_el = we;
  p->w_ad = wad;
}

int dem_energy_at_alpha_max(const dem_contact *ct, const dem_geom *g, double alpha_max,
                            dem_energy_point *p, dem_err *err) {
  int kind = law_kind(ct->law);
  if (kind == LAW_NONE) return unsupported(ct, err);
  dem_epa_unload u;
  double mvi2;
  geometry(kind, ct->c, g, alpha_max, &u, &mvi2);
  if (!(mvi2 > 0.0) || !(alpha_max > u.alpha_0) || !isfinite(alpha_max))
    return dem_err_set(err, DEM_ERANGE,
                       "law '%s': alpha_max = %g m is not reached by any impact (alpha_0 = %g "
                       "m; the impact energy of eq 4.13/4.18 is %g J)",
                       ct->law->name, alpha_max, u.alpha_0, 0.5 * mvi2);
  fill(kind, ct->c, g, alpha_max, mvi2, &u, p);
  return DEM_OK;
}

/* alpha_max reached at v: (4.13) or (4.18) solved for alpha_max. */
static double amax_at(int kind, const double *c, const dem_geom *g, double v) {
  dem_epa_unload u;
  double mvi2;
  geometry(kind, c, g, 0.0, &u, &mvi2); /* only for alpha_0 */
  double a0 = u.alpha_0, mv2 = g->m * v * v;
  if (kind == LAW_PASHA) return a0 + sqrt((mv2 + c[DEM_PAS_KE] * a0 * a0) / c[DEM_PAS_KP]);
  double kp = kind == LAW_SIMPLIFIED ? c[DEM_PSS_KP] : c[DEM_LUD_KP];
  return a0 + sqrt(a0 * a0 + mv2 / kp);
}

int dem_energy_at_velocity(const dem_contact *ct, const dem_geom *g, double v,
                           dem_energy_point *p, dem_err *err) {
  int kind = law_kind(ct->law);
  if (kind == LAW_NONE) return unsupported(ct, err);
  if (!(v > 0.0) || !isfinite(v))
    return dem_err_set(err, DEM_ERANGE, "impact velocity v = %g m/s must be finite and > 0", v);
  double amax = amax_at(kind, ct->c, g, v);
  dem_epa_unload u;
  double mvi2;
  geometry(kind, ct->c, g, amax, &u, &mvi2);
  fill(kind, ct->c, g, amax, g->m * v * v, &u, p);
  return DEM_OK;
}

static int stuck_at(int kind, const double *c, const dem_geom *g, double amax) {
  dem_epa_unload u;
  double mvi2, we, wad;
  geometry(kind, c, g, amax, &u, &mvi2);
  return !(rebound(kind, c, &u, &we, &wad) > 0.0);
}

static double v_at_amax(int kind, const double *c, const dem_geom *g, double amax) {
  dem_epa_unload u;
  double mvi2;
  geometry(kind, c, g, amax, &u, &mvi2);
  return sqrt(fmax(mvi2, 0.0) / g->m);
}

int dem_energy_v_stick(const dem_contact *ct, const dem_geom *g, double alpha_lim,
                       double *v_stick, dem_err *err) {
  int kind = law_kind(ct->law);
  if (kind == LAW_NONE) return unsupported(ct, err);
  /* The smallest alpha_max: reached as v -> 0 (m v_i^2 = 0). */
  double a_lo = amax_at(kind, ct->c, g, 0.0);
  if (!(alpha_lim > a_lo))
    return dem_err_set(err, DEM_ERANGE,
                       "law '%s': alpha_lim = %g m must exceed the overlap %g m reached at "
                       "v -> 0",
                       ct->law->name, alpha_lim, a_lo);
  if (stuck_at(kind, ct->c, g, alpha_lim)) {
    *v_stick = INFINITY;
    return DEM_OK;
  }
  /* Scan down from alpha_lim on a log grid in (alpha_max - a_lo) for the first stuck point. */
  const int n = 4000;
  double span = alpha_lim - a_lo, lo = NAN, hi = alpha_lim;
  for (int i = 1; i <= n; i++) {
    double a = a_lo + span * pow(1e-14, (double)i / n);
    if (stuck_at(kind, ct->c, g, a)) {
      lo = a;
      break;
    }
    hi = a;
  }
  if (isnan(lo)) {
    *v_stick = 0.0;
    return DEM_OK;
  }
  for (int it = 0; it < 200 && (hi - lo) > 1e-13 * hi; it++) {
    double mid = 0.5 * (lo + hi);
    if (stuck_at(kind, ct->c, g, mid))
      lo = mid;
    else
      hi = mid;
  }
  *v_stick = v_at_amax(kind, ct->c, g, 0.5 * (lo + hi));
  return DEM_OK;
}

int dem_energy_v_stick_closed(const dem_contact *ct, const dem_geom *g, double *v_stick,
                              dem_err *err) {
  int kind = law_kind(ct->law);
  if (kind == LAW_NONE) return unsupported(ct, err);
  const double *c = ct->c, R = g->R;
  double amax;
  if (kind == LAW_PASHA) {
    if (c[DEM_PAS_KEMAX] > 0.0) goto numeric_only;
    double ke = c[DEM_PAS_KE], kp = c[DEM_PAS_KP], pig = c[DEM_PAS_PIG];
    double a0 = 8.0 / 9.0 * c[DEM_PAS_FCE_R] * R / ke, r = 1.0 - kp / ke;
    /* 1/2 kp^2 x^2/ke = pi Gamma (2 R* r x - r^2 x^2)   (A2.9 with A1.6 = A1.10) */
    double x = 2.0 * pig * R * r / (0.5 * kp * kp / ke + pig * r * r);
    amax = a0 + x;
    dem_epa_unload u;
    dem_pasha_unload(c, R, amax, &u);
    /* Valid only if neither the f_ce floor nor the R* clamp is active at the root. */
    if (u.alpha_p - a0 > R || sqrt(162.0 / 137.0 * ke * pig * (2 * R * r * x - r * r * x * x)) <
                                  c[DEM_PAS_FCE_R] * R)
      goto numeric_only;
    *v_stick = sqrt(fmax(kp * x * x - ke * a0 * a0, 0.0) / g->m);
    return DEM_OK;
  }
  if (kind == LAW_SIMPLIFIED) {
    if (c[DEM_PSS_KEMAX] > 0.0) goto numeric_only;
    double f0, f0p, fce, ke = c[DEM_PSS_KE], kp = c[DEM_PSS_KP], kcp = c[DEM_PSS_KCP];
    dem_pashas_forces(c, R, &f0, &f0p, &fce);
    double a0 = f0 / kp;
    /* W_e = |W_ad|:  kp x / sqrt 2 = f_cp = ke (kcp alpha_p + f0p)/(ke + kcp) (A3.7-A3.8). */
    double den = (ke + kcp) * kp / M_SQRT2 - kcp * (ke - kp);
    if (!(den > 0.0)) {
      *v_stick = INFINITY;
      return DEM_OK;
    }
    double x = ke * (kcp * a0 + f0p) / den;
    amax = a0 + x;
    *v_stick = sqrt(kp * (amax * amax - 2.0 * a0 * amax) / g->m);
    return DEM_OK;
  }
  /* luding, capped, root beyond alpha*: k_e = ke_max; with d0 = r (a0 + x), r = 1 - kp/ke,
   * q = kc ke/(ke + kc):  kp^2 x^2/ke = q d0^2 + 2 f0 d0 + f0^2/ke   (A3.7, A3.10). */
  if (c[DEM_LUD_CAPPED] == 0.0) goto numeric_only;
  {
    double ke = c[DEM_LUD_KEMAX], kp = c[DEM_LUD_KP], kc = c[DEM_LUD_KC], f0 = c[DEM_LUD_F0];
    double a0 = f0 / kp, r = 1.0 - kp / ke, q = kc * ke / (ke + kc);
    double A = kp * kp / ke - q * r * r;
    double B = -(2.0 * q * r * r * a0 + 2.0 * f0 * r);
    double C = -(q * r * r * a0 * a0 + 2.0 * f0 * r * a0 + f0 * f0 / ke);
    if (!(A > 0.0)) {
      *v_stick = INFINITY;
      return DEM_OK;
    }
    double x = (-B + sqrt(B * B - 4.0 * A * C)) / (2.0 * A);
    amax = a0 + x;
    if (amax < c[DEM_LUD_ASTAR] * R) goto numeric_only;
    *v_stick = sqrt(kp * (amax * amax - 2.0 * a0 * amax) / g->m);
    return DEM_OK;
  }
numeric_only:
  return dem_err_set(err, DEM_EUNSUPPORTED,
                     "law '%s': no closed-form sticking velocity for this parameter set "
                     "(load-dependent k_e, or the root lies where a floor/cap/clamp is active); "
                     "use dem_energy_v_stick",
                     ct->law->name);
}

int dem_energy_e_limit(const dem_contact *ct, double *e_inf, dem_err *err) {
  int kind = law_kind(ct->law);
  const double *c = ct->c;
  double e2;
  if (kind == LAW_SIMPLIFIED && c[DEM_PSS_KEMAX] == 0.0) {
    double ke = c[DEM_PSS_KE], kp = c[DEM_PSS_KP], kcp = c[DEM_PSS_KCP];
    e2 = kp / ke - 2.0 * kcp * kcp * (ke - kp) * (ke - kp) / (ke * kp * (ke + kcp) * (ke + kcp));
  } else if (kind == LAW_LUDING && c[DEM_LUD_CAPPED] != 0.0) {
    double ke = c[DEM_LUD_KEMAX], kp = c[DEM_LUD_KP], kc = c[DEM_LUD_KC];
    e2 = kp / ke - kc * (ke - kp) * (ke - kp) / (ke * kp * (ke + kc));
  } else {
    return dem_err_set(err, DEM_EUNSUPPORTED,
                       "law '%s': the limit of e(v) is defined here for pasha-simplified with "
                       "a constant ke and for luding with ke_capped = 1",
                       ct->law ? ct->law->name : "(none)");
  }
  *e_inf = e2 > 0.0 ? sqrt(e2) : 0.0;
  return DEM_OK;
}
