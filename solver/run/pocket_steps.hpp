// Step-resolved pocket-contact statistics (docs/output_layout.md, "Pocket contacts at step
// resolution"): the pocket contacts observed at every accepted integrator step, not only at the
// output times, so that their events, peaks and impulses do not depend on the sampling.
//
// After each accepted step the run loop hands over the segment records of the step's last
// right-hand side (the integrator's own evaluation: its last Newton iterate or stage, at that
// evaluation's time; nothing is evaluated for it). Per pocket and side the pocket's normal forces
// on that side are summed (spatial ball_pocket segments: side 0 where the cage's circumferential
// force on the ball is negative, i.e. the bar ahead in +z, side 1 otherwise; planar: side 0 the
// cage_bar_front segment, side 1 cage_bar_rear). Between consecutive evaluations (t_a, F_a),
// (t_b, F_b) the statistics of the output interval holding t_b gain: an onset if F_a = 0 < F_b,
// the peak max(F_b), the impulse (F_a + F_b) (t_b - t_a) / 2 and the contact time
// ([F_a > 0] + [F_b > 0]) (t_b - t_a) / 2 (the trapezoid rule of the report's sampled statistics).
//
// The last step towards an output time may end past it; its evaluation is held until the row it
// belongs to is taken, and dropped when CVODE restarts at the output time (a periodic checkpoint,
// a resume), since the restarted integration covers that time again. So every evaluation is taken
// in step order, once, whatever the output interval: the run's totals are the same bits at any
// sampling with the same steps, and at any rank count (the records are summed on rank 0 in
// canonical order).
#pragma once

#include <vector>

#include "io/json/summary_json.hpp"
#include "solver/bearing/model.hpp"
#include "solver/run/checkpoint.hpp"

namespace raceway::run {

class PocketSteps {
 public:
  static constexpr int sides = 2;
  /// The statistics of a row, in this order, each [pockets x sides].
  static constexpr int quantities = 4;  // onsets, peak force, impulse, contact time

  explicit PocketSteps(const bearing::Model& m);
  /// The model has pocket contacts (ball_pocket or cage bar segments).
  bool active() const { return !columns_.empty(); }
  int pockets() const { return pockets_; }

  /// After an accepted step: `records` (Equations::segment_records()) of the right-hand side at t.
  void observe(double t, const std::vector<double>& records);
  /// The integration restarts at the last row's time: evaluations after it are dropped.
  void restart();
  /// The statistics of the output interval ending at t (the evaluations up to t not yet taken)
  /// into `row` (quantities x pockets x sides), then a new interval begins.
  void take_row(double t, std::vector<double>& row);

  /// What a resume needs (the last evaluation taken, the totals) into / from the checkpoint's values.
  void save(Checkpoint& cp) const;
  void restore(const Checkpoint& cp);
  /// The run's totals per side: onsets, peak force, impulse, contact time (summary_json).
  json::JsonObject totals_json() const;

 private:
  struct Column {
    int segment;
    int pocket;
    int side;  ///< 0 or 1; -1: by the sign of the circumferential force (spatial)
  };
  void sum_forces(const std::vector<double>& records, double* force) const;
  void take(double t, const double* force);

  std::vector<Column> columns_;
  int pockets_ = 0;
  std::size_t cells_ = 0;  ///< pockets x sides
  // Evaluations after the last row's time, not taken yet: times, forces (cells_ each).
  std::vector<double> pending_t_, pending_force_;
  // The last evaluation taken.
  bool seeded_ = false;
  double last_t_ = 0;
  std::vector<double> last_force_;
  // The current interval: onsets, peak, impulse, contact time (cells_ each, in that order).
  std::vector<double> interval_;
  // The run's totals per side, in step order.
  double total_[quantities][sides] = {};
};

}  // namespace raceway::run
