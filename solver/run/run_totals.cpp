#include "solver/run/run_totals.hpp"

#include "solver/bearing/power_terms.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "solver/run/output_writer.hpp"

namespace raceway::run {

using contact::Vec3;

namespace {

// The integrator counters the summary sums over CVODE restarts, by name (checkpoint values).
struct CounterField {
  const char* name;
  long numerics::IntegratorStatistics::*member;
};
constexpr CounterField kCounters[] = {{"steps", &numerics::IntegratorStatistics::steps},
                                      {"cvode_rhs_evaluations", &numerics::IntegratorStatistics::rhs_evaluations},
                                      {"cvode_jacobian_evaluations", &numerics::IntegratorStatistics::jacobian_evaluations},
                                      {"linear_setups", &numerics::IntegratorStatistics::linear_setups},
                                      {"newton_iterations", &numerics::IntegratorStatistics::newton_iterations},
                                      {"newton_failures", &numerics::IntegratorStatistics::newton_failures},
                                      {"error_test_failures", &numerics::IntegratorStatistics::error_test_failures}};

constexpr const char* kBaseNames[] = {"model_rhs_evaluations", "model_jacobian_evaluations", "segment_evaluations",
                                      "rhs_seconds", "jacobian_seconds", "wall_seconds"};

}  // namespace

// The counters of this process (equations, executor, wall clock), in kBaseNames order.
void RunTotals::process_counts(const bearing::Equations& eq, const scheduler::Executor& executor, double wall,
                               double out[6]) const {
  out[0] = static_cast<double>(eq.rhs_evaluations());
  out[1] = static_cast<double>(eq.jacobian_evaluations());
  out[2] = static_cast<double>(eq.segment_evaluations());
  out[3] = executor.total_seconds(scheduler::Phase::rhs);
  out[4] = executor.total_seconds(scheduler::Phase::jacobian);
  out[5] = wall;
  if (also_eq_ == nullptr) return;
  out[0] += static_cast<double>(also_eq_->rhs_evaluations());
  out[2] += static_cast<double>(also_eq_->segment_evaluations());
  out[3] += also_executor_->total_seconds(scheduler::Phase::rhs);
}

RunTotals::RunTotals(const bearing::Model& m, double end_time)
    : m_(m),
      end_(end_time),
      drive_(m.params().inner_ring.motion == scene::RingMotion::driven ? &m.params().inner_ring : &m.params().outer_ring) {}

void RunTotals::turn_to(double t) {
  if (!turned_) last_t_ = t, turned_ = true;
  if (drive_->motion == scene::RingMotion::driven)
    revolutions_ += 0.5 * (drive_->speed(last_t_) + drive_->speed(t)) * (t - last_t_) / (2 * std::numbers::pi);
  last_t_ = t;
}

void RunTotals::record(double t, const std::vector<double>& z, const bearing::Equations& eq, double energy) {
  const double stored = bearing::PowerTerms::stored_energy(eq, t, z.data(), energy);
  if (samples_ == 0) energy_initial_ = energy, stored_initial_ = stored;
  energy_final_ = energy, stored_final_ = stored;
  energy_max_drift_ = std::max(energy_max_drift_, std::abs(energy - energy_initial_));
  ++samples_;
  if (t < 0.5 * end_ - 1e-12) return;
  // The second half's means (summary): contact force and load on the inner ring, cage speed.
  force_sum_ += eq.contact_loads()[static_cast<std::size_t>(m_.inner_ring)].force;
  const auto& l = m_.params().inner_ring.load;
  load_sum_ += Vec3(l.fx(t), l.fy(t), l.fz(t));
  constexpr int normal_force = contact::field_index(contact::point_diagnostic_fields, "normal_force");
  std::vector<double> element_load(static_cast<std::size_t>(m_.element_count), 0.0);
  for (std::size_t s = 0; s < m_.segments.size(); ++s)
    if (m_.segments[s].kind == bearing::SegmentKind::ball_inner_groove ||
        m_.segments[s].kind == bearing::SegmentKind::roller_inner_slice)  // a spatial roller: its slices added
      element_load[static_cast<std::size_t>(m_.segments[s].element)] += eq.diagnostic(s, normal_force);
  for (double q : element_load) max_element_load_ = std::max(max_element_load_, q);
  const std::vector<double> none(z.size(), 0.0);
  cage_sum_ += sample_body(m_, m_.cage, t, z, none, bearing::Wrench{}).angular_velocity.z();
  epicyclic_sum_ += m_.epicyclic_cage_speed(t);
  rolling_sum_ += OutputWriter::rolling_cage_speed(m_, eq, t);
  ++half_count_;
}

void RunTotals::add_finished_integrator(const numerics::IntegratorStatistics& s) {
  for (const CounterField& c : kCounters) finished_.*c.member += s.*c.member;
}

void RunTotals::save(Checkpoint& cp, const numerics::IntegratorStatistics& current, const bearing::Equations& eq,
                     const scheduler::Executor& executor, double wall_seconds) const {
  auto& v = cp.values;
  for (const CounterField& c : kCounters) v[c.name] = static_cast<double>(finished_.*c.member + current.*c.member);
  double now[6];
  process_counts(eq, executor, wall_seconds, now);
  for (int i = 0; i < 6; ++i) v[kBaseNames[i]] = base_[i] + now[i];
  v["energy_initial"] = energy_initial_, v["energy_final"] = energy_final_, v["energy_max_drift"] = energy_max_drift_;
  v["stored_energy_initial"] = stored_initial_, v["stored_energy_final"] = stored_final_;
  v["revolutions"] = revolutions_, v["last_t"] = last_t_, v["output_samples"] = static_cast<double>(samples_);
  for (int d = 0; d < 3; ++d) {
    v["second_half.force_" + std::to_string(d)] = force_sum_[d];
    v["second_half.load_" + std::to_string(d)] = load_sum_[d];
  }
  v["second_half.cage"] = cage_sum_, v["second_half.epicyclic"] = epicyclic_sum_;
  v["second_half.rolling"] = rolling_sum_;
  v["second_half.max_element_load"] = max_element_load_, v["second_half.count"] = static_cast<double>(half_count_);
}

void RunTotals::restore(const Checkpoint& cp, const bearing::Equations& eq, const scheduler::Executor& executor) {
  auto get = [&](const std::string& name) {
    const auto it = cp.values.find(name);
    if (it == cp.values.end()) throw ResumeRefused("cannot resume: the checkpoint lacks the value '" + name + "'");
    return it->second;
  };
  for (const CounterField& c : kCounters) finished_.*c.member = std::lround(get(c.name));
  double now[6];
  process_counts(eq, executor, 0.0, now);
  for (int i = 0; i < 6; ++i) base_[i] = get(kBaseNames[i]) - now[i];
  energy_initial_ = get("energy_initial"), energy_final_ = get("energy_final"), energy_max_drift_ = get("energy_max_drift");
  stored_initial_ = get("stored_energy_initial"), stored_final_ = get("stored_energy_final");
  revolutions_ = get("revolutions"), last_t_ = get("last_t"), turned_ = true, samples_ = std::lround(get("output_samples"));
  for (int d = 0; d < 3; ++d) {
    force_sum_[d] = get("second_half.force_" + std::to_string(d));
    load_sum_[d] = get("second_half.load_" + std::to_string(d));
  }
  cage_sum_ = get("second_half.cage"), epicyclic_sum_ = get("second_half.epicyclic");
  rolling_sum_ = get("second_half.rolling");
  max_element_load_ = get("second_half.max_element_load"), half_count_ = std::lround(get("second_half.count"));
}

void RunTotals::summarize(RunSummary& sum, double t, const numerics::IntegratorStatistics& current, const bearing::Equations& eq,
                          const scheduler::Executor& executor, double wall_seconds) const {
  sum.stats = current;
  for (const CounterField& c : kCounters) sum.stats.*c.member = finished_.*c.member + current.*c.member;
  double now[6];
  process_counts(eq, executor, wall_seconds, now);
  sum.model_rhs_evaluations = std::lround(base_[0] + now[0]);
  sum.model_jacobian_evaluations = std::lround(base_[1] + now[1]);
  sum.segment_evaluations = std::lround(base_[2] + now[2]);
  sum.rhs_seconds = base_[3] + now[3], sum.jacobian_seconds = base_[4] + now[4], sum.wall_time_s = base_[5] + now[5];
  sum.simulated_time_s = t;
  sum.output_samples = static_cast<int>(samples_);
  sum.energy_initial_j = energy_initial_, sum.energy_final_j = energy_final_, sum.energy_max_drift_j = energy_max_drift_;
  sum.driven_ring_revolutions = revolutions_;
  if (half_count_ == 0) return;
  const auto n = static_cast<double>(half_count_);
  constexpr double rpm = 30.0 / std::numbers::pi;
  sum.cage_speed_rpm = cage_sum_ / n * rpm;
  sum.epicyclic_cage_speed_rpm = epicyclic_sum_ / n * rpm;
  // One slip everywhere (the report's too): against the cage speed of elements rolling at the angle
  // they are loaded at (/cage/rolling_speed); the nominal angle's epicyclic speed is kept beside it.
  sum.rolling_cage_speed_rpm = rolling_sum_ / n * rpm;
  sum.cage_slip = sum.rolling_cage_speed_rpm != 0 ? 1.0 - sum.cage_speed_rpm / sum.rolling_cage_speed_rpm : 0.0;
  sum.max_ball_load_n = max_element_load_;
  const int dims = m_.kind == scene::ModelKind::spatial ? 3 : 2;
  for (int d = 0; d < dims; ++d) {
    sum.inner_ring_contact_force_n.push_back(force_sum_[d] / n);
    sum.inner_ring_load_n.push_back(load_sum_[d] / n);
  }
}

}  // namespace raceway::run
