#include "solver/bearing/race_defects.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "contact/laws/element_imperfections.hpp"
#include "contact/segments/roller_slice_segment.hpp"
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

std::shared_ptr<const contact::RaceImperfections> element_imperfections(const scene::Scene& scene, int k, double r) {
  const scene::RollingElementSpec& e = scene.rolling_element;
  const bool spall = e.spall.present && e.spall_element == k;
  const bool waviness = e.waviness.present() && e.waviness_element == k;
  if (!spall && !waviness) return nullptr;
  auto out = std::make_shared<contact::RaceImperfections>();
  out->race_radius = r;
  out->ball_radius = r;
  out->has_spall = spall;
  if (spall) out->spall = {e.spall.angle, e.spall.length, e.spall.width, e.spall.depth, e.spall.edge};
  if (waviness) out->waviness = {e.waviness.orders, e.waviness.amplitudes, e.waviness.phases};
  return out;
}

std::vector<int> roller_slice_laws(Model& m, const scene::Scene& scene, int k, const std::vector<int>& shared,
                                   double reach_per_radius) {
  const auto own = element_imperfections(scene, k, m.radius_of_element(k));
  if (!own && m.element_radii.empty()) return shared;
  const double grow = (m.radius_of_element(k) - m.element_radius) * reach_per_radius;
  std::vector<int> laws;
  for (const int law : shared) {
    contact::RollerSliceSegment copy = std::get<contact::RollerSliceSegment>(m.laws[static_cast<std::size_t>(law)]);
    copy.roller_imperfections = own;
    copy.roller_radius += grow;
    m.laws.push_back(std::move(copy));
    laws.push_back(static_cast<int>(m.laws.size()) - 1);
  }
  return laws;
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

/// The step limit for a ball's own spall at one race contact.
double element_limit(const contact::BallGrooveSegment& law, const contact::SpatialKinematics& ring,
                     const contact::SpatialKinematics& ball) {
  const contact::GrooveContactFrame frame = contact::groove_contact_frame(law, ring, ball);
  const double speed = (ball.angular_velocity - frame.rate).norm();
  if (!frame.valid || !(speed > 0)) return std::numeric_limits<double>::infinity();
  const contact::RaceImperfections& e = *law.element_imperfections;
  const double half = contact::spall_half_angle(e);
  const double within = 2.0 * half / speed / steps_within_spall;
  const double distance = contact::element_spall_distance(e, ball.rotation, frame.n) - half;
  return distance <= 0 ? within : std::max(within, distance / speed);
}

/// The step limit for a roller's own spall at one race (its contact's direction: the ring's radial
/// line through the roller's centre, towards the race; the roller's spin about its axis relative to it).
double roller_limit(const contact::RollerSliceSegment& law, const contact::SpatialKinematics& ring,
                    const contact::SpatialKinematics& roller) {
  const contact::Vec3 rel = roller.position - ring.position;
  const contact::Vec3 p = ring.rotation.transpose() * rel;
  const double rho2 = p.x() * p.x() + p.y() * p.y();
  if (!(rho2 > 0)) return std::numeric_limits<double>::infinity();
  const contact::Vec3 p_dot =
      ring.rotation.transpose() * (roller.velocity - ring.velocity - ring.angular_velocity.cross(rel));
  const double azimuth_rate = (p.x() * p_dot.y() - p.y() * p_dot.x()) / rho2;
  const contact::Vec3 radial = ring.rotation * contact::Vec3(p.x(), p.y(), 0.0);
  const contact::Vec3 d = law.outer ? radial : contact::Vec3(-radial);
  const contact::Vec3 frame_rate = ring.angular_velocity + azimuth_rate * ring.rotation.col(2);
  const double speed = std::abs((roller.angular_velocity - frame_rate).dot(roller.rotation.col(2)));
  if (!(speed > 0)) return std::numeric_limits<double>::infinity();
  const contact::RaceImperfections& e = *law.roller_imperfections;
  const double half = contact::spall_half_angle(e);
  const double within = 2.0 * half / speed / steps_within_spall;
  const double distance = contact::roller_spall_distance(e, roller.rotation, d) - half;
  return distance <= 0 ? within : std::max(within, distance / speed);
}

/// The roller's own imperfections a roller slice's law carries, or null.
const contact::RaceImperfections* roller_own(const Model& m, const Segment& seg) {
  if (seg.kind != SegmentKind::roller_inner_slice && seg.kind != SegmentKind::roller_outer_slice) return nullptr;
  return m.law<contact::RollerSliceSegment>(seg).roller_imperfections.get();
}

/// The race's imperfections a race segment's law carries (a ball groove or a roller slice), or null.
const contact::RaceImperfections* race_of(const Model& m, const Segment& seg) {
  switch (seg.kind) {
    case SegmentKind::ball_inner_groove:
    case SegmentKind::ball_outer_groove:
      return m.law<contact::BallGrooveSegment>(seg).imperfections.get();
    case SegmentKind::roller_inner_slice:
    case SegmentKind::roller_outer_slice:
      return m.law<contact::RollerSliceSegment>(seg).imperfections.get();
    default:
      return nullptr;
  }
}

bool is_ball_groove(const Segment& seg) {
  return seg.kind == SegmentKind::ball_inner_groove || seg.kind == SegmentKind::ball_outer_groove;
}

}  // namespace

