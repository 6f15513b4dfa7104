#include "solver/numerics/petsc_runtime.hpp"

#include <fmt/format.h>
#include <petscsys.h>

#include <cstdlib>

namespace raceway::numerics {

PetscRuntime* PetscRuntime::live_ = nullptr;

/// PETSc's error handler while a runtime lives: records PETSc's message in the runtime instead of
/// printing a traceback. raceway reports errors itself, once, with the context (scene key,
/// command-line option) PETSc does not know.
struct PetscErrorRecorder {
  static PetscErrorCode record(MPI_Comm, int, const char* function, const char*, PetscErrorCode code,
                               PetscErrorType type, const char* message, void* runtime) {
    if (type == PETSC_ERROR_INITIAL) {
      std::string m = message ? message : "";
      while (!m.empty() && (m.back() == '\n' || m.back() == ' ')) m.pop_back();
      static_cast<PetscRuntime*>(runtime)->last_error_ = fmt::format(
          "{} (PETSc error {} in {})", m.empty() ? "PETSc error" : m, static_cast<int>(code), function ? function : "?");
    }
    return code;
  }
};

PetscRuntime::PetscRuntime(std::string command_line_options) {
  if (live_) throw std::logic_error("PetscRuntime: one per process");
  // PETSc's information flags are refused before PetscInitialize, which would print its help for
  // one in PETSC_OPTIONS (petsc_options.cpp, information_flag).
  const char* env = std::getenv("PETSC_OPTIONS");
  if (const std::string flag = information_flag(env ? env : ""); !flag.empty())
    throw OptionsError("PETSC_OPTIONS (environment): " + information_flag_refusal(flag));
  if (const std::string flag = information_flag(command_line_options); !flag.empty())
    throw OptionsError("--petsc-options: " + information_flag_refusal(flag));
  // raceway keeps the default crash behaviour (core dumps, sanitizers): no PETSc signal handler.
  PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr);
  // The Newton systems live on the master rank alone (solver/driver/main.cpp creates the runtime
  // there), and only the master starts PETSc: PETSc's world is this process, so its collective
  // start-up involves no other rank.
  PETSC_COMM_WORLD = MPI_COMM_SELF;
  if (PetscInitialize(nullptr, nullptr, nullptr, nullptr) != 0) throw std::runtime_error("PetscInitialize failed");
  PetscPushErrorHandler(PetscErrorRecorder::record, this);
  live_ = this;
  command_line_options_ = std::move(command_line_options);
}

PetscRuntime::~PetscRuntime() {
  live_ = nullptr;
  PetscPopErrorHandler();
  PetscFinalize();
}

bool PetscRuntime::active() { return live_ != nullptr; }

PetscRuntime& PetscRuntime::current() {
  if (!live_)
    throw std::logic_error("the petsc-bordered linear solver needs PETSc initialised: create a "
                           "numerics::PetscRuntime after MPI_Init (the raceway driver and the test mains do)");
  return *live_;
}

void PetscRuntime::check(int code, const char* what) const {
  if (code == 0) return;
  throw std::runtime_error(fmt::format("PETSc: {} failed: {}", what, last_error_));
}

}  // namespace raceway::numerics
