// The rules of a race's imperfections (spall, waviness), of the balls', rollers' and pockets' scatter and of the
// housing (scene_rules.hpp).
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "io/scene/scatter_draws.hpp"
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
  // The rolling elements' spacing on the race: a longer spall holds two at once, which the defect
  // models (one element entering, rolling over, leaving) do not describe.
  const BearingGeometry& g = b.scene.bearing;
  const bool inner = b.ring == &b.scene.inner_ring;
  const double race = inner ? g.inner_race_diameter() : g.outer_race_diameter();
  const double spacing = std::numbers::pi * race / g.rolling_elements;
  const Section table = s.sub("spall");
  table.check(spall.length < spacing, "length", [&] {
    return fmt::format("a spall of {} is longer than the rolling elements' spacing on the race ({}); one at a time "
                       "rolls over a spall",
                       mm(spall.length), mm(spacing));
  });
}

namespace {
/// One amplitude (and phase, or none) per order, at least one order.
void waviness_terms_match(WavinessSpec& w, const Section& table) {
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
}  // namespace

void waviness_lists_match(const Row&, const Section& s, Bind& b) {
  ring_angle_known(s, b, "waviness");
  waviness_terms_match(b.ring->waviness, s.sub("waviness"));
}

void element_spall_given(const Row&, const Section& s, Bind& b) {
  SpallSpec& spall = b.scene.rolling_element.spall;
  spall.present = true;
  const BearingGeometry& g = b.scene.bearing;
  const bool ball = g.is_ball_bearing();
  const double quarter = 0.25 * std::numbers::pi * (ball ? g.ball.ball_diameter : g.roller_diameter);
  const Section table = s.sub("spall");
  const char* what = ball ? "ball" : "roller";
  for (const auto& [key, size] : {std::pair{"length", spall.length}, std::pair{"width", spall.width}}) {
    if (!ball && std::string_view(key) == "width") continue;  // along a roller's axis: any width up to its length
    table.check(size < quarter, key, [&] {
      return fmt::format("a {}'s spall {} of {} reaches over a quarter of the {}'s circumference ({}); the "
                         "{}'s two race contacts, half a circumference apart, meet it one at a time",
                         what, key, mm(size), what, mm(quarter), what);
    });
  }
}

void element_waviness_given(const Row&, const Section& s, Bind& b) {
  waviness_terms_match(b.scene.rolling_element.waviness, s.sub("waviness"));
}

namespace {
std::string um(double metres) { return fmt::format("{:.4g} um", metres * 1e6); }

/// A given list of deviations has one value per rolling element.
void one_per_element(const Section& s, std::string_view key, const std::vector<double>& list, const Bind& b,
                     const char* what) {
  const int count = b.scene.bearing.rolling_elements;
  s.check(static_cast<int>(list.size()) == count, key, [&] {
    return fmt::format("{} values for {} {}s; give one per {} ({} first)", list.size(), count, what, what,
                       std::string(what) == "pocket" ? "pocket 0" : std::string(what) + "[0]");
  });
}

/// A scatter draws the list of deviations, unless the list is given (then the scatter must be 0).
void draw_unless_given(const Section& s, std::string_view key, std::string_view list_key, double scatter,
                       std::vector<double>& list, const Bind& b, ScatterStream stream) {
  if (scatter == 0) return;
  s.check(list.empty(), key, [&] {
    return fmt::format("give either {} or {}, not both (the list already sets every value)", key, list_key);
  });
  const int count = b.scene.bearing.rolling_elements;
  list = standard_normal_draws(static_cast<std::uint64_t>(b.scene.bearing.scatter_seed), stream, count);
  for (double& d : list) d *= scatter;
}
}  // namespace

void ball_deviations_per_ball(const Row& row, const Section& s, Bind& b) {
  one_per_element(s, row.key, b.scene.bearing.ball_diameter_deviations, b, "ball");
}

void ball_diameters_drawn(const Row& row, const Section& s, Bind& b) {
  BearingGeometry& g = b.scene.bearing;
  draw_unless_given(s, row.key, "ball_diameter_deviations", g.ball_diameter_scatter, g.ball_diameter_deviations, b,
                    ScatterStream::element_diameter);
}

void roller_deviations_per_roller(const Row& row, const Section& s, Bind& b) {
  one_per_element(s, row.key, b.scene.bearing.roller_diameter_deviations, b, "roller");
}

/// The rollers' diameters: drawn from the balls' stream of the seed (a bearing has balls or rollers,
/// never both).
void roller_diameters_drawn(const Row& row, const Section& s, Bind& b) {
  BearingGeometry& g = b.scene.bearing;
  draw_unless_given(s, row.key, "roller_diameter_deviations", g.roller_diameter_scatter, g.roller_diameter_deviations,
                    b, ScatterStream::element_diameter);
}

void pocket_deviations_per_pocket(const Row& row, const Section& s, Bind& b) {
  one_per_element(s, row.key, b.scene.cage.pocket_clearance_deviations, b, "pocket");
}

void pocket_clearances_drawn(const Row& row, const Section& s, Bind& b) {
  CageSpec& cage = b.scene.cage;
  draw_unless_given(s, row.key, "pocket_clearance_deviations", cage.pocket_clearance_scatter,
                    cage.pocket_clearance_deviations, b, ScatterStream::pocket_clearance);
  // Every pocket must still hold its ball with play: the pocket's diameter (ball_diameter +
  // its clearance) exceeds its ball's.
  const std::vector<double>& balls = b.scene.bearing.ball_diameter_deviations;
  for (int k = 0; k < b.scene.bearing.rolling_elements; ++k) {
    const double pocket = cage.pocket_clearance + (cage.pocket_clearance_deviations.empty()
                                                       ? 0.0 : cage.pocket_clearance_deviations[std::size_t(k)]);
    const double ball = balls.empty() ? 0.0 : balls[std::size_t(k)];
    const std::string_view key = cage.pocket_clearance_scatter > 0             ? row.key
                                 : !cage.pocket_clearance_deviations.empty() ? "pocket_clearance_deviations"
                                                                             : "pocket_clearance";
    s.check(pocket - ball > 0, key, [&] {
      return fmt::format("pocket {} leaves its ball no play: its clearance {} less the ball's oversize {} is {} (a "
                         "smaller scatter, another scatter_seed or a larger pocket_clearance)",
                         k, um(pocket), um(ball), um(pocket - ball));
    });
  }
}

std::optional<std::string> housing_holds_fixed_outer_ring(const Section&, const Bind& b) {
  if (b.scene.outer_ring.motion == RingMotion::fixed) return std::nullopt;
  return fmt::format("the housing holds the outer ring, which then moves with it: needs [outer_ring] motion = "
                     "\"fixed\", found \"{}\"",
                     option_name(kRingMotions, int(b.scene.outer_ring.motion)));
}

void housing_mode_lists_match(const Row&, const Section& s, Bind& b) {
  HousingSpec& h = b.scene.housing;
  const Section table = s.sub("modes");
  const std::size_t n = h.mode_masses.size();
  table.check(n > 0, "masses", [] { return std::string("give at least one further mode"); });
  table.check(h.mode_stiffnesses.size() == n, "stiffnesses", [&] {
    return fmt::format("{} stiffnesses for {} masses; give one stiffness per mode", h.mode_stiffnesses.size(), n);
  });
  if (h.mode_dampings.empty()) h.mode_dampings.assign(n, 0.0);
  table.check(h.mode_dampings.size() == n, "dampings", [&] {
    return fmt::format("{} dampings for {} masses; give one damping per mode (or none: all 0)", h.mode_dampings.size(),
                       n);
  });
}

void sensor_participation_per_mode(const Row&, const Section& s, Bind& b) {
  const HousingSpec& h = b.scene.housing;
  const std::size_t modes = 1 + h.mode_masses.size();
  s.check(h.sensor_participation.size() == modes, "sensor_participation", [&] {
    return fmt::format("{} values for {} modes of the housing (its own and {} in [housing.modes]); give one per mode",
                       h.sensor_participation.size(), modes, modes - 1);
  });
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
