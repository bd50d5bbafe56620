/* dem/material.h — reduced (equivalent) properties of a contact and time-step estimates.
 *
 * A wall is a body with infinite radius and infinite mass: pass INFINITY for R2 or m2.
 * A rigid wall is E2 = INFINITY.
 */
#ifndef DEM_MATERIAL_H
#define DEM_MATERIAL_H

/* R* = (1/R1 + 1/R2)^-1, thesis eq (3.16). m. */
double dem_reduced_radius(double R1, double R2);
/* E* = ((1-nu1^2)/E1 + (1-nu2^2)/E2)^-1, thesis eq (3.15). Pa. */
double dem_reduced_modulus(double E1, double nu1, double E2, double nu2);
/* Shear modulus G = E / (2 (1 + nu)). Pa. */
double dem_shear_modulus(double E, double nu);
/* G* = ((2-nu1)/G1 + (2-nu2)/G2)^-1 (Mindlin 1949). The thesis' eq (3.20) prints
 * (1-nu^2)/G, which would make the tangential stiffness exceed the normal one
 * (k_t/k_n = 2/(1+nu) > 1); see docs/contact-laws.md. Pa. */
double dem_reduced_shear_modulus(double E1, double nu1, double E2, double nu2);
/* m* = m1 m2 / (m1 + m2); m2 = INFINITY gives m1. kg. */
double dem_reduced_mass(double m1, double m2);
/* Mass of a sphere, 4/3 pi R^3 rho. kg. */
double dem_sphere_mass(double R, double rho);

/* Rayleigh time step T_R = pi R sqrt(rho/G) / (0.1631 nu + 0.8766), thesis eq (3.1),
 * paper eq (71). s. */
double dem_dt_rayleigh(double R, double rho, double E, double nu);
/* Mass-spring critical time step t_crit = sqrt(m_eq / k_eq) with m_eq = m_smallest/2 and
 * k_eq = k_largest/2 (thesis eqs 4.29-4.31, 7.2): for a pair, sqrt(m_smallest/k_largest).
 * The thesis then uses 0.2 t_crit. s. */
double dem_dt_mass_spring(double m_smallest, double k_largest);
/* The same bound for a single degree of freedom of mass m on a spring k: sqrt(m/k). s. */
double dem_dt_sdof(double m, double k);

#endif
