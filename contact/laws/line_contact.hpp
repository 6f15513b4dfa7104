// Line-contact force laws: Palmgren's load-deflection relation (optionally sliced, with a crowned
// profile), Hunt-Crossley damping and a regularised traction curve.
//
// Pure functions of their arguments. SI units throughout. Derived constants are computed once when
// a law is built (make_line_contact_law), never per call.
#pragma once

#include <string>
#include <vector>

namespace raceway::contact {

/// Reduced (contact) modulus E* from two materials: 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2  [Pa].
double reduced_modulus(double youngs_1, double poisson_1, double youngs_2, double poisson_2);

/// Palmgren's line-contact stiffness for one contact of effective length `length` [m]:
/// Q = K delta^(10/9) with K = c_P E* l^(8/9) [N/m^(10/9)].
/// c_P = 0.7087 reproduces Palmgren's steel-on-steel constant 8.06e4 N/mm^(10/9) l^(8/9)
/// (Harris & Kotzalas, Rolling Bearing Analysis, eq. 6.40) at E = 207 GPa, nu = 0.3, and scales
/// with E* for other material pairs (brass or polymer cage bars).
double palmgren_stiffness(double reduced_modulus, double length);
inline constexpr double palmgren_exponent = 10.0 / 9.0;
inline constexpr double palmgren_coefficient = 0.70866;

/// A sliced Palmgren line contact with Hunt-Crossley damping.
/// Each slice j carries K_j = K * w_j / L (the whole-length law for a uniform approach) and sees the
/// approach delta - drop_j, where drop_j is the profile drop of the crowned roller at the slice centre.
struct LineContactLaw {
  double stiffness = 0;                ///< K of the whole length [N/m^(10/9)]
  std::vector<double> slice_stiffness; ///< K_j [N/m^(10/9)], sums to stiffness
  std::vector<double> slice_drop;      ///< profile drop at slice centres [m], >= 0
  double damping_factor = 0;           ///< Hunt-Crossley factor [s/m]: F = sum K_j d_j^(10/9) (1 + factor * d')
  double max_approach = 0;             ///< validity limit [m]: larger approach is a recoverable error
};

/// Builds the law: `slices` equal slices over `length`, parabolic crown with `crown_drop` at the ends.
LineContactLaw make_line_contact_law(double reduced_modulus, double length, int slices,
                                     double crown_drop, double damping_factor, double max_approach);

struct NormalForce {
  double force = 0;           ///< N, >= 0 (compressive), elastic + damping, clipped at zero
  double elastic_force = 0;   ///< N, elastic part
  double elastic_energy = 0;  ///< J, potential energy stored in the contact
  double damping_power = 0;   ///< W, power dissipated by the damping part (>= 0 while it pushes)
  bool valid = true;          ///< false: approach beyond the validity limit or not finite
};

/// Normal force for approach `approach` [m] (> 0 in contact) and approach rate [m/s].
/// Zero when apart, continuous with a continuous first derivative at onset.
NormalForce evaluate_normal(const LineContactLaw& law, double approach, double approach_rate);

/// Regularised traction curve mu(u) = mu_max tanh(u / u_scale): odd, smooth, no jump at zero slip.
struct TractionCurve {
  double friction_coefficient = 0;  ///< mu_max; 0 switches traction off
  double slip_velocity_scale = 1;   ///< u_scale [m/s]
  double coefficient(double slip_velocity) const;
};

}  // namespace raceway::contact
