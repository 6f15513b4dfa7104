// The rules of a scene that tie keys together (scene_rules.hpp).
#include "io/scene/scene_rules.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace raceway::scene::schema::rules {

namespace {

constexpr double kPi = std::numbers::pi;

std::string_view element(const Bind& b) { return b.ball() ? "ball" : "roller"; }
double element_diameter(const Bind& b) { return b.scene.bearing.element_diameter(); }
std::string_view motion_name(const RingSpec& r) { return option_name(kRingMotions, int(r.motion)); }
std::string_view tilt_name(const RingSpec& r) { return option_name(kRingTilts, int(r.tilt)); }

}  // namespace

// ---- defaults that follow from other keys ------------------------------------------------------

std::optional<double> inner_bore_default(const Bind& b) {
  return b.scene.bearing.inner_race_diameter() - element_diameter(b);
}
std::optional<double> outer_outside_default(const Bind& b) {
  return b.scene.bearing.outer_race_diameter() + element_diameter(b);
}
// A roller bearing's rings are as wide as the rollers; a ball bearing's width has no natural
// default (it sets the ring masses and the cage width).
std::optional<double> ring_width_default(const Bind& b) {
  return b.ball() ? std::nullopt : std::optional<double>(b.scene.bearing.roller_length);
}
std::optional<double> bar_width_default(const Bind& b) { return b.scene.bearing.roller_length; }
// Rollers: half the roller length rides on the land; balls: the land is the two ring shoulders
// beside the groove, ring width - ball diameter in all.
std::optional<double> land_width_default(const Bind& b) {
  const BearingGeometry& g = b.scene.bearing;
  return b.ball() ? g.ring_width - element_diameter(b) : 0.5 * g.roller_length;
}
// A machined cage ring: d_m -/+ 0.6 D across and 0.8 ring widths wide.
std::optional<double> cage_bore_default(const Bind& b) {
  return b.scene.bearing.pitch_diameter - 0.6 * element_diameter(b);
}
std::optional<double> cage_outside_default(const Bind& b) {
  return b.scene.bearing.pitch_diameter + 0.6 * element_diameter(b);
}
std::optional<double> cage_width_default(const Bind& b) { return 0.8 * b.scene.bearing.ring_width; }
// A planar support is radial only, so its stiffness is the support; a spatial one names directions.
std::optional<double> ring_support_stiffness_default(const Bind& b) {
  return b.ball() ? std::optional<double>(0.0) : std::nullopt;
}
// Lubricated steel and brass on the rolling elements; less on the cage land.
std::optional<double> friction_default(const Bind& b) {
  return b.contact_kind == contact::cage_land_contact ? 0.05 : 0.1;
}
// EHL rolling resistance: on wherever there is a lubricant (a film).
std::optional<double> rolling_resistance_default(const Bind& b) {
  return b.scene.lubricant.viscosity > 0 ? 1.0 : 0.0;
}
// Per method: the default and the largest max_order. bdf and adams: CVODE's largest orders; erk:
// Dormand-Prince 5(4) by default, Fehlberg 8(7) the highest; ark: ARKODE's default implicit order 4.
namespace {
struct MethodOrders {
  IntegrationMethod method;
  int default_order, largest_order;
};
constexpr MethodOrders kMethodOrders[] = {{IntegrationMethod::bdf, 5, 5},
                                          {IntegrationMethod::adams, 12, 12},
                                          {IntegrationMethod::erk, 5, 8},
                                          {IntegrationMethod::ark, 4, 5}};
const MethodOrders& orders_of(IntegrationMethod m) {
  for (const MethodOrders& o : kMethodOrders)
    if (o.method == m) return o;
  return kMethodOrders[0];
}
}  // namespace
std::optional<double> max_order_default(const Bind& b) { return orders_of(b.scene.solver.method).default_order; }
long max_order_limit(const Bind& b) { return orders_of(b.scene.solver.method).largest_order; }
std::optional<double> automatic_order_default(const Bind& b) {
  return b.scene.solver.method == IntegrationMethod::bdf && b.scene.line_of("solver.max_order") == 0 ? 1.0 : 0.0;
}

// ---- conditions --------------------------------------------------------------------------------

