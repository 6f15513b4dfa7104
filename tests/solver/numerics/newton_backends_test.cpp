// The Newton linear solvers of solver/numerics/newton_backends.hpp, one conformance suite for every backend
// (petsc-bordered, block-elimination, sundials-dense), through the same SUNMatrix / SUNLinearSolver
// calls CVODE makes:
//  1. random bordered systems M = I - gamma J (with an empty border, a single rolling element, and
//     larger ones) solve to 1e-12 relative against Eigen's dense LU of the same matrix;
//  2. CVODE's jok path (the saved J copied back, M formed for a new gamma) and a new J in the same
//     objects solve the new systems, not the old ones;
//  3. a singular rolling-element block is a recoverable failure (CVODE retries with a smaller step);
//  4. PETSc options: valid ones (another LU package) work, a misspelt type, an option nothing reads and
//     an unusable combination are errors naming the scene key or --petsc-options;
//  5. the backend table's names and aliases are the ones the scene parser maps to the same kinds.
#include <gtest/gtest.h>
#include <nvector/nvector_serial.h>

#include <Eigen/Dense>
#include <random>
#include <string>
#include <tuple>

#include "io/scene/scene_parser.hpp"
#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/numerics/integrator.hpp"
#include "solver/bearing/model.hpp"
#include "solver/numerics/newton_backends.hpp"
#include "solver/bearing/startup.hpp"
#include "tests/support/solver_test_support.hpp"
#include "tests/support/spatial_scene_builder.hpp"

namespace raceway::numerics {
namespace {

using Kind = scene::LinearSolverKind;

struct Context {
  SUNContext ctx = nullptr;
  Context() { SUNContext_Create(nullptr, &ctx); }
  ~Context() { SUNContext_Free(&ctx); }
};

/// A random Jacobian with the bordered structure: entries in [-1, 1] scaled per row by 10^(+-3) so
/// that the system is badly scaled as the SI Newton matrices are; diagonal blocks made dominant.
BorderedMatrix random_jacobian(const BorderedLayout& l, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(-3.0, 3.0);
  BorderedMatrix j(l.border, l.blocks, l.block_size);
  for (int r = 0; r < l.size(); ++r) {
    const double scale = std::pow(10.0, e(rng));
    for (int c = 0; c < l.size(); ++c) {
      const bool coupled = r < l.border || c < l.border || (r - l.border) / l.block_size == (c - l.border) / l.block_size;
      if (coupled) j.add(r, c, scale * u(rng));
    }
    j.add(r, r, -scale * (l.block_size + l.border + 2.0));  // M = I - gamma J: diagonal grows
  }
  return j;
}

Eigen::MatrixXd newton_matrix(const BorderedMatrix& j, double gamma) {
  return Eigen::MatrixXd::Identity(j.size(), j.size()) - gamma * j.to_dense();
}

/// Solves M x = b with the backend's solver (set up on the system's matrix as it is) and returns the
/// relative difference to Eigen's dense LU of `m`.
double solve_error(NewtonLinearSystem& sys, const Eigen::MatrixXd& m, N_Vector b, N_Vector x, int* flag) {
  *flag = SUNLinSolSetup(sys.solver(), sys.matrix());
  if (*flag != 0) return -1;
  *flag = SUNLinSolSolve(sys.solver(), sys.matrix(), x, b, 0);
  if (*flag != 0) return -1;
  const auto n = m.rows();
  const Eigen::Map<const Eigen::VectorXd> bv(N_VGetArrayPointer(b), n), xv(N_VGetArrayPointer(x), n);
  const Eigen::VectorXd ref = m.partialPivLu().solve(bv);
  return (xv - ref).norm() / ref.norm();
}

class Backend : public ::testing::TestWithParam<std::tuple<Kind, int, int, int>> {};

TEST_P(Backend, RandomBorderedSystemsSolveLikeDenseLU) {
  const auto [kind, border, blocks, block_size] = GetParam();
  const BorderedLayout l{border, blocks, block_size};
  std::mt19937 rng(100u + static_cast<unsigned>(border * 1000 + blocks * 10 + block_size));
  Context c;
  N_Vector b = N_VNew_Serial(l.size(), c.ctx), x = N_VNew_Serial(l.size(), c.ctx);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < l.size(); ++i) NV_Ith_S(b, i) = u(rng);
  NewtonLinearSystem sys(kind, c.ctx, b, l);
  SUNMatrix saved = SUNMatClone(sys.matrix());
  ASSERT_NE(saved, nullptr);

