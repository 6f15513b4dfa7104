// The [carrier] section (a bearing on a rotating planet carrier, seed 003): read in SI with its units,
// absent by default, and every bad value an error naming the file, line, key and reason.
#include <gtest/gtest.h>

#include <string>

#include "io/scene/scene_parser.hpp"
#include "tests/io/scene_test_util.hpp"

namespace raceway::io {
namespace {

using namespace test;

std::string with_carrier(std::string_view carrier) {
  return std::string(kPlanarMinimal) + "\n[carrier]\n" + std::string(carrier);
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
  struct Bad {
    std::string text, key, reason;
  };
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
  for (const Bad& b : bad) {
    const SceneError e = error_of(b.text);
    EXPECT_EQ(e.key(), b.key) << b.text;
    EXPECT_NE(e.reason().find(b.reason), std::string::npos) << e.what();
    EXPECT_GT(e.line(), 0) << e.what();
  }
}

}  // namespace
}  // namespace raceway::io
