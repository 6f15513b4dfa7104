// The internal geometry of a tapered roller bearing, from the cup angle, the pitch radius and the
// roller's mean radius: the cup (outer) raceway, the cone (inner) raceway and the roller's axis are
// cones whose apexes meet at one point on the bearing axis, so that rollers roll on both raceways
// without sliding along their length (Harris & Kotzalas, ch. 2: docs/references.md).
//
// In a meridian plane (r from the bearing axis, z along it), the roller's middle lies at (r_m, 0),
// r_m the pitch radius; its axis leans by beta from the bearing axis, its large end outwards and
// towards +z (away from the apex, which lies at z_a = -r_m / tan(beta) on the axis). The roller is a
// cone of half angle gamma about its axis with the same apex: its radius at a distance x from its
// middle along the axis is (L + x) tan(gamma), L = r_m / sin(beta) the apex distance of the middle,
// so the mean radius r_r = L tan(gamma). The cup's generatrix leans by alpha_o = beta + gamma, the
// cone's by alpha_i = beta - gamma, both through the apex: the cup angle alpha_o (the contact
// angle of catalogues) and r_r fix gamma through tan(gamma) = r_r sin(alpha_o - gamma) / r_m, solved
// here by Newton's method. Pure functions; SI units.
#pragma once

#include <string>

namespace raceway::contact {

struct TaperedGeometry {
  double cup_angle = 0;       ///< alpha_o [rad], the cup's generatrix from the bearing axis
  double cone_angle = 0;      ///< alpha_i [rad], the cone's generatrix from the bearing axis
  double axis_angle = 0;      ///< beta [rad], the roller's axis from the bearing axis
  double half_angle = 0;      ///< gamma [rad], the roller's half cone angle
  double apex_distance = 0;   ///< L [m], from the apex to the roller's middle along its axis
  double apex_axial = 0;      ///< z_a [m] (< 0), the apex on the bearing axis
  /// The raceway's radius at z = 0 of its own ring frame: r(z) = race_radius + z tan(angle).
  double cup_radius = 0;      ///< m
  double cone_radius = 0;     ///< m
  /// The roller's radius at x from its middle along its axis [m].
  double roller_radius_at(double x) const;
};

/// The geometry, or throws std::invalid_argument (see tapered_geometry_problem).
TaperedGeometry tapered_geometry(double pitch_radius, double mean_roller_radius, double cup_angle);

/// Empty if the geometry exists with a cone angle above zero, else the reason, for the scene's
/// error messages.
std::string tapered_geometry_problem(double pitch_radius, double mean_roller_radius, double cup_angle);

}  // namespace raceway::contact
