#include "solver/numerics/integrator.hpp"

#include <cvode/cvode.h>
#include <fmt/format.h>
#include <nvector/nvector_serial.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <exception>

namespace raceway::solver {

namespace {

void check(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(fmt::format("CVODE set-up failed in {} (flag {})", what, flag));
}

}  // namespace

struct Integrator::Impl {
  DynamicSystem& eq;
  io::SolverSpec spec;
  SUNContext ctx = nullptr;
  void* cvode = nullptr;
  N_Vector y = nullptr;
  std::unique_ptr<NewtonLinearSystem> linear;
  BorderedMatrix scratch;  // the Jacobian is formed here, then loaded into the backend's matrix
  std::exception_ptr callback_error;
  std::string last_cvode_message;
  long steps_budget = 0;
  // Wall-clock budget ([solver] max_wall_time): checked at every right-hand side and Jacobian, so
  // a run that crawls ends within one evaluation of its budget.
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  bool out_of_wall_time = false;
  double wall_seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  }
  bool wall_time_exhausted() {
    if (spec.max_wall_time > 0 && wall_seconds() > spec.max_wall_time) out_of_wall_time = true;
    return out_of_wall_time;
  }

  Impl(DynamicSystem& e, const io::SolverSpec& s) : eq(e), spec(s) {}
  ~Impl() {
    if (cvode) CVodeFree(&cvode);
    linear.reset();
    if (y) N_VDestroy(y);
    if (ctx) SUNContext_Free(&ctx);
  }

  static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
    auto* self = static_cast<Impl*>(user);
    if (self->wall_time_exhausted()) return -1;  // unrecoverable: CVode returns, advance_to diagnoses
    try {
      return self->eq.rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
    } catch (...) {
      self->callback_error = std::current_exception();
      return -1;
    }
  }
  static int jacobian(sunrealtype t, N_Vector y, N_Vector, SUNMatrix j, void* user, N_Vector, N_Vector,
                      N_Vector) {
    auto* self = static_cast<Impl*>(user);
    if (self->wall_time_exhausted()) return -1;
    try {
      const int status = self->eq.jacobian(t, N_VGetArrayPointer(y), self->scratch);
      NewtonLinearSystem::load_jacobian(self->scratch, j);
      return status;
    } catch (...) {
      self->callback_error = std::current_exception();
      return -1;
    }
  }
  static void error_handler(int code, const char* module, const char* function, char* msg, void* user) {
    auto* self = static_cast<Impl*>(user);
    self->last_cvode_message = fmt::format("{} {} (code {}): {}", module, function, code, msg);
  }

  std::string diagnose(int flag) const;
};

Integrator::Integrator(DynamicSystem& equations, const io::SolverSpec& spec, double t0,
                       const std::vector<double>& z0)
    : impl_(std::make_unique<Impl>(equations, spec)) {
  Impl& s = *impl_;
  const auto n = static_cast<sunindextype>(z0.size());
  check(SUNContext_Create(nullptr, &s.ctx), "SUNContext_Create");
  s.y = N_VNew_Serial(n, s.ctx);
  std::copy(z0.begin(), z0.end(), N_VGetArrayPointer(s.y));
  s.cvode = CVodeCreate(spec.method == io::IntegrationMethod::bdf ? CV_BDF : CV_ADAMS, s.ctx);
  if (!s.cvode) throw std::runtime_error("CVodeCreate failed");
  check(CVodeSetErrHandlerFn(s.cvode, Impl::error_handler, &s), "CVodeSetErrHandlerFn");
  check(CVodeInit(s.cvode, Impl::rhs, t0, s.y), "CVodeInit");
  check(CVodeSetUserData(s.cvode, &s), "CVodeSetUserData");
  N_Vector atol = N_VNew_Serial(n, s.ctx);
  const auto abs_tol = equations.absolute_tolerance();
  std::copy(abs_tol.begin(), abs_tol.end(), N_VGetArrayPointer(atol));
  check(CVodeSVtolerances(s.cvode, spec.rtol, atol), "CVodeSVtolerances");
  N_VDestroy(atol);
  check(CVodeSetMaxOrd(s.cvode, spec.max_order), "CVodeSetMaxOrd");
  if (spec.max_step > 0) check(CVodeSetMaxStep(s.cvode, spec.max_step), "CVodeSetMaxStep");
  if (spec.initial_step > 0) check(CVodeSetInitStep(s.cvode, spec.initial_step), "CVodeSetInitStep");
  s.steps_budget = spec.max_steps;

  const BorderedLayout layout{equations.border_size(), equations.block_count(), equations.block_size()};
  const io::LinearSolverKind kind = resolve_linear_solver(spec.linear_solver, layout);
  // PETSc options are validated here at the latest (run_scene does it before opening the output).
  if (kind == io::LinearSolverKind::petsc_bordered) configure_petsc_options(spec, layout);
  s.scratch = BorderedMatrix(layout.border, layout.blocks, layout.block_size);
  s.linear = std::make_unique<NewtonLinearSystem>(kind, s.ctx, s.y, layout);
  check(CVodeSetLinearSolver(s.cvode, s.linear->solver(), s.linear->matrix()), "CVodeSetLinearSolver");
  check(CVodeSetJacFn(s.cvode, Impl::jacobian), "CVodeSetJacFn");
}

