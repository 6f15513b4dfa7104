#include "solver/bearing/spatial_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace raceway::solver {

using contact::Mat3;
using contact::Vec3;

const char* spatial_segment_kind_name(SpatialSegmentKind k) {
  switch (k) {
    case SpatialSegmentKind::ball_inner_groove: return "ball_inner_groove";
    case SpatialSegmentKind::ball_outer_groove: return "ball_outer_groove";
    case SpatialSegmentKind::ball_pocket: return "ball_pocket";
    case SpatialSegmentKind::cage_land: return "cage_land";
  }
  return "?";
}

Mat3 cardan_rotation(double ax, double ay, double az) {
  return (Eigen::AngleAxisd(ax, Vec3::UnitX()) * Eigen::AngleAxisd(ay, Vec3::UnitY()) *
          Eigen::AngleAxisd(az, Vec3::UnitZ()))
      .toRotationMatrix();
}

Vec3 cardan_rates(double ay, double az, const Vec3& w) {
  const double cb = std::cos(ay), sb = std::sin(ay), cc = std::cos(az), sc = std::sin(az);
  const double ax_rate = (w.x() * cc - w.y() * sc) / cb;
  return {ax_rate, w.x() * sc + w.y() * cc, w.z() - sb * ax_rate};
}

namespace {

constexpr double pi = std::numbers::pi;

double annulus_mass(double density, double r_in, double r_out, double width) {
  return density * pi * (r_out * r_out - r_in * r_in) * width;
}
/// Polar and diametral moments of inertia of a thick ring (hollow cylinder).
double annulus_axial_inertia(double mass, double r_in, double r_out) { return 0.5 * mass * (r_in * r_in + r_out * r_out); }
double annulus_transverse_inertia(double mass, double r_in, double r_out, double width) {
  return mass * (3.0 * (r_in * r_in + r_out * r_out) + width * width) / 12.0;
}

struct StateAdder {
  SpatialModel& m;
  SpatialBody& b;
  void operator()(SpatialComponent c, VariableClass cls, const char* what) {
    b.slot[c] = m.state_size++;
    m.state_class.push_back(cls);
    m.state_name.push_back(b.name + "." + what);
  }
};

/// Ring states: positions (x, y, z, tilts) then velocities (vx, vy, vz, tilt rates, spin).
void add_ring(SpatialModel& m, SpatialBodyKind kind, const char* name, const io::RingSpec& spec, double r_in,
              double r_out, double width, double density) {
  SpatialBody b;
  b.name = name;
  b.kind = kind;
  b.ring = &spec;
  b.mass = spec.mass > 0 ? spec.mass : annulus_mass(density, r_in, r_out, width);
  b.axial_inertia = spec.inertia > 0 ? spec.inertia : annulus_axial_inertia(b.mass, r_in, r_out);
  b.transverse_inertia =
      spec.transverse_inertia > 0 ? spec.transverse_inertia : annulus_transverse_inertia(b.mass, r_in, r_out, width);
  const bool moves = spec.motion != io::RingMotion::fixed;
  const bool radial = moves && spec.translation_free, axial = moves && spec.axial_free;
  const bool tilt = moves && spec.tilt == io::RingTilt::free;
  const bool spin = spec.motion == io::RingMotion::free;
  b.offset = m.state_size;
  StateAdder add{m, b};
  if (radial) add(sx, VariableClass::position, "x"), add(sy, VariableClass::position, "y");
  if (axial) add(sz, VariableClass::position, "z");
  if (tilt) add(sax, VariableClass::angle, "tilt_x"), add(say, VariableClass::angle, "tilt_y");
  if (radial) add(svx, VariableClass::velocity, "vx"), add(svy, VariableClass::velocity, "vy");
  if (axial) add(svz, VariableClass::velocity, "vz");
  if (tilt) add(swx, VariableClass::angular_velocity, "tilt_rate_x"), add(swy, VariableClass::angular_velocity, "tilt_rate_y");
  if (spin) add(swz, VariableClass::angular_velocity, "spin");
  b.size = m.state_size - b.offset;
  m.bodies.push_back(b);
}

}  // namespace

