#include "solver/bearing/equations.hpp"

#include <cmath>

#include "contact/segments/segment_jacobian.hpp"

namespace raceway::solver {

using contact::Component;
using contact::PlanarKinematics;
using contact::SegmentResult;

namespace {
constexpr int jacobian_entries = 6 * 12;
constexpr int jacobian_record = SegmentRecord::size + jacobian_entries;
}  // namespace

Equations::Equations(const Model& model, scheduler::Executor& executor)
    : model_(model),
      executor_(executor),
      loads_(model.bodies.size()),
      context_(1 + static_cast<std::size_t>(model.state_size)),
      rhs_task_([this](std::span<const double> ctx, int s, std::span<double> rec) { rhs_task(ctx, s, rec); }),
      jacobian_task_([this](std::span<const double> ctx, int s, std::span<double> rec) { jacobian_task(ctx, s, rec); }) {
  // Finite-difference increments per state. Positions and angles: a contact sees differences of
  // positions, not their size, and its approach may be a few nm (an outer contact carrying only the
  // centrifugal force), so the step is absolute: rel * 1e-3 * the tolerance scale (2.3e-12 m for a
  // 22.9 mm pitch radius at rel = 1e-7), far below any closed contact's approach and far above
  // round-off. Velocities: relative to the value, with the tolerance scale as a floor.
  const auto atol = model.absolute_tolerance();
  const double rel = model.scene->solver.jacobian_perturbation;
  position_step_.assign(model.state_size, 0.0);
  scale_.resize(model.state_size);
  for (int i = 0; i < model.state_size; ++i) {
    scale_[i] = atol[i] / model.scene->solver.rtol;
    const auto c = model.state_class[i];
    if (c == VariableClass::position || c == VariableClass::angle) position_step_[i] = rel * 1e-3 * scale_[i];
  }
}

SegmentResult Equations::evaluate_segment(int s, const PlanarKinematics& a,
                                          const PlanarKinematics& b) const {
  const Segment& seg = model_.segments[s];
  switch (seg.kind) {
    case SegmentKind::roller_inner_race:
    case SegmentKind::roller_outer_race:
      return contact::evaluate(model_.race_segments[seg.parameters], a, b);
    case SegmentKind::cage_bar_front:
    case SegmentKind::cage_bar_rear:
      return contact::evaluate(model_.bar_segments[seg.parameters], a, b);
    case SegmentKind::cage_land:
      return contact::evaluate(model_.land_segments[seg.parameters], a, b);
  }
  return {};
}

namespace {
void write_result(const SegmentResult& r, std::span<double> rec) {
  rec[SegmentRecord::on_a + 0] = r.on_a.fx;
  rec[SegmentRecord::on_a + 1] = r.on_a.fy;
  rec[SegmentRecord::on_a + 2] = r.on_a.mz;
  rec[SegmentRecord::on_b + 0] = r.on_b.fx;
  rec[SegmentRecord::on_b + 1] = r.on_b.fy;
  rec[SegmentRecord::on_b + 2] = r.on_b.mz;
  const auto& d = r.diagnostics;
  const double diag[contact::diagnostics_count] = {d.approach,      d.normal_force,   d.traction_force,
                                                   d.slip_velocity, d.elastic_energy, d.power_loss};
  for (int i = 0; i < contact::diagnostics_count; ++i) rec[SegmentRecord::diagnostics + i] = diag[i];
  rec[SegmentRecord::valid] = r.valid ? 1.0 : 0.0;
}
}  // namespace

void Equations::add_external_loads(double t, const double* z) {
  for (std::size_t b = 0; b < model_.bodies.size(); ++b) {
    const Body& body = model_.bodies[b];
    auto& w = loads_[b];
    if (body.slot[Component::vy] >= 0) w.fy -= body.mass * model_.gravity;
    if (!body.ring) continue;
    w.fx += body.ring->load.fx(t);
    w.fy += body.ring->load.fy(t);
    w.mz += body.ring->load.mz(t);
    const auto& sup = body.ring->support;
    if (sup.stiffness > 0 && body.slot[Component::px] >= 0) {
      w.fx -= sup.stiffness * z[body.slot[Component::px]] + sup.damping * z[body.slot[Component::vx]];
      w.fy -= sup.stiffness * z[body.slot[Component::py]] + sup.damping * z[body.slot[Component::vy]];
    }
  }
}

void Equations::rhs_task(std::span<const double> context, int s, std::span<double> rec) const {
  const double t = context[0];
  const double* z = context.data() + 1;
  const Segment& seg = model_.segments[s];
  write_result(evaluate_segment(s, model_.kinematics(seg.body_a, t, z), model_.kinematics(seg.body_b, t, z)), rec);
}

scheduler::TaskCatalogue Equations::task_catalogue() const {
  scheduler::TaskCatalogue c;
  c.task_count = static_cast<int>(model_.segments.size());
  c.context_size = 1 + model_.state_size;
  for (const Segment& seg : model_.segments) {
    int group = scheduler::border_group;
    for (int b : {seg.body_a, seg.body_b})
      if (model_.bodies[b].kind == BodyKind::roller) group = b - model_.first_roller;
    c.group.push_back(group);
    c.bodies.push_back({model_.bodies[seg.body_a].has_states() ? seg.body_a : -1,
                        model_.bodies[seg.body_b].has_states() ? seg.body_b : -1});
  }
  c.function[static_cast<int>(scheduler::Phase::rhs)] = [this](std::span<const double> ctx, int s, std::span<double> rec) {
    rhs_task(ctx, s, rec);
  };
  c.function[static_cast<int>(scheduler::Phase::jacobian)] =
      [this](std::span<const double> ctx, int s, std::span<double> rec) { jacobian_task(ctx, s, rec); };
  c.record_size[static_cast<int>(scheduler::Phase::rhs)] = SegmentRecord::size;
  c.record_size[static_cast<int>(scheduler::Phase::jacobian)] = jacobian_record;
  return c;
}

int Equations::rhs(double t, const double* z, double* zdot) {
  ++rhs_count_;
  const int nseg = static_cast<int>(model_.segments.size());
  segment_count_ += nseg;
  context_[0] = t;
  std::copy(z, z + model_.state_size, context_.begin() + 1);
  executor_.run(scheduler::Phase::rhs, context_, nseg, SegmentRecord::size, rhs_task_, records_);
  // Sum in the canonical (segment) order: bitwise identical for any schedule.
  for (auto& w : loads_) w = {};
  int status = 0;
  for (int s = 0; s < nseg; ++s) {
    const double* rec = records_.data() + static_cast<std::size_t>(s) * SegmentRecord::size;
    const Segment& seg = model_.segments[s];
    auto& a = loads_[seg.body_a];
    auto& b = loads_[seg.body_b];
    a.fx += rec[0], a.fy += rec[1], a.mz += rec[2];
    b.fx += rec[3], b.fy += rec[4], b.mz += rec[5];
    if (rec[SegmentRecord::valid] == 0.0) {
      status = 1;
      last_invalid_ = s;
    }
  }
  add_external_loads(t, z);
  for (std::size_t i = 0; i < model_.bodies.size(); ++i) {
    const Body& body = model_.bodies[i];
    const auto& w = loads_[i];
    const auto& sl = body.slot;
    if (sl[Component::px] >= 0) {
      zdot[sl[Component::px]] = z[sl[Component::vx]];
      zdot[sl[Component::py]] = z[sl[Component::vy]];
      zdot[sl[Component::vx]] = w.fx / body.mass;
      zdot[sl[Component::vy]] = w.fy / body.mass;
    }
    if (sl[Component::theta] >= 0) zdot[sl[Component::theta]] = z[sl[Component::omega]];
    if (sl[Component::omega] >= 0) zdot[sl[Component::omega]] = w.mz / body.inertia;
  }
  return status;
}

void Equations::jacobian_task(std::span<const double> context, int s, std::span<double> rec) const {
  const double t = context[0];
  const double* z = context.data() + 1;
  const double rel = model_.scene->solver.jacobian_perturbation;
  const Segment& seg = model_.segments[s];
  const Body& ba = model_.bodies[seg.body_a];
  const Body& bb = model_.bodies[seg.body_b];
  const PlanarKinematics ka = model_.kinematics(seg.body_a, t, z);
  const PlanarKinematics kb = model_.kinematics(seg.body_b, t, z);
  const SegmentResult base = evaluate_segment(s, ka, kb);
  std::array<double, 12> step{};
  for (int j = 0; j < 12; ++j) {
    const int slot = (j < 6 ? ba : bb).slot[j % 6];
    if (slot >= 0)
      step[j] = position_step_[slot] > 0 ? position_step_[slot]
                                         : rel * std::max(std::abs(z[slot]), scale_[slot]);
  }
  std::array<std::array<double, 12>, 6> block{};
  bool ok = base.valid;
  switch (seg.kind) {
    case SegmentKind::roller_inner_race:
    case SegmentKind::roller_outer_race:
      ok &= contact::segment_jacobian(model_.race_segments[seg.parameters], ka, kb,
                                      base, step, block);
      break;
    case SegmentKind::cage_bar_front:
    case SegmentKind::cage_bar_rear:
      ok &= contact::segment_jacobian(model_.bar_segments[seg.parameters], ka, kb,
                                      base, step, block);
      break;
    case SegmentKind::cage_land:
      ok &= contact::segment_jacobian(model_.land_segments[seg.parameters], ka, kb,
                                      base, step, block);
      break;
  }
  write_result(base, rec);
  rec[SegmentRecord::valid] = ok ? 1.0 : 0.0;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 12; ++j) rec[SegmentRecord::size + 12 * i + j] = block[i][j];
}

