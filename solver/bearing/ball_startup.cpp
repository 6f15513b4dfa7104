#include "solver/bearing/startup.hpp"

#include <fmt/format.h>

#include "solver/bearing/equations.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <limits>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace raceway::bearing {

using contact::Mat3;
using contact::SpatialKinematics;
using contact::Vec3;

namespace {

constexpr double pi = std::numbers::pi;

/// The seating's contact loads evaluated here, one contact after the other (no executor).
void add_groove_loads_at_rest(const Model& m, double t0, const double* z, std::vector<contact::SpatialWrench>& w) {
  for (const auto& seg : m.segments) {
    if (!is_ball_groove(seg)) continue;
    const auto [ring, ball] = groove_kinematics_at_rest(m, seg, t0, z);
    const auto r = contact::evaluate(m.law<contact::BallGrooveSegment>(seg), ring, ball);
    auto& wa = w[static_cast<std::size_t>(seg.body_a)];
    auto& wb = w[static_cast<std::size_t>(seg.body_b)];
    wa.force += r.on_a.force, wa.moment += r.on_a.moment;
    wb.force += r.on_b.force, wb.moment += r.on_b.moment;
  }
}

/// The force balance of the seating problem. Unknowns: the rings' position-type states (x, y, z,
/// tilts) and each ball's radial and axial position in its azimuthal plane.
struct Seating {
  const Model& m;
  double t0;
  double orbit = 0;         ///< epicyclic cage speed [rad/s]
  double force_scale = 1;   ///< N
  // A weak spring on every unknown keeps the problem regular while contacts are open (a ball in
  // its clearance, a ring not yet seated). 1e3 N/m is about 1e-4 of a loaded ball contact's
  // stiffness: it shifts the equilibrium by about 1e-3 N per um of displacement.
  double regularization = 1e3;
  double azimuth_offset = 0;  ///< rad, of ball 0 and the cage
  Equations* equations = nullptr;  ///< given: the contacts are evaluated through its executor

  struct Unknown {
    int body = -1;       ///< ring body, or ball body
    int component = -1;  ///< ring: Coordinate (sx..say); ball: 0 radial, 1 axial
    bool ball = false;
    double scale = 1e-6; ///< m or rad per unit of the scaled unknown
  };
  std::vector<Unknown> unknowns;

  explicit Seating(const Model& model, double t) : m(model), t0(t) {
    orbit = m.epicyclic_cage_speed(t0);
    for (int r : {m.inner_ring, m.outer_ring}) {
      const auto& b = m.bodies[static_cast<std::size_t>(r)];
      for (int c = sx; c <= say; ++c)
        if (b.slot[c] >= 0) unknowns.push_back({r, c, false, c >= sax ? 1e-4 : 1e-6});
    }
    for (int k = 0; k < m.element_count; ++k) {
      unknowns.push_back({m.first_element + k, 0, true, 1e-6});
      unknowns.push_back({m.first_element + k, 1, true, 1e-6});
    }
    double load = 0;
    for (int r : {m.inner_ring, m.outer_ring}) {
      const auto& l = m.bodies[static_cast<std::size_t>(r)].ring->load;
      load = std::max({load, std::abs(l.fx(t0)), std::abs(l.fy(t0)), std::abs(l.fz(t0))});
    }
    force_scale = std::max(load, 1.0);
  }

  double azimuth(int ball) const { return azimuth_offset + 2.0 * pi * ball / m.element_count; }

