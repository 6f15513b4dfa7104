#include "contact/laws/tapered_geometry.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace raceway::contact {

namespace {

/// gamma from tan(gamma) = rr sin(alpha_o - gamma) / rm (Newton, from the small-angle value); NaN if none.
double half_angle_of(double rm, double rr, double alpha_o) {
  double g = std::atan(rr * std::sin(alpha_o) / rm);
  for (int i = 0; i < 50; ++i) {
    const double f = std::tan(g) - rr * std::sin(alpha_o - g) / rm;
    const double df = 1.0 / (std::cos(g) * std::cos(g)) + rr * std::cos(alpha_o - g) / rm;
    const double step = f / df;
    g -= step;
    if (std::abs(step) < 1e-16) break;
  }
  return std::isfinite(g) ? g : std::nan("");
}

}  // namespace

double TaperedGeometry::roller_radius_at(double x) const { return (apex_distance + x) * std::tan(half_angle); }

std::string tapered_geometry_problem(double rm, double rr, double alpha_o) {
  if (!(rm > 0) || !(rr > 0) || !(rr < rm)) return "the roller's mean radius must be positive and below the pitch radius";
  if (!(alpha_o > 0) || !(alpha_o < std::numbers::pi / 4)) return "the cup angle must lie between 0 and 45 deg";
  const double g = half_angle_of(rm, rr, alpha_o);
  if (!(g > 0)) return "no roller cone meets the cup's apex on the axis";
  if (!(alpha_o - 2.0 * g > 0))
    return "the cone's raceway would lean outwards (cone angle alpha_o - 2 gamma <= 0): the roller is too large for "
           "this cup angle";
  return {};
}

TaperedGeometry tapered_geometry(double rm, double rr, double alpha_o) {
  if (const std::string why = tapered_geometry_problem(rm, rr, alpha_o); !why.empty())
    throw std::invalid_argument("tapered geometry: " + why);
  TaperedGeometry t;
  t.cup_angle = alpha_o;
  t.half_angle = half_angle_of(rm, rr, alpha_o);
  t.axis_angle = alpha_o - t.half_angle;
  t.cone_angle = alpha_o - 2.0 * t.half_angle;
  t.apex_distance = rm / std::sin(t.axis_angle);
  t.apex_axial = -rm / std::tan(t.axis_angle);
  t.cup_radius = -t.apex_axial * std::tan(t.cup_angle);
  t.cone_radius = -t.apex_axial * std::tan(t.cone_angle);
  return t;
}

}  // namespace raceway::contact
