#include "solver/bearing/model.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "solver/bearing/orbital_frame.hpp"
#include "solver/bearing/thermal_network.hpp"

namespace raceway::bearing {

using contact::Mat3;
using contact::Vec3;

const char* segment_kind_name(SegmentKind k) {
  switch (k) {
    case SegmentKind::roller_inner_race: return "roller_inner_race";
    case SegmentKind::roller_outer_race: return "roller_outer_race";
    case SegmentKind::cage_bar_front: return "cage_bar_front";
    case SegmentKind::cage_bar_rear: return "cage_bar_rear";
    case SegmentKind::ball_inner_groove: return "ball_inner_groove";
    case SegmentKind::ball_outer_groove: return "ball_outer_groove";
    case SegmentKind::ball_pocket: return "ball_pocket";
    case SegmentKind::cage_land: return "cage_land";
    case SegmentKind::cage_bridge: return "cage_bridge";
    case SegmentKind::outer_ring_mode: return "outer_ring_mode";
    case SegmentKind::roller_inner_slice: return "roller_inner_slice";
    case SegmentKind::roller_outer_slice: return "roller_outer_slice";
    case SegmentKind::roller_flange: return "roller_flange";
    case SegmentKind::ball_drag: return "ball_drag";
    case SegmentKind::cage_churning: return "cage_churning";
  }
  return "?";
}

namespace {

std::shared_ptr<const ModelParameters> copy_parameters(const scene::Scene& scene) {
  auto p = std::make_shared<ModelParameters>();
  p->scene_name = scene.scene.name;
  p->source = scene.source;
  p->bearing = scene.bearing;
  p->cage = scene.cage;
  p->inner_ring = scene.inner_ring;
  p->outer_ring = scene.outer_ring;
  p->carrier = scene.carrier;
  p->solver = scene.solver;
  p->ball_race = scene.ball_race;
  p->ball_cage = scene.ball_cage;
  return p;
}

}  // namespace

Model build_model(const scene::Scene& scene) {
  return build_model(scene, builder_for(scene.bearing.type, scene.scene.model));
}

Model build_model(const scene::Scene& scene, const ModelBuilder& builder) {
  builder.check(scene);
  Model m;
  m.describer = builder.describe;
  m.parameters = copy_parameters(scene);
  m.bearing_type = scene.bearing.type;
  m.gravity = scene.gravity ? 9.80665 : 0.0;
  builder.geometry(m, scene);
  builder.rings(m, scene);
  builder.cage(m, scene);
  const int thermal_first = add_thermal_states(m, scene);
  m.border_size = m.state_size;
  builder.rolling_elements(m, scene);
  m.block_size = m.element_count > 0 ? (m.state_size - m.border_size) / m.element_count : 0;
  builder.segments(m, scene);
  // A body-centre marker for every body; elements that name no marker attach at their bodies' centres.
  const int first_centre = static_cast<int>(m.markers.size());
  for (std::size_t b = 0; b < m.bodies.size(); ++b) m.markers.emplace_back(BodyCentre{static_cast<int>(b)});
  for (Segment& seg : m.segments) {
    if (seg.marker_a < 0) seg.marker_a = first_centre + seg.body_a;
    if (seg.marker_b < 0) seg.marker_b = first_centre + seg.body_b;
  }
  if (thermal_first >= 0) add_thermal_network(m, scene, thermal_first);
  return m;
}

std::string Model::describe() const { return describer ? describer(*this) : std::string(); }

int Model::add_marker(Marker marker) {
  markers.push_back(std::move(marker));
  return static_cast<int>(markers.size()) - 1;
}

int Model::add_node(std::shared_ptr<Node> node) {
  int forces = 0;
  for (const auto& n : nodes) forces += n->force_count();
  node->force_offset = forces;
  nodes.push_back(std::move(node));
  return static_cast<int>(nodes.size()) - 1;
}

int Model::node_force_count() const {
  int forces = 0;
  for (const auto& n : nodes) forces += n->force_count();
  return forces;
}

int add_state(Model& m, VariableClass cls, const std::string& name) {
  m.state_class.push_back(cls);
  m.state_name.push_back(name);
  return m.state_size++;
}

void add_state(Model& m, Body& b, Coordinate c, VariableClass cls, const char* what) {
  b.slot[c] = m.state_size++;
  m.state_class.push_back(cls);
  m.state_name.push_back(b.name + "." + what);
}

void add_states(Model& m, Body& b, Coordinate first, VariableClass cls, const std::array<const char*, 3>& what) {
  for (int d = 0; d < 3; ++d) add_state(m, b, static_cast<Coordinate>(first + d), cls, what[static_cast<std::size_t>(d)]);
}

void add_rolling_elements(Model& m, const char* name, double mass, double axial_inertia, double transverse_inertia,
                          void (*add_states)(Model&, Body&)) {
  for (int k = 0; k < m.element_count; ++k) {
    Body b;
    b.name = fmt::format("{}[{}]", name, k);
    b.kind = BodyKind::rolling_element;
    b.index = k;
    b.mass = mass;
    b.axial_inertia = axial_inertia;
    b.transverse_inertia = transverse_inertia;
    b.offset = m.state_size;
    add_states(m, b);
    b.size = m.state_size - b.offset;
    m.bodies.push_back(b);
  }
}

namespace {
void roller_states(Model& m, Body& r, bool spin_angle) {
  add_states(m, r, sx, VariableClass::position, {"x", "y", "z"});
  add_state(m, r, sax, VariableClass::angle, "axis_angle_x");
  add_state(m, r, say, VariableClass::angle, "axis_angle_y");
  if (spin_angle) add_state(m, r, saz, VariableClass::angle, "spin_angle");
  add_states(m, r, svx, VariableClass::velocity, {"vx", "vy", "vz"});
  add_states(m, r, swx, VariableClass::angular_velocity, {"wx", "wy", "wz"});
}
}  // namespace

void (*spatial_roller_states(bool spin_angle))(Model&, Body&) {
  if (spin_angle) return [](Model& m, Body& r) { roller_states(m, r, true); };
  return [](Model& m, Body& r) { roller_states(m, r, false); };
}

void set_roller_radii(Model& m, const scene::BearingGeometry& g) {
  m.element_radii.clear();
  for (const double deviation : g.roller_diameter_deviations) m.element_radii.push_back(0.5 * (g.roller_diameter + deviation));
}

void scale_scattered_rollers(Model& m, double nominal_mass, double r_small, double r_large, double length) {
  if (m.element_radii.empty()) return;
  const double nominal_square = (r_small * r_small + r_small * r_large + r_large * r_large) / 3.0;
  for (Body& b : m.bodies) {
    if (b.kind != BodyKind::rolling_element) continue;
    const double grow = m.radius_of_element(b.index) - m.element_radius, a = r_small + grow, c = r_large + grow;
    const double square = (a * a + a * c + c * c) / 3.0;  // the sections' mean square radius
    b.mass = nominal_mass * square / nominal_square;
    b.axial_inertia = 0.5 * b.mass * square;
    if (b.transverse_inertia > 0) b.transverse_inertia = b.mass * (3.0 * square + length * length) / 12.0;
  }
}

std::string describe_roller_diameters(const Model& m) {
  if (m.element_radii.empty()) return {};
  const scene::BearingGeometry& g = m.params().bearing;
  std::string values;
  for (const double d : g.roller_diameter_deviations) values += fmt::format("{}{:+.4g}", values.empty() ? "" : " ", 1e6 * d);
  const std::string how = g.roller_diameter_scatter > 0
                              ? fmt::format("drawn, standard deviation {:.4g} um, scatter_seed {}",
                                            1e6 * g.roller_diameter_scatter, g.scatter_seed)
                              : std::string("given");
  return fmt::format("  roller diameters ({}): D + [{}] um\n", how, values);
}

double annulus_mass(double density, double r_in, double r_out, double width) {
  return density * std::numbers::pi * (r_out * r_out - r_in * r_in) * width;
}

const Segment* Model::first_segment(SegmentKind k) const {
  for (const Segment& s : segments)
    if (s.kind == k) return &s;
  return nullptr;
}

Mat3 cardan_rotation(double ax, double ay, double az) {
  return (Eigen::AngleAxisd(ax, Vec3::UnitX()) * Eigen::AngleAxisd(ay, Vec3::UnitY()) *
          Eigen::AngleAxisd(az, Vec3::UnitZ()))
      .toRotationMatrix();
}

const Mat3& memo_rotation(std::size_t slot, double ax, double ay, double az) {
  struct Entry {
    std::uint64_t key[3];
    Mat3 rotation;
    bool filled = false;
  };
  thread_local std::vector<Entry> memo;
  if (slot >= memo.size()) memo.resize(slot + 1);
  Entry& e = memo[slot];
  const std::uint64_t key[3] = {std::bit_cast<std::uint64_t>(ax), std::bit_cast<std::uint64_t>(ay),
                                std::bit_cast<std::uint64_t>(az)};
  if (!e.filled || e.key[0] != key[0] || e.key[1] != key[1] || e.key[2] != key[2]) {
    e.rotation = cardan_rotation(ax, ay, az);
    std::copy(key, key + 3, e.key);
    e.filled = true;
  }
  return e.rotation;
}

Vec3 cardan_rates(double ay, double az, const Vec3& w) {
  const double cb = std::cos(ay), sb = std::sin(ay), cc = std::cos(az), sc = std::sin(az);
  const double ax_rate = (w.x() * cc - w.y() * sc) / cb;
  return {ax_rate, w.x() * sc + w.y() * cc, w.z() - sb * ax_rate};
}

contact::PlanarKinematics Model::planar_kinematics(int b, double t, const double* z) const {
  const Body& body = bodies[static_cast<std::size_t>(b)];
  auto state = [&](Coordinate c) { return body.slot[c] >= 0 ? z[body.slot[c]] : 0.0; };
  double omega = state(swz);
  if (body.ring && body.ring->motion == scene::RingMotion::driven) omega = body.ring->speed(t);
  if (has_orbital_velocity(body)) {
    const Vec3 v = OrbitalFrame(state(sx), state(sy)).to_bearing({state(svx), state(svy), 0.0});
    return {state(sx), state(sy), state(saz), v.x(), v.y(), omega};
  }
  return {state(sx), state(sy), state(saz), state(svx), state(svy), omega};
}

double Model::ring_spin(int b, double t, const double* z) const {
  const Body& body = bodies[static_cast<std::size_t>(b)];
  if (body.slot[swz] >= 0) return z[body.slot[swz]];
  return body.ring && body.ring->motion == scene::RingMotion::driven ? body.ring->speed(t) : 0.0;
}

namespace {

// Model::kinematics' memo on this thread (KinematicsMemo): the model, t and z of the scope that
// lives, the scope's generation (an entry of another scope is stale) and per body its kinematics.
struct KinematicsEntry {
  std::uint64_t generation = 0;
  contact::SpatialKinematics k;
};
struct KinematicsMemoState {
  const Model* model = nullptr;
  const double* z = nullptr;
  const double* copy_of = nullptr;  // a second pointer to the same values, or null
  double t = 0;
  std::uint64_t generation = 0;
  std::vector<KinematicsEntry> entries;
};
thread_local KinematicsMemoState kinematics_memo;

}  // namespace

KinematicsMemo::KinematicsMemo(const Model& model, double t, const double* z, const double* copy_of)
    : previous_model_(kinematics_memo.model),
      previous_z_(kinematics_memo.z),
      previous_copy_of_(kinematics_memo.copy_of),
      previous_t_(kinematics_memo.t) {
  KinematicsMemoState& memo = kinematics_memo;
  // Within a scope at the values z copies (the same model and t): the same kinematics, kept on.
  continues_ = copy_of != nullptr && memo.model == &model && memo.z == copy_of && memo.copy_of == nullptr &&
               std::bit_cast<std::uint64_t>(memo.t) == std::bit_cast<std::uint64_t>(t);
  memo.model = &model, memo.z = z, memo.copy_of = copy_of, memo.t = t;
  if (!continues_) ++memo.generation;
  if (memo.entries.size() < model.bodies.size()) memo.entries.resize(model.bodies.size());
}

KinematicsMemo::~KinematicsMemo() {
  KinematicsMemoState& memo = kinematics_memo;
  memo.model = previous_model_, memo.z = previous_z_, memo.copy_of = previous_copy_of_, memo.t = previous_t_;
  if (!continues_) ++memo.generation;  // the outer scope's entries may have been overwritten
}

contact::SpatialKinematics Model::kinematics(int b, double t, const double* z) const {
  KinematicsMemoState& memo = kinematics_memo;
  if (memo.model != this || (memo.z != z && (memo.copy_of != z || z == nullptr)) ||
      std::bit_cast<std::uint64_t>(memo.t) != std::bit_cast<std::uint64_t>(t))
    return body_kinematics(b, t, z);
  KinematicsEntry& entry = memo.entries[static_cast<std::size_t>(b)];
  if (entry.generation != memo.generation) {
    entry.k = body_kinematics(b, t, z);
    entry.generation = memo.generation;
  }
  return entry.k;
}

contact::SpatialKinematics Model::body_kinematics(int b, double t, const double* z) const {
  const Body& body = bodies[static_cast<std::size_t>(b)];
  double v[coordinate_count] = {};
  for (int c = 0; c < coordinate_count; ++c)
    if (body.slot[c] >= 0) v[c] = z[body.slot[c]];
  contact::SpatialKinematics k;
  if (body.ring && body.slot[sz] < 0) v[sz] = body.ring->axial_position;  // held axially: where it is held
  k.position = Vec3(v[sx], v[sy], v[sz]);
  k.velocity = Vec3(v[svx], v[svy], v[svz]);
  if (has_orbital_velocity(body)) k.velocity = OrbitalFrame(v[sx], v[sy]).to_bearing(k.velocity);
  switch (body.kind) {
    case BodyKind::rolling_element:
      // A ball that carries a defect, or a spatial roller (its spin angle with a defect): every one
      // of a roller's slices asks for the same rotation.
      if (body.ball_orientation || body.slot[sax] >= 0)
        k.rotation = memo_rotation(2 * static_cast<std::size_t>(b), v[sax], v[say], v[saz]);
      k.angular_velocity = Vec3(v[swx], v[swy], v[swz]);
      break;
    case BodyKind::cage:
      k.rotation = memo_rotation(2 * static_cast<std::size_t>(b), v[sax], v[say], v[saz]);
      k.angular_velocity = k.rotation * Vec3(v[swx], v[swy], v[swz]);
      break;
    case BodyKind::inner_ring:
    case BodyKind::outer_ring: {
      if (body.ring->tilt == scene::RingTilt::prescribed) {
        v[sax] = body.ring->misalignment_x(t), v[say] = body.ring->misalignment_y(t);
        v[swx] = body.ring->misalignment_x.derivative(t), v[swy] = body.ring->misalignment_y.derivative(t);
      }
      k.rotation = memo_rotation(2 * static_cast<std::size_t>(b), v[sax], v[say], 0.0);
      const Mat3& rx = memo_rotation(2 * static_cast<std::size_t>(b) + 1, v[sax], 0.0, 0.0);
      k.angular_velocity = ring_spin(b, t, z) * k.rotation.col(2) + v[swx] * Vec3::UnitX() + v[swy] * rx.col(1);
      if (body.ring->motion == scene::RingMotion::driven) k.spin_angle = body.ring->speed.integral(t);
      break;
    }
  }
  return k;
}

void Model::set_velocity(int b, const Vec3& v, double* z) const {
  const Body& body = bodies[static_cast<std::size_t>(b)];
  const Vec3 stored = has_orbital_velocity(body) ? OrbitalFrame(z[body.slot[sx]], z[body.slot[sy]]).to_orbital(v) : v;
  for (int d = 0; d < 3; ++d)
    if (body.slot[svx + d] >= 0) z[body.slot[svx + d]] = stored[d];
}

Vec3 Model::acceleration(int b, const double* z, const double* zdot) const {
  const Body& body = bodies[static_cast<std::size_t>(b)];
  Vec3 rates, v;
  for (int d = 0; d < 3; ++d) {
    const int j = body.slot[svx + d];
    rates[d] = j >= 0 ? zdot[j] : 0.0, v[d] = j >= 0 ? z[j] : 0.0;
  }
  if (!has_orbital_velocity(body)) return rates;
  return OrbitalFrame(z[body.slot[sx]], z[body.slot[sy]]).acceleration(rates, v);
}

double Model::epicyclic_cage_speed(double t) const {
  if (cup_angle > 0) {  // tapered: rolling on both raceway cones about their common apex
    auto speed = [&](int b) {
      const auto* r = bodies[static_cast<std::size_t>(b)].ring;
      return r->motion == scene::RingMotion::driven ? r->speed(t) : 0.0;
    };
    const double si = std::sin(cone_angle), so = std::sin(cup_angle);
    return (speed(inner_ring) * si + speed(outer_ring) * so) / (si + so);
  }
  if (kind == scene::ModelKind::spatial) return epicyclic_cage_speed(t, nominal_contact_angle);
  auto speed = [&](int b) {
    const auto* r = bodies[static_cast<std::size_t>(b)].ring;
    return r->motion == scene::RingMotion::driven ? r->speed(t) : 0.0;
  };
  const double ri = inner_race_radius, ro = outer_race_radius;
  return (speed(inner_ring) * ri + speed(outer_ring) * ro) / (ri + ro);
}

double Model::epicyclic_cage_speed(double t, double contact_angle) const {
  auto speed = [&](int b) {
    const auto* r = bodies[static_cast<std::size_t>(b)].ring;
    return r->motion == scene::RingMotion::driven ? r->speed(t) : 0.0;
  };
  const double gamma = 2.0 * element_radius * std::cos(contact_angle) / (2.0 * pitch_radius);
  return 0.5 * (speed(inner_ring) * (1.0 - gamma) + speed(outer_ring) * (1.0 + gamma));
}

double max_abs(const scene::TimeFunction& f) {
  double v = 0;
  for (double x : f.values) v = std::max(v, std::abs(x));
  return v;
}

std::vector<double> physical_absolute_tolerance(const ModelParameters& p, const std::vector<VariableClass>& state_class,
                                                double pitch_radius, double rolling_element_radius) {
  const auto& s = p.solver;
  double drive = std::max(max_abs(p.inner_ring.speed), max_abs(p.outer_ring.speed));
  drive = std::max(drive, 1.0);
  const double surface_speed = drive * pitch_radius;
  const double spin_scale = drive * pitch_radius / rolling_element_radius;
  std::vector<double> atol(state_class.size());
  for (std::size_t i = 0; i < state_class.size(); ++i) {
    switch (state_class[i]) {
      case VariableClass::position: atol[i] = s.atol_position > 0 ? s.atol_position : s.rtol * pitch_radius; break;
      case VariableClass::angle: atol[i] = s.atol_angle > 0 ? s.atol_angle : s.rtol; break;
      case VariableClass::velocity: atol[i] = s.atol_velocity > 0 ? s.atol_velocity : s.rtol * surface_speed; break;
      case VariableClass::angular_velocity:
        atol[i] = s.atol_angular_velocity > 0 ? s.atol_angular_velocity : s.rtol * spin_scale;
        break;
    }
  }
  return atol;
}

std::vector<double> Model::absolute_tolerance() const {
  std::vector<double> atol = physical_absolute_tolerance(*parameters, state_class, pitch_radius, element_radius);
  for (const auto& node : nodes) node->set_tolerances(atol);
  const double radial = params().solver.radial_velocity_tolerance_factor;
  for (const Body& b : bodies)  // orbital frame: the radial velocity's own tolerance
    if (has_orbital_velocity(b) && radial != 1.0) atol[static_cast<std::size_t>(b.slot[svx])] *= radial;
  return atol;
}

void add_body_columns(const Model& m, int b, bool on_a, std::vector<SegmentColumn>& out) {
  for (int c = 0; c < coordinate_count; ++c)
    if (const int j = m.bodies[static_cast<std::size_t>(b)].slot[c]; j >= 0) out.push_back({b, c, j, on_a});
}

std::vector<SegmentColumn> segment_columns(const Model& m, const Segment& seg) {
  std::vector<SegmentColumn> columns;
  for (const bool on_a : {true, false}) {
    const Marker& marker = m.markers[static_cast<std::size_t>(on_a ? seg.marker_a : seg.marker_b)];
    if (const auto* centre = std::get_if<BodyCentre>(&marker))
      add_body_columns(m, centre->body, on_a, columns);
    else
      std::get<std::shared_ptr<const MarkerKind>>(marker)->columns(m, on_a, columns);
  }
  return columns;
}

void Loads::clear() {
  for (auto& w : body) w = {};
  for (double& f : node) f = 0.0;
}

contact::LineFilm line_film(const scene::Scene& scene, double e_star, double reduced_radius, double length,
                            double roller_radius) {
  contact::LineFilm f;
  f.viscosity = scene.lubricant.viscosity;
  f.pressure_viscosity = scene.lubricant.pressure_viscosity;
  f.reduced_modulus = e_star;
  f.reduced_radius = reduced_radius;
  f.length = length;
  f.cutoff = 0.02 * roller_radius;
  return f;
}

std::optional<contact::EhdRaceFilm> roller_race_film(const scene::Scene& scene, const contact::LineFilm& film,
                                                     double stiffness, double max_approach, double damping_factor) {
  const scene::ContactSpec& spec = scene.roller_race;
  if (spec.normal.id != contact::LawId::moes_ehd) return std::nullopt;
  contact::EhdRaceFilm f;
  f.law.film = film;
  f.law.stiffness = stiffness;
  f.law.max_approach = max_approach;
  f.damping_factor = damping_factor;
  f.traction = spec.traction.id == contact::LawId::ehd_traction;
  f.couette = {spec.traction.friction_coefficient, 0.05, spec.traction.slip_velocity_scale};
  return f;
}

}  // namespace raceway::bearing
