// ARKODE's Runge-Kutta methods behind the TimeStepper of time_stepper.hpp:
//  - erk: ERKStep, an explicit embedded pair of the scene's order (5: Dormand-Prince 5(4), 6: Verner
//    6(5), 8: Fehlberg 8(7); 2-4: Heun-Euler, Bogacki-Shampine, Zonneveld). No Newton solve.
//  - ark: ARKStep with the whole right-hand side implicit (a diagonally implicit pair: 2 SDIRK 2(1),
//    3 ARK3(2)4L[2]SA, 4 SDIRK 4(3), 5 ARK5(4)8L[2]SA), each stage solved by Newton iteration with the
//    same bordered linear solvers and Jacobian as CVODE. An IMEX split would need the right-hand side
//    in a stiff and a non-stiff part; the contact forces are both the stiff and the expensive part,
//    so the whole of it is implicit.
#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_erkstep.h>

#include <cstdlib>
#include <stdexcept>
#include <utility>

#include "solver/numerics/time_stepper.hpp"

namespace raceway::numerics::stepping {

namespace {

/// A Runge-Kutta pair of ARKODE: its order, its table's id and its name.
template <class Id>
struct RkTable {
  int order;
  Id id;
  const char* name;
};
constexpr RkTable<ARKODE_ERKTableID> kErkTables[] = {{2, ARKODE_HEUN_EULER_2_1_2, "Heun-Euler 2(1)"},
                                                     {3, ARKODE_BOGACKI_SHAMPINE_4_2_3, "Bogacki-Shampine 3(2)"},
                                                     {4, ARKODE_ZONNEVELD_5_3_4, "Zonneveld 4(3)"},
                                                     {5, ARKODE_DORMAND_PRINCE_7_4_5, "Dormand-Prince 5(4)"},
                                                     {6, ARKODE_VERNER_8_5_6, "Verner 6(5)"},
                                                     {8, ARKODE_FEHLBERG_13_7_8, "Fehlberg 8(7)"}};
constexpr RkTable<ARKODE_DIRKTableID> kDirkTables[] = {{2, ARKODE_SDIRK_2_1_2, "SDIRK 2(1)"},
                                                       {3, ARKODE_ARK324L2SA_DIRK_4_2_3, "ARK3(2)4L[2]SA DIRK"},
                                                       {4, ARKODE_SDIRK_5_3_4, "SDIRK 4(3)"},
                                                       {5, ARKODE_ARK548L2SA_DIRK_8_4_5, "ARK5(4)8L[2]SA DIRK"}};

template <class Table, std::size_t N>
const Table& table_of_order(const Table (&tables)[N], int order, const char* method) {
  for (const Table& t : tables)
    if (t.order == order) return t;
  throw std::runtime_error(std::string("no Runge-Kutta pair of this order for method ") + method);
}

/// The ERKStep and ARKStep calls the stepper makes, so one class serves both modules.
struct ArkodeCalls {
  int (*evolve)(void*, sunrealtype, N_Vector, sunrealtype*, int);
  int (*get_dky)(void*, sunrealtype, int, N_Vector);
  int (*current_time)(void*, sunrealtype*);
  int (*local_errors)(void*, N_Vector);
  int (*error_weights)(void*, N_Vector);
  int (*steps)(void*, long*);
  int (*error_test_failures)(void*, long*);
  int (*last_step)(void*, sunrealtype*);
  int (*current_step)(void*, sunrealtype*);
  char* (*flag_name)(long);
  void (*free)(void**);
  int (*set_stop_time)(void*, sunrealtype);
};
constexpr ArkodeCalls kErkCalls{ERKStepEvolve,          ERKStepGetDky,         ERKStepGetCurrentTime,
                                ERKStepGetEstLocalErrors, ERKStepGetErrWeights, ERKStepGetNumSteps,
                                ERKStepGetNumErrTestFails, ERKStepGetLastStep,  ERKStepGetCurrentStep,
                                ERKStepGetReturnFlagName, ERKStepFree,          ERKStepSetStopTime};
constexpr ArkodeCalls kArkCalls{ARKStepEvolve,          ARKStepGetDky,         ARKStepGetCurrentTime,
                                ARKStepGetEstLocalErrors, ARKStepGetErrWeights, ARKStepGetNumSteps,
                                ARKStepGetNumErrTestFails, ARKStepGetLastStep,  ARKStepGetCurrentStep,
                                ARKStepGetReturnFlagName, ARKStepFree,          ARKStepSetStopTime};

class ArkodeStepper final : public TimeStepper {
 public:
  explicit ArkodeStepper(const StepperSetup& s)
      : implicit_(s.spec.method == scene::IntegrationMethod::ark), calls_(implicit_ ? kArkCalls : kErkCalls),
        order_(s.spec.max_order) {
    const scene::SolverSpec& spec = s.spec;
    const Callbacks& cb = s.callbacks;
    if (implicit_) {
      const auto& t = table_of_order(kDirkTables, spec.max_order, "ark");
      name_ = std::string("ARKODE ARKStep ") + t.name;
      mem_ = ARKStepCreate(nullptr, cb.rhs, s.t0, s.y0, s.ctx);
      if (!mem_) throw std::runtime_error("ARKStepCreate failed");
      check(ARKStepSetErrHandlerFn(mem_, cb.error_handler, cb.user), "ARKStepSetErrHandlerFn");
      check(ARKStepSetUserData(mem_, cb.user), "ARKStepSetUserData");
      check(ARKStepSVtolerances(mem_, spec.rtol, s.atol), "ARKStepSVtolerances");
      if (cb.error_weights) check(ARKStepWFtolerances(mem_, cb.error_weights), "ARKStepWFtolerances");
      check(ARKStepSetTableNum(mem_, t.id, ARKODE_ERK_NONE), "ARKStepSetTableNum");
      if (spec.max_step > 0) check(ARKStepSetMaxStep(mem_, spec.max_step), "ARKStepSetMaxStep");
      if (spec.initial_step > 0) check(ARKStepSetInitStep(mem_, spec.initial_step), "ARKStepSetInitStep");
      check(ARKStepSetLinearSolver(mem_, s.linear_solver, s.linear->matrix()), "ARKStepSetLinearSolver");
      check(ARKStepSetJacFn(mem_, cb.jacobian), "ARKStepSetJacFn");
    } else {
      const auto& t = table_of_order(kErkTables, spec.max_order, "erk");
      name_ = std::string("ARKODE ERKStep ") + t.name;
      mem_ = ERKStepCreate(cb.rhs, s.t0, s.y0, s.ctx);
      if (!mem_) throw std::runtime_error("ERKStepCreate failed");
      check(ERKStepSetErrHandlerFn(mem_, cb.error_handler, cb.user), "ERKStepSetErrHandlerFn");
      check(ERKStepSetUserData(mem_, cb.user), "ERKStepSetUserData");
      check(ERKStepSVtolerances(mem_, spec.rtol, s.atol), "ERKStepSVtolerances");
      if (cb.error_weights) check(ERKStepWFtolerances(mem_, cb.error_weights), "ERKStepWFtolerances");
      check(ERKStepSetTableNum(mem_, t.id), "ERKStepSetTableNum");
      if (spec.max_step > 0) check(ERKStepSetMaxStep(mem_, spec.max_step), "ERKStepSetMaxStep");
      if (spec.initial_step > 0) check(ERKStepSetInitStep(mem_, spec.initial_step), "ERKStepSetInitStep");
    }
  }
  ~ArkodeStepper() override { calls_.free(&mem_); }
  ArkodeStepper(const ArkodeStepper&) = delete;
  ArkodeStepper& operator=(const ArkodeStepper&) = delete;