std::optional<std::string> four_point_only(const Section&, const Bind& b) {
  if (b.scene.bearing.type == BearingType::four_point_contact_ball) return std::nullopt;
  return "only for type = \"four_point_contact_ball\": a deep groove ball bearing's contact angle comes out of its "
         "clearance, conformities and loads";
}
std::optional<std::string> contact_angle_applies(const Section& s, const Bind& b) {
  if (b.scene.bearing.type != BearingType::angular_contact_ball)
    return "only for type = \"angular_contact_ball\": a deep groove or four-point bearing's contact angle comes out "
           "of its clearance, conformities (and arc angle) and loads";
  if (s.has("radial_clearance"))
    return "the free contact angle follows here from radial_clearance (cos alpha_0 = 1 - P_d / (2 (f_i + f_o - 1) "
           "D)): give one of them";
  return std::nullopt;
}
std::optional<std::string> axially_held_only(const Section&, const Bind& b) {
  if (!(b.ring->motion != RingMotion::fixed && b.ring->axial_free)) return std::nullopt;
  return "only for a ring held axially (motion = \"fixed\" or axial = \"fixed\"): a ring free along z finds its "
         "axial position from its loads";
}
std::optional<std::string> unless_ball_material(const Section& s, const Bind& b) {
  if (!(b.ball() && s.has("ball_material"))) return std::nullopt;
  return "give the ball material once: ball_material and roller_material name the same thing";
}
std::optional<std::string> land_guided_only(const Section&, const Bind& b) {
  if (b.scene.cage.guidance != CageGuidance::rolling_element) return std::nullopt;
  return fmt::format("not allowed with guidance = \"rolling_element\": a {}-guided cage touches no land", element(b));
}
std::optional<std::string> driven_ring_only(const Section&, const Bind& b) {
  if (b.ring->motion == RingMotion::driven) return std::nullopt;
  return fmt::format("speed is only for motion = \"driven\"; this ring is \"{}\"", motion_name(*b.ring));
}
std::optional<std::string> moving_ring_only(const Section&, const Bind& b) {
  if (b.ring->motion != RingMotion::fixed) return std::nullopt;
  return "not allowed with motion = \"fixed\": a fixed ring is held in every direction";
}
std::optional<std::string> outer_ring_only(const Section& s, const Bind&) {
  if (s.path() == "outer_ring") return std::nullopt;
  return "only for [outer_ring]: the planet gear's rim (a flexible inner ring is not modelled)";
}
std::optional<std::string> ring_modes_only(const Section& s, const Bind& b) {
  if (auto why = outer_ring_only(s, b)) return why;
  if (b.ring->flexibility == RingFlexibility::ring_modes) return std::nullopt;
  return "only with flexibility = \"ring_modes\": a rigid ring has no bending modes";
}
std::optional<std::string> prescribed_tilt_only(const Section&, const Bind& b) {
  if (b.ring->tilt == RingTilt::prescribed) return std::nullopt;
  return fmt::format("only for tilt = \"prescribed\"; this ring's tilt is \"{}\"", tilt_name(*b.ring));
}
std::optional<std::string> force_needs_free_centre(const Section&, const Bind& b) {
  if (b.ring->translation_free) return std::nullopt;
  return "this ring's centre is held (motion = \"fixed\" or translation = \"fixed\"): a force on it has no effect";
}
std::optional<std::string> axial_force_needs_axially_free(const Section&, const Bind& b) {
  if (b.ring->axial_free) return std::nullopt;
  return "this ring is held axially (motion = \"fixed\" or axial = \"fixed\"): an axial force on it has no effect";
}
std::optional<std::string> tilting_moment_needs_free_tilt(const Section&, const Bind& b) {
  if (b.ring->tilt == RingTilt::free) return std::nullopt;
  return fmt::format("a tilting moment needs tilt = \"free\"; this ring's tilt is \"{}\"", tilt_name(*b.ring));
}
std::optional<std::string> moment_needs_free_ring(const Section&, const Bind& b) {
  if (b.ring->motion == RingMotion::free) return std::nullopt;
  return fmt::format("a moment is only allowed for motion = \"free\"; this ring is \"{}\"", motion_name(*b.ring));
}
// Planar supports are radial: the centre must be free. Spatial supports name their directions,
// each checked on its own; the ring must move at all.
std::optional<std::string> support_needs_moving_ring(const Section&, const Bind& b) {
  if (!b.ball() && !b.ring->translation_free) return "a support is only for a ring with translation = \"free\"";
  if (b.ball() && b.ring->motion == RingMotion::fixed)
    return "a support is only for a ring that moves (motion = \"driven\" or \"free\")";
  return std::nullopt;
}
std::optional<std::string> radial_support_needs_free_centre(const Section&, const Bind& b) {
  if (b.ring->translation_free) return std::nullopt;
  return "this ring's translation is \"fixed\": a support in that direction has no effect";
}
std::optional<std::string> axial_support_needs_axially_free(const Section&, const Bind& b) {
  if (b.ring->axial_free) return std::nullopt;
  return "this ring's axial position is \"fixed\": a support in that direction has no effect";
}
std::optional<std::string> tilt_support_needs_free_tilt(const Section&, const Bind& b) {
  if (b.ring->tilt == RingTilt::free) return std::nullopt;
  return fmt::format("this ring's tilt is \"{}\" (not \"free\"): a support in that direction has no effect",
                     tilt_name(*b.ring));
}
std::optional<std::string> damping_law_on(const Section&, const Bind& b) {
  if (b.contact->damping.id != contact::LawId::no_damping) return std::nullopt;
  return "has no effect with damping = \"none\"";
}
std::optional<std::string> traction_law_on(const Section&, const Bind& b) {
  if (b.contact->traction.id != contact::LawId::no_traction) return std::nullopt;
  return "has no effect with traction = \"none\"";
}
std::optional<std::string> bdf_only(const Section&, const Bind& b) {
  if (b.scene.solver.method == IntegrationMethod::bdf) return std::nullopt;
  return "only for method = \"bdf\": the stability-limit detection watches CVODE's BDF orders 3 to 5";
}

