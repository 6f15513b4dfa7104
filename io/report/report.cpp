// raceway report: read a spatial run, compute cage metrics, write summary.json and plots
// (see report.hpp; the file layout is docs/output_layout.md).
#include "io/report/report.hpp"

#include <hdf5.h>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <numbers>
#include <span>
#include <utility>

#include <fmt/format.h>

#include "io/report/cage_metrics.hpp"
#include "io/h5/h5_handle.hpp"

extern char** environ;  // NOLINT: POSIX, for posix_spawn

#ifndef RACEWAY_SOURCE_DIR
#define RACEWAY_SOURCE_DIR "."
#endif

namespace raceway::io {

namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kRadToDeg = 180.0 / std::numbers::pi;

// ---- HDF5 reading -------------------------------------------------------------------------------

// HDF5's automatic error printing off while the report reads (restored afterwards).
using ErrorSilencer = h5::QuietErrors;

// The innermost message of the current HDF5 error stack ("" if none).
std::string hdf5_error_text() {
  std::string last;
  auto walk = [](unsigned, const H5E_error2_t* e, void* data) -> herr_t {
    if (e->desc && *e->desc) *static_cast<std::string*>(data) = e->desc;
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, walk, &last);
  return last;
}

using h5::Handle;

struct Array {
  std::vector<std::size_t> dims;
  std::vector<double> data;
  std::size_t rows() const { return dims.empty() ? 1 : dims[0]; }
  std::size_t row_size() const {
    std::size_t n = 1;
    for (std::size_t d = 1; d < dims.size(); ++d) n *= dims[d];
    return n;
  }
};

class Reader {
 public:
  explicit Reader(std::string path) : path_(std::move(path)), file_(open(path_), H5Fclose) {}

  const std::string& path() const { return path_; }

  // True if every component of the absolute path exists as a link.
  bool exists(const std::string& object) const {
    std::string partial;
    std::size_t pos = 1;
    while (pos <= object.size()) {
      const std::size_t next = object.find('/', pos);
      partial = object.substr(0, next);
      if (H5Lexists(file_.get(), partial.c_str(), H5P_DEFAULT) <= 0) return false;
      if (next == std::string::npos) break;
      pos = next + 1;
    }
    return true;
  }

  Array read(const std::string& dataset) const {
    if (!exists(dataset)) throw ReportInputError(fmt::format("report: '{}': dataset '{}' is missing", path_, dataset));
    Handle d(H5Dopen2(file_.get(), dataset.c_str(), H5P_DEFAULT), H5Dclose);
    if (!d.ok()) throw ReportInputError(fmt::format("report: '{}': '{}' is not a readable dataset", path_, dataset));
    Handle space(H5Dget_space(d.get()), H5Sclose);
    const int rank = space.ok() ? H5Sget_simple_extent_ndims(space.get()) : -1;
    if (rank < 0) throw ReportInputError(fmt::format("report: '{}': cannot read the shape of '{}'", path_, dataset));
    std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
    H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
    Array a;
    std::size_t n = 1;
    for (const hsize_t v : dims) a.dims.push_back(static_cast<std::size_t>(v)), n *= static_cast<std::size_t>(v);
    Handle type(H5Dget_type(d.get()), H5Tclose);
    const H5T_class_t cls = type.ok() ? H5Tget_class(type.get()) : H5T_NO_CLASS;
    if (cls != H5T_FLOAT && cls != H5T_INTEGER)
      throw ReportInputError(fmt::format("report: '{}': dataset '{}' is not numeric", path_, dataset));
    a.data.resize(n);
    if (n > 0 && H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, a.data.data()) < 0)
      throw ReportInputError(fmt::format("report: '{}': cannot read dataset '{}'", path_, dataset));
    return a;
  }

