// Which rolling elements hold the step back, and in what contact state they are then.
//
//   step_limits SCENE.toml [END_TIME_S] [INTERVAL_S] > intervals.csv
//
// Integrates the scene (without output files) interval by interval. After each interval it takes
// the integrator's per-state accounting (Integrator::step_limiting_states) for that interval: the
// state that most often had the largest weighted local error, its class, and for a rolling element
// its contact state at the interval's end (inner race, outer race, cage bars, from the segment
// diagnostics). One CSV row per interval on standard output; on standard error a table of the
// share of the steps held by rolling elements in each contact state against the share of time the
// rolling elements spend in it. perf/bench/results/seed002_step_limits.md records and explains the output.
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "contact/segments/diagnostic_fields.hpp"
#include "io/scene/scene_parser.hpp"
#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/numerics/integrator.hpp"

using namespace raceway;
using namespace raceway::bearing;
using namespace raceway::numerics;

namespace {

/// "loaded" (inner and outer race), "outer only" (centrifugal), "inner only", "free", plus "+bar"
/// when a cage bar (pocket) presses on it.
std::vector<std::string> contact_states(const Model& m, const Equations& eq) {
  const bool planar = m.kind == scene::ModelKind::planar;
  const int force = planar ? contact::field_index(contact::line_diagnostic_fields, "normal_force")
                           : contact::field_index(contact::point_diagnostic_fields, "normal_force");
  std::vector<double> inner(static_cast<std::size_t>(m.element_count)), outer(inner.size()), bar(inner.size());
  for (std::size_t s = 0; s < m.segments.size(); ++s) {
    const Segment& seg = m.segments[s];
    if (seg.element < 0) continue;
    const double f = eq.diagnostic(s, force);
    const auto e = static_cast<std::size_t>(seg.element);
    switch (seg.kind) {
      case SegmentKind::roller_inner_race:
      case SegmentKind::ball_inner_groove: inner[e] += f; break;
      case SegmentKind::roller_outer_race:
      case SegmentKind::ball_outer_groove: outer[e] += f; break;
      default: bar[e] += f; break;
    }
  }
  std::vector<std::string> out;
  for (std::size_t e = 0; e < inner.size(); ++e) {
    std::string s = inner[e] > 0 && outer[e] > 0 ? "loaded" : outer[e] > 0 ? "outer only" : inner[e] > 0 ? "inner only" : "free";
    if (bar[e] > 0) s += " +bar";
    out.push_back(s);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: step_limits SCENE.toml [END_TIME_S] [INTERVAL_S]\n");
    return 2;
  }
  scene::Scene scene = scene::load_scene(argv[1]);
  const double end = argc > 2 ? std::atof(argv[2]) : scene.scene.end_time;
  const double dt = argc > 3 ? std::atof(argv[3]) : scene.scene.output_interval;
  const Model model = build_model(scene);
  scheduler::SerialExecutor executor;
  Equations eq(model, executor);
  executor.attach(eq.task_catalogue());
  std::vector<double> z = initial_state(model, 0.0).state, zdot(z.size());
  Integrator integrator(eq, scene.solver, 0.0, z);

  std::vector<long> last_largest(z.size(), 0);
  long last_steps = 0, last_failures = 0;
  std::map<std::string, double> held, present;  // contact state -> steps held; element-intervals in it
  std::vector<std::string> before(static_cast<std::size_t>(model.element_count), "start");
  long onsets = 0;  // a rolling element free at one interval's end and touching a race at the next
  std::printf("t_s,steps,error_test_failures,limiting_state,limiting_element,contact_state\n");
  const long intervals = std::lround(end / dt);
  for (long i = 1; i <= intervals; ++i) {
    const double t = static_cast<double>(i) * dt;
    integrator.advance_to(t, z);
    eq.rhs(t, z.data(), zdot.data());
    const std::vector<std::string> states = contact_states(model, eq);
    for (std::size_t e = 0; e < states.size(); ++e) {
      if (before[e].starts_with("free") && !states[e].starts_with("free")) ++onsets;
      before[e] = states[e];
    }
    const StepLimitingStates& lim = integrator.step_limiting_states();
    const IntegratorStatistics st = integrator.statistics();
    std::size_t worst = 0;
    long worst_count = -1;
    for (std::size_t k = 0; k < z.size(); ++k) {
      const long d = lim.largest[k] - last_largest[k];
      if (d > worst_count) worst_count = d, worst = k;
    }
    // Charge the interval's steps to the elements that held them, by contact state.
    for (int e = 0; e < model.element_count; ++e) {
      const Body& b = model.bodies[static_cast<std::size_t>(model.first_element + e)];
      long count = 0;
      for (int c = 0; c < 12; ++c)
        if (b.slot[c] >= 0) count += lim.largest[static_cast<std::size_t>(b.slot[c])] - last_largest[static_cast<std::size_t>(b.slot[c])];
      held[states[static_cast<std::size_t>(e)]] += static_cast<double>(count);
      present[states[static_cast<std::size_t>(e)]] += 1;
    }
    int element = -1;
    for (int e = 0; e < model.element_count; ++e) {
      const Body& b = model.bodies[static_cast<std::size_t>(model.first_element + e)];
      for (int c = 0; c < 12; ++c)
        if (b.slot[c] == static_cast<int>(worst)) element = e;
    }
    std::printf("%.9g,%ld,%ld,%s,%d,%s\n", t, st.steps - last_steps, st.error_test_failures - last_failures,
                model.state_name[worst].c_str(), element,
                element >= 0 ? states[static_cast<std::size_t>(element)].c_str() : "");
    last_largest = lim.largest;
    last_steps = st.steps, last_failures = st.error_test_failures;
  }
  const IntegratorStatistics st = integrator.statistics();
  double held_total = 0, present_total = 0;
  for (const auto& [k, v] : held) held_total += v;
  for (const auto& [k, v] : present) present_total += v;
  std::fprintf(stderr, "%s: %.4g s, %ld steps, %ld error-test failures, %ld steps held by rolling elements\n",
               argv[1], end, st.steps, st.error_test_failures, static_cast<long>(held_total));
  std::fprintf(stderr, "race contact onsets of free rolling elements (seen at the interval ends): %ld, %.3g per "
               "element per ms\n", onsets, static_cast<double>(onsets) / model.element_count / (end * 1e3));
  std::fprintf(stderr, "%-18s %16s %16s\n", "contact state", "steps held", "time share");
  for (const auto& [k, v] : present)
    std::fprintf(stderr, "%-18s %15.1f%% %15.1f%%\n", k.c_str(), 100 * held[k] / held_total, 100 * v / present_total);
  return 0;
}
