// The PETSc options of the petsc-bordered backend: raceway's defaults, the scene's
// ([solver] petsc_options) and the command line's (--petsc-options) put into PETSc's options
// database, and checked by a trial setup + solve, so that a bad option stops the run at start-up
// with the place it came from.
#include <fmt/format.h>
#include <nvector/nvector_serial.h>
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "io/scene/scene_parser.hpp"
#include "solver/numerics/backend_factories.hpp"
#include "solver/numerics/newton_backends.hpp"
#include "solver/numerics/petsc_runtime.hpp"

namespace raceway::numerics {

namespace {

// Options raceway sets when neither the scene nor the command line does: exact block LU on split 0
// and exact LU of the explicit Schur complement, each applied once (preonly). The outer KSP and
// the fieldsplit type are set in code before KSPSetFromOptions, so options override them too.
const std::vector<std::pair<const char*, const char*>> kDefaultOptions = {
    {"-fieldsplit_0_ksp_type", "preonly"},
    {"-fieldsplit_0_pc_type", "lu"},
    {"-fieldsplit_1_ksp_type", "preonly"},
    {"-fieldsplit_1_pc_type", "lu"},
};

struct Trial {
  bool ok = false;
  std::string error;
  double residual = 0;  ///< ||M x - b|| / ||b||
  std::string description;
};

/// Sets up and solves a small well-conditioned bordered system with the database's options.
Trial trial_solve(const BorderedLayout& real) {
  Trial t;
  BorderedLayout l = real;
  l.border = std::max(real.border, 1);
  l.blocks = std::clamp(real.blocks, 1, 3);
  l.block_size = std::max(real.block_size, 1);
  BorderedMatrix j(l.border, l.blocks, l.block_size);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int r = 0; r < l.size(); ++r)
    for (int c = 0; c < l.size(); ++c) {
      const bool coupled = r < l.border || c < l.border || (r - l.border) / l.block_size == (c - l.border) / l.block_size;
      if (coupled) j.add(r, c, u(rng));
    }
  try {
    SUNContext ctx = nullptr;
    SUNContext_Create(nullptr, &ctx);
    struct Guard {
      SUNContext& c;
      ~Guard() { SUNContext_Free(&c); }
    } guard{ctx};
    N_Vector b = N_VNew_Serial(l.size(), ctx), x = N_VNew_Serial(l.size(), ctx), y = N_VNew_Serial(l.size(), ctx);
    struct Vectors {
      N_Vector a, b, c;
      ~Vectors() { N_VDestroy(a), N_VDestroy(b), N_VDestroy(c); }
    } vectors{b, x, y};
    NewtonLinearSystem sys(scene::LinearSolverKind::petsc_bordered, ctx, b, l);
    NewtonLinearSystem::load_jacobian(j, sys.matrix());
    SUNMatScaleAddI(-0.05, sys.matrix());  // I - gamma J, diagonally dominant
    if (SUNLinSolSetup(sys.solver(), sys.matrix()) != 0) {
      t.error = sys.last_error();
      return t;
    }
    for (int i = 0; i < l.size(); ++i) NV_Ith_S(b, i) = u(rng);
    if (SUNLinSolSolve(sys.solver(), sys.matrix(), x, b, 0) != 0) {
      t.error = sys.last_error();
      return t;
    }
    SUNMatMatvec(sys.matrix(), x, y);
    N_VLinearSum(1.0, y, -1.0, b, y);
    t.residual = std::sqrt(N_VDotProd(y, y) / N_VDotProd(b, b));
    if (!std::isfinite(t.residual)) {
      t.error = "the trial solve gave a non-finite solution";
      return t;
    }
    t.description = backend::describe_petsc_bordered(sys.solver());
    t.ok = true;
  } catch (const std::exception& e) {
    t.error = e.what();
  }
  return t;
}

/// PETSc's own diagnostic options (profiling, memory, option reports): read by PETSc itself, at
/// start-up or PetscFinalize, never by the solver, so the unused-option check lets them pass.
bool petsc_diagnostic_option(const std::string& name) {
  for (const char* prefix : {"-log_", "-info", "-options_", "-malloc", "-memory_view", "-on_error_", "-fp_trap",
                             "-no_signal_handler", "-check_pointer_intensity", "-history", "-objects_dump"})
    if (name.rfind(prefix, 0) == 0) return true;
  return false;
}


/// Names of options nobody read, apart from raceway's own defaults and PETSc's diagnostics.
std::vector<std::string> unused_options(const std::vector<std::string>& ignore) {
  PetscInt n = 0;
  char** names = nullptr;
  char** values = nullptr;
  std::vector<std::string> out;
  if (PetscOptionsLeftGet(nullptr, &n, &names, &values) != 0) return out;
  for (PetscInt i = 0; i < n; ++i) {
    const std::string name = std::string("-") + names[i];
    if (std::find(ignore.begin(), ignore.end(), name) != ignore.end()) continue;
    if (petsc_diagnostic_option(name)) continue;
    out.push_back(values[i] ? name + " " + values[i] : name);
  }
  PetscOptionsLeftRestore(nullptr, &n, &names, &values);
  return out;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

}  // namespace

// PETSc's information flags: -help (-h) prints every option of every object the solver creates
// (434 lines for the bordered solver) and PETSc then carries on; -version prints PETSc's version.
// Neither is a solver option: they are refused with a short answer rather than passed on (the
// options that matter are named in README.md, "PETSc options"; -ksp_view shows the solver built).
std::string information_flag(const std::string& options) {
  std::istringstream words(options);
  for (std::string word; words >> word;)
    if (word == "-help" || word == "-h" || word == "--help" || word == "-version" || word == "--version")
      return word;
  return "";
}

std::string information_flag_refusal(const std::string& flag) {
  return fmt::format("'{}' is PETSc's information flag, not a solver option, and is not passed on (it prints "
                     "hundreds of lines of every PETSc object's options); the bordered solver reads the KSP and PC "
                     "options of its splits (-fieldsplit_0_..., -fieldsplit_1_...: README.md, \"PETSc options\"), "
                     "and -ksp_view shows the solver it builds",
                     flag);
}

std::string PetscRuntime::configure_options(const scene::SolverSpec& spec, const BorderedLayout& layout) {
  // PETSC_OPTIONS from the environment, as PETSc reads it: the lowest priority (the scene and the
  // command line override it). PetscOptionsClear below drops what PetscInitialize read, so it is
  // put back first; PETSc's diagnostics in it (-log_view) then reach PetscFinalize.
  const char* env = std::getenv("PETSC_OPTIONS");
  const std::string env_options = env ? env : "";
  const std::string key = fmt::format("{}\n{}\n{}\n{} {} {}", env_options, spec.petsc_options, command_line_options_,
                                      layout.border, layout.block_size, layout.blocks > 0);
  if (key == applied_key_) return applied_summary_;
  applied_key_.clear();
  check(PetscOptionsClear(nullptr), "PetscOptionsClear");
  std::vector<std::string> defaults_set;

  // One stage per source, so that an error names where the bad option came from.
  auto stage = [&](const std::string& options, auto&& fail) {
    clear_last_error();
    if (const std::string flag = information_flag(options); !flag.empty()) fail(information_flag_refusal(flag));
    if (!options.empty() && PetscOptionsInsertString(nullptr, options.c_str()) != 0)
      fail(fmt::format("cannot parse the PETSc options \"{}\": {}", options, last_error_));
    for (const auto& [name, value] : kDefaultOptions) {
      PetscBool set = PETSC_FALSE;
      PetscOptionsHasName(nullptr, nullptr, name, &set);
      if (!set) {
        PetscOptionsSetValue(nullptr, name, value);
        defaults_set.emplace_back(name);
      }
    }
    const Trial t = trial_solve(layout);
    if (!t.ok)
      fail(fmt::format("PETSc options \"{}\" give no working bordered solver (trial setup and solve): {}", options,
                       t.error.empty() ? "unknown PETSc error" : t.error));
    const auto left = unused_options(defaults_set);
    if (!left.empty())
      fail(fmt::format("PETSc option(s) not used by the bordered solver (misspelt, or for a part it does not have): "
                       "{}; the solver built: {}",
                       join(left), t.description));
    return t;
  };
  if (!env_options.empty())
    stage(env_options, [&](const std::string& reason) {
      PetscOptionsClear(nullptr);
      throw OptionsError("PETSC_OPTIONS (environment): " + reason);
    });
  Trial t = stage(spec.petsc_options, [&](const std::string& reason) {
    PetscOptionsClear(nullptr);
    throw scene::SceneError(spec.petsc_options_file.empty() ? "<scene>" : spec.petsc_options_file,
                         spec.petsc_options_line, "solver.petsc_options", reason);
  });
  if (!command_line_options_.empty())
    t = stage(command_line_options_, [&](const std::string& reason) {
      PetscOptionsClear(nullptr);
      throw OptionsError("--petsc-options: " + reason);
    });
  applied_summary_ = fmt::format("{}; trial relative residual {:.1e}{}", t.description, t.residual,
                                 t.residual > 1e-10 ? " (an inexact solve: CVODE's Newton iteration will need more "
                                                      "iterations, or fail to converge)"
                                                    : "");
  applied_key_ = key;
  return applied_summary_;
}

std::string configure_petsc_options(const scene::SolverSpec& spec, const BorderedLayout& layout) {
  return PetscRuntime::current().configure_options(spec, layout);
}

}  // namespace raceway::numerics