  // A root attribute as text (variable- or fixed-length string); nullopt if absent.
  std::optional<std::string> string_attribute(const std::string& name) const {
    if (H5Aexists(file_.get(), name.c_str()) <= 0) return std::nullopt;
    Handle attr(H5Aopen(file_.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
    Handle type(attr.ok() ? H5Aget_type(attr.get()) : -1, H5Tclose);
    if (!type.ok() || H5Tget_class(type.get()) != H5T_STRING)
      throw ReportInputError(fmt::format("report: '{}': root attribute '{}' is not a string", path_, name));
    std::string out;
    if (H5Tis_variable_str(type.get()) > 0) {
      Handle mem(H5Tcopy(H5T_C_S1), H5Tclose);
      H5Tset_size(mem.get(), H5T_VARIABLE);
      H5Tset_cset(mem.get(), H5Tget_cset(type.get()));
      char* s = nullptr;
      if (H5Aread(attr.get(), mem.get(), &s) < 0)
        throw ReportInputError(fmt::format("report: '{}': cannot read root attribute '{}'", path_, name));
      if (s) out = s;
      H5free_memory(s);
    } else {
      const std::size_t size = H5Tget_size(type.get());
      std::string buf(size, '\0');
      if (H5Aread(attr.get(), type.get(), buf.data()) < 0)
        throw ReportInputError(fmt::format("report: '{}': cannot read root attribute '{}'", path_, name));
      out = buf.substr(0, buf.find('\0'));
    }
    return out;
  }

  // A numeric scalar root attribute (integer or float); NaN if absent.
  double number_attribute(const std::string& name) const {
    if (H5Aexists(file_.get(), name.c_str()) <= 0) return kNaN;
    Handle attr(H5Aopen(file_.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
    Handle type(attr.ok() ? H5Aget_type(attr.get()) : -1, H5Tclose);
    Handle space(attr.ok() ? H5Aget_space(attr.get()) : -1, H5Sclose);
    const H5T_class_t cls = type.ok() ? H5Tget_class(type.get()) : H5T_NO_CLASS;
    if ((cls != H5T_FLOAT && cls != H5T_INTEGER) || !space.ok() || H5Sget_simple_extent_npoints(space.get()) != 1)
      throw ReportInputError(fmt::format("report: '{}': root attribute '{}' is not a number", path_, name));
    double v = kNaN;
    if (H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &v) < 0)
      throw ReportInputError(fmt::format("report: '{}': cannot read root attribute '{}'", path_, name));
    return v;
  }

  // Names of the links in a group ({} if the group is missing).
  std::vector<std::string> members(const std::string& group) const {
    std::vector<std::string> names;
    if (!exists(group)) return names;
    auto collect = [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
      static_cast<std::vector<std::string>*>(data)->emplace_back(name);
      return 0;
    };
    hsize_t idx = 0;
    if (H5Literate_by_name(file_.get(), group.c_str(), H5_INDEX_NAME, H5_ITER_INC, &idx, collect, &names,
                           H5P_DEFAULT) < 0)
      throw ReportInputError(fmt::format("report: '{}': cannot list group '{}'", path_, group));
    return names;
  }

 private:
  static hid_t open(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw ReportInputError(fmt::format("report: cannot open '{}': no such file", path));
    if (fs::is_directory(path, ec))
      throw ReportInputError(fmt::format("report: '{}' is a directory, not an HDF5 file", path));
    if (H5Fis_hdf5(path.c_str()) <= 0)
      throw ReportInputError(fmt::format("report: '{}' is not an HDF5 file (or cannot be read)", path));
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) {
      // A file still open for writing is locked by HDF5 1.10; HDF5_USE_FILE_LOCKING=FALSE reads it anyway.
      throw ReportInputError(fmt::format("report: cannot open '{}' read-only: {} (a file that a run is still "
                                         "writing is locked; HDF5_USE_FILE_LOCKING=FALSE reads it anyway)",
                                         path, hdf5_error_text()));
    }
    return f;
  }

  std::string path_;
  Handle file_;
};

// Checks the shape [T x row_shape...] of a time series; returns its row count.
std::size_t check_series(const Reader& r, const std::string& name, const Array& a, std::vector<std::size_t> row_shape) {
  bool ok = a.dims.size() == row_shape.size() + 1;
  for (std::size_t d = 0; ok && d < row_shape.size(); ++d) ok = a.dims[d + 1] == row_shape[d];
  if (!ok) {
    std::string want = "[T";
    for (const auto d : row_shape) want += fmt::format(" x {}", d);
    std::string got = "[";
    for (std::size_t d = 0; d < a.dims.size(); ++d) got += fmt::format("{}{}", d ? " x " : "", a.dims[d]);
    throw ReportInputError(fmt::format("report: '{}': dataset '{}' has shape {}], expected {}]", r.path(), name,
                                       got, want));
  }
  return a.rows();
}

void cut_rows(std::vector<double>& v, std::size_t rows, std::size_t row_size) {
  if (v.size() > rows * row_size) v.resize(rows * row_size);
}

// ---- plotting -------------------------------------------------------------------------------------

bool executable(const std::string& p) { return !p.empty() && access(p.c_str(), X_OK) == 0; }

// Runs argv[0] with argv (no shell) and waits; returns the exit status, -1 if it could not start.
int run_process(const std::vector<std::string>& args, std::string& error) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ);
  if (rc != 0) {
    error = std::strerror(rc);
    return -1;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      error = std::strerror(errno);
      return -1;
    }
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  error = WIFSIGNALED(status) ? fmt::format("killed by signal {}", WTERMSIG(status)) : "ended abnormally";
  return -1;
}

