// One simulation from a validated scene to an output file and a summary: model, start-up state,
// CVODE, output at fixed times by interpolation. No MPI here: the run driver (solver/driver) owns it.
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/h5/shared_rows.hpp"
#include "io/scene/scene.hpp"
#include "io/json/summary_json.hpp"
#include "scheduler/executor.hpp"
#include "solver/numerics/integrator.hpp"
#include "solver/run/run_profile.hpp"

namespace raceway::run {

struct Progress {
  double time = 0, end_time = 0;  ///< s
  double revolutions = 0;         ///< of the driven ring
  double wall_seconds = 0;
  long steps = 0;
};

/// The parallel output (docs/output_layout.md, "Who writes"), given by the driver when the run has
/// more ranks and --parallel-output: the segment diagnostics are written by the ranks that
/// evaluated them, every rank taking part in their writes (io/h5/h5_parallel.hpp).
class SharedOutput {
 public:
  virtual ~SharedOutput() = default;
  /// Right after the right-hand side at output sample `sample`: the other ranks keep the
  /// diagnostics of their segments for the file. Returns each segment's rank in that evaluation.
  virtual const std::vector<int>& sample(long sample) = 0;
  /// The collective write of the shared series' rows of `file` (h5::write_shared_rows on every
  /// rank); throws std::runtime_error naming the failure.
  virtual void write(const std::string& file, std::vector<h5::SharedRows>& rows) = 0;
};

struct RunOptions {
  std::string output_path = "raceway.h5";
  std::function<void(const Progress&)> on_progress;  ///< called after every output time
  std::function<void(const std::string&)> on_info;   ///< start-up and model messages
  double azimuth_offset = 0;  ///< spatial: ball set and cage turned about z at start (tests of frame invariance)
  /// Evaluates the contact tasks (not owned). nullptr: a serial executor on this process. The run
  /// attach()es the equations' task catalogue to it and writes its schedule_log() to /scheduler.
  scheduler::Executor* executor = nullptr;
  /// Write the scheduler's log (/scheduler) also when one rank ran (with P > 1 it is always written).
  bool scheduler_log = false;
  /// The MPI library's version text (MPI_Get_library_version) for the build attributes; "" without MPI.
  std::string mpi_library;
  /// Continue OUT.h5.partial from its checkpoint OUT.h5.checkpoint (docs/output_layout.md): refused
  /// (ResumeRefused) when the scene, the build or result_options differ; a fresh run, said so
  /// through on_info, when there is no checkpoint.
  bool resume = false;
  /// Command-line options that change the results (e.g. PETSc options), part of a checkpoint's
  /// fingerprint.
  std::string result_options;
  /// Set to a signal number (stop_signals.hpp: stop_request): the run writes a checkpoint at the
  /// next output time, flushes and closes the output and throws RunInterrupted.
  const std::atomic<int>* stop_signal = nullptr;
  /// Parallel output (not owned); nullptr: rank 0 writes the whole file (serial output).
  SharedOutput* shared_output = nullptr;
  /// The output's work at output times on a thread of its own (serial output only): worth it only
  /// when that thread has a core to itself (the driver decides: output_thread_wanted). Off: on the
  /// run's thread, the diagnostics through the run's executor. The same bits either way.
  bool output_thread = true;
  /// The logical CPU the output thread and the chunk compressor are bound to (a core no rank of the
  /// job is bound to: the driver finds it); -1: they run wherever the process may.
  int output_thread_core = -1;
};

/// A run stopped by a signal after writing a checkpoint (continue it with --resume).
class RunInterrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RunSummary {
  double simulated_time_s = 0, wall_time_s = 0;
  numerics::IntegratorStatistics stats;
  long model_rhs_evaluations = 0, model_jacobian_evaluations = 0, segment_evaluations = 0;
  double rhs_seconds = 0, jacobian_seconds = 0;  ///< task time inside segment evaluations
  /// Wall time of the output on the run's thread: handing the samples to the output thread (or, with
  /// the parallel output, the diagnostics at output times and writing), checkpoints, the commit.
  double output_seconds = 0;
  /// Of output_seconds, all but the right-hand sides at output times (sampling, appending, filtering,
  /// flushes, checkpoints, the commit): what the writer costs rank 0.
  double output_write_seconds = 0;
  /// Wall time the output thread worked (the right-hand sides at output times, appending, flushes
  /// there), beside the run's thread; 0 when the run's thread writes (the parallel output).
  double output_thread_seconds = 0;
  double cage_speed_rpm = 0;            ///< mean over the second half of the run
  double epicyclic_cage_speed_rpm = 0;  ///< mean over the same samples, at the nominal contact angle
  double rolling_cage_speed_rpm = 0;    ///< the same at the loaded contact angle (/cage/rolling_speed)
  double cage_slip = 0;                 ///< 1 - cage / rolling (the loaded contact angle)
  double driven_ring_revolutions = 0;
  std::vector<double> inner_ring_contact_force_n;  ///< mean over the second half, from the rolling elements
  std::vector<double> inner_ring_load_n;           ///< applied, mean over the same samples
  double max_ball_load_n = 0;       ///< spatial: largest inner-groove ball (or roller: its slices) load, second half
  bool spatial_rollers = false;     ///< a spatial roller bearing: the summary says max_roller_load_n
  std::string model_kind = "planar";
  double energy_initial_j = 0, energy_final_j = 0, energy_max_drift_j = 0;
  int output_samples = 0;
  std::string method;                        ///< the integrator's method ("CVODE BDF", ...)
  /// BDF's largest order: "fixed: max_order = 5", or the automatic choice's account (order_choice.hpp).
  std::string order_choice;
  std::vector<StateClassShare> step_limiting;  ///< which states limit the step, largest share first
  numerics::IntegratorTiming timing;                   ///< where the integrator's time went
  /// The scene's keys set on the command line ("key": "value as given") and its resolved
  /// parameters ("key": {"value": SI value or word, "unit": SI unit}): scene_summary.hpp.
  json::JsonObject scene_overrides, scene_parameters;
  /// The step-resolved pocket statistics' run totals (solver/run/pocket_steps.hpp); empty without pockets.
  json::JsonObject pocket_step_totals;
  /// The power balance over the run (solver/run/power_balance.hpp): work of each input and loss,
  /// the stored energy's change, the residual.
  json::JsonObject power_balance;
  /// With a thermal network: each part's temperature at the end [K].
  json::JsonObject thermal;
  /// Signs that the run ended far from any physical running regime (regime_warnings()), by name:
  /// printed as warnings at the end and kept in the summary's "warnings".
  std::vector<std::pair<std::string, std::string>> warnings;
  json::JsonObject to_json() const;
};

/// Cage slip (1 - cage / epicyclic speed, second half) at or beyond which a run is said to have
/// ended far from a bearing's running regime: the cage hardly follows the rolling elements.
inline constexpr double kCageSlipFarFromRolling = 0.8;

/// The signs in `sum` that the run ended far from any physical regime ("cage_slip": |slip| at or
/// above kCageSlipFarFromRolling with the ring turning; "energy": a non-finite energy), each with a
/// sentence naming what to check; empty for a run in a plausible regime.
std::vector<std::pair<std::string, std::string>> regime_warnings(const RunSummary& sum);

/// The output's share of the run on the run's thread above which output_share_note() speaks.
inline constexpr double kOutputShareToMention = 0.05;

/// A line for the end of a run whose output took more than kOutputShareToMention of its wall time
/// on the run's thread (output_seconds of wall_time_s), naming what makes it smaller: fewer samples
/// ([scene] output_interval) or no segment diagnostics ([output] segments = false); "" otherwise.
std::string output_share_note(const RunSummary& sum);

/// Runs the scene and writes `options.output_path` (via a .partial file: an existing output is
/// replaced only when the run ends), with checkpoints (solver/run/checkpoint.hpp) as the scene's
/// [output] section asks. On an integration failure the partial output is kept as OUT.h5.partial
/// and IntegrationFailure is rethrown with its diagnosis. A bad output path throws
/// h5::OutputPathError, a refused resume ResumeRefused, a stop by a signal RunInterrupted.
RunSummary run_scene(const scene::Scene& scene, const RunOptions& options);

/// The worker side of a run: builds the same model and equations as run_scene does on the
/// master and hands their task catalogue to `serve` (which evaluates tasks until the master stops
/// it, e.g. scheduler::MpiExecutor::serve) with the layout's segment series (segment_series(), for
/// the parallel output's worker side). No integration.
struct SegmentSeries;
void serve_scene(const scene::Scene& scene,
                 const std::function<void(const scheduler::TaskCatalogue&, const std::map<std::string, SegmentSeries>&)>& serve);

}  // namespace raceway::run
