#include "contact/laws/race_imperfections.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace raceway::contact {

namespace {
constexpr double pi = std::numbers::pi;

/// The angle a - b folded into [-pi, pi).
double angle_difference(double a, double b) {
  const double d = std::remainder(a - b, 2.0 * pi);
  return d >= pi ? d - 2.0 * pi : d;
}

/// The centre's drop and its slope pivoting on an edge at distance x (0 <= x < r).
SpallDrop pivot(double r, double x) {
  const double root = std::sqrt(r * r - x * x);
  return {r - root, x / root};
}
}  // namespace

double spall_effective_depth(const RaceSpall& s, double ball_radius) {
  const double half = std::min(0.5 * s.length, ball_radius);
  return std::min(s.depth, ball_radius - std::sqrt(ball_radius * ball_radius - half * half));
}

SpallDrop spall_drop(const RaceSpall& s, double ball_radius, double x) {
  if (!(x > 0) || !(x < s.length)) return {};
  const double peak = spall_effective_depth(s, ball_radius);
  if (s.edge == SpallEdge::smooth) {
    const double k = 2.0 * pi / s.length;
    return {0.5 * peak * (1.0 - std::cos(k * x)), 0.5 * peak * k * std::sin(k * x)};
  }
  // Sharp: pivoting on the nearer edge, at most the depth.
  const bool leading = x <= 0.5 * s.length;
  const double from_edge = leading ? x : s.length - x;
  if (from_edge >= ball_radius) return {peak, 0.0};
  SpallDrop d = pivot(ball_radius, from_edge);
  if (d.drop >= peak) return {peak, 0.0};
  if (!leading) d.slope = -d.slope;
  return d;
}

double spall_half_angle(const RaceImperfections& r) { return 0.5 * r.spall.length / r.race_radius; }

RaceHeight race_height(const RaceImperfections& r, double azimuth, double transverse) {
  RaceHeight h;
  if (r.has_spall && std::abs(transverse) <= 0.5 * r.spall.width) {
    const double half = spall_half_angle(r);
    const double from_centre = angle_difference(azimuth, r.spall.angle);
    if (std::abs(from_centre) < half) {
      const SpallDrop d = spall_drop(r.spall, r.ball_radius, (from_centre + half) * r.race_radius);
      h.height -= d.drop;
      h.per_azimuth -= d.slope * r.race_radius;
    }
  }
  const RaceWaviness& w = r.waviness;
  for (std::size_t k = 0; k < w.orders.size(); ++k) {
    const double n = w.orders[k];
    const double phase = n * azimuth + w.phases[k];
    h.height += w.amplitudes[k] * std::cos(phase);
    h.per_azimuth -= w.amplitudes[k] * n * std::sin(phase);
  }
  return h;
}

}  // namespace raceway::contact