// ---- summary helpers ------------------------------------------------------------------------------

std::vector<double> to_deg(const std::vector<double>& rad) {
  std::vector<double> out(rad.size());
  std::transform(rad.begin(), rad.end(), out.begin(), [](double v) { return v * kRadToDeg; });
  return out;
}

JsonObject contact_json(const ContactStats& c) {
  JsonObject o;
  o.add("rms_n", c.rms)
      .add("peak_n", c.peak)
      .add("impulse_n_s", c.impulse)
      .add("events", c.events)
      .add("contact_time_s", c.contact_time)
      .add("mean_duration_s", c.mean_duration)
      .add("duty_cycle", c.duty_cycle);
  return o;
}

JsonObject per_pocket_json(const std::vector<ContactStats>& v) {
  auto field = [&](auto get) {
    std::vector<double> out;
    for (const auto& c : v) out.push_back(static_cast<double>(get(c)));
    return out;
  };
  JsonObject o;
  o.add("rms_n", field([](const ContactStats& c) { return c.rms; }))
      .add("peak_n", field([](const ContactStats& c) { return c.peak; }))
      .add("impulse_n_s", field([](const ContactStats& c) { return c.impulse; }))
      .add("events", field([](const ContactStats& c) { return c.events; }))
      .add("mean_duration_s", field([](const ContactStats& c) { return c.mean_duration; }))
      .add("duty_cycle", field([](const ContactStats& c) { return c.duty_cycle; }));
  return o;
}

std::vector<double> column(const std::vector<double>& table, std::size_t row_size, std::size_t c) {
  std::vector<double> out(table.size() / row_size);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = table[i * row_size + c];
  return out;
}

}  // namespace

// ---- reading ------------------------------------------------------------------------------------------

