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

#include "../contact/hertz_kernel.h"
#include "internal.h"

void dem_engine_inter_compile(dem_inter *in) {
  in->fl = (in->normal.law->init ? DEM_IF_INIT : 0u) |
           (in->tang.kind != DEM_TANGENTIAL_NONE ? DEM_IF_TANG : 0u) |
           (in->roll.mu_r > 0.0 ? DEM_IF_ROLL : 0u);
  in->hz_ct = 0.0;
  if (in->normal.law == &dem_law_hertz) {
    in->fl |= DEM_IF_HERTZ;
    const double Es = in->normal.c[DEM_HERTZ_C_ES];
    if (in->tang.kind == DEM_TANGENTIAL_MINDLIN && Es > 0.0) {
      /* k_t = 8 G* sqrt(R* alpha) = (4 G* / E*) S_n (3.25 / 3.14), so
       * eta_t sqrt(m* k_t) = eta_t sqrt(4 G* / E*) sqrt(m* S_n)  (paper eq 25) */
      in->fl |= DEM_IF_HZMINDLIN;
      in->hz_ct = in->tang.eta * sqrt(4.0 * in->tang.G / Es);
    }
  }
  memset(in->bc, 0, sizeof in->bc);
  if ((in->fl & DEM_IF_HERTZ) && !(in->fl & DEM_IF_ROLL) &&
      (!(in->fl & DEM_IF_TANG) || (in->fl & DEM_IF_HZMINDLIN))) {
    in->fl |= DEM_IF_BATCH;
    in->bc[DEM_BC_2ES] = 2.0 * in->normal.c[DEM_HERTZ_C_ES];
    in->bc[DEM_BC_ETA] = in->normal.c[DEM_HERTZ_C_ETA];
    if (in->fl & DEM_IF_TANG) {
      in->bc[DEM_BC_8G] = 8.0 * in->tang.G;
      in->bc[DEM_BC_CT] = in->hz_ct;
      in->bc[DEM_BC_MU] = in->tang.mu;
      in->bc[DEM_BC_TANG] = 1.0;
    }
  }
}


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

/* The paths off the common case (Hertz, no rolling resistance) are kept out of line, so
 * that they do not take registers from the hot loop. */
__attribute__((noinline)) static void generic_law(const dem_inter *in, const dem_geom *g,
                                                  double *h, double alpha, double alpha_dot,
                                                  dem_normal *out) {
  if ((in->fl & DEM_IF_INIT) && h[0] == 0.0) dem_contact_init(&in->normal, g, h, NULL);
  in->normal.law->force(in->normal.c, g, h, alpha, alpha_dot, out);
}

/* Rolling torque on i (added to tqi) and j (tqj) of a pair in contact, |F_n| = fn_abs. */
__attribute__((noinline)) static void rolling(const dem_sim *s, const dem_inter *in, size_t i,
                                              size_t j, const double wi[3], const double wj[3],
                                              double fn_abs, double ri, double rj, double ir,
                                              double dt, double tqi[3], double tqj[3]) {
  const double wrel[3] = {wi[0] - wj[0], wi[1] - wj[1], wi[2] - wj[2]};
  double mr[3];
  /* regularisation: the relative-rotation inertia (dem/tangential.h) */
  const double Irel = 1.0 / (s->invI[i] + rj * ir * s->invI[j]);
  const double weps = dem_rolling_omega_eps(in->roll.mu_r, fn_abs, ri, Irel, dt);
  dem_rolling_torque(&in->roll, wrel, fn_abs, ri, weps, mr);
  const double sc = rj / ri;
  for (int k = 0; k < 3; k++) {
    tqi[k] += mr[k];
    tqj[k] -= sc * mr[k];
  }
}

