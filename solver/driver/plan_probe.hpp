// `raceway plan` for a scene the fidelity table has not measured: a short probe run of the scene
// itself, at its own settings, measures what one simulated second costs (CPU time, steps,
// revolutions), and the effect of each modelling choice is transferred from the reference scene of
// the table whose measured options apply to this scene: each option's cost ratio times the probe's
// cost, its changes as measured there.
#pragma once

#include <string>
#include <vector>

#include "io/scene/scene.hpp"
#include "solver/driver/plan_command.hpp"

namespace raceway::driver {

/// The probe's length of simulated time unless --probe-time says otherwise: a few ms, the second
/// half of which (after the start-up's transient and CVODE's first, smallest steps) gives the rates.
inline constexpr double kDefaultProbeSeconds = 0.01;

/// What the probe run measured, one rank, the output thread off (as the fidelity table's runs).
struct Probe {
  double simulated_s = 0;      ///< the probe's end time
  double window_start_s = 0;   ///< the rates are over [window_start_s, simulated_s]
  double cpu_s = 0;            ///< CPU time (process: every thread) of the whole probe, start-up included
  double cpu_at_window_s = 0;  ///< ... up to the window's start (start-up, the first steps)
  long steps = 0, steps_at_window = 0;
  double revolutions = 0, revolutions_at_window = 0;  ///< of the driven ring
  std::string method;                                 ///< the integrator's method as run

  double window_s() const { return simulated_s - window_start_s; }
  double cpu_per_second() const { return (cpu_s - cpu_at_window_s) / window_s(); }
  double steps_per_second() const { return static_cast<double>(steps - steps_at_window) / window_s(); }
  double revolutions_per_second() const { return (revolutions - revolutions_at_window) / window_s(); }
  /// CPU seconds and steps predicted for a run to END_TIME: the probe up to the window's start, then
  /// the window's rates.
  double predicted_cpu_s(double end_time) const { return cpu_at_window_s + cpu_per_second() * (end_time - window_start_s); }
  double predicted_steps(double end_time) const {
    return static_cast<double>(steps_at_window) + steps_per_second() * (end_time - window_start_s);
  }
};

/// Runs SCENE for min(PROBE_SECONDS, its end time) of simulated time (at least two output
/// intervals, so the window has a start) into a temporary folder that is removed afterwards.
/// Integration failures propagate (numerics::IntegrationFailure: the scene does not run).
Probe probe_scene(const scene::Scene& scene, double probe_seconds);

/// The rows of one reference scene of the fidelity table transferred to another scene.
struct Transfer {
  std::string reference;               ///< the reference scene's name; empty when no scene applies
  std::vector<FidelityRow> rows;       ///< its rows whose overrides apply to the scene and change it
  std::vector<std::string> reasons;    ///< per table scene: how many of its options apply, and the choice
};

/// The table scene whose measured options (rows with overrides, reference rows aside) apply to most
/// of SCENE_PATH's settings (with OVERRIDES): an option applies when the scene with its overrides
/// is valid and differs from the scene (an option that is the scene's own setting does not). Ties go
/// to the table's first. Its applicable rows, the reference rows and the measured combinations
/// whose overrides all apply, are the transfer.
Transfer transfer_from_table(const std::string& scene_path, const std::vector<std::string>& overrides,
                             const std::vector<FidelityRow>& table);

}  // namespace raceway::driver