std::optional<std::string> bdf_order_choice(const Section&, const Bind& b) {
  if (b.scene.solver.method == IntegrationMethod::bdf) return std::nullopt;
  return "only for method = \"bdf\": it chooses between BDF's orders up to max_order and the A-stable BDF2";
}

// ---- checks after a key is read ----------------------------------------------------------------

// Every name must be a key of this scene file: a misspelt one would silently allow nothing.
void allowed_keys_in_scene(const Row& row, const Section& s, Bind& b) {
  const Scene& scene = b.scene;
  Names keys;
  for (const auto& [key, line] : scene.key_lines) keys.push_back(key);
  for (const std::string& name : scene.scene.allow_out_of_range)
    s.check(scene.key_lines.contains(name), row.key, [&] {
      return fmt::format("'{}' is not a key of this scene file{} (name keys as section.key, e.g. "
                         "\"inner_ring.speed\")",
                         name, suggestion(name, keys));
    });
}

void output_interval_within_run(const Row&, const Section& s, Bind& b) {
  const SceneInfo& info = b.scene.scene;
  s.check(info.output_interval <= info.end_time, "output_interval", [&] {
    return fmt::format("output interval of {:g} s is longer than end_time ({:g} s)", info.output_interval,
                       info.end_time);
  });
}

// Gravity is fixed in space and so turns in the carrier's frame; raceway's gravity is fixed in the
// bearing frame, which would be wrong here (and it is 1e-4 of a carrier's field in practice).
void carrier_without_gravity(const Row&, const Section& s, Bind& b) {
  s.check(!b.scene.gravity, "radius", [] {
    return std::string("a bearing on a rotating carrier cannot take scene.gravity = true: gravity would turn in the "
                       "carrier's frame, which raceway does not model (it is a ten-thousandth of the carrier's field "
                       "in a planetary gearbox); set gravity = false");
  });
}

void initial_step_within_run(const Row&, const Section& s, Bind& b) {
  const double step = b.scene.solver.initial_step, end = b.scene.scene.end_time;
  s.check(step <= end, "initial_step", [&] {
    return fmt::format("initial step of {:g} s is longer than the run (end_time = {:g} s)", step, end);
  });
}

