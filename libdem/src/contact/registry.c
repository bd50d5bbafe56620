/* The registry of contact laws and the generic set-up shared by all of them. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "dem/contact.h"
#include "dem/material.h"

static const dem_law *const laws[] = {
#define DEM_LAW(sym) &sym,
#include "dem/laws.def"
#undef DEM_LAW
};

int dem_contact_law_count(void) { return (int)(sizeof laws / sizeof laws[0]); }

const dem_law *dem_contact_law_at(int i) {
  return (i >= 0 && i < dem_contact_law_count()) ? laws[i] : NULL;
}

const dem_law *dem_contact_law_find(const char *name) {
  if (!name) return NULL;
  for (int i = 0; i < dem_contact_law_count(); i++)
    if (strcmp(laws[i]->name, name) == 0) return laws[i];
  return NULL;
}

int dem_contact_law_has_coef(const dem_law *law, const char *key) {
  for (int i = 0; i < law->ncoef; i++)
    if (strcmp(law->coef[i].key, key) == 0) return 1;
  return 0;
}

/* "[1e-09, 1]" or "> 0" for a readable allowed range. */
static void range_text(const dem_coef_spec *s, char *buf, size_t n) {
  const char *lo = (s->min == DBL_MIN) ? "(0" : NULL;
  if (lo && isinf(s->max))
    snprintf(buf, n, "> 0");
  else if (lo)
    snprintf(buf, n, "(0, %g]", s->max);
  else if (isinf(s->max))
    snprintf(buf, n, ">= %g", s->min);
  else
    snprintf(buf, n, "[%g, %g]", s->min, s->max);
}

int dem_contact_setup(dem_contact *ct, const dem_law *law, const dem_params *ps, dem_err *err) {
  if (!ct || !law || !ps) return dem_err_set(err, DEM_EINVAL, "dem_contact_setup: NULL argument");
  memset(ct, 0, sizeof *ct);
  dem_params full = *ps;
  for (int i = 0; i < law->ncoef; i++) {
    const dem_coef_spec *s = &law->coef[i];
    double v;
    char range[64];
    range_text(s, range, sizeof range);
    if (!dem_params_get(ps, s->key, &v)) {
      if (isnan(s->def))
        return dem_err_set(err, DEM_EMISSING,
                           "law '%s' needs coefficient '%s' (%s, %s; allowed %s)", law->name,
                           s->key, s->about, s->unit, range);
      int rc = dem_params_set(&full, s->key, s->def, "default", err);
      if (rc) return rc;
      continue;
    }
    if (!isfinite(v))
      return dem_err_set(err, DEM_ENONFINITE, "%slaw '%s': coefficient '%s' = %g is not finite",
                         dem_params_origin(ps, s->key), law->name, s->key, v);
    if (!(v >= s->min && v <= s->max))
      return dem_err_set(err, DEM_ERANGE,
                         "%slaw '%s': coefficient '%s' = %g %s is outside the allowed range %s "
                         "(%s)",
                         dem_params_origin(ps, s->key), law->name, s->key, v, s->unit, range,
                         s->about);
  }
  ct->law = law;
  int rc = law->set_coeffs(&full, ct->c, err);
  if (rc) {
    ct->law = NULL;
    return rc;
  }
  for (int i = 0; i < DEM_LAW_NCOEF_MAX; i++)
    if (!isfinite(ct->c[i])) {
      ct->law = NULL;
      return dem_err_set(err, DEM_EPHYSICS,
                         "law '%s': the parameter set gives a non-finite derived coefficient "
                         "(slot %d)",
                         law->name, i);
    }
  return DEM_OK;
}

int dem_contact_check_keys(const dem_law *law, const dem_params *ps, const char *const *extra,
                           dem_err *err) {
  for (int i = 0; i < ps->n; i++) {
    const char *k = ps->p[i].key;
    if (dem_contact_law_has_coef(law, k)) continue;
    int found = 0;
    for (const char *const *e = extra; e && *e; e++)
      if (strcmp(*e, k) == 0) found = 1;
    if (found) continue;
    char list[DEM_ERRMSG_LEN / 2] = "";
    size_t used = 0;
    for (int j = 0; j < law->ncoef && used + 16 < sizeof list; j++)
      used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", j ? ", " : "",
                               law->coef[j].key);
    for (const char *const *e = extra; e && *e && used + 16 < sizeof list; e++)
      used += (size_t)snprintf(list + used, sizeof list - used, ", %s", *e);
    return dem_err_set(err, DEM_ENOTFOUND, "%sunknown key '%s' for law '%s' (known: %s)",
                       dem_params_origin(ps, k), k, law->name, list);
  }
  return DEM_OK;
}

int dem_contact_init(const dem_contact *ct, const dem_geom *g, double *hist, dem_err *err) {
  if (!ct->law) return dem_err_set(err, DEM_EINVAL, "contact law not set up");
  if (!(g->R > 0.0) || !(g->m > 0.0) || !isfinite(g->R) || !isfinite(g->m))
    return dem_err_set(err, DEM_ERANGE,
                       "contact geometry R* = %g m, m* = %g kg: both must be finite and > 0",
                       g->R, g->m);
  memset(hist, 0, sizeof(double) * (size_t)ct->law->nhist);
  return ct->law->init ? ct->law->init(ct->c, g, hist, err) : DEM_OK;
}

double dem_contact_kref(const dem_contact *ct, const dem_geom *g, double v) {
  return ct->law->kref(ct->c, g, v);
}

double dem_contact_reduced_modulus(const dem_params *ps) {
  double E = dem_params_get_or(ps, "E", NAN), nu = dem_params_get_or(ps, "nu", NAN);
  double wE = dem_params_get_or(ps, "wall_E", -1.0), wnu = dem_params_get_or(ps, "wall_nu", -2.0);
  if (wE < 0.0) wE = E;    /* the DEM_COEF_ELASTIC default: an equal sphere */
  if (wnu < -1.0) wnu = nu;
  return dem_reduced_modulus(E, nu, wE, wnu);
}
