#include "solver/bearing/equations.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <utility>

#include "solver/bearing/element_evaluation.hpp"
#include "solver/bearing/race_defects.hpp"

namespace raceway::bearing {

std::unique_ptr<BodyDynamics> make_planar_dynamics(const Model& model);
std::unique_ptr<BodyDynamics> make_spatial_dynamics(const Model& model);
int segment_part_count(const SegmentLaw& law);  // segment_parts.cpp

std::unique_ptr<BodyDynamics> make_body_dynamics(const Model& model) {
  return model.kind == scene::ModelKind::spatial ? make_spatial_dynamics(model) : make_planar_dynamics(model);
}

FiniteDifferenceSteps::FiniteDifferenceSteps(const Model& model)
    : relative_(model.params().solver.jacobian_perturbation),
      scale_(static_cast<std::size_t>(model.state_size)),
      position_step_(static_cast<std::size_t>(model.state_size), 0.0) {
  // The class scales, not the bridges' tighter bending tolerances: a bridge's kinematics add its
  // bending angle to the cage's, so a smaller step would drown in the sum's round-off.
  const auto atol = physical_absolute_tolerance(model.params(), model.state_class, model.pitch_radius,
                                                model.element_radius);
  for (std::size_t i = 0; i < scale_.size(); ++i) {
    scale_[i] = atol[i] / model.params().solver.rtol;
    const auto c = model.state_class[i];
    if (c == VariableClass::position || c == VariableClass::angle) position_step_[i] = relative_ * 1e-3 * scale_[i];
  }
}

double FiniteDifferenceSteps::operator()(int state, const double* z) const {
  const auto i = static_cast<std::size_t>(state);
  if (position_step_[i] > 0) return position_step_[i];
  return relative_ * std::max(std::abs(z[state]), scale_[i]);
}

ElementShape element_shape(const Model& m, const Segment& seg) {
  ElementShape shape;
  shape.columns = segment_columns(m, seg);
  for (const bool on_a : {true, false}) {
    const MarkerKind* kind = element_detail::kind_of(m.markers[static_cast<std::size_t>(on_a ? seg.marker_a : seg.marker_b)]);
    if (!kind) continue;
    (on_a ? shape.shift_a : shape.shift_b) = kind->shift_columns();
    shape.coupled = shape.coupled || kind->follows_partner();
  }
  if (shape.record_columns() > 2 * coordinate_count)
    throw std::logic_error(fmt::format("element {}: more Jacobian columns ({}) than a record holds", seg.name,
                                       shape.record_columns()));
  return shape;
}

namespace {

template <class Law>
int elastic_energy_field() {
  return diagnostic_index<Law>("elastic_energy");
}

}  // namespace

Equations::Equations(const Model& model, scheduler::Executor& executor)
    : model_(model),
      executor_(executor),
      dynamics_(make_body_dynamics(model)),
      step_(model),
      net_(model.bodies.size()),
      context_(2 + static_cast<std::size_t>(model.state_size), 0.0),
      rhs_task_([this](std::span<const double> ctx, int s, std::span<double> rec) { rhs_task(ctx, s, rec); }),
      jacobian_task_([this](std::span<const double> ctx, int s, std::span<double> rec) { jacobian_task(ctx, s, rec); }) {
  followers_.resize(model.bodies.size());
  for (const Model::RateFollower& f : model.rate_followers) followers_[static_cast<std::size_t>(f.body)].push_back(f);
  contact_.body.resize(model.bodies.size());
  contact_.node.resize(static_cast<std::size_t>(model.node_force_count()));
  // Counted here, not in the tasks, which may run on other ranks.
  for (const Segment& seg : model.segments) {
    shapes_.push_back(element_shape(model, seg));
    jacobian_segment_evaluations_ += 1 + shapes_.back().record_columns();
    elastic_energy_field_.push_back(std::visit(
        [](const auto& law) { return elastic_energy_field<std::decay_t<decltype(law)>>(); },
        model.laws[static_cast<std::size_t>(seg.law)]));
    const int parts = segment_part_count(model.laws[static_cast<std::size_t>(seg.law)]);
    first_task_.push_back(static_cast<int>(task_segment_.size()));
    parts_.push_back(parts);
    task_segment_.insert(task_segment_.end(), static_cast<std::size_t>(parts), static_cast<int>(parts_.size() - 1));
    cut_ = cut_ || parts > 1;
  }
  for (std::size_t s = 0; s < model.segments.size(); ++s) {
    // Its result and columns (a cut element's combined record), or a part's share.
    jacobian_record_ = std::max(jacobian_record_, SegmentRecord::size + SegmentRecord::wrench_rows * shapes_[s].record_columns());
    if (parts_[s] > 1)
      for (int part = 0; part < parts_[s]; ++part)
        jacobian_record_ = std::max(jacobian_record_,
                                    segment_part_record_size(scheduler::Phase::jacobian, static_cast<int>(s), part));
    const SegmentKind k = model.segments[s].kind;
    if (k == SegmentKind::ball_pocket || k == SegmentKind::cage_bar_front || k == SegmentKind::cage_bar_rear)
      pocket_segments_.push_back(static_cast<int>(s));
  }
  pocket_weight_factor_ = model.params().solver.pocket_tolerance_factor;
  pocket_cage_rate_ = model.params().solver.pocket_tolerance_cage;
  pocket_margin_ = 1e-4 * model.element_radius;
}

namespace {

/// Element seg's record at (t, z): the one place this file instantiates every law's evaluation (a
/// second set, in the pocket weights, made GCC stop inlining the records' writing into the
/// right-hand side's: +0.7 % instructions on seed 002).
void write_element(const Model& m, const Segment& seg, double t, const double* z, std::span<double> rec) {
  std::visit([&](const auto& law) { write_element_result(m, law, seg, t, z, rec); },
             m.laws[static_cast<std::size_t>(seg.law)]);
}

/// Body b's centre at (t, z), kinematics(b, t, z).position: straight from its states where it has
/// all three (a ball), without the rest of its kinematics.
contact::Vec3 body_centre(const Model& m, int b, double t, const double* z) {
  const Body& body = m.bodies[static_cast<std::size_t>(b)];
  if (body.ring || body.slot[sx] < 0 || body.slot[sy] < 0 || body.slot[sz] < 0) return m.kinematics(b, t, z).position;
  return {z[body.slot[sx]], z[body.slot[sy]], z[body.slot[sz]]};
}

/// Body b's centre in the plane at (t, z), planar_kinematics(b, t, z)'s x and y: straight from its
/// states where it has both (a roller), without its velocities (in the orbital frame, a conversion).
std::pair<double, double> planar_centre(const Model& m, int b, double t, const double* z) {
  const Body& body = m.bodies[static_cast<std::size_t>(b)];
  if (body.ring || body.slot[sx] < 0 || body.slot[sy] < 0) {
    const contact::PlanarKinematics k = m.planar_kinematics(b, t, z);
    return {k.x, k.y};
  }
  return {z[body.slot[sx]], z[body.slot[sy]]};
}

/// The planar cage's kinematics at the pocket weights' (t, z), computed for its first bar and kept
/// for the others (a spatial cage's are in the KinematicsMemo scope).
struct PlanarCage {
  int body = -1;
  contact::PlanarKinematics k;
  const contact::PlanarKinematics& of(const Model& m, int b, double t, const double* z) {
    if (body != b) body = b, k = m.planar_kinematics(b, t, z);
    return k;
  }
};

/// The approach of pocket element seg at (t, z): a ball's pocket and a planar roller's cage bar on
/// two body centres by their gap alone (contact::pocket_approach, contact::bar_approach: the bits of
/// their full evaluation), any other element (a bar on a flexible bridge) evaluated.
double pocket_element_approach(const Model& m, const Segment& seg, double t, const double* z, PlanarCage& planar_cage) {
  const SegmentLaw& law = m.laws[static_cast<std::size_t>(seg.law)];
  const auto* cage = std::get_if<BodyCentre>(&m.markers[static_cast<std::size_t>(seg.marker_a)]);
  const auto* element = std::get_if<BodyCentre>(&m.markers[static_cast<std::size_t>(seg.marker_b)]);
  if (cage && element) {
    if (const auto* pocket = std::get_if<contact::BallPocketSegment>(&law))
      return contact::pocket_approach(*pocket, m.kinematics(cage->body, t, z), body_centre(m, element->body, t, z));
    if (const auto* bar = std::get_if<contact::CageBarSegment>(&law)) {
      const auto [x, y] = planar_centre(m, element->body, t, z);
      return contact::bar_approach(*bar, planar_cage.of(m, cage->body, t, z), x, y);
    }
  }
  std::array<double, SegmentRecord::size> rec{};
  write_element(m, seg, t, z, rec);
  return rec[SegmentRecord::diagnostics + approach_field];
}

}  // namespace

void Equations::adjust_error_weights(double t, const double* z, double* ewt) const {
  const KinematicsMemo memo(model_, t, z);  // the cage's kinematics once for all its pockets
  PlanarCage planar_cage;
  pocket_touched_.assign(model_.bodies.size(), 0);
  for (const int s : pocket_segments_) {
    const Segment& seg = model_.segments[static_cast<std::size_t>(s)];
    if (!(pocket_element_approach(model_, seg, t, z, planar_cage) > -pocket_margin_)) continue;
    for (const int b : {seg.body_a, seg.body_b}) {
      const BodyKind kind = model_.bodies[static_cast<std::size_t>(b)].kind;
      if (kind == BodyKind::rolling_element || (pocket_cage_rate_ && kind == BodyKind::cage))
        pocket_touched_[static_cast<std::size_t>(b)] = 1;
    }
  }
  // Only the element's translational velocities: the relative tolerance on its orbital velocity is
  // far looser than the approach velocities of a pocket contact (docs/integration_methods.md). In
  // the orbital frame only v_theta, along which the pocket pushes (not the radial vibration). The
  // cage (pocket_tolerance_cage): its rotation rate, once however many elements touch it.
  for (std::size_t b = 0; b < model_.bodies.size(); ++b) {
    if (!pocket_touched_[b]) continue;
    const Body& body = model_.bodies[b];
    if (body.kind == BodyKind::cage) {
      if (body.has(swz)) ewt[body.slot[swz]] *= pocket_weight_factor_;
      continue;
    }
    if (model_.has_orbital_velocity(body)) {
      ewt[body.slot[svy]] *= pocket_weight_factor_;
      continue;
    }
    for (int i = body.offset; i < body.offset + body.size; ++i)
      if (model_.state_class[static_cast<std::size_t>(i)] == VariableClass::velocity) ewt[i] *= pocket_weight_factor_;
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
  write_element(model_, seg, t, z, rec);
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
  std::visit(
      [&](const auto& law) {
        write_element_jacobian(model_, step_, law, seg, shapes_[static_cast<std::size_t>(s)], context[0],
                               context.data() + 1, rec);
      },
      model_.laws[static_cast<std::size_t>(seg.law)]);
}

scheduler::TaskCatalogue Equations::task_catalogue() const {
  scheduler::TaskCatalogue c;
  c.task_count = static_cast<int>(task_segment_.size());
  c.context_size = 2 + model_.state_size;
  for (int s : task_segment_) {
    const Segment& seg = model_.segments[static_cast<std::size_t>(s)];
    c.group.push_back(seg.element >= 0 ? seg.element : scheduler::border_group);
    c.bodies.push_back({planning_id(seg.marker_a), planning_id(seg.marker_b)});
  }
  c.parent = task_segment_;
  c.function[static_cast<int>(scheduler::Phase::rhs)] = rhs_task_;
  c.function[static_cast<int>(scheduler::Phase::jacobian)] = jacobian_task_;
  c.record_size[static_cast<int>(scheduler::Phase::rhs)] = SegmentRecord::size;
  c.record_size[static_cast<int>(scheduler::Phase::jacobian)] = jacobian_record_;
  // What each task's record carries between ranks: a cut segment's parts their share, an uncut
  // segment its whole record (in the Jacobian: its result and one column per state it depends on).
  for (std::size_t t = 0; t < task_segment_.size(); ++t) {
    const int s = task_segment_[t];
    for (const auto phase : {scheduler::Phase::rhs, scheduler::Phase::jacobian}) {
      int used = SegmentRecord::size;
      if (parts_[static_cast<std::size_t>(s)] > 1)
        used = segment_part_record_size(phase, s, static_cast<int>(t) - first_task_[static_cast<std::size_t>(s)]);
      else if (phase == scheduler::Phase::jacobian)
        used += SegmentRecord::wrench_rows * shapes_[static_cast<std::size_t>(s)].record_columns();
      c.used_size[static_cast<std::size_t>(phase)].push_back(used);
    }
  }
  return c;
}

int Equations::rhs(double t, const double* z, double* zdot) {
  ++rhs_count_;
  rhs_time_ = t;
  rhs_state_.assign(z, z + model_.state_size);
  const int nseg = static_cast<int>(model_.segments.size());
  segment_count_ += nseg;
  context_[0] = t;
  std::copy(z, z + model_.state_size, context_.begin() + 1);
  const int ntask = static_cast<int>(task_segment_.size());
  {
    // Each body's kinematics once, however many elements this rank evaluates touch it (at the
    // context's copy of z, or at z itself: an output sample's rows ask there after).
    const KinematicsMemo memo(model_, t, context_.data() + 1, z);
    executor_.run(scheduler::Phase::rhs, context_, ntask, SegmentRecord::size, rhs_task_, cut_ ? task_records_ : records_);
  }
  if (cut_) combine_rhs_parts(records_);
  // Sum in the canonical (element) order: bitwise identical for any schedule.
  contact_.clear();
  int status = 0;
  for (int s = 0; s < nseg; ++s) {
    const double* rec = records_.data() + static_cast<std::size_t>(s) * SegmentRecord::size;
    scatter(model_.segments[static_cast<std::size_t>(s)], rec, t, z, contact_);
    if (rec[SegmentRecord::valid] == 0.0) {
      status = 1;
      last_invalid_ = s;
    }
  }
  for (std::size_t b = 0; b < model_.bodies.size(); ++b)
    dynamics_->rates(static_cast<int>(b), t, z, contact_.body[b], net_[b], zdot);
  for (const auto& node : model_.nodes) node->rates(model_, t, z, contact_.node.data() + node->force_offset, zdot);
  for (const auto& node : model_.nodes) node->add_segment_rates(model_, t, z, records_.data(), zdot);
  return status;
}

void Equations::add_rate_derivative(int b, int state, const double* z, const Wrench& dw, numerics::BorderedMatrix& jac) const {
  const Body& body = model_.bodies[static_cast<std::size_t>(b)];
  double rates[coordinate_count];
  dynamics_->contact_rate_derivative(b, z, dw, rates);
  for (int c = svx; c < coordinate_count; ++c)
    if (body.slot[c] >= 0 && rates[c] != 0.0) jac.add(body.slot[c], state, rates[c]);
  for (const Model::RateFollower& f : followers_[static_cast<std::size_t>(b)])  // relative coordinates
    if (rates[f.coordinate] != 0.0) jac.add(f.row, state, f.factor * rates[f.coordinate]);
}

void Equations::scatter(const Segment& seg, const double* rec, double t, const double* z, Loads& loads) const {
  for (const bool on_a : {true, false}) {
    const Marker& marker = model_.markers[static_cast<std::size_t>(on_a ? seg.marker_a : seg.marker_b)];
    const double* w = rec + (on_a ? SegmentRecord::on_a : SegmentRecord::on_b);
    if (const auto* centre = std::get_if<BodyCentre>(&marker))
      add_wrench(loads.body[static_cast<std::size_t>(centre->body)], w);
    else
      std::get<std::shared_ptr<const MarkerKind>>(marker)->scatter(model_, seg, on_a, w, t, z, loads);
  }
}

int Equations::planning_id(int marker_index) const {
  const Marker& marker = model_.markers[static_cast<std::size_t>(marker_index)];
  if (const auto* centre = std::get_if<BodyCentre>(&marker))
    return model_.bodies[static_cast<std::size_t>(centre->body)].has_states() ? centre->body : -1;
  return std::get<std::shared_ptr<const MarkerKind>>(marker)->planning_id();
}

void Equations::add_segment_jacobian(int s, const double* rec, const JacobianAssembly& assembly) const {
  const Segment& seg = model_.segments[static_cast<std::size_t>(s)];
  const Marker* markers[2] = {&model_.markers[static_cast<std::size_t>(seg.marker_a)],
                              &model_.markers[static_cast<std::size_t>(seg.marker_b)]};
  const std::vector<SegmentColumn>& columns = shapes_[static_cast<std::size_t>(s)].columns;
  for (std::size_t column = 0; column < columns.size(); ++column) {
    const SegmentColumn& c = columns[column];
    const double* d = rec + SegmentRecord::size + SegmentRecord::wrench_rows * column;
    // A relative coordinate's column stands for its carrier's state too (the marker adds both).
    for (const int state : {c.state, c.also}) {
      if (state < 0) continue;
      for (int target = 0; target < 2; ++target) {
        const double* w = d + 6 * target;
        // A body's rates are linear in the wrench: a zero derivative adds nothing (an element out
        // of contact, most pocket bars and the slices outside the load zone).
        if (std::holds_alternative<BodyCentre>(*markers[target]) && std::all_of(w, w + 6, [](double v) { return v == 0.0; }))
          continue;
        Wrench dw;
        for (int i = 0; i < 3; ++i) dw.force[i] = w[i], dw.moment[i] = w[3 + i];
        marker_add_rate_derivative(model_, *markers[target], assembly, state, dw);
      }
    }
  }
  for (const Marker* marker : markers)
    if (const MarkerKind* kind = element_detail::kind_of(*marker)) kind->add_jacobian_terms(assembly, seg, columns, rec);
}

int Equations::jacobian(double t, const double* z, numerics::BorderedMatrix& jac) {
  ++jac_count_;
  const int nseg = static_cast<int>(model_.segments.size());
  segment_count_ += jacobian_segment_evaluations_;
  context_[0] = t;
  std::copy(z, z + model_.state_size, context_.begin() + 1);
  const int ntask = static_cast<int>(task_segment_.size());
  {
    const KinematicsMemo memo(model_, t, context_.data() + 1);  // at z: the unperturbed bodies' once
    executor_.run(scheduler::Phase::jacobian, context_, ntask, jacobian_record_, jacobian_task_,
                  cut_ ? jac_task_records_ : jac_records_);
  }
  if (cut_) combine_jacobian_parts(z);
  jac.set_zero();
  int status = 0;
  Loads contacts{std::vector<Wrench>(model_.bodies.size()), std::vector<double>(contact_.node.size(), 0.0)};
  const JacobianAssembly assembly{model_, *this, t, z, jac};
  for (int s = 0; s < nseg; ++s) {
    const double* rec = jac_records_.data() + static_cast<std::size_t>(s) * static_cast<std::size_t>(jacobian_record_);
    if (rec[SegmentRecord::valid] == 0.0) {
      status = 1;
      last_invalid_ = s;
    }
    scatter(model_.segments[static_cast<std::size_t>(s)], rec, t, z, contacts);
    add_segment_jacobian(s, rec, assembly);
  }
  dynamics_->add_body_jacobian(t, z, contacts.body, step_, jac);
  for (const auto& node : model_.nodes) node->add_own_jacobian(model_, t, jac);
  return status;
}

double Equations::energy(double t, const double* z) const {
  double e = dynamics_->body_energy(t, z);
  for (const auto& node : model_.nodes) node->add_energy(model_, t, z, e);
  for (std::size_t s = 0; s < model_.segments.size(); ++s) e += diagnostic(s, elastic_energy_field_[s]);
  return e;
}

double Equations::step_limit(double t, const double* z) const { return spall_step_limit(model_, t, z); }
bool Equations::limits_steps() const { return has_spall(model_); }

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

}  // namespace raceway::bearing