  // 1. A fresh Jacobian, as CVODE does it: zero, fill, save a copy, M = I - gamma J.
  const BorderedMatrix j1 = random_jacobian(l, rng);
  ASSERT_EQ(SUNMatZero(sys.matrix()), 0);
  NewtonLinearSystem::load_jacobian(j1, sys.matrix());
  ASSERT_EQ(SUNMatCopy(sys.matrix(), saved), 0);
  ASSERT_EQ(SUNMatScaleAddI(-0.05, sys.matrix()), 0);
  int flag = 0;
  double err = solve_error(sys, newton_matrix(j1, 0.05), b, x, &flag);
  ASSERT_EQ(flag, 0) << sys.last_error();
  EXPECT_LT(err, 1e-12) << "fresh Jacobian";

  // 2. jok: the saved J back into M, a new gamma.
  ASSERT_EQ(SUNMatCopy(saved, sys.matrix()), 0);
  ASSERT_EQ(SUNMatScaleAddI(-0.013, sys.matrix()), 0);
  err = solve_error(sys, newton_matrix(j1, 0.013), b, x, &flag);
  ASSERT_EQ(flag, 0) << sys.last_error();
  EXPECT_LT(err, 1e-12) << "saved Jacobian, new gamma";

  // ... and a new Jacobian in the same objects (a re-setup must not keep the old factors).
  const BorderedMatrix j2 = random_jacobian(l, rng);
  NewtonLinearSystem::load_jacobian(j2, sys.matrix());
  ASSERT_EQ(SUNMatScaleAddI(-0.05, sys.matrix()), 0);
  err = solve_error(sys, newton_matrix(j2, 0.05), b, x, &flag);
  ASSERT_EQ(flag, 0) << sys.last_error();
  EXPECT_LT(err, 1e-12) << "new Jacobian";

  // The matrix-vector product of the saved J (before any setup: SUNDIALS dense factors in place).
  N_Vector y = N_VClone(x);
  ASSERT_EQ(SUNMatMatvec(saved, b, y), 0);
  const Eigen::VectorXd ref = j1.to_dense() * Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(b), l.size());
  EXPECT_LT((Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(y), l.size()) - ref).norm(), 1e-12 * ref.norm());
  N_VDestroy(y);
  SUNMatDestroy(saved);
  N_VDestroy(b);
  N_VDestroy(x);
}

INSTANTIATE_TEST_SUITE_P(
    AllBackends, Backend,
    ::testing::Combine(::testing::Values(Kind::petsc_bordered, Kind::block_elimination, Kind::sundials_dense),
                       ::testing::Values(0, 1, 12), ::testing::Values(1, 3, 40), ::testing::Values(5, 9)),
    [](const ::testing::TestParamInfo<std::tuple<Kind, int, int, int>>& p) {
      std::string name = linear_solver_name(std::get<0>(p.param));
      for (char& ch : name)
        if (ch == '-') ch = '_';
      return name + "_border" + std::to_string(std::get<1>(p.param)) + "_blocks" + std::to_string(std::get<2>(p.param)) +
             "_of" + std::to_string(std::get<3>(p.param));
    });

class SingularBlock : public ::testing::TestWithParam<Kind> {};

TEST_P(SingularBlock, IsARecoverableFailure) {
  const BorderedLayout l{4, 3, 5};
  Context c;
  N_Vector b = N_VNew_Serial(l.size(), c.ctx), x = N_VNew_Serial(l.size(), c.ctx);
  N_VConst(1.0, b);
  NewtonLinearSystem sys(GetParam(), c.ctx, b, l);
  // M = I - J with J = I on the second rolling element's block: that block of M is zero.
  BorderedMatrix j(l.border, l.blocks, l.block_size);
  for (int r = l.border + l.block_size; r < l.border + 2 * l.block_size; ++r) j.add(r, r, 1.0);
  NewtonLinearSystem::load_jacobian(j, sys.matrix());
  ASSERT_EQ(SUNMatScaleAddI(-1.0, sys.matrix()), 0);
  int flag = SUNLinSolSetup(sys.solver(), sys.matrix());
  if (flag == 0) flag = SUNLinSolSolve(sys.solver(), sys.matrix(), x, b, 0);
  EXPECT_GT(flag, 0) << "a singular Newton matrix must be a recoverable failure (positive flag), got " << flag << "; "
                     << sys.last_error();
  N_VDestroy(b);
  N_VDestroy(x);
}

INSTANTIATE_TEST_SUITE_P(AllBackends, SingularBlock,
                         ::testing::Values(Kind::petsc_bordered, Kind::block_elimination, Kind::sundials_dense));

// ---- PETSc options ---------------------------------------------------------------------------

scene::SolverSpec spec_with(const std::string& options) {
  scene::SolverSpec s;
  s.linear_solver = Kind::petsc_bordered;
  s.petsc_options = options;
  s.petsc_options_file = "scene.toml";
  s.petsc_options_line = 42;
  return s;
}

struct RestoreOptions {
  ~RestoreOptions() {
    PetscRuntime::current().set_command_line_options("");
    configure_petsc_options(scene::SolverSpec{}, {12, 3, 9});
  }
};

