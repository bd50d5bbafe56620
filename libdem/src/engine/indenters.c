/* Rigid indenters (thesis 6.2.2: spherical, flat-ended cylindrical and cubic indenters of
 * 16 mm): analytic contact geometry of a sphere particle (centre x, radius r) against a
 * closed rigid body, and a wall translation without work.
 *
 * In every case the contact is with the closest point q of the body's surface:
 *   outside the body:  alpha = r - |x - q|,        n = (x - q) / |x - q|
 *   centre inside:     alpha = r + (depth of x below the nearest face), n = that face's
 *                      outward normal (only reached if the overlap exceeds r: a breakdown)
 * n points from the wall surface towards the particle centre, as for the other walls, and
 * the contact point used for torques, x - (r - alpha) n, is q.
 *
 *   SPHERE   centre p, radius Rs: |x - q| = |x - p| - Rs, n radial. Two convex spheres:
 *            R* = r Rs / (r + Rs) (thesis eq 3.16), rfac = Rs / (Rs + r).
 *   FLATCYL  axis n through the face centre p, radius Rc, body at -L <= z <= 0 with
 *            z = (x - p).n and rho the distance from the axis. Closest point:
 *            z_q = clamp(z, -L, 0), rho_q = min(rho, Rc). Regions: flat face (rho <= Rc,
 *            z > 0; normal n, rfac 1), rim edge (rho > Rc, z > 0; normal in the (n, radial)
 *            plane, rfac 1: an edge has no radius of its own, the particle's radius governs,
 *            as for the disc rim in walls.c), side (rho > Rc, -L <= z <= 0; radial normal,
 *            a convex cylinder: principal radii r and r Rc/(r + Rc), Hertz equivalent
 *            R* = sqrt(r * r Rc/(r + Rc)), rfac = sqrt(Rc / (Rc + r))), back face
 *            (rho <= Rc, z < -L; normal -n) and back rim (rho > Rc, z < -L) like the front
 *            ones; L = `length` (0: L = infinity, no back face).
 *   BOX      local frame e1 (the coordinate axis least aligned with n, projected, turned
 *            by `angle` about n), e2 = n x e1, e3 = n, origin p; body |l1| <= a,
 *            |l2| <= a, -L <= l3 <= 0 with a = `radius`, L = `length` (0: infinity);
 *            closest point = the local coordinates clamped into the body:
 *            one clamped coordinate = a face (rfac 1), two = an edge, three = a corner
 *            (rfac 1 for both).
 */
#include <math.h>

#include "internal.h"

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* A unit vector perpendicular to the unit vector n, from hint (projected) or a default. */
static void perp_unit(const double n[3], const double hint[3], double e[3]) {
  double h[3] = {hint[0], hint[1], hint[2]};
  for (int pass = 0; pass < 2; pass++) {
    double hn = dot3(h, n);
    for (int k = 0; k < 3; k++) e[k] = h[k] - hn * n[k];
    double l = sqrt(dot3(e, e));
    if (l > 1e-9 * (sqrt(dot3(h, h)) + 1e-300)) {
      for (int k = 0; k < 3; k++) e[k] /= l;
      return;
    }
    /* no usable hint: the coordinate axis least aligned with n */
    h[0] = h[1] = h[2] = 0.0;
    int m = fabs(n[0]) <= fabs(n[1]) ? (fabs(n[0]) <= fabs(n[2]) ? 0 : 2)
                                      : (fabs(n[1]) <= fabs(n[2]) ? 1 : 2);
    h[m] = 1.0;
  }
}

static double sphere_gap(const dem_wall_spec *w, const double x[3], double r, double n[3],
                         double *rfac) {
  const double d[3] = {x[0] - w->p[0], x[1] - w->p[1], x[2] - w->p[2]};
  const double l = sqrt(dot3(d, d));
  if (l > 0.0)
    for (int k = 0; k < 3; k++) n[k] = d[k] / l;
  else
    for (int k = 0; k < 3; k++) n[k] = w->n[k];
  *rfac = w->radius / (w->radius + r);
  return r - (l - w->radius);
}

