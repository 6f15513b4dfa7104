#include "contact/laws/roller_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace raceway::contact {

namespace {

constexpr ProfileEntry kProfiles[] = {
    {RollerProfileKind::straight, "straight", "a straight roller with its ends rounded by corner_radius"},
    {RollerProfileKind::circular, "circular",
     "a circular crown of crown_radius beyond a straight middle of flat_length"},
    {RollerProfileKind::lundberg, "lundberg",
     "Lundberg's logarithmic crown for design_load (uniform pressure in an elastic half-space)"},
    {RollerProfileKind::johns_gohar, "johns_gohar",
     "Johns and Gohar's logarithmic crown for design_load, finite at the ends"},
};

// Drop of a circular arc of radius r, tangent to the straight line at `start`, at distance u >= 0
// from the middle (0 before the start). R - sqrt(R^2 - s^2) written as s^2 / (R + sqrt(R^2 - s^2)):
// no cancellation for a crown of micrometres on a radius of metres.
double arc_drop(double radius, double start, double u) {
  const double s = u - start;
  if (s <= 0) return 0.0;
  return s * s / (radius + std::sqrt(radius * radius - s * s));
}

// Q_d / (pi l_e E*): the scale of both logarithmic profiles [m].
double log_scale(const RollerProfile& p) {
  return p.design_load / (std::numbers::pi * effective_length(p) * p.reduced_modulus);
}

}  // namespace

double johns_gohar_half_width(const RollerProfile& p) {
  return std::sqrt(4.0 * p.design_load * p.rolling_radius /
                   (std::numbers::pi * effective_length(p) * p.reduced_modulus));
}

double effective_length(const RollerProfile& p) { return p.length - 2.0 * p.corner_radius; }

std::string validate_profile(const RollerProfile& p) {
  if (!(p.length > 0) || !std::isfinite(p.length)) return "length must be positive";
  if (!(p.corner_radius >= 0) || !(p.corner_radius < 0.5 * p.length))
    return "corner_radius must be at least 0 and below half the length";
  const double l_e = effective_length(p);
  switch (p.kind) {
    case RollerProfileKind::straight: return "";
    case RollerProfileKind::circular:
      if (!(p.flat_length >= 0) || !(p.flat_length < l_e))
        return "flat_length must be at least 0 and below the effective length (length - 2 corner_radius)";
      if (!(p.crown_radius > 0.5 * (l_e - p.flat_length)) || !std::isfinite(p.crown_radius))
        return "crown_radius must exceed the crowned half-length (length - 2 corner_radius - flat_length) / 2";
      return "";
    case RollerProfileKind::johns_gohar:
      if (!(p.rolling_radius > 0) || !std::isfinite(p.rolling_radius)) return "rolling_radius must be positive";
      if (p.design_load > 0 && p.reduced_modulus > 0 && !(johns_gohar_half_width(p) < 0.5 * l_e))
        return "the design load's Hertz half-width must be below half the effective length";
      [[fallthrough]];
    case RollerProfileKind::lundberg:
      if (!(p.design_load > 0) || !std::isfinite(p.design_load)) return "design_load must be positive";
      if (!(p.reduced_modulus > 0) || !std::isfinite(p.reduced_modulus)) return "reduced_modulus must be positive";
      return "";
  }
  return "unknown profile";
}

double profile_drop(const RollerProfile& p, double x) {
  if (const std::string why = validate_profile(p); !why.empty()) throw std::invalid_argument("roller profile: " + why);
  const double u = std::abs(x);
  if (!(u < 0.5 * p.length)) throw std::invalid_argument("roller profile: |x| must be below half the length");
  const double l_e = effective_length(p);
  const double corner = arc_drop(p.corner_radius, 0.5 * l_e, u);
  const double r = std::min(2.0 * u / l_e, 1.0);  // position over the effective half-length
  double crown = 0.0;
  switch (p.kind) {
    case RollerProfileKind::straight: break;
    case RollerProfileKind::circular: crown = arc_drop(p.crown_radius, 0.5 * p.flat_length, std::min(u, 0.5 * l_e)); break;
    case RollerProfileKind::lundberg:
      // Beyond the effective length the log is infinite: no contact there (the corner carries on).
      crown = r < 1.0 ? -log_scale(p) * std::log1p(-r * r) : std::numeric_limits<double>::infinity();
      break;
    case RollerProfileKind::johns_gohar: {
      const double b_over_a = johns_gohar_half_width(p) / (0.5 * l_e);
      crown = -log_scale(p) * std::log1p(-(1.0 - b_over_a * b_over_a) * r * r);
      break;
    }
  }
  return crown + corner;
}

std::span<const ProfileEntry> registered_profiles() { return kProfiles; }

const ProfileEntry* find_profile(std::string_view name) {
  for (const ProfileEntry& p : kProfiles)
    if (p.name == name) return &p;
  return nullptr;
}

std::string known_profile_names() {
  std::string s;
  for (const ProfileEntry& p : kProfiles) s += (s.empty() ? "" : ", ") + std::string(p.name);
  return s;
}

}  // namespace raceway::contact
