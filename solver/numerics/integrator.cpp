#include "solver/numerics/integrator.hpp"

#include <fmt/format.h>
#include <nvector/nvector_serial.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>

#include "solver/numerics/time_stepper.hpp"
#include "solver/numerics/timed_linear_solver.hpp"

namespace raceway::numerics {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// Adds the time of the enclosing scope to a counter.
class ScopedTimer {
 public:
  explicit ScopedTimer(double& seconds) : seconds_(seconds), start_(Clock::now()) {}
  ~ScopedTimer() { seconds_ += seconds_since(start_); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double& seconds_;
  Clock::time_point start_;
};

bool implicit_method(scene::IntegrationMethod m) { return m != scene::IntegrationMethod::erk; }

/// A serial vector's clone, filled with zeros. CVODE allocates its history (the Nordsieck array
/// zn) by cloning the state vector and reads one entry before it writes it: when the largest order
/// is raised without a restart (the automatic order's probe of order 5 after a run at order 2),
/// its estimate of the step at order q+1 (cvComputeEtaqp1) subtracts zn[qmax], the corrector saved
/// at the previous qmax, which no step has written since. Read uninitialised, that value was
/// whatever the heap held, and runs whose heap history differed (the collective output's
/// allocations) took different orders and left each other partway. Zeros make that first estimate
/// a fixed function of the step (the corrector's own norm), the same in every run.
N_Vector clone_zeroed(N_Vector w) {
  N_Vector v = N_VClone_Serial(w);  // copies w's operations, this one included: clones of clones too
  if (v != nullptr) N_VConst_Serial(0.0, v);
  return v;
}

}  // namespace

struct Integrator::Impl {
  DynamicSystem& eq;
  scene::SolverSpec spec;
  SUNContext ctx = nullptr;
  N_Vector y = nullptr;
  N_Vector error = nullptr, weights = nullptr;  // scratch for the step-limiting accounting
  std::unique_ptr<NewtonLinearSystem> linear;
  SUNLinearSolver timed_solver = nullptr;  // wraps linear->solver() to time it
  std::unique_ptr<stepping::TimeStepper> stepper;
  BorderedMatrix scratch;  // the Jacobian is formed here, then loaded into the backend's matrix
  std::exception_ptr callback_error;
  std::function<void()> step_observer;
  std::string last_message;
  long steps_budget = 0;
  StepLimitingStates limiting;
  IntegratorTiming timing;
  // The error weights' pieces (error_weights below), when the system adjusts them.
  std::vector<double> atol;
  double t0 = 0;
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

  // The physics' step limit (DynamicSystem::step_limit), from the state where the step starts.
  bool limits_steps = false;
  N_Vector at_start = nullptr;
  bool stepped = false;  // before the first step y is the start state (there is no interpolant yet)
  void limit_next_step() {
    const double t = stepper->time();
    if (!at_start) at_start = N_VClone(y);
    if (!stepped)
      N_VScale(1.0, y, at_start);
    else if (stepper->interpolate(t, at_start) < 0)
      return;
    const double h = eq.step_limit(t, N_VGetArrayPointer(at_start));
    if (h > 0 && std::isfinite(h)) stepping::check(stepper->stop_at(t + h), "the step limit's stop time");
  }

  Impl(DynamicSystem& e, const scene::SolverSpec& s) : eq(e), spec(s) {}
  ~Impl() {
    stepper.reset();
    if (timed_solver) SUNLinSolFree(timed_solver);
    linear.reset();
    for (N_Vector v : {y, error, weights, at_start})
      if (v) N_VDestroy(v);
    if (ctx) SUNContext_Free(&ctx);
  }