std::string describe_race_imperfections(const Model& m) {
  std::string out;
  for (const SegmentKind kind : {SegmentKind::ball_inner_groove, SegmentKind::ball_outer_groove,
                                 SegmentKind::roller_inner_slice, SegmentKind::roller_outer_slice}) {
    const Segment* seg = m.first_segment(kind);
    if (!seg) continue;
    const contact::RaceImperfections* race = race_of(m, *seg);
    if (!race) continue;
    const bool inner = kind == SegmentKind::ball_inner_groove || kind == SegmentKind::roller_inner_slice;
    const char* ring = inner ? "inner" : "outer";
    if (race->has_spall) {
      const contact::RaceSpall& s = race->spall;
      out += fmt::format("  {} race: spall at {:.4g} deg (ring frame), {:.4g} x {:.4g} mm, {:.4g} mm deep, {} edges: a "
                         "{} drops at most {:.4g} um into it; at least {} steps across it\n",
                         ring, s.angle * 180 / std::numbers::pi, 1e3 * s.length, 1e3 * s.width, 1e3 * s.depth,
                         s.edge == contact::SpallEdge::sharp ? "sharp" : "smooth", is_ball_groove(*seg) ? "ball" : "roller",
                         1e6 * contact::spall_effective_depth(s, race->ball_radius), steps_within_spall);
    }
    const contact::RaceWaviness& w = race->waviness;
    for (std::size_t k = 0; k < w.orders.size(); ++k)
      out += fmt::format("  {} race: waviness of order {}, amplitude {:.4g} um, phase {:.4g} deg\n", ring, w.orders[k],
                         1e6 * w.amplitudes[k], w.phases[k] * 180 / std::numbers::pi);
  }
  for (const Segment& seg : m.segments) {  // a ball's own defect: its inner groove's law holds it
    if (seg.kind != SegmentKind::ball_inner_groove) continue;
    const auto& e = m.law<contact::BallGrooveSegment>(seg).element_imperfections;
    if (!e || (!seg.name.ends_with("groove") && !seg.name.ends_with("groovea"))) continue;
    if (e->has_spall)
      out += fmt::format("  ball[{}]: spall at {:.4g} deg round its equator (ball frame), {:.4g} x {:.4g} mm, {:.4g} mm "
                         "deep, {} edges: a race reaches at most {:.4g} um into it; the balls' orientations are states\n",
                         seg.element, e->spall.angle * 180 / std::numbers::pi, 1e3 * e->spall.length,
                         1e3 * e->spall.width, 1e3 * e->spall.depth,
                         e->spall.edge == contact::SpallEdge::sharp ? "sharp" : "smooth",
                         1e6 * contact::spall_effective_depth(e->spall, e->ball_radius));
    for (std::size_t k = 0; k < e->waviness.orders.size(); ++k)
      out += fmt::format("  ball[{}]: waviness of order {} round its equator, amplitude {:.4g} um, phase {:.4g} deg\n",
                         seg.element, e->waviness.orders[k], 1e6 * e->waviness.amplitudes[k],
                         e->waviness.phases[k] * 180 / std::numbers::pi);
  }
  for (const Segment& seg : m.segments) {  // a roller's own defect: its first inner slice's law holds it
    const contact::RaceImperfections* e = roller_own(m, seg);
    if (!e || seg.kind != SegmentKind::roller_inner_slice || !seg.name.ends_with("slice[0]")) continue;
    if (e->has_spall)
      out += fmt::format("  roller[{}]: spall at {:.4g} deg round its circumference (roller frame), {:.4g} mm long, "
                         "{:.4g} mm wide (along its axis), {:.4g} mm deep, {} edges: a race reaches at most {:.4g} um "
                         "into it; the rollers' angles about their axes are states\n",
                         seg.element, e->spall.angle * 180 / std::numbers::pi, 1e3 * e->spall.length,
                         1e3 * e->spall.width, 1e3 * e->spall.depth,
                         e->spall.edge == contact::SpallEdge::sharp ? "sharp" : "smooth",
                         1e6 * contact::spall_effective_depth(e->spall, e->ball_radius));
    for (std::size_t k = 0; k < e->waviness.orders.size(); ++k)
      out += fmt::format("  roller[{}]: waviness of order {} round its circumference, amplitude {:.4g} um, phase "
                         "{:.4g} deg\n",
                         seg.element, e->waviness.orders[k], 1e6 * e->waviness.amplitudes[k],
                         e->waviness.phases[k] * 180 / std::numbers::pi);
  }
  return out;
}

