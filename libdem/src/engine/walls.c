/* Walls: an infinite plane, the inside of a cylindrical die, a flat disc (piston).
 *
 * Contact geometry is analytic: the penetration depth alpha = r - (distance from the
 * surface to the centre) and the unit normal n from the surface to the particle centre.
 *   plane     d = (x - p) . n;  alpha = r - d;  normal n.
 *   cylinder  (inside, axis through p along a = n, radius Rc): rho = |(x - p) - ((x-p).a) a|,
 *             alpha = r + rho - Rc, normal towards the axis; the concave surface gives
 *             R* = (1/r - 1/Rc)^-1 = r Rc / (Rc - r) (thesis eq 3.16 with R2 = -Rc).
 *   disc      (centre p, face normal n, radius Rd): over the face (rho <= Rd) as a plane;
 *             beyond it, contact with the rim circle: alpha = r - |x - q|, q the nearest
 *             rim point, normal (x - q)/|x - q|.
 * A wall is rigid and infinitely heavy: m* = m_i; its material enters through the law's
 * coefficients of the interaction (particle material, wall material).
 * Force on the particle: F = f_n n + F_t; torque on the particle: -a_i n x F_t + M_roll
 * with a_i = r_i - alpha, the distance from the centre to the wall surface. The wall
 * receives -F at the contact point x_c = x_i - a_i n; its torque is taken about p.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"


static int normalise(double n[3]) {
  double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(l > 0.0) || !isfinite(l)) return 0;
  for (int k = 0; k < 3; k++) n[k] /= l;
  return 1;
}

int dem_sim_add_wall(dem_sim *s, const dem_wall_spec *w, int *index, dem_err *err) {
  if (s->nwall >= DEM_ENGINE_MAX_WALLS)
    return dem_err_set(err, DEM_ERANGE, "walls: at most %d allowed", DEM_ENGINE_MAX_WALLS);
  if (w->kind < DEM_WALL_PLANE || w->kind > DEM_WALL_BOX)
    return dem_err_set(err, DEM_EINVAL, "wall %d: unknown kind %d", s->nwall, (int)w->kind);
  if (w->material < 0 || w->material >= s->nmat)
    return dem_err_set(err, DEM_ERANGE, "wall %d: material %d outside [0, %d)", s->nwall,
                       w->material, s->nmat);
  dem_wall nw;
  memset(&nw, 0, sizeof nw);
  nw.spec = *w;
  for (int k = 0; k < 3; k++)
    if (!isfinite(w->p[k]) || !isfinite(w->v[k]))
      return dem_err_set(err, DEM_ENONFINITE, "wall %d: non-finite point or velocity", s->nwall);
  if (!normalise(nw.spec.n))
    return dem_err_set(err, DEM_EINVAL, "wall %d: normal/axis (%g, %g, %g) has no direction",
                       s->nwall, w->n[0], w->n[1], w->n[2]);
  if (w->kind != DEM_WALL_PLANE && !(w->radius > 0.0 && isfinite(w->radius)))
    return dem_err_set(err, DEM_ERANGE, "wall %d: radius = %g m (allowed: > 0)", s->nwall,
                       w->radius);
  if (!(w->length >= 0.0 && isfinite(w->length)))
    return dem_err_set(err, DEM_ERANGE, "wall %d: length = %g m (allowed: >= 0, finite; 0 "
                       "without end)", s->nwall, w->length);
  if (!isfinite(w->angle))
    return dem_err_set(err, DEM_ERANGE, "wall %d: angle = %g rad (allowed: finite)", s->nwall,
                       w->angle);
  if (s->nh > 0) {
    nw.hist = calloc(s->cap ? s->cap : 1, (size_t)s->nh * sizeof(double));
    if (!nw.hist) return dem_err_set(err, DEM_ENOMEM, "wall %d: out of memory", s->nwall);
  }
  s->wall[s->nwall] = nw;
  if (index) *index = s->nwall;
  s->nwall++;
  s->need_build = 1;
  return DEM_OK;
}

int dem_sim_set_wall_velocity(dem_sim *s, int wall, const double v[3], dem_err *err) {
  if (wall < 0 || wall >= s->nwall)
    return dem_err_set(err, DEM_ERANGE, "wall %d outside [0, %d)", wall, s->nwall);
  for (int k = 0; k < 3; k++)
    if (!isfinite(v[k])) return dem_err_set(err, DEM_ENONFINITE, "wall %d: velocity", wall);
  for (int k = 0; k < 3; k++) s->wall[wall].spec.v[k] = v[k];
  s->wall[wall].servo = 0;
  return DEM_OK;
}

int dem_sim_set_wall_servo(dem_sim *s, int wall, double f_target, double gain, double v_max,
                           dem_err *err) {
  if (wall < 0 || wall >= s->nwall)
    return dem_err_set(err, DEM_ERANGE, "wall %d outside [0, %d)", wall, s->nwall);
  if (!isfinite(f_target) || !(gain > 0.0 && isfinite(gain)) || !(v_max > 0.0 && isfinite(v_max)))
    return dem_err_set(err, DEM_ERANGE,
                       "wall %d servo: f_target = %g N (finite), gain = %g m/(s N) (> 0), "
                       "v_max = %g m/s (> 0)",
                       wall, f_target, gain, v_max);
  dem_wall *wl = &s->wall[wall];
  wl->servo = 1;
  wl->f_target = f_target;
  wl->gain = gain;
  wl->v_max = v_max;
  dem_engine_servo(s);
  return DEM_OK;
}

void dem_engine_servo(dem_sim *s) {
  for (int w = 0; w < s->nwall; w++) {
    dem_wall *wl = &s->wall[w];
    if (!wl->servo) continue;
    const double *n = wl->spec.n;
    /* The servo reads the rate-independent load f - fd, not f: the dashpots of the wall's
     * contacts see the wall's own velocity, so a servo reading f fed v_n back into
     * v_(n+1) through their sum c_tot and alternated, growing, once gain c_tot > 1
     * (docs/scene.md, "What limits the servo's gain"). */
    double f[3];
    dem_sim_wall_load_rate_independent(s, w, f);
    const double fc = -(f[0] * n[0] + f[1] * n[1] + f[2] * n[2]);
    double sp = wl->gain * (wl->f_target - fc);
    sp = sp > wl->v_max ? wl->v_max : (sp < -wl->v_max ? -wl->v_max : sp);
    for (int k = 0; k < 3; k++) wl->spec.v[k] = sp * n[k];
  }
}

