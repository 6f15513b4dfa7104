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

namespace raceway::run {

class RunTotals {
 public:
  RunTotals(const bearing::Model& m, double end_time);

  /// Counts the evaluations of a second set of equations with the run's (the right-hand sides at
  /// output times on the output thread, solver/run/output_thread.hpp): set before restore().
  void count_also(const bearing::Equations& eq, const scheduler::Executor& executor) { also_eq_ = &eq, also_executor_ = &executor; }

  /// The driven ring's turns up to output time t (called for every output time, in order).
  void turn_to(double t);
  /// One output sample: rhs at (t, z) has just filled the equations' records; `energy` at (t, z).
  /// It touches none of what turn_to() does: the two may run on different threads.
  void record(double t, const std::vector<double>& z, const bearing::Equations& eq, double energy);
  /// The statistics of an integrator that ends here (CVODE restarts with a new one).
  void add_finished_integrator(const numerics::IntegratorStatistics& s);

  /// Into the checkpoint's values: everything so far, `current` the running integrator's statistics.
  void save(Checkpoint& cp, const numerics::IntegratorStatistics& current, const bearing::Equations& eq,
            const scheduler::Executor& executor, double wall_seconds) const;
  /// From a checkpoint, in a new process whose equations and executor start counting now.
  void restore(const Checkpoint& cp, const bearing::Equations& eq, const scheduler::Executor& executor);

  /// The run summary at time t (the last output time reached).
  void summarize(RunSummary& sum, double t, const numerics::IntegratorStatistics& current, const bearing::Equations& eq,
                 const scheduler::Executor& executor, double wall_seconds) const;

  double revolutions() const { return revolutions_; }
  /// The stored energy (bearing::PowerTerms::stored_energy) at the first and the last sample [J].
  double stored_energy_initial() const { return stored_initial_; }
  double stored_energy_final() const { return stored_final_; }
  long steps(const numerics::IntegratorStatistics& current) const { return finished_.steps + current.steps; }

 private:
  const bearing::Model& m_;
  double end_;
  const scene::RingSpec* drive_;
  // Over all samples.
  double energy_initial_ = 0, energy_final_ = 0, energy_max_drift_ = 0;
  double stored_initial_ = 0, stored_final_ = 0;
  long samples_ = 0;
  // Of turn_to().
  double revolutions_ = 0, last_t_ = 0;
  bool turned_ = false;
  // Over the second half.
  contact::Vec3 force_sum_ = contact::Vec3::Zero(), load_sum_ = contact::Vec3::Zero();
  double cage_sum_ = 0, epicyclic_sum_ = 0, rolling_sum_ = 0, max_element_load_ = 0;
  long half_count_ = 0;
  // Counters of the integrators that have ended, and what this process's counters start from.
  numerics::IntegratorStatistics finished_;
  double base_[6] = {0, 0, 0, 0, 0, 0};  // model rhs, model jacobian, segment evaluations, rhs s, jacobian s, wall s
  const bearing::Equations* also_eq_ = nullptr;
  const scheduler::Executor* also_executor_ = nullptr;
  void process_counts(const bearing::Equations& eq, const scheduler::Executor& executor, double wall, double out[6]) const;
};

}  // namespace raceway::run