SpatialRun read_spatial_run(const std::string& path) {
  const ErrorSilencer quiet;
  const Reader r(path);
  const auto kind = r.string_attribute("model_kind");
  if (!kind || *kind != "spatial") {
    const std::string what = kind ? fmt::format("a '{}' run", *kind) : "a planar run";
    throw ReportInputError(fmt::format("report: {} is {} (root attribute model_kind = {}); `raceway report` reads "
                                       "spatial (ball-bearing) runs only, whose model_kind is \"spatial\" "
                                       "(docs/output_layout.md); a planar run's cage speed and slip are in its "
                                       "summary_json attribute",
                                       path, what, kind ? "\"" + *kind + "\"" : std::string("absent")));
  }
  SpatialRun run;
  run.path = path;
  Array time = r.read("/time");
  if (time.dims.size() == 2 && time.dims[1] == 1) time.dims.pop_back();
  std::size_t rows = check_series(r, "/time", time, {});
  run.time = std::move(time.data);

  auto series = [&](const std::string& name, std::vector<std::size_t> row_shape) {
    Array a = r.read(name);
    if (row_shape.empty() && a.dims.size() == 2 && a.dims[1] == 1) a.dims.pop_back();  // [T x 1] as [T]
    rows = std::min(rows, check_series(r, name, a, std::move(row_shape)));
    return a;
  };
  const Array balls = r.read("/balls/position");
  if (balls.dims.size() != 3 || balls.dims[2] != 3 || balls.dims[1] == 0)
    throw ReportInputError(fmt::format("report: '{}': dataset '/balls/position' is not [T x n x 3]", path));
  run.balls = balls.dims[1];
  rows = std::min(rows, balls.rows());
  run.ball_position = balls.data;
  run.cage_position = series("/cage/position", {3}).data;
  run.cage_velocity = series("/cage/velocity", {3}).data;
  run.cage_angular_velocity = series("/cage/angular_velocity", {3}).data;
  run.epicyclic_speed = series("/cage/epicyclic_speed", {}).data;
  if (r.exists("/cage/rolling_speed")) run.rolling_speed = series("/cage/rolling_speed", {}).data;  // newer files

  for (const auto& kind_name : r.members("/segments")) {
    const std::string g = "/segments/" + kind_name;
    // Only the kinds and diagnostics the report uses.
    std::vector<std::string> wanted;
    if (kind_name == "ball_inner_groove") wanted = {"normal_force"};
    if (kind_name == "ball_pocket") wanted = {"normal_force", "circumferential_force"};
    if (r.exists(g + "/power_loss")) wanted.emplace_back("power_loss");
    if (wanted.empty()) continue;
    SegmentColumns cols;
    const Array ball = r.read(g + "/ball");
    if (ball.dims.size() != 1)
      throw ReportInputError(fmt::format("report: '{}': dataset '{}/ball' is not one-dimensional", path, g));
    if (ball.data.empty()) {
      run.notes.push_back(fmt::format("{} has no columns: skipped", g));
      continue;
    }
    for (const double b : ball.data) {
      if (!(b >= -1) || b != std::floor(b) || b >= static_cast<double>(run.balls))
        throw ReportInputError(fmt::format("report: '{}': dataset '{}/ball' holds {} (not a ball index in [-1, {}))",
                                           path, g, b, run.balls));
      cols.ball.push_back(static_cast<int>(b));
    }
    for (const auto& d : wanted) {
      const std::string name = g + "/" + d;
      cols.diagnostic[d] = series(name, {cols.columns()}).data;
    }
    run.segments[kind_name] = std::move(cols);
  }
  if (!run.segments.contains("ball_pocket"))
    run.notes.emplace_back("no ball_pocket segment diagnostics in the file: pocket forces skipped");
  if (!run.segments.contains("ball_inner_groove"))
    run.notes.emplace_back("no ball_inner_groove segment diagnostics in the file: ball loads skipped");

  if (rows < run.time.size())
    run.notes.emplace_back(fmt::format("series of unequal length (a partial file?): {} of {} output times used", rows,
                                       run.time.size()));
  cut_rows(run.time, rows, 1);
  cut_rows(run.ball_position, rows, run.balls * 3);
  cut_rows(run.cage_position, rows, 3);
  cut_rows(run.cage_velocity, rows, 3);
  cut_rows(run.cage_angular_velocity, rows, 3);
  cut_rows(run.epicyclic_speed, rows, 1);
  if (!run.rolling_speed.empty()) cut_rows(run.rolling_speed, rows, 1);
  for (auto& [k, cols] : run.segments)
    for (auto& [d, v] : cols.diagnostic) cut_rows(v, rows, cols.columns());

  run.pitch_radius = r.number_attribute("pitch_radius");
  run.pocket_clearance = r.number_attribute("pocket_clearance");
  run.land_clearance = r.number_attribute("land_clearance");
  return run;
}

// ---- metrics ------------------------------------------------------------------------------------------