static void pair_forces_generic(dem_sim *s, dem_tdata *td) {
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
      dem_normal out;
      double kt = 0.0, ct = 0.0; /* tangential stiffness and damping (DEM_IF_HZMINDLIN) */
      if (fl & DEM_IF_HERTZ) {
        /* the common law inline, no call through the table (same kernel as hertz.c) */
        if (!(alpha > 0.0)) {
          touch[q] = 0;
          double *xi = h + hoff;
          xi[0] = xi[1] = xi[2] = 0.0;
          continue;
        }
        dem_engine_hertz_normal(in, &g, alpha, vn, &out, &kt, &ct);
      } else {
        generic_law(in, &g, h, alpha, -vn, &out);
      }
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
        /* tangential part of the contact-point relative velocity: (w_s x n) . n = 0, so
         * (v_c . n) = (v_r . n) = vn */
        const double vt[3] = {vr[0] - vn * n[0] - wxn[0], vr[1] - vn * n[1] - wxn[1],
                              vr[2] - vn * n[2] - wxn[2]};
        double ft[3], nxf[3];
        if (!(fl & DEM_IF_HZMINDLIN))
          dem_tangential_stiffness(&in->tang, g.R, out.alpha_t, g.m, &kt, &ct);
        dem_tangential_spring(&in->tang, h + hoff, n, vt, dt, kt, ct, out.f, out.f_adh, ft);
        F[0] += ft[0];
        F[1] += ft[1];
        F[2] += ft[2];
        cross(n, ft, nxf);
        for (int k = 0; k < 3; k++) {
          tqi[k] = -ai * nxf[k];
          tqj[k] = -aj * nxf[k];
        }
      }
      if ((fl & DEM_IF_ROLL) && out.contact)
        rolling(s, in, i, j, wi, wj, fabs(out.f), ri, rj, ir, dt, tqi, tqj);
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

/* ---- Batched kernel: Hertz with a Mindlin spring (or none), no rolling resistance ----
 *
 * The scalar loop above is bound by latency: per contact a chain of square roots and
 * divisions (|r|, 1/|r|, sqrt(R* alpha), sqrt(m* S_n), the spring rotation, ...) of
 * 15-20 cycles each, which the out-of-order core can hardly overlap with the next
 * contact's. Here the contacts of consecutive rows are gathered into a batch (struct of
 * arrays), the physics runs as one branch-free loop over the batch whose iterations are
 * independent (vectorised: 2 lanes with the baseline SSE2, 4-8 with -march), and the
 * forces are added in the original contact order afterwards, so every force and torque
 * sum sees the same additions in the same order as in the scalar loop: same result for a
 * given thread count, and the same arithmetic per contact as pair_forces_generic and
 * dem_tangential_spring (branches become selects; a select never changes a value). */
#define DEM_BATCH 64
#define DEM_PREFETCH_AHEAD 32 /* particles beyond a row's farthest neighbour */

#if defined(_OPENMP)
#define DEM_SIMD _Pragma("omp simd")
#elif defined(__GNUC__) && !defined(__clang__)
#define DEM_SIMD _Pragma("GCC ivdep")
#else
#define DEM_SIMD
#endif

typedef struct hm_batch {
  /* in */
  _Alignas(64) double dx[DEM_BATCH];
  _Alignas(64) double dy[DEM_BATCH];
  _Alignas(64) double dz[DEM_BATCH];
  _Alignas(64) double rs[DEM_BATCH];   /* r_i + r_j */
  _Alignas(64) double ri[DEM_BATCH];
  _Alignas(64) double rj[DEM_BATCH];
  _Alignas(64) double sr[DEM_BATCH];   /* 1/r_i + 1/r_j */
  _Alignas(64) double sm[DEM_BATCH];   /* 1/m_i + 1/m_j */
  _Alignas(64) double vx[DEM_BATCH];   /* v_i - v_j */
  _Alignas(64) double vy[DEM_BATCH];
  _Alignas(64) double vz[DEM_BATCH];
  _Alignas(64) double wix[DEM_BATCH];
  _Alignas(64) double wiy[DEM_BATCH];
  _Alignas(64) double wiz[DEM_BATCH];
  _Alignas(64) double wjx[DEM_BATCH];
  _Alignas(64) double wjy[DEM_BATCH];
  _Alignas(64) double wjz[DEM_BATCH];
  _Alignas(64) double sx[DEM_BATCH];   /* spring, in and out */
  _Alignas(64) double sy[DEM_BATCH];
  _Alignas(64) double sz[DEM_BATCH];
  _Alignas(64) double c2es[DEM_BATCH]; /* dem_inter.bc */
  _Alignas(64) double ceta[DEM_BATCH];
  _Alignas(64) double c8g[DEM_BATCH];
  _Alignas(64) double cct[DEM_BATCH];
  _Alignas(64) double cmu[DEM_BATCH];
  _Alignas(64) double ctg[DEM_BATCH];
  /* out */
  _Alignas(64) double alpha[DEM_BATCH];
  _Alignas(64) double fx[DEM_BATCH];
  _Alignas(64) double fy[DEM_BATCH];
  _Alignas(64) double fz[DEM_BATCH];
  _Alignas(64) double tix[DEM_BATCH];
  _Alignas(64) double tiy[DEM_BATCH];
  _Alignas(64) double tiz[DEM_BATCH];
  _Alignas(64) double tjx[DEM_BATCH];
  _Alignas(64) double tjy[DEM_BATCH];
  _Alignas(64) double tjz[DEM_BATCH];
  /* bookkeeping */
  double ovf[DEM_BATCH];               /* 1 / min(r_i, r_j) */
  uint32_t i[DEM_BATCH], j[DEM_BATCH], q[DEM_BATCH];
} hm_batch;

