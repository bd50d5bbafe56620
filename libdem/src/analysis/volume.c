/* Measurement volumes: boxes, the thesis' bins, sphere-box intersection volume, solids
 * fraction (dem/analysis.h; thesis Figs 5.8, 5.13, 5.18, 6.4).
 *
 * Sphere-box volume (docs/analysis.md): V = integral over z of A(z), A the area of the disc
 * of radius rho(z) = sqrt(R^2 - (z - zc)^2) inside the box's x-y rectangle. A is exact
 * (inclusion-exclusion of four quarter-plane areas Q, each a sum of circular-segment
 * integrals). The integral is taken over theta, z - zc = R sin(theta), dz = R cos(theta)
 * dtheta, rho = R cos(theta), which removes the branch points of rho(z) at the poles.
 * A has kinks where the disc touches an edge of the rectangle (A ~ (rho - d)^(3/2)) or
 * passes a corner; the range is split there, and each piece [a, b] is integrated by
 * 20-point Gauss-Legendre in u with theta = a + (b - a)(1 - cos(pi u))/2, which makes the
 * integrand analytic at the piece's ends (theta - a ~ u^2). Relative error ~1e-13
 * (tests/check_analysis.c compares with closed forms and additivity).
 */
#include <math.h>
#include <stddef.h>

#include "dem/analysis.h"

dem_box dem_box_centred(const double c[3], const double size[3]) {
  dem_box b;
  for (int k = 0; k < 3; k++) {
    b.lo[k] = c[k] - 0.5 * size[k];
    b.hi[k] = c[k] + 0.5 * size[k];
  }
  return b;
}

dem_box dem_dynamic_bin(const double tip[3], const double size[3], double gap) {
  const double def[3] = {DEM_BIN_DX, DEM_BIN_DY, DEM_BIN_DZ};
  const double *s = size ? size : def;
  double c[3] = {tip[0], tip[1], tip[2] - gap - 0.5 * s[2]};
  return dem_box_centred(c, s);
}

double dem_box_volume(const dem_box *b) {
  double v = 1.0;
  for (int k = 0; k < 3; k++) v *= b->hi[k] > b->lo[k] ? b->hi[k] - b->lo[k] : 0.0;
  return v;
}

dem_grid dem_grid_thesis(double ax, double ay, double z_base, size_t nz) {
  dem_grid g;
  g.cell[0] = DEM_BIN_DX;
  g.cell[1] = DEM_BIN_DY;
  g.cell[2] = DEM_BIN_DZ;
  g.nx = 5;
  g.ny = 1;
  g.nz = nz;
  g.origin[0] = ax - 2.5 * DEM_BIN_DX;
  g.origin[1] = ay - 0.5 * DEM_BIN_DY;
  g.origin[2] = z_base;
  return g;
}

dem_box dem_grid_box(const dem_grid *g, size_t index) {
  size_t i = index % g->nx, j = (index / g->nx) % g->ny, k = index / (g->nx * g->ny);
  size_t ijk[3] = {i, j, k};
  dem_box b;
  for (int d = 0; d < 3; d++) {
    b.lo[d] = g->origin[d] + (double)ijk[d] * g->cell[d];
    b.hi[d] = b.lo[d] + g->cell[d];
  }
  return b;
}

/* 20-point Gauss-Legendre nodes and weights on [0, 1]. */
static const double gl20[20][2] = {
    {0.0034357004074525577, 0.0088070035695760589}, {0.018014036361043095, 0.020300714900193469},
    {0.043882785874337027, 0.031336024167054534},  {0.080441514088890609, 0.041638370788352377},
    {0.1268340467699246, 0.050965059908620221},    {0.18197315963674249, 0.059097265980759206},
    {0.24456649902458644, 0.065844319224588319},   {0.31314695564229023, 0.071048054659191021},
    {0.38610707442917747, 0.074586493236301871},   {0.46173673943325133, 0.076376693565362919},
    {0.53826326056674867, 0.076376693565362919},   {0.61389292557082253, 0.074586493236301871},
    {0.68685304435770977, 0.071048054659191021},   {0.75543350097541362, 0.065844319224588319},
    {0.81802684036325757, 0.059097265980759206},   {0.8731659532300754, 0.050965059908620221},
    {0.91955848591110945, 0.041638370788352377},   {0.95611721412566297, 0.031336024167054534},
    {0.98198596363895696, 0.020300714900193469},   {0.99656429959254744, 0.0088070035695760589},
};

/* Antiderivative of sqrt(rho^2 - x^2) on [-rho, rho]. */
static double seg_P(double x, double rho) {
  double s = rho * rho - x * x;
  double t = x / rho;
  if (t > 1.0) t = 1.0;
  if (t < -1.0) t = -1.0;
  return 0.5 * (x * sqrt(s > 0.0 ? s : 0.0) + rho * rho * asin(t));
}

/* Integral over [l, h] (clipped to [-rho, a]) of w*sqrt(rho^2 - x^2) + c. */
static double piece(double l, double h, double a, double rho, double w, double c) {
  if (h > a) h = a;
  if (h <= l) return 0.0;
  return w * (seg_P(h, rho) - seg_P(l, rho)) + c * (h - l);
}