SpatialModel build_spatial_model(const io::Scene& scene) {
  if (scene.scene.model != io::ModelKind::spatial || !scene.bearing.is_ball_bearing())
    throw std::runtime_error("scene.model: the spatial model needs a ball bearing (bearing.type)");
  SpatialModel m;
  m.scene = &scene;
  const auto& g = scene.bearing;
  const auto& bg = g.ball;
  const auto& ball_mat = scene.material(g.roller_material);
  const auto& ring_mat = scene.material(g.ring_material);
  const auto& cage_mat = scene.material(scene.cage.material);
  const bool four_point = g.type == io::BearingType::four_point_contact_ball;
  m.ball_count = g.rolling_elements;
  m.pitch_radius = 0.5 * g.pitch_diameter;
  m.ball_radius = 0.5 * bg.ball_diameter;
  m.nominal_contact_angle = four_point ? bg.arc_contact_angle : 0.0;
  m.arcs_per_ring = four_point ? 2 : 1;
  m.gravity = scene.gravity ? 9.80665 : 0.0;
  const double D = bg.ball_diameter, rb = m.ball_radius, rp = m.pitch_radius;
  const double width = g.ring_width > 0 ? g.ring_width : 1.5 * D;
  const double inner_groove_bottom = 0.5 * g.inner_race_diameter();
  const double outer_groove_bottom = 0.5 * g.outer_race_diameter();

  // Rings: the groove side of each ring is taken as a quarter ball diameter deep on average.
  add_ring(m, SpatialBodyKind::inner_ring, "inner_ring", scene.inner_ring, 0.5 * g.inner_bore_diameter,
           inner_groove_bottom + 0.25 * D, width, ring_mat.density);
  add_ring(m, SpatialBodyKind::outer_ring, "outer_ring", scene.outer_ring, outer_groove_bottom - 0.25 * D,
           0.5 * g.outer_outside_diameter, width, ring_mat.density);

  // Cage: an annulus with one radial hole per pocket.
  const auto& cs = scene.cage;
  const double cage_r_in = cs.inner_diameter > 0 ? 0.5 * cs.inner_diameter : rp - 0.6 * rb;
  const double cage_r_out = cs.outer_diameter > 0 ? 0.5 * cs.outer_diameter : rp + 0.6 * rb;
  const double cage_width = cs.width > 0 ? cs.width : 0.8 * width;
  {
    SpatialBody c;
    c.name = "cage";
    c.kind = SpatialBodyKind::cage;
    const double pocket_r = 0.5 * (D + cs.pocket_clearance);
    const double holes = cage_mat.density * m.ball_count * pi * pocket_r * pocket_r * (cage_r_out - cage_r_in);
    const double computed = annulus_mass(cage_mat.density, cage_r_in, cage_r_out, cage_width) - holes;
    c.mass = cs.mass > 0 ? cs.mass : computed;
    if (c.mass <= 0)
      throw std::runtime_error("cage: the pockets leave no material (check cage.inner_diameter, outer_diameter, width)");
    c.axial_inertia = cs.inertia > 0 ? cs.inertia : annulus_axial_inertia(c.mass, cage_r_in, cage_r_out);
    c.transverse_inertia = cs.transverse_inertia > 0 ? cs.transverse_inertia
                                                     : annulus_transverse_inertia(c.mass, cage_r_in, cage_r_out, cage_width);
    c.offset = m.state_size;
    StateAdder add{m, c};
    add(sx, VariableClass::position, "x"), add(sy, VariableClass::position, "y"), add(sz, VariableClass::position, "z");
    add(sax, VariableClass::angle, "angle_x"), add(say, VariableClass::angle, "angle_y"), add(saz, VariableClass::angle, "angle_z");
    add(svx, VariableClass::velocity, "vx"), add(svy, VariableClass::velocity, "vy"), add(svz, VariableClass::velocity, "vz");
    add(swx, VariableClass::angular_velocity, "wx_body"), add(swy, VariableClass::angular_velocity, "wy_body");
    add(swz, VariableClass::angular_velocity, "wz_body");
    c.size = m.state_size - c.offset;
    m.bodies.push_back(c);
  }
  m.border_size = m.state_size;

  // Balls: position, velocity, angular velocity (bearing frame).
  const double ball_mass = ball_mat.density * 4.0 / 3.0 * pi * rb * rb * rb;
  for (int k = 0; k < m.ball_count; ++k) {
    SpatialBody b;
    b.name = fmt::format("ball[{}]", k);
    b.kind = SpatialBodyKind::ball;
    b.index = k;
    b.mass = ball_mass;
    b.axial_inertia = b.transverse_inertia = 0.4 * ball_mass * rb * rb;
    b.offset = m.state_size;
    StateAdder add{m, b};
    add(sx, VariableClass::position, "x"), add(sy, VariableClass::position, "y"), add(sz, VariableClass::position, "z");
    add(svx, VariableClass::velocity, "vx"), add(svy, VariableClass::velocity, "vy"), add(svz, VariableClass::velocity, "vz");
    add(swx, VariableClass::angular_velocity, "wx"), add(swy, VariableClass::angular_velocity, "wy");
    add(swz, VariableClass::angular_velocity, "wz");
    b.size = m.state_size - b.offset;
    m.bodies.push_back(b);
  }

  // ---- Laws: derived constants once, here ----
  auto e_star = [](const io::Material& a, const io::Material& b) {
    return contact::reduced_modulus(a.youngs_modulus, a.poisson_ratio, b.youngs_modulus, b.poisson_ratio);
  };
  auto damping_of = [](const io::ContactSpec& spec) { return spec.damping.name == "none" ? 0.0 : spec.damping.factor; };
  // Validity: an approach of 2 % of the ball radius is far beyond any elastic deflection.
  const double max_approach = 0.02 * rb;
  const double e_race = e_star(ball_mat, ring_mat);

  contact::PointTraction race_traction;
  const auto& rt = scene.ball_race.traction;
  race_traction.model = rt.name == "none"             ? contact::TractionModel::none
                        : rt.name == "limiting_shear" ? contact::TractionModel::limiting_shear
                                                      : contact::TractionModel::curve;
  race_traction.friction_coefficient = rt.friction_coefficient;
  race_traction.slip_velocity_scale = rt.slip_velocity_scale > 0 ? rt.slip_velocity_scale : 1.0;
  race_traction.grid_x = rt.grid_x;
  race_traction.grid_y = rt.grid_y;
  contact::PointLubricant lube;
  lube.viscosity = scene.lubricant.viscosity;
  lube.pressure_viscosity = scene.lubricant.pressure_viscosity;
  lube.limiting_shear_coefficient = scene.lubricant.limiting_shear_coefficient;
  lube.viscosity_exponent_cap = scene.lubricant.viscosity_exponent_cap;

  // Groove arcs. u: unit vector from the ball centre to the design contact point in the (radial,
  // axial) plane; the arc centre lies at (R_b - r_groove) u from a centred ball, and the clearance
  // moves the outer arcs out and the inner arcs in by P_d / 4 each (radial play P_d / 2).
  const double a0 = m.nominal_contact_angle;
  struct Arc {
    bool outer;
    double centre_radius, centre_axial, groove_radius;
    const char* label;
  };
  std::vector<Arc> arcs;
  for (int ring = 0; ring < 2; ++ring) {
    const bool outer = ring == 1;
    const double rg = (outer ? bg.outer_conformity : bg.inner_conformity) * D;
    const double shift = (outer ? 1.0 : -1.0) * 0.25 * g.radial_clearance;
    for (int side = 0; side < m.arcs_per_ring; ++side) {
      const double sign_axial = four_point ? (side == 0 ? 1.0 : -1.0) : 0.0;
      const double u_r = (outer ? 1.0 : -1.0) * std::cos(a0), u_z = sign_axial * std::sin(a0);
      const char* label = four_point ? (side == 0 ? "a" : "b") : "";
      arcs.push_back({outer, rp + (rb - rg) * u_r + shift, (rb - rg) * u_z, rg, label});
    }
  }
  for (const Arc& arc : arcs) {
    contact::BallGrooveSegment s;
    s.centre_radius = arc.centre_radius;
    s.centre_axial = arc.centre_axial;
    s.groove_radius = arc.groove_radius;
    s.ball_radius = rb;
    s.outer = arc.outer;
    // Hertz constants over cos(contact angle) in [0.2, 1]: ball 1/R_b both ways; groove -1/r_g
    // across; race +-cos(a)/rho along the rolling direction, rho = r_p -+ R_b cos(a).
    const double rg = arc.groove_radius;
    const bool outer = arc.outer;
    s.normal.hertz = contact::HertzTable(
        [&](double c, double& kx, double& ky) {
          const double rho = outer ? rp + rb * c : rp - rb * c;
          kx = 1.0 / rb + (outer ? -c : c) / rho;
          ky = 1.0 / rb - 1.0 / rg;
        },
        0.2, 1.0, 33, e_race);
    s.normal.reduced_modulus = e_race;
    s.normal.damping_factor = damping_of(scene.ball_race);
    s.normal.max_approach = max_approach;
    s.traction = race_traction;
    s.lubricant = lube;
    s.rolling_resistance = rt.rolling_resistance && lube.viscosity > 0;
    m.groove_segments.push_back(s);
  }

  // Pockets.
  const double e_pocket = e_star(ball_mat, cage_mat);
  const double pocket_r = rb + 0.5 * cs.pocket_clearance;
  const bool spherical = cs.pocket_shape == io::PocketShape::spherical;
  const double conformal = 1.0 / rb - 1.0 / pocket_r;
  contact::PointNormalLaw pocket_law;
  pocket_law.hertz = contact::HertzTable(
      contact::hertz_point_contact(spherical ? conformal : 1.0 / rb, conformal, e_pocket));
  pocket_law.reduced_modulus = e_pocket;
  pocket_law.damping_factor = damping_of(scene.ball_cage);
  pocket_law.max_approach = max_approach;
  contact::TractionCurve pocket_friction;
  if (scene.ball_cage.traction.name != "none") {
    pocket_friction.friction_coefficient = scene.ball_cage.traction.friction_coefficient;
    pocket_friction.slip_velocity_scale =
        scene.ball_cage.traction.slip_velocity_scale > 0 ? scene.ball_cage.traction.slip_velocity_scale : 0.01;
  }

  for (int k = 0; k < m.ball_count; ++k) {
    const int body = m.first_ball + k;
    const int arc_count = static_cast<int>(arcs.size());
    for (int a = 0; a < arc_count; ++a) {
      const bool outer = arcs[static_cast<std::size_t>(a)].outer;
      m.segments.push_back({outer ? SpatialSegmentKind::ball_outer_groove : SpatialSegmentKind::ball_inner_groove,
                            outer ? m.outer_ring : m.inner_ring, body, a, k,
                            fmt::format("ball[{}]/{}_groove{}", k, outer ? "outer" : "inner",
                                        arcs[static_cast<std::size_t>(a)].label)});
    }
    contact::BallPocketSegment p;
    p.pitch_radius = rp;
    p.pocket_angle = 2.0 * pi * k / m.ball_count;
    p.clearance = cs.pocket_clearance;
    p.ball_radius = rb;
    p.shape = spherical ? contact::PocketShape::spherical : contact::PocketShape::cylindrical;
    p.normal = pocket_law;
    p.friction = pocket_friction;
    m.segments.push_back({SpatialSegmentKind::ball_pocket, m.cage, body, static_cast<int>(m.pocket_segments.size()), k,
                          fmt::format("ball[{}]/pocket", k)});
    m.pocket_segments.push_back(p);
  }
  if (cs.guidance != io::CageGuidance::rolling_element) {
    const bool outer = cs.guidance == io::CageGuidance::outer_land;
    const int ring = outer ? m.outer_ring : m.inner_ring;
    contact::CageLandSegment3 l;
    l.outer_land = outer;
    l.clearance = cs.land_clearance;
    l.land_radius = outer ? cage_r_out + cs.land_clearance : cage_r_in - cs.land_clearance;
    l.width = cs.land_width > 0 ? cs.land_width : 0.3 * cage_width;
    l.stations = 2;
    const double e_land = e_star(cage_mat, ring_mat);
    l.law = contact::make_line_contact_law(e_land, l.width / l.stations, 1, 0.0, damping_of(scene.cage_land),
                                           0.02 * rb);
    if (scene.cage_land.traction.name != "none") {
      l.friction.friction_coefficient = scene.cage_land.traction.friction_coefficient;
      l.friction.slip_velocity_scale =
          scene.cage_land.traction.slip_velocity_scale > 0 ? scene.cage_land.traction.slip_velocity_scale : 0.01;
    }
    m.land_segments.push_back(l);
    m.segments.push_back({SpatialSegmentKind::cage_land, m.cage, ring, 0, -1,
                          outer ? "cage/outer_ring_land" : "cage/inner_ring_land"});
  }
  return m;
}

