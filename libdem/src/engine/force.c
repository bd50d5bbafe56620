/* Particle-particle contact forces over the half neighbour list, and the parallel scheme.
 *
 * Geometry of a pair (i, j), n the unit normal from j to i, r = |x_i - x_j|:
 *   overlap      alpha = r_i + r_j - r                      (m, > 0 compression)
 *   approach     alpha_dot = -(v_i - v_j) . n               (m/s, > 0 approaching)
 *   contact point in the middle of the overlap, at a_i = r_i - alpha/2 from centre i and
 *   a_j = r_j - alpha/2 from centre j (the same point for both, so angular momentum is
 *   conserved exactly); its relative velocity
 *                v_c = v_i - v_j - (a_i w_i + a_j w_j) x n
 *   tangential   v_t = v_c - (v_c . n) n
 *   R* = r_i r_j / (r_i + r_j), m* = m_i m_j / (m_i + m_j)   (thesis eq 3.16)
 * Force on i: F = f_n n + F_t (f_n from the law, > 0 repulsive; F_t from dem/tangential.h);
 * on j: -F. Torques: T_i = -a_i n x F_t, T_j = -a_j n x F_t; rolling M_i from
 * dem_rolling_torque with w_rel = w_i - w_j, M_j = -M_i r_j / r_i, regularised below
 * w_eps = dem_rolling_omega_eps (relative-rotation inertia) so that one step never
 * reverses the relative spin.
 *
 * Parallel scheme (docs/engine.md): the particles are in cell order and thread t owns a
 * contiguous range of rows [a_t, b_t), balanced by pair count. Because j > i >= a_t, thread
 * t writes the reaction on j directly when j < b_t (no other thread touches that range);
 * when j >= b_t the reaction goes to the thread's spill list, and the spill lists are added
 * after the loop in thread order. The summation order is therefore fixed for a given
 * thread count (bit-identical runs) and only the order of a few additions changes with the
 * thread count (round-off).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"


void dem_engine_partition(dem_sim *s) {
  const dem_nlist *l = &s->nl;
  size_t n = s->p.n;
  int nt = s->nthreads;
  /* cost of a row: its pairs plus a constant for the particle's own work (walls, zeroing) */
  double total = (double)l->npairs + 2.0 * (double)n;
  size_t i = 0;
  double acc = 0.0;
  for (int t = 0; t < nt; t++) {
    s->td[t].row_begin = i;
    double target = total * (double)(t + 1) / nt;
    while (i < n && (t == nt - 1 || acc + 0.5 * ((l->first[i + 1] - l->first[i]) + 2.0) < target)) {
      acc += (double)(l->first[i + 1] - l->first[i]) + 2.0;
      i++;
    }
    s->td[t].row_end = i;
  }
}

int dem_engine_spill_reserve(dem_sim *s, dem_err *err) {
  const dem_nlist *l = &s->nl;
  size_t maxrow = 1;
  for (size_t i = 0; i < l->n; i++)
    if (l->first[i + 1] - l->first[i] > maxrow) maxrow = l->first[i + 1] - l->first[i];
  for (int t = 0; t < s->nthreads; t++) {
    dem_tdata *td = &s->td[t];
    if (2 * maxrow > td->cap_cand) {
      uint32_t *c = realloc(td->cand, 2 * maxrow * sizeof *c);
      if (!c) return dem_err_set(err, DEM_ENOMEM, "force scratch: out of memory");
      td->cand = c;
      td->cap_cand = 2 * maxrow;
    }
    size_t cnt = 0;
    for (size_t i = td->row_begin; i < td->row_end; i++)
      for (uint32_t q = l->first[i]; q < l->first[i + 1]; q++) cnt += l->nbr[q] >= td->row_end;
    if (cnt > td->cap_spill) {
      dem_spill *sp = realloc(td->spill, cnt * sizeof *sp);
      if (!sp) return dem_err_set(err, DEM_ENOMEM, "force spill buffers: out of memory");
      td->spill = sp;
      td->cap_spill = cnt;
    }
    td->nspill = 0;
  }
  return DEM_OK;
}

