// Micro-benchmarks of the planar model on seed 002 (13 rollers, 40 Hz, 1 kN): one contact segment,
// one right-hand side, one Jacobian, one bordered factorisation + solve (against dense LU).
// Run: perf/bench/run_benchmarks.sh (records perf/bench/results/bench_planar.txt).
#include <benchmark/benchmark.h>

#include "contact/segments/roller_segments.hpp"
#include "io/scene/scene_parser.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/startup.hpp"

namespace {

using namespace raceway;

struct Fixture {
  scene::Scene scene = scene::load_scene(RACEWAY_SOURCE_DIR "/jobs/scenes/seed002_40hz.toml");
  bearing::Model model = bearing::build_model(scene);
  scheduler::SerialExecutor executor;
  bearing::Equations eq{model, executor};
  std::vector<double> z = bearing::initial_state(model, 0.0).state;
  std::vector<double> zdot = std::vector<double>(z.size());
};
Fixture& fixture() {
  static Fixture f;
  return f;
}

/// An empty Jacobian of the fixture's model: the rings' and cage's border, one block per roller.
numerics::BorderedMatrix empty_jacobian(const Fixture& f) {
  const int nb = f.model.border_size, n = f.model.element_count;
  return numerics::BorderedMatrix(nb, n, (f.model.state_size - nb) / n);
}

/// The Newton matrix I - gamma J at the start-up state, gamma = 1e-6 s (the order of a CVODE step).
numerics::BorderedMatrix newton_matrix(Fixture& f) {
  numerics::BorderedMatrix j = empty_jacobian(f);
  f.eq.jacobian(0.0, f.z.data(), j);
  j.scale_add_identity(-1e-6);
  return j;
}

void BM_RollerRaceSegment(benchmark::State& state) {
  auto& f = fixture();
  const auto& seg = f.model.segments[0];  // roller 0 (most loaded) on the inner race
  const auto a = f.model.planar_kinematics(seg.body_a, 0, f.z.data());
  const auto b = f.model.planar_kinematics(seg.body_b, 0, f.z.data());
  const auto& law = f.model.law<contact::RollerRaceSegment>(seg);
  for (auto _ : state) benchmark::DoNotOptimize(contact::evaluate(law, a, b));
}
BENCHMARK(BM_RollerRaceSegment);

void BM_RightHandSide(benchmark::State& state) {
  auto& f = fixture();
  for (auto _ : state) benchmark::DoNotOptimize(f.eq.rhs(0.0, f.z.data(), f.zdot.data()));
  state.counters["segments"] = static_cast<double>(f.model.segments.size());
}
BENCHMARK(BM_RightHandSide);

void BM_Jacobian(benchmark::State& state) {
  auto& f = fixture();
  numerics::BorderedMatrix j = empty_jacobian(f);
  for (auto _ : state) benchmark::DoNotOptimize(f.eq.jacobian(0.0, f.z.data(), j));
}
BENCHMARK(BM_Jacobian);

void BM_BorderedFactorSolve(benchmark::State& state) {
  const numerics::BorderedMatrix j = newton_matrix(fixture());
  numerics::BorderedFactorization lu;
  std::vector<double> b(j.size(), 1.0), x(j.size());
  for (auto _ : state) {
    lu.factor(j);
    lu.solve(b.data(), x.data());
    benchmark::DoNotOptimize(x.data());
  }
}
BENCHMARK(BM_BorderedFactorSolve);

void BM_DenseFactorSolve(benchmark::State& state) {
  const Eigen::MatrixXd d = newton_matrix(fixture()).to_dense();
  Eigen::VectorXd b = Eigen::VectorXd::Ones(d.rows());
  for (auto _ : state) {
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(d);
    benchmark::DoNotOptimize(lu.solve(b).eval());
  }
}
BENCHMARK(BM_DenseFactorSolve);

}  // namespace

BENCHMARK_MAIN();
