#include "solver/bearing/equations.hpp"

#include <fmt/format.h>

#include <cmath>
#include <type_traits>

#include "solver/bearing/ring_modes.hpp"

namespace raceway::solver {

std::unique_ptr<BodyDynamics> make_planar_dynamics(const Model& model);
std::unique_ptr<BodyDynamics> make_spatial_dynamics(const Model& model);
int segment_part_count(const SegmentLaw& law);  // segment_parts.cpp

std::unique_ptr<BodyDynamics> make_body_dynamics(const Model& model) {
  return model.kind == io::ModelKind::spatial ? make_spatial_dynamics(model) : make_planar_dynamics(model);
}

FiniteDifferenceSteps::FiniteDifferenceSteps(const Model& model)
    : relative_(model.scene->solver.jacobian_perturbation),
      scale_(static_cast<std::size_t>(model.state_size)),
      position_step_(static_cast<std::size_t>(model.state_size), 0.0) {
  // The class scales, not the bridges' tighter bending tolerances: a bridge's kinematics add its
  // bending angle to the cage's, so a smaller step would drown in the sum's round-off.
  const auto atol = physical_absolute_tolerance(*model.scene, model.state_class, model.pitch_radius,
                                                model.element_radius);
  for (std::size_t i = 0; i < scale_.size(); ++i) {
    scale_[i] = atol[i] / model.scene->solver.rtol;
    const auto c = model.state_class[i];
    if (c == VariableClass::position || c == VariableClass::angle) position_step_[i] = relative_ * 1e-3 * scale_[i];
  }
}

double FiniteDifferenceSteps::operator()(int state, const double* z) const {
  const auto i = static_cast<std::size_t>(state);
  if (position_step_[i] > 0) return position_step_[i];
  return relative_ * std::max(std::abs(z[state]), scale_[i]);
}

namespace {

/// Laws of the line-contact family take planar kinematics; the point-contact family spatial ones.
template <class Law>
constexpr bool line_family = std::is_same_v<Law, contact::RollerRaceSegment> ||
                             std::is_same_v<Law, contact::CageBarSegment> ||
                             std::is_same_v<Law, contact::CageLandSegment> ||
                             std::is_same_v<Law, contact::CageBridgeSegment> ||
                             std::is_same_v<Law, contact::RingModeSegment>;

template <class Law>
auto kinematics_for(const Model& m, int b, double t, const double* z) {
  if constexpr (line_family<Law>)
    return m.planar_kinematics(b, t, z);
  else
    return m.kinematics(b, t, z);
}

template <class Law>
int elastic_energy_field() {
  if constexpr (line_family<Law>)
    return contact::field_index(contact::line_diagnostic_fields, "elastic_energy");
  else
    return contact::field_index(contact::point_diagnostic_fields, "elastic_energy");
}

int state_count(const Body& b) {
  int n = 0;
  for (int c = 0; c < coordinate_count; ++c) n += b.slot[c] >= 0;
  return n;
}

/// The record of one segment's Jacobian task: its result at (t, z), then one column of wrench
/// differences per state of body A, then of body B (in coordinate order), by forward differences.
template <class Law>
void segment_jacobian_record(const Model& m, const FiniteDifferenceSteps& step, const Law& law, const Segment& seg,
                             double t, const double* z, std::span<double> rec) {
  const auto ka = kinematics_for<Law>(m, seg.body_a, t, z);
  const auto kb = kinematics_for<Law>(m, seg.body_b, t, z);
  const auto base = contact::evaluate(law, ka, kb);
  bool ok = base.valid;
  std::vector<double> zp(z, z + m.state_size);
  const std::vector<SegmentColumn> columns = segment_columns(m, seg);
  for (std::size_t column = 0; column < columns.size(); ++column) {
    const SegmentColumn& c = columns[column];
    const auto j = static_cast<std::size_t>(c.state);
    const double h = step(c.state, z);
    zp[j] = z[j] + h;
    const auto kp = kinematics_for<Law>(m, c.body, t, zp.data());
    const auto r = c.on_a ? contact::evaluate(law, kp, kb) : contact::evaluate(law, ka, kp);
    zp[j] = z[j];
    ok = ok && r.valid;
    write_difference(r, base, 1.0 / h, rec.data() + SegmentRecord::size + SegmentRecord::wrench_rows * column);
  }
  // The columns of states it does not depend on: zero (a task writes its whole record).
  std::fill(rec.begin() + SegmentRecord::size + SegmentRecord::wrench_rows * static_cast<std::ptrdiff_t>(columns.size()),
            rec.end(), 0.0);
  write_result(base, rec);
  rec[SegmentRecord::valid] = ok ? 1.0 : 0.0;
}

/// Adds a segment's wrench on body b to the sums; a body riding on a carrier (a flexible cage
/// bridge) passes the force on to it (both share one centre, so no moment goes with it).
void add_body_wrench(const Model& m, std::vector<Wrench>& sums, int b, const double* rec) {
  add_wrench(sums[static_cast<std::size_t>(b)], rec);
  const int carrier = m.bodies[static_cast<std::size_t>(b)].carrier;
  if (carrier >= 0)
    for (int i = 0; i < 3; ++i) sums[static_cast<std::size_t>(carrier)].force[i] += rec[i];
}

}  // namespace

Equations::Equations(const Model& model, scheduler::Executor& executor)
    : model_(model),
      executor_(executor),
      dynamics_(make_body_dynamics(model)),
      step_(model),
      contact_(model.bodies.size()),
      net_(model.bodies.size()),
      context_(2 + static_cast<std::size_t>(model.state_size), 0.0),
      rhs_task_([this](std::span<const double> ctx, int s, std::span<double> rec) { rhs_task(ctx, s, rec); }),
      jacobian_task_([this](std::span<const double> ctx, int s, std::span<double> rec) { jacobian_task(ctx, s, rec); }) {
  // Counted here, not in the tasks, which may run on other ranks.
  for (const Segment& seg : model.segments) {
    jacobian_segment_evaluations_ += 1 + state_count(model.bodies[static_cast<std::size_t>(seg.body_a)]) +
                                     state_count(model.bodies[static_cast<std::size_t>(seg.body_b)]) +
                                     (on_rim(model, seg) ? rim_shift_columns : 0);
    elastic_energy_field_.push_back(std::visit(
        [](const auto& law) { return elastic_energy_field<std::decay_t<decltype(law)>>(); },
        model.laws[static_cast<std::size_t>(seg.law)]));
    const int parts = segment_part_count(model.laws[static_cast<std::size_t>(seg.law)]);
    first_task_.push_back(static_cast<int>(task_segment_.size()));
    parts_.push_back(parts);
    task_segment_.insert(task_segment_.end(), static_cast<std::size_t>(parts), static_cast<int>(parts_.size() - 1));
    cut_ = cut_ || parts > 1;
  }
}

void Equations::rhs_task(std::span<const double> context, int task, std::span<double> rec) const {
  const int s = task_segment_[static_cast<std::size_t>(task)];
  if (parts_[static_cast<std::size_t>(s)] > 1)
    return rhs_part(context.data(), s, task - first_task_[static_cast<std::size_t>(s)], rec);
  const double t = context[0];
  const double* z = context.data() + 1;
  if (context.back() != 0.0) return rest_task(s, t, z, rec);
  const Segment& seg = model_.segments[static_cast<std::size_t>(s)];
  if (on_rim(model_, seg))
    return write_result(evaluate_on_rim(model_.law<contact::RollerRaceSegment>(seg), model_, seg, t, z), rec);
  std::visit(
      [&](const auto& law) {
        using Law = std::decay_t<decltype(law)>;
        write_result(contact::evaluate(law, kinematics_for<Law>(model_, seg.body_a, t, z),
                                       kinematics_for<Law>(model_, seg.body_b, t, z)),
                     rec);
      },
      model_.laws[static_cast<std::size_t>(seg.law)]);
}

std::pair<contact::SpatialKinematics, contact::SpatialKinematics> groove_kinematics_at_rest(const Model& m,
                                                                                           const Segment& seg,
                                                                                           double t, const double* z) {
  contact::SpatialKinematics ring = m.kinematics(seg.body_a, t, z);
  ring.velocity.setZero();
  ring.angular_velocity.setZero();
  return {ring, m.kinematics(seg.body_b, t, z)};
}

void Equations::rest_task(int s, double t, const double* z, std::span<double> rec) const {
  const Segment& seg = model_.segments[static_cast<std::size_t>(s)];
  if (!is_ball_groove(seg)) {  // not part of the seating's balance
    std::fill(rec.begin(), rec.end(), 0.0);
    rec[SegmentRecord::valid] = 1.0;
    return;
  }
  const auto [ring, ball] = groove_kinematics_at_rest(model_, seg, t, z);
  write_result(contact::evaluate(model_.law<contact::BallGrooveSegment>(seg), ring, ball), rec);
}

void Equations::add_groove_loads_at_rest(double t, const double* z, std::vector<contact::SpatialWrench>& sums) {
  context_[0] = t;
  std::copy(z, z + model_.state_size, context_.begin() + 1);
  context_.back() = 1.0;
  const int ntask = static_cast<int>(task_segment_.size());
  executor_.run(scheduler::Phase::rhs, context_, ntask, SegmentRecord::size, rhs_task_,
                cut_ ? task_records_ : rest_records_);
  context_.back() = 0.0;
  if (cut_) combine_rhs_parts(rest_records_);
  for (std::size_t s = 0; s < model_.segments.size(); ++s) {
    const Segment& seg = model_.segments[s];
    if (!is_ball_groove(seg)) continue;
    const double* rec = rest_records_.data() + s * SegmentRecord::size;
    add_wrench(sums[static_cast<std::size_t>(seg.body_a)], rec + SegmentRecord::on_a);
    add_wrench(sums[static_cast<std::size_t>(seg.body_b)], rec + SegmentRecord::on_b);
  }
}

void Equations::jacobian_task(std::span<const double> context, int task, std::span<double> rec) const {
  const int s = task_segment_[static_cast<std::size_t>(task)];
  if (parts_[static_cast<std::size_t>(s)] > 1)
    return jacobian_part(context.data(), s, task - first_task_[static_cast<std::size_t>(s)], rec);
  const Segment& seg = model_.segments[static_cast<std::size_t>(s)];
  if (on_rim(model_, seg))
    return rim_jacobian_record(model_.law<contact::RollerRaceSegment>(seg), model_, step_, seg, context[0],
                               context.data() + 1, rec);
  std::visit([&](const auto& law) { segment_jacobian_record(model_, step_, law, seg, context[0], context.data() + 1, rec); },
             model_.laws[static_cast<std::size_t>(seg.law)]);
}

scheduler::TaskCatalogue Equations::task_catalogue() const {
  scheduler::TaskCatalogue c;
  c.task_count = static_cast<int>(task_segment_.size());
  c.context_size = 2 + model_.state_size;
  for (int s : task_segment_) {
    const Segment& seg = model_.segments[static_cast<std::size_t>(s)];
    c.group.push_back(seg.element >= 0 ? seg.element : scheduler::border_group);
    c.bodies.push_back({model_.bodies[static_cast<std::size_t>(seg.body_a)].has_states() ? seg.body_a : -1,
                        model_.bodies[static_cast<std::size_t>(seg.body_b)].has_states() ? seg.body_b : -1});
  }
  c.parent = task_segment_;
  c.function[static_cast<int>(scheduler::Phase::rhs)] = rhs_task_;
  c.function[static_cast<int>(scheduler::Phase::jacobian)] = jacobian_task_;
  c.record_size[static_cast<int>(scheduler::Phase::rhs)] = SegmentRecord::size;
  c.record_size[static_cast<int>(scheduler::Phase::jacobian)] = jacobian_record;
  // What each task's record carries between ranks: a cut segment's parts their share, an uncut
  // segment its whole record (in the Jacobian: its result and one column per state it depends on).
  for (std::size_t t = 0; t < task_segment_.size(); ++t) {
    const int s = task_segment_[t];
    const Segment& seg = model_.segments[static_cast<std::size_t>(s)];
    for (const auto phase : {scheduler::Phase::rhs, scheduler::Phase::jacobian}) {
      int used = SegmentRecord::size;
      if (parts_[static_cast<std::size_t>(s)] > 1)
        used = segment_part_record_size(phase, s, static_cast<int>(t) - first_task_[static_cast<std::size_t>(s)]);
      else if (phase == scheduler::Phase::jacobian)
        used += SegmentRecord::wrench_rows * (static_cast<int>(segment_columns(model_, seg).size()) +
                                              (on_rim(model_, seg) ? rim_shift_columns : 0));
      c.used_size[static_cast<std::size_t>(phase)].push_back(used);
    }
  }
  return c;
}

int Equations::rhs(double t, const double* z, double* zdot) {
  ++rhs_count_;
  rhs_time_ = t;
  const int nseg = static_cast<int>(model_.segments.size());
  segment_count_ += nseg;
  context_[0] = t;
  std::copy(z, z + model_.state_size, context_.begin() + 1);
  const int ntask = static_cast<int>(task_segment_.size());
  executor_.run(scheduler::Phase::rhs, context_, ntask, SegmentRecord::size, rhs_task_, cut_ ? task_records_ : records_);
  if (cut_) combine_rhs_parts(records_);
  // Sum in the canonical (segment) order: bitwise identical for any schedule.
  for (auto& w : contact_) w = {};
  int status = 0;
  for (int s = 0; s < nseg; ++s) {
    const double* rec = records_.data() + static_cast<std::size_t>(s) * SegmentRecord::size;
    const Segment& seg = model_.segments[static_cast<std::size_t>(s)];
    add_body_wrench(model_, contact_, seg.body_a, rec + SegmentRecord::on_a);
    add_body_wrench(model_, contact_, seg.body_b, rec + SegmentRecord::on_b);
    if (on_rim(model_, seg)) add_rim_forces(seg, t, z, rec, contact_);
    if (rec[SegmentRecord::valid] == 0.0) {
      status = 1;
      last_invalid_ = s;
    }
  }
  for (std::size_t b = 0; b < model_.bodies.size(); ++b)
    dynamics_->rates(static_cast<int>(b), t, z, contact_[b], net_[b], zdot);
  return status;
}

void Equations::add_rate_derivative(int b, int state, const double* z, const Wrench& dw, BorderedMatrix& jac) const {
  const Body& body = model_.bodies[static_cast<std::size_t>(b)];
  double rates[coordinate_count];
  dynamics_->contact_rate_derivative(b, z, dw, rates);
  for (int c = svx; c < coordinate_count; ++c)
    if (body.slot[c] >= 0 && rates[c] != 0.0) jac.add(body.slot[c], state, rates[c]);
  if (rates[swz] != 0.0)  // a rider's angle is relative: its acceleration less its carrier's
    for (int r : body.riders) jac.add(model_.bodies[static_cast<std::size_t>(r)].slot[swz], state, -rates[swz]);
}

void Equations::add_segment_jacobian(int s, const double* rec, const double* z, BorderedMatrix& jac) const {
  const Segment& seg = model_.segments[static_cast<std::size_t>(s)];
  const int body_index[2] = {seg.body_a, seg.body_b};
  const Body* bodies[2] = {&model_.bodies[static_cast<std::size_t>(seg.body_a)],
                           &model_.bodies[static_cast<std::size_t>(seg.body_b)]};
  const std::vector<SegmentColumn> columns = segment_columns(model_, seg);
  for (std::size_t column = 0; column < columns.size(); ++column) {
    const SegmentColumn& c = columns[column];
    const int k = c.coordinate;
    const double* d = rec + SegmentRecord::size + SegmentRecord::wrench_rows * column;
    // A rider's kinematics hold its carrier's angle plus its own: the column counts for both.
    const int carrier = model_.bodies[static_cast<std::size_t>(c.body)].carrier;
    const bool relative = carrier >= 0 && (k == saz || k == swz);
    for (const int state : {c.state, relative ? model_.bodies[static_cast<std::size_t>(carrier)].slot[k] : -1}) {
      if (state < 0) continue;
      for (int target = 0; target < 2; ++target) {
        const Body& rb = *bodies[target];
        if (!rb.has_states()) continue;
        Wrench dw;
        for (int i = 0; i < 3; ++i) dw.force[i] = d[6 * target + i], dw.moment[i] = d[6 * target + 3 + i];
        add_rate_derivative(body_index[target], state, z, dw, jac);
        if (rb.carrier >= 0) {  // the force on a bridge moves its carrier (add_body_wrench)
          dw.moment = contact::Vec3::Zero();
          add_rate_derivative(rb.carrier, state, z, dw, jac);
        }
      }
    }
  }
}

void Equations::add_rim_forces(const Segment& seg, double t, const double* z, const double* rec,
                               std::vector<Wrench>& sums) const {
  const RimPoint p = rim_point(model_, model_.planar_kinematics(seg.body_a, t, z),
                               model_.planar_kinematics(seg.body_b, t, z), z);
  add_modal_forces(model_, p, rec + SegmentRecord::on_a, sums);
}

// A rim contact (ring_modes.hpp): its force on the ring drives the modes through Q = f . phi_n(theta),
// theta the contact's azimuth. Rows of the modes: dQ/dz = (df/dz) . phi_n + f . phi_n'(theta) dtheta/dz,
// with phi_a' = -(n - 1/n) sin(n theta) e_r and phi_b' = (n - 1/n) cos(n theta) e_r (e_r' = e_t,
// e_t' = -e_r). Columns of the modes: the contact depends on them through the rim's displacement
// u = sum phi_n a_n at the contact, so d(wrench)/d a_n = d(wrench)/d u . phi_n from the record's
// shift columns, for the ring's, the roller's and the modes' own rows.
void Equations::add_rim_jacobian(const Segment& seg, const double* rec, double t, const double* z,
                                 BorderedMatrix& jac) const {
  const Model& m = model_;
  const RimPoint p = rim_point(m, m.planar_kinematics(seg.body_a, t, z), m.planar_kinematics(seg.body_b, t, z), z);
  const double co = p.cos_theta, si = p.sin_theta;
  const ModeShapes shape(co, si, m.ring_mode_count + 1);
  const double radial = rec[SegmentRecord::on_a] * co + rec[SegmentRecord::on_a + 1] * si;
  // The modes' rows from a column: d (force on the ring) and d theta.
  auto add_mode_rows = [&](int state, const double* d, double dtheta) {
    const double dr = d[0] * co + d[1] * si, dt = -d[0] * si + d[1] * co;
    for (int k = 0; k < m.ring_mode_count; ++k) {
      const int n = k + 2;
      const double c = shape.c[n], s = shape.s[n], inv_n = 1.0 / n, turn = (n - inv_n) * radial * dtheta;
      Wrench dq;
      dq.force.x() = dr * c - dt * s * inv_n - turn * s;
      dq.force.y() = dr * s + dt * c * inv_n + turn * c;
      add_rate_derivative(m.first_ring_mode + k, state, z, dq, jac);
    }
  };
  const std::vector<SegmentColumn> columns = segment_columns(m, seg);
  for (std::size_t i = 0; i < columns.size(); ++i) {
    const SegmentColumn& c = columns[i];
    const double side = c.on_a ? -1.0 : 1.0;  // theta is the roller's azimuth about the ring's centre
    const double dtheta = c.coordinate == sx ? -side * si / p.distance : c.coordinate == sy ? side * co / p.distance : 0.0;
    add_mode_rows(c.state, rec + SegmentRecord::size + SegmentRecord::wrench_rows * i, dtheta);
  }
  const double* shift = rec + SegmentRecord::size + SegmentRecord::wrench_rows * columns.size();
  for (int k = 0; k < m.ring_mode_count; ++k) {
    const Body& mode = m.bodies[static_cast<std::size_t>(m.first_ring_mode + k)];
    const int n = k + 2;
    const double c = shape.c[n], s = shape.s[n], inv_n = 1.0 / n;
    // phi_a = c e_r - (s / n) e_t, phi_b = s e_r + (c / n) e_t, as x, y components.
    const double phi[2][2] = {{c * co + s * inv_n * si, c * si - s * inv_n * co},
                              {s * co - c * inv_n * si, s * si + c * inv_n * co}};
    for (const auto& [state, shape_index, rate] : {std::tuple{mode.slot[sx], 0, 0}, std::tuple{mode.slot[sy], 1, 0},
                                                   std::tuple{mode.slot[svx], 0, 1}, std::tuple{mode.slot[svy], 1, 1}}) {
      double d[SegmentRecord::wrench_rows];
      const double* dx = shift + SegmentRecord::wrench_rows * (2 * rate);
      const double* dy = dx + SegmentRecord::wrench_rows;
      for (int r = 0; r < SegmentRecord::wrench_rows; ++r) d[r] = dx[r] * phi[shape_index][0] + dy[r] * phi[shape_index][1];
      for (int target = 0; target < 2; ++target) {
        const int b = target == 0 ? seg.body_a : seg.body_b;
        if (!m.bodies[static_cast<std::size_t>(b)].has_states()) continue;
        Wrench dw;
        for (int i = 0; i < 3; ++i) dw.force[i] = d[6 * target + i], dw.moment[i] = d[6 * target + 3 + i];
        add_rate_derivative(b, state, z, dw, jac);
      }
      add_mode_rows(state, d, 0.0);
    }
  }
}

int Equations::jacobian(double t, const double* z, BorderedMatrix& jac) {
  ++jac_count_;
  const int nseg = static_cast<int>(model_.segments.size());
  segment_count_ += jacobian_segment_evaluations_;
  context_[0] = t;
  std::copy(z, z + model_.state_size, context_.begin() + 1);
  const int ntask = static_cast<int>(task_segment_.size());
  executor_.run(scheduler::Phase::jacobian, context_, ntask, jacobian_record, jacobian_task_,
                cut_ ? jac_task_records_ : jac_records_);
  if (cut_) combine_jacobian_parts(z);
  jac.set_zero();
  int status = 0;
  std::vector<Wrench> contacts(model_.bodies.size());
  for (int s = 0; s < nseg; ++s) {
    const double* rec = jac_records_.data() + static_cast<std::size_t>(s) * jacobian_record;
    const Segment& seg = model_.segments[static_cast<std::size_t>(s)];
    if (rec[SegmentRecord::valid] == 0.0) {
      status = 1;
      last_invalid_ = s;
    }
    add_body_wrench(model_, contacts, seg.body_a, rec + SegmentRecord::on_a);
    add_body_wrench(model_, contacts, seg.body_b, rec + SegmentRecord::on_b);
    add_segment_jacobian(s, rec, z, jac);
    if (on_rim(model_, seg)) {
      add_rim_forces(seg, t, z, rec, contacts);
      add_rim_jacobian(seg, rec, t, z, jac);
    }
  }
  dynamics_->add_body_jacobian(t, z, contacts, step_, jac);
  return status;
}

double Equations::energy(double t, const double* z) const {
  double e = dynamics_->body_energy(t, z);
  for (std::size_t s = 0; s < model_.segments.size(); ++s) e += diagnostic(s, elastic_energy_field_[s]);
  return e;
}

std::string Equations::explain_state(int index) const {
  const Model& m = model_;
  std::string out = m.state_name[static_cast<std::size_t>(index)];
  int body = -1;
  for (std::size_t b = 0; b < m.bodies.size(); ++b)
    if (index >= m.bodies[b].offset && index < m.bodies[b].offset + m.bodies[b].size) body = static_cast<int>(b);
  std::size_t best = m.segments.size();
  double best_force = -1;
  for (std::size_t s = 0; s < m.segments.size() && !records_.empty(); ++s) {
    const auto& seg = m.segments[s];
    if (seg.body_a != body && seg.body_b != body) continue;
    const double f = diagnostic(s, normal_force_field);
    if (f > best_force) best_force = f, best = s;
  }
  if (best < m.segments.size())
    out += fmt::format("; most loaded contact of that body: {} ({:.4g} N, approach {:.4g} um)", m.segments[best].name,
                       best_force, 1e6 * diagnostic(best, approach_field));
  if (last_invalid_ >= 0)
    out += fmt::format("; contact that last left its valid range: {}",
                       m.segments[static_cast<std::size_t>(last_invalid_)].name);
  return out;
}

}  // namespace raceway::solver