static inline void cross(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

void dem_engine_pair_forces(dem_sim *s, dem_tdata *td) {
  const dem_particles *p = &s->p;
  const double *restrict x = p->x, *restrict v = p->v, *restrict w = p->omega;
  const double *restrict rad = p->radius;
  const double *restrict invr = s->invr, *restrict invm = s->invm;
  const int *restrict mat = p->material;
  double *restrict f = p->f, *restrict tq = p->torque;
  const uint32_t *restrict first = s->nl.first, *restrict nbr = s->nl.nbr;
  double *restrict hist = s->nl.hist;
  uint8_t *restrict touch = s->nl.touch;
  const int nh = s->nh, hoff = s->hoff, need_state = s->need_state;
  const double dt = s->dt;
  const size_t a = td->row_begin, b = td->row_end;
  size_t contacts = 0, nspill = 0;
  double max_ov = td->max_overlap;

  for (size_t i = a; i < b; i++) {
    const double xi0 = x[3 * i], xi1 = x[3 * i + 1], xi2 = x[3 * i + 2];
    const double ri = rad[i], ir = invr[i], im = invm[i];
    const int mati = mat[i];
    double fi[3] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
    double ti[3] = {tq[3 * i], tq[3 * i + 1], tq[3 * i + 2]};
    /* the row's own velocities, kept in registers across the law calls */
    const double vi[3] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
    const double wi[3] = {w[3 * i], w[3 * i + 1], w[3 * i + 2]};
    /* Pass 1 (branch-free): the pairs that need the law (overlapping, or a live state
     * word of an adhesive/plastic law) go to cand[0..m); pairs apart whose spring may
     * still be loaded (touch[q]) go to the tail and are reset. Pairs apart that were
     * apart before touch nothing but the positions. */
    const uint32_t q0 = first[i], q1 = first[i + 1];
    uint32_t *restrict cand = td->cand;
    uint32_t m = 0, z = q1 - q0;
    for (uint32_t q = q0; q < q1; q++) {
      const size_t j = nbr[q];
      const double dx = xi0 - x[3 * j], dy = xi1 - x[3 * j + 1], dz = xi2 - x[3 * j + 2];
      const double rs = ri + rad[j];
      int c = dx * dx + dy * dy + dz * dz < rs * rs;
      if (need_state) c |= hist[(size_t)q * nh] != 0.0;
      const int stale = (c ^ 1) & touch[q];
      cand[m] = q;
      m += (uint32_t)c;
      cand[z] = q;
      z += (uint32_t)stale;
    }
    for (uint32_t k = q1 - q0; k < z; k++) {
      double *xs = hist + (size_t)cand[k] * nh + hoff;
      xs[0] = xs[1] = xs[2] = 0.0;
      touch[cand[k]] = 0;
    }
    /* Pass 2: the contacts. */
    for (uint32_t kc = 0; kc < m; kc++) {
      const uint32_t q = cand[kc];
      const size_t j = nbr[q];
      double *restrict h = hist + (size_t)q * nh;
      const double dx = xi0 - x[3 * j], dy = xi1 - x[3 * j + 1], dz = xi2 - x[3 * j + 2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      const double rj = rad[j], rs = ri + rj;
      const dem_inter *in = dem_engine_inter(s, mati, mat[j]);
      const double r = sqrt(r2);
      const double inv = r > 0.0 ? 1.0 / r : 0.0;
      const double n[3] = {r > 0.0 ? dx * inv : 0.0, r > 0.0 ? dy * inv : 0.0,
                           r > 0.0 ? dz * inv : 1.0};
      const double alpha = rs - r;
      /* R* = 1/(1/r_i + 1/r_j), m* = 1/(1/m_i + 1/m_j) with one division */
      const double sr = ir + invr[j], sm = im + invm[j], d = 1.0 / (sr * sm);
      dem_geom g = {sm * d, sr * d};
      const double *vj = v + 3 * j, *wj = w + 3 * j;
      const double vr[3] = {vi[0] - vj[0], vi[1] - vj[1], vi[2] - vj[2]};
      const double vn = vr[0] * n[0] + vr[1] * n[1] + vr[2] * n[2];
      const unsigned fl = in->fl;
      if ((fl & DEM_IF_INIT) && h[0] == 0.0) dem_contact_init(&in->normal, &g, h, NULL);
      dem_normal out;
      in->normal.law->force(in->normal.c, &g, h, alpha, -vn, &out);
      touch[q] = (uint8_t)out.contact;
      if (!out.contact) {
        double *xi = h + hoff;
        xi[0] = xi[1] = xi[2] = 0.0;
        if (out.f == 0.0) continue;
      }
      contacts++;
      {
        double ov = alpha * (ir > invr[j] ? ir : invr[j]); /* alpha / min(r_i, r_j) */
        max_ov = ov > max_ov ? ov : max_ov;
      }
      double F[3] = {out.f * n[0], out.f * n[1], out.f * n[2]};
      double tqi[3] = {0.0, 0.0, 0.0}, tqj[3] = {0.0, 0.0, 0.0};
      if ((fl & DEM_IF_TANG) && out.contact) {
        /* branch vectors to the middle of the overlap: both bodies share the contact
         * point, so the torques conserve angular momentum exactly */
        const double ai = ri - 0.5 * alpha, aj = rj - 0.5 * alpha;
        const double ws[3] = {ai * wi[0] + aj * wj[0], ai * wi[1] + aj * wj[1],
                              ai * wi[2] + aj * wj[2]};
        double wxn[3];
        cross(ws, n, wxn);
        /* contact-point relative velocity; dem_tangential_force drops its normal part */
        const double vt[3] = {vr[0] - wxn[0], vr[1] - wxn[1], vr[2] - wxn[2]};
        double ft[3], nxf[3];
        dem_tangential_force(&in->tang, h + hoff, n, vt, dt, g.R, out.alpha_t,
                             g.m, out.f, out.f_adh, ft);
        F[0] += ft[0];
        F[1] += ft[1];
        F[2] += ft[2];
        cross(n, ft, nxf);
        for (int k = 0; k < 3; k++) {
          tqi[k] = -ai * nxf[k];
          tqj[k] = -aj * nxf[k];
        }
      }
      if ((fl & DEM_IF_ROLL) && out.contact) {
        const double wrel[3] = {wi[0] - wj[0], wi[1] - wj[1], wi[2] - wj[2]};
        double mr[3];
        /* regularisation: the relative-rotation inertia (dem/tangential.h) */
        const double Irel = 1.0 / (s->invI[i] + rj * ir * s->invI[j]);
        const double weps = dem_rolling_omega_eps(in->roll.mu_r, fabs(out.f), ri, Irel, dt);
        dem_rolling_torque(&in->roll, wrel, fabs(out.f), ri, weps, mr);
        const double sc = rj / ri;
        for (int k = 0; k < 3; k++) {
          tqi[k] += mr[k];
          tqj[k] -= sc * mr[k];
        }
      }
      for (int k = 0; k < 3; k++) {
        fi[k] += F[k];
        ti[k] += tqi[k];
      }
      if (j < b) {
        for (int k = 0; k < 3; k++) {
          f[3 * j + k] -= F[k];
          tq[3 * j + k] += tqj[k];
        }
      } else {
        dem_spill *sp = td->spill + nspill++;
        sp->j = (uint32_t)j;
        for (int k = 0; k < 3; k++) {
          sp->f[k] = -F[k];
          sp->t[k] = tqj[k];
        }
      }
    }
    for (int k = 0; k < 3; k++) {
      f[3 * i + k] = fi[k];
      tq[3 * i + k] = ti[k];
    }
  }
  td->contacts += contacts;
  td->nspill = nspill;
  td->max_overlap = max_ov;
}
