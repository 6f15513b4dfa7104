// The estimates of a tapered roller bearing's internal geometry (catalogue_tapered.hpp).
#include "io/scene/catalogue_tapered.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace raceway::scene::catalogue {

namespace {

double to_tenth(double mm) { return std::round(mm * 10) / 10; }

}  // namespace

std::optional<AngleRange> iso355_angle_series(int series) {
  // ISO 355's angle series 2 to 7: over 10 deg up to 13 deg 52', .., over 27 deg up to 30 deg.
  static constexpr AngleRange kSeries[] = {{10, 13 + 52 / 60.0},           {13 + 52 / 60.0, 15 + 59 / 60.0},
                                           {15 + 59 / 60.0, 18 + 55 / 60.0}, {18 + 55 / 60.0, 23},
                                           {23, 27},                         {27, 30}};
  if (series < 2 || series > 7) return std::nullopt;
  return kSeries[series - 2];
}

double estimated_cup_angle(const TaperedBoundary& b) {
  if (b.published_e) return std::round(2 * std::atan(*b.published_e / 1.5) * 180 / std::numbers::pi) / 2;
  const std::optional<AngleRange> range = iso355_angle_series(b.angle_series);
  if (!range) throw std::invalid_argument("ISO 355 has no angle series " + std::to_string(b.angle_series));
  return std::round(range->lo_deg + range->hi_deg) / 2;  // the middle, to 0.5 deg
}

TaperedEstimate estimate_tapered(const TaperedBoundary& b, const TaperedRules& rules) {
  TaperedEstimate t;
  t.pitch_diameter = 0.5 * (b.bore + b.outside);
  t.roller_diameter = to_tenth(rules.roller_factor * (b.outside - b.bore));
  t.rollers = static_cast<int>(std::floor(std::numbers::pi * t.pitch_diameter / (rules.roller_pitch * t.roller_diameter)));
  t.roller_length = to_tenth(rules.length_factor * b.cup_width);
  t.corner_radius = to_tenth(rules.corner_factor * t.roller_diameter);
  t.cup_angle = estimated_cup_angle(b);
  t.pocket_clearance = std::round(rules.pocket_factor * t.roller_diameter * 1e3) / 1e3;
  return t;
}

}  // namespace raceway::scene::catalogue
