// raceway report: reading a spatial run's output file (read_spatial_run of report.hpp; the file
// layout is docs/output_layout.md, "Spatial (ball-bearing) runs").
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "io/h5/h5_handle.hpp"
#include "io/report/report.hpp"

namespace raceway::io {

namespace {

namespace fs = std::filesystem;
using h5::Handle;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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

struct Array {
  std::vector<std::size_t> dims;
  std::vector<double> data;
  std::size_t rows() const { return dims.empty() ? 1 : dims[0]; }
};

// The report's read-only view of one HDF5 file; every failure is a ReportInputError naming the
// file and the object.
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
    if (!exists(dataset)) throw error("dataset '{}' is missing", dataset);
    Handle d(H5Dopen2(file_.get(), dataset.c_str(), H5P_DEFAULT), H5Dclose);
    if (!d.ok()) throw error("'{}' is not a readable dataset", dataset);
    Handle space(H5Dget_space(d.get()), H5Sclose);
    const int rank = space.ok() ? H5Sget_simple_extent_ndims(space.get()) : -1;
    if (rank < 0) throw error("cannot read the shape of '{}'", dataset);
    std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
    H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
    Array a;
    std::size_t n = 1;
    for (const hsize_t v : dims) a.dims.push_back(static_cast<std::size_t>(v)), n *= static_cast<std::size_t>(v);
    Handle type(H5Dget_type(d.get()), H5Tclose);
    const H5T_class_t cls = type.ok() ? H5Tget_class(type.get()) : H5T_NO_CLASS;
    if (cls != H5T_FLOAT && cls != H5T_INTEGER) throw error("dataset '{}' is not numeric", dataset);
    a.data.resize(n);
    if (n > 0 && H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, a.data.data()) < 0)
      throw error("cannot read dataset '{}'", dataset);
    return a;
  }

  // A root attribute as text (variable- or fixed-length string); nullopt if absent.
  std::optional<std::string> string_attribute(const std::string& name) const {
    if (H5Aexists(file_.get(), name.c_str()) <= 0) return std::nullopt;
    Handle attr(H5Aopen(file_.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
    Handle type(attr.ok() ? H5Aget_type(attr.get()) : -1, H5Tclose);
    if (!type.ok() || H5Tget_class(type.get()) != H5T_STRING) throw error("root attribute '{}' is not a string", name);
    std::string out;
    if (H5Tis_variable_str(type.get()) > 0) {
      Handle mem(H5Tcopy(H5T_C_S1), H5Tclose);
      H5Tset_size(mem.get(), H5T_VARIABLE);
      H5Tset_cset(mem.get(), H5Tget_cset(type.get()));
      char* s = nullptr;
      if (H5Aread(attr.get(), mem.get(), &s) < 0) throw error("cannot read root attribute '{}'", name);
      if (s) out = s;
      H5free_memory(s);
    } else {
      const std::size_t size = H5Tget_size(type.get());
      std::string buf(size, '\0');
      if (H5Aread(attr.get(), type.get(), buf.data()) < 0) throw error("cannot read root attribute '{}'", name);
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
      throw error("root attribute '{}' is not a number", name);
    double v = kNaN;
    if (H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &v) < 0) throw error("cannot read root attribute '{}'", name);
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
      throw error("cannot list group '{}'", group);
    return names;
  }

  // "report: '<file>': <what>" as a ReportInputError.
  template <typename... Args>
  ReportInputError error(fmt::format_string<Args...> what, Args&&... args) const {
    return ReportInputError(fmt::format("report: '{}': {}", path_, fmt::format(what, std::forward<Args>(args)...)));
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
    throw r.error("dataset '{}' has shape {}], expected {}]", name, got, want);
  }
  return a.rows();
}

void cut_rows(std::vector<double>& v, std::size_t rows, std::size_t row_size) {
  if (v.size() > rows * row_size) v.resize(rows * row_size);
}

// The time series of a run, read with their shapes checked; rows() is the shortest length so far.
class SeriesReader {
 public:
  explicit SeriesReader(const Reader& r) : r_(r) {
    Array time = r.read("/time");
    if (time.dims.size() == 2 && time.dims[1] == 1) time.dims.pop_back();
    rows_ = check_series(r, "/time", time, {});
    time_ = std::move(time.data);
  }

  std::vector<double> read(const std::string& name, std::vector<std::size_t> row_shape) {
    Array a = r_.read(name);
    if (row_shape.empty() && a.dims.size() == 2 && a.dims[1] == 1) a.dims.pop_back();  // [T x 1] as [T]
    rows_ = std::min(rows_, check_series(r_, name, a, std::move(row_shape)));
    return std::move(a.data);
  }

  // /balls/position [T x n x 3]; n goes to `balls`.
  std::vector<double> ball_positions(std::size_t& balls) {
    Array a = r_.read("/balls/position");
    if (a.dims.size() != 3 || a.dims[2] != 3 || a.dims[1] == 0)
      throw r_.error("dataset '/balls/position' is not [T x n x 3]");
    balls = a.dims[1];
    rows_ = std::min(rows_, a.rows());
    return std::move(a.data);
  }

  std::vector<double>& time() { return time_; }
  std::size_t rows() const { return rows_; }

 private:
  const Reader& r_;
  std::vector<double> time_;
  std::size_t rows_ = 0;
};

// The root attribute model_kind must say "spatial".
void require_spatial(const Reader& r) {
  const auto kind = r.string_attribute("model_kind");
  if (kind && *kind == "spatial") return;
  const std::string what = kind ? fmt::format("a '{}' run", *kind) : "a planar run";
  throw ReportInputError(fmt::format("report: {} is {} (root attribute model_kind = {}); `raceway report` reads "
                                     "spatial (ball-bearing) runs only, whose model_kind is \"spatial\" "
                                     "(docs/output_layout.md); a planar run's cage speed and slip are in its "
                                     "summary_json attribute",
                                     r.path(), what, kind ? "\"" + *kind + "\"" : std::string("absent")));
}

// The ball index of each column of segment group g (-1: no ball), checked against the ball count.
std::vector<int> segment_balls(const Reader& r, const std::string& g, std::size_t balls) {
  const Array ball = r.read(g + "/ball");
  if (ball.dims.size() != 1) throw r.error("dataset '{}/ball' is not one-dimensional", g);
  std::vector<int> out;
  for (const double b : ball.data) {
    if (!(b >= -1) || b != std::floor(b) || b >= static_cast<double>(balls))
      throw r.error("dataset '{}/ball' holds {} (not a ball index in [-1, {}))", g, b, balls);
    out.push_back(static_cast<int>(b));
  }
  return out;
}

// The segment kinds and diagnostics the report uses: pocket and inner-groove forces, power loss.
void read_segments(const Reader& r, SeriesReader& series, SpatialRun& run) {
  for (const auto& kind_name : r.members("/segments")) {
    const std::string g = "/segments/" + kind_name;
    std::vector<std::string> wanted;
    if (kind_name == "ball_inner_groove") wanted = {"normal_force"};
    if (kind_name == "ball_pocket") wanted = {"normal_force", "circumferential_force"};
    if (r.exists(g + "/power_loss")) wanted.emplace_back("power_loss");
    if (wanted.empty()) continue;
    SegmentColumns cols;
    cols.ball = segment_balls(r, g, run.balls);
    if (cols.ball.empty()) {
      run.notes.push_back(fmt::format("{} has no columns: skipped", g));
      continue;
    }
    for (const auto& d : wanted) cols.diagnostic[d] = series.read(g + "/" + d, {cols.columns()});
    run.segments[kind_name] = std::move(cols);
  }
  if (!run.segments.contains("ball_pocket"))
    run.notes.emplace_back("no ball_pocket segment diagnostics in the file: pocket forces skipped");
  if (!run.segments.contains("ball_inner_groove"))
    run.notes.emplace_back("no ball_inner_groove segment diagnostics in the file: ball loads skipped");
}

// Every series cut to the common length `rows` (a .partial file may have some one row longer).
void cut_to_rows(SpatialRun& run, std::size_t rows) {
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
}

}  // namespace

SpatialRun read_spatial_run(const std::string& path) {
  const h5::QuietErrors quiet;
  const Reader r(path);
  require_spatial(r);
  SpatialRun run;
  run.path = path;
  SeriesReader series(r);
  run.ball_position = series.ball_positions(run.balls);
  run.cage_position = series.read("/cage/position", {3});
  run.cage_velocity = series.read("/cage/velocity", {3});
  run.cage_angular_velocity = series.read("/cage/angular_velocity", {3});
  run.epicyclic_speed = series.read("/cage/epicyclic_speed", {});
  if (r.exists("/cage/rolling_speed")) run.rolling_speed = series.read("/cage/rolling_speed", {});  // newer files
  read_segments(r, series, run);
  run.time = std::move(series.time());
  cut_to_rows(run, series.rows());
  run.pitch_radius = r.number_attribute("pitch_radius");
  run.pocket_clearance = r.number_attribute("pocket_clearance");
  run.land_clearance = r.number_attribute("land_clearance");
  return run;
}

}  // namespace raceway::io