/* Area of the disc x^2 + y^2 < rho^2 with x < a and y < b. */
static double quarter_area(double a, double b, double rho) {
  if (rho <= 0.0 || a <= -rho || b <= -rho) return 0.0;
  if (a > rho) a = rho;
  if (b >= rho) return piece(-rho, rho, a, rho, 2.0, 0.0);
  double c = sqrt(rho * rho - b * b);
  if (b >= 0.0)
    return piece(-rho, -c, a, rho, 2.0, 0.0) + piece(-c, c, a, rho, 1.0, b) +
           piece(c, rho, a, rho, 2.0, 0.0);
  return piece(-c, c, a, rho, 1.0, b);
}

/* Area of the disc of radius rho centred at the origin inside [x0, x1] x [y0, y1]. */
static double disc_rect_area(double rho, double x0, double x1, double y0, double y1) {
  double a = quarter_area(x1, y1, rho) - quarter_area(x0, y1, rho) - quarter_area(x1, y0, rho) +
             quarter_area(x0, y0, rho);
  return a > 0.0 ? a : 0.0;
}

static void sort_small(double *v, int n) {
  for (int i = 1; i < n; i++) {
    double t = v[i];
    int j = i - 1;
    while (j >= 0 && v[j] > t) {
      v[j + 1] = v[j];
      j--;
    }
    v[j + 1] = t;
  }
}

double dem_sphere_box_volume(const double c[3], double R, const dem_box *b) {
  if (!(R > 0.0)) return 0.0;
  /* Outside: the box's nearest point is at least R away. Inside: every face R away. */
  double d2 = 0.0;
  int inside = 1;
  for (int k = 0; k < 3; k++) {
    if (!(b->hi[k] > b->lo[k])) return 0.0;
    double e = 0.0;
    if (c[k] < b->lo[k]) e = b->lo[k] - c[k];
    if (c[k] > b->hi[k]) e = c[k] - b->hi[k];
    d2 += e * e;
    if (c[k] - R < b->lo[k] || c[k] + R > b->hi[k]) inside = 0;
  }
  if (d2 >= R * R) return 0.0;
  if (inside) return 4.0 / 3.0 * M_PI * R * R * R;

  double x0 = b->lo[0] - c[0], x1 = b->hi[0] - c[0];
  double y0 = b->lo[1] - c[1], y1 = b->hi[1] - c[1];
  double za = fmax(b->lo[2] - c[2], -R), zb = fmin(b->hi[2] - c[2], R);
  if (!(zb > za)) return 0.0;

  /* Integrate over theta, z = R sin(theta), rho = R cos(theta): no branch points of
   * rho(z) = sqrt(R^2 - z^2) near the ends of a piece. Break points where the disc touches an
   * edge line (d = |x0|, ...) or passes a corner: cos(theta) = d / R. */
  double dist[8] = {fabs(x0), fabs(x1), fabs(y0), fabs(y1),
                    hypot(x0, y0), hypot(x0, y1), hypot(x1, y0), hypot(x1, y1)};
  double ta = asin(fmax(za / R, -1.0)), tb = asin(fmin(zb / R, 1.0));
  double ts[20];
  int nt = 0;
  ts[nt++] = ta;
  for (int i = 0; i < 8; i++) {
    if (dist[i] >= R) continue;
    double tt = acos(dist[i] / R);
    if (tt > ta && tt < tb) ts[nt++] = tt;
    if (-tt > ta && -tt < tb) ts[nt++] = -tt;
  }
  ts[nt++] = tb;
  sort_small(ts, nt);

  double vol = 0.0;
  for (int p = 0; p + 1 < nt; p++) {
    double a = ts[p], h = ts[p + 1] - a;
    if (!(h > 0.0)) continue;
    double sum = 0.0;
    for (int q = 0; q < 20; q++) {
      double u = gl20[q][0];
      double t = a + 0.5 * h * (1.0 - cos(M_PI * u));
      double dt = 0.5 * h * M_PI * sin(M_PI * u);
      double rho = R * cos(t);
      sum += gl20[q][1] * dt * rho * disc_rect_area(rho, x0, x1, y0, y1);
    }
    vol += sum;
  }
  return vol;
}

double dem_box_free_volume(const dem_box *b, const double c[3], double R) {
  double v = dem_box_volume(b) - dem_sphere_box_volume(c, R, b);
  return v > 0.0 ? v : 0.0;
}

int dem_solids_fraction(size_t n, const double *x, const double *radius, const dem_box *b,
                        double volume, double *phi, dem_err *err) {
  if (n > 0 && (!x || !radius))
    return dem_err_set(err, DEM_EINVAL, "solids fraction: NULL particle arrays with n = %zu", n);
  double V = volume > 0.0 ? volume : dem_box_volume(b);
  if (!(V > 0.0) || !isfinite(V))
    return dem_err_set(err, DEM_ERANGE, "solids fraction: volume = %g m^3, must be > 0", V);
  double s = 0.0;
  for (size_t i = 0; i < n; i++) {
    if (!isfinite(radius[i]) || !isfinite(x[3 * i]) || !isfinite(x[3 * i + 1]) ||
        !isfinite(x[3 * i + 2]))
      return dem_err_set(err, DEM_ENONFINITE, "solids fraction: particle %zu: non-finite "
                                              "position or radius", i);
    if (radius[i] < 0.0)
      return dem_err_set(err, DEM_ERANGE, "solids fraction: radius[%zu] = %g m, must be >= 0",
                         i, radius[i]);
    s += dem_sphere_box_volume(x + 3 * i, radius[i], b);
  }
  *phi = s / V;
  return DEM_OK;
}
