// Lubricated line contacts (seed 003 section 2.2): the elastohydrodynamic (EHD) roller/ring contact
// after Moes with Poiseuille and Couette traction, and the hydrodynamic (HD) roller/cage contact
// with squeeze damping. Pure functions of their arguments, SI units, per unit length where a name
// says so ("_per_length"); derived constants once when a law is built.
//
// Seed 003's dimensionless groups (eq. 8-10), with u_m the entrainment speed (mean surface speed),
// R the reduced radius, E' = 2 E* Moes' reduced modulus (E* of line_contact.hpp: 1/E* = (1-nu1^2)/E1 +
// (1-nu2^2)/E2, so 2/E' = (1-nu1^2)/E1 + (1-nu2^2)/E2, as Moes, Hamrock-Dowson and the ball contacts
// of point_contact.hpp define it), alpha the pressure-viscosity coefficient, w_1 the
// load per unit length and h_m the minimum film thickness:
//   U = 2 eta u_m / (E' R),  M_1 = w_1 / (E' R sqrt(U)),  H_m = h_m / (R sqrt(U)),  L = alpha E' U^(1/4).
// Film load capacity:
//   rigid-isoviscous (IVR):         M_1 = C_M / H_m, C_M = 2.4475 (Martin, Reynolds' boundary condition);
//   elastic-piezoviscous (PVE):     M_1 = L^6 (1.31 / H_m)^8   (Moes; seed 003 eq. 8);
//   between: M_1 = (M_IVR^s + M_PVE^s)^(1/s), s = 7/2 (the exponent of Moes' own blend of regimes):
//   the film carries what the stronger regime carries, smoothly.
// Seed 003's eq. 9 prints M_1 = 3 / H_m, 1.2257 times Martin's result (docs/references.md, Errata);
// C_M is Martin's constant, which tests/contact/test_lubricated_line_laws.cpp recomputes from the
// Reynolds equation.
#pragma once

#include "contact/laws/line_contact.hpp"