TEST(PetscOptions, ValidOptionsBuildTheDescribedSolver) {
  RestoreOptions restore;
  const std::string d = configure_petsc_options(spec_with(""), {12, 3, 9});
  EXPECT_NE(d.find("pc fieldsplit"), std::string::npos) << d;
  EXPECT_NE(d.find("split 0 (rolling elements): ksp preonly, pc lu"), std::string::npos) << d;
  // Another LU package for split 0 (SuperLU is in Debian's PETSc): accepted and exact.
  const std::string s = configure_petsc_options(spec_with("-fieldsplit_0_pc_factor_mat_solver_type superlu"), {12, 3, 9});
  EXPECT_NE(s.find("superlu"), std::string::npos) << s;
  EXPECT_NE(s.find("residual"), std::string::npos);
  EXPECT_EQ(s.find("inexact"), std::string::npos) << s;
  // ILU on the Schur split is allowed but said to be inexact.
  const std::string i = configure_petsc_options(spec_with("-fieldsplit_1_pc_type ilu -fieldsplit_1_ksp_type preonly"),
                                                {12, 3, 9});
  EXPECT_NE(i.find("pc ilu"), std::string::npos) << i;
}

TEST(PetscOptions, BadSceneOptionsNameTheKeyAndLine) {
  RestoreOptions restore;
  try {
    configure_petsc_options(spec_with("-fieldsplit_0_pc_type no_such_pc"), {12, 3, 9});
    FAIL() << "a misspelt PC type was accepted";
  } catch (const scene::SceneError& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("scene.toml:42: key 'solver.petsc_options'"), std::string::npos) << w;
    EXPECT_NE(w.find("no_such_pc"), std::string::npos) << w;
  }
  try {
    configure_petsc_options(spec_with("-fieldsplit_0_pc_typo lu"), {12, 3, 9});
    FAIL() << "an option nothing reads was accepted";
  } catch (const scene::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("not used"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("-fieldsplit_0_pc_typo"), std::string::npos) << e.what();
  }
}

TEST(PetscOptions, BadCommandLineOptionsNameTheOption) {
  RestoreOptions restore;
  PetscRuntime::current().set_command_line_options("-ksp_type no_such_ksp");
  try {
    configure_petsc_options(spec_with(""), {12, 3, 9});
    FAIL() << "a misspelt KSP type was accepted";
  } catch (const OptionsError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--petsc-options: ", 0), 0u) << e.what();
  }
  // An unusable combination: MUMPS cannot factor the dense Schur complement.
  PetscRuntime::current().set_command_line_options("-fieldsplit_1_pc_factor_mat_solver_type mumps");
  EXPECT_THROW(configure_petsc_options(spec_with(""), {12, 3, 9}), OptionsError);
}

// ---- the backend table against the scene parser --------------------------------------------------

/// The default scene with `linear_solver = "<name>"`, parsed.
scene::LinearSolverKind parsed_kind(const std::string& name) {
  std::string text = scene::default_scene_text();
  const std::string key = "linear_solver = \"auto\"";
  const auto at = text.find(key);
  EXPECT_NE(at, std::string::npos) << "the default scene no longer sets " << key;
  if (at == std::string::npos) return Kind::automatic;
  text.replace(at, key.size(), "linear_solver = \"" + name + "\"");
  return scene::parse_scene(text, "edited.toml").solver.linear_solver;
}

TEST(LinearSolverBackends, NamesAndAliasesParseToTheirKinds) {
  int with_factory = 0;
  for (const LinearSolverBackend& b : linear_solver_backends()) {
    EXPECT_EQ(parsed_kind(b.name), b.kind) << b.name;
    if (b.alias) {
      EXPECT_EQ(parsed_kind(b.alias), b.kind) << b.alias;
    }
    EXPECT_STREQ(linear_solver_name(b.kind), b.name);
    EXPECT_EQ(&linear_solver_backend(b.kind), &b);
    // Every kind but auto creates a backend; auto stands for one that does.
    EXPECT_EQ(b.create == nullptr, b.kind == Kind::automatic) << b.name;
    with_factory += b.create != nullptr;
  }
  EXPECT_EQ(with_factory, 3);
  EXPECT_NE(linear_solver_backend(resolve_linear_solver(Kind::automatic, {12, 3, 9})).create, nullptr);
  EXPECT_THROW(parsed_kind("no-such-solver"), scene::SceneError);
}