/* The physics of nb contacts (same formulas as the scalar path: geometry above,
 * contact/hertz_kernel.h, dem_tangential_spring). The branches of the scalar path become
 * 0/1 masks that multiply (a conditional expression would let the compiler move a square
 * root, division or load into a branch, and a loop with branches is not vectorised); every
 * division and square root is taken of a safe argument in every lane. Where the scalar
 * path takes a branch, the mask multiplies by exactly 1.0 or adds exactly 0.0, so the
 * values are the same bits. */
static inline __attribute__((always_inline)) void hm_compute_body(hm_batch *restrict b, int nb,
                                                                 double dt, const double *cu,
                                                                 int uni) {
  DEM_SIMD
  for (int k = 0; k < nb; k++) {
    const double dx = b->dx[k], dy = b->dy[k], dz = b->dz[k];
    const double r2 = dx * dx + dy * dy + dz * dz;
    const double r = sqrt(r2);
    const double rz = (r <= 0.0 ? 1.0 : 0.0); /* coincident centres: n = (0, 0, 1) */
    const double inv = 1.0 / (r + rz);
    const double nx = dx * inv, ny = dy * inv, nz = dz * inv + rz;
    const double alpha = b->rs[k] - r;
    const double on = alpha > 0.0 ? 1.0 : 0.0;
    const double al = alpha * on; /* 0 (of either sign) apart: masked below */
    /* R* = 1/(1/r_i + 1/r_j), m* = 1/(1/m_i + 1/m_j) with one division */
    const double sr = b->sr[k], sm = b->sm[k], d = 1.0 / (sr * sm);
    const double R = sm * d, m = sr * d;
    const double vrx = b->vx[k], vry = b->vy[k], vrz = b->vz[k];
    const double vn = vrx * nx + vry * ny + vrz * nz;
    /* Hertz (hertz_kernel.h): S_n = 2 E* sqrt(R* alpha), f = 2/3 S_n alpha + eta sqrt(m* S_n) alpha_dot */
    const double sra = sqrt(R * al);
    const double kn = (uni ? cu[DEM_BC_2ES] : b->c2es[k]) * sra;
    const double f_el = (2.0 / 3.0) * kn * al;
    const double smk = sqrt(m * kn);
    const double fn = f_el + (uni ? cu[DEM_BC_ETA] : b->ceta[k]) * smk * -vn;
    /* Mindlin k_t = 8 G* sqrt(R* alpha) (3.25), damping eta_t sqrt(m* k_t) (paper eq 25) */
    const double kt = (uni ? cu[DEM_BC_8G] : b->c8g[k]) * sra, ct = (uni ? cu[DEM_BC_CT] : b->cct[k]) * smk;
    /* branch vectors to the middle of the overlap */
    const double ai = b->ri[k] - 0.5 * al, aj = b->rj[k] - 0.5 * al;
    const double wsx = ai * b->wix[k] + aj * b->wjx[k];
    const double wsy = ai * b->wiy[k] + aj * b->wjy[k];
    const double wsz = ai * b->wiz[k] + aj * b->wjz[k];
    const double wxnx = wsy * nz - wsz * ny, wxny = wsz * nx - wsx * nz,
                 wxnz = wsx * ny - wsy * nx;
    const double vtx = vrx - vn * nx - wxnx, vty = vry - vn * ny - wxny,
                 vtz = vrz - vn * nz - wxnz;
    /* the spring (dem_tangential_spring): rotate into the tangent plane keeping |xi|
     * (a spring along n, m1 = 0, is lost) */
    const double x0 = b->sx[k], x1 = b->sy[k], x2 = b->sz[k];
    const double m0 = x0 * x0 + x1 * x1 + x2 * x2;
    const double xn = x0 * nx + x1 * ny + x2 * nz;
    const double px = x0 - xn * nx, py = x1 - xn * ny, pz = x2 - xn * nz;
    const double m1 = px * px + py * py + pz * pz;
    const double mz = (m1 <= 0.0 ? 1.0 : 0.0);
    const double sc = sqrt(m0 / (m1 + mz)) * (1.0 - mz);
    const double dtt = (uni ? cu[DEM_BC_TANG] : b->ctg[k]) * dt;
    double sx = sc * px + vtx * dtt, sy = sc * py + vty * dtt, sz = sc * pz + vtz * dtt;
    /* Coulomb limit (thesis 4.27-4.28), compared squared */
    const double flim = (uni ? cu[DEM_BC_MU] : b->cmu[k]) * (fn > 0.0 ? fn : 0.0);
    const double flim2 = flim * flim;
    const double xx = sx * sx + sy * sy + sz * sz;
    /* sliding: shorten the spring to k_t |xi| = F_lim, no damping */
    const double sl = (kt * kt * xx > flim2 ? 1.0 : 0.0);
    const double shr = flim / (kt * sqrt(xx) + (1.0 - sl));
    const double fs = shr * sl + (1.0 - sl);
    sx *= fs;
    sy *= fs;
    sz *= fs;
    const double c = ct * (1.0 - sl);
    double ftx = -kt * sx - c * vtx, fty = -kt * sy - c * vty, ftz = -kt * sz - c * vtz;
    /* damping may not lift the total above the limit */
    const double f2 = ftx * ftx + fty * fty + ftz * ftz;
    const double cp = (f2 > flim2 ? 1.0 : 0.0);
    const double qd = flim / (sqrt(f2) + (1.0 - cp));
    const double fq = qd * cp + (1.0 - cp);
    ftx *= fq;
    fty *= fq;
    ftz *= fq;
    b->fx[k] = fn * nx + ftx;
    b->fy[k] = fn * ny + fty;
    b->fz[k] = fn * nz + ftz;
    const double nfx = ny * ftz - nz * fty, nfy = nz * ftx - nx * ftz, nfz = nx * fty - ny * ftx;
    b->tix[k] = -ai * nfx;
    b->tiy[k] = -ai * nfy;
    b->tiz[k] = -ai * nfz;
    b->tjx[k] = -aj * nfx;
    b->tjy[k] = -aj * nfy;
    b->tjz[k] = -aj * nfz;
    b->sx[k] = alpha > 0.0 ? sx : 0.0;
    b->sy[k] = alpha > 0.0 ? sy : 0.0;
    b->sz[k] = alpha > 0.0 ? sz : 0.0;
    b->alpha[k] = alpha;
  }
}