JsonObject summarize_spatial_run(const SpatialRun& run, const ReportOptions& options,
                                 std::vector<std::string>* headlines) {
  std::vector<std::string> lines;
  if (!(options.bin_width_deg > 0 && options.bin_width_deg <= 360))
    throw std::invalid_argument(fmt::format("report: --bin-width {} deg is not in (0, 360]", options.bin_width_deg));
  const auto& t = run.time;
  const std::size_t n = run.balls;
  const TimeWindow w = select_window(t, options.window_start);

  JsonObject sum;
  sum.add("report_format", 1LL).add("input", run.path).add("model_kind", "spatial").add("ball_count", n);
  JsonObject win;
  win.add("start_s", w.t_begin).add("end_s", w.t_end).add("samples", w.samples());
  win.add("default_second_half", !options.window_start.has_value());
  sum.add("window", std::move(win));

  // Cage speed about the bearing axis (z component).
  const std::vector<double> omega_z = column(run.cage_angular_velocity, 3, 2);
  const CageSpeedStats cs = cage_speed_stats(t, omega_z, run.epicyclic_speed, w);
  const int direction = cage_direction(cs.cage_speed);
  JsonObject speed;
  speed.add("mean_rad_s", cs.cage_speed)
      .add("mean_rpm", cs.cage_speed_rpm)
      .add("min_rad_s", cs.cage_speed_min)
      .add("max_rad_s", cs.cage_speed_max)
      .add("epicyclic_rad_s", cs.epicyclic_speed)
      .add("epicyclic_rpm", cs.epicyclic_speed_rpm)
      .add("slip", cs.slip)
      .add("direction", direction);
  std::string rolling_line;
  if (!run.rolling_speed.empty()) {
    // Against the kinematic speed at the angle the balls actually roll at (under axial load a deep
    // groove bearing runs at 10-15 deg, not its nominal 0).
    const CageSpeedStats rs = cage_speed_stats(t, omega_z, run.rolling_speed, w);
    speed.add("rolling_rad_s", rs.epicyclic_speed).add("rolling_rpm", rs.epicyclic_speed_rpm).add("slip_rolling", rs.slip);
    rolling_line = fmt::format("kinematic cage speed at the loaded contact angle {:.2f} rpm: slip {:.3f} %",
                               rs.epicyclic_speed_rpm, 100 * rs.slip);
  }
  sum.add("cage_speed", std::move(speed));
  lines.push_back(fmt::format("window {:.6g} .. {:.6g} s ({} samples): cage {:.2f} rpm, epicyclic {:.2f} rpm, "
                              "slip {:.3f} %",
                              w.t_begin, w.t_end, w.samples(), cs.cage_speed_rpm, cs.epicyclic_speed_rpm,
                              100 * cs.slip));
  if (!rolling_line.empty()) lines.push_back(rolling_line);

  // Centroid trajectory.
  const CentroidMetrics cm =
      centroid_metrics(t, column(run.cage_position, 3, 0), column(run.cage_position, 3, 1),
                       column(run.cage_velocity, 3, 0), column(run.cage_velocity, 3, 1), w, cs.cage_speed);
  JsonObject cen;
  cen.add("centre_x_m", cm.centre_x)
      .add("centre_y_m", cm.centre_y)
      .add("vortex_radius_mean_m", cm.radius_mean)
      .add("vortex_radius_min_m", cm.radius_min)
      .add("vortex_radius_max_m", cm.radius_max)
      .add("vortex_radius_ratio", cm.radius_ratio)
      .add("axis_radius_mean_m", cm.axis_radius_mean)
      .add("axis_radius_min_m", cm.axis_radius_min)
      .add("axis_radius_max_m", cm.axis_radius_max)
      .add("axis_radius_ratio", cm.axis_radius_ratio)
      .add("speed_mean_m_s", cm.speed_mean)
      .add("speed_std_m_s", cm.speed_std)
      .add("sigma_v", cm.sigma_v)
      .add("whirl_frequency_rad_s", cm.whirl_frequency)
      .add("whirl_frequency_hz", cm.whirl_frequency_hz)
      .add("whirl_to_cage_speed_ratio", cm.whirl_to_cage_ratio)
      .add("whirl_revolutions", cm.revolutions)
      .add("land_clearance_m", run.land_clearance)
      .add("pocket_clearance_m", run.pocket_clearance)
      .add("pitch_radius_m", run.pitch_radius);
  sum.add("cage_centroid", std::move(cen));
  lines.push_back(fmt::format("cage centroid: vortex radius {:.3g} um (ratio {:.3f}), sigma_v {:.3f}, whirl {:.3g} "
                              "rad/s = {:.3f} x cage speed",
                              1e6 * cm.radius_mean, cm.radius_ratio, cm.sigma_v, cm.whirl_frequency,
                              cm.whirl_to_cage_ratio));

  const double bin_width = options.bin_width_deg / kRadToDeg;
  JsonObject az;
  az.add("bin_width_deg", options.bin_width_deg);
  bool az_centres = false;
  auto add_bins = [&](const std::string& prefix, const AzimuthBins& b) {
    if (!az_centres) az.add("bin_centre_deg", to_deg(b.centre)), az_centres = true;
    az.add(prefix + "_mean_n", b.mean).add(prefix + "_max_n", b.max);
  };
  // Azimuth of ball k at sample i.
  auto ball_azimuth = [&](std::size_t i, std::size_t k) {
    const double* p = run.ball_position.data() + (i * n + k) * 3;
    return azimuth(p[0], p[1]);
  };

  // Pocket (bar) forces.
  if (const auto it = run.segments.find("ball_pocket"); it != run.segments.end()) {
    const SegmentColumns& pc = it->second;
    for (const int b : pc.ball)
      if (b < 0) throw ReportInputError(fmt::format("report: '{}': '/segments/ball_pocket/ball' holds -1", run.path));
    const auto& fn = pc.diagnostic.at("normal_force");
    const auto& fc = pc.diagnostic.at("circumferential_force");
    const BarForces bars = split_bar_forces(fn, fc, pc.ball, n, direction);
    const PocketForceSummary ps = pocket_force_summary(t, bars, fc, pc.ball, w, options.contact_threshold);
    JsonObject pf;
    pf.add("threshold_n", ps.threshold)
        .add("direction", direction)
        .add("rear_impulse_fraction", ps.rear_impulse_fraction)
        .add("rms_circumferential_force_n", ps.rms_circumferential_force)
        .add("mean_net_circumferential_force_n", ps.mean_net_circumferential_force)
        .add("front", contact_json(ps.front_total))
        .add("rear", contact_json(ps.rear_total))
        .add("front_per_pocket", per_pocket_json(ps.front))
        .add("rear_per_pocket", per_pocket_json(ps.rear));
    sum.add("pocket_forces", std::move(pf));
    lines.push_back(fmt::format("pocket forces (threshold {:.3g} N): front {} contacts, peak {:.3g} N; rear {} "
                                "contacts, peak {:.3g} N; rear impulse fraction {:.3f}",
                                ps.threshold, ps.front_total.events, ps.front_total.peak, ps.rear_total.events,
                                ps.rear_total.peak, ps.rear_impulse_fraction));

    std::vector<double> azs, front, rear;
    for (std::size_t i = w.begin; i < w.end; ++i)
      for (std::size_t k = 0; k < n; ++k) {
        azs.push_back(ball_azimuth(i, k));
        front.push_back(bars.front[k][i]);
        rear.push_back(bars.rear[k][i]);
      }
    add_bins("front_force", bin_by_azimuth(azs, front, bin_width));
    add_bins("rear_force", bin_by_azimuth(azs, rear, bin_width));
  }

  // Ball loads in the inner groove (all arcs of a ball added).
  if (const auto it = run.segments.find("ball_inner_groove"); it != run.segments.end()) {
    const SegmentColumns& gc = it->second;
    for (const int b : gc.ball)
      if (b < 0)
        throw ReportInputError(fmt::format("report: '{}': '/segments/ball_inner_groove/ball' holds -1", run.path));
    const std::vector<double> load = ball_loads(gc.diagnostic.at("normal_force"), gc.ball, n);
    std::vector<double> azs, values;
    double qmax = -1, q_az = kNaN, q_t = kNaN;
    long long q_ball = -1;
    for (std::size_t i = w.begin; i < w.end; ++i)
      for (std::size_t k = 0; k < n; ++k) {
        const double q = load[i * n + k];
        azs.push_back(ball_azimuth(i, k));
        values.push_back(q);
        if (q > qmax) qmax = q, q_az = azs.back(), q_t = t[i], q_ball = static_cast<long long>(k);
      }
    const AzimuthBins bins = bin_by_azimuth(azs, values, bin_width);
    add_bins("ball_load", bins);
    double bin_peak = 0;
    for (const double m : bins.mean)
      if (std::isfinite(m)) bin_peak = std::max(bin_peak, m);
    const double zone_threshold = std::max(0.01 * bin_peak, 1e-3);
    const LoadZone z = load_zone(bins, zone_threshold);
    JsonObject bl;
    bl.add("max_n", qmax)
        .add("max_azimuth_deg", q_az * kRadToDeg)
        .add("max_time_s", q_t)
        .add("max_ball", q_ball)
        .add("max_bin_mean_n", bin_peak)
        .add("load_zone_threshold_n", zone_threshold)
        .add("load_zone_start_deg", z.start * kRadToDeg)
        .add("load_zone_end_deg", z.end * kRadToDeg)
        .add("load_zone_width_deg", z.width * kRadToDeg)
        .add("load_zone_centre_deg", z.centre * kRadToDeg);
    sum.add("ball_load", std::move(bl));
    lines.push_back(fmt::format("inner-groove ball load: max {:.4g} N at {:.1f} deg; load zone {:.0f} deg wide "
                                "centred at {:.0f} deg",
                                qmax, q_az * kRadToDeg, z.width * kRadToDeg, z.centre * kRadToDeg));
  }
  if (az_centres) sum.add("azimuth", std::move(az));

  // Power loss: time mean over the window of each kind's sum over its segments.
  JsonObject pl;
  double total = 0;
  const std::vector<double> wts = trapezoid_weights(t, w);
  for (const auto& [kind, cols] : run.segments) {
    const auto d = cols.diagnostic.find("power_loss");
    if (d == cols.diagnostic.end() || cols.columns() == 0) continue;
    double e = 0;
    for (std::size_t i = w.begin; i < w.end; ++i) {
      double row = 0;
      for (std::size_t c = 0; c < cols.columns(); ++c) row += d->second[i * cols.columns() + c];
      e += wts[i - w.begin] * row;
    }
    pl.add(kind + "_mean_w", e / w.length());
    total += e / w.length();
  }
  if (!pl.empty()) {
    pl.add("total_mean_w", total);
    sum.add("power_loss", std::move(pl));
    lines.push_back(fmt::format("power loss: {:.4g} W (window mean)", total));
  }
  if (headlines) *headlines = std::move(lines);
  return sum;
}

