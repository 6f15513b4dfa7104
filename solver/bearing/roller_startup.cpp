#include "solver/bearing/startup.hpp"
#include "solver/bearing/thermal_network.hpp"

#include "solver/bearing/carrier_frame.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace raceway::bearing {

using contact::PlanarKinematics;

namespace {

/// Each roller's inner and outer race laws, roller k's at 2 k and 2 k + 1.
std::vector<const contact::RollerRaceSegment*> roller_race_laws(const Model& m) {
  std::vector<const contact::RollerRaceSegment*> laws(static_cast<std::size_t>(2 * m.element_count), nullptr);
  for (const Segment& seg : m.segments) {
    const bool inner = seg.kind == SegmentKind::roller_inner_race;
    if (!inner && seg.kind != SegmentKind::roller_outer_race) continue;
    laws[static_cast<std::size_t>(2 * seg.element + (inner ? 0 : 1))] = &m.law<contact::RollerRaceSegment>(seg);
  }
  for (const auto* law : laws)
    if (!law) throw std::logic_error("start-up: a roller without its two race segments");
  return laws;
}

struct Seating {
  const Model& m;
  double t0;
  double orbit;           // epicyclic cage speed [rad/s]
  double load_direction;  // azimuth of the load on the inner ring relative to the outer [rad]
  double spin = 0;                 // roller spin of the returned state [rad/s]
  double ring_speed[2] = {0, 0};   // inner, outer ring rotation speeds at t0 [rad/s]
  std::optional<CarrierFrame> frame = carrier_frame(m.params().carrier, t0);  // planetary bearings
  std::vector<const contact::RollerRaceSegment*> race_laws = roller_race_laws(m);  // roller k's inner, outer

  /// The kinematics the returned state will have: rings at rest but for their drive speed, the
  /// roller orbiting at the epicyclic speed with its rolling spin (so damping and traction are in
  /// the balance, as they are in Equations::rhs).
  PlanarKinematics ring_at(int r, double cx, double cy) const { return {cx, cy, 0, 0, 0, ring_speed[r]}; }
  PlanarKinematics roller_at(double rho, double psi) const {
    return {rho * std::cos(psi), rho * std::sin(psi), 0, -orbit * rho * std::sin(psi), orbit * rho * std::cos(psi), spin};
  }

  /// The race law of ring r (0 inner, 1 outer) on roller k: its own where the rollers' diameters scatter.
  const contact::RollerRaceSegment& race(int r, int k) const { return *race_laws[static_cast<std::size_t>(2 * k + r)]; }

  double azimuth(int k) const { return load_direction + 2.0 * std::numbers::pi * k / m.element_count; }

  /// Radial contact force of a race on a roller centred at radius rho along azimuth psi, given the
  /// ring centre. Positive = along the outward radial direction e_psi.
  double race_force(int segment, int k, double cx, double cy, double rho, double psi) const {
    const auto& seg = race(segment, k);
    const auto r = contact::evaluate(seg, ring_at(segment, cx, cy), roller_at(rho, psi));
    return r.on_b.fx * std::cos(psi) + r.on_b.fy * std::sin(psi);
  }