  static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
    auto* self = static_cast<Impl*>(user);
    if (self->wall_time_exhausted()) return -1;  // unrecoverable: the step returns, advance_to diagnoses
    ScopedTimer timer(self->timing.rhs);
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
    ScopedTimer timer(self->timing.jacobian);
    try {
      const int status = self->eq.jacobian(t, N_VGetArrayPointer(y), self->scratch);
      NewtonLinearSystem::load_jacobian(self->scratch, j);
      return status;
    } catch (...) {
      self->callback_error = std::current_exception();
      return -1;
    }
  }
  /// 1 / (rtol |y_i| + atol_i), SUNDIALS' own weights (the same operations, so the same bits),
  /// then the system's adjustment (DynamicSystem::adjust_error_weights).
  static int error_weights(N_Vector y, N_Vector ewt, void* user) {
    auto* self = static_cast<Impl*>(user);
    const double* v = N_VGetArrayPointer(y);
    double* w = N_VGetArrayPointer(ewt);
    const double rtol = self->spec.rtol;
    for (std::size_t i = 0; i < self->atol.size(); ++i) {
      const double tolerance = rtol * std::abs(v[i]) + self->atol[i];
      if (!(tolerance > 0)) return -1;
      w[i] = 1.0 / tolerance;
    }
    try {
      self->eq.adjust_error_weights(self->stepper ? self->stepper->time() : self->t0, v, w);
    } catch (...) {
      self->callback_error = std::current_exception();
      return -1;
    }
    return 0;
  }
  static void error_handler(int code, const char* module, const char* function, char* msg, void* user) {
    auto* self = static_cast<Impl*>(user);
    self->last_message = fmt::format("{} {} (code {}): {}", module, function, code, msg);
  }

  // The automatic order ([solver] automatic_order): the choice (not owned), the order applied, the
  // counters of the methods restarted by lowering it, the work counted so far.
  OrderChoice* choice = nullptr;
  int applied_order = 0;
  IntegratorStatistics carried;
  long counted_rhs = 0, counted_jacobians = 0;
  IntegratorStatistics totals() const;
  void apply_order(int order);
  void follow_order_choice(double t);

  void record_step_error();
  std::string diagnose(int flag, bool budget_exhausted) const;
};

Integrator::Integrator(DynamicSystem& equations, const scene::SolverSpec& spec, double t0,
                       const std::vector<double>& z0)
    : impl_(std::make_unique<Impl>(equations, spec)) {
  Impl& s = *impl_;
  const auto n = static_cast<sunindextype>(z0.size());
  stepping::check(SUNContext_Create(nullptr, &s.ctx), "SUNContext_Create");
  s.y = N_VNew_Serial(n, s.ctx);
  s.y->ops->nvclone = clone_zeroed;
  std::copy(z0.begin(), z0.end(), N_VGetArrayPointer(s.y));
  s.error = N_VClone(s.y);
  s.weights = N_VClone(s.y);
  s.limits_steps = equations.limits_steps();
  N_Vector atol = N_VNew_Serial(n, s.ctx);
  const auto abs_tol = equations.absolute_tolerance();
  std::copy(abs_tol.begin(), abs_tol.end(), N_VGetArrayPointer(atol));
  s.atol = abs_tol;
  s.t0 = t0;
  const bool adjusts = equations.adjusts_error_weights();
  s.steps_budget = spec.max_steps;
  s.limiting.share_sum.assign(z0.size(), 0.0);
  s.limiting.largest.assign(z0.size(), 0);
  s.limiting.weighted_error_sum.assign(z0.size(), 0.0);

  if (implicit_method(spec.method)) {
    const BorderedLayout layout{equations.border_size(), equations.block_count(), equations.block_size()};
    const scene::LinearSolverKind kind = resolve_linear_solver(spec.linear_solver, layout);
    // PETSc options are validated here at the latest (run_scene does it before opening the output).
    if (kind == scene::LinearSolverKind::petsc_bordered) configure_petsc_options(spec, layout);
    s.scratch = BorderedMatrix(layout.border, layout.blocks, layout.block_size);
    s.linear = std::make_unique<NewtonLinearSystem>(kind, s.ctx, s.y, layout);
    s.timed_solver = backend::make_timed_solver(s.ctx, s.linear->solver(), &s.timing.linear_setup,
                                                &s.timing.linear_solve);
  }
  const stepping::StepperSetup setup{spec, s.ctx, s.y, t0, atol,
                                     {Impl::rhs, Impl::jacobian, Impl::error_handler, adjusts ? Impl::error_weights : nullptr, &s},
                                     s.linear.get(), s.timed_solver};
  try {
    s.stepper = spec.method == scene::IntegrationMethod::bdf || spec.method == scene::IntegrationMethod::adams
                    ? stepping::make_cvode_stepper(setup)
                    : stepping::make_arkode_stepper(setup);
  } catch (...) {
    N_VDestroy(atol);
    throw;
  }
  N_VDestroy(atol);
}