double SpatialModel::ring_spin(int b, double t, const double* z) const {
  const SpatialBody& body = bodies[static_cast<std::size_t>(b)];
  if (body.slot[swz] >= 0) return z[body.slot[swz]];
  return body.ring && body.ring->motion == io::RingMotion::driven ? body.ring->speed(t) : 0.0;
}

contact::SpatialKinematics SpatialModel::kinematics(int b, double t, const double* z) const {
  const SpatialBody& body = bodies[static_cast<std::size_t>(b)];
  double v[spatial_components] = {};
  for (int c = 0; c < spatial_components; ++c)
    if (body.slot[c] >= 0) v[c] = z[body.slot[c]];
  contact::SpatialKinematics k;
  k.position = Vec3(v[sx], v[sy], v[sz]);
  k.velocity = Vec3(v[svx], v[svy], v[svz]);
  switch (body.kind) {
    case SpatialBodyKind::ball:
      k.angular_velocity = Vec3(v[swx], v[swy], v[swz]);
      break;
    case SpatialBodyKind::cage:
      k.rotation = cardan_rotation(v[sax], v[say], v[saz]);
      k.angular_velocity = k.rotation * Vec3(v[swx], v[swy], v[swz]);
      break;
    case SpatialBodyKind::inner_ring:
    case SpatialBodyKind::outer_ring: {
      if (body.ring->tilt == io::RingTilt::prescribed) {
        v[sax] = body.ring->misalignment_x(t), v[say] = body.ring->misalignment_y(t);
        v[swx] = body.ring->misalignment_x.derivative(t), v[swy] = body.ring->misalignment_y.derivative(t);
      }
      k.rotation = cardan_rotation(v[sax], v[say], 0.0);
      const Mat3 rx = cardan_rotation(v[sax], 0.0, 0.0);
      k.angular_velocity = ring_spin(b, t, z) * k.rotation.col(2) + v[swx] * Vec3::UnitX() + v[swy] * rx.col(1);
      break;
    }
  }
  return k;
}

