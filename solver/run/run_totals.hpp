// What a run accumulates over its output samples and CVODE restarts (energy, revolutions, the
// second half's means, counters, times), kept so that it survives a checkpoint and a resume: the
// summary of a resumed run is the one the uninterrupted run would have written.
#pragma once

#include <vector>

#include "io/scene/scene.hpp"
#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/numerics/integrator.hpp"
#include "solver/run/checkpoint.hpp"
#include "solver/run/run.hpp"

namespace raceway::solver {

class RunTotals {
 public:
  RunTotals(const Model& m, double end_time);

  /// One output sample: rhs at (t, z) has just filled the equations' records; `energy` at (t, z).
  void record(double t, const std::vector<double>& z, const Equations& eq, double energy);
  /// The statistics of an integrator that ends here (CVODE restarts with a new one).
  void add_finished_integrator(const IntegratorStatistics& s);

  /// Into the checkpoint's values: everything so far, `current` the running integrator's statistics.
  void save(Checkpoint& cp, const IntegratorStatistics& current, const Equations& eq,
            const scheduler::Executor& executor, double wall_seconds) const;
  /// From a checkpoint, in a new process whose equations and executor start counting now.
  void restore(const Checkpoint& cp, const Equations& eq, const scheduler::Executor& executor);

  /// The run summary at time t (the last output time reached).
  void summarize(RunSummary& sum, double t, const IntegratorStatistics& current, const Equations& eq,
                 const scheduler::Executor& executor, double wall_seconds) const;

  double revolutions() const { return revolutions_; }
  long steps(const IntegratorStatistics& current) const { return finished_.steps + current.steps; }

 private:
  const Model& m_;
  double end_;
  const io::RingSpec* drive_;
  // Over all samples.
  double energy_initial_ = 0, energy_final_ = 0, energy_max_drift_ = 0, revolutions_ = 0, last_t_ = 0;
  long samples_ = 0;
  // Over the second half.
  contact::Vec3 force_sum_ = contact::Vec3::Zero(), load_sum_ = contact::Vec3::Zero();
  double cage_sum_ = 0, epicyclic_sum_ = 0, max_element_load_ = 0;
  long half_count_ = 0;
  // Counters of the integrators that have ended, and what this process's counters start from.
  IntegratorStatistics finished_;
  double base_[6] = {0, 0, 0, 0, 0, 0};  // model rhs, model jacobian, segment evaluations, rhs s, jacobian s, wall s
};

}  // namespace raceway::solver