// ---- whole runs: every backend against the SUNDIALS dense baseline ------------------------------
// Named DenseVsBordered* so that it runs with the long solver tests (label solver_long).
// Step counts within 2 % (README "Newton linear solvers": the backends give the same runs) and trajectories within 3x the round-off baseline + 10 tolerance
// units (a dense run from the start state scaled by 1 + 1e-15: two correct linear solvers differ by
// round-off, and CVODE's step-size sequence forks on it; see dense_vs_bordered_test.cpp). Measured:
// seed 002, 10 ms: dense 6335 steps, petsc-bordered 6301 (0.5 %), block-elimination 6231 (1.6 %),
// but the perturbed dense run 6551 (3.4 %): the 2 % bound on this scene holds with little margin
// (round-off alone can exceed it); trajectories 5.2e3 / 1.5e4 units against a baseline of 1.8e4 (the
// rattling unloaded rollers). Ball bearing, 5 ms: 686 steps for all, 1.5 / 0.6 units, baseline 0.17.


struct Run {
  std::vector<std::vector<double>> states;  ///< at every output time
  IntegratorStatistics stats;
};

/// Integrates `eq` from z0 through `samples` output times dt apart.
Run integrate(DynamicSystem& eq, scene::SolverSpec spec, Kind kind, std::vector<double> z0, double dt, int samples,
              double perturbation = 0) {
  spec.linear_solver = kind;
  for (double& v : z0) v *= 1 + perturbation;
  Integrator integrator(eq, spec, 0.0, z0);
  Run r;
  for (int i = 1; i <= samples; ++i) {
    std::vector<double> z;
    integrator.advance_to(i * dt, z);
    r.states.push_back(z);
  }
  r.stats = integrator.statistics();
  return r;
}

/// Largest |a - b| / (rtol max(|a|, |b|) + atol) over all states and output times.
double units(const Run& a, const Run& b, double rtol, const std::vector<double>& atol) {
  double worst = 0;
  for (std::size_t i = 0; i < a.states.size(); ++i)
    for (std::size_t j = 0; j < atol.size(); ++j) {
      const double x = a.states[i][j], y = b.states[i][j];
      worst = std::max(worst, std::abs(x - y) / (rtol * std::max(std::abs(x), std::abs(y)) + atol[j]));
    }
  return worst;
}

void compare_backends(const char* name, DynamicSystem& eq, const scene::SolverSpec& spec, const std::vector<double>& z0,
                      double dt, int samples) {
  const auto atol = eq.absolute_tolerance();
  const Run dense = integrate(eq, spec, Kind::sundials_dense, z0, dt, samples);
  const Run baseline = integrate(eq, spec, Kind::sundials_dense, z0, dt, samples, 1e-15);
  const double noise = units(dense, baseline, spec.rtol, atol);
  for (Kind kind : {Kind::petsc_bordered, Kind::block_elimination}) {
    const Run r = integrate(eq, spec, kind, z0, dt, samples);
    const double d = units(dense, r, spec.rtol, atol);
    const double step_ratio = static_cast<double>(r.stats.steps) / static_cast<double>(dense.stats.steps);
    std::printf("[ backends ] %s: %s %ld steps, dense %ld (ratio %.4f), dense perturbed by 1e-15 %ld; trajectory "
                "difference to dense %.3g tolerance units, round-off baseline %.3g\n",
                name, linear_solver_name(kind), r.stats.steps, dense.stats.steps, step_ratio, baseline.stats.steps, d,
                noise);
    EXPECT_NEAR(step_ratio, 1.0, 0.02) << name << ", " << linear_solver_name(kind);
    EXPECT_LT(d, 3 * noise + 10) << name << ", " << linear_solver_name(kind);
  }
}

TEST(DenseVsBorderedBackends, Seed002RollerBearingRunsAgree) {
  scene::Scene scene = test::load_seed002_former_solver();
  // The step counts of the backends agree to 2 % at BDF order 5, rtol 1e-7 (the settings this was
  // measured with, in the bearing frame without the pocket factor); at the scene's own looser
  // settings round-off alone moves them by 10 %.
  scene.solver.rtol = 1e-7;
  scene.solver.max_order = 5;
  scene.solver.atol_position = scene.solver.atol_velocity = 0;
  const bearing::Model model = bearing::build_model(scene);
  scheduler::SerialExecutor executor;
  bearing::Equations eq(model, executor);
  compare_backends("seed 002, 10 ms", eq, scene.solver, initial_state(model, 0.0).state, 1e-3, 10);
}

TEST(DenseVsBorderedBackends, BallBearingRunsAgree) {
  test::BallSceneOptions o;
  o.fx = 300, o.fy = -1000, o.fz = 500;
  const scene::Scene scene = test::deep_groove_scene(o);
  const bearing::Model model = bearing::build_model(scene);
  scheduler::SerialExecutor executor;
  bearing::Equations eq(model, executor);
  compare_backends("6309-size ball bearing, 5 ms", eq, scene.solver, initial_state(model, 0.0).state, 1e-4, 50);
}
}  // namespace
}  // namespace raceway::numerics