static double flatcyl_gap(const dem_wall_spec *w, const double x[3], double r, double n[3],
                          double *rfac) {
  const double *a = w->n;
  const double Rc = w->radius, L = w->length > 0.0 ? w->length : INFINITY; /* engine.h */
  const double d[3] = {x[0] - w->p[0], x[1] - w->p[1], x[2] - w->p[2]};
  const double z = dot3(d, a);
  double e[3] = {d[0] - z * a[0], d[1] - z * a[1], d[2] - z * a[2]};
  const double rho = sqrt(dot3(e, e));
  if (rho > 0.0)
    for (int k = 0; k < 3; k++) e[k] /= rho;
  else
    perp_unit(a, (const double[3]){1.0, 0.0, 0.0}, e);
  *rfac = 1.0;
  const int inside_r = rho <= Rc, inside_z = z <= 0.0 && z >= -L;
  if (inside_r && inside_z) { /* centre inside the body: push out through the nearest face */
    const double df = -z, db = z + L, ds = Rc - rho;
    if (df <= db && df <= ds) {
      for (int k = 0; k < 3; k++) n[k] = a[k];
      return r + df;
    }
    if (db <= ds) {
      for (int k = 0; k < 3; k++) n[k] = -a[k];
      return r + db;
    }
    for (int k = 0; k < 3; k++) n[k] = e[k];
    *rfac = sqrt(Rc / (Rc + r));
    return r + ds;
  }
  const double zq = z > 0.0 ? 0.0 : (z < -L ? -L : z);
  const double rq = rho < Rc ? rho : Rc;
  const double dz = z - zq, dr = rho - rq;
  const double dist = sqrt(dz * dz + dr * dr);
  for (int k = 0; k < 3; k++) n[k] = (dz * a[k] + dr * e[k]) / dist;
  if (dz == 0.0) *rfac = sqrt(Rc / (Rc + r)); /* the side; back face and back rim: 1 */
  return r - dist;
}

static double box_gap(const dem_wall_spec *w, const double x[3], double r, double n[3],
                      double *rfac) {
  double e[3][3];
  for (int k = 0; k < 3; k++) e[2][k] = w->n[k];
  perp_unit(e[2], (const double[3]){0.0, 0.0, 0.0}, e[0]);
  e[1][0] = e[2][1] * e[0][2] - e[2][2] * e[0][1];
  e[1][1] = e[2][2] * e[0][0] - e[2][0] * e[0][2];
  e[1][2] = e[2][0] * e[0][1] - e[2][1] * e[0][0];
  if (w->angle != 0.0) { /* turn the edges about n: e1' = c e1 + s e2, e2' = c e2 - s e1 */
    const double c = cos(w->angle), s = sin(w->angle);
    for (int k = 0; k < 3; k++) {
      const double u = e[0][k], v = e[1][k];
      e[0][k] = c * u + s * v;
      e[1][k] = c * v - s * u;
    }
  }
  /* local coordinates from the face centre: |l1|, |l2| <= a across, -L <= l3 <= 0 */
  const double a = w->radius, L = w->length > 0.0 ? w->length : INFINITY;
  const double d[3] = {x[0] - w->p[0], x[1] - w->p[1], x[2] - w->p[2]};
  const double h[2] = {a, a};
  double l[3], dl[3];
  int outside = 0;
  for (int k = 0; k < 3; k++) {
    l[k] = dot3(d, e[k]);
    double lo = k < 2 ? -a : -L, hi = k < 2 ? a : 0.0;
    double q = l[k] > hi ? hi : (l[k] < lo ? lo : l[k]);
    dl[k] = l[k] - q;
    outside |= dl[k] != 0.0;
  }
  *rfac = 1.0;
  if (!outside) { /* centre inside: the face of least depth */
    int m = 0;
    double best = INFINITY;
    for (int k = 0; k < 3; k++) {
      double dep = k < 2 ? h[k] - fabs(l[k]) : fmin(-l[k], l[k] + L);
      if (dep < best) best = dep, m = k;
    }
    /* side faces by the sign of l; along n: the front face unless the back is nearer */
    const double sg = m == 2 ? (-l[2] <= l[2] + L ? 1.0 : -1.0) : (l[m] >= 0.0 ? 1.0 : -1.0);
    for (int k = 0; k < 3; k++) n[k] = sg * e[m][k];
    return r + best;
  }
  const double dist = sqrt(dot3(dl, dl));
  for (int k = 0; k < 3; k++)
    n[k] = (dl[0] * e[0][k] + dl[1] * e[1][k] + dl[2] * e[2][k]) / dist;
  return r - dist;
}

double dem_indenter_gap(const dem_wall_spec *w, const double x[3], double r, double n[3],
                        double *rfac) {
  switch (w->kind) {
  case DEM_WALL_SPHERE:
    return sphere_gap(w, x, r, n, rfac);
  case DEM_WALL_FLATCYL:
    return flatcyl_gap(w, x, r, n, rfac);
  case DEM_WALL_BOX:
    return box_gap(w, x, r, n, rfac);
  default:
    *rfac = 1.0;
    n[0] = n[1] = 0.0;
    n[2] = 1.0;
    return -INFINITY;
  }
}

double dem_wall_penetration(const dem_wall_spec *w, const double x[3], double r, double n[3],
                            double *rfac) {
  return dem_wall_gap(w, x, r, n, rfac);
}

int dem_sim_move_wall(dem_sim *s, int wall, const double dp[3], dem_err *err) {
  if (wall < 0 || wall >= s->nwall)
    return dem_err_set(err, DEM_ERANGE, "wall %d outside [0, %d)", wall, s->nwall);
  for (int k = 0; k < 3; k++)
    if (!isfinite(dp[k])) return dem_err_set(err, DEM_ENONFINITE, "wall %d: displacement", wall);
  for (int k = 0; k < 3; k++) s->wall[wall].spec.p[k] += dp[k];
  s->need_build = 1;
  s->need_forces = 1;
  return DEM_OK;
}
