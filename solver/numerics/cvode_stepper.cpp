// CVODE's BDF and Adams methods behind the TimeStepper of time_stepper.hpp: variable order (up to
// the scene's max_order), Newton iteration with the bordered linear solvers, optional BDF
// stability-limit detection.
#include <cvode/cvode.h>
#include <fmt/format.h>

#include <cstdlib>
#include <stdexcept>

#include "solver/numerics/time_stepper.hpp"

namespace raceway::numerics::stepping {

void check(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(fmt::format("SUNDIALS set-up failed in {} (flag {})", what, flag));
}

namespace {

class CvodeStepper final : public TimeStepper {
 public:
  explicit CvodeStepper(const StepperSetup& s) : bdf_(s.spec.method == scene::IntegrationMethod::bdf) {
    const scene::SolverSpec& spec = s.spec;
    mem_ = CVodeCreate(bdf_ ? CV_BDF : CV_ADAMS, s.ctx);
    if (!mem_) throw std::runtime_error("CVodeCreate failed");
    check(CVodeSetErrHandlerFn(mem_, s.callbacks.error_handler, s.callbacks.user), "CVodeSetErrHandlerFn");
    check(CVodeInit(mem_, s.callbacks.rhs, s.t0, s.y0), "CVodeInit");
    check(CVodeSetUserData(mem_, s.callbacks.user), "CVodeSetUserData");
    check(CVodeSVtolerances(mem_, spec.rtol, s.atol), "CVodeSVtolerances");
    if (s.callbacks.error_weights) check(CVodeWFtolerances(mem_, s.callbacks.error_weights), "CVodeWFtolerances");
    check(CVodeSetMaxOrd(mem_, spec.max_order), "CVodeSetMaxOrd");
    if (spec.max_step > 0) check(CVodeSetMaxStep(mem_, spec.max_step), "CVodeSetMaxStep");
    if (spec.initial_step > 0) check(CVodeSetInitStep(mem_, spec.initial_step), "CVodeSetInitStep");
    if (bdf_ && spec.stability_limit_detection) check(CVodeSetStabLimDet(mem_, SUNTRUE), "CVodeSetStabLimDet");
    check(CVodeSetLinearSolver(mem_, s.linear_solver, s.linear->matrix()), "CVodeSetLinearSolver");
    check(CVodeSetJacFn(mem_, s.callbacks.jacobian), "CVodeSetJacFn");
  }
  ~CvodeStepper() override { CVodeFree(&mem_); }
  CvodeStepper(const CvodeStepper&) = delete;
  CvodeStepper& operator=(const CvodeStepper&) = delete;

  int step(double t_out, N_Vector y, double& t_reached) override {
    sunrealtype t = 0;
    const int flag = CVode(mem_, t_out, y, &t, CV_ONE_STEP);
    t_reached = t;
    return flag;
  }
  int interpolate(double t, N_Vector y, int derivative) override { return CVodeGetDky(mem_, t, derivative, y); }
  int stop_at(double t_stop) override { return CVodeSetStopTime(mem_, t_stop); }
  double time() const override {
    sunrealtype t = 0;
    CVodeGetCurrentTime(mem_, &t);
    return t;
  }
  bool local_errors(N_Vector error, N_Vector weights) const override {
    return CVodeGetEstLocalErrors(mem_, error) == CV_SUCCESS && CVodeGetErrWeights(mem_, weights) == CV_SUCCESS;
  }
  IntegratorStatistics statistics() const override {
    IntegratorStatistics st;
    CVodeGetNumSteps(mem_, &st.steps);
    CVodeGetNumRhsEvals(mem_, &st.rhs_evaluations);
    CVodeGetNumJacEvals(mem_, &st.jacobian_evaluations);
    CVodeGetNumLinSolvSetups(mem_, &st.linear_setups);
    CVodeGetNumNonlinSolvIters(mem_, &st.newton_iterations);
    CVodeGetNumNonlinSolvConvFails(mem_, &st.newton_failures);
    CVodeGetNumErrTestFails(mem_, &st.error_test_failures);
    CVodeGetLastOrder(mem_, &st.last_order);
    CVodeGetLastStep(mem_, &st.last_step);
    if (bdf_) CVodeGetNumStabLimOrderReds(mem_, &st.stability_order_reductions);
    return st;
  }
  bool set_max_order(int order, N_Vector y) override {
    int next = 0;
    check(CVodeGetCurrentOrder(mem_, &next), "CVodeGetCurrentOrder");
    const bool restart = next > order;
    if (restart) {
      sunrealtype t = 0, h = 0;
      check(CVodeGetCurrentTime(mem_, &t), "CVodeGetCurrentTime");
      check(CVodeGetLastStep(mem_, &h), "CVodeGetLastStep");
      check(CVodeGetDky(mem_, t, 0, y), "CVodeGetDky");  // the state at the last step's end, exactly
      check(CVodeReInit(mem_, t, y), "CVodeReInit");
      if (h > 0) check(CVodeSetInitStep(mem_, h), "CVodeSetInitStep");
    }
    check(CVodeSetMaxOrd(mem_, order), "CVodeSetMaxOrd");
    return restart;
  }
  double attempted_step() const override {
    sunrealtype h = 0;
    CVodeGetCurrentStep(mem_, &h);
    return h;
  }
  std::string flag_name(int flag) const override {
    char* name = CVodeGetReturnFlagName(flag);  // allocated by CVODE
    std::string out = name ? name : "unknown flag";
    std::free(name);
    return out;
  }
  std::string method_name() const override { return bdf_ ? "CVODE BDF" : "CVODE Adams"; }

 private:
  bool bdf_;
  void* mem_ = nullptr;
};

}  // namespace

std::unique_ptr<TimeStepper> make_cvode_stepper(const StepperSetup& setup) {
  return std::make_unique<CvodeStepper>(setup);
}

}  // namespace raceway::numerics::stepping
