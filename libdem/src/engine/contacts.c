/* Contact export (dem/engine.h, dem_sim_contacts): every contact of the last force
 * evaluation with the force it applied, by a read-only re-evaluation.
 *
 * Why a separate pass: the force loop (force.c, walls.c) is the hot path and stores no
 * per-contact forces. After a step the engine holds everything needed to rebuild them:
 *   - positions and wall points: unchanged since the evaluation (the drift comes first in a
 *     step, run.c);
 *   - velocities: the evaluation saw the half-step velocities v_h; the second half kick
 *     made v = v_h + dt/2 F/m with the stored total force F, so v_h = v - dt/2 F/m (exact
 *     up to one rounding of v). After dem_sim_run(s, 0) (an evaluation without a kick,
 *     s->f_unkicked) the velocities are used as they are;
 *   - wall velocities: a servo sets spec.v from the load right after the evaluation, so the
 *     velocity used is kept in dem_wall.v_eval (run.c, collect);
 *   - histories: the normal law's block as the evaluation left it. A law evaluated again at
 *     the same overlap with its updated block returns the same force (the plastic laws'
 *     alpha_max is then alpha itself, a broken or reset contact stays at zero force); the
 *     law runs on a copy, so nothing changes;
 *   - the tangential spring xi as the evaluation left it: dem_tangential_spring rotates and
 *     increments xi, then either slides (shortens xi so that k |xi| = F_lim; force -k xi, no
 *     damping) or sticks (force -k xi - c v_t); in both cases the capped total is applied.
 *     From the stored xi: k |xi| >= F_lim (to a relative 1e-9, the rounding of the
 *     shortening) means it slid. A sticking contact within 1e-9 of the limit would be taken
 *     as sliding and lose its (capped) damping term: a rare event and a small error.
 * The candidate tests (which pairs and walls the loops evaluate) are the loops' own. The
 * pass is single-threaded; it costs about one force evaluation on one thread.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "../contact/hertz_kernel.h"
#include "internal.h"

static inline void cross(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* The tangential force that dem_tangential_spring applied, from the spring xi it left
 * (read only), stiffness k, sticking damping c, tangential velocity v (in the tangent
 * plane), normal force fn and adhesive addition f_adh. */
static void spring_applied(const dem_tangential *t, const double xi[3], const double v[3],
                           double k, double c, double fn, double f_adh, double ft[3]) {
  const double cap = fn + f_adh;
  const double flim = (t->kind == DEM_TANGENTIAL_NONE ? 0.0 : t->mu) * (cap > 0.0 ? cap : 0.0);
  const double flim2 = flim * flim;
  const double x2 = xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2];
  if (k * k * x2 >= flim2 * (1.0 - 1e-9)) c = 0.0; /* slid: xi at the limit, no damping */
  for (int a = 0; a < 3; a++) ft[a] = -k * xi[a] - c * v[a];
  const double f2 = ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2];
  if (f2 > flim2) {
    const double q = flim / sqrt(f2);
    for (int a = 0; a < 3; a++) ft[a] *= q;
  }
}

/* Append one record, growing the buffer. */
static dem_sim_contact *push(dem_sim_contact **buf, size_t *cap, size_t *n, dem_err *err) {
  if (*n == *cap) {
    size_t c = *cap ? 2 * *cap : 1024;
    dem_sim_contact *b = realloc(*buf, c * sizeof *b);
    if (!b) {
      dem_err_set(err, DEM_ENOMEM, "dem_sim_contacts: out of memory (%zu records)", c);
      return NULL;
    }
    *buf = b;
    *cap = c;
  }
  return *buf + (*n)++;
}

/* The velocities the last evaluation saw (see the top of the file). */
static void half_step(const dem_sim *s, size_t i, double v[3], double w[3]) {
  const dem_particles *p = &s->p;
  const double h = s->f_unkicked ? 0.0 : 0.5 * s->dt;
  const double cm = h * s->invm[i], ci = h * s->invI[i];
  for (int k = 0; k < 3; k++) {
    v[k] = p->v[3 * i + k] - cm * p->f[3 * i + k];
    w[k] = p->omega[3 * i + k] - ci * p->torque[3 * i + k];
  }
}