Integrator::~Integrator() = default;

void Integrator::advance_to(double t_out, std::vector<double>& z) {
  Impl& s = *impl_;
  long steps = 0;
  CVodeGetNumSteps(s.cvode, &steps);
  // Guard against a run that crawls: at most 200000 steps per output interval, and the scene's
  // total budget. Either ends the run with a diagnosis, never a hang.
  const long per_call = std::min<long>(200000, std::max<long>(1, s.steps_budget - steps));
  CVodeSetMaxNumSteps(s.cvode, per_call);
  sunrealtype t_reached = 0;
  const int flag = CVode(s.cvode, t_out, s.y, &t_reached, CV_NORMAL);
  if (s.callback_error) std::rethrow_exception(s.callback_error);
  if (flag < 0) throw IntegrationFailure(s.diagnose(flag));
  const sunrealtype* y = N_VGetArrayPointer(s.y);
  z.assign(y, y + N_VGetLength(s.y));
}

std::string Integrator::Impl::diagnose(int flag) const {
  sunrealtype t = 0, h_last = 0, h_cur = 0;
  CVodeGetCurrentTime(cvode, &t);
  CVodeGetLastStep(cvode, &h_last);
  CVodeGetCurrentStep(cvode, &h_cur);
  long steps = 0;
  CVodeGetNumSteps(cvode, &steps);
  char* flag_name = CVodeGetReturnFlagName(flag);  // allocated by CVODE
  const std::string flag_text =
      out_of_wall_time ? fmt::format("wall-time budget exhausted ({:.4g} s of [solver] max_wall_time = {:g} s)",
                                     wall_seconds(), spec.max_wall_time)
      : flag_name      ? flag_name
                       : "unknown flag";
  std::free(flag_name);
  std::string out = fmt::format("integration failed at t = {:.9g} s: {} after {} steps; last step {:.3g} s, "
                                "attempted step {:.3g} s",
                                t, flag_text, steps, h_last, h_cur);
  if (flag == CV_TOO_MUCH_WORK)
    out += fmt::format(" (step budget exhausted: max_steps = {} in the scene, or 200000 within one output "
                       "interval)", steps_budget);
  // The state with the largest weighted local error, and the contact loading its body the most.
  const auto n = N_VGetLength(y);
  N_Vector err = N_VClone(y), w = N_VClone(y);
  if (CVodeGetEstLocalErrors(cvode, err) == CV_SUCCESS && CVodeGetErrWeights(cvode, w) == CV_SUCCESS) {
    const double* e = N_VGetArrayPointer(err);
    const double* wt = N_VGetArrayPointer(w);
    sunindextype worst = 0;
    for (sunindextype i = 1; i < n; ++i)
      if (std::abs(e[i] * wt[i]) > std::abs(e[worst] * wt[worst])) worst = i;
    out += fmt::format("; largest weighted local error ({:.3g}) in ", std::abs(e[worst] * wt[worst]));
    out += eq.explain_state(static_cast<int>(worst));
  }
  N_VDestroy(err);
  N_VDestroy(w);
  if (!last_cvode_message.empty() && !out_of_wall_time) out += "; CVODE: " + last_cvode_message;
  if (const std::string e = linear->last_error(); !e.empty()) out += "; linear solver: " + e;
  return out;
}

IntegratorStatistics Integrator::statistics() const {
  const Impl& s = *impl_;
  IntegratorStatistics st;
  CVodeGetNumSteps(s.cvode, &st.steps);
  CVodeGetNumRhsEvals(s.cvode, &st.rhs_evaluations);
  CVodeGetNumJacEvals(s.cvode, &st.jacobian_evaluations);
  CVodeGetNumLinSolvSetups(s.cvode, &st.linear_setups);
  CVodeGetNumNonlinSolvIters(s.cvode, &st.newton_iterations);
  CVodeGetNumNonlinSolvConvFails(s.cvode, &st.newton_failures);
  CVodeGetNumErrTestFails(s.cvode, &st.error_test_failures);
  CVodeGetLastOrder(s.cvode, &st.last_order);
  CVodeGetLastStep(s.cvode, &st.last_step);
  return st;
}

}  // namespace raceway::solver
