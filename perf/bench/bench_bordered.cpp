// Newton linear algebra against the number of rolling elements (README "Newton linear solvers"): on
// a synthetic large deep groove ball bearing (the 6309 ball, 8 to 512 balls on a pitch circle that
// grows with N), times:
//   - one Jacobian evaluation (O(N) segment evaluations),
//   - assembly + factorisation + one solve: J loaded into the backend's matrix, M = I - gamma J
//     formed, the solver's setup, one solve (together: a library may defer factorisation work),
//   - one solve alone (after the setup),
// for each backend of solver/numerics/newton_backends.hpp (petsc-bordered, block-elimination,
// sundials-dense), and checks that the backends' solutions agree. Then the same for the real bearings (seed 002 roller
// bearing, 13 rollers; 6309, 8 balls; QJ215, 15 balls). Each time is the minimum over repetitions
// (other engineers share the 2 cores: the minimum is the least disturbed), the median beside it.
//
// Output: CSV on stdout (one row per scene and backend), notes on stderr. With scene files of
// jobs/scenes after the three optional arguments, only those scenes.
// Run: perf/bench/run_bordered_scaling.sh (records perf/bench/results/bordered_scaling.{csv,txt,png}).
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "io/scene/scene_parser.hpp"
#include "scheduler/executor.hpp"
#include "scheduler/mpi_session.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/numerics/newton_backends.hpp"
#include "solver/bearing/startup.hpp"
#include "tests/support/spatial_scene_builder.hpp"

namespace {

using namespace raceway;
using Clock = std::chrono::steady_clock;

struct Timing {
  double min = 0, median = 0;
  int reps = 0;
};

/// Repeats f until `budget` seconds have passed (at least `min_reps`, at most 2000 times).
template <class F>
Timing time_it(F&& f, double budget, int min_reps = 3) {
  std::vector<double> t;
  const auto start = Clock::now();
  while (static_cast<int>(t.size()) < min_reps ||
         (std::chrono::duration<double>(Clock::now() - start).count() < budget && t.size() < 2000)) {
    const auto a = Clock::now();
    f();
    t.push_back(std::chrono::duration<double>(Clock::now() - a).count());
  }
  std::sort(t.begin(), t.end());
  return {t.front(), t[t.size() / 2], static_cast<int>(t.size())};
}

/// The 6309 ball bearing of the tests with N balls: pitch circle grown so that the balls keep the
/// 6309's spacing (8 balls on 72.5 mm) once N exceeds what fits, rings and cage grown with it; a
/// radial and axial load so that the balls are loaded unevenly, as in a real run.
scene::Scene synthetic_scene(int balls) {
  test::BallSceneOptions o;
  o.fx = 300.0 * balls / 8, o.fy = -1000.0 * balls / 8, o.fz = 500.0 * balls / 8;
  scene::Scene s = test::deep_groove_scene(o);
  const double pitch = std::max(72.5e-3, 72.5e-3 * balls / 8.0 * 0.75);
  const double grow = pitch - s.bearing.pitch_diameter;
  s.bearing.rolling_elements = balls;
  s.bearing.pitch_diameter = pitch;
  s.bearing.inner_bore_diameter += grow;
  s.bearing.outer_outside_diameter += grow;
  s.scene.name = "synthetic 6309-ball bearing, " + std::to_string(balls) + " balls";
  return s;
}

struct Problem {
  std::string name;
  numerics::BorderedLayout layout;
  std::function<int(numerics::BorderedMatrix&)> jacobian;
};

void measure(const Problem& p, int balls, double budget, int max_dense_blocks) {
  const auto& l = p.layout;
  numerics::BorderedMatrix j(l.border, l.blocks, l.block_size);
  const Timing tj = time_it([&] { p.jacobian(j); }, budget);
  const double gamma = 1e-6;  // a typical CVODE step (h / l_0) of these runs
  numerics::BorderedMatrix m = j;
  m.scale_add_identity(-gamma);
  SUNContext ctx = nullptr;
  SUNContext_Create(nullptr, &ctx);
  N_Vector b = N_VNew_Serial(l.size(), ctx), x = N_VNew_Serial(l.size(), ctx);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < l.size(); ++i) NV_Ith_S(b, i) = u(rng);
  std::vector<double> reference;
  for (auto kind : {scene::LinearSolverKind::petsc_bordered, scene::LinearSolverKind::block_elimination,
                    scene::LinearSolverKind::sundials_dense}) {
    if (kind == scene::LinearSolverKind::sundials_dense && l.blocks > max_dense_blocks) continue;
    numerics::NewtonLinearSystem sys(kind, ctx, b, l);
    auto setup = [&] {
      numerics::NewtonLinearSystem::load_jacobian(j, sys.matrix());
      SUNMatScaleAddI(-gamma, sys.matrix());
      if (SUNLinSolSetup(sys.solver(), sys.matrix()) != 0) {
        std::fprintf(stderr, "setup failed: %s\n", sys.last_error().c_str());
        std::exit(1);
      }
    };
    // Dense at large N takes seconds per setup: fewer repetitions there.
    const int min_reps = kind == scene::LinearSolverKind::sundials_dense && l.blocks >= 128 ? 1 : 3;
    // Setup and one solve together: a library may defer work from the setup to the first solve.
    const Timing ts = time_it([&] {
      setup();
      SUNLinSolSolve(sys.solver(), sys.matrix(), x, b, 0);
    }, budget, min_reps);
    const Timing tv = time_it([&] { SUNLinSolSolve(sys.solver(), sys.matrix(), x, b, 0); }, budget, min_reps);
    const double* xv = N_VGetArrayPointer(x);
    // Relative residual of the solve against M formed independently.
    std::vector<double> mx(static_cast<std::size_t>(l.size()));
    m.multiply(xv, mx.data());
    double rnum = 0, rden = 0;
    for (int i = 0; i < l.size(); ++i)
      rnum += std::pow(mx[static_cast<std::size_t>(i)] - NV_Ith_S(b, i), 2), rden += std::pow(NV_Ith_S(b, i), 2);
    const double residual = std::sqrt(rnum / rden);
    double diff = 0;
    if (reference.empty()) {
      reference.assign(xv, xv + l.size());
    } else {
      double num = 0, den = 0;
      for (int i = 0; i < l.size(); ++i) num += std::pow(xv[i] - reference[static_cast<std::size_t>(i)], 2),
                                         den += std::pow(reference[static_cast<std::size_t>(i)], 2);
      diff = std::sqrt(num / den);
    }
    std::printf("%s,%d,%d,%s,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%d,%d,%.2e,%.2e\n", p.name.c_str(), balls, l.size(),
                numerics::linear_solver_name(kind), tj.min, tj.median, ts.min, ts.median, tv.min, tv.median, ts.reps,
                tv.reps, diff, residual);
    std::fflush(stdout);
  }
  N_VDestroy(b);
  N_VDestroy(x);
  SUNContext_Free(&ctx);
}