Integrator::~Integrator() = default;

void Integrator::advance_to(double t_out, std::vector<double>& z) {
  Impl& s = *impl_;
  ScopedTimer timer(s.timing.total);
  // Guard against a run that crawls: at most 200000 steps per output interval, and the scene's
  // total budget. Either ends the run with a diagnosis, never a hang.
  const long per_call = std::min<long>(200000, std::max<long>(1, s.steps_budget - s.totals().steps));
  // One internal step at a time until t_out is reached, then the interpolant there: what CVODE's
  // normal mode does inside, with the accounting of each accepted step in between.
  for (long taken = 0; s.stepper->time() < t_out; ++taken) {
    if (taken >= per_call) throw IntegrationFailure(s.diagnose(0, true));
    // A change of the largest order takes effect before the next step (not after the last one: a
    // restart there would leave no interpolant for t_out).
    if (s.choice && s.choice->order() != s.applied_order) s.apply_order(s.choice->order());
    if (s.limits_steps) s.limit_next_step();
    double t_reached = 0;
    const int flag = s.stepper->step(t_out, s.y, t_reached);
    if (s.callback_error) std::rethrow_exception(s.callback_error);
    if (flag < 0) throw IntegrationFailure(s.diagnose(flag, false));
    s.stepped = true;
    s.record_step_error();
    if (s.choice) s.follow_order_choice(t_reached);
    if (s.step_observer) s.step_observer();
  }
  const int flag = s.stepper->interpolate(t_out, s.y);
  if (flag < 0) throw IntegrationFailure(s.diagnose(flag, false));
  const sunrealtype* y = N_VGetArrayPointer(s.y);
  z.assign(y, y + N_VGetLength(s.y));
}

double Integrator::time() const { return impl_->stepper->time(); }

void Integrator::interpolate(double t, int derivative, std::vector<double>& out) {
  Impl& s = *impl_;
  if (!s.at_start) s.at_start = N_VClone(s.y);
  const int flag = s.stepper->interpolate(t, s.at_start, derivative);
  if (flag < 0) throw IntegrationFailure(s.diagnose(flag, false));
  const sunrealtype* y = N_VGetArrayPointer(s.at_start);
  out.assign(y, y + N_VGetLength(s.at_start));
}

void Integrator::Impl::record_step_error() {
  ScopedTimer timer(timing.accounting);
  if (!stepper->local_errors(error, weights)) return;
  const double* e = N_VGetArrayPointer(error);
  const double* w = N_VGetArrayPointer(weights);
  const auto n = static_cast<std::size_t>(N_VGetLength(error));
  double norm2 = 0, worst = -1;
  std::size_t worst_index = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double we = std::abs(e[i] * w[i]);
    norm2 += we * we;
    limiting.weighted_error_sum[i] += we;
    if (we > worst) worst = we, worst_index = i;
  }
  ++limiting.steps;
  ++limiting.largest[worst_index];
  if (norm2 > 0)
    for (std::size_t i = 0; i < n; ++i) limiting.share_sum[i] += e[i] * w[i] * e[i] * w[i] / norm2;
}

