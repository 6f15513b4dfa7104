// Drag and churning in an oil-air mixture on a whole run (solver/bearing/ball_model.cpp,
// add_mixture_drag): the 6205 of the first scene over one inner-ring revolution, with and without
// `[lubricant] oil_volume_fraction`. The drag slows the cage; the balls' drag power is the sphere drag
// at their orbital speed, the cage's churning power von Karman's moment at its speed; without the key
// the model has no drag element at all.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "contact/laws/mixture_drag.hpp"
#include "solver/bearing/model.hpp"
#include "solver/run/run.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::run {
namespace {

scene::Scene first_scene(double oil_volume_fraction) {
  scene::Scene s = test::load_job_scene("6205_first_scene.toml");
  s.scene.end_time = 0.02;  // one inner-ring revolution at 3000 rpm
  s.lubricant.density = 870;
  s.lubricant.oil_volume_fraction = oil_volume_fraction;
  return s;
}

struct DragRun {
  test::Dataset time, cage_speed, ball_drag, churning;
  double mean_cage_speed = 0;  ///< rad/s over the second half
};

DragRun run(const scene::Scene& s, bool drag) {
  test::TempDir dir;
  RunOptions options;
  options.output_path = dir.file("drag.h5");
  run_scene(s, options);
  DragRun r;
  r.time = test::read_dataset(options.output_path, "/time");
  r.cage_speed = test::read_dataset(options.output_path, "/cage/angular_velocity");
  if (drag) {
    r.ball_drag = test::read_dataset(options.output_path, "/segments/ball_drag/power_loss");
    r.churning = test::read_dataset(options.output_path, "/segments/cage_churning/power_loss");
  }
  int n = 0;
  for (std::size_t i = r.time.values.size() / 2; i < r.time.values.size(); ++i, ++n)
    r.mean_cage_speed += r.cage_speed.at(i, 2);
  r.mean_cage_speed /= n;
  return r;
}

TEST(MixtureDragRun, SlowsTheCageAndLosesTheDragPower) {
  const scene::Scene dry = first_scene(0), wet = first_scene(0.05);
  EXPECT_EQ(bearing::build_model(dry).first_segment(bearing::SegmentKind::ball_drag), nullptr);
  const bearing::Model m = bearing::build_model(wet);
  const auto& ball = m.law<contact::BallDragSegment>(*m.first_segment(bearing::SegmentKind::ball_drag));
  const auto& cage = m.law<contact::CageChurningSegment>(*m.first_segment(bearing::SegmentKind::cage_churning));
  const DragRun without = run(dry, false), with = run(wet, true);
  std::printf("[ drag ] cage %.3f rpm without drag, %.3f rpm with (oil volume fraction 0.05)\n",
              without.mean_cage_speed * 30 / std::numbers::pi, with.mean_cage_speed * 30 / std::numbers::pi);
  EXPECT_LT(with.mean_cage_speed, without.mean_cage_speed);
  // Per sample of the second half: the cage's churning power is von Karman's moment times its speed
  // (the outer ring is fixed: the mixture is at rest); the balls' drag is Z times the sphere drag at
  // the orbital speed (cage speed times pitch radius), up to each ball's own radial and axial motion
  // and its lead or lag in the pocket.
  double drag_sum = 0, expected_sum = 0;
  for (std::size_t i = with.time.values.size() / 2; i < with.time.values.size(); ++i) {
    const double w = with.cage_speed.at(i, 2);
    const double churning = -contact::ring_churning_moment(cage.mixture, cage.bore_radius, cage.outside_radius, w) * w;
    EXPECT_NEAR(with.churning.at(i, 0), churning, 1e-6 * churning);
    const Eigen::Vector3d orbital(w * m.pitch_radius, 0, 0);
    expected_sum += m.element_count * contact::sphere_drag(ball.mixture, ball.ball_diameter, orbital).power_loss;
    for (std::size_t k = 0; k < with.ball_drag.shape.at(1); ++k) drag_sum += with.ball_drag.at(i, k);
  }
  std::printf("[ drag ] balls' drag power %.4g W against %.4g W at the orbital speed\n", drag_sum, expected_sum);
  EXPECT_NEAR(drag_sum / expected_sum, 1.0, 0.02);
}

}  // namespace
}  // namespace raceway::run
