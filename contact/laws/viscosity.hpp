// Lubricant viscosity as a function of temperature and pressure: pure functions, SI inside.
//
// Temperature:
//  - Walther's equation as ASTM D341 has it: log10(log10(nu + 0.7)) = A - B log10(T), nu the kinematic
//    viscosity in mm^2/s (cSt), T in kelvin; A and B from two measured points (an oil's data sheet
//    gives nu at 40 and 100 degC). Valid for nu above about 2 mm^2/s (D341's further terms for thinner
//    fluids are left out).
//  - Vogel's equation: eta = a exp(b / (T - c)), three constants from three measured points.
// Pressure:
//  - Barus: eta = eta0 exp(alpha p).
//  - Roelands: eta = eta0 exp((ln(eta0 / eta_inf)) ((1 + p / p_r)^Z - 1)), eta_inf = 6.31e-5 Pa s,
//    p_r = 1.96e8 Pa, the pressure-viscosity index Z from alpha (the initial slope
//    d ln(eta)/dp = alpha: Z = alpha p_r / ln(eta0 / eta_inf)); below Barus at high pressure.
// Closed forms, written out: a handful of lines each, no Debian package has them.
#pragma once

namespace raceway::contact {

/// Walther's (ASTM D341) constants A, B from two points (kinematic viscosity [m^2/s], temperature [K]).
struct WaltherConstants {
  double a = 0, b = 0;
};
WaltherConstants walther_constants(double nu1, double t1, double nu2, double t2);
/// Kinematic viscosity [m^2/s] at temperature t [K].
double walther_viscosity(const WaltherConstants& w, double t);

/// Vogel's constants a [Pa s], b [K], c [K] from three points (dynamic viscosity [Pa s], temperature [K]).
struct VogelConstants {
  double a = 0, b = 0, c = 0;
};
VogelConstants vogel_constants(double eta1, double t1, double eta2, double t2, double eta3, double t3);
/// Dynamic viscosity [Pa s] at temperature t [K] (t > c).
double vogel_viscosity(const VogelConstants& v, double t);

/// ln(eta(p) / eta0) of Barus' law.
inline double barus_exponent(double alpha, double p) { return alpha * p; }

inline constexpr double roelands_reference_pressure = 1.96e8;  ///< p_r [Pa]
inline constexpr double roelands_limit_viscosity = 6.31e-5;     ///< eta_inf [Pa s]
/// Roelands' pressure-viscosity index Z for a lubricant of viscosity eta0 [Pa s] and pressure-viscosity
/// coefficient alpha [1/Pa] (the same initial slope as Barus).
double roelands_index(double eta0, double alpha);
/// ln(eta(p) / eta0) of Roelands' law.
double roelands_exponent(double eta0, double z, double p);

}  // namespace raceway::contact
