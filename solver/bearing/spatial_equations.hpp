// Equations of motion of the spatial ball bearing: dz/dt = f(t, z) (seed 000 eq. 2) and its
// Jacobian, assembled from contact segments evaluated as tasks through a scheduler::Executor.
//
// Newton for translation in the inertial bearing frame (centrifugal forces come out of the
// equations), Euler for rotation: balls are spheres (I dw/dt = M), the cage uses Euler's equations
// in its principal frame with the gyroscopic term, rings the small-tilt rotor equations (see
// solver/spatial_model.hpp). Segment results are summed in the canonical (segment) order, so the
// right-hand side is bitwise identical for any schedule.
#pragma once

#include <vector>

#include "scheduler/executor.hpp"
#include "solver/numerics/dynamic_system.hpp"
#include "solver/bearing/spatial_model.hpp"

namespace raceway::solver {

/// Layout of one segment's record in the right-hand-side phase.
struct SpatialRecord {
  static constexpr int on_a = 0;          // force (3), moment (3) on body A at its centre
  static constexpr int on_b = 6;          // force (3), moment (3) on body B
  static constexpr int diagnostics = 12;  // contact::PointDiagnostics, in declaration order
  static constexpr int valid = diagnostics + contact::point_diagnostics_count;
  static constexpr int size = valid + 1;
};

class SpatialEquations final : public DynamicSystem {
 public:
  SpatialEquations(const SpatialModel& model, scheduler::Executor& executor);
  // The task functions capture `this` (they are handed to executors): no copies, no moves.
  SpatialEquations(const SpatialEquations&) = delete;
  SpatialEquations& operator=(const SpatialEquations&) = delete;

  int state_size() const override { return model_.state_size; }
  int border_size() const override { return model_.border_size; }
  int block_count() const override { return model_.ball_count; }
  int block_size() const override { return SpatialModel::ball_block_size; }
  std::vector<double> absolute_tolerance() const override { return model_.absolute_tolerance(); }
  int rhs(double t, const double* z, double* zdot) override;
  /// Finite differences of one segment at a time over the states of its two bodies, mapped to
  /// accelerations with the bodies' inertia at z; plus each body's own terms (kinematics,
  /// gyroscopic, supports) by finite differences of that body alone.
  int jacobian(double t, const double* z, BorderedMatrix& jac) override;
  std::string explain_state(int index) const override;

  /// Records of the last rhs(), segment-major (SpatialRecord layout).
  const std::vector<double>& segment_records() const { return records_; }
  /// Net wrench on each body from the last rhs() (contacts + loads + supports + gravity).
  const std::vector<contact::SpatialWrench>& body_loads() const { return net_; }
  /// Wrench on each body from its contacts alone, last rhs().
  const std::vector<contact::SpatialWrench>& contact_loads() const { return contact_; }
  /// Total mechanical energy (kinetic + elastic + supports + load and gravity potential) [J].
  /// Uses the last rhs() records: call rhs(t, z) first.
  double energy(double t, const double* z) const;
  int last_invalid_segment() const { return last_invalid_; }

  long rhs_evaluations() const { return rhs_count_; }
  long jacobian_evaluations() const { return jac_count_; }
  long segment_evaluations() const { return segment_count_; }
  const SpatialModel& model() const { return model_; }
  scheduler::Executor& executor() { return executor_; }
  /// The tasks (one per segment) with their grouping (ball, or border for cage-land) and task
  /// functions, for an executor's attach() on the master and serve() on the workers.
  scheduler::TaskCatalogue task_catalogue() const;

  /// d(state)/dt of body b's states, given the wrench on it from its contacts (loads, supports,
  /// gravity and gyroscopic terms added here). Writes zdot at b's slots only.
  void body_rates(int b, double t, const double* z, const contact::SpatialWrench& contacts, double* zdot) const;
  /// Loads, supports and gravity on body b at (t, z).
  contact::SpatialWrench external_wrench(int b, double t, const double* z) const;

 private:
  contact::SpatialSegmentResult evaluate_segment(int s, const contact::SpatialKinematics& a,
                                                 const contact::SpatialKinematics& b) const;
  /// The part of body b's velocity-state rates linear in a wrench w, at z (no gyroscopic terms):
  /// rates[c] for velocity components c = svx..swz.
  void wrench_rates(int b, const double* z, const contact::SpatialWrench& w, double rates[spatial_components]) const;
  double step_for(int state, const double* z) const;
  /// Task functions: context = [t, z...] (see scheduler::TaskFunction).
  void rhs_task(std::span<const double> context, int s, std::span<double> rec) const;
  void jacobian_task(std::span<const double> context, int s, std::span<double> rec) const;

  const SpatialModel& model_;
  scheduler::Executor& executor_;
  std::vector<double> records_, jac_records_;
  std::vector<contact::SpatialWrench> contact_, net_;
  std::vector<double> scale_, position_step_;
  std::vector<double> context_;  ///< [t, z...] sent with every evaluation
  scheduler::TaskFunction rhs_task_, jacobian_task_;
  long jacobian_segment_evaluations_ = 0;
  int last_invalid_ = -1;
  long rhs_count_ = 0, jac_count_ = 0;
  long segment_count_ = 0;
};

}  // namespace raceway::solver
