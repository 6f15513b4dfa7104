#include "solver/bearing/race_defects.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "solver/bearing/element_traits.hpp"

namespace raceway::bearing {

std::shared_ptr<const contact::RaceImperfections> race_imperfections(const scene::RingSpec& ring, double race_radius,
                                                                     double ball_radius) {
  if (!ring.spall.present && !ring.waviness.present()) return nullptr;
  auto r = std::make_shared<contact::RaceImperfections>();
  r->race_radius = race_radius;
  r->ball_radius = ball_radius;
  r->has_spall = ring.spall.present;
  r->spall = {ring.spall.angle, ring.spall.length, ring.spall.width, ring.spall.depth, ring.spall.edge};
  r->waviness = {ring.waviness.orders, ring.waviness.amplitudes, ring.waviness.phases};
  return r;
}

namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;

/// The angle folded into [0, 2 pi).
double turn(double a) {
  const double r = std::fmod(a, two_pi);
  return r < 0 ? r + two_pi : r;
}

/// The step limit for one ball and one spalled race.
double ball_limit(const contact::RaceImperfections& race, const contact::SpatialKinematics& ring,
                  const contact::SpatialKinematics& ball) {
  const contact::Vec3 rel = ball.position - ring.position;
  const contact::Vec3 p = ring.rotation.transpose() * rel;
  const double rho = std::sqrt(p.x() * p.x() + p.y() * p.y());
  if (!(rho > 0)) return std::numeric_limits<double>::infinity();
  const contact::Vec3 p_dot =
      ring.rotation.transpose() * (ball.velocity - ring.velocity - ring.angular_velocity.cross(rel));
  const double rate = (p.x() * p_dot.y() - p.y() * p_dot.x()) / (rho * rho);  // azimuth rate, ring frame
  const double speed = std::abs(rate);
  if (!(speed > 0)) return std::numeric_limits<double>::infinity();
  const double span = 2.0 * contact::spall_half_angle(race);
  const double within = span / speed / steps_within_spall;
  const double azimuth = std::atan2(p.y(), p.x()) - ring.spin_angle;
  const double start = race.spall.angle - 0.5 * span;
  const double past_start = turn(azimuth - start);  // how far past the leading edge (moving forward)
  if (past_start < span) return within;             // within the spall
  // Outside: up to the edge it meets next (the start moving forward, the end moving backward).
  const double distance = rate > 0 ? two_pi - past_start : past_start - span;
  return std::max(within, distance / speed);
}

}  // namespace

std::string describe_race_imperfections(const Model& m) {
  std::string out;
  for (const SegmentKind kind : {SegmentKind::ball_inner_groove, SegmentKind::ball_outer_groove}) {
    const Segment* seg = m.first_segment(kind);
    if (!seg) continue;
    const auto& race = m.law<contact::BallGrooveSegment>(*seg).imperfections;
    if (!race) continue;
    const char* ring = kind == SegmentKind::ball_inner_groove ? "inner" : "outer";
    if (race->has_spall) {
      const contact::RaceSpall& s = race->spall;
      out += fmt::format("  {} race: spall at {:.4g} deg (ring frame), {:.4g} x {:.4g} mm, {:.4g} mm deep, {} edges: a "
                         "ball drops at most {:.4g} um into it; at least {} steps across it\n",
                         ring, s.angle * 180 / std::numbers::pi, 1e3 * s.length, 1e3 * s.width, 1e3 * s.depth,
                         s.edge == contact::SpallEdge::sharp ? "sharp" : "smooth",
                         1e6 * contact::spall_effective_depth(s, race->ball_radius), steps_within_spall);
    }
    const contact::RaceWaviness& w = race->waviness;
    for (std::size_t k = 0; k < w.orders.size(); ++k)
      out += fmt::format("  {} race: waviness of order {}, amplitude {:.4g} um, phase {:.4g} deg\n", ring, w.orders[k],
                         1e6 * w.amplitudes[k], w.phases[k] * 180 / std::numbers::pi);
  }
  return out;
}

bool has_spall(const Model& m) {
  for (const Segment& seg : m.segments) {
    if (seg.kind != SegmentKind::ball_inner_groove && seg.kind != SegmentKind::ball_outer_groove) continue;
    const auto& race = m.law<contact::BallGrooveSegment>(seg).imperfections;
    if (race && race->has_spall) return true;
  }
  return false;
}

double spall_step_limit(const Model& m, double t, const double* z) {
  double limit = std::numeric_limits<double>::infinity();
  bool any = false;
  for (const Segment& seg : m.segments) {
    if (seg.kind != SegmentKind::ball_inner_groove && seg.kind != SegmentKind::ball_outer_groove) continue;
    const auto& race = m.law<contact::BallGrooveSegment>(seg).imperfections;
    if (!race || !race->has_spall) continue;
    any = true;
    limit = std::min(limit, ball_limit(*race, m.kinematics(seg.body_a, t, z), m.kinematics(seg.body_b, t, z)));
  }
  return any ? limit : 0.0;
}

}  // namespace raceway::bearing
