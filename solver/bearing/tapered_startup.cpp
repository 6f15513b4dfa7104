// The seating of a spatial tapered roller bearing: a quasi-static equilibrium found with the
// contact functions the dynamics use (the race slices and the rib), velocity-free. Unknowns: the
// rings' free position coordinates (translation, axial, tilt) and each roller's radial and axial
// position and its axis's tilt in its meridian plane (its lean beta + delta); residuals: the rings'
// force and moment balance under their loads, supports and gravity, each roller's radial and axial
// force (centrifugal at the epicyclic orbit included) and its moment about its tangent. The
// rollers' gyroscopic moment is left to the dynamics. Levenberg-Marquardt with a continuation in a
// regularization spring, as the ball bearing's seating (ball_startup.cpp): every contact starts just
// touching, where the Palmgren law has no stiffness.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "solver/bearing/startup.hpp"

namespace raceway::bearing {

using contact::SpatialKinematics;
using contact::Vec3;

namespace {

constexpr double pi = std::numbers::pi;

struct Unknown {
  int body = -1;       ///< ring or roller body
  int component = -1;  ///< ring: Coordinate (sx..say); roller: 0 radial, 1 axial, 2 tilt
  bool roller = false;
  double scale = 1e-6;  ///< m or rad per unit of the scaled unknown
};

struct TaperedSeating {
  const Model& m;
  double t0;
  double orbit = 0, force_scale = 1, regularization = 1e3;
  double beta = 0;  ///< the rollers' nominal lean
  std::vector<Unknown> unknowns;

  TaperedSeating(const Model& model, double t) : m(model), t0(t) {
    orbit = m.epicyclic_cage_speed(t0);
    beta = 0.5 * (m.cone_angle + m.cup_angle);
    for (int r : {m.inner_ring, m.outer_ring}) {
      const auto& b = m.bodies[static_cast<std::size_t>(r)];
      for (int c = sx; c <= say; ++c)
        if (b.slot[c] >= 0) unknowns.push_back({r, c, false, c >= sax ? 1e-4 : 1e-6});
    }
    for (int k = 0; k < m.element_count; ++k)
      for (int c = 0; c < 3; ++c) unknowns.push_back({m.first_element + k, c, true, c == 2 ? 1e-5 : 1e-6});
    double load = 0;
    for (int r : {m.inner_ring, m.outer_ring}) {
      const auto& l = m.bodies[static_cast<std::size_t>(r)].ring->load;
      load = std::max({load, std::abs(l.fx(t0)), std::abs(l.fy(t0)), std::abs(l.fz(t0))});
    }
    force_scale = std::max(load, 1.0);
  }

  double azimuth(int k) const { return 2.0 * pi * k / m.element_count; }

  /// The state for scaled unknowns u: positions and axes set, velocities zero.
  std::vector<double> state(const Eigen::VectorXd& u) const {
    std::vector<double> z(static_cast<std::size_t>(m.state_size), 0.0);
    std::vector<std::array<double, 3>> pose(static_cast<std::size_t>(m.element_count), {m.pitch_radius, 0.0, 0.0});
    for (std::size_t i = 0; i < unknowns.size(); ++i) {
      const auto& q = unknowns[i];
      const double v = u[static_cast<Eigen::Index>(i)] * q.scale;
      if (q.roller)
        pose[static_cast<std::size_t>(q.body - m.first_element)][static_cast<std::size_t>(q.component)] += v;
      else
        z[static_cast<std::size_t>(m.bodies[static_cast<std::size_t>(q.body)].slot[q.component])] = v;
    }
    for (int k = 0; k < m.element_count; ++k) {
      const auto& b = m.bodies[static_cast<std::size_t>(m.first_element + k)];
      const auto& p = pose[static_cast<std::size_t>(k)];
      const double psi = azimuth(k), lean = beta + p[2];
      const Vec3 axis(std::sin(lean) * std::cos(psi), std::sin(lean) * std::sin(psi), std::cos(lean));
      z[static_cast<std::size_t>(b.slot[sx])] = p[0] * std::cos(psi);
      z[static_cast<std::size_t>(b.slot[sy])] = p[0] * std::sin(psi);
      z[static_cast<std::size_t>(b.slot[sz])] = p[1];
      // R = Rx(ax) Ry(ay): R e_z = (sin ay, -sin ax cos ay, cos ax cos ay).
      z[static_cast<std::size_t>(b.slot[say])] = std::asin(axis.x());
      z[static_cast<std::size_t>(b.slot[sax])] = std::atan2(-axis.y(), axis.z());
    }
    return z;
  }

  SpatialKinematics at_rest(int b, const std::vector<double>& z) const {
    SpatialKinematics k = m.kinematics(b, t0, z.data());
    k.velocity = Vec3::Zero();
    k.angular_velocity = Vec3::Zero();
    return k;
  }

