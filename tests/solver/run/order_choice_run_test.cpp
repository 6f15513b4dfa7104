// The automatic BDF order in whole runs (solver/numerics/order_choice.hpp): the default scene, whose
// light rollers' contact vibrations hold BDF orders 3-5 at their stability limit, goes to order 2
// within its first 200 steps' probe and takes far fewer steps than at a fixed order 5; a run
// stopped by a signal after that and resumed from its checkpoint keeps the choice (order 2, the
// same switch time) instead of choosing again. 6309 R3 (a ball bearing whose film damps the
// balls' vibrations) keeps order 5: its probes of order 2 lose.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <span>
#include <string>

#include "io/scene/scene_parser.hpp"
#include "io/scene/scene_override.hpp"
#include "solver/run/run.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::run {
namespace {

scene::Scene default_scene(const std::string& end_time, const char* max_order = nullptr) {
  std::string text = scene::override_scene_key(scene::default_scene_text(), "scene", "end_time", end_time);
  if (max_order) text = scene::override_scene_key(text, "solver", "max_order", max_order);
  return scene::parse_scene(text, "default");
}

/// "BDF order at most 2 since t = ..." without the counts that follow.
std::string choice_head(const RunSummary& s) { return s.order_choice.substr(0, s.order_choice.find(" (")); }

TEST(AutomaticOrder, DefaultSceneGoesToOrderTwoAndAResumeKeepsIt) {
  test::TempDir dir;
  const scene::Scene automatic = default_scene("\"5 ms\"");
  ASSERT_TRUE(automatic.solver.automatic_order);
  RunOptions options;
  options.output_path = dir.file("whole.h5");
  const RunSummary whole = run_scene(automatic, options);
  options.output_path = dir.file("order5.h5");
  const RunSummary order5 = run_scene(default_scene("\"5 ms\"", "5"), options);
  std::printf("[ automatic order ] 5 ms: %ld steps (%s), at order 5 %ld steps (%s)\n", whole.stats.steps,
              whole.order_choice.c_str(), order5.stats.steps, order5.order_choice.c_str());
  EXPECT_EQ(whole.order_choice.rfind("BDF order at most 2 since t = ", 0), 0u) << whole.order_choice;
  EXPECT_LT(2 * whole.stats.steps, order5.stats.steps);

  // Stopped at 3 ms (after the switch, 2 ms in), resumed from the signal checkpoint.
  std::atomic<int> stop{0};
  options.output_path = dir.file("resumed.h5");
  options.stop_signal = &stop;
  options.on_progress = [&](const Progress& p) {
    if (p.time >= 3e-3) stop = 15;
  };
  EXPECT_THROW(run_scene(automatic, options), RunInterrupted);
  stop = 0;
  options.on_progress = nullptr;
  options.resume = true;
  const RunSummary resumed = run_scene(automatic, options);
  EXPECT_EQ(choice_head(resumed), choice_head(whole)) << resumed.order_choice;
  EXPECT_NEAR(resumed.simulated_time_s, 5e-3, 1e-12);
}

TEST(AutomaticOrder, BallBearingKeepsOrderFive) {
  const std::string path = std::string(RACEWAY_SOURCE_DIR) + "/jobs/scenes/6309_R3.toml";
  // BDF at rtol 1e-6 in the bearing frame, as the scene shipped it when this was measured (it ships
  // Adams of order at most 2 in the balls' orbital frame now; the radial factor is no key of the
  // bearing frame, so the frame is set on the scene read).
  const std::string automatic_keys[] = {"scene.end_time=10 ms", "solver.method=bdf", "solver.rtol=1e-6",
                                        "solver.max_order=5", "solver.automatic_order=true"};
  const std::string fixed[] = {"scene.end_time=10 ms", "solver.method=bdf", "solver.rtol=1e-6", "solver.max_order=5"};
  const auto in_bearing_frame = [&](const auto& keys) {
    scene::Scene s = scene::load_scene(path, keys);
    s.solver.element_velocity_frame = scene::ElementVelocityFrame::bearing;
    s.solver.radial_velocity_tolerance_factor = 1;
    s.solver.pocket_tolerance_factor = 1;
    return s;
  };
  test::TempDir dir;
  RunOptions options;
  options.output_path = dir.file("auto.h5");
  const RunSummary automatic = run_scene(in_bearing_frame(automatic_keys), options);
  options.output_path = dir.file("order5.h5");
  const RunSummary order5 = run_scene(in_bearing_frame(fixed), options);
  std::printf("[ automatic order ] 6309 R3, 10 ms: %ld steps (%s), at order 5 %ld steps\n", automatic.stats.steps,
              automatic.order_choice.c_str(), order5.stats.steps);
  EXPECT_EQ(automatic.order_choice.rfind("BDF order at most 5 since t = 0 s (0 switches after ", 0), 0u)
      << automatic.order_choice;
  // Its two probes of order 2 cost 2.5 % of the steps (measured 1,262 against 1,231).
  EXPECT_LT(static_cast<double>(automatic.stats.steps), 1.1 * static_cast<double>(order5.stats.steps));
}

}  // namespace
}  // namespace raceway::run