// Planar: cylindrical roller bearings (x, y, rotation about z); spatial: ball bearings and
// cylindrical roller bearings, all six directions. Ball-groove contacts are three-dimensional.
void model_fits_bearing_type(const Row&, const Section&, Bind& b) {
  const bool spatial = b.scene.scene.model == ModelKind::spatial;
  if (!spatial && b.scene.bearing.is_tapered())
    b.info->fail("model", "a tapered_roller bearing needs model = \"spatial\": its raceways are cones and its rollers "
                          "lean to the axis (the planar model is for cylindrical roller bearings)");
  if (!spatial && b.ball())
    b.info->fail("model", fmt::format("a {} bearing needs model = \"spatial\": ball-groove contacts are three-"
                                      "dimensional (the planar model is for cylindrical roller bearings)",
                                      option_name(kBearingTypes, int(b.scene.bearing.type))));
}

void clearance_fits_elements(const Row&, const Section& s, Bind& b) {
  const BearingGeometry& g = b.scene.bearing;
  const double dw = element_diameter(b);
  // A negative clearance is a preload (an interference fit, a tapered seat): roller bearings only,
  // and at most 1 % of the roller, beyond which the rollers would be crushed before any load.
  s.check(g.radial_clearance >= 0 || !b.ball(), "radial_clearance", [&] {
    return fmt::format("a negative clearance ({}, a preload) is for roller bearings; preload a ball bearing by "
                       "an axial load on a ring",
                       mm(g.radial_clearance));
  });
  s.check(g.radial_clearance >= -0.01 * dw, "radial_clearance", [&] {
    return fmt::format("a preload of {} (negative clearance) is more than 1 % of the {} diameter ({}); preloads "
                       "are a few micrometres to a few tens of them",
                       mm(-g.radial_clearance), element(b), mm(dw));
  });
  s.check(g.radial_clearance < dw, "radial_clearance", [&] {
    return fmt::format("clearance larger than a {}: {} clearance with {} {}s", element(b), mm(g.radial_clearance),
                       mm(dw), element(b));
  });
  // Ball bearings: clearances are micrometres to a few tens of them; 5 % of the ball catches a unit slip.
  if (b.ball())
    s.check(g.radial_clearance <= 0.05 * dw, "radial_clearance", [&] {
      return fmt::format("a clearance of {} is more than 5 % of the ball diameter ({}); ball bearing clearances are "
                         "a few to a few tens of micrometres",
                         mm(g.radial_clearance), mm(dw));
    });
  // An angular contact bearing given by its groove geometry: the grooves' curvature centres are
  // A = (f_i + f_o - 1) D apart, and the clearance taken up axially puts them at the free contact
  // angle, cos(alpha_0) = 1 - P_d / (2 A).
  if (g.type == BearingType::angular_contact_ball && s.has("radial_clearance")) {
    const double a = (g.ball.inner_conformity + g.ball.outer_conformity - 1) * dw;
    const double angle = std::acos(std::clamp(1 - g.radial_clearance / (2 * a), -1.0, 1.0));
    s.check(angle > 0 && angle < kPi / 3, "radial_clearance", [&] {
      return fmt::format("a clearance of {} gives a free contact angle of {:.3g} deg with these conformities; angular "
                         "contact bearings are made with 15 to 40 deg (at most 60)",
                         mm(g.radial_clearance), angle * 180 / kPi);
    });
    b.scene.bearing.ball.free_contact_angle = angle;
  }
  const double inner_race = g.inner_race_diameter();
  s.check(inner_race > 0, b.ball() ? "ball_diameter" : "roller_diameter", [&] {
    return fmt::format("{} {}s on a {} pitch diameter (clearance {}) leave no inner race: its diameter would be {}",
                       mm(dw), element(b), mm(g.pitch_diameter), mm(g.radial_clearance), mm(inner_race));
  });
}

void bore_inside_inner_race(const Row&, const Section& s, Bind& b) {
  const BearingGeometry& g = b.scene.bearing;
  const double inner_race = g.inner_race_diameter();
  s.check(g.inner_bore_diameter > 0 && g.inner_bore_diameter < inner_race, "inner_bore_diameter", [&] {
    return fmt::format("inner bore of {}{} must be greater than zero and smaller than the inner race diameter ({})",
                       mm(g.inner_bore_diameter),
                       s.has("inner_bore_diameter") ? "" : fmt::format(" (default: inner race - {} diameter)", element(b)),
                       mm(inner_race));
  });
}