namespace raceway::contact {

/// Martin's rigid-isoviscous line-contact load: w_1 h_m = 2 C_M eta u_m R, i.e. M_1 H_m = C_M.
inline constexpr double martin_load_constant = 2.4475;
/// Moes' elastic-piezoviscous constant: H_m = 1.31 L^(3/4) M_1^(-1/8) (seed 003 eq. 8).
inline constexpr double moes_pve_constant = 1.31;
/// Exponent of the blend of the two regimes' load parameters.
inline constexpr double regime_blend_exponent = 3.5;

/// The lubricant and geometry of one lubricated line contact.
struct LineFilm {
  double viscosity = 0;           ///< eta_0 [Pa s]
  double pressure_viscosity = 0;  ///< alpha [1/Pa]; 0: isoviscous
  double reduced_modulus = 0;     ///< E* [Pa] of line_contact.hpp; the film's groups use E' = 2 E*
  double reduced_radius = 0;      ///< R [m]: 1/R = 1/r_roller +- 1/r_race
  double length = 0;              ///< effective contact length [m]
  /// Beyond this film thickness the film carries nothing (fully flooded conditions end); between
  /// cutoff/2 and cutoff its load fades with a C1 smoothstep [m].
  double cutoff = 0;
};

/// Moes' E' = 2 E* [Pa].
double moes_modulus(const LineFilm& f);
/// Seed 003's groups at entrainment speed u_m > 0.
double speed_parameter(const LineFilm& f, double entrainment_speed);  ///< U
double material_parameter(const LineFilm& f, double speed_parameter);  ///< L

/// M_1 at H_m: the blend of IVR and PVE above; its derivative dM_1/dH_m into *slope if given.
double film_load_parameter(double film_parameter, double material_parameter, double* slope = nullptr);

/// The load per unit length a film of minimum thickness h [m] carries at entrainment speed |u_m|
/// [N/m], with the cutoff window; derivatives d/dh and d/du_m into the pointers if given.
double film_load_per_length(const LineFilm& f, double film_thickness, double entrainment_speed,
                            double* d_thickness = nullptr, double* d_speed = nullptr);

/// The minimum film thickness under a load per unit length w_1 > 0 at u_m > 0 (the inverse of
/// film_load_per_length without the cutoff) [m].
double film_thickness(const LineFilm& f, double load_per_length, double entrainment_speed);

/// An EHD line contact: Palmgren's elastic law (the whole length) carrying the film's load.
struct EhdLineLaw {
  LineFilm film;
  double stiffness = 0;     ///< K of Palmgren's law for the whole length [N/m^(10/9)]
  double max_approach = 0;  ///< validity limit of the elastic approach [m]
};

/// The state of an EHD contact at undeformed gap `gap` (> 0 apart, < 0 overlapping) and entrainment
/// speed u_m: the elastic deflection delta >= 0 at which Palmgren's force equals the film's load at
/// h = gap + delta (seed 003 2.2.2). Without entrainment the film carries nothing and the contact is
/// dry (delta = max(0, -gap), h = 0).
struct EhdState {
  double force = 0;              ///< N: the elastic force = the film's load
  double deflection = 0;         ///< m, delta
  double film_thickness = 0;     ///< m, h = gap + delta
  double load_parameter = 0;     ///< M_1 (0 without a film)
  double d_force_d_gap = 0;      ///< N/m
  double d_force_d_speed = 0;    ///< N s/m
  bool valid = true;
};
EhdState evaluate_ehd(const EhdLineLaw& law, double gap, double entrainment_speed);

/// Poiseuille (rolling) viscous force per unit length for a load parameter M_1 at U (seed 003
/// eq. 10): f_p = E' R U^0.75 min(1.42 sqrt(M_1), 1.47). Seed 003 switches at M_1 = 1.07; the two
/// branches meet at M_1 = (1.47 / 1.42)^2 = 1.0717, so the minimum is the continuous form of it [N/m].
double poiseuille_force_per_length(const LineFilm& f, double speed_parameter, double load_parameter);

/// Couette (sliding) friction coefficient: zero in pure rolling, rising linearly with the
/// slide-to-roll ratio S = u_s / |u_m| (seed 003: "increases linearly ... until the maximum"),
/// here mu = mu_max tanh(S / S_0), linear for S << S_0 and smooth (S_0 = `saturation_ratio`);
/// `speed_floor` [m/s] keeps S finite when u_m -> 0: S = u_s / sqrt(u_m^2 + floor^2).
struct CouetteTraction {
  double friction_coefficient = 0;  ///< mu_max
  double saturation_ratio = 0.05;   ///< S_0
  double speed_floor = 0.05;        ///< m/s
  double coefficient(double slip_velocity, double entrainment_speed) const;
};

/// The hydrodynamic roller/cage line contact (seed 003 2.2.1): rigid surfaces (no elastic
/// deformation in the film), a cylinder of radius R on a flat bar, the film carrying the load of
/// the Reynolds equation with rolling and squeeze together and Reynolds' cavitation condition
/// (reynolds_line_film.hpp), per unit length. Its limits:
///   rolling alone:   w_r = 2 C_M eta |u_m| R / h           (Martin),
///   approach alone:  w_s = 3 sqrt(2) pi eta R^1.5 (-dh/dt) / h^1.5 (full film),
///   separation alone: nothing (the film cavitates);
/// seed 003 adds w_r and w_s, which a joint solution shows 13-28 % too high on approach and more
/// on separation (a separating film cavitates where rolling alone would carry load: 18 % at a
/// squeeze a sixth of the rolling speed, see the tests). When the film collapses the bodies meet: the film's thickness is
/// held above `film_floor` (a smooth maximum, of the order of the surface roughness) and the dry
/// Palmgren law of the overlap adds to it, so the force passes smoothly from film to dry contact.
struct HydrodynamicLineLaw {
  LineFilm film;
  double film_floor = 0;  ///< m
  LineContactLaw dry;     ///< Palmgren (and its damping) once the surfaces overlap
};
struct HydrodynamicForce {
  double force = 0;       ///< N, film + dry
  double film_force = 0;  ///< N
  double film_thickness = 0;  ///< m, the floored film thickness
  double couette_force_per_speed = 0;  ///< N s/m: viscous sliding force = this * slip speed
  NormalForce dry;
  bool valid = true;
};
/// At gap `gap` (> 0 apart), its rate d(gap)/dt and entrainment speed u_m.
HydrodynamicForce evaluate_hydrodynamic(const HydrodynamicLineLaw& law, double gap, double gap_rate,
                                        double entrainment_speed);

}  // namespace raceway::contact