/* Portable builds carry the kernel also for AVX2 and AVX-512 and pick one when the program
 * loads (gcc function multiversioning, x86-64 only); the results are the same bits in every
 * version (IEEE add, multiply, divide and square root; no contraction into FMA under
 * -std=c11). A -march build (DEM_NATIVE) compiles the one version it targets. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__AVX2__) && \
    defined(__gnu_linux__)
#define DEM_CLONES __attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
#else
#define DEM_CLONES
#endif

/* uni: every contact has the constants cu (one particle material), not gathered per contact */
DEM_CLONES __attribute__((noinline)) static void hm_compute_u(hm_batch *restrict b, int nb, double dt,
                                                   const double *cu) {
  hm_compute_body(b, nb, dt, cu, 1);
}
DEM_CLONES __attribute__((noinline)) static void hm_compute_v(hm_batch *restrict b, int nb, double dt) {
  hm_compute_body(b, nb, dt, NULL, 0);
}

/* State of one thread's pass over its rows, shared by the gather and the scatter. */
typedef struct hm_run {
  double *restrict f, *restrict tq, *restrict hist;
  uint8_t *restrict touch;
  dem_spill *spill;
  size_t nspill, contacts, bnd;
  int nh, hoff;
  double max_ov;
} hm_run;

/* Add the batch's forces in contact order and store the springs. A run of contacts of
 * the same row i is summed in registers: no contact of the run has j = i (j > i), so the
 * additions to f_i are the same as through memory. */