int Equations::jacobian(double t, const double* z, BorderedMatrix& jac) {
  ++jac_count_;
  const int nseg = static_cast<int>(model_.segments.size());
  segment_count_ += 13L * nseg;  // the base point and 12 perturbed columns per segment
  context_[0] = t;
  std::copy(z, z + model_.state_size, context_.begin() + 1);
  executor_.run(scheduler::Phase::jacobian, context_, nseg, jacobian_record, jacobian_task_, jac_records_);
  jac.set_zero();
  int status = 0;
  for (int s = 0; s < nseg; ++s) {
    const double* rec = jac_records_.data() + static_cast<std::size_t>(s) * jacobian_record;
    if (rec[SegmentRecord::valid] == 0.0) {
      status = 1;
      last_invalid_ = s;
    }
    const Segment& seg = model_.segments[s];
    const Body* bodies[2] = {&model_.bodies[seg.body_a], &model_.bodies[seg.body_b]};
    for (int i = 0; i < 6; ++i) {
      const Body& rb = *bodies[i / 3];
      const int comp = 3 + i % 3;  // force fx, fy, mz -> accelerations of vx, vy, omega
      const int row = rb.slot[comp];
      if (row < 0) continue;
      const double inv = 1.0 / (comp == Component::omega ? rb.inertia : rb.mass);
      for (int j = 0; j < 12; ++j) {
        const int col = bodies[j / 6]->slot[j % 6];
        const double v = rec[SegmentRecord::size + 12 * i + j];
        if (col >= 0 && v != 0.0) jac.add(row, col, v * inv);
      }
    }
  }
  // Kinematic rows (dq/dt = v) and supports.
  for (const Body& body : model_.bodies) {
    const auto& sl = body.slot;
    if (sl[Component::px] >= 0) {
      jac.add(sl[Component::px], sl[Component::vx], 1.0);
      jac.add(sl[Component::py], sl[Component::vy], 1.0);
      if (body.ring && body.ring->support.stiffness > 0) {
        const auto& sup = body.ring->support;
        for (int d = 0; d < 2; ++d) {
          jac.add(sl[Component::vx + d], sl[Component::px + d], -sup.stiffness / body.mass);
          jac.add(sl[Component::vx + d], sl[Component::vx + d], -sup.damping / body.mass);
        }
      }
    }
    if (sl[Component::theta] >= 0) jac.add(sl[Component::theta], sl[Component::omega], 1.0);
  }
  return status;
}

