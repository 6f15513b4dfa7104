// PETSc's lifetime in a raceway process and the state that goes with it: the PETSc options given on
// the command line, the message of the last PETSc error, and which options are in PETSc's options
// database (so that an unchanged configuration is not validated twice).
//
// PETSc is process-wide: one PetscInitialize per process, one options database, one stack of error
// handlers. The PetscRuntime object mirrors that: one per process, created by whoever initialises
// PETSc (the driver, the test mains, the benchmark) and owning all of the state above. The only
// process-wide variable is the pointer to the live runtime (PetscRuntime::current()), so that the
// petsc-bordered backend, created deep inside a run, finds it without the runtime being threaded
// through the bearing and run layers.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

#include "io/scene/scene.hpp"
#include "solver/numerics/bordered_matrix.hpp"

namespace raceway::numerics {

/// Bad PETSc options given on the command line (--petsc-options): exit code 2, like a bad scene.
/// Bad options from the scene are scene::SceneError naming the file, line and key solver.petsc_options.
class OptionsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The first of PETSc's information flags (-help, -h, -version) among `options`, or "": they are not
/// solver options and are refused (information_flag_refusal) rather than passed on to PETSc.
std::string information_flag(const std::string& options);
/// Why `flag` is refused and which options matter instead, for an OptionsError or a SceneError.
std::string information_flag_refusal(const std::string& flag);

struct PetscErrorRecorder;

/// PETSc for the lifetime of the object. Create it after MPI_Init (PETSc then leaves MPI_Finalize to
/// the caller) and before any petsc-bordered solver; destroy it before MPI_Finalize. One per process.
/// PETSc's own argv parsing is not used: options come from the scene ([solver] petsc_options) and
/// from `command_line_options` (raceway run --petsc-options "..."), which override the scene's.
class PetscRuntime {
 public:
  /// Throws OptionsError when PETSC_OPTIONS or `command_line_options` hold an information flag.
  explicit PetscRuntime(std::string command_line_options = "");
  ~PetscRuntime();
  PetscRuntime(const PetscRuntime&) = delete;
  PetscRuntime& operator=(const PetscRuntime&) = delete;

  /// Whether a PetscRuntime exists.
  static bool active();
  /// The live runtime; throws std::logic_error if there is none.
  static PetscRuntime& current();

  const std::string& command_line_options() const { return command_line_options_; }
  /// Replaces the command-line options (tests).
  void set_command_line_options(std::string options) { command_line_options_ = std::move(options); }

  /// See configure_petsc_options (solver/numerics/newton_backends.hpp).
  std::string configure_options(const scene::SolverSpec& spec, const BorderedLayout& layout);

  /// First line of the last PETSc error since clear_last_error(), with PETSc's code and function.
  const std::string& last_error() const { return last_error_; }
  void clear_last_error() { last_error_.clear(); }
  /// Throws std::runtime_error naming `what` and PETSc's message when `code` (a PetscErrorCode) is
  /// an error.
  void check(int code, const char* what) const;

 private:
  friend struct PetscErrorRecorder;  // PETSc's error handler, which fills last_error_

  static PetscRuntime* live_;  ///< the one runtime of this process, or nullptr (see the top of the file)
  std::string command_line_options_;
  std::string last_error_;
  std::string applied_key_;  ///< the options now in PETSc's database and the layout they were tried on
  std::string applied_summary_;  ///< what configure_options said for them
};

}  // namespace raceway::numerics
