// The spatial cylindrical roller bearing (NU, NJ, NUP, N): rings, cage and rollers in all six
// directions, each roller's line contact on a race cut into slices along the roller with its
// profile, the roller's ends against the ribs its design has, and its pocket bars in 3-D.
//
// A roller carries x, y, z, the two angles of its axis (tilt and skew: R = Rx(ax) Ry(ay) maps its
// body z, the axis, into the bearing frame) and its angular velocity in the bearing frame: 11 states.
// Its angle about its own axis is no state: a body of revolution's contacts do not depend on it (the
// planar roller's reason, kept here; with a roller's own defect in the scene every roller's is, 12 states), while its spin is a full rate of the angular velocity, whose
// Euler equations (spatial_dynamics.cpp) couple spin, tilt and skew. The cage keeps its full pose, as
// a ball bearing's; rings as a spatial ball bearing's (axial, tilt, misalignment).
//
// Restricted to the plane (aligned, no axial load) this is the planar model (roller_model.cpp): the
// slices of an aligned straight roller carry exactly the planar law's K l^(8/9) delta^(10/9), the
// pocket bars and the land theirs, and the start-up is the planar seating lifted into space.
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "solver/bearing/housing.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/race_defects.hpp"

namespace raceway::bearing {

using contact::Vec3;

namespace {

constexpr double pi = std::numbers::pi;

/// Validity of every roller contact: an approach of 2 % of the roller radius is far beyond any elastic deflection.
double max_approach(const Model& m) { return 0.02 * m.element_radius; }
double damping_of(const scene::ContactSpec& spec) {
  return spec.damping.id == contact::LawId::no_damping ? 0.0 : spec.damping.factor;
}
double e_star(const scene::Material& a, const scene::Material& b) {
  return contact::reduced_modulus(a.youngs_modulus, a.poisson_ratio, b.youngs_modulus, b.poisson_ratio);
}
contact::TractionCurve traction_curve(const scene::ContactSpec& spec) {
  contact::TractionCurve t;
  if (spec.traction.id != contact::LawId::no_traction) {
    t.friction_coefficient = spec.traction.friction_coefficient;
    t.slip_velocity_scale = spec.traction.slip_velocity_scale;
  }
  return t;
}
int add_law(Model& m, SegmentLaw law) {
  m.laws.push_back(std::move(law));
  return static_cast<int>(m.laws.size()) - 1;
}

struct CageGeometry {
  double land_radius = 0, r_in = 0, r_out = 0;
};

/// The planar cage's section (roller_model.cpp): lands half a roller radius high on the guiding ring.
CageGeometry cage_geometry(const Model& m, const scene::CageSpec& cs) {
  CageGeometry c;
  const double rr = m.element_radius;
  c.r_in = m.pitch_radius - 0.6 * rr;
  c.r_out = m.pitch_radius + 0.6 * rr;
  if (cs.guidance == scene::CageGuidance::inner_land) {
    c.land_radius = m.inner_race_radius + 0.5 * rr;
    c.r_in = c.land_radius + cs.land_clearance;
  } else if (cs.guidance == scene::CageGuidance::outer_land) {
    c.land_radius = m.outer_race_radius - 0.5 * rr;
    c.r_out = c.land_radius - cs.land_clearance;
  }
  return c;
}

void check_scene(const scene::Scene& scene) {
  if (scene.scene.model != scene::ModelKind::spatial || scene.bearing.is_ball_bearing())
    throw std::runtime_error("scene.model: the spatial roller model needs a cylindrical roller bearing in the spatial model");
}

void set_geometry(Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  m.kind = scene::ModelKind::spatial;
  m.element_group = "rollers";
  m.element_count = g.rolling_elements;
  m.pitch_radius = 0.5 * g.pitch_diameter;
  m.element_radius = 0.5 * g.roller_diameter;
  m.inner_race_radius = 0.5 * g.inner_race_diameter();
  m.outer_race_radius = 0.5 * g.outer_race_diameter();
  set_roller_radii(m, g);
  // The planar model of the same scene: its seating starts this one.
  scene::Scene planar = scene;
  planar.scene.model = scene::ModelKind::planar;
  m.planar_restriction = std::make_shared<const Model>(build_model(planar, roller_model_builder()));
}

void add_rings(Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  const double density = scene.material(g.ring_material).density;
  const double width = g.ring_width > 0 ? g.ring_width : g.roller_length;
  add_spatial_ring(m, BodyKind::inner_ring, "inner_ring", m.params().inner_ring, 0.5 * g.inner_bore_diameter,
                   m.inner_race_radius, width, density);
  add_spatial_ring(m, BodyKind::outer_ring, "outer_ring", m.params().outer_ring, m.outer_race_radius,
                   0.5 * g.outer_outside_diameter, width, density);
  add_housing(m, scene);
}

/// The planar cage's mass (two side rings 30 % of the roller length wide, n bars), full pose.
void add_cage(Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  const auto& cs = scene.cage;
  const CageGeometry geo = cage_geometry(m, cs);
  const double density = scene.material(cs.material).density;
  Body c;
  c.name = "cage";
  c.kind = BodyKind::cage;
  const double chord = g.pitch_diameter * std::sin(pi / g.rolling_elements);
  const double bar_thickness = chord - g.roller_diameter - cs.pocket_clearance;
  const double rings = annulus_mass(density, geo.r_in, geo.r_out, 0.3 * g.roller_length);
  const double bars = density * g.rolling_elements * bar_thickness * (geo.r_out - geo.r_in) * g.roller_length;
  c.mass = cs.mass > 0 ? cs.mass : rings + bars;
  const double rr2 = geo.r_in * geo.r_in + geo.r_out * geo.r_out;
  c.axial_inertia = cs.inertia > 0 ? cs.inertia : 0.5 * c.mass * rr2;
  c.transverse_inertia = c.mass * (3.0 * rr2 + g.roller_length * g.roller_length) / 12.0;
  c.offset = m.state_size;
  add_states(m, c, sx, VariableClass::position, {"x", "y", "z"});
  add_states(m, c, sax, VariableClass::angle, {"angle_x", "angle_y", "angle_z"});
  add_states(m, c, svx, VariableClass::velocity, {"vx", "vy", "vz"});
  add_states(m, c, swx, VariableClass::angular_velocity, {"wx_body", "wy_body", "wz_body"});
  c.size = m.state_size - c.offset;
  m.bodies.push_back(c);
}

/// Rollers: a solid cylinder of the straight length; position, the axis's two angles, velocity,
/// angular velocity (bearing frame).
void add_rollers(Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  const double rr = m.element_radius, l = g.roller_length;
  const double mass = scene.material(g.roller_material).density * pi * rr * rr * l;
  add_rolling_elements(m, "roller", mass, 0.5 * mass * rr * rr, mass * (3.0 * rr * rr + l * l) / 12.0,
                       spatial_roller_states(scene.rolling_element.any()));
  scale_scattered_rollers(m, mass, rr, rr, l);
}

/// The roller's profile (BearingGeometry::roller_profile) with the races' modulus.
contact::RollerProfile roller_profile(const Model& m, const scene::Scene& scene, double e_race) {
  // Johns-Gohar's rolling radius: the inner contact's, the more curved one.
  return scene.bearing.roller_profile(
      e_race, m.element_radius * m.inner_race_radius / (m.element_radius + m.inner_race_radius));
}

/// The ribs of a design: (ring, side) pairs, ring 0 inner, 1 outer; side +1 the rib on the +z side.
std::vector<std::pair<int, int>> ribs_of(scene::RibArrangement ribs) {
  switch (ribs) {
    case scene::RibArrangement::nu: return {{1, -1}, {1, +1}};
    case scene::RibArrangement::nj: return {{0, -1}, {1, -1}, {1, +1}};
    case scene::RibArrangement::nup: return {{0, -1}, {0, +1}, {1, -1}, {1, +1}};
    case scene::RibArrangement::n: return {{0, -1}, {0, +1}};
  }
  return {};
}

/// One rib's contact, its face placed so that a centred, aligned roller has half the end play on
/// each side: the approach at the nominal place is computed and the face moved along the axis by
/// the difference (the approach falls by cos(g) per unit of axial shift; twice for round-off).
contact::RollerFlangeSegment rib_law(const Model& m, const scene::Scene& scene, int ring, int side) {
  const auto& g = scene.bearing;
  const auto& r = g.roller;
  contact::RollerFlangeGeometry geo;
  geo.side = side;
  geo.rib_radius = ring == 0 ? m.inner_race_radius + 0.25 * g.roller_diameter
                             : m.outer_race_radius - 0.25 * g.roller_diameter;
  // The face comes closer to the roller towards the race it stands on (an inner rib's face opens
  // outwards, an outer rib's inwards).
  geo.rib_angle = ring == 0 ? r.rib_angle : -r.rib_angle;
  geo.end = r.end == scene::RollerEnd::flat ? contact::RollerEndShape::flat : contact::RollerEndShape::spherical;
  geo.roller_length = g.roller_length + 2 * r.corner_radius;
  geo.roller_radius = m.element_radius;
  geo.end_radius = r.end_radius;
  geo.axis_radius = m.pitch_radius;
  geo.rib_axial = side * 0.5 * geo.roller_length;
  const auto& spec = scene.roller_flange;
  contact::PointTraction traction;
  traction.model = spec.traction.id == contact::LawId::no_traction ? contact::TractionModel::none
                                                                  : contact::TractionModel::curve;
  traction.friction_coefficient = spec.traction.friction_coefficient;
  traction.slip_velocity_scale = spec.traction.slip_velocity_scale > 0 ? spec.traction.slip_velocity_scale : 1.0;
  const double e = e_star(scene.material(g.roller_material), scene.material(g.ring_material));
  contact::RollerFlangeSegment law = contact::make_roller_flange_segment(geo, e, damping_of(spec), max_approach(m), traction);
  contact::SpatialKinematics ring_at_rest, roller_at_rest;
  roller_at_rest.position = Vec3(m.pitch_radius, 0, 0);
  for (int pass = 0; pass < 2; ++pass) {
    const double approach = contact::evaluate(law, ring_at_rest, roller_at_rest).diagnostics.approach;
    law.geometry.rib_axial += side * (approach + 0.5 * r.end_clearance) / std::cos(geo.rib_angle);
  }
  return law;
}

void add_land_segment(Model& m, const scene::Scene& scene) {
  const auto& cs = scene.cage;
  if (cs.guidance == scene::CageGuidance::rolling_element) return;
  const CageGeometry geo = cage_geometry(m, cs);
  contact::CageLandSegment3 l;
  l.outer_land = cs.guidance == scene::CageGuidance::outer_land;
  l.clearance = cs.land_clearance;
  l.land_radius = geo.land_radius;
  l.width = cs.land_width > 0 ? cs.land_width : 0.5 * scene.bearing.roller_length;
  l.stations = 2;
  // Each station carries its share of the planar land's K of the whole width.
  l.law = contact::make_line_contact_law(e_star(scene.material(cs.material), scene.material(scene.bearing.ring_material)),
                                         l.width, 1, 0.0, damping_of(scene.cage_land), max_approach(m));
  l.law.stiffness /= l.stations;
  l.law.slice_stiffness[0] = l.law.stiffness;
  const auto friction = traction_curve(scene.cage_land);
  l.friction.friction_coefficient = friction.friction_coefficient;
  l.friction.slip_velocity_scale = friction.slip_velocity_scale;
  const int law = add_law(m, l);
  m.segments.push_back({SegmentKind::cage_land, m.cage, l.outer_land ? m.outer_ring : m.inner_ring, law, -1,
                        l.outer_land ? "cage/outer_ring_land" : "cage/inner_ring_land"});
}

/// The EHD film of a race slice where the scene chooses normal = "moes_ehd": a line contact of the
/// slice's width with its K_j (its reduced radius the slice's own, set when evaluated: a scattered
/// roller's radius is its own), as the planar race film.
void add_slice_film(contact::RollerSliceSegment& slice, const contact::SlicedLineContact& sliced,
                    const scene::Scene& scene, double e_race, double roller_radius) {
  slice.ehd = roller_race_film(scene, line_film(scene, e_race, 0.0, sliced.slice_width, roller_radius), slice.stiffness,
                               slice.max_approach, slice.damping_factor);
}

void add_segments(Model& m, const scene::Scene& scene) {
  const auto& g = scene.bearing;
  const auto& cs = scene.cage;
  const auto& roller_mat = scene.material(g.roller_material);
  const double e_race = e_star(roller_mat, scene.material(g.ring_material));
  const contact::SlicedLineContact sliced = contact::make_sliced_line_contact(
      e_race, roller_profile(m, scene, e_race), scene.roller_race.normal.slices, damping_of(scene.roller_race),
      max_approach(m));
  const auto race_traction = traction_curve(scene.roller_race);
  std::vector<int> inner_slices, outer_slices;
  const auto inner_race = race_imperfections(scene.inner_ring, m.inner_race_radius, m.element_radius);
  const auto outer_race = race_imperfections(scene.outer_ring, m.outer_race_radius, m.element_radius);
  for (std::size_t j = 0; j < sliced.slice_centre.size(); ++j) {
    auto inner = contact::make_roller_slice_segment(sliced, j, m.inner_race_radius, m.element_radius, false, race_traction);
    auto outer = contact::make_roller_slice_segment(sliced, j, m.outer_race_radius, m.element_radius, true, race_traction);
    inner.imperfections = inner_race, outer.imperfections = outer_race;
    add_slice_film(inner, sliced, scene, e_race, m.element_radius);
    add_slice_film(outer, sliced, scene, e_race, m.element_radius);
    inner_slices.push_back(add_law(m, std::move(inner)));
    outer_slices.push_back(add_law(m, std::move(outer)));
  }
  std::vector<std::pair<std::pair<int, int>, int>> ribs;
  for (const auto& rib : ribs_of(g.roller.ribs)) ribs.push_back({rib, add_law(m, rib_law(m, scene, rib.first, rib.second))});
  const double bar_width = cs.bar_width > 0 ? cs.bar_width : g.roller_length;
  const double e_bar = e_star(roller_mat, scene.material(cs.material));
  for (int k = 0; k < m.element_count; ++k) {
    const int body = m.first_element + k;
    const std::vector<int> inner = roller_slice_laws(m, scene, k, inner_slices);
    const std::vector<int> outer = roller_slice_laws(m, scene, k, outer_slices);
    for (std::size_t j = 0; j < inner.size(); ++j)
      m.segments.push_back({SegmentKind::roller_inner_slice, m.inner_ring, body, inner[j], k,
                            fmt::format("roller[{}]/inner_race/slice[{}]", k, j)});
    for (std::size_t j = 0; j < outer.size(); ++j)
      m.segments.push_back({SegmentKind::roller_outer_slice, m.outer_ring, body, outer[j], k,
                            fmt::format("roller[{}]/outer_race/slice[{}]", k, j)});
    const double pocket = 2.0 * pi * k / m.element_count;
    for (const int side : {+1, -1}) {
      const int law = add_law(m, contact::make_roller_pocket_bar_segment(
                                     e_bar, bar_width, scene.roller_cage.normal.slices, m.pitch_radius, pocket,
                                     0.5 * cs.pocket_clearance, m.radius_of_element(k), side, damping_of(scene.roller_cage),
                                     max_approach(m), traction_curve(scene.roller_cage)));
      m.segments.push_back({side > 0 ? SegmentKind::cage_bar_front : SegmentKind::cage_bar_rear, m.cage, body, law, k,
                            fmt::format("roller[{}]/cage_bar_{}", k, side > 0 ? "front" : "rear")});
    }
    for (const auto& [rib, law] : ribs)
      m.segments.push_back({SegmentKind::roller_flange, rib.first == 0 ? m.inner_ring : m.outer_ring, body, law, k,
                            fmt::format("roller[{}]/{}_rib_{}", k, rib.first == 0 ? "inner" : "outer",
                                        rib.second > 0 ? "plus_z" : "minus_z")});
  }
  add_land_segment(m, scene);
  attach_outer_ring_to_housing(m);
}

}  // namespace

std::string describe_spatial_roller_model(const Model& m);

const ModelBuilder& spatial_roller_model_builder() {
  static const ModelBuilder builder{check_scene, set_geometry, add_rings, add_cage, add_rollers, add_segments,
                                    describe_spatial_roller_model};
  return builder;
}

std::string describe_spatial_roller_model(const Model& m) {
  const auto& sc = m.params();
  const auto& r = sc.bearing.roller;
  static const char* const ribs[] = {"NU", "NJ", "NUP", "N"};
  std::string out = fmt::format("scene '{}' ({}): spatial model, {} bodies, {} states, {} contact segments\n",
                                sc.scene_name, sc.source, m.bodies.size(), m.state_size, m.segments.size());
  out += fmt::format("  {} {} cylindrical rollers, D = {:.4g} mm, straight length {:.4g} mm, pitch diameter {:.5g} mm\n",
                     m.element_count, ribs[static_cast<int>(r.ribs)], 2e3 * m.element_radius,
                     1e3 * sc.bearing.roller_length, 2e3 * m.pitch_radius);
  out += "bodies (states integrated; prescribed motions are functions of time, not states):\n";
  for (const auto& b : m.bodies) {
    if (b.kind == BodyKind::rolling_element && b.index > 0) continue;
    const char* why = b.kind == BodyKind::rolling_element
                          ? (b.has_roller_spin_angle()
                                 ? "each roller: position, its axis's two angles (tilt, skew), its angle about its "
                                   "axis (a roller's defect turns with it), velocity, angular velocity"
                                 : "each roller: position, its axis's two angles (tilt, skew), velocity, angular "
                                   "velocity; no angle about its own axis (a body of revolution)")
                      : b.kind == BodyKind::cage ? "full pose and body-frame angular velocity"
                                                 : "as its motion, axial freedom and tilt make them states";
    out += fmt::format("  {:<12} mass {:.4g} kg, inertia {:.4g} / {:.4g} kg m^2 (axial / transverse), {} states: {}\n",
                       b.name, b.mass, b.axial_inertia, b.transverse_inertia, b.size, why);
  }
  for (const auto& node : m.nodes) out += node->describe(m);
  int count[segment_kind_count] = {};
  for (const auto& s : m.segments) ++count[static_cast<int>(s.kind)];
  out += "contact segments:\n";
  for (int k = 0; k < segment_kind_count; ++k)
    if (count[k] > 0) out += fmt::format("  {:<18} {}\n", segment_kind_name(static_cast<SegmentKind>(k)), count[k]);
  if (const Segment* slice = m.first_segment(SegmentKind::roller_inner_slice)) {
    const auto& s = m.law<contact::RollerSliceSegment>(*slice);
    out += fmt::format("  race slices: {} per race and roller, Palmgren K_j = {:.4g} N/m^(10/9) each (straight part), "
                       "Hunt-Crossley {:.3g} s/m, traction mu {:.3g}\n",
                       count[static_cast<int>(SegmentKind::roller_inner_slice)] / m.element_count, s.stiffness,
                       s.damping_factor, s.traction.friction_coefficient);
    if (s.ehd)
      out += fmt::format("  race films: Moes EHD line contact per slice (eta {:.4g} mPa s, alpha {:.4g} 1/GPa), {}\n",
                         1e3 * s.ehd->law.film.viscosity, 1e9 * s.ehd->law.film.pressure_viscosity,
                         s.ehd->traction ? "Couette and Poiseuille traction" : "the traction curve on the film's force");
  }
  out += describe_race_imperfections(m);
  out += describe_roller_diameters(m);
  if (const Segment* rib = m.first_segment(SegmentKind::roller_flange)) {
    const auto& f = m.law<contact::RollerFlangeSegment>(*rib);
    out += fmt::format("  ribs: {} {} ends (radius {:.4g} mm) on ribs at {:.3g} deg, end play {:.4g} mm, Hertz K = {:.4g}\n",
                       ribs[static_cast<int>(r.ribs)], r.end == scene::RollerEnd::flat ? "flat" : "spherical",
                       1e3 * r.end_radius, r.rib_angle * 180 / pi, 1e3 * r.end_clearance, f.hertz.stiffness);
  }
  out += fmt::format("state layout: border {} states (rings, cage), then {} blocks of {} (rollers)\n", m.border_size,
                     m.element_count, m.block_size);
  return out;
}

}  // namespace raceway::bearing