double SpatialModel::epicyclic_cage_speed(double t) const { return epicyclic_cage_speed(t, nominal_contact_angle); }

double SpatialModel::epicyclic_cage_speed(double t, double contact_angle) const {
  auto speed = [&](int b) {
    const auto* r = bodies[static_cast<std::size_t>(b)].ring;
    return r->motion == io::RingMotion::driven ? r->speed(t) : 0.0;
  };
  const double gamma = 2.0 * ball_radius * std::cos(contact_angle) / (2.0 * pitch_radius);
  return 0.5 * (speed(inner_ring) * (1.0 - gamma) + speed(outer_ring) * (1.0 + gamma));
}

std::vector<double> SpatialModel::absolute_tolerance() const {
  return physical_absolute_tolerance(*scene, state_class, pitch_radius, ball_radius);
}

std::string SpatialModel::describe() const {
  std::string out;
  const auto& sc = *scene;
  out += fmt::format("scene '{}' ({}): spatial model, {} bodies, {} states, {} contact segments\n", sc.scene.name,
                     sc.source, bodies.size(), state_size, segments.size());
  out += fmt::format("  {} {} balls, D = {:.4g} mm, pitch diameter {:.5g} mm, nominal contact angle {:.3g} deg\n",
                     ball_count, arcs_per_ring == 2 ? "four-point contact" : "deep groove", 2e3 * ball_radius,
                     2e3 * pitch_radius, nominal_contact_angle * 180 / std::numbers::pi);
  out += "bodies (states integrated; prescribed motions are functions of time, not states):\n";
  for (const auto& b : bodies) {
    if (b.kind == SpatialBodyKind::ball && b.index > 0) continue;
    std::string why;
    switch (b.kind) {
      case SpatialBodyKind::inner_ring:
      case SpatialBodyKind::outer_ring: {
        const auto& r = *b.ring;
        const char* motion = r.motion == io::RingMotion::fixed ? "fixed" : r.motion == io::RingMotion::driven ? "driven" : "free";
        const char* tilt = r.tilt == io::RingTilt::free ? "tilt free" : r.tilt == io::RingTilt::prescribed ? "misalignment prescribed" : "tilt held";
        why = fmt::format("{}, {}; its angle about its own axis is not a state (grooves are surfaces of revolution)", motion, tilt);
        break;
      }
      case SpatialBodyKind::cage: why = "full pose and body-frame angular velocity: its pockets are not symmetric"; break;
      case SpatialBodyKind::ball:
        why = fmt::format("each of the {} balls: position, velocity, angular velocity; no orientation (a sphere)", ball_count);
        break;
    }
    out += fmt::format("  {:<12} mass {:.4g} kg, inertia {:.4g} / {:.4g} kg m^2 (axial / transverse), {} states: {}\n",
                       b.name, b.mass, b.axial_inertia, b.transverse_inertia, b.size, why);
  }
  int count[spatial_segment_kind_count] = {};
  for (const auto& s : segments) ++count[static_cast<int>(s.kind)];
  out += "contact segments:\n";
  for (int k = 0; k < spatial_segment_kind_count; ++k)
    if (count[k] > 0) out += fmt::format("  {:<18} {}\n", spatial_segment_kind_name(static_cast<SpatialSegmentKind>(k)), count[k]);
  out += fmt::format("  ball-groove: Hertz (exact ellipticity, tabulated over the contact angle), damping {}, traction {} "
                     "({}x{} grid), rolling resistance {}\n",
                     sc.ball_race.damping.name, sc.ball_race.traction.name, sc.ball_race.traction.grid_x,
                     sc.ball_race.traction.grid_y, !groove_segments.empty() && groove_segments[0].rolling_resistance ? "on" : "off");
  out += fmt::format("  ball-pocket: Hertz in a {} pocket, clearance {:.4g} mm, friction {}\n",
                     sc.cage.pocket_shape == io::PocketShape::spherical ? "spherical" : "cylindrical",
                     1e3 * sc.cage.pocket_clearance, sc.ball_cage.traction.name);
  if (land_segments.empty())
    out += "  cage-land: none (the cage is guided by the balls" + std::string(sc.cage.support.any() ? " and its spindle support)\n" : ")\n");
  else
    out += fmt::format("  cage-land: {} land, clearance {:.4g} mm, 2 stations (tilt moments)\n",
                       land_segments[0].outer_land ? "outer-ring" : "inner-ring", 1e3 * land_segments[0].clearance);
  out += fmt::format("state layout: border {} states (rings, cage), then {} blocks of {} (balls)\n", border_size,
                     ball_count, ball_block_size);
  return out;
}

}  // namespace raceway::solver