void outside_beyond_outer_race(const Row&, const Section& s, Bind& b) {
  const BearingGeometry& g = b.scene.bearing;
  s.check(g.outer_outside_diameter > g.outer_race_diameter(), "outer_outside_diameter", [&] {
    return fmt::format("outside diameter of {} must exceed the outer race diameter ({})", mm(g.outer_outside_diameter),
                       mm(g.outer_race_diameter()));
  });
}

void ring_wider_than_ball(const Row&, const Section& s, Bind& b) {
  const BearingGeometry& g = b.scene.bearing;
  if (b.ball())
    s.check(g.ring_width > element_diameter(b), "ring_width", [&] {
      return fmt::format("ring width of {} must exceed the ball diameter ({}): the groove would open through the "
                         "ring's faces",
                         mm(g.ring_width), mm(element_diameter(b)));
    });
}

// Ball pockets: typically 1 to 4 % of the ball diameter; a tenth catches unit slips.
void ball_pocket_clearance_fits(const Row&, const Section& s, Bind& b) {
  const double pocket = b.scene.cage.pocket_clearance, dw = element_diameter(b);
  if (b.ball())
    s.check(pocket < 0.1 * dw, "pocket_clearance", [&] {
      return fmt::format("pocket clearance of {} must be smaller than a tenth of the ball diameter ({})", mm(pocket),
                         mm(0.1 * dw));
    });
}

void land_clearance_fits(const Row&, const Section& s, Bind& b) {
  const double land = b.scene.cage.land_clearance, dw = element_diameter(b);
  s.check(land < 0.5 * dw, "land_clearance", [&] {
    return fmt::format("land clearance of {} must be smaller than half the {} diameter ({})", mm(land), element(b),
                       mm(0.5 * dw));
  });
}

// A cage started off-centre must start free: inside its land clearance and its pockets' play.
void cage_offset_within_clearances(const Row&, const Section& s, Bind& b) {
  const auto& cage = b.scene.cage;
  const double offset = cage.initial_offset;
  const bool land = cage.guidance != CageGuidance::rolling_element;
  const double limit = land ? std::min(cage.land_clearance, 0.5 * cage.pocket_clearance) : 0.5 * cage.pocket_clearance;
  s.check(offset < limit, "initial_offset", [&] {
    return fmt::format("initial offset of {} must be smaller than {} ({}): the cage must start clear of {}", mm(offset),
                       land && cage.land_clearance <= 0.5 * cage.pocket_clearance ? "the land clearance"
                                                                                    : "half the pocket clearance",
                       mm(limit), land ? "its land and the balls" : "the balls");
  });
}

// A land is a shoulder of a ring: it cannot be wider than the ring.
void land_width_within_rings(const Row&, const Section& s, Bind& b) {
  const double land = b.scene.cage.land_width, ring = b.scene.bearing.ring_width;
  s.check(land <= ring, "land_width", [&] {
    return fmt::format("land width of {} is wider than the rings ({}{})", mm(land), mm(ring),
                       b.ball() ? "" : "; ring_width defaults to roller_length");
  });
}

// A roller touches a bar over its length at most: a longer bar contact has no roller to touch.
void bars_within_rollers(const Row&, const Section& s, Bind& b) {
  const double bar = b.scene.cage.bar_width, roller = b.scene.bearing.roller_length;
  s.check(bar <= roller, "bar_width", [&] {
    return fmt::format("bar contact of {} is longer than the rollers ({}): the cage's pockets hold rollers of "
                       "roller_length",
                       mm(bar), mm(roller));
  });
}

namespace {
/// Twice the land clearance on the side the cage is guided on (inner or outer), else 0.
double land_play(const CageSpec& c, CageGuidance side) { return c.guidance == side ? 2 * c.land_clearance : 0.0; }
}  // namespace

void cage_bore_between_race_and_pitch(const Row&, const Section& s, Bind& b) {
  const CageSpec& c = b.scene.cage;
  const double dm = b.scene.bearing.pitch_diameter, play = land_play(c, CageGuidance::inner_land);
  const double lo = b.scene.bearing.inner_race_diameter() + play;
  s.check(c.inner_diameter > lo && c.inner_diameter < dm, "inner_diameter", [&] {
    return fmt::format("cage bore of {}{} must lie between the inner race diameter{} ({}) and the pitch diameter ({})",
                       mm(c.inner_diameter), s.has("inner_diameter") ? "" : " (default: d_m - 0.6 D)",
                       play > 0 ? " plus twice the land clearance" : "", mm(lo), mm(dm));
  });
}

