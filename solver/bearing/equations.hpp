// Equations of motion of a bearing: dz/dt = f(t, z) (seed 000 eq. 2) and its Jacobian, assembled
// from contact segments evaluated as tasks through a scheduler::Executor. One loop for every bearing
// kind: segment results are summed in the canonical (segment) order, so the right-hand side is
// bitwise identical for any schedule; the kind's BodyDynamics turns each body's net wrench into
// rates. The Jacobian: each segment's block by finite differences of that segment alone (it
// touches two bodies), each body's own terms from its dynamics.
#pragma once

#include <memory>
#include <vector>

#include "scheduler/executor.hpp"
#include "solver/bearing/body_dynamics.hpp"
#include "solver/bearing/element_evaluation.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/segment_record.hpp"
#include "solver/numerics/bordered_matrix.hpp"
#include "solver/numerics/dynamic_system.hpp"

namespace raceway::bearing {

/// The seating's contacts (solver/bearing/ball_startup.cpp): a ball-groove segment, evaluated with
/// its ring (A) held at rest.
inline bool is_ball_groove(const Segment& seg) {
  return seg.kind == SegmentKind::ball_inner_groove || seg.kind == SegmentKind::ball_outer_groove;
}
std::pair<contact::SpatialKinematics, contact::SpatialKinematics> groove_kinematics_at_rest(const Model& m,
                                                                                           const Segment& seg,
                                                                                           double t, const double* z);

class Equations final : public numerics::DynamicSystem {
 public:
  Equations(const Model& model, scheduler::Executor& executor);
  // The task functions capture `this` (they are handed to executors): no copies, no moves.
  Equations(const Equations&) = delete;
  Equations& operator=(const Equations&) = delete;

  int state_size() const override { return model_.state_size; }
  int border_size() const override { return model_.border_size; }
  int block_count() const override { return model_.element_count; }
  int block_size() const override { return model_.block_size; }
  std::vector<double> absolute_tolerance() const override { return model_.absolute_tolerance(); }
  bool adjusts_error_weights() const override { return pocket_weight_factor_ > 1 && !pocket_segments_.empty(); }
  /// While a rolling element touches its pocket, or is within pocket_margin_ of it, the error
  /// weights of its translational velocities are multiplied by pocket_weight_factor_ (with
  /// pocket_tolerance_cage the cage's rotation rate's as well).
  void adjust_error_weights(double t, const double* z, double* ewt) const override;
  /// f(t, z). Returns 0, or 1 (recoverable) when a contact law left its valid range.
  int rhs(double t, const double* z, double* zdot) override;
  /// J = df/dz into the bordered matrix. Returns 0, or 1 (recoverable).
  int jacobian(double t, const double* z, numerics::BorderedMatrix& jac) override;
  std::string explain_state(int index) const override;
  /// The race defects' limit (race_defects.hpp: spall_step_limit).
  double step_limit(double t, const double* z) const override;
  bool limits_steps() const override;

  /// Records of the last rhs() evaluation, segment-major (SegmentRecord layout).
  const std::vector<double>& segment_records() const { return records_; }
  /// Time of the last rhs() evaluation (the records' time).
  double last_rhs_time() const { return rhs_time_; }
  /// The state of the last rhs() evaluation (state_size values).
  const double* last_rhs_state() const { return rhs_state_.data(); }
  /// The space's body dynamics.
  const BodyDynamics& dynamics() const { return *dynamics_; }
  /// A diagnostic of segment s from the last rhs(), by its position in the segment family's field table.
  double diagnostic(std::size_t s, int field) const {
    return records_[s * SegmentRecord::size + SegmentRecord::diagnostics + static_cast<std::size_t>(field)];
  }
  /// Total mechanical energy: kinetic + elastic contact + support springs + potential of the
  /// current external loads and gravity [J]. Uses the last rhs() records: call rhs(t, z) first.
  double energy(double t, const double* z) const;
  /// Net force and moment on each body from the last rhs() (contacts + loads + supports + gravity).
  const std::vector<Wrench>& body_loads() const { return net_; }
  /// Contact force and moment on each body from the last rhs() (elements only).
  const std::vector<Wrench>& contact_loads() const { return contact_.body; }
  /// d(rates of body b) / d(state) from a wrench derivative dw on b, into the Jacobian (with the
  /// rows that follow b's rates: relative coordinates).
  void add_rate_derivative(int b, int state, const double* z, const Wrench& dw, numerics::BorderedMatrix& jac) const;
  /// Adds the wrenches of the ball-groove segments with their rings at rest (the seating's force
  /// balance) to `sums` (per body), in segment order: evaluated as tasks through the executor like
  /// a right-hand side (spread over the ranks; a cut contact's parts combined as in rhs()), the
  /// same bits as contact::evaluate on rank 0. Leaves the last rhs() records as they were.
  void add_groove_loads_at_rest(double t, const double* z, std::vector<contact::SpatialWrench>& sums);
  /// Some segment is cut into parts (a heavy contact: several traction blocks).
  bool has_cut_segments() const { return cut_; }
  /// Index of the segment that most recently reported leaving its valid range, or -1.
  int last_invalid_segment() const { return last_invalid_; }