static void hm_scatter(const hm_batch *restrict b, int nb, hm_run *restrict u) {
  double *restrict f = u->f, *restrict tq = u->tq, *restrict hist = u->hist;
  uint8_t *restrict touch = u->touch;
  dem_spill *restrict spill = u->spill;
  size_t nspill = u->nspill, contacts = u->contacts;
  const size_t bnd = u->bnd, nh = (size_t)u->nh, hoff = (size_t)u->hoff;
  double max_ov = u->max_ov;
  int k = 0;
  while (k < nb) {
    const size_t i = b->i[k];
    double fx = f[3 * i], fy = f[3 * i + 1], fz = f[3 * i + 2];
    double tx = tq[3 * i], ty = tq[3 * i + 1], tz = tq[3 * i + 2];
    for (; k < nb && b->i[k] == i; k++) {
      const size_t q = b->q[k];
      double *xs = hist + q * nh + hoff;
      xs[0] = b->sx[k];
      xs[1] = b->sy[k];
      xs[2] = b->sz[k];
      const double al = b->alpha[k];
      touch[q] = (uint8_t)(al > 0.0);
      if (!(al > 0.0)) continue;
      contacts++;
      const double ov = al * b->ovf[k];
      max_ov = ov > max_ov ? ov : max_ov;
      const double Fx = b->fx[k], Fy = b->fy[k], Fz = b->fz[k];
      fx += Fx;
      fy += Fy;
      fz += Fz;
      tx += b->tix[k];
      ty += b->tiy[k];
      tz += b->tiz[k];
      const size_t j = b->j[k];
      if (j < bnd) {
        f[3 * j] -= Fx;
        f[3 * j + 1] -= Fy;
        f[3 * j + 2] -= Fz;
        tq[3 * j] += b->tjx[k];
        tq[3 * j + 1] += b->tjy[k];
        tq[3 * j + 2] += b->tjz[k];
      } else {
        dem_spill *sp = spill + nspill++;
        sp->j = (uint32_t)j;
        sp->f[0] = -Fx;
        sp->f[1] = -Fy;
        sp->f[2] = -Fz;
        sp->t[0] = b->tjx[k];
        sp->t[1] = b->tjy[k];
        sp->t[2] = b->tjz[k];
      }
    }
    f[3 * i] = fx;
    f[3 * i + 1] = fy;
    f[3 * i + 2] = fz;
    tq[3 * i] = tx;
    tq[3 * i + 1] = ty;
    tq[3 * i + 2] = tz;
  }
  u->nspill = nspill;
  u->contacts = contacts;
  u->max_ov = max_ov;
}

