// The [carrier] section (a bearing on a rotating planet carrier, seed 003): read in SI with its units,
// absent by default, and every bad value an error naming the file, line, key and reason. The same for
// the planet gear's flexible rim ([outer_ring] flexibility = "ring_modes").
#include <gtest/gtest.h>

#include <span>
#include <string>

#include "io/scene/scene_parser.hpp"
#include "tests/support/scene_test_util.hpp"

namespace raceway::scene {
namespace {

using namespace test;

std::string with_carrier(std::string_view carrier) {
  return std::string(kPlanarMinimal) + "\n[carrier]\n" + std::string(carrier);
}

/// A scene text and the key and reason of the error it must give.
struct Bad {
  std::string text, key, reason;
};

void expect_errors(std::span<const Bad> bad) {
  for (const Bad& b : bad) {
    const SceneError e = error_of(b.text);
    EXPECT_EQ(e.key(), b.key) << b.text;
    EXPECT_NE(e.reason().find(b.reason), std::string::npos) << e.what();
    EXPECT_GT(e.line(), 0) << e.what();
  }
}

TEST(CarrierScene, AbsentByDefault) {
  const Scene s = parse(kPlanarMinimal);
  EXPECT_FALSE(s.carrier.present);
  EXPECT_FALSE(default_scene().carrier.present);
}

TEST(CarrierScene, ReadInSI) {
  const Scene s = parse(with_carrier("radius = \"120 mm\"\nspeed = { time = [\"0 s\", \"10 ms\"], value = [\"0 rpm\", "
                                     "\"3000 rpm\"] }\n"));
  ASSERT_TRUE(s.carrier.present);
  EXPECT_DOUBLE_EQ(s.carrier.radius, 0.12);
  EXPECT_NEAR(s.carrier.speed(0.01), 3000 * 2 * pi / 60, 1e-12);
  EXPECT_NEAR(s.carrier.speed.derivative(0.005), 3000 * 2 * pi / 60 / 0.01, 1e-9);
}

TEST(CarrierScene, BadValuesNameTheKey) {
  const Bad bad[] = {
      {with_carrier("speed = \"3000 rpm\"\n"), "carrier.radius", "required key is missing"},
      {with_carrier("radius = \"0 mm\"\nspeed = \"3000 rpm\"\n"), "carrier.radius", "must be greater than zero"},
      {with_carrier("radius = \"100 rpm\"\nspeed = \"3000 rpm\"\n"), "carrier.radius", "expected a length"},
      {with_carrier("radius = \"100 mm\"\n"), "carrier.speed", "required key is missing"},
      {with_carrier("radius = \"100 mm\"\nspeed = \"3 mm\"\n"), "carrier.speed", "expected an angular speed"},
      {with_carrier("radius = \"100 mm\"\nspeed = \"3000 rpm\"\ntilt = 1\n"), "carrier.tilt", "unknown key"},
      {spatial("", "\n[carrier]\nradius = \"100 mm\"\nspeed = \"3000 rpm\"\n"), "carrier.radius",
       "only for planar roller bearings"},
      {replaced(with_carrier("radius = \"100 mm\"\nspeed = \"3000 rpm\"\n"), "[scene]\n", "[scene]\ngravity = true\n"),
       "carrier.radius", "cannot take scene.gravity = true"},
  };
  expect_errors(bad);
}

std::string with_outer_ring(std::string_view keys) {
  return replaced(kPlanarMinimal, "translation = \"fixed\"\n", "translation = \"fixed\"\n" + std::string(keys));
}

TEST(FlexibleRingScene, RigidByDefaultAndReadInSI) {
  const Scene rigid = parse(kPlanarMinimal);
  EXPECT_EQ(rigid.outer_ring.flexibility, RingFlexibility::rigid);
  const Scene s = parse(with_outer_ring("flexibility = \"ring_modes\"\nmodes = 6\nrim_thickness = \"4 mm\"\n"
                                        "rim_width = \"9 mm\"\nrim_damping_ratio = 0.05\n"));
  EXPECT_EQ(s.outer_ring.flexibility, RingFlexibility::ring_modes);
  EXPECT_EQ(s.outer_ring.modes, 6);
  EXPECT_DOUBLE_EQ(s.outer_ring.rim_thickness, 0.004);
  EXPECT_DOUBLE_EQ(s.outer_ring.rim_width, 0.009);
  EXPECT_DOUBLE_EQ(s.outer_ring.rim_damping_ratio, 0.05);
  const Scene defaults = parse(with_outer_ring("flexibility = \"ring_modes\"\n"));
  EXPECT_EQ(defaults.outer_ring.modes, 8);
  EXPECT_DOUBLE_EQ(defaults.outer_ring.rim_damping_ratio, 0.02);
}

TEST(FlexibleRingScene, BadValuesNameTheKey) {
  const Bad bad[] = {
      {with_outer_ring("flexibility = \"rubber\"\n"), "outer_ring.flexibility", "ring_modes"},
      {with_outer_ring("modes = 6\n"), "outer_ring.modes", "only with flexibility = \"ring_modes\""},
      {with_outer_ring("rim_thickness = \"4 mm\"\n"), "outer_ring.rim_thickness", "only with flexibility"},
      {with_outer_ring("flexibility = \"ring_modes\"\nmodes = 1\n"), "outer_ring.modes", "between 2 and 40"},
      {with_outer_ring("flexibility = \"ring_modes\"\nrim_thickness = \"0 mm\"\n"), "outer_ring.rim_thickness",
       "must be greater than zero"},
      {with_outer_ring("flexibility = \"ring_modes\"\nrim_width = \"3 s\"\n"), "outer_ring.rim_width",
       "expected a length"},
      {with_outer_ring("flexibility = \"ring_modes\"\nrim_damping_ratio = 2\n"), "outer_ring.rim_damping_ratio",
       "1"},
      {replaced(kPlanarMinimal, "[inner_ring]\n", "[inner_ring]\nflexibility = \"ring_modes\"\n"),
       "inner_ring.flexibility", "only for [outer_ring]"},
      {spatial("[outer_ring]\nmotion = \"fixed\"\n", "[outer_ring]\nmotion = \"fixed\"\nflexibility = \"ring_modes\"\n"),
       "outer_ring.flexibility",
       "only for planar roller bearings"},
  };
  expect_errors(bad);
}

}  // namespace
}  // namespace raceway::scene