  long rhs_evaluations() const { return rhs_count_; }
  long jacobian_evaluations() const { return jac_count_; }
  long segment_evaluations() const { return segment_count_; }
  const Model& model() const { return model_; }
  scheduler::Executor& executor() { return executor_; }
  /// The tasks (one per segment, several for a segment cut into parts) with their grouping and
  /// task functions, for an executor's
  /// attach() on the master and serve() on the workers: every rank evaluates the same code.
  scheduler::TaskCatalogue task_catalogue() const;
  /// Size of a Jacobian task's record: the longest any of this model's tasks fills (an uncut
  /// element's result and columns; a cut one's part), not the longest any model could.
  int jacobian_record() const { return jacobian_record_; }

 private:
  /// Task functions: context = [t, z...] (see scheduler::TaskFunction).
  void rhs_task(std::span<const double> context, int task, std::span<double> rec) const;
  void jacobian_task(std::span<const double> context, int task, std::span<double> rec) const;
  /// Element s's Jacobian terms from its record, through its markers.
  void add_segment_jacobian(int s, const double* rec, const JacobianAssembly& assembly) const;
  /// Adds an element's record's wrenches to the loads through its markers.
  void scatter(const Segment& seg, const double* rec, double t, const double* z, Loads& loads) const;
  /// The scheduler's identity of a marker (a body with states, a node), or -1.
  int planning_id(int marker) const;
  /// Sub-task `part` of a segment cut into parts_[s] (rhs: a traction-grid block; Jacobian: every
  /// parts_[s]-th of its evaluations: the base point, then the columns).
  void rhs_part(const double* context, int s, int part, std::span<double> rec) const;
  void jacobian_part(const double* context, int s, int part, std::span<double> rec) const;
  /// Doubles at the front of part `part`'s record of cut segment s that it fills (the rest zero).
  int segment_part_record_size(scheduler::Phase phase, int s, int part) const;
  /// Master: the segment records from the tasks' records, combining each cut segment's parts in
  /// part order (the same bits for any rank count and plan).
  void combine_rhs_parts(std::vector<double>& records);
  /// A whole segment's rhs record in the seating's mode (context's last entry 1).
  void rest_task(int s, double t, const double* z, std::span<double> rec) const;
  void combine_jacobian_parts(const double* z);

  const Model& model_;
  scheduler::Executor& executor_;
  std::unique_ptr<BodyDynamics> dynamics_;
  FiniteDifferenceSteps step_;
  std::vector<double> records_, jac_records_, rest_records_;
  // [solver] pocket_tolerance_factor: the pocket segments, the factor, the margin (m) and the
  // bodies touched (scratch of adjust_error_weights, on the integrating thread).
  std::vector<int> pocket_segments_;
  double pocket_weight_factor_ = 1, pocket_margin_ = 0;
  bool pocket_cage_rate_ = false;  // [solver] pocket_tolerance_cage
  mutable std::vector<char> pocket_touched_;
  // Segments cut into sub-tasks (a ball-groove contact whose traction grid has several blocks):
  std::vector<int> parts_;       ///< per segment: its tasks (1: one task, as a whole)
  std::vector<int> first_task_;  ///< per segment: its first task; its tasks are consecutive
  std::vector<int> task_segment_;
  bool cut_ = false;             ///< some segment has more than one task
  std::vector<double> task_records_, jac_task_records_;
  std::vector<ElementShape> shapes_;  ///< per element: its Jacobian columns
  int jacobian_record_ = SegmentRecord::size;
  std::vector<std::vector<Model::RateFollower>> followers_;  ///< per body
  Loads contact_;
  std::vector<Wrench> net_;
  std::vector<int> elastic_energy_field_;  ///< per segment, in its family's field table
  /// [t, z..., mode] sent with every evaluation; mode 1: the seating's (add_groove_loads_at_rest)
  std::vector<double> context_;
  scheduler::TaskFunction rhs_task_, jacobian_task_;
  int last_invalid_ = -1;
  double rhs_time_ = 0;
  std::vector<double> rhs_state_;  ///< z of the last rhs()
  long rhs_count_ = 0, jac_count_ = 0;
  long segment_count_ = 0;
  long jacobian_segment_evaluations_ = 0;  ///< per Jacobian: base point and one per state of each segment's bodies
};

}  // namespace raceway::bearing