  /// The state for scaled unknowns u: positions set, velocities zero.
  std::vector<double> state(const Eigen::VectorXd& u) const {
    std::vector<double> z(static_cast<std::size_t>(m.state_size), 0.0);
    std::vector<double> radial(static_cast<std::size_t>(m.element_count), m.pitch_radius),
        axial(static_cast<std::size_t>(m.element_count), 0.0);
    for (std::size_t i = 0; i < unknowns.size(); ++i) {
      const auto& q = unknowns[i];
      const double v = u[static_cast<Eigen::Index>(i)] * q.scale;
      if (!q.ball) {
        z[static_cast<std::size_t>(m.bodies[static_cast<std::size_t>(q.body)].slot[q.component])] = v;
      } else {
        const auto k = static_cast<std::size_t>(q.body - m.first_element);
        (q.component == 0 ? radial[k] : axial[k]) += v;
      }
    }
    for (int k = 0; k < m.element_count; ++k) {
      const auto& b = m.bodies[static_cast<std::size_t>(m.first_element + k)];
      const double psi = azimuth(k);
      const auto kk = static_cast<std::size_t>(k);
      z[static_cast<std::size_t>(b.slot[sx])] = radial[kk] * std::cos(psi);
      z[static_cast<std::size_t>(b.slot[sy])] = radial[kk] * std::sin(psi);
      z[static_cast<std::size_t>(b.slot[sz])] = axial[kk];
    }
    return z;
  }

