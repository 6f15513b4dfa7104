// What the lubricated cage costs: one right-hand side and one Jacobian of the QJ215 (seed 001, 15
// balls, outer-land guided) dry as shipped, with the balls' pocket films (normal = "pocket_film") and
// with the land's film as well (short_bearing), at the seated start; and one pocket segment, dry and
// lubricated. The ratio of the right-hand sides is what the lubricated cage costs a run per step.
// Run on an idle machine: build/perf/bench/bench_lubricated_cage.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "io/scene/scene_parser.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/startup.hpp"

namespace {

using namespace raceway;

struct Fixture {
  explicit Fixture(std::vector<std::string> overrides)
      : scene(scene::load_scene(RACEWAY_SOURCE_DIR "/jobs/scenes/qj215_validation.toml", overrides)),
        model(bearing::build_model(scene)),
        eq(model, executor),
        z(bearing::initial_state(model, 0.0).state),
        zdot(z.size()) {}
  scene::Scene scene;
  bearing::Model model;
  scheduler::SerialExecutor executor;
  bearing::Equations eq;
  std::vector<double> z, zdot;
};

Fixture& fixture(int variant) {
  static Fixture dry({});
  static Fixture pocket({"lubricant.viscosity=0.11 Pa s", "contact.ball_cage.normal=pocket_film"});
  static Fixture both({"lubricant.viscosity=0.11 Pa s", "contact.ball_cage.normal=pocket_film",
                       "contact.cage_land.normal=short_bearing"});
  return variant == 0 ? dry : variant == 1 ? pocket : both;
}

void BM_RightHandSide(benchmark::State& state) {
  auto& f = fixture(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(f.eq.rhs(0.0, f.z.data(), f.zdot.data()));
}
BENCHMARK(BM_RightHandSide)->Arg(0)->Arg(1)->Arg(2)->ArgName("dry0_pocket1_both2");

void BM_Jacobian(benchmark::State& state) {
  auto& f = fixture(static_cast<int>(state.range(0)));
  const int nb = f.model.border_size, n = f.model.element_count;
  numerics::BorderedMatrix j(nb, n, (f.model.state_size - nb) / n);
  for (auto _ : state) benchmark::DoNotOptimize(f.eq.jacobian(0.0, f.z.data(), j));
}
BENCHMARK(BM_Jacobian)->Arg(0)->Arg(1)->Arg(2)->ArgName("dry0_pocket1_both2");

void BM_PocketSegment(benchmark::State& state) {
  auto& f = fixture(static_cast<int>(state.range(0)));
  const bearing::Segment* seg = f.model.first_segment(bearing::SegmentKind::ball_pocket);
  const auto a = f.model.kinematics(seg->body_a, 0, f.z.data());
  const auto b = f.model.kinematics(seg->body_b, 0, f.z.data());
  const auto& law = f.model.law<contact::BallPocketSegment>(*seg);
  for (auto _ : state) benchmark::DoNotOptimize(contact::evaluate(law, a, b));
}
BENCHMARK(BM_PocketSegment)->Arg(0)->Arg(1)->ArgName("dry0_pocket1");

}  // namespace

BENCHMARK_MAIN();
