// Equations of motion of the planar bearing: dz/dt = f(t, z) (seed 000 eq. 2) and its Jacobian,
// both assembled from contact segments evaluated as tasks through a scheduler::Executor.
//
// Newton for translation and Euler for rotation in an inertial bearing frame: centrifugal and
// gyroscopic effects come out of the equations (Cartesian coordinates), not out of added terms.
#pragma once

#include <vector>

#include "scheduler/executor.hpp"
#include "solver/numerics/bordered_matrix.hpp"
#include "solver/numerics/dynamic_system.hpp"
#include "solver/bearing/model.hpp"

namespace raceway::solver {

/// Layout of one segment's record in the right-hand-side phase.
struct SegmentRecord {
  static constexpr int on_a = 0;         // fx, fy, mz on body A
  static constexpr int on_b = 3;         // fx, fy, mz on body B
  static constexpr int diagnostics = 6;  // contact::SegmentDiagnostics, in declaration order
  static constexpr int valid = diagnostics + contact::diagnostics_count;
  static constexpr int size = valid + 1;
};

class Equations final : public DynamicSystem {
 public:
  Equations(const Model& model, scheduler::Executor& executor);
  // The task functions capture `this` (they are handed to executors): no copies, no moves.
  Equations(const Equations&) = delete;
  Equations& operator=(const Equations&) = delete;

  int state_size() const override { return model_.state_size; }
  int border_size() const override { return model_.border_size; }
  int block_count() const override { return model_.roller_count; }
  int block_size() const override {
    return model_.roller_count > 0 ? (model_.state_size - model_.border_size) / model_.roller_count : 0;
  }
  std::vector<double> absolute_tolerance() const override { return model_.absolute_tolerance(); }
  /// f(t, z). Returns 0, or 1 (recoverable) when a contact law left its valid range.
  int rhs(double t, const double* z, double* zdot) override;
  /// J = df/dz by finite differences of one segment at a time, into the bordered matrix.
  /// Returns 0, or 1 (recoverable).
  int jacobian(double t, const double* z, BorderedMatrix& jac) override;
  std::string explain_state(int index) const override;

  /// Records of the last rhs() evaluation, segment-major (SegmentRecord layout).
  const std::vector<double>& segment_records() const { return records_; }
  /// Total mechanical energy: kinetic + elastic contact + support springs + potential of the
  /// current external loads and gravity [J]. Uses the last rhs() records: call rhs(t, z) first.
  double energy(double t, const double* z) const;
  /// Net force/moment on each body from the last rhs() (contacts + loads + supports + gravity).
  const std::vector<contact::PlanarWrench>& body_loads() const { return loads_; }
  /// Index of the segment that most recently reported leaving its valid range, or -1.
  int last_invalid_segment() const { return last_invalid_; }

  long rhs_evaluations() const { return rhs_count_; }
  long jacobian_evaluations() const { return jac_count_; }
  long segment_evaluations() const { return segment_count_; }
  const Model& model() const { return model_; }
  scheduler::Executor& executor() { return executor_; }
  /// The tasks (one per segment) with their grouping and task functions, for an executor's
  /// attach() on the master and serve() on the workers: every rank evaluates the same code.
  scheduler::TaskCatalogue task_catalogue() const;

 private:
  contact::SegmentResult evaluate_segment(int s, const contact::PlanarKinematics& a,
                                          const contact::PlanarKinematics& b) const;
  void add_external_loads(double t, const double* z);
  /// Task functions: context = [t, z...] (see scheduler::TaskFunction).
  void rhs_task(std::span<const double> context, int s, std::span<double> rec) const;
  void jacobian_task(std::span<const double> context, int s, std::span<double> rec) const;

  const Model& model_;
  scheduler::Executor& executor_;
  std::vector<double> records_, jac_records_;
  std::vector<contact::PlanarWrench> loads_;
  std::vector<double> context_;  ///< [t, z...] sent with every evaluation
  scheduler::TaskFunction rhs_task_, jacobian_task_;
  std::vector<double> scale_;          ///< physical scale per state
  std::vector<double> position_step_;  ///< absolute finite-difference step (positions, angles), else 0
  int last_invalid_ = -1;
  long rhs_count_ = 0, jac_count_ = 0;
  long segment_count_ = 0;
};

}  // namespace raceway::solver