double Equations::energy(double t, const double* z) const {
  double e = 0;
  for (std::size_t i = 0; i < model_.bodies.size(); ++i) {
    const Body& body = model_.bodies[i];
    const auto& sl = body.slot;
    if (sl[Component::vx] >= 0) {
      const double vx = z[sl[Component::vx]], vy = z[sl[Component::vy]];
      const double x = z[sl[Component::px]], y = z[sl[Component::py]];
      e += 0.5 * body.mass * (vx * vx + vy * vy);
      e += body.mass * model_.gravity * y;
      if (body.ring) {
        e -= body.ring->load.fx(t) * x + body.ring->load.fy(t) * y;
        e += 0.5 * body.ring->support.stiffness * (x * x + y * y);
      }
    }
    if (sl[Component::omega] >= 0) {
      const double w = z[sl[Component::omega]];
      e += 0.5 * body.inertia * w * w;
    }
  }
  const std::size_t nseg = model_.segments.size();
  for (std::size_t s = 0; s < nseg; ++s)
    e += records_[s * SegmentRecord::size + SegmentRecord::diagnostics + 4];
  return e;
}

std::string Equations::explain_state(int index) const {
  return explain_model_state(model_, index, records_, SegmentRecord::size, SegmentRecord::diagnostics, last_invalid_);
}

}  // namespace raceway::solver