  /// Every ring-roller contact's wrench at rest, summed per body.
  std::vector<contact::SpatialWrench> wrenches(const std::vector<double>& z) const {
    std::vector<contact::SpatialWrench> w(m.bodies.size());
    for (const auto& seg : m.segments) {
      if (seg.kind != SegmentKind::roller_inner_slice && seg.kind != SegmentKind::roller_outer_slice &&
          seg.kind != SegmentKind::roller_flange)
        continue;
      const SpatialKinematics ring = at_rest(seg.body_a, z), roller = at_rest(seg.body_b, z);
      const auto r = seg.kind == SegmentKind::roller_flange
                         ? contact::evaluate(m.law<contact::RollerFlangeSegment>(seg), ring, roller)
                         : contact::evaluate(m.law<contact::RollerSliceSegment>(seg), ring, roller);
      auto& wa = w[static_cast<std::size_t>(seg.body_a)];
      auto& wb = w[static_cast<std::size_t>(seg.body_b)];
      wa.force += r.on_a.force, wa.moment += r.on_a.moment;
      wb.force += r.on_b.force, wb.moment += r.on_b.moment;
    }
    return w;
  }

  double ring_residual(const Unknown& q, double value, const std::vector<double>& z,
                       const contact::SpatialWrench& cw) const {
    const auto& body = m.bodies[static_cast<std::size_t>(q.body)];
    contact::SpatialWrench ext;
    const auto& l = body.ring->load;
    ext.force = Vec3(l.fx(t0), l.fy(t0), l.fz(t0));
    ext.moment = Vec3(l.mx(t0), l.my(t0), 0.0);
    if (body.slot[svy] >= 0) ext.force.y() -= body.mass * m.gravity;
    const auto& s = body.ring->support;
    auto pos = [&](int c) { return body.slot[c] >= 0 ? z[static_cast<std::size_t>(body.slot[c])] : 0.0; };
    ext.force -= Vec3(s.stiffness * pos(sx), s.stiffness * pos(sy), s.axial_stiffness * pos(sz));
    ext.moment -= Vec3(s.tilt_stiffness * pos(sax), s.tilt_stiffness * pos(say), 0.0);
    const bool angle = q.component >= sax;
    const double f = angle ? (cw.moment[q.component - sax] + ext.moment[q.component - sax]) / m.pitch_radius
                           : cw.force[q.component] + ext.force[q.component];
    return f - regularization * value * (angle ? m.pitch_radius : 1.0);
  }

  double roller_residual(const Unknown& q, double value, const std::vector<double>& z,
                         const contact::SpatialWrench& cw) const {
    const auto& body = m.bodies[static_cast<std::size_t>(q.body)];
    const double psi = azimuth(q.body - m.first_element);
    const Vec3 er(std::cos(psi), std::sin(psi), 0.0), et(-std::sin(psi), std::cos(psi), 0.0);
    Vec3 force = cw.force;
    const Vec3 x(z[static_cast<std::size_t>(body.slot[sx])], z[static_cast<std::size_t>(body.slot[sy])], 0.0);
    force += body.mass * orbit * orbit * x;
    force.y() -= body.mass * m.gravity;
    const double rr = m.element_radius;
    if (q.component == 2) return cw.moment.dot(et) / rr - regularization * value * rr;
    return (q.component == 0 ? force.dot(er) : force.z()) - regularization * value;
  }