std::string Integrator::Impl::diagnose(int flag, bool budget_exhausted) const {
  const IntegratorStatistics st = totals();
  const std::string what =
      out_of_wall_time ? fmt::format("wall-time budget exhausted ({:.4g} s of [solver] max_wall_time = {:g} s)",
                                     wall_seconds(), spec.max_wall_time)
      : budget_exhausted ? std::string("too much work")
                         : stepper->flag_name(flag);
  std::string out = fmt::format("integration failed at t = {:.9g} s ({}): {} after {} steps; last step {:.3g} s, "
                                "attempted step {:.3g} s",
                                stepper->time(), stepper->method_name(), what, st.steps, st.last_step,
                                stepper->attempted_step());
  if (budget_exhausted)
    out += fmt::format(" (step budget exhausted: max_steps = {} in the scene, or 200000 within one output "
                       "interval)", steps_budget);
  // The state with the largest weighted local error, and the contact loading its body the most.
  if (stepper->local_errors(error, weights)) {
    const double* e = N_VGetArrayPointer(error);
    const double* wt = N_VGetArrayPointer(weights);
    const auto n = N_VGetLength(y);
    sunindextype worst = 0;
    for (sunindextype i = 1; i < n; ++i)
      if (std::abs(e[i] * wt[i]) > std::abs(e[worst] * wt[worst])) worst = i;
    out += fmt::format("; largest weighted local error ({:.3g}) in ", std::abs(e[worst] * wt[worst]));
    out += eq.explain_state(static_cast<int>(worst));
  }
  if (!last_message.empty() && !out_of_wall_time) out += "; " + last_message;
  if (linear)
    if (const std::string e = linear->last_error(); !e.empty()) out += "; linear solver: " + e;
  return out;
}

void Integrator::set_step_observer(std::function<void()> observer) { impl_->step_observer = std::move(observer); }

IntegratorStatistics Integrator::statistics() const { return impl_->totals(); }

IntegratorStatistics Integrator::Impl::totals() const {
  IntegratorStatistics st = stepper->statistics();
  st.steps += carried.steps;
  st.rhs_evaluations += carried.rhs_evaluations;
  st.jacobian_evaluations += carried.jacobian_evaluations;
  st.linear_setups += carried.linear_setups;
  st.newton_iterations += carried.newton_iterations;
  st.newton_failures += carried.newton_failures;
  st.error_test_failures += carried.error_test_failures;
  st.stability_order_reductions += carried.stability_order_reductions;
  return st;
}

void Integrator::Impl::apply_order(int order) {
  const IntegratorStatistics before = totals();
  if (stepper->set_max_order(order, y)) {  // restarted: its counters start again
    carried = before;
    carried.last_order = 0, carried.last_step = 0;
    stepped = false;
  }
  applied_order = order;
}

void Integrator::Impl::follow_order_choice(double t) {
  const IntegratorStatistics st = totals();
  choice->after_step(t, st.rhs_evaluations - counted_rhs, st.jacobian_evaluations - counted_jacobians);
  counted_rhs = st.rhs_evaluations, counted_jacobians = st.jacobian_evaluations;
}

void Integrator::set_order_choice(OrderChoice* choice) {
  Impl& s = *impl_;
  if (s.spec.method != scene::IntegrationMethod::bdf) throw std::logic_error("the automatic order is for BDF only");
  s.choice = choice;
  s.applied_order = s.spec.max_order;
  const IntegratorStatistics st = s.totals();
  s.counted_rhs = st.rhs_evaluations, s.counted_jacobians = st.jacobian_evaluations;
  if (choice->order() != s.applied_order) s.apply_order(choice->order());
}
const StepLimitingStates& Integrator::step_limiting_states() const { return impl_->limiting; }
const IntegratorTiming& Integrator::timing() const { return impl_->timing; }
std::string Integrator::method_name() const { return impl_->stepper->method_name(); }

}  // namespace raceway::numerics