  int step(double t_out, N_Vector y, double& t_reached) override {
    sunrealtype t = 0;
    const int flag = calls_.evolve(mem_, t_out, y, &t, ARK_ONE_STEP);
    t_reached = t;
    return flag;
  }
  int interpolate(double t, N_Vector y, int derivative) override { return calls_.get_dky(mem_, t, derivative, y); }
  int stop_at(double t_stop) override { return calls_.set_stop_time(mem_, t_stop); }
  double time() const override {
    sunrealtype t = 0;
    calls_.current_time(mem_, &t);
    return t;
  }
  bool local_errors(N_Vector error, N_Vector weights) const override {
    return calls_.local_errors(mem_, error) == ARK_SUCCESS && calls_.error_weights(mem_, weights) == ARK_SUCCESS;
  }
  bool set_max_order(int, N_Vector) override {
    throw std::logic_error("the automatic order is for CVODE's BDF only");
  }
  IntegratorStatistics statistics() const override {
    IntegratorStatistics st;
    calls_.steps(mem_, &st.steps);
    calls_.error_test_failures(mem_, &st.error_test_failures);
    calls_.last_step(mem_, &st.last_step);
    st.last_order = order_;
    if (implicit_) {
      long explicit_rhs = 0;
      ARKStepGetNumRhsEvals(mem_, &explicit_rhs, &st.rhs_evaluations);
      ARKStepGetNumJacEvals(mem_, &st.jacobian_evaluations);
      ARKStepGetNumLinSolvSetups(mem_, &st.linear_setups);
      ARKStepGetNumNonlinSolvIters(mem_, &st.newton_iterations);
      ARKStepGetNumNonlinSolvConvFails(mem_, &st.newton_failures);
    } else {
      ERKStepGetNumRhsEvals(mem_, &st.rhs_evaluations);
    }
    return st;
  }
  double attempted_step() const override {
    sunrealtype h = 0;
    calls_.current_step(mem_, &h);
    return h;
  }
  std::string flag_name(int flag) const override {
    char* name = calls_.flag_name(flag);  // allocated by ARKODE
    std::string out = name ? name : "unknown flag";
    std::free(name);
    return out;
  }
  std::string method_name() const override { return name_; }

 private:
  bool implicit_;
  ArkodeCalls calls_;
  int order_;
  std::string name_;
  void* mem_ = nullptr;
};

}  // namespace

std::unique_ptr<TimeStepper> make_arkode_stepper(const StepperSetup& setup) {
  return std::make_unique<ArkodeStepper>(setup);
}

}  // namespace raceway::numerics::stepping