static void pair_forces_batched(dem_sim *s, dem_tdata *td) {
  const dem_particles *p = &s->p;
  const double *restrict x = p->x, *restrict v = p->v, *restrict w = p->omega;
  const double *restrict rad = p->radius;
  const double *restrict invr = s->invr, *restrict invm = s->invm;
  const int *restrict mat = p->material;
  const uint32_t *restrict first = s->nl.first, *restrict nbr = s->nl.nbr;
  const size_t a = td->row_begin, bnd = td->row_end, n = p->n;
  const int nh = s->nh, hoff = s->hoff;
  hm_run u = {p->f, p->torque, s->nl.hist, s->nl.touch, td->spill, 0, 0, bnd, nh, hoff,
              td->max_overlap};
  hm_batch bt;
  hm_batch *restrict b = &bt;
  int nb = 0;
  /* one particle material: its constants for every contact */
  const double *cu = s->pmat >= 0 ? s->inter[s->pmat][s->pmat].bc : NULL;
  for (size_t i = a; i < bnd; i++) {
    const double xi0 = x[3 * i], xi1 = x[3 * i + 1], xi2 = x[3 * i + 2];
    const double ri = rad[i], ir = invr[i], im = invm[i];
    const int mati = mat[i];
    const uint32_t q0 = first[i], q1 = first[i + 1];
    /* The rows' neighbours j > i lie within about one layer of cells ahead (neighbour.c), so
     * the particles first touched in this force evaluation are near the farthest j of the
     * row: fetch their lines a little ahead of use (they were evicted by the rest of the
     * step; the hardware prefetcher does not see this front among the other streams). */
    if (q1 > q0) {
      const size_t jf = (size_t)nbr[q1 - 1] + DEM_PREFETCH_AHEAD;
      if (jf < n) {
        __builtin_prefetch(x + 3 * jf, 0, 3);
        __builtin_prefetch(v + 3 * jf, 0, 3);
        __builtin_prefetch(w + 3 * jf, 0, 3);
        __builtin_prefetch(u.f + 3 * jf, 1, 3);
        __builtin_prefetch(u.tq + 3 * jf, 1, 3);
      }
    }
    /* Pass 1 (branch-free) as in pair_forces_generic: contacts to cand[0..m), pairs apart
     * whose spring may be loaded to the tail (reset). */
    uint32_t *restrict cand = td->cand;
    uint32_t m = 0, z = q1 - q0;
    for (uint32_t q = q0; q < q1; q++) {
      const size_t j = nbr[q];
      const double dx = xi0 - x[3 * j], dy = xi1 - x[3 * j + 1], dz = xi2 - x[3 * j + 2];
      const double rs = ri + rad[j];
      const int c = dx * dx + dy * dy + dz * dz < rs * rs;
      const int stale = (c ^ 1) & u.touch[q];
      cand[m] = q;
      m += (uint32_t)c;
      cand[z] = q;
      z += (uint32_t)stale;
    }
    for (uint32_t k = q1 - q0; k < z; k++) {
      double *xs = u.hist + (size_t)cand[k] * nh + hoff;
      xs[0] = xs[1] = xs[2] = 0.0;
      u.touch[cand[k]] = 0;
    }
    /* Gather the contacts into the batch. */
    for (uint32_t kc = 0; kc < m; kc++) {
      const uint32_t q = cand[kc];
      const size_t j = nbr[q];
      const double rj = rad[j], irj = invr[j];
      const double *hs = u.hist + (size_t)q * nh + hoff;
      b->dx[nb] = xi0 - x[3 * j];
      b->dy[nb] = xi1 - x[3 * j + 1];
      b->dz[nb] = xi2 - x[3 * j + 2];
      b->rs[nb] = ri + rj;
      b->ri[nb] = ri;
      b->rj[nb] = rj;
      b->sr[nb] = ir + irj;
      b->sm[nb] = im + invm[j];
      b->ovf[nb] = ir > irj ? ir : irj;
      b->vx[nb] = v[3 * i] - v[3 * j];
      b->vy[nb] = v[3 * i + 1] - v[3 * j + 1];
      b->vz[nb] = v[3 * i + 2] - v[3 * j + 2];
      b->wix[nb] = w[3 * i];
      b->wiy[nb] = w[3 * i + 1];
      b->wiz[nb] = w[3 * i + 2];
      b->wjx[nb] = w[3 * j];
      b->wjy[nb] = w[3 * j + 1];
      b->wjz[nb] = w[3 * j + 2];
      b->sx[nb] = hs[0];
      b->sy[nb] = hs[1];
      b->sz[nb] = hs[2];
      if (!cu) {
        const double *bc = s->inter[mati][mat[j]].bc;
        b->c2es[nb] = bc[DEM_BC_2ES];
        b->ceta[nb] = bc[DEM_BC_ETA];
        b->c8g[nb] = bc[DEM_BC_8G];
        b->cct[nb] = bc[DEM_BC_CT];
        b->cmu[nb] = bc[DEM_BC_MU];
        b->ctg[nb] = bc[DEM_BC_TANG];
      }
      b->i[nb] = (uint32_t)i;
      b->j[nb] = (uint32_t)j;
      b->q[nb] = q;
      if (++nb == DEM_BATCH) {
        if (cu) hm_compute_u(b, nb, s->dt, cu);
        else hm_compute_v(b, nb, s->dt);
        hm_scatter(b, nb, &u);
        nb = 0;
      }
    }
  }
  if (nb) {
    if (cu) hm_compute_u(b, nb, s->dt, cu);
    else hm_compute_v(b, nb, s->dt);
    hm_scatter(b, nb, &u);
  }
  td->contacts += u.contacts;
  td->nspill = u.nspill;
  td->max_overlap = u.max_ov;
}

void dem_engine_pair_forces(dem_sim *s, dem_tdata *td) {
  /* the batched kernel when every interaction set is of its kind and no law keeps state */
  int batched = !s->need_state;
  for (int a = 0; a < s->nmat && batched; a++)
    for (int c = 0; c < s->nmat; c++)
      if (s->inter[a][c].set && !(s->inter[a][c].fl & DEM_IF_BATCH)) batched = 0;
  if (batched) pair_forces_batched(s, td);
  else pair_forces_generic(s, td);
}