/// measure() on a ball bearing's Jacobian at its start-up state, with raceway's default PETSc options.
/// Every backend on the Newton systems of a bearing scene (its Jacobian at the start-up state).
void measure_bearing(const char* name, const scene::Scene& scene, double budget, int max_dense) {
  const bearing::Model model = bearing::build_model(scene);
  scheduler::SerialExecutor executor;
  bearing::Equations eq(model, executor);
  const std::vector<double> z = bearing::initial_state(model, 0.0).state;
  const numerics::BorderedLayout l{model.border_size, model.element_count, model.block_size};
  numerics::configure_petsc_options(scene::SolverSpec{}, l);
  measure({name, l, [&](numerics::BorderedMatrix& j) { return eq.jacobian(0.0, z.data(), j); }}, model.element_count,
          budget, max_dense);
}

}  // namespace

int main(int argc, char** argv) {
  const scheduler::MpiSession mpi(argc, argv);
  {
    // Optional third argument: PETSc options for petsc-bordered (as raceway run --petsc-options).
    numerics::PetscRuntime petsc(argc > 3 ? argv[3] : "");
    const double budget = argc > 1 ? std::atof(argv[1]) : 0.5;   // s per measurement
    const int max_dense = argc > 2 ? std::atoi(argv[2]) : 512;  // largest N for the dense baseline
    std::printf("scene,N,states,backend,jacobian_min_s,jacobian_median_s,setup_solve_min_s,setup_solve_median_s,solve_min_s,"
                "solve_median_s,setup_reps,solve_reps,difference_to_petsc,residual\n");
    if (argc > 4) {  // only the named scenes of jobs/scenes (e.g. a larger border: seed003_flexible_bridges.toml)
      for (int a = 4; a < argc; ++a)
        measure_bearing(argv[a], scene::load_scene(std::string(RACEWAY_SOURCE_DIR "/jobs/scenes/") + argv[a]), budget,
                        max_dense);
      return 0;
    }
    for (int n : {8, 16, 32, 64, 128, 256, 512}) measure_bearing("synthetic", synthetic_scene(n), budget, max_dense);
    // The real bearings: N = 8..16.
    for (const char* file : {"6309_R3.toml", "qj215_validation.toml"})
      measure_bearing(file, scene::load_scene(std::string(RACEWAY_SOURCE_DIR "/jobs/scenes/") + file), budget,
                           max_dense);
    measure_bearing("seed002_40hz.toml", scene::load_scene(RACEWAY_SOURCE_DIR "/jobs/scenes/seed002_40hz.toml"), budget,
                    max_dense);
  }
  return 0;
}