static int pairs(const dem_sim *s, dem_sim_contact **buf, size_t *cap, size_t *n,
                 dem_err *err) {
  const dem_particles *p = &s->p;
  const double *x = p->x, *rad = p->radius, *invr = s->invr, *invm = s->invm;
  const uint32_t *first = s->nl.first, *nbr = s->nl.nbr;
  const int nh = s->nh, hoff = s->hoff;
  double hcopy[DEM_LAW_NHIST_MAX + DEM_TANGENTIAL_NHIST];
  for (size_t i = 0; i < s->nl.n && i < p->n; i++) {
    double vi[3], wi[3];
    half_step(s, i, vi, wi);
    const double ri = rad[i];
    for (uint32_t q = first[i]; q < first[i + 1]; q++) {
      const size_t j = nbr[q];
      const double *h = s->nl.hist + (size_t)q * nh;
      const double dx = x[3 * i] - x[3 * j], dy = x[3 * i + 1] - x[3 * j + 1],
                   dz = x[3 * i + 2] - x[3 * j + 2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      const double rj = rad[j], rs = ri + rj;
      int c = r2 < rs * rs;
      if (s->need_state) c |= h[0] != 0.0;
      if (!c) continue;
      const dem_inter *in = dem_engine_inter(s, p->material[i], p->material[j]);
      const double r = sqrt(r2);
      const double inv = r > 0.0 ? 1.0 / r : 0.0;
      const double nv[3] = {r > 0.0 ? dx * inv : 0.0, r > 0.0 ? dy * inv : 0.0,
                            r > 0.0 ? dz * inv : 1.0};
      const double alpha = rs - r;
      /* R*, m* exactly as force.c forms them */
      const double sr = invr[i] + invr[j], sm = invm[i] + invm[j], d = 1.0 / (sr * sm);
      dem_geom g = {sm * d, sr * d};
      double vj[3], wj[3];
      half_step(s, j, vj, wj);
      const double vr[3] = {vi[0] - vj[0], vi[1] - vj[1], vi[2] - vj[2]};
      const double vn = vr[0] * nv[0] + vr[1] * nv[1] + vr[2] * nv[2];
      const unsigned fl = in->fl;
      dem_normal out;
      double kt = 0.0, ct = 0.0;
      if (fl & DEM_IF_HERTZ) {
        if (!(alpha > 0.0)) continue;
        dem_engine_hertz_normal(in, &g, alpha, vn, &out, &kt, &ct);
      } else {
        memcpy(hcopy, h, (size_t)nh * sizeof *hcopy);
        if ((fl & DEM_IF_INIT) && hcopy[0] == 0.0) dem_contact_init(&in->normal, &g, hcopy, NULL);
        in->normal.law->force(in->normal.c, &g, hcopy, alpha, -vn, &out);
      }
      if (!out.contact && out.f == 0.0) continue;
      dem_sim_contact *ct_ = push(buf, cap, n, err);
      if (!ct_) return DEM_ENOMEM;
      double F[3] = {out.f * nv[0], out.f * nv[1], out.f * nv[2]};
      if ((fl & DEM_IF_TANG) && out.contact) {
        const double ai = ri - 0.5 * alpha, aj = rj - 0.5 * alpha;
        const double ws[3] = {ai * wi[0] + aj * wj[0], ai * wi[1] + aj * wj[1],
                              ai * wi[2] + aj * wj[2]};
        double wxn[3], ft[3];
        cross(ws, nv, wxn);
        const double vt[3] = {vr[0] - vn * nv[0] - wxn[0], vr[1] - vn * nv[1] - wxn[1],
                              vr[2] - vn * nv[2] - wxn[2]};
        if (!(fl & DEM_IF_HZMINDLIN))
          dem_tangential_stiffness(&in->tang, g.R, out.alpha_t, g.m, &kt, &ct);
        spring_applied(&in->tang, h + hoff, vt, kt, ct, out.f, out.f_adh, ft);
        for (int k = 0; k < 3; k++) F[k] += ft[k];
      }
      ct_->i = i;
      ct_->j = j;
      ct_->wall = -1;
      ct_->alpha = alpha;
      ct_->fn = out.f;
      const double a = ri - 0.5 * alpha;
      for (int k = 0; k < 3; k++) {
        ct_->n[k] = nv[k];
        ct_->point[k] = x[3 * i + k] - a * nv[k];
        ct_->f[k] = F[k];
      }
    }
  }
  return DEM_OK;
}

static int walls(const dem_sim *s, dem_sim_contact **buf, size_t *cap, size_t *n,
                 dem_err *err) {
  const dem_particles *p = &s->p;
  const int nh = s->nh, hoff = s->hoff;
  double hcopy[DEM_LAW_NHIST_MAX + DEM_TANGENTIAL_NHIST];
  for (int wi = 0; wi < s->nwall; wi++) {
    const dem_wall *wl = &s->wall[wi];
    const dem_wall_spec *ws = &wl->spec;
    const double *wv = wl->have_v_eval ? wl->v_eval : ws->v;
    for (size_t kk = 0; kk < wl->nlist; kk++) {
      const size_t i = wl->list[kk];
      if (i >= p->n) continue;
      const double *x = p->x + 3 * i, ri = p->radius[i];
      const double *h = wl->hist + i * (size_t)nh;
      double nv[3], rfac;
      const double alpha = dem_wall_gap(ws, x, ri, nv, &rfac);
      if (alpha < 0.0 && h[0] == 0.0) continue;
      const dem_inter *in = dem_engine_inter(s, p->material[i], ws->material);
      double v[3], w[3];
      half_step(s, i, v, w);
      const double vr[3] = {v[0] - wv[0], v[1] - wv[1], v[2] - wv[2]};
      const double vn = vr[0] * nv[0] + vr[1] * nv[1] + vr[2] * nv[2];
      dem_geom g = {ri * rfac, p->mass[i]};
      memcpy(hcopy, h, (size_t)nh * sizeof *hcopy);
      if ((in->fl & DEM_IF_INIT) && hcopy[0] == 0.0) dem_contact_init(&in->normal, &g, hcopy, NULL);
      dem_normal out;
      in->normal.law->force(in->normal.c, &g, hcopy, alpha, -vn, &out);
      if (!out.contact && out.f == 0.0) continue;
      dem_sim_contact *ct_ = push(buf, cap, n, err);
      if (!ct_) return DEM_ENOMEM;
      double F[3] = {out.f * nv[0], out.f * nv[1], out.f * nv[2]};
      const double ai = ri - alpha; /* centre to the contact point on the wall surface */
      if ((in->fl & DEM_IF_TANG) && out.contact) {
        double wxn[3], ft[3], kt, ctg;
        const double ws3[3] = {ai * w[0], ai * w[1], ai * w[2]};
        cross(ws3, nv, wxn);
        const double vt[3] = {vr[0] - wxn[0], vr[1] - wxn[1], vr[2] - wxn[2]};
        /* as dem_tangential_force: stiffness, then the tangent-plane velocity */
        dem_tangential_stiffness(&in->tang, g.R, out.alpha_t, g.m, &kt, &ctg);
        const double tn = vt[0] * nv[0] + vt[1] * nv[1] + vt[2] * nv[2];
        const double vp[3] = {vt[0] - tn * nv[0], vt[1] - tn * nv[1], vt[2] - tn * nv[2]};
        spring_applied(&in->tang, h + hoff, vp, kt, ctg, out.f, out.f_adh, ft);
        for (int k = 0; k < 3; k++) F[k] += ft[k];
      }
      ct_->i = i;
      ct_->j = SIZE_MAX;
      ct_->wall = wi;
      ct_->alpha = alpha;
      ct_->fn = out.f;
      for (int k = 0; k < 3; k++) {
        ct_->n[k] = nv[k];
        ct_->point[k] = x[k] - ai * nv[k];
        ct_->f[k] = F[k];
      }
    }
  }
  return DEM_OK;
}

int dem_sim_contacts(const dem_sim *s, dem_sim_contact **buf, size_t *cap, size_t *n,
                     dem_err *err) {
  if (!s || !buf || !cap || !n)
    return dem_err_set(err, DEM_EINVAL, "dem_sim_contacts: NULL argument");
  *n = 0;
  if (s->p.n == 0) return DEM_OK;
  if (s->need_forces || s->nh == 0)
    return dem_err_set(err, DEM_EINVAL,
                       "dem_sim_contacts: the forces are not evaluated for the current state "
                       "(particles added, a wall moved or gravity changed since the last run); "
                       "dem_sim_run with 0 steps evaluates them");
  int rc;
  if ((rc = pairs(s, buf, cap, n, err))) return rc;
  return walls(s, buf, cap, n, err);
}
