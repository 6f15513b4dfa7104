// The rules of a race's imperfections (spall, waviness) and of the housing (scene_rules.hpp).
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "io/scene/scene_rules.hpp"

namespace raceway::scene::schema::rules {

namespace {
/// A race's imperfection turns with its ring: a driven ring's angle is its speed's integral, a fixed
/// ring's 0; a free ring's angle about its axis is not integrated (its grooves are surfaces of revolution).
void ring_angle_known(const Section& s, const Bind& b, std::string_view key) {
  s.check(b.ring->motion != RingMotion::free, key, [&] {
    return fmt::format("a {} needs a ring whose angle is known: motion = \"fixed\" or \"driven\" (a free ring's "
                       "angle about its axis is not integrated)",
                       key);
  });
}
}  // namespace

void spall_given(const Row&, const Section& s, Bind& b) {
  ring_angle_known(s, b, "spall");
  SpallSpec& spall = b.ring->spall;
  spall.present = true;
  // The ball spacing on the race: a longer spall holds two balls at once, which the defect models
  // (one ball entering, rolling over, leaving) do not describe.
  const BearingGeometry& g = b.scene.bearing;
  const bool inner = b.ring == &b.scene.inner_ring;
  const double race = inner ? g.inner_race_diameter() : g.outer_race_diameter();
  const double spacing = std::numbers::pi * race / g.rolling_elements;
  const Section table = s.sub("spall");
  table.check(spall.length < spacing, "length", [&] {
    return fmt::format("a spall of {} is longer than the balls' spacing on the race ({}); one ball at a time rolls "
                       "over a spall",
                       mm(spall.length), mm(spacing));
  });
}

void waviness_lists_match(const Row&, const Section& s, Bind& b) {
  ring_angle_known(s, b, "waviness");
  WavinessSpec& w = b.ring->waviness;
  const Section table = s.sub("waviness");
  table.check(w.amplitudes.size() == w.orders.size(), "amplitudes", [&] {
    return fmt::format("{} amplitudes for {} orders; give one amplitude per order", w.amplitudes.size(),
                       w.orders.size());
  });
  if (w.phases.empty()) w.phases.assign(w.orders.size(), 0.0);
  table.check(w.phases.size() == w.orders.size(), "phases", [&] {
    return fmt::format("{} phases for {} orders; give one phase per order (or none: all 0)", w.phases.size(),
                       w.orders.size());
  });
  table.check(!w.orders.empty(), "orders", [] { return std::string("give at least one order"); });
}

std::optional<std::string> housing_holds_fixed_outer_ring(const Section&, const Bind& b) {
  if (b.scene.outer_ring.motion == RingMotion::fixed) return std::nullopt;
  return fmt::format("the housing holds the outer ring, which then moves with it: needs [outer_ring] motion = "
                     "\"fixed\", found \"{}\"",
                     option_name(kRingMotions, int(b.scene.outer_ring.motion)));
}

void sensor_interval_within_output(const Row&, const Section& s, Bind& b) {
  const double sensor = b.scene.housing.sensor_interval, output = b.scene.scene.output_interval;
  s.check(sensor <= output, "sensor_interval", [&] {
    return fmt::format("a sensor interval of {:g} s is longer than output_interval ({:g} s); the sensor samples at "
                       "least as often as the output",
                       sensor, output);
  });
  const double ratio = output / sensor;
  s.check(std::abs(ratio - std::round(ratio)) <= 1e-6 * ratio && ratio <= 1e5, "sensor_interval", [&] {
    return fmt::format("output_interval ({:g} s) must be a whole multiple of the sensor interval ({:g} s), at most "
                       "100000 of them; it is {:.6g} of them",
                       output, sensor, ratio);
  });
}

}  // namespace raceway::scene::schema::rules