  /// Seats roller k between the rings (radial balance with the centrifugal force): bisection on
  /// rho, monotone because the inner force grows and the outer force falls... as rho decreases.
  double seat(int k, const double* inner, const double* outer) const {
    const double psi = azimuth(k);
    const double mass = m.bodies[m.first_element + k].mass;
    auto residual = [&](double rho) {
      const double r = race_force(0, k, inner[0], inner[1], rho, psi) + race_force(1, k, outer[0], outer[1], rho, psi) +
                       mass * orbit * orbit * rho - mass * m.gravity * std::sin(psi);
      if (!frame) return r;
      // The carrier's field along the radius (its tangential part is left to the cage).
      const PlanarKinematics at = roller_at(rho, psi);
      const auto f = frame->force(mass, at.x, at.y, at.vx, at.vy);
      return r + f[0] * std::cos(psi) + f[1] * std::sin(psi);
    };
    // The outer race alone bounds rho from above (residual < 0 deep in the outer race); search down.
    double hi = m.outer_race_radius - m.element_radius + 1e-2 * m.element_radius;
    double lo = m.inner_race_radius + m.element_radius - 1e-2 * m.element_radius;
    // A displaced ring (clearance taken up) moves its race by its centre's offset along psi.
    if (residual(hi) > 0) hi += std::max(0.0, outer[0] * std::cos(psi) + outer[1] * std::sin(psi)) + 1e-2 * m.element_radius;
    if (residual(lo) < 0) lo += std::min(0.0, inner[0] * std::cos(psi) + inner[1] * std::sin(psi)) - 1e-2 * m.element_radius;
    if (residual(hi) > 0 || residual(lo) < 0)
      throw std::runtime_error(fmt::format("start-up: cannot seat roller {} between the races", k));
    for (int it = 0; it < 200 && hi - lo > 1e-16; ++it) {
      const double mid = 0.5 * (lo + hi);
      (residual(mid) > 0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }

  /// Net force on the rings (contacts + loads + gravity + supports) with rollers seated.
  /// x = the free ring translations, in body order.
  Eigen::VectorXd ring_residual(const Eigen::VectorXd& x, const std::vector<int>& free_rings) const {
    double centre[2][2] = {{0, 0}, {0, 0}};
    for (std::size_t i = 0; i < free_rings.size(); ++i) {
      centre[free_rings[i]][0] = x[2 * i];
      centre[free_rings[i]][1] = x[2 * i + 1];
    }
    double force[2][2] = {{0, 0}, {0, 0}};
    for (int k = 0; k < m.element_count; ++k) {
      const double rho = seat(k, centre[0], centre[1]);
      const double psi = azimuth(k);
      const PlanarKinematics roller = roller_at(rho, psi);
      for (int r = 0; r < 2; ++r) {
        const auto res = contact::evaluate(race(r, k), ring_at(r, centre[r][0], centre[r][1]), roller);
        force[r][0] += res.on_a.fx;
        force[r][1] += res.on_a.fy;
      }
    }
    Eigen::VectorXd out(x.size());
    for (std::size_t i = 0; i < free_rings.size(); ++i) {
      const Body& b = m.bodies[free_rings[i] == 0 ? m.inner_ring : m.outer_ring];
      const auto& sup = b.ring->support;
      out[2 * i] = force[free_rings[i]][0] + b.ring->load.fx(t0) - sup.stiffness * x[2 * i];
      out[2 * i + 1] = force[free_rings[i]][1] + b.ring->load.fy(t0) - b.mass * m.gravity -
                       sup.stiffness * x[2 * i + 1];
      if (frame) {
        const auto f = frame->force(b.mass, x[2 * i], x[2 * i + 1], 0, 0);
        out[2 * i] += f[0], out[2 * i + 1] += f[1];
      }
    }
    return out;
  }
};

/// The free rings' centres at x(a): each moved by a along the load (the inner ring with it, the
/// outer ring against it).
Eigen::VectorXd along_load(const Seating& s, const std::vector<int>& free_rings, double a) {
  Eigen::VectorXd x(2 * static_cast<Eigen::Index>(free_rings.size()));
  for (std::size_t i = 0; i < free_rings.size(); ++i) {
    const double sign = free_rings[i] == 0 ? 1 : -1;
    x[2 * static_cast<Eigen::Index>(i)] = a * std::cos(s.load_direction) * sign;
    x[2 * static_cast<Eigen::Index>(i) + 1] = a * std::sin(s.load_direction) * sign;
  }
  return x;
}

/// The net force along the load on the rings at x(a): > 0 while the load is not yet carried.
double force_along_load(const Seating& s, const std::vector<int>& free_rings, double a) {
  const Eigen::VectorXd r = s.ring_residual(along_load(s, free_rings, a), free_rings);
  return r.dot(along_load(s, free_rings, 1.0));
}

/// With clearance the contacts under the load close one by one as the rings take up the play: the
/// rings are first moved along the load until the force along it balances (bisection: that force
/// falls monotonically as the contacts close), so that the Newton iteration starts with the load
/// shared by the rollers that carry it in the end. `touch` is the play along the load; a load
/// the rollers do not have to carry (none, or held by a support within the play) leaves the
/// rings where the force along it vanishes inside the play.
double take_up_play(const Seating& s, const std::vector<int>& free_rings, double touch) {
  double lo = 0, hi = touch + 1e-7;
  if (force_along_load(s, free_rings, lo) <= 0) return 0.0;
  for (int grow = 0; grow < 60 && force_along_load(s, free_rings, hi) > 0; ++grow) lo = hi, hi *= 2;
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (force_along_load(s, free_rings, mid) > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// Newton with finite differences and backtracking on the ring translations x, on the net ring
/// forces plus a spring `spring` (N/m) that pulls the rings to `anchor`. Returns the residual.
Eigen::VectorXd newton_on_rings(const Seating& s, const std::vector<int>& free_rings, double spring,
                                const Eigen::VectorXd& anchor, double tolerance, Eigen::VectorXd& x, int& iterations) {
  const auto n = x.size();
  auto residual = [&](const Eigen::VectorXd& at) {
    Eigen::VectorXd r = s.ring_residual(at, free_rings);
    if (spring > 0) r -= spring * (at - anchor);
    return r;
  };
  Eigen::VectorXd r = residual(x);
  for (int it = 0; it < 100; ++it, ++iterations) {
    if (r.cwiseAbs().maxCoeff() < tolerance) break;
    Eigen::MatrixXd jac(n, n);
    for (Eigen::Index j = 0; j < n; ++j) {
      Eigen::VectorXd xp = x;
      const double h = 1e-10;
      xp[j] += h;
      jac.col(j) = (residual(xp) - r) / h;
    }
    const Eigen::VectorXd dx = jac.fullPivLu().solve(-r);
    double lambda = 1.0;
    for (int ls = 0; ls < 30; ++ls, lambda *= 0.5) {
      Eigen::VectorXd xn = x + lambda * dx;
      Eigen::VectorXd rn;
      try {
        rn = residual(xn);
      } catch (const std::runtime_error&) {
        continue;  // a step so long that a roller cannot be seated: shorten it
      }
      if (rn.norm() < r.norm()) {
        x = xn;
        r = rn;
        break;
      }
    }
  }
  return r;
}

/// The free rings' centres in equilibrium under their loads. Throws naming the keys when there
/// is none.
///
/// Zero clearance: Newton from a tiny initial approach, so the contacts are closed (Palmgren has
/// zero stiffness at onset). With clearance the inner ring first takes up the play along the load
/// (it moves by P_d / 2 before it touches the roller under the load; two free rings share it).
/// There one roller may carry the whole load, and a ring on one roller is an inverted pendulum:
/// across the load its stiffness is negative (-Q / R) until a neighbour engages, so Newton steps
/// across the load go the wrong way. As in the ball start-up, a spring to that point keeps the
/// problem regular and is relaxed in stages (1e9 to 1e3 N/m, then none), each stage starting next
/// to its solution.
///
/// At zero clearance, or a negative one (a preload: every roller pressed in, the rings centred
/// and stiff in every direction), the direct Newton is tried first; at high speed the rollers' centrifugal
/// force presses them into the outer race and opens a play of its own, so when the direct Newton
/// fails the continuation is used there too.
Eigen::VectorXd seat_rings(const Seating& s, const std::vector<int>& free_rings, double load_scale,
                           StartupReport& rep) {
  const double clearance = s.m.params().bearing.radial_clearance;
  const double share = 0.5 * clearance / static_cast<double>(free_rings.size());
  auto solve = [&](bool continuation, Eigen::VectorXd& x) {
    x = along_load(s, free_rings, continuation ? take_up_play(s, free_rings, share) : 1e-7);
    const Eigen::VectorXd anchor = x;
    if (continuation)
      for (const double spring : {1e9, 1e8, 1e7, 1e6, 1e5, 1e4, 1e3})
        newton_on_rings(s, free_rings, spring, anchor, 1e-8 * load_scale, x, rep.iterations);
    return newton_on_rings(s, free_rings, 0.0, anchor, 1e-10 * load_scale, x, rep.iterations).cwiseAbs().maxCoeff();
  };
  Eigen::VectorXd x;
  rep.iterations = 0;
  rep.residual = std::numeric_limits<double>::infinity();
  if (clearance <= 0) {
    try {
      rep.residual = solve(false, x);
    } catch (const std::runtime_error&) {
      // a roller that cannot be seated on the way: the continuation below starts elsewhere
    }
  }
  if (!(rep.residual < 1e-6 * load_scale)) rep.residual = solve(true, x);
  if (!(rep.residual < 1e-6 * load_scale))
    throw std::runtime_error(fmt::format(
        "start-up: no quasi-static equilibrium of the rings under their loads (largest unbalanced force {:.3g} N "
        "after {} Newton iterations); the keys involved: bearing.radial_clearance ({:.4g} um), inner_ring.load, "
        "outer_ring.load, the rings' support.stiffness and translation, scene.gravity",
        rep.residual, rep.iterations, 1e6 * clearance));
  return x;
}

}  // namespace

StartupReport seat_roller_bearing(const Model& m, double t0) {
  StartupReport rep;
  std::vector<int> free_rings;  // 0 inner, 1 outer
  if (m.bodies[m.inner_ring].slot[sx] >= 0) free_rings.push_back(0);
  if (m.bodies[m.outer_ring].slot[sx] >= 0) free_rings.push_back(1);

  // Direction in which the load pushes the inner ring against the outer one.
  const auto& in = m.params().inner_ring.load;
  const auto& out = m.params().outer_ring.load;
  double lx = in.fx(t0) - out.fx(t0), ly = in.fy(t0) - out.fy(t0);
  const double g = m.gravity;
  ly -= g * (m.bodies[m.inner_ring].mass - m.bodies[m.outer_ring].mass);
  if (const auto frame = carrier_frame(m.params().carrier, t0)) {
    // The carrier's field pulls both rings outwards (+x) and the rollers onto the outer race.
    const auto free_mass = [&](int r) { return m.bodies[r].slot[sx] >= 0 ? m.bodies[r].mass : 0.0; };
    double outward = free_mass(m.inner_ring) - free_mass(m.outer_ring);
    for (int k = 0; k < m.element_count; ++k) outward -= m.bodies[m.first_element + k].mass;
    const auto f = frame->force(outward, 0, 0, 0, 0);
    lx += f[0], ly += f[1];
  }
  Seating s{m, t0, m.epicyclic_cage_speed(t0),
            (lx == 0 && ly == 0) ? -0.5 * std::numbers::pi : std::atan2(ly, lx)};

  {
    auto speed = [&](int b) {
      const auto* spec = m.bodies[b].ring;
      return spec->motion == scene::RingMotion::driven ? spec->speed(t0) : 0.0;
    };
    s.ring_speed[0] = speed(m.inner_ring);
    s.ring_speed[1] = speed(m.outer_ring);
    s.spin = s.orbit - (s.ring_speed[0] - s.orbit) * m.inner_race_radius / m.element_radius;
  }
  const int n = 2 * static_cast<int>(free_rings.size());
  double load_scale = 1.0;
  for (const auto* l : {&in, &out}) load_scale = std::max({load_scale, std::abs(l->fx(t0)), std::abs(l->fy(t0))});
  const Eigen::VectorXd x = n > 0 ? seat_rings(s, free_rings, load_scale, rep) : Eigen::VectorXd::Zero(0);

  // Assemble the state.
  rep.state.assign(m.state_size, 0.0);
  double centre[2][2] = {{0, 0}, {0, 0}};
  for (std::size_t i = 0; i < free_rings.size(); ++i) {
    const Body& b = m.bodies[free_rings[i] == 0 ? m.inner_ring : m.outer_ring];
    centre[free_rings[i]][0] = rep.state[b.slot[sx]] = x[2 * i];
    centre[free_rings[i]][1] = rep.state[b.slot[sy]] = x[2 * i + 1];
  }
  const double wc = s.orbit;
  for (int r : {m.inner_ring, m.outer_ring}) {
    const Body& b = m.bodies[r];
    if (b.slot[swz] >= 0) rep.state[b.slot[swz]] = 0.0;
  }
  // Rollers: the seated positions with the kinematics the seating balanced (epicyclic orbit, pure
  // rolling spin on the inner race).
  for (int k = 0; k < m.element_count; ++k) {
    const Body& b = m.bodies[m.first_element + k];
    const PlanarKinematics r = s.roller_at(s.seat(k, centre[0], centre[1]), s.azimuth(k));
    rep.state[b.slot[sx]] = r.x;
    rep.state[b.slot[sy]] = r.y;
    m.set_velocity(m.first_element + k, {r.vx, r.vy, 0.0}, rep.state.data());
    rep.state[b.slot[swz]] = r.omega;
  }
  // Cage: concentric with its guiding ring, pocket k centred on roller k, at the epicyclic speed.
  const Body& cage = m.bodies[m.cage];
  int guide = -1;
  if (const Segment* land = m.first_segment(SegmentKind::cage_land))
    guide = m.law<contact::CageLandSegment>(*land).outer_land ? 1 : 0;
  if (guide >= 0) {
    rep.state[cage.slot[sx]] = centre[guide][0];
    rep.state[cage.slot[sy]] = centre[guide][1];
  }
  rep.state[cage.slot[saz]] = s.load_direction;
  rep.state[cage.slot[swz]] = wc;
  for (const auto& node : m.nodes) node->initial_state(rep.state);  // flexible parts: their own start
  rep.summary = fmt::format(
      "start-up: rings seated in {} Newton iterations (residual {:.2e} N), inner ring at ({:.4f}, {:.4f}) um, "
      "rollers at {:.2f} rpm orbit, spin {:.1f} rad/s",
      rep.iterations, rep.residual, 1e6 * centre[0][0], 1e6 * centre[0][1], wc * 30 / std::numbers::pi,
      s.spin);
  return rep;
}

StartupReport seat_spatial_roller_bearing(const Model& m, double t0) {
  if (!m.planar_restriction) throw std::logic_error("start-up: a spatial roller model without its planar restriction");
  const Model& planar = *m.planar_restriction;
  StartupReport planar_start = seat_roller_bearing(planar, t0);
  StartupReport rep;
  rep.state.assign(static_cast<std::size_t>(m.state_size), 0.0);
  // The same bodies in the same order: every coordinate both models have is copied (x, y, the
  // angle and rate about z); the rest (axial, tilt, skew) starts at zero.
  for (std::size_t b = 0; b < m.bodies.size(); ++b)
    for (int c = 0; c < coordinate_count; ++c) {
      const int from = planar.bodies[b].slot[c], to = m.bodies[b].slot[c];
      if (from >= 0 && to >= 0) rep.state[static_cast<std::size_t>(to)] = planar_start.state[static_cast<std::size_t>(from)];
    }
  rep.iterations = planar_start.iterations;
  rep.residual = planar_start.residual;
  rep.summary = planar_start.summary + " (the planar seating, lifted into space: aligned, axially centred)";
  return rep;
}

StartupReport initial_state(const Model& model, double t0, double azimuth_offset, Equations* equations) {
  StartupReport start;
  if (model.bearing_type == scene::BearingType::tapered_roller)
    start = seat_tapered_roller_bearing(model, t0);
  else if (model.kind == scene::ModelKind::spatial && model.bearing_type == scene::BearingType::cylindrical_roller)
    start = seat_spatial_roller_bearing(model, t0);
  else if (model.kind == scene::ModelKind::spatial)
    start = seat_ball_bearing(model, t0, azimuth_offset, equations);
  else
    start = seat_roller_bearing(model, t0);
  if (const ThermalNetwork* thermal = thermal_network_of(model)) thermal->initial_state(start.state);  // no seating
  return start;
}

}  // namespace raceway::bearing