void cage_outside_between_pitch_and_race(const Row&, const Section& s, Bind& b) {
  const CageSpec& c = b.scene.cage;
  const double dm = b.scene.bearing.pitch_diameter, play = land_play(c, CageGuidance::outer_land);
  const double hi = b.scene.bearing.outer_race_diameter() - play;
  s.check(c.outer_diameter < hi && c.outer_diameter > dm, "outer_diameter", [&] {
    return fmt::format("cage outside diameter of {}{} must lie between the pitch diameter ({}) and the outer race "
                       "diameter{} ({})",
                       mm(c.outer_diameter), s.has("outer_diameter") ? "" : " (default: d_m + 0.6 D)", mm(dm),
                       play > 0 ? " minus twice the land clearance" : "", mm(hi));
  });
}

// Wide enough to hold the balls, and within the rings (the cage runs between them).
void cage_width_fits(const Row&, const Section& s, Bind& b) {
  const double width = b.scene.cage.width, dw = element_diameter(b), ring = b.scene.bearing.ring_width;
  s.check(width > 0.5 * dw, "width", [&] {
    return fmt::format("cage width of {} must exceed half the ball diameter ({}): narrower pockets cannot hold the "
                       "balls",
                       mm(width), mm(0.5 * dw));
  });
  s.check(width <= ring, "width", [&] {
    return fmt::format("cage width of {} is wider than the rings ({}): the cage runs between them", mm(width),
                       mm(ring));
  });
}

void cage_support_has_spring(const Row&, const Section& s, Bind& b) {
  if (!b.scene.cage.support.any())
    s.fail("support", "a cage support needs at least one of radial_stiffness, axial_stiffness, tilt_stiffness");
}

// "damping" pairs with "stiffness", "axial_damping" with "axial_stiffness", ...
void damper_has_spring(const Row& row, const Section& s, Bind&) {
  const std::string spring = std::string(row.key.substr(0, row.key.size() - std::string_view("damping").size())) +
                             "stiffness";
  if (s.has(row.key) && !s.has(spring)) s.fail(row.key, fmt::format("a damper needs its spring: give {} too", spring));
}

void fixed_ring_tilt_not_free(const Row&, const Section& s, Bind& b) {
  if (b.ring->motion == RingMotion::fixed && b.ring->tilt == RingTilt::free)
    s.fail("tilt", "a ring with motion = \"fixed\" cannot tilt freely; a misaligned housing is tilt = \"prescribed\"");
}

void misalignment_given(const Row&, const Section& s, Bind&) {
  const Section m = s.sub("misalignment");
  if (!m.has("x") && !m.has("y"))
    s.fail("misalignment", "give x and/or y: rotations about the x and y axes, e.g. x = \"1.42 mrad\"");
}

void ring_support_has_spring(const Row&, const Section& s, Bind& b) {
  const RingSupport& r = b.ring->support;
  if (!(r.stiffness > 0 || r.axial_stiffness > 0 || r.tilt_stiffness > 0))
    s.fail("support", "a support needs at least one of stiffness, axial_stiffness, tilt_stiffness");
}

void crown_drop_fits(const Row&, const Section& s, Bind& b) {
  const double drop = b.contact->normal.crown_drop, dw = element_diameter(b);
  s.check(drop < 0.25 * dw, "crown_drop", [&] {
    return fmt::format("crown drop of {} must be less than a quarter of the {} diameter ({})", mm(drop), element(b),
                       mm(0.25 * dw));
  });
}

// Limiting-shear traction integrates the film's shear stress; where there is no film (dry spots,
// film collapse) it falls back on the friction curve.
void limiting_shear_has_lubricant(const Row&, const Section& s, Bind& b) {
  if (b.contact->traction.id != contact::LawId::limiting_shear) return;
  const Lubricant& lub = b.scene.lubricant;
  if (!(lub.viscosity > 0))
    s.fail("traction", "traction = \"limiting_shear\" needs a lubricant film: set lubricant.viscosity (there is no "
                       "[lubricant] section)");
  if (!(lub.limiting_shear_coefficient > 0))
    s.fail("traction", "traction = \"limiting_shear\" needs lubricant.limiting_shear_coefficient > 0 (limiting shear "
                       "stress = coefficient x pressure; 0.02 to 0.1 for mineral oils)");
}

