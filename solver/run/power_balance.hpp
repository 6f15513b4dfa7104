// The power balance integrated over the integrator's steps (docs/output_layout.md, "Power
// balance"): the work of each input and each loss of solver/bearing/power_terms.hpp from the start
// of the run, so that over any window of output times
//
//   drive + loads + carrier frame + unbalance work = sum of the loss work + change of the stored energy.
//
// Sampled at the output times alone, the losses of short events (a ball hitting its pocket between
// two samples) are missed or overweighted; here every accepted step counts. After each accepted step
// the run loop hands over the equations as the step's last right-hand side left them (the
// integrator's own evaluation: for BDF its last Newton iterate at the step's end; nothing is
// evaluated for it); the terms at that evaluation's (t, z) are integrated by the trapezoid rule
// between consecutive evaluations. The run's first evaluation is one right-hand side at its start.
// A row at output time t is the work up to the last evaluation at or before t, plus the trapezoid
// to t with the terms interpolated linearly towards the first evaluation after t.
//
// Evaluations past an output time are held until the row that takes them, and dropped when CVODE
// restarts at the output time (a periodic checkpoint, a resume), since the restarted integration
// covers that time again; the totals so far and the last evaluation taken are in the checkpoint.
// So a resumed run writes the bits of the uninterrupted one, at any rank count.
#pragma once

#include <vector>

#include "io/h5/h5_series.hpp"
#include "io/json/summary_json.hpp"
#include "solver/bearing/power_terms.hpp"
#include "solver/run/checkpoint.hpp"

namespace raceway::run {

class PowerBalance {
 public:
  explicit PowerBalance(const bearing::Model& m);
  const bearing::PowerTerms& terms() const { return terms_; }
  /// Values in a row: the work of each term (PowerTerms order) [J].
  std::size_t row_size() const { return terms_.size(); }

  /// After an accepted step (or the start): the equations' last right-hand side.
  void observe(const bearing::Equations& eq);
  /// The integration restarts at the last row's time: evaluations after it are dropped.
  void restart();
  /// Appends the work up to output time t to `row`.
  void take_row(double t, std::vector<double>& row);

  void save(Checkpoint& cp) const;
  void restore(const Checkpoint& cp);
  /// The balance over the run: the work at the last row and the stored energy at its first and last
  /// rows (`stored_initial`, `stored_final`), each term by name, the residual and its share of the
  /// inputs' work (summary_json's "power_balance").
  json::JsonObject summary_json(double window_start, double window_end, double stored_initial, double stored_final) const;

 private:
  void take(double t, const double* p);

  bearing::PowerTerms terms_;
  std::size_t n_ = 0;
  std::vector<double> pending_t_, pending_p_;  // evaluations after the last row's time
  bool seeded_ = false;
  double last_t_ = 0;
  std::vector<double> last_p_, total_, last_row_;
};

/// The /power_balance series of the output (docs/output_layout.md): the inputs' work [T x 4], the
/// losses' work [T x L], the stored energy [T].
struct PowerBalanceSeries {
  h5::H5SeriesWriter::SeriesId input = 0, loss = 0, stored = 0;
  std::size_t inputs = 0, losses = 0;
  /// Datasets and values per sample it adds to a file (OutputEstimate).
  static constexpr int datasets = 3;
  static long values(const bearing::Model& m);
};
PowerBalanceSeries define_power_balance_series(h5::H5SeriesWriter& file, const bearing::Model& m);
/// Appends a sample: `work` (PowerBalance's row, inputs then losses) and the stored energy at
/// (t, z) from the equations' energy `energy` (the right-hand side at (t, z) just evaluated).
void append_power_balance(h5::H5SeriesWriter& file, const PowerBalanceSeries& s, const double* work,
                          const bearing::Equations& eq, double t, const double* z, double energy);

}  // namespace raceway::run