  Eigen::VectorXd residual(const Eigen::VectorXd& u) const {
    const std::vector<double> z = state(u);
    const auto w = wrenches(z);
    Eigen::VectorXd res(static_cast<Eigen::Index>(unknowns.size()));
    for (std::size_t i = 0; i < unknowns.size(); ++i) {
      const auto& q = unknowns[i];
      const double value = u[static_cast<Eigen::Index>(i)] * q.scale;
      const auto& cw = w[static_cast<std::size_t>(q.body)];
      res[static_cast<Eigen::Index>(i)] =
          (q.roller ? roller_residual(q, value, z, cw) : ring_residual(q, value, z, cw)) / force_scale;
    }
    return res;
  }
};

/// Levenberg-Marquardt at the current regularization, forward-difference Jacobian; returns iterations.
int solve_stage(const TaperedSeating& seat, double tolerance, Eigen::VectorXd& u, Eigen::VectorXd& r) {
  const auto n = u.size();
  r = seat.residual(u);
  double cost = r.squaredNorm(), lambda = 1e-3;
  int iterations = 0;
  for (; iterations < 200 && r.lpNorm<Eigen::Infinity>() > tolerance; ++iterations) {
    Eigen::MatrixXd jac(n, n);
    for (Eigen::Index j = 0; j < n; ++j) {
      Eigen::VectorXd up = u;
      up[j] += 1e-4;
      jac.col(j) = (seat.residual(up) - r) / 1e-4;
    }
    const Eigen::MatrixXd a = jac.transpose() * jac;
    const Eigen::VectorXd g = jac.transpose() * r;
    bool improved = false;
    for (int attempt = 0; attempt < 30 && !improved; ++attempt) {
      Eigen::MatrixXd damped = a;
      const double floor = 1e-4 * a.diagonal().maxCoeff() + 1e-30;
      for (Eigen::Index i = 0; i < n; ++i) damped(i, i) += lambda * std::max(a(i, i), floor);
      Eigen::VectorXd step = damped.ldlt().solve(-g);
      const double largest = step.lpNorm<Eigen::Infinity>();
      if (largest > 5.0) step *= 5.0 / largest;  // a few micrometres per step: contacts close gradually
      const Eigen::VectorXd trial = u + step;
      const Eigen::VectorXd rt = seat.residual(trial);
      if (rt.allFinite() && rt.squaredNorm() < cost) {
        u = trial, r = rt, cost = rt.squaredNorm();
        lambda = std::max(lambda / 5.0, 1e-12);
        improved = true;
      } else {
        lambda *= 8.0;
      }
    }
    if (!improved) break;
  }
  return iterations;
}

/// Rolling without sliding about the raceways' common apex: the cage and each roller's orbit at the
/// epicyclic speed, its spin about its own axis (w_o - w_c) sin(alpha_o) / sin(gamma); the cage
/// centred with pocket k on roller k.
void set_rolling(const Model& m, const TaperedSeating& seat, std::vector<double>& z) {
  const double wc = seat.orbit;
  const double wo = m.ring_spin(m.outer_ring, seat.t0, z.data());
  const double gamma = 0.5 * (m.cup_angle - m.cone_angle);
  const double spin = (wo - wc) * std::sin(m.cup_angle) / std::sin(gamma);
  for (int k = 0; k < m.element_count; ++k) {
    const auto& b = m.bodies[static_cast<std::size_t>(m.first_element + k)];
    const auto at = [&](int c) { return z[static_cast<std::size_t>(b.slot[c])]; };
    const Vec3 axis = cardan_rotation(at(sax), at(say), 0.0).col(2);
    const Vec3 v = wc * Vec3::UnitZ().cross(Vec3(at(sx), at(sy), at(sz)));
    const Vec3 w = wc * Vec3::UnitZ() + spin * axis;
    for (int d = 0; d < 3; ++d) {
      z[static_cast<std::size_t>(b.slot[svx + d])] = v[d];
      z[static_cast<std::size_t>(b.slot[swx + d])] = w[d];
    }
  }
  const Body& cage = m.bodies[static_cast<std::size_t>(m.cage)];
  z[static_cast<std::size_t>(cage.slot[swz])] = wc;
}

}  // namespace

StartupReport seat_tapered_roller_bearing(const Model& m, double t0) {
  TaperedSeating seat(m, t0);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(seat.unknowns.size()));
  Eigen::VectorXd r;
  StartupReport rep;
  for (const double spring : {1e8, 1e7, 1e6, 1e5, 1e4, 1e3}) {
    seat.regularization = spring;
    rep.iterations += solve_stage(seat, spring > 1e3 ? 1e-6 : 1e-9, u, r);
  }
  rep.residual = r.lpNorm<Eigen::Infinity>() * seat.force_scale;
  if (!(rep.residual <= 1e-6 * seat.force_scale + 1e-6))
    throw std::runtime_error(fmt::format(
        "start-up: no quasi-static equilibrium of the tapered roller bearing found after {} iterations (largest "
        "unbalanced force {:.4g} N); a single tapered bearing needs its cone pushed into its cup: an inner_ring.load "
        "fz along -z large enough for the radial load, or inner_ring.axial_free = false with an axial_position",
        rep.iterations, rep.residual));
  std::vector<double> z = seat.state(u);
  rep.inner_contact_force.assign(static_cast<std::size_t>(m.element_count), 0.0);
  rep.outer_contact_force.assign(static_cast<std::size_t>(m.element_count), 0.0);
  for (const auto& seg : m.segments) {
    if (seg.kind != SegmentKind::roller_inner_slice && seg.kind != SegmentKind::roller_outer_slice) continue;
    const auto c = contact::evaluate(m.law<contact::RollerSliceSegment>(seg), seat.at_rest(seg.body_a, z),
                                     seat.at_rest(seg.body_b, z));
    auto& sum = seg.kind == SegmentKind::roller_inner_slice ? rep.inner_contact_force : rep.outer_contact_force;
    sum[static_cast<std::size_t>(seg.element)] += c.diagnostics.normal_force;
  }
  set_rolling(m, seat, z);
  for (const auto& node : m.nodes) node->initial_state(z);
  rep.state = std::move(z);
  const double q_max = *std::max_element(rep.inner_contact_force.begin(), rep.inner_contact_force.end());
  rep.summary = fmt::format(
      "start-up: quasi-static seating of the tapered rollers in {} iterations (largest unbalanced force {:.3g} N); "
      "largest cone load {:.4g} N; cage at the epicyclic {:.4g} rpm",
      rep.iterations, rep.residual, q_max, seat.orbit * 30.0 / pi);
  return rep;
}

}  // namespace raceway::bearing