// The film laws (EHD roller-race, hydrodynamic roller-cage, the cage land's and the ball pocket's films) need a
// viscosity.
void film_law_has_lubricant(const Row&, const Section& s, Bind& b) {
  const contact::LawId id = b.contact->normal.id;
  if (id != contact::LawId::moes_ehd && id != contact::LawId::hydrodynamic && id != contact::LawId::short_bearing &&
      id != contact::LawId::pocket_film)
    return;
  if (id == contact::LawId::pocket_film && b.scene.cage.pocket_shape != PocketShape::cylindrical)
    s.fail("normal", "normal = \"pocket_film\" is the film of a ball in a cylindrical pocket (pocket_shape = "
                     "\"cylindrical\"); a spherical pocket's film is not modelled: give normal = \"hertz\"");
  // The spatial cylindrical roller bearing has the EHD film on its race slices; its pocket bars, land and
  // ribs, and every contact of the tapered roller bearing, are dry.
  const bool race_slices = b.contact_kind == contact::roller_race_contact && !b.scene.bearing.is_tapered();
  if (b.spatial_roller() && !(id == contact::LawId::moes_ehd && race_slices))
    s.fail("normal", fmt::format("normal = \"{}\" is a film law; in the spatial roller model only the cylindrical "
                                 "roller bearing's race slices have a film (normal = \"moes_ehd\"): its pocket bars "
                                 "and cage land, and the tapered roller bearing's contacts, are dry (palmgren): their "
                                 "films are modelled in the planar roller bearing",
                                 b.contact->normal.name()));
  if (!(b.scene.lubricant.viscosity > 0))
    s.fail("normal", fmt::format("normal = \"{}\" is a film law and needs a lubricant: set lubricant.viscosity (and "
                                 "lubricant.pressure_viscosity for an EHD film)",
                                 b.contact->normal.name()));
}

// EHD traction is the shear of the EHD film: it needs that film; limiting shear needs its lubricant.
void traction_fits_normal_law(const Row& row, const Section& s, Bind& b) {
  limiting_shear_has_lubricant(row, s, b);
  if (b.contact->traction.id == contact::LawId::ehd_traction && b.contact->normal.id != contact::LawId::moes_ehd)
    s.fail("traction", "traction = \"ehd\" is the shear of an EHD film: it needs normal = \"moes_ehd\"");
}

void rolling_resistance_has_film(const Row&, const Section& s, Bind& b) {
  if (b.contact->traction.rolling_resistance && !(b.scene.lubricant.viscosity > 0))
    s.fail("rolling_resistance", "EHL rolling resistance needs a film: set lubricant.viscosity, or "
                                 "rolling_resistance = false");
}

// PETSc options are checked when the solver is built (a trial setup needs PETSc:
// solver/numerics/newton_backends.hpp); here only their place is kept, for that error message.
void remember_petsc_options_place(const Row&, const Section& s, Bind& b) {
  b.scene.solver.petsc_options_file = s.file();
  b.scene.solver.petsc_options_line = s.line("petsc_options");
}
// The Runge-Kutta pairs ARKODE has: explicit of order 2 to 6 and 8 (no embedded order-7 pair),
// diagonally implicit of order 2 to 5; none of order 1.
void order_exists_for_method(const Row& row, const Section& s, Bind& b) {
  const SolverSpec& spec = b.scene.solver;
  const int order = spec.max_order;
  if (spec.method == IntegrationMethod::erk && (order < 2 || order == 7))
    s.fail(row.key, fmt::format("method \"erk\" has explicit Runge-Kutta pairs of order 2, 3, 4, 5, 6 and 8, not {}", order));
  if (spec.method == IntegrationMethod::ark && order < 2)
    s.fail(row.key, fmt::format("method \"ark\" has implicit Runge-Kutta pairs of order 2 to 5, not {}", order));
}

void automatic_order_has_choice(const Row& row, const Section& s, Bind& b) {
  const SolverSpec& spec = b.scene.solver;
  if (spec.automatic_order && spec.max_order < 3)
    s.fail(row.key, fmt::format("the automatic order chooses between max_order and 2, but max_order is {}: give "
                                "max_order = 3 or more, or automatic_order = false",
                                spec.max_order));
}

