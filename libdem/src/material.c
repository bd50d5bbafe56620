/* Reduced properties and time-step estimates (dem/material.h). */
#include "dem/material.h"

#include <math.h>

double dem_reduced_radius(double R1, double R2) { return 1.0 / (1.0 / R1 + 1.0 / R2); }

double dem_reduced_modulus(double E1, double nu1, double E2, double nu2) {
  return 1.0 / ((1.0 - nu1 * nu1) / E1 + (1.0 - nu2 * nu2) / E2);
}

double dem_shear_modulus(double E, double nu) { return E / (2.0 * (1.0 + nu)); }

double dem_reduced_shear_modulus(double E1, double nu1, double E2, double nu2) {
  double G1 = dem_shear_modulus(E1, nu1), G2 = dem_shear_modulus(E2, nu2);
  return 1.0 / ((2.0 - nu1) / G1 + (2.0 - nu2) / G2);
}

double dem_reduced_mass(double m1, double m2) {
  if (isinf(m2)) return m1;
  if (isinf(m1)) return m2;
  return m1 * m2 / (m1 + m2);
}

double dem_sphere_mass(double R, double rho) { return 4.0 / 3.0 * M_PI * R * R * R * rho; }

double dem_dt_rayleigh(double R, double rho, double E, double nu) {
  double G = dem_shear_modulus(E, nu);
  return M_PI * R * sqrt(rho / G) / (0.1631 * nu + 0.8766);
}

double dem_dt_mass_spring(double m_smallest, double k_largest) {
  /* sqrt(m_eq / k_eq) with m* = m/2, k* = k/2: the halves cancel (thesis 4.29-4.31). */
  return sqrt((0.5 * m_smallest) / (0.5 * k_largest));
}

double dem_dt_sdof(double m, double k) { return sqrt(m / k); }