bool has_spall(const Model& m) {
  for (const Segment& seg : m.segments) {
    const contact::RaceImperfections* race = race_of(m, seg);
    if (race && race->has_spall) return true;
    const contact::RaceImperfections* own = roller_own(m, seg);
    if (own && own->has_spall) return true;
    if (!is_ball_groove(seg)) continue;
    const auto& element = m.law<contact::BallGrooveSegment>(seg).element_imperfections;
    if (element && element->has_spall) return true;
  }
  return false;
}

double spall_step_limit(const Model& m, double t, const double* z) {
  double limit = std::numeric_limits<double>::infinity();
  bool any = false;
  const Segment* previous = nullptr;  // a roller's slices share its limit: the first one's
  for (const Segment& seg : m.segments) {
    const contact::RaceImperfections* race = race_of(m, seg);
    const bool ball = is_ball_groove(seg);
    const auto* law = ball ? &m.law<contact::BallGrooveSegment>(seg) : nullptr;
    const bool element = law && law->element_imperfections && law->element_imperfections->has_spall;
    const bool same_roller = !ball && previous && previous->kind == seg.kind && previous->element == seg.element;
    if (seg.kind == SegmentKind::roller_inner_slice || seg.kind == SegmentKind::roller_outer_slice) previous = &seg;
    const contact::RaceImperfections* own = same_roller ? nullptr : roller_own(m, seg);
    const bool roller_spall = own && own->has_spall;
    if ((!race || !race->has_spall || same_roller) && !element && !roller_spall) continue;
    any = true;
    const contact::SpatialKinematics ring = m.kinematics(seg.body_a, t, z), body = m.kinematics(seg.body_b, t, z);
    if (race && race->has_spall && !same_roller) limit = std::min(limit, ball_limit(*race, ring, body));
    if (element) limit = std::min(limit, element_limit(*law, ring, body));
    if (roller_spall) limit = std::min(limit, roller_limit(m.law<contact::RollerSliceSegment>(seg), ring, body));
  }
  return any ? limit : 0.0;
}

}  // namespace raceway::bearing