int dem_sim_wall_load_rate_independent(const dem_sim *s, int wall, double f[3]) {
  if (wall < 0 || wall >= s->nwall) return DEM_ERANGE;
  for (int k = 0; k < 3; k++) f[k] = s->wall[wall].f[k] - s->wall[wall].fd[k];
  return DEM_OK;
}

int dem_sim_wall(const dem_sim *s, int wall, dem_wall_spec *out) {
  if (wall < 0 || wall >= s->nwall) return DEM_ERANGE;
  *out = s->wall[wall].spec;
  return DEM_OK;
}

int dem_sim_wall_load(const dem_sim *s, int wall, double f[3], double t[3], double *work) {
  if (wall < 0 || wall >= s->nwall) return DEM_ERANGE;
  for (int k = 0; k < 3; k++) {
    if (f) f[k] = s->wall[wall].f[k];
    if (t) t[k] = s->wall[wall].t[k];
  }
  if (work) *work = s->wall[wall].work;
  return DEM_OK;
}

double dem_wall_gap(const dem_wall_spec *w, const double x[3], double r, double n[3],
                    double *rfac) {
  const double d[3] = {x[0] - w->p[0], x[1] - w->p[1], x[2] - w->p[2]};
  const double dn = d[0] * w->n[0] + d[1] * w->n[1] + d[2] * w->n[2];
  *rfac = 1.0;
  if (w->kind >= DEM_WALL_SPHERE) return dem_indenter_gap(w, x, r, n, rfac);
  if (w->kind == DEM_WALL_PLANE) {
    n[0] = w->n[0];
    n[1] = w->n[1];
    n[2] = w->n[2];
    return r - dn;
  }
  const double rad[3] = {d[0] - dn * w->n[0], d[1] - dn * w->n[1], d[2] - dn * w->n[2]};
  const double rho = sqrt(rad[0] * rad[0] + rad[1] * rad[1] + rad[2] * rad[2]);
  if (w->kind == DEM_WALL_CYLINDER) {
    if (rho > 0.0) {
      for (int k = 0; k < 3; k++) n[k] = -rad[k] / rho;
    } else { /* on the axis: any radial direction, the particle is far from the wall */
      double e[3] = {1.0, 0.0, 0.0};
      if (fabs(w->n[0]) > 0.9) e[0] = 0.0, e[1] = 1.0;
      double en = e[0] * w->n[0] + e[1] * w->n[1] + e[2] * w->n[2];
      for (int k = 0; k < 3; k++) n[k] = e[k] - en * w->n[k];
      normalise(n);
    }
    *rfac = w->radius > r ? w->radius / (w->radius - r) : 1e6;
    return r + rho - w->radius;
  }
  /* disc */
  if (rho <= w->radius) {
    n[0] = w->n[0];
    n[1] = w->n[1];
    n[2] = w->n[2];
    return r - dn;
  }
  const double q[3] = {w->p[0] + w->radius * rad[0] / rho, w->p[1] + w->radius * rad[1] / rho,
                       w->p[2] + w->radius * rad[2] / rho};
  const double e[3] = {x[0] - q[0], x[1] - q[1], x[2] - q[2]};
  const double dist = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
  if (dist > 0.0)
    for (int k = 0; k < 3; k++) n[k] = e[k] / dist;
  else
    for (int k = 0; k < 3; k++) n[k] = w->n[k];
  return r - dist;
}