// ---- the report ---------------------------------------------------------------------------------------

std::string plot_script_path() {
  if (const char* env = std::getenv("RACEWAY_PLOT_SCRIPT"); env && *env) return env;
  return std::string(RACEWAY_SOURCE_DIR) + "/io/report/plot_report.py";
}

ReportResult make_report(const ReportOptions& options) {
  const SpatialRun run = read_spatial_run(options.input);
  ReportResult res;
  res.notes = run.notes;
  res.summary = summarize_spatial_run(run, options, &res.headlines);
  if (!res.notes.empty()) {
    std::string all;
    for (const auto& note : res.notes) all += (all.empty() ? "" : "; ") + note;
    res.summary.add("notes", all);
  }

  fs::path dir = options.output_dir;
  if (dir.empty()) {
    const fs::path in(options.input);
    dir = in.parent_path() / (in.stem().string() + "_report");
  }
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error(fmt::format("report: cannot create folder '{}': {}", dir.string(), ec.message()));
  res.output_dir = dir.string();
  res.summary_path = (dir / "summary.json").string();
  write_json_file(res.summary_path, res.summary);

  if (!options.plots) {
    res.plot_message = "plots skipped (--no-plots)";
    return res;
  }
  const char* py_env = std::getenv("RACEWAY_PYTHON");
  const std::string python = py_env && *py_env ? py_env : "/usr/bin/python3";
  const std::string script = plot_script_path();
  const std::string install =
      "install python3, python3-matplotlib, python3-h5py and python3-numpy (scripts/bootstrap.sh)";
  if (!executable(python)) {
    res.plot_message = fmt::format("plots skipped: no python interpreter at {}; {}", python, install);
    return res;
  }
  if (!fs::is_regular_file(script, ec)) {
    res.plot_message = fmt::format("plots skipped: plotting script {} not found (set RACEWAY_PLOT_SCRIPT)", script);
    return res;
  }
  // Remove stale plots so that the list below holds only what this run drew.
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.path().extension() == ".png") fs::remove(entry.path(), ec);
  std::string error;
  const int status = run_process({python, script, options.input, res.summary_path, res.output_dir}, error);
  if (status == 3) {
    res.plot_message = fmt::format("plots skipped: {} lacks matplotlib, h5py or numpy; {}", python, install);
  } else if (status != 0) {
    res.plot_message = status < 0 ? fmt::format("plots failed: cannot run {} {}: {}", python, script, error)
                                  : fmt::format("plots failed: {} {} exited with code {}", python, script, status);
  }
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.path().extension() == ".png") res.plots.push_back(entry.path().string());
  std::sort(res.plots.begin(), res.plots.end());
  if (status == 0 && res.plots.empty()) res.plot_message = "plots failed: the plotting script wrote no PNG";
  return res;
}

}  // namespace raceway::io
