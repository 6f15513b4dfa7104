#include "solver/run/output_writer.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "io/scene/scene_parameters.hpp"
#include "io/scene/scene_parser.hpp"
#include "solver/bearing/element_traits.hpp"
#include "solver/run/housing_sensor.hpp"
#include "solver/run/pocket_steps.hpp"
#include "solver/run/schedule_output.hpp"

namespace raceway::run {

using contact::Vec3;

namespace {

enum class Quantity { position, velocity, angles, angular_velocity, acceleration, force };

/// One dataset of a body group: `count` components of a sampled quantity.
struct BodySeries {
  const char* name;
  Quantity quantity;
  std::vector<int> components;
  const char* unit;
  const char* meaning;
};

// One name per quantity in both spaces (layout version 3): a planar bearing stores the planar
// components (x, y and about z) of the quantity a spatial one stores in full; each series' attribute
// `components` names its columns. docs/output_layout.md lists the names of earlier versions.
const std::vector<BodySeries>& border_series(scene::ModelKind kind) {
  static const std::vector<BodySeries> planar = {
      {"position", Quantity::position, {0, 1}, "m", "centre x, y in the bearing frame"},
      {"velocity", Quantity::velocity, {0, 1}, "m/s", "centre velocity"},
      {"angles", Quantity::angles, {2}, "rad", "rotation about z (0 where not a state)"},
      {"angular_velocity", Quantity::angular_velocity, {2}, "rad/s", "rotation rate about z (drive speed if driven)"},
      {"acceleration", Quantity::acceleration, {0, 1, 5}, "m/s^2, m/s^2, rad/s^2",
       "ax, ay, angular acceleration (0 where not a state)"},
      {"force", Quantity::force, {0, 1, 5}, "N, N, N m", "net force and moment (contacts, loads, supports)"}};
  static const std::vector<BodySeries> spatial = {
      {"position", Quantity::position, {0, 1, 2}, "m", "centre in the bearing frame"},
      {"velocity", Quantity::velocity, {0, 1, 2}, "m/s", "centre velocity"},
      {"angles", Quantity::angles, {0, 1, 2}, "rad", "tilt about x, tilt about y, rotation about z (rings: 0 about z)"},
      {"angular_velocity", Quantity::angular_velocity, {0, 1, 2}, "rad/s", "angular velocity, bearing frame"},
      {"acceleration", Quantity::acceleration, {0, 1, 2, 3, 4, 5}, "m/s^2, rad/s^2",
       "centre acceleration and angular acceleration, bearing frame (0 where not a state)"},
      {"force", Quantity::force, {0, 1, 2, 3, 4, 5}, "N, N m",
       "net force and moment at the centre (contacts, loads, supports, gravity)"}};
  return kind == scene::ModelKind::spatial ? spatial : planar;
}

const std::vector<BodySeries>& element_series(const bearing::Model& m) {
  static const std::vector<BodySeries> planar = {
      {"position", Quantity::position, {0, 1}, "m", "roller centres x, y"},
      {"velocity", Quantity::velocity, {0, 1}, "m/s", "roller centre velocities"},
      {"angular_velocity", Quantity::angular_velocity, {2}, "rad/s", "roller rotation rate about its axis"},
      {"acceleration", Quantity::acceleration, {0, 1, 5}, "m/s^2, m/s^2, rad/s^2", "ax, ay, spin acceleration"}};
  static const std::vector<BodySeries> spatial = {
      {"position", Quantity::position, {0, 1, 2}, "m", "ball centres"},
      {"velocity", Quantity::velocity, {0, 1, 2}, "m/s", "ball centre velocities"},
      {"angular_velocity", Quantity::angular_velocity, {0, 1, 2}, "rad/s", "ball angular velocities, bearing frame"},
      {"acceleration", Quantity::acceleration, {0, 1, 2, 3, 4, 5}, "m/s^2, rad/s^2",
       "ball centre acceleration and angular acceleration, bearing frame"}};
  // Spatial rollers: the balls' series, said of rollers, and the angles of their axes.
  static const std::vector<BodySeries> spatial_rollers = {
      {"position", Quantity::position, {0, 1, 2}, "m", "roller centres"},
      {"angles", Quantity::angles, {0, 1}, "rad",
       "the roller axis's Cardan angles about x and y (axis = Rx Ry e_z: its tilt and skew at the roller's azimuth)"},
      {"velocity", Quantity::velocity, {0, 1, 2}, "m/s", "roller centre velocities"},
      {"angular_velocity", Quantity::angular_velocity, {0, 1, 2}, "rad/s", "roller angular velocities, bearing frame"},
      {"acceleration", Quantity::acceleration, {0, 1, 2, 3, 4, 5}, "m/s^2, rad/s^2",
       "roller centre acceleration and angular acceleration, bearing frame"}};
  if (m.kind != scene::ModelKind::spatial) return planar;
  return !m.params().bearing.is_ball_bearing() ? spatial_rollers : spatial;
}

/// The `components` attribute of a series: what each of its columns is ("x", "about z", ...).
std::vector<std::string> component_names(const BodySeries& s) {
  static const char* const linear[] = {"x", "y", "z"};
  static const char* const angular[] = {"about x", "about y", "about z"};
  static const char* const wrench[] = {"x", "y", "z", "about x", "about y", "about z"};
  std::vector<std::string> names;
  for (int c : s.components) {
    switch (s.quantity) {
      case Quantity::position:
      case Quantity::velocity: names.emplace_back(linear[c]); break;
      case Quantity::angles:
      case Quantity::angular_velocity: names.emplace_back(angular[c]); break;
      case Quantity::acceleration:
      case Quantity::force: names.emplace_back(wrench[c]); break;
    }
  }
  return names;
}

/// The row shape of a series: `leading` (the rolling elements, or none), then the components unless
/// there is one (a scalar per body is stored [T], not [T x 1]).
std::vector<std::size_t> row_shape(const BodySeries& s, std::vector<std::size_t> leading) {
  if (s.components.size() > 1) leading.push_back(s.components.size());
  return leading;
}

/// Whether the rolling elements' series of a quantity are stored deflated: not their positions,
/// velocities and accelerations, full-precision trajectories that deflate shrinks by 11-22 % (6309 R3,
/// QJ215, seed 002) for a fifth to a quarter of the compressor's work
/// (perf/studies/results/revolution_instructions.md).
bool compressible(Quantity q) {
  return q != Quantity::position && q != Quantity::velocity && q != Quantity::acceleration;
}

/// The sampled quantity's components, by its component index.
const double* components_of(const BodySample& s, Quantity q) {
  switch (q) {
    case Quantity::position: return s.position.data();
    case Quantity::velocity: return s.velocity.data();
    case Quantity::angles: return s.angles.data();
    case Quantity::angular_velocity: return s.angular_velocity.data();
    case Quantity::acceleration: return s.acceleration;
    case Quantity::force: return s.force;
  }
  return nullptr;
}

/// Appends the series' components of the sample to `row` from `at` on; returns the end.
double* put_components(const BodySeries& series, const BodySample& s, double* at) {
  const double* values = components_of(s, series.quantity);
  for (const int c : series.components) *at++ = values[c];
  return at;
}


template <class Table>
void define_diagnostics(h5::H5SeriesWriter& file, const std::string& group, const Table& fields, std::size_t columns,
                        bool shared, std::size_t stride) {
  for (const auto& f : fields) file.define_series(group + "/" + f.name, {columns}, f.unit, f.meaning, shared, true, stride);
}

template <class Table>
std::vector<h5::H5SeriesWriter::SeriesId> diagnostic_ids(const h5::H5SeriesWriter& file, const std::string& group,
                                                         const Table& fields) {
  std::vector<h5::H5SeriesWriter::SeriesId> ids;
  for (const auto& f : fields) ids.push_back(file.series_id(group + "/" + f.name));
  return ids;
}

/// The step-resolved pocket statistics (solver/run/pocket_steps.hpp), in the order of a row's quantities.
struct PocketStepSeries {
  const char* path;
  const char* unit;
  const char* meaning;
};
constexpr PocketStepSeries pocket_step_series[PocketSteps::quantities] = {
    {"/cage/pocket_step_onsets", "-",
     "contact onsets (force 0 at one evaluation, > 0 at the next) per pocket and side in the interval ending here"},
    {"/cage/pocket_step_peak_force", "N",
     "largest pocket normal force per pocket and side at the steps of the interval"},
    {"/cage/pocket_step_impulse", "N s",
     "pocket normal-force impulse per pocket and side over the interval (trapezoid over the steps)"},
    {"/cage/pocket_step_contact_time", "s",
     "time in contact per pocket and side over the interval (trapezoid over the steps)"}};

long columns(const std::vector<BodySeries>& series) {
  long n = 0;
  for (const BodySeries& s : series) n += static_cast<long>(s.components.size());
  return n;
}

/// "1.99 MB", "4 GB": a byte count in decimal units.
std::string bytes_text(double bytes) {
  constexpr std::pair<double, const char*> units[] = {{1e12, "TB"}, {1e9, "GB"}, {1e6, "MB"}, {1e3, "kB"}};
  for (const auto& [size, name] : units)
    if (bytes >= size) return fmt::format("{:.3g} {}", bytes / size, name);
  return fmt::format("{:.0f} B", bytes);
}

// Upper bounds of the parts of a file beside its series' values, measured on this writer's files
// (tests/system/cli/cli_test.sh output_size checks the whole file against the estimate): the superblock,
// the root's fixed attributes (build, versions) and the summary's fixed keys; per dataset its
// object header (shape, chunking, filters, units, description, the time scale's references) and
// its first chunk-index node; per series byte the chunk index's growth and deflate's worst case.
// Measured on the default scene (63 datasets): 455 kB on disk for 224 kB of stored chunks, 3.7 kB
// per dataset beside its chunks, of which the summary (12 kB: the scene's parameters, 3.4 times the
// scene text) and the root's attributes are a fifth.
constexpr double kFileBaseBytes = 32e3;
constexpr double kBytesPerDataset = 4e3;
constexpr double kIndexShare = 0.01;

/// The datasets the writer defines for `m` (OutputWriter's constructor and define_segment_groups).
double dataset_count(const bearing::Model& m, bool segments) {
  double n = 2 + static_cast<double>(m.first_element * static_cast<int>(border_series(m.kind).size())) +
             static_cast<double>(element_series(m).size()) + PocketSteps::quantities + PowerBalanceSeries::datasets +
             ThermalSeries::datasets(m);
  n += 2;  // /cage/epicyclic_speed, /cage/rolling_speed (both kinds)
  if (!segments) return n;
  std::set<std::pair<int, bool>> kinds;  // (kind, line family)
  for (const bearing::Segment& s : m.segments)
    kinds.emplace(static_cast<int>(s.kind), is_planar_element(m.laws[static_cast<std::size_t>(s.law)]));
  for (const auto& [kind, line] : kinds)
    n += 2 + static_cast<double>(line ? contact::line_diagnostic_fields.size() : contact::point_diagnostic_fields.size());
  return n;
}

/// Everything of a file but its series' values and the /scheduler log's arrays (OutputEstimate).
double fixed_output_bytes(const bearing::Model& m, const scene::Scene& scene, double series_bytes) {
  // The scene text in scene_text and about four times in the summary's parameters; the model's description.
  double text = 5 * static_cast<double>(scene.text.size()) + static_cast<double>(scene.source.size() + m.describe().size());
  for (const std::string& o : scene.overrides) text += 2 * static_cast<double>(o.size());
  double names = 0;  // variable-length strings: a 16-byte reference and the text in a heap
  for (const std::string& n : m.state_name) names += 32 + static_cast<double>(n.size());
  if (scene.output.segments)
    for (const bearing::Segment& s : m.segments) names += 40 + static_cast<double>(s.name.size());
  return kFileBaseBytes + text + names + kBytesPerDataset * dataset_count(m, scene.output.segments) +
         kIndexShare * series_bytes + kScheduleLogFixedBytes;
}

}  // namespace

std::string OutputEstimate::describe(double limit) const {
  const std::string coarse = segment_every > 1 && segment_values > 0
                                 ? fmt::format(" ({} of them once every {} samples)", segment_values, segment_every)
                                 : "";
  return fmt::format("output: {} samples x {} values{} = {} + {} of names, attributes and indexes (limit {}, [output] "
                     "max_size)",
                     samples, values_per_sample, coarse, bytes_text(bytes), bytes_text(fixed_bytes), bytes_text(limit));
}

OutputEstimate estimate_output(const bearing::Model& m, const scene::Scene& scene) {
  OutputEstimate e;
  const double end = scene.scene.end_time, dt = scene.scene.output_interval;
  // As run_scene counts them: t = 0 and every whole interval up to end_time. Held as a double
  // first: a scene that passed the sane ranges can still ask for 1e17 samples.
  const double samples = std::floor(end / dt + 1e-9) + 1;
  long values = 2 + m.first_element * columns(border_series(m.kind)) + m.element_count * columns(element_series(m));
  values += 2;  // /cage/epicyclic_speed, /cage/rolling_speed
  values += PocketSteps::quantities * PocketSteps::sides * PocketSteps(m).pockets();
  values += PowerBalanceSeries::values(m) + ThermalSeries::values(m);
  if (const bearing::Housing* housing = bearing::housing_of(m)) values += HousingSensor::quantities * housing->sensor_samples();
  long segment_values = 0;  // at every segment_every-th sample: ceil(samples / segment_every) rows
  if (scene.output.segments)
    for (const bearing::Segment& s : m.segments)
      segment_values += static_cast<long>(diagnostic_count(m.laws[static_cast<std::size_t>(s.law)]));
  const double segment_rows = std::ceil(samples / scene.output.segment_every);
  e.values_per_sample = values + segment_values;
  e.segment_values = segment_values, e.segment_every = scene.output.segment_every;
  e.bytes = (samples * static_cast<double>(values) + segment_rows * static_cast<double>(segment_values)) * sizeof(double);
  e.samples = samples < 9e18 ? static_cast<long>(samples) : -1;
  e.fixed_bytes = fixed_output_bytes(m, scene, e.bytes);
  return e;
}

void check_output_size(const OutputEstimate& e, const scene::Scene& scene) {
  const double limit = scene.output.max_size;
  if (e.total() <= limit) return;
  const std::string key = "scene.output_interval";
  throw scene::SceneError(
      scene.source, scene.line_of(key), key,
      fmt::format("the output would be {} ({:.4g} samples, one every {:g} s over end_time = {:g} s, x {} values x 8 "
                  "bytes, + {} of names, attributes and indexes), more than [output] max_size = {}: raise "
                  "output_interval, shorten end_time{}, or raise max_size",
                  bytes_text(e.total()), std::floor(scene.scene.end_time / scene.scene.output_interval + 1e-9) + 1,
                  scene.scene.output_interval, scene.scene.end_time, e.values_per_sample, bytes_text(e.fixed_bytes),
                  bytes_text(limit),
                  scene.output.segments ? ", set [output] segments = false or raise segment_every" : ""));
}

namespace {

/// A choice key's word as the scene spells it ("deep_groove_ball"), from the schema's resolved
/// parameters (the one table of those names).
std::string scene_word(const scene::Scene& scene, const std::string& key) {
  for (const scene::SceneParameter& p : scene::scene_parameters(scene))
    if (p.key == key && p.word) return *p.word;
  return "";
}

}  // namespace

void write_bearing_attributes(h5::H5SeriesWriter& file, const bearing::Model& m, const scene::Scene& scene) {
  const scene::BearingGeometry& g = scene.bearing;
  const bool spatial = m.kind == scene::ModelKind::spatial;
  file.set_attribute("/", "model_kind", std::string(spatial ? "spatial" : "planar"));
  file.set_attribute("/", "bearing_type", scene_word(scene, "bearing.type"));
  file.set_attribute("/", "rolling_element", std::string(g.is_ball_bearing() ? "ball" : "roller"));
  file.set_attribute("/", "element_group", std::string(m.element_group));
  file.set_attribute("/", "element_count", static_cast<long long>(m.element_count));
  file.set_attribute("/", "pitch_radius", m.pitch_radius);
  file.set_attribute("/", "element_radius", m.element_radius);
  if (!m.element_radii.empty()) {
    std::vector<double> diameters;
    for (const double r : m.element_radii) diameters.push_back(2.0 * r);
    file.set_attribute("/", "element_diameters", diameters);
  }
  if (!scene.cage.pocket_clearance_deviations.empty()) {
    std::vector<double> clearances;
    for (const double d : scene.cage.pocket_clearance_deviations) clearances.push_back(scene.cage.pocket_clearance + d);
    file.set_attribute("/", "pocket_clearances", clearances);
  }
  file.set_attribute("/", "inner_race_radius", 0.5 * g.inner_race_diameter());
  file.set_attribute("/", "outer_race_radius", 0.5 * g.outer_race_diameter());
  file.set_attribute("/", "diametral_clearance", g.radial_clearance);
  file.set_attribute("/", "nominal_contact_angle", m.nominal_contact_angle);
  file.set_attribute("/", "arcs_per_ring", static_cast<long long>(m.arcs_per_ring));
  if (g.is_ball_bearing()) {
    file.set_attribute("/", "inner_groove_radius", g.ball.inner_conformity * g.ball.ball_diameter);
    file.set_attribute("/", "outer_groove_radius", g.ball.outer_conformity * g.ball.ball_diameter);
  } else {
    file.set_attribute("/", "roller_length", g.roller_length);
  }
  if (g.is_tapered()) {
    file.set_attribute("/", "cup_angle", m.cup_angle);
    file.set_attribute("/", "cone_angle", m.cone_angle);
  }
  file.set_attribute("/", "cage_guidance", scene_word(scene, "cage.guidance"));
  file.set_attribute("/", "pocket_clearance", scene.cage.pocket_clearance);
  file.set_attribute("/", "land_clearance",
                     m.first_segment(bearing::SegmentKind::cage_land) ? scene.cage.land_clearance : 0.0);
  // The integrator's error control on the rolling elements' positions: the resolution of what is
  // read from them (the report's contact-angle resolution).
  const std::vector<double> atol = m.absolute_tolerance();
  const bearing::Body& element = m.bodies[static_cast<std::size_t>(m.first_element)];
  const int slot = element.slot[spatial ? bearing::sz : bearing::sx];
  file.set_attribute("/", "element_position_tolerance", slot >= 0 ? atol[static_cast<std::size_t>(slot)] : 0.0);
  file.set_attribute("/", "relative_tolerance", scene.solver.rtol);
}

BodySample sample_body(const bearing::Model& m, int b, double t, const std::vector<double>& z, const std::vector<double>& zdot,
                       const bearing::Wrench& net) {
  const bearing::Body& body = m.bodies[static_cast<std::size_t>(b)];
  auto state = [&](int c) { return body.slot[c] >= 0 ? z[static_cast<std::size_t>(body.slot[c])] : 0.0; };
  BodySample s;
  for (int c = 0; c < 6; ++c) {
    s.acceleration[c] = body.slot[bearing::svx + c] >= 0 ? zdot[static_cast<std::size_t>(body.slot[bearing::svx + c])] : 0.0;
    s.force[c] = c < 3 ? net.force[c] : net.moment[c - 3];
  }
  if (m.has_orbital_velocity(body)) {  // the states' rates are orbital: the file keeps the bearing frame
    const Vec3 a = m.acceleration(b, z.data(), zdot.data());
    for (int c = 0; c < 3; ++c) s.acceleration[c] = a[c];
  }
  if (m.kind == scene::ModelKind::planar) {
    const auto k = m.planar_kinematics(b, t, z.data());
    s.position = Vec3(k.x, k.y, 0), s.velocity = Vec3(k.vx, k.vy, 0);
    s.angles = Vec3(0, 0, k.theta), s.angular_velocity = Vec3(0, 0, k.omega);
    return s;
  }
  const auto k = m.kinematics(b, t, z.data());
  s.position = k.position, s.velocity = k.velocity, s.angular_velocity = k.angular_velocity;
  s.angles = Vec3(state(bearing::sax), state(bearing::say), state(bearing::saz));
  if (body.ring && body.ring->tilt == scene::RingTilt::prescribed)
    s.angles.x() = body.ring->misalignment_x(t), s.angles.y() = body.ring->misalignment_y(t);
  return s;
}

std::map<std::string, SegmentSeries> segment_series(const bearing::Model& m) {
  std::map<std::string, SegmentSeries> all;
  for (int k = 0; k < bearing::segment_kind_count; ++k) {
    std::vector<int> segments;
    for (std::size_t s = 0; s < m.segments.size(); ++s)
      if (static_cast<int>(m.segments[s].kind) == k) segments.push_back(static_cast<int>(s));
    if (segments.empty()) continue;
    const std::string g = std::string("/segments/") + segment_kind_name(static_cast<bearing::SegmentKind>(k)) + "/";
    auto add = [&](const auto& fields) {
      for (std::size_t f = 0; f < fields.size(); ++f) all[g + fields[f].name] = {static_cast<int>(f), segments};
    };
    if (is_planar_element(m.laws[static_cast<std::size_t>(m.segments[static_cast<std::size_t>(segments[0])].law)]))
      add(contact::line_diagnostic_fields);
    else
      add(contact::point_diagnostic_fields);
  }
  return all;
}

OutputWriter::OutputWriter(h5::H5SeriesWriter& file, const bearing::Model& m, bool segments, bool shared_segments,
                           int segment_every)
    : file_(file), m_(m), segments_(segments), shared_(shared_segments), segment_every_(std::max(1, segment_every)) {
  file_.define_series("/time", {}, "s", "output times (interpolated, not solver steps)");
  file_.define_series("/energy", {}, "J", "kinetic + elastic + support + load potential energy");
  for (int b = 0; b < m.first_element; ++b)
    for (const BodySeries& s : border_series(m.kind)) {
      const std::string path = "/" + m.bodies[static_cast<std::size_t>(b)].name + "/" + s.name;
      file_.define_series(path, row_shape(s, {}), s.unit, s.meaning);
      file_.set_attribute(path, "components", component_names(s));
    }
  if (m.bearing_type == scene::BearingType::tapered_roller) {
    file_.define_series("/cage/epicyclic_speed", {}, "rad/s",
                        "kinematic cage speed: tapered rollers rolling without slip on both raceway cones about their "
                        "common apex (w_i sin a_i + w_o sin a_o) / (sin a_i + sin a_o)");
    file_.define_series("/cage/rolling_speed", {}, "rad/s",
                        "kinematic cage speed at the loaded contact angles: a tapered roller's line contacts lie on "
                        "the raceway cones, so the epicyclic speed");
  } else if (m.kind == scene::ModelKind::spatial) {
    file_.define_series("/cage/epicyclic_speed", {}, "rad/s", "kinematic cage speed (seed 001 eq. 5, nominal contact angle)");
    file_.define_series("/cage/rolling_speed", {}, "rad/s",
                        "kinematic cage speed at the load-weighted mean contact angle of the inner-groove contacts "
                        "(nominal angle when none is loaded)");
  } else {
    file_.define_series("/cage/epicyclic_speed", {}, "rad/s",
                        "kinematic cage speed: rollers rolling without slip on both races (line contacts, 0 deg)");
    file_.define_series("/cage/rolling_speed", {}, "rad/s",
                        "kinematic cage speed at the loaded contact angle: line contacts roll at 0 deg, so the "
                        "epicyclic speed");
  }
  const auto n = static_cast<std::size_t>(m.element_count);
  for (const BodySeries& s : element_series(m)) {
    const std::string path = std::string("/") + m.element_group + "/" + s.name;
    file_.define_series(path, row_shape(s, {n}), s.unit, s.meaning, false, compressible(s.quantity));
    file_.set_attribute(path, "components", component_names(s));
  }
  define_pocket_steps();
  define_housing_sensor();
  power_ = define_power_balance_series(file_, m);
  thermal_.emplace(file_, m);
  if (segments_) define_segment_groups();
  time_ = file_.series_id("/time"), energy_ = file_.series_id("/energy");
  for (int b = 0; b < m.first_element; ++b)
    for (const BodySeries& s : border_series(m.kind))
      border_ids_.push_back(file_.series_id("/" + m.bodies[static_cast<std::size_t>(b)].name + "/" + s.name));
  epicyclic_ = file_.series_id("/cage/epicyclic_speed"), rolling_ = file_.series_id("/cage/rolling_speed");
  for (const BodySeries& s : element_series(m))
    element_ids_.push_back(file_.series_id(std::string("/") + m.element_group + "/" + s.name));
  file_.set_time_scale("/time", "time");
  file_.set_attribute("/", "state_names", m.state_name);
}

void OutputWriter::define_pocket_steps() {
  const int pockets = PocketSteps(m_).pockets();
  if (pockets == 0) return;
  for (const PocketStepSeries& s : pocket_step_series) {
    file_.define_series(s.path, {static_cast<std::size_t>(pockets), PocketSteps::sides}, s.unit, s.meaning);
    pocket_step_ids_.push_back(file_.series_id(s.path));
    pocket_cells_ = static_cast<std::size_t>(pockets) * PocketSteps::sides;
  }
}

/// The housing sensor's series (solver/run/housing_sensor.hpp), in the order of its row.
struct SensorSeries {
  const char* path;
  const char* unit;
  const char* meaning;
};
constexpr SensorSeries sensor_series[] = {
    {"/housing/sensor_time", "s", "times of the sensor's samples in the output interval that ends here (NaN at t = 0)"},
    {"/housing/displacement", "m", "housing (and outer ring) displacement x, y at the sensor's samples"},
    {"/housing/velocity", "m/s", "housing velocity x, y at the sensor's samples"},
    {"/housing/acceleration", "m/s^2", "housing acceleration x, y at the sensor's samples (what an accelerometer reads)"}};

void OutputWriter::define_housing_sensor() {
  const bearing::Housing* housing = bearing::housing_of(m_);
  if (!housing) return;
  const auto per = static_cast<std::size_t>(housing->sensor_samples());
  sensor_per_ = per;
  for (const SensorSeries& s : sensor_series) {
    const bool time = sensor_ids_.empty();
    file_.define_series(s.path, time ? std::vector<std::size_t>{per} : std::vector<std::size_t>{per, 2}, s.unit,
                        s.meaning);
    sensor_ids_.push_back(file_.series_id(s.path));
  }
  file_.set_attribute("/housing", "mass", housing->mass());
  file_.set_attribute("/housing", "stiffness", housing->stiffness());
  file_.set_attribute("/housing", "damping", housing->damping());
  // The lowest resonance (the report's envelope band is about it), and every one with more modes.
  file_.set_attribute("/housing", "natural_frequency", housing->frequencies().front());
  if (housing->mode_count() > 1) {
    file_.set_attribute("/housing", "mode_frequencies", housing->frequencies());
    std::vector<double> participation;
    for (const bearing::Housing::Mode& mode : housing->modes()) participation.push_back(mode.sensor);
    file_.set_attribute("/housing", "sensor_participation", participation);
  }
}

void OutputWriter::define_segment_groups() {
  const auto stride = static_cast<std::size_t>(segment_every_);
  if (stride > 1)
    file_.define_series("/segments/time", {}, "s", "output times of the rows of /segments: every sample_stride-th of /time",
                        false, true, stride);
  for (int k = 0; k < bearing::segment_kind_count; ++k) {
    std::vector<std::string> names;
    std::vector<double> elements;
    for (std::size_t s = 0; s < m_.segments.size(); ++s)
      if (static_cast<int>(m_.segments[s].kind) == k) {
        names.push_back(m_.segments[s].name);
        elements.push_back(m_.segments[s].element);
        index_[k].push_back(static_cast<int>(s));
      }
    if (names.empty()) continue;
    line_family_[k] = bearing::is_planar_element(m_.laws[static_cast<std::size_t>(m_.segments[static_cast<std::size_t>(index_[k][0])].law)]);
    const std::string g = std::string("/segments/") + segment_kind_name(static_cast<bearing::SegmentKind>(k));
    file_.write_array(g + "/names", names, "segment names, in column order of the datasets of this group");
    file_.write_array(g + "/element", {elements.size()}, elements, "-",
                      "rolling element (0-based) of each column; -1 for cage-land");
    if (line_family_[k]) {
      define_diagnostics(file_, g, contact::line_diagnostic_fields, names.size(), shared_, stride);
      diagnostic_ids_[k] = diagnostic_ids(file_, g, contact::line_diagnostic_fields);
    } else {
      define_diagnostics(file_, g, contact::point_diagnostic_fields, names.size(), shared_, stride);
      diagnostic_ids_[k] = diagnostic_ids(file_, g, contact::point_diagnostic_fields);
    }
  }
  file_.set_attribute("/segments", "sample_stride", static_cast<long long>(stride));
  if (stride == 1) return;
  segment_time_ = file_.series_id("/segments/time");
  file_.set_time_scale("/segments/time", "segment time");
}

double OutputWriter::loaded_contact_angle(const bearing::Model& m, const bearing::Equations& eq) {
  constexpr int normal_force = contact::field_index(contact::point_diagnostic_fields, "normal_force");
  constexpr int contact_angle = contact::field_index(contact::point_diagnostic_fields, "contact_angle");
  double load = 0, weighted = 0;
  for (std::size_t s = 0; s < m.segments.size(); ++s) {
    if (m.segments[s].kind != bearing::SegmentKind::ball_inner_groove) continue;
    const double q = eq.diagnostic(s, normal_force);
    load += q, weighted += q * std::abs(eq.diagnostic(s, contact_angle));
  }
  return load > 0 ? weighted / load : m.nominal_contact_angle;
}

double OutputWriter::rolling_cage_speed(const bearing::Model& m, const bearing::Equations& eq, double t) {
  // Line contacts roll at fixed angles: 0 deg (planar), the raceway cones' (tapered rollers).
  if (m.kind != scene::ModelKind::spatial || m.bearing_type == scene::BearingType::tapered_roller)
    return m.epicyclic_cage_speed(t);
  return m.epicyclic_cage_speed(t, loaded_contact_angle(m, eq));
}

void OutputWriter::append_bodies(double t, const std::vector<double>& z, const std::vector<double>& zdot,
                                 const bearing::Equations& eq) {
  const auto& loads = eq.body_loads();
  auto id = border_ids_.begin();
  for (int bi = 0; bi < m_.first_element; ++bi) {
    const BodySample s = sample_body(m_, bi, t, z, zdot, loads[static_cast<std::size_t>(bi)]);
    for (const BodySeries& series : border_series(m_.kind)) {
      row_.resize(series.components.size());
      put_components(series, s, row_.data());
      file_.append(*id++, row_);
    }
  }
  const double epi = m_.epicyclic_cage_speed(t);
  file_.append(epicyclic_, std::span<const double>(&epi, 1));
  const double rolling = rolling_cage_speed(m_, eq, t);
  file_.append(rolling_, std::span<const double>(&rolling, 1));
  const auto& all = element_series(m_);
  samples_.resize(static_cast<std::size_t>(m_.element_count));
  for (int k = 0; k < m_.element_count; ++k) {
    const int b = m_.first_element + k;
    samples_[static_cast<std::size_t>(k)] = sample_body(m_, b, t, z, zdot, loads[static_cast<std::size_t>(b)]);
  }
  for (std::size_t i = 0; i < all.size(); ++i) {
    row_.resize(samples_.size() * all[i].components.size());
    double* at = row_.data();
    for (const BodySample& s : samples_) at = put_components(all[i], s, at);
    file_.append(element_ids_[i], row_);
  }
}

void OutputWriter::append(double t, const std::vector<double>& z, const std::vector<double>& zdot, const bearing::Equations& eq,
                          double energy, const std::vector<double>& pocket_steps, long sample,
                          const std::vector<int>* segment_rank) {
  file_.append(time_, std::span<const double>(&t, 1));
  file_.append(energy_, std::span<const double>(&energy, 1));
  append_bodies(t, z, zdot, eq);
  std::size_t used = 0;
  for (std::size_t q = 0; q < pocket_step_ids_.size(); ++q, used += pocket_cells_)
    file_.append(pocket_step_ids_[q], std::span<const double>(pocket_steps.data() + used, pocket_cells_));
  for (std::size_t q = 0; q < sensor_ids_.size(); ++q) {
    const std::size_t cells = q == 0 ? sensor_per_ : 2 * sensor_per_;
    file_.append(sensor_ids_[q], std::span<const double>(pocket_steps.data() + used, cells));
    used += cells;
  }
  append_power_balance(file_, power_, pocket_steps.data() + used, eq, t, z.data(), energy);
  thermal_->append(file_, z, eq);
  if (!stores_segments(sample)) return;
  if (segment_every_ > 1) file_.append(segment_time_, std::span<const double>(&t, 1));
  for (int k = 0; k < bearing::segment_kind_count; ++k) {
    const std::vector<int>& index = index_[k];
    row_.resize(index.size());
    if (shared_) {
      mine_.resize(index.size());
      for (std::size_t i = 0; i < index.size(); ++i)
        mine_[i] = segment_rank == nullptr || (*segment_rank)[static_cast<std::size_t>(index[i])] == 0;
    }
    for (std::size_t d = 0; d < diagnostic_ids_[k].size(); ++d) {
      for (std::size_t i = 0; i < index.size(); ++i)
        row_[i] = eq.diagnostic(static_cast<std::size_t>(index[i]), static_cast<int>(d));
      if (shared_)
        file_.append(diagnostic_ids_[k][d], row_, mine_);
      else
        file_.append(diagnostic_ids_[k][d], row_);
    }
  }
}

}  // namespace raceway::run
