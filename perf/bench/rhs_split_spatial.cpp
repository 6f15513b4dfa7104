// Time per right-hand side of a spatial scene, split into contact kinds: the segment tasks' own
// timers (scheduler::Executor::task_seconds), summed per kind over many evaluations at the
// start-up state. Usage: rhs_split_spatial SCENE.toml [EVALUATIONS]
// Recorded output: perf/bench/results/rhs_split_6309_R3.txt (run by perf/bench/run_benchmarks.sh).
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "io/scene/scene_parser.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/startup.hpp"

int main(int argc, char** argv) {
  using namespace raceway;
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE.toml [EVALUATIONS]\n", argv[0]);
    return 2;
  }
  const scene::Scene scene = scene::load_scene(argv[1]);
  const int evaluations = argc > 2 ? std::atoi(argv[2]) : 20000;
  const bearing::Model model = bearing::build_model(scene);
  const auto start = bearing::initial_state(model, 0.0);
  scheduler::SerialExecutor executor;
  bearing::Equations eq(model, executor);
  std::vector<double> zdot(start.state.size());
  double per_kind[bearing::segment_kind_count] = {};
  int count[bearing::segment_kind_count] = {};
  for (const auto& s : model.segments) ++count[static_cast<int>(s.kind)];
  const std::vector<int> task_segment = eq.task_catalogue().parent;  // a cut segment has several tasks
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < evaluations; ++i) {
    eq.rhs(1e-6 * i, start.state.data(), zdot.data());
    const auto& sec = executor.task_seconds(scheduler::Phase::rhs);
    for (std::size_t t = 0; t < sec.size(); ++t)
      per_kind[static_cast<int>(model.segments[static_cast<std::size_t>(task_segment[t])].kind)] += sec[t];
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("scene %s: %d right-hand sides at the start-up state\n", argv[1], evaluations);
  std::printf("wall time per rhs: %.3f us (all segments, summation, body equations, timers)\n", 1e6 * wall / evaluations);
  double tasks = 0;
  for (int k = 0; k < bearing::segment_kind_count; ++k) tasks += per_kind[k];
  for (int k = 0; k < bearing::segment_kind_count; ++k)
    if (count[k] > 0)
      std::printf("  %-18s %3d segments: %8.3f us per rhs (%5.1f %%), %.3f us per segment\n",
                  bearing::segment_kind_name(static_cast<bearing::SegmentKind>(k)), count[k],
                  1e6 * per_kind[k] / evaluations, 100 * per_kind[k] / tasks, 1e6 * per_kind[k] / evaluations / count[k]);
  // Rank 0's serial work per rhs: the sum over segments, combining cut segments' parts, the bodies.
  std::printf("  outside the segment tasks: %.3f us per rhs\n", 1e6 * (wall - tasks) / evaluations);
  return 0;
}