  /// Contact, load, support and gravity balance; velocity-free (no damping, no traction).
  Eigen::VectorXd residual(const Eigen::VectorXd& u) const {
    const std::vector<double> z = state(u);
    std::vector<contact::SpatialWrench> w(m.bodies.size());
    if (equations)  // the same contacts, the same arithmetic and order, spread over the ranks
      equations->add_groove_loads_at_rest(t0, z.data(), w);
    else
      add_groove_loads_at_rest(m, t0, z.data(), w);
    Eigen::VectorXd res(static_cast<Eigen::Index>(unknowns.size()));
    for (std::size_t i = 0; i < unknowns.size(); ++i) {
      const auto& q = unknowns[i];
      const auto& body = m.bodies[static_cast<std::size_t>(q.body)];
      const double value = u[static_cast<Eigen::Index>(i)] * q.scale;
      double f = 0;
      if (!q.ball) {
        // External wrench at rest: loads, supports (springs), gravity.
        contact::SpatialWrench ext;
        const auto& l = body.ring->load;
        ext.force = Vec3(l.fx(t0), l.fy(t0), l.fz(t0));
        ext.moment = Vec3(l.mx(t0), l.my(t0), 0.0);
        if (body.slot[svy] >= 0) ext.force.y() -= body.mass * m.gravity;
        const auto& s = body.ring->support;
        auto pos = [&](int c) { return body.slot[c] >= 0 ? z[static_cast<std::size_t>(body.slot[c])] : 0.0; };
        ext.force -= Vec3(s.stiffness * pos(sx), s.stiffness * pos(sy), s.axial_stiffness * pos(sz));
        ext.moment -= Vec3(s.tilt_stiffness * pos(sax), s.tilt_stiffness * pos(say), 0.0);
        const auto& cw = w[static_cast<std::size_t>(q.body)];
        const double scale = q.component >= sax ? m.pitch_radius : 1.0;
        f = (q.component >= sax ? cw.moment[q.component - sax] + ext.moment[q.component - sax]
                                : cw.force[q.component] + ext.force[q.component]) / scale;
        f -= regularization * value * (q.component >= sax ? m.pitch_radius : 1.0);
      } else {
        const int k = q.body - m.first_element;
        const double psi = azimuth(k);
        const Vec3 er(std::cos(psi), std::sin(psi), 0.0);
        const Vec3 x(z[static_cast<std::size_t>(body.slot[sx])], z[static_cast<std::size_t>(body.slot[sy])], 0.0);
        Vec3 force = w[static_cast<std::size_t>(q.body)].force;
        force += body.mass * orbit * orbit * x;  // centrifugal, at the epicyclic orbital speed
        force.y() -= body.mass * m.gravity;
        f = q.component == 0 ? force.dot(er) : force.z();
        f -= regularization * value;
      }
      res[static_cast<Eigen::Index>(i)] = f / force_scale;
    }
    return res;
  }
};

/// Contact point and normal (bearing frame) of a ball in a groove arc, from the same geometry as
/// contact::evaluate(BallGrooveSegment).
void groove_contact(const contact::BallGrooveSegment& g, const SpatialKinematics& ring, const Vec3& ball, Vec3& point,
                    Vec3& normal) {
  const Vec3 p = ring.rotation.transpose() * (ball - ring.position);
  const double phi = std::atan2(p.y(), p.x());
  const Vec3 centre(g.centre_radius * std::cos(phi), g.centre_radius * std::sin(phi), g.centre_axial);
  const Vec3 n = (p - centre).normalized();
  point = ring.position + ring.rotation * (centre + g.groove_radius * n);
  normal = ring.rotation * n;
}

/// One stage of the continuation: Levenberg-Marquardt with a forward-difference Jacobian at the
/// seating's current regularization spring. Updates u and its residual r; returns the iterations.
int levenberg_marquardt_stage(const Seating& seat, double tolerance, Eigen::VectorXd& u, Eigen::VectorXd& r) {
  const auto n = u.size();
  r = seat.residual(u);
  double cost = r.squaredNorm();
  double lambda = 1e-3;
  int iterations = 0;
  for (int stage_iterations = 0; stage_iterations < 200 && r.lpNorm<Eigen::Infinity>() > tolerance;
       ++stage_iterations, ++iterations) {
    Eigen::MatrixXd jac(n, n);
    for (Eigen::Index j = 0; j < n; ++j) {
      Eigen::VectorXd up = u;
      const double h = 1e-4;  // 0.1 nm, 1e-8 rad
      up[j] += h;
      jac.col(j) = (seat.residual(up) - r) / h;
    }
    const Eigen::MatrixXd a = jac.transpose() * jac;
    const Eigen::VectorXd g = jac.transpose() * r;
    bool improved = false;
    for (int attempt = 0; attempt < 30 && !improved; ++attempt) {
      Eigen::MatrixXd damped = a;
      // Marquardt's scaling, floored: an unknown whose contacts are all open has a nearly zero
      // diagonal and must still be damped, or its step is the load over the regularization spring.
      const double floor = 1e-4 * a.diagonal().maxCoeff() + 1e-30;
      for (Eigen::Index i = 0; i < n; ++i) damped(i, i) += lambda * std::max(a(i, i), floor);
      Eigen::VectorXd step = damped.ldlt().solve(-g);
      // Trust region: at most 5 um (or 5e-4 rad) per iteration, a fraction of a contact's
      // deflection, so open contacts close gradually instead of the ring jumping through them.
      const double largest = step.lpNorm<Eigen::Infinity>();
      if (largest > 5.0) step *= 5.0 / largest;
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

/// Rolling equations of one ball: one row per loaded contact and tangent direction t,
///   (orbit e_z x x + w x lever - ring surface velocity) . t = 0,
/// in the unknowns (orbit * r_p / R, w): the orbit column is scaled by R / r_p so that both kinds
/// of unknown weigh alike in the singular values. Rows weighted by sqrt(load).
struct Rolling {
  Eigen::MatrixXd a = Eigen::MatrixXd(0, 4);
  Eigen::VectorXd rhs = Eigen::VectorXd(0);
  int contacts = 0;
  double load = 0;
};

Vec3 ball_position(const Model& m, const std::vector<double>& z, int k) {
  const auto& b = m.bodies[static_cast<std::size_t>(m.first_element + k)];
  return Vec3(z[static_cast<std::size_t>(b.slot[sx])], z[static_cast<std::size_t>(b.slot[sy])],
              z[static_cast<std::size_t>(b.slot[sz])]);
}

/// The rolling equations of ball k at the seated state z; adds its groove loads to the report.
Rolling rolling_equations(const Model& m, double t0, const std::vector<double>& z, int k, double orbit_column_scale,
                          StartupReport& rep) {
  Rolling eqs;
  const Vec3 x = ball_position(m, z, k);
  for (const auto& seg : m.segments) {
    if (seg.element != k || (seg.kind != SegmentKind::ball_inner_groove && seg.kind != SegmentKind::ball_outer_groove))
      continue;
    const SpatialKinematics ring = m.kinematics(seg.body_a, t0, z.data());
    const auto& g = m.law<contact::BallGrooveSegment>(seg);
    SpatialKinematics at_rest = ring;
    at_rest.velocity.setZero();
    at_rest.angular_velocity.setZero();
    SpatialKinematics ball_rest;
    ball_rest.position = x;
    const double q = contact::evaluate(g, at_rest, ball_rest).diagnostics.normal_force;
    (seg.kind == SegmentKind::ball_inner_groove ? rep.inner_contact_force : rep.outer_contact_force)
        [static_cast<std::size_t>(k)] += q;
    if (q <= 0) continue;
    ++eqs.contacts, eqs.load += q;
    Vec3 point, normal;
    groove_contact(g, ring, x, point, normal);
    const Vec3 t1 = normal.cross(Vec3::UnitZ()).normalized(), t2 = normal.cross(t1);
    const Vec3 ring_surface = ring.velocity + ring.angular_velocity.cross(point - ring.position);
    const Vec3 lever = point - x, orbit_direction = Vec3::UnitZ().cross(x);
    const double weight = std::sqrt(q);
    for (const Vec3& t : {t1, t2}) {
      eqs.a.conservativeResize(eqs.a.rows() + 1, 4);
      eqs.rhs.conservativeResize(eqs.rhs.size() + 1);
      eqs.a.row(eqs.a.rows() - 1) << weight * orbit_direction.dot(t) * orbit_column_scale,
          weight * lever.cross(t).transpose();  // (w x lever) . t = w . (lever x t)
      eqs.rhs[eqs.rhs.size() - 1] = weight * ring_surface.dot(t);
    }
  }
  return eqs;
}

/// Contacts on (nearly) one line leave the spin about that line (nearly) free: directions the
/// equations fix less than 1e-3 as well as the best one are treated as free (minimum norm),
/// instead of taking huge values from a near-singular fit. Singular values (SVD), not the
/// diagonal of a column-pivoted QR: that rank decision depends on the orientation of the frame.
Eigen::VectorXd least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& rhs) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  svd.setThreshold(1e-3);
  return Eigen::VectorXd(svd.solve(rhs));
}

/// Velocities: rings as prescribed (drive speeds come from the kinematics, not states). Each ball
/// rolls without sliding at its loaded contacts: a ball held between two or more contacts gets its
/// orbital speed and spin from them (at the seated contact angle, not the nominal one, which for a
/// deep groove bearing under axial load is 12 deg off); a ball on one contact (or none) orbits with
/// the cage and spins to roll on that contact. The cage turns at the load-weighted mean orbital
/// speed of the held balls (the epicyclic speed when none is held), its pockets on the balls.
/// Returns the cage speed.
double set_rolling_velocities(const Model& m, double t0, double epicyclic, std::vector<double>& z, StartupReport& rep) {
  const double orbit_column_scale = m.element_radius / m.pitch_radius;
  const auto count = static_cast<std::size_t>(m.element_count);
  std::vector<Rolling> rolling;
  for (int k = 0; k < m.element_count; ++k) rolling.push_back(rolling_equations(m, t0, z, k, orbit_column_scale, rep));
  std::vector<double> orbit(count, epicyclic);
  std::vector<Vec3> spin(count, Vec3::Zero());
  double held_load = 0, held_orbit = 0;
  for (std::size_t k = 0; k < count; ++k) {
    if (rolling[k].contacts < 2) continue;
    const Eigen::VectorXd sol = least_squares(rolling[k].a, rolling[k].rhs);
    orbit[k] = sol[0] * orbit_column_scale;
    spin[k] = sol.tail<3>();
    held_load += rolling[k].load, held_orbit += rolling[k].load * orbit[k];
  }
  const double cage_speed = held_load > 0 ? held_orbit / held_load : epicyclic;
  z[static_cast<std::size_t>(m.bodies[static_cast<std::size_t>(m.cage)].slot[swz])] = cage_speed;
  for (std::size_t k = 0; k < count; ++k) {
    const Rolling& eqs = rolling[k];
    if (eqs.contacts == 1) {
      // Orbit with the cage; spin from the rolling rows with the orbit known.
      orbit[k] = cage_speed;
      const Eigen::VectorXd rhs = eqs.rhs - eqs.a.col(0) * (cage_speed / orbit_column_scale);
      spin[k] = least_squares(eqs.a.rightCols<3>(), rhs);
    } else if (eqs.contacts == 0) {
      orbit[k] = cage_speed;
    }
    const auto& b = m.bodies[static_cast<std::size_t>(m.first_element) + k];
    const Vec3 v = orbit[k] * Vec3::UnitZ().cross(ball_position(m, z, static_cast<int>(k)));
    m.set_velocity(m.first_element + static_cast<int>(k), v, z.data());
    for (int d = 0; d < 3; ++d) z[static_cast<std::size_t>(b.slot[swx + d])] = spin[k][d];
  }
  return cage_speed;
}

/// The cage starts where its pockets hold the balls. Each ball allows the cage's axial position
/// within its pocket's play: |z_k - z_c| <= sqrt((c/2)^2 - r_k^2), r_k the ball's other offset from
/// the pocket centre (radial, spherical pockets; none for cylindrical ones, whose axis is radial).
/// The cage stays at the bearing's mid-plane (z = 0, where its supports hold it) when every ball
/// allows that, and moves only as far as it must otherwise; when no single axial position holds
/// every ball (the ball set tilted, a misaligned ring), the cage takes the plane fitted to the
/// balls' centres: its offset and tilt. Returns the largest pocket force of the start.
double place_cage(const Model& m, std::vector<double>& z) {
  const Body& cage = m.bodies[static_cast<std::size_t>(m.cage)];
  const Segment* pocket_segment = m.first_segment(SegmentKind::ball_pocket);
  if (pocket_segment == nullptr) return 0.0;
  const auto& pocket = m.law<contact::BallPocketSegment>(*pocket_segment);
  const bool spherical = pocket.shape == contact::PocketShape::spherical;
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  Eigen::MatrixXd plane(m.element_count, 3);
  Eigen::VectorXd heights(m.element_count);
  for (int k = 0; k < m.element_count; ++k) {
    const Vec3 x = ball_position(m, z, k);
    const double radial = spherical ? std::hypot(x.x(), x.y()) - m.pitch_radius : 0.0;
    const double play = std::sqrt(std::max(0.0, 0.25 * pocket.clearance * pocket.clearance - radial * radial));
    lo = std::max(lo, x.z() - play), hi = std::min(hi, x.z() + play);
    plane.row(k) << 1.0, x.x(), x.y();
    heights[k] = x.z();
  }
  auto at = [&](Coordinate c) -> double& { return z[static_cast<std::size_t>(cage.slot[c])]; };
  if (lo <= hi) {
    at(sz) = std::clamp(0.0, lo, hi);
  } else {
    const Eigen::Vector3d fit = plane.colPivHouseholderQr().solve(heights);  // z = z0 + a x + b y
    at(sz) = fit[0];
    at(sax) = std::atan(fit[2]);   // pocket heights z0 + r_p (ax sin - ay cos) of its angle
    at(say) = -std::atan(fit[1]);
  }
  double largest = 0;
  for (const Segment& seg : m.segments)
    if (seg.kind == SegmentKind::ball_pocket)
      largest = std::max(largest, contact::evaluate(m.law<contact::BallPocketSegment>(seg),
                                                    m.kinematics(seg.body_a, 0.0, z.data()),
                                                    m.kinematics(seg.body_b, 0.0, z.data()))
                                      .diagnostics.normal_force);
  return largest;
}

}  // namespace

StartupReport seat_ball_bearing(const Model& m, double t0, double azimuth_offset, Equations* equations) {
  Seating seat(m, t0);
  seat.azimuth_offset = azimuth_offset;
  // Through the executor only where contacts are heavy (cut into traction blocks): a light contact
  // (one block, a few us) costs less on rank 0 than a round of messages per residual, and on shared
  // cores each round waits for a descheduled rank.
  seat.equations = equations && equations->has_cut_segments() ? equations : nullptr;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(seat.unknowns.size()));
  Eigen::VectorXd r;
  int iterations = 0;
  // Continuation in the regularization spring: with every contact open, moving the ring and its
  // balls together costs nothing but that spring, so a stiff spring first carries the load until
  // the contacts close; each stage then starts next to its solution.
  for (const double spring : {1e8, 1e7, 1e6, 1e5, 1e4, 1e3}) {
    seat.regularization = spring;
    iterations += levenberg_marquardt_stage(seat, spring > 1e3 ? 1e-6 : 1e-9, u, r);  // relative to the load scale
  }
  StartupReport rep;
  rep.iterations = iterations;
  rep.residual = r.lpNorm<Eigen::Infinity>() * seat.force_scale;
  if (!(rep.residual <= 1e-6 * seat.force_scale + 1e-6))
    throw std::runtime_error(fmt::format(
        "start-up: no quasi-static equilibrium found after {} iterations (largest unbalanced force {:.4g} N); "
        "the keys involved: bearing.radial_clearance ({:.4g} um){}, inner_ring.load, outer_ring.load, the rings' "
        "support, axial and tilt, scene.gravity",
        iterations, rep.residual, 1e6 * m.params().bearing.radial_clearance,
        m.params().bearing.type == scene::BearingType::angular_contact_ball ? " or bearing.contact_angle" : ""));
  std::vector<double> z = seat.state(u);
  z[static_cast<std::size_t>(m.bodies[static_cast<std::size_t>(m.cage)].slot[saz])] = azimuth_offset;
  rep.pocket_force = place_cage(m, z);
  // A disturbed start (cage.initial_offset): the cage centre moved along +x, at rest, clear of its
  // land and pockets (the scene's rules), so the seated balls and their loads are unchanged.
  z[static_cast<std::size_t>(m.bodies[static_cast<std::size_t>(m.cage)].slot[sx])] += m.params().cage.initial_offset;
  rep.inner_contact_force.assign(static_cast<std::size_t>(m.element_count), 0.0);
  rep.outer_contact_force.assign(static_cast<std::size_t>(m.element_count), 0.0);
  const double cage_speed = set_rolling_velocities(m, t0, seat.orbit, z, rep);
  rep.state = std::move(z);
  double q_max = 0;
  for (double q : rep.inner_contact_force) q_max = std::max(q_max, q);
  rep.summary = fmt::format(
      "start-up: quasi-static seating in {} iterations (largest unbalanced force {:.3g} N); largest inner-groove "
      "ball load {:.4g} N; cage at {:.4g} rpm (rolling balls; epicyclic at the nominal contact angle {:.4g} rpm)",
      rep.iterations, rep.residual, q_max, cage_speed * 30.0 / pi, seat.orbit * 30.0 / pi);
  const Body& cage = m.bodies[static_cast<std::size_t>(m.cage)];
  const auto cage_at = [&](Coordinate c) { return rep.state[static_cast<std::size_t>(cage.slot[c])]; };
  if (m.params().cage.initial_offset != 0.0)
    rep.summary += fmt::format("; cage started {:.4g} um off-centre along +x", 1e6 * m.params().cage.initial_offset);
  if (cage_at(sz) != 0.0 || cage_at(sax) != 0.0 || cage_at(say) != 0.0)
    rep.summary += fmt::format("; cage at the balls: {:.4g} mm off the mid-plane, tilted ({:.3g}, {:.3g}) mrad, "
                               "largest pocket force {:.3g} N",
                               1e3 * cage_at(sz), 1e3 * cage_at(sax), 1e3 * cage_at(say), rep.pocket_force);
  return rep;
}

}  // namespace raceway::bearing
