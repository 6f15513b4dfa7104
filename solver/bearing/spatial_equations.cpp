#include "solver/bearing/spatial_equations.hpp"

#include <cmath>

namespace raceway::solver {

using contact::Mat3;
using contact::SpatialKinematics;
using contact::SpatialSegmentResult;
using contact::SpatialWrench;
using contact::Vec3;

namespace {

constexpr int wrench_rows = 12;       // wrench on A (6), on B (6)
constexpr int max_columns = 2 * spatial_components;
constexpr int jacobian_record = SpatialRecord::size + wrench_rows * max_columns;

void write_result(const SpatialSegmentResult& r, std::span<double> rec) {
  for (int i = 0; i < 3; ++i) {
    rec[SpatialRecord::on_a + i] = r.on_a.force[i];
    rec[SpatialRecord::on_a + 3 + i] = r.on_a.moment[i];
    rec[SpatialRecord::on_b + i] = r.on_b.force[i];
    rec[SpatialRecord::on_b + 3 + i] = r.on_b.moment[i];
  }
  const auto& d = r.diagnostics;
  const double diag[contact::point_diagnostics_count] = {
      d.approach,       d.normal_force,   d.contact_angle,         d.max_pressure,   d.film_thickness, d.slip_velocity,
      d.spin_velocity,  d.traction_force, d.circumferential_force, d.elastic_energy, d.power_loss};
  for (int i = 0; i < contact::point_diagnostics_count; ++i) rec[static_cast<std::size_t>(SpatialRecord::diagnostics + i)] = diag[i];
  rec[SpatialRecord::valid] = r.valid ? 1.0 : 0.0;
}

void add_wrench(SpatialWrench& w, const double* rec) {
  for (int i = 0; i < 3; ++i) w.force[i] += rec[i], w.moment[i] += rec[3 + i];
}

/// States of body b in component order (the segment Jacobian's column order).
int body_states(const SpatialBody& b, int out[spatial_components]) {
  int n = 0;
  for (int c = 0; c < spatial_components; ++c)
    if (b.slot[c] >= 0) out[n++] = b.slot[c];
  return n;
}

}  // namespace

SpatialEquations::SpatialEquations(const SpatialModel& model, scheduler::Executor& executor)
    : model_(model),
      executor_(executor),
      contact_(model.bodies.size()),
      net_(model.bodies.size()),
      context_(1 + static_cast<std::size_t>(model.state_size)),
      rhs_task_([this](std::span<const double> ctx, int s, std::span<double> rec) { rhs_task(ctx, s, rec); }),
      jacobian_task_([this](std::span<const double> ctx, int s, std::span<double> rec) { jacobian_task(ctx, s, rec); }) {
  // Segment evaluations of one Jacobian: the base point and one per state of the segment's bodies
  // (counted here, not in the tasks, which may run on other ranks).
  for (const SpatialSegment& seg : model.segments) {
    int states[spatial_components];
    jacobian_segment_evaluations_ += 1 + body_states(model.bodies[static_cast<std::size_t>(seg.body_a)], states) +
                                     body_states(model.bodies[static_cast<std::size_t>(seg.body_b)], states);
  }
  // Finite-difference increments as in the planar model (solver/equations.cpp): positions and
  // angles absolute (rel * 1e-3 * tolerance scale: far below any closed contact's approach, far
  // above round-off), velocities relative with the tolerance scale as a floor.
  const auto atol = model.absolute_tolerance();
  const double rel = model.scene->solver.jacobian_perturbation;
  position_step_.assign(static_cast<std::size_t>(model.state_size), 0.0);
  scale_.resize(static_cast<std::size_t>(model.state_size));
  for (std::size_t i = 0; i < scale_.size(); ++i) {
    scale_[i] = atol[i] / model.scene->solver.rtol;
    const auto c = model.state_class[i];
    if (c == VariableClass::position || c == VariableClass::angle) position_step_[i] = rel * 1e-3 * scale_[i];
  }
}

double SpatialEquations::step_for(int state, const double* z) const {
  const auto i = static_cast<std::size_t>(state);
  if (position_step_[i] > 0) return position_step_[i];
  return model_.scene->solver.jacobian_perturbation * std::max(std::abs(z[state]), scale_[i]);
}

SpatialSegmentResult SpatialEquations::evaluate_segment(int s, const SpatialKinematics& a,
                                                        const SpatialKinematics& b) const {
  const SpatialSegment& seg = model_.segments[static_cast<std::size_t>(s)];
  const auto p = static_cast<std::size_t>(seg.parameters);
  switch (seg.kind) {
    case SpatialSegmentKind::ball_inner_groove:
    case SpatialSegmentKind::ball_outer_groove: return contact::evaluate(model_.groove_segments[p], a, b);
    case SpatialSegmentKind::ball_pocket: return contact::evaluate(model_.pocket_segments[p], a, b);
    case SpatialSegmentKind::cage_land: return contact::evaluate(model_.land_segments[p], a, b);
  }
  return {};
}

SpatialWrench SpatialEquations::external_wrench(int b, double t, const double* z) const {
  const SpatialBody& body = model_.bodies[static_cast<std::size_t>(b)];
  SpatialWrench w;
  auto state = [&](int c) { return body.slot[c] >= 0 ? z[body.slot[c]] : 0.0; };
  if (body.slot[svy] >= 0) w.force.y() -= body.mass * model_.gravity;
  double k_radial = 0, c_radial = 0, k_axial = 0, c_axial = 0, k_tilt = 0, c_tilt = 0;
  if (body.ring) {
    const auto& l = body.ring->load;
    w.force += Vec3(l.fx(t), l.fy(t), l.fz(t));
    w.moment += Vec3(l.mx(t), l.my(t), l.mz(t));
    const auto& s = body.ring->support;
    k_radial = s.stiffness, c_radial = s.damping, k_axial = s.axial_stiffness, c_axial = s.axial_damping;
    k_tilt = s.tilt_stiffness, c_tilt = s.tilt_damping;
  } else if (body.kind == SpatialBodyKind::cage) {
    const auto& s = model_.scene->cage.support;
    k_radial = s.radial_stiffness, c_radial = s.radial_damping, k_axial = s.axial_stiffness, c_axial = s.axial_damping;
    k_tilt = s.tilt_stiffness, c_tilt = s.tilt_damping;
  }
  if (k_radial > 0 || c_radial > 0) {
    w.force.x() -= k_radial * state(sx) + c_radial * state(svx);
    w.force.y() -= k_radial * state(sy) + c_radial * state(svy);
  }
  if (k_axial > 0 || c_axial > 0) w.force.z() -= k_axial * state(sz) + c_axial * state(svz);
  if (k_tilt > 0 || c_tilt > 0) {
    if (body.kind == SpatialBodyKind::cage) {
      // The spindle holds the direction of the cage axis a = R e_z: a spring with the potential
      // k (1 - a.e_z) (= k (1 - cos ax cos ay), k |tilt|^2 / 2 when small) and a damper on the
      // angular velocity across the axis, w - (w.a) a. Both are independent of the cage's turning
      // angle. (A damper on the body-frame rates wx, wy, which turn with the cage, rotates its
      // moment by the cage angle and pumps energy in for half of every cage revolution: the tilt
      // whirl that jammed the balls in 6309 case A12.)
      const Mat3 r = cardan_rotation(state(sax), state(say), state(saz));
      const Vec3 axis = r.col(2);
      const Vec3 w_fixed = r * Vec3(state(swx), state(swy), state(swz));
      w.moment += k_tilt * axis.cross(Vec3::UnitZ()) - c_tilt * (w_fixed - w_fixed.dot(axis) * axis);
    } else {
      // Rings: small-tilt rotor equations in the tilt angles themselves (states swx, swy are their rates).
      w.moment.x() -= k_tilt * state(sax) + c_tilt * state(swx);
      w.moment.y() -= k_tilt * state(say) + c_tilt * state(swy);
    }
  }
  return w;
}

void SpatialEquations::wrench_rates(int b, const double* z, const SpatialWrench& w,
                                    double rates[spatial_components]) const {
  const SpatialBody& body = model_.bodies[static_cast<std::size_t>(b)];
  for (int c = 0; c < spatial_components; ++c) rates[c] = 0;
  for (int d = 0; d < 3; ++d) rates[svx + d] = w.force[d] / body.mass;
  switch (body.kind) {
    case SpatialBodyKind::ball:
      for (int d = 0; d < 3; ++d) rates[swx + d] = w.moment[d] / body.axial_inertia;
      break;
    case SpatialBodyKind::cage: {
      const Mat3 r = cardan_rotation(z[body.slot[sax]], z[body.slot[say]], z[body.slot[saz]]);
      const Vec3 m_body = r.transpose() * w.moment;
      rates[swx] = m_body.x() / body.transverse_inertia;
      rates[swy] = m_body.y() / body.transverse_inertia;
      rates[swz] = m_body.z() / body.axial_inertia;
      break;
    }
    case SpatialBodyKind::inner_ring:
    case SpatialBodyKind::outer_ring:
      rates[swx] = w.moment.x() / body.transverse_inertia;
      rates[swy] = w.moment.y() / body.transverse_inertia;
      rates[swz] = w.moment.z() / body.axial_inertia;
      break;
  }
}

void SpatialEquations::body_rates(int b, double t, const double* z, const SpatialWrench& contacts, double* zdot) const {
  const SpatialBody& body = model_.bodies[static_cast<std::size_t>(b)];
  if (!body.has_states()) return;
  const auto& sl = body.slot;
  SpatialWrench w = external_wrench(b, t, z);
  w.force += contacts.force;
  w.moment += contacts.moment;
  double rates[spatial_components];
  wrench_rates(b, z, w, rates);
  for (int d = 0; d < 3; ++d)
    if (sl[sx + d] >= 0) zdot[sl[sx + d]] = z[sl[svx + d]], zdot[sl[svx + d]] = rates[svx + d];
  switch (body.kind) {
    case SpatialBodyKind::ball:
      for (int d = 0; d < 3; ++d) zdot[sl[swx + d]] = rates[swx + d];
      break;
    case SpatialBodyKind::cage: {
      // Cardan x-y-z angle rates from the body-frame angular velocity, and Euler's equations.
      const Vec3 wb(z[sl[swx]], z[sl[swy]], z[sl[swz]]);
      const Vec3 angle_rates = cardan_rates(z[sl[say]], z[sl[saz]], wb);
      for (int d = 0; d < 3; ++d) zdot[sl[sax + d]] = angle_rates[d];
      const Vec3 inertia(body.transverse_inertia, body.transverse_inertia, body.axial_inertia);
      const Vec3 gyro = wb.cross(inertia.cwiseProduct(wb));
      zdot[sl[swx]] = rates[swx] - gyro.x() / inertia.x();
      zdot[sl[swy]] = rates[swy] - gyro.y() / inertia.y();
      zdot[sl[swz]] = rates[swz] - gyro.z() / inertia.z();
      break;
    }
    case SpatialBodyKind::inner_ring:
    case SpatialBodyKind::outer_ring: {
      const double spin = model_.ring_spin(b, t, z);
      if (sl[sax] >= 0) {
        const double wx = z[sl[swx]], wy = z[sl[swy]];
        const double gyro = body.axial_inertia / body.transverse_inertia * spin;
        zdot[sl[sax]] = wx;
        zdot[sl[say]] = wy;
        zdot[sl[swx]] = rates[swx] - gyro * wy;
        zdot[sl[swy]] = rates[swy] + gyro * wx;
      }
      if (sl[swz] >= 0) zdot[sl[swz]] = rates[swz];
      break;
    }
  }
}

void SpatialEquations::rhs_task(std::span<const double> context, int s, std::span<double> rec) const {
  const double t = context[0];
  const double* z = context.data() + 1;
  const SpatialSegment& seg = model_.segments[static_cast<std::size_t>(s)];
  write_result(evaluate_segment(s, model_.kinematics(seg.body_a, t, z), model_.kinematics(seg.body_b, t, z)), rec);
}

scheduler::TaskCatalogue SpatialEquations::task_catalogue() const {
  scheduler::TaskCatalogue c;
  c.task_count = static_cast<int>(model_.segments.size());
  c.context_size = 1 + model_.state_size;
  for (const SpatialSegment& seg : model_.segments) {
    c.group.push_back(seg.ball >= 0 ? seg.ball : scheduler::border_group);
    c.bodies.push_back({model_.bodies[static_cast<std::size_t>(seg.body_a)].has_states() ? seg.body_a : -1,
                        model_.bodies[static_cast<std::size_t>(seg.body_b)].has_states() ? seg.body_b : -1});
  }
  c.function[static_cast<int>(scheduler::Phase::rhs)] = [this](std::span<const double> ctx, int s, std::span<double> rec) {
    rhs_task(ctx, s, rec);
  };
  c.function[static_cast<int>(scheduler::Phase::jacobian)] =
      [this](std::span<const double> ctx, int s, std::span<double> rec) { jacobian_task(ctx, s, rec); };
  c.record_size[static_cast<int>(scheduler::Phase::rhs)] = SpatialRecord::size;
  c.record_size[static_cast<int>(scheduler::Phase::jacobian)] = jacobian_record;
  return c;
}

int SpatialEquations::rhs(double t, const double* z, double* zdot) {
  ++rhs_count_;
  const int nseg = static_cast<int>(model_.segments.size());
  segment_count_ += nseg;
  context_[0] = t;
  std::copy(z, z + model_.state_size, context_.begin() + 1);
  executor_.run(scheduler::Phase::rhs, context_, nseg, SpatialRecord::size, rhs_task_, records_);
  // Sum in the canonical (segment) order: bitwise identical for any schedule.
  for (auto& w : contact_) w = {};
  int status = 0;
  for (int s = 0; s < nseg; ++s) {
    const double* rec = records_.data() + static_cast<std::size_t>(s) * SpatialRecord::size;
    const SpatialSegment& seg = model_.segments[static_cast<std::size_t>(s)];
    add_wrench(contact_[static_cast<std::size_t>(seg.body_a)], rec + SpatialRecord::on_a);
    add_wrench(contact_[static_cast<std::size_t>(seg.body_b)], rec + SpatialRecord::on_b);
    if (rec[SpatialRecord::valid] == 0.0) {
      status = 1;
      last_invalid_ = s;
    }
  }
  for (std::size_t b = 0; b < model_.bodies.size(); ++b) {
    const int bi = static_cast<int>(b);
    body_rates(bi, t, z, contact_[b], zdot);
    const SpatialWrench ext = external_wrench(bi, t, z);
    net_[b].force = contact_[b].force + ext.force;
    net_[b].moment = contact_[b].moment + ext.moment;
  }
  return status;
}

void SpatialEquations::jacobian_task(std::span<const double> context, int s, std::span<double> rec) const {
  const double t = context[0];
  const double* z = context.data() + 1;
  const std::size_t n = static_cast<std::size_t>(model_.state_size);
  const SpatialSegment& seg = model_.segments[static_cast<std::size_t>(s)];
  const SpatialKinematics ka = model_.kinematics(seg.body_a, t, z);
  const SpatialKinematics kb = model_.kinematics(seg.body_b, t, z);
  const SpatialSegmentResult base = evaluate_segment(s, ka, kb);
  bool ok = base.valid;
  std::vector<double> zp(z, z + n);
  int column = 0;
  for (int side = 0; side < 2; ++side) {
    const int b = side == 0 ? seg.body_a : seg.body_b;
    int states[spatial_components];
    const int count = body_states(model_.bodies[static_cast<std::size_t>(b)], states);
    for (int k = 0; k < count; ++k, ++column) {
      const int j = states[k];
      const double h = step_for(j, z);
      zp[static_cast<std::size_t>(j)] = z[j] + h;
      const SpatialKinematics kp = model_.kinematics(b, t, zp.data());
      const SpatialSegmentResult r = side == 0 ? evaluate_segment(s, kp, kb) : evaluate_segment(s, ka, kp);
      zp[static_cast<std::size_t>(j)] = z[j];
      ok = ok && r.valid;
      double* out = rec.data() + SpatialRecord::size + wrench_rows * column;
      const double inv = 1.0 / h;
      for (int i = 0; i < 3; ++i) {
        out[i] = (r.on_a.force[i] - base.on_a.force[i]) * inv;
        out[3 + i] = (r.on_a.moment[i] - base.on_a.moment[i]) * inv;
        out[6 + i] = (r.on_b.force[i] - base.on_b.force[i]) * inv;
        out[9 + i] = (r.on_b.moment[i] - base.on_b.moment[i]) * inv;
      }
    }
  }
  write_result(base, rec);
  rec[SpatialRecord::valid] = ok ? 1.0 : 0.0;
}

int SpatialEquations::jacobian(double t, const double* z, BorderedMatrix& jac) {
  ++jac_count_;
  const int nseg = static_cast<int>(model_.segments.size());
  const std::size_t n = static_cast<std::size_t>(model_.state_size);
  segment_count_ += jacobian_segment_evaluations_;
  context_[0] = t;
  std::copy(z, z + model_.state_size, context_.begin() + 1);
  executor_.run(scheduler::Phase::jacobian, context_, nseg, jacobian_record, jacobian_task_, jac_records_);
  jac.set_zero();
  int status = 0;
  std::vector<SpatialWrench> contacts(model_.bodies.size());
  for (int s = 0; s < nseg; ++s) {
    const double* rec = jac_records_.data() + static_cast<std::size_t>(s) * jacobian_record;
    const SpatialSegment& seg = model_.segments[static_cast<std::size_t>(s)];
    if (rec[SpatialRecord::valid] == 0.0) {
      status = 1;
      last_invalid_ = s;
    }
    add_wrench(contacts[static_cast<std::size_t>(seg.body_a)], rec + SpatialRecord::on_a);
    add_wrench(contacts[static_cast<std::size_t>(seg.body_b)], rec + SpatialRecord::on_b);
    const SpatialBody* bodies[2] = {&model_.bodies[static_cast<std::size_t>(seg.body_a)],
                                    &model_.bodies[static_cast<std::size_t>(seg.body_b)]};
    const int body_index[2] = {seg.body_a, seg.body_b};
    int column = 0;
    for (int side = 0; side < 2; ++side) {
      int states[spatial_components];
      const int count = body_states(*bodies[side], states);
      for (int k = 0; k < count; ++k, ++column) {
        const double* d = rec + SpatialRecord::size + wrench_rows * column;
        for (int target = 0; target < 2; ++target) {
          const SpatialBody& rb = *bodies[target];
          if (!rb.has_states()) continue;
          SpatialWrench dw;
          for (int i = 0; i < 3; ++i) dw.force[i] = d[6 * target + i], dw.moment[i] = d[6 * target + 3 + i];
          double rates[spatial_components];
          wrench_rates(body_index[target], z, dw, rates);
          for (int c = svx; c < spatial_components; ++c)
            if (rb.slot[c] >= 0 && rates[c] != 0.0) jac.add(rb.slot[c], states[k], rates[c]);
        }
      }
    }
  }
  // Each body's own terms: kinematic rows, gyroscopic terms, supports, the rotation of the cage's
  // contact moment into its frame: finite differences of body_rates with its contact wrench frozen.
  std::vector<double> zp(z, z + n), f0(n), f1(n);
  for (std::size_t b = 0; b < model_.bodies.size(); ++b) {
    const SpatialBody& body = model_.bodies[b];
    if (!body.has_states()) continue;
    const int bi = static_cast<int>(b);
    body_rates(bi, t, z, contacts[b], f0.data());
    int states[spatial_components];
    const int count = body_states(body, states);
    for (int k = 0; k < count; ++k) {
      const int j = states[k];
      const double h = step_for(j, z);
      zp[static_cast<std::size_t>(j)] = z[j] + h;
      body_rates(bi, t, zp.data(), contacts[b], f1.data());
      zp[static_cast<std::size_t>(j)] = z[j];
      for (int i = 0; i < count; ++i) {
        const auto row = static_cast<std::size_t>(states[i]);
        const double v = (f1[row] - f0[row]) / h;
        if (v != 0.0) jac.add(states[i], j, v);
      }
    }
  }
  return status;
}

double SpatialEquations::energy(double t, const double* z) const {
  double e = 0;
  for (std::size_t b = 0; b < model_.bodies.size(); ++b) {
    const SpatialBody& body = model_.bodies[b];
    const auto& sl = body.slot;
    auto state = [&](int c) { return sl[c] >= 0 ? z[sl[c]] : 0.0; };
    const Vec3 x(state(sx), state(sy), state(sz)), v(state(svx), state(svy), state(svz));
    e += 0.5 * body.mass * v.squaredNorm();
    if (sl[svy] >= 0) e += body.mass * model_.gravity * x.y();
    if (body.kind == SpatialBodyKind::ball) {
      e += 0.5 * body.axial_inertia * Vec3(state(swx), state(swy), state(swz)).squaredNorm();
    } else {
      e += 0.5 * body.transverse_inertia * (state(swx) * state(swx) + state(swy) * state(swy));
      e += 0.5 * body.axial_inertia * state(swz) * state(swz);
    }
    double k_radial = 0, k_axial = 0, k_tilt = 0;
    if (body.ring) {
      const auto& l = body.ring->load;
      e -= l.fx(t) * x.x() + l.fy(t) * x.y() + l.fz(t) * x.z() + l.mx(t) * state(sax) + l.my(t) * state(say);
      k_radial = body.ring->support.stiffness, k_axial = body.ring->support.axial_stiffness;
      k_tilt = body.ring->support.tilt_stiffness;
    } else if (body.kind == SpatialBodyKind::cage) {
      const auto& s = model_.scene->cage.support;
      k_radial = s.radial_stiffness, k_axial = s.axial_stiffness, k_tilt = s.tilt_stiffness;
    }
    e += 0.5 * k_radial * (x.x() * x.x() + x.y() * x.y()) + 0.5 * k_axial * x.z() * x.z();
    if (body.kind == SpatialBodyKind::cage)
      e += k_tilt * (1.0 - std::cos(state(sax)) * std::cos(state(say)));  // see external_wrench
    else
      e += 0.5 * k_tilt * (state(sax) * state(sax) + state(say) * state(say));
  }
  for (std::size_t s = 0; s < model_.segments.size(); ++s)
    e += records_[s * SpatialRecord::size + SpatialRecord::diagnostics + 9];
  return e;
}

std::string SpatialEquations::explain_state(int index) const {
  return explain_model_state(model_, index, records_, SpatialRecord::size, SpatialRecord::diagnostics, last_invalid_);
}

}  // namespace raceway::solver