// ---- across sections ---------------------------------------------------------------------------

namespace {

void elements_fit(const Section& bearing, const Scene& scene) {
  const BearingGeometry& b = scene.bearing;
  const bool ball = b.is_ball_bearing();
  const std::string_view elements = ball ? "balls" : "rollers";
  const int n = b.rolling_elements;
  const double dw = b.element_diameter(), pocket = scene.cage.pocket_clearance;
  const double chord = b.pitch_diameter * std::sin(kPi / n);
  const double need = dw + pocket;
  bearing.check(chord > need, "rolling_elements", [&] {
    return fmt::format("{} {} of {} with {} pocket clearance need a pitch diameter of at least {} (found {})", n,
                       elements, mm(dw), mm(pocket), mm(need / std::sin(kPi / n)), mm(b.pitch_diameter));
  });
  // Ball cages need bars between the pockets: the pockets may take at most 98 % of the pitch circle.
  if (ball) {
    const double circle = kPi * b.pitch_diameter;
    bearing.check(n * need <= 0.98 * circle, "rolling_elements", [&] {
      return fmt::format("{} balls of {} with {} pocket clearance take {:.1f} % of the pitch circle ({} around), "
                         "more than 98 %: no room for the cage bars",
                         n, mm(dw), mm(pocket), 100.0 * n * need / circle, mm(circle));
    });
  }
}

void rings_held(const Section& outer, const Scene& scene) {
  const auto held = [](const RingSpec& r) {
    return r.motion == RingMotion::fixed || !r.translation_free || r.support.stiffness > 0;
  };
  if (scene.inner_ring.motion == RingMotion::fixed && scene.outer_ring.motion == RingMotion::fixed)
    outer.fail("motion", "both rings are fixed: nothing turns the bearing (make one ring motion = \"driven\" or "
                         "\"free\")");
  if (!held(scene.inner_ring) && !held(scene.outer_ring))
    outer.fail("motion",
               "both rings float: nothing holds the bearing (make one ring motion = \"fixed\", give it "
               "translation = \"fixed\", or a support)");
  if (scene.scene.model != ModelKind::spatial) return;
  const auto held_axially = [](const RingSpec& r) {
    return r.motion == RingMotion::fixed || !r.axial_free || r.support.axial_stiffness > 0;
  };
  if (!held_axially(scene.inner_ring) && !held_axially(scene.outer_ring))
    outer.fail("axial",
               "both rings are free axially: nothing holds the bearing along its axis (make one ring motion = "
               "\"fixed\", give it axial = \"fixed\", or an axial_stiffness support)");
  const auto held_tilt = [](const RingSpec& r) { return r.tilt != RingTilt::free || r.support.tilt_stiffness > 0; };
  if (!held_tilt(scene.inner_ring) && !held_tilt(scene.outer_ring))
    outer.fail("tilt",
               "both rings tilt freely: nothing holds the bearing's orientation (give one ring tilt = \"fixed\" or "
               "\"prescribed\", or a tilt_stiffness support)");
}

}  // namespace

void check_scene(const Section& bearing, const Section& outer_ring, const Scene& scene) {
  elements_fit(bearing, scene);
  rings_held(outer_ring, scene);
}

void check_cage_held(const Section& cage, const Scene& scene) {
  const CageSpec& c = scene.cage;
  if (!scene.bearing.is_ball_bearing() || c.guidance != CageGuidance::rolling_element) return;
  if (c.pocket_shape == PocketShape::spherical || c.support.radial_stiffness > 0) return;
  cage.fail(cage.has("pocket_shape") ? "pocket_shape" : "guidance",
            "nothing holds this cage radially: it is ball-guided (guidance = \"rolling_element\") with cylindrical "
            "pockets, whose radial axes let the balls slide through them, and once the balls bunch the cage drifts "
            "through the rings; give pocket_shape = \"spherical\" (pressed and snap cages, held by the balls), "
            "guidance = \"inner_land\" or \"outer_land\" with a land_clearance (machined cages), or a [cage.support] "
            "with radial_stiffness (a cage on a spindle)");
}

}  // namespace raceway::scene::schema::rules