static inline void cross(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

static int block_active(const double *h, int nh) {
  for (int k = 0; k < nh; k++)
    if (h[k] != 0.0) return 1;
  return 0;
}

int dem_engine_wall_lists(dem_sim *s, dem_err *err) {
  const dem_particles *p = &s->p;
  for (int w = 0; w < s->nwall; w++) {
    dem_wall *wl = &s->wall[w];
    size_t m = 0;
    for (size_t i = 0; i < p->n; i++) {
      double n[3], rfac;
      double alpha = dem_wall_gap(&wl->spec, p->x + 3 * i, p->radius[i], n, &rfac);
      if (alpha > -s->skin || block_active(wl->hist + i * (size_t)s->nh, s->nh)) {
        if (m == wl->cap_list) {
          size_t c = wl->cap_list ? 2 * wl->cap_list : 256;
          uint32_t *l = realloc(wl->list, c * sizeof *l);
          if (!l) return dem_err_set(err, DEM_ENOMEM, "wall %d: out of memory", w);
          wl->list = l;
          wl->cap_list = c;
        }
        wl->list[m++] = (uint32_t)i;
      } else {
        /* out of reach: a contact that ended long ago leaves nothing behind */
        double *h = wl->hist + i * (size_t)s->nh;
        h[s->hoff] = h[s->hoff + 1] = h[s->hoff + 2] = 0.0;
      }
    }
    wl->nlist = m;
    for (int k = 0; k < 3; k++) wl->p_build[k] = wl->spec.p[k];
  }
  return DEM_OK;
}

int dem_engine_walls_moved(const dem_sim *s) {
  const double lim = 0.25 * s->skin * s->skin;
  for (int w = 0; w < s->nwall; w++) {
    const dem_wall *wl = &s->wall[w];
    double d2 = 0.0;
    for (int k = 0; k < 3; k++) d2 += (wl->spec.p[k] - wl->p_build[k]) * (wl->spec.p[k] - wl->p_build[k]);
    if (d2 > lim) return 1;
  }
  return 0;
}

static size_t lower_bound(const uint32_t *a, size_t n, size_t key) {
  size_t lo = 0, hi = n;
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (a[mid] < key) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

/* Wall forces on particles [i0, i1), added to f and torque; the loads on the walls go to
 * the thread's accumulators. */
void dem_engine_wall_forces(dem_sim *s, dem_tdata *td, size_t i0, size_t i1) {
  const dem_particles *p = &s->p;
  const int nh = s->nh, hoff = s->hoff;
  size_t contacts = 0;
  double max_ov = td->max_overlap;
  for (int wi = 0; wi < s->nwall; wi++) {
    const dem_wall *wl = &s->wall[wi];
    const dem_wall_spec *ws = &wl->spec;
    double wf[3] = {0, 0, 0}, wt[3] = {0, 0, 0}, wfd[3] = {0, 0, 0}, pow_ = 0.0;
    const size_t k0 = lower_bound(wl->list, wl->nlist, i0);
    const size_t k1 = lower_bound(wl->list, wl->nlist, i1);
    for (size_t kk = k0; kk < k1; kk++) {
      const size_t i = wl->list[kk];
      const double *x = p->x + 3 * i, ri = p->radius[i];
      double *h = wl->hist + i * (size_t)nh;
      double n[3], rfac;
      const double alpha = dem_wall_gap(ws, x, ri, n, &rfac);
      if (alpha < 0.0 && h[0] == 0.0) {
        double *xi = h + hoff;
        if (xi[0] != 0.0 || xi[1] != 0.0 || xi[2] != 0.0) xi[0] = xi[1] = xi[2] = 0.0;
        continue;
      }
      const dem_inter *in = dem_engine_inter(s, p->material[i], ws->material);
      const double *v = p->v + 3 * i, *w = p->omega + 3 * i;
      const double vr[3] = {v[0] - ws->v[0], v[1] - ws->v[1], v[2] - ws->v[2]};
      const double vn = vr[0] * n[0] + vr[1] * n[1] + vr[2] * n[2];
      dem_geom g = {ri * rfac, p->mass[i]};
      if ((in->fl & DEM_IF_INIT) && h[0] == 0.0) dem_contact_init(&in->normal, &g, h, NULL);
      dem_normal out;
      in->normal.law->force(in->normal.c, &g, h, alpha, -vn, &out);
      if (!out.contact) {
        h[hoff] = h[hoff + 1] = h[hoff + 2] = 0.0;
        if (out.f == 0.0) continue;
      }
      contacts++;
      max_ov = alpha / ri > max_ov ? alpha / ri : max_ov;
      double F[3] = {out.f * n[0], out.f * n[1], out.f * n[2]}, T[3] = {0, 0, 0};
      if ((in->fl & DEM_IF_TANG) && out.contact) {
        double wxn[3], ft[3], nxf[3];
        const double ai = ri - alpha; /* centre to the contact point on the wall surface */
        const double ws3[3] = {ai * w[0], ai * w[1], ai * w[2]};
        cross(ws3, n, wxn);
        const double vt[3] = {vr[0] - wxn[0], vr[1] - wxn[1], vr[2] - wxn[2]};
        dem_tangential_force(&in->tang, h + hoff, n, vt, s->dt, g.R, out.alpha_t, g.m,
                             out.f, out.f_adh, ft);
        cross(n, ft, nxf);
        for (int k = 0; k < 3; k++) {
          F[k] += ft[k];
          T[k] = -ai * nxf[k];
        }
      }
      if ((in->fl & DEM_IF_ROLL) && out.contact) {
        double mr[3];
        const double weps =
            dem_rolling_omega_eps(in->roll.mu_r, fabs(out.f), ri, p->inertia[i], s->dt);
        dem_rolling_torque(&in->roll, w, fabs(out.f), ri, weps, mr);
        for (int k = 0; k < 3; k++) {
          T[k] += mr[k];
          wt[k] -= mr[k];
        }
      }
      for (int k = 0; k < 3; k++) {
        p->f[3 * i + k] += F[k];
        p->torque[3 * i + k] += T[k];
        wf[k] -= F[k];
        wfd[k] -= out.f_damp * n[k];
      }
      /* torque on the wall about its point p: (x_c - p) x (-F) */
      const double arm[3] = {x[0] - (ri - alpha) * n[0] - ws->p[0],
                             x[1] - (ri - alpha) * n[1] - ws->p[1],
                             x[2] - (ri - alpha) * n[2] - ws->p[2]};
      const double mF[3] = {-F[0], -F[1], -F[2]};
      double c[3];
      cross(arm, mF, c);
      for (int k = 0; k < 3; k++) wt[k] += c[k];
      pow_ += F[0] * ws->v[0] + F[1] * ws->v[1] + F[2] * ws->v[2];
    }
    for (int k = 0; k < 3; k++) {
      td->wf[wi][k] = wf[k];
      td->wfd[wi][k] = wfd[k];
      td->wt[wi][k] = wt[k];
    }
    td->wpow[wi] = pow_;
  }
  td->wall_contacts += contacts;
  td->max_overlap = max_ov;
}
