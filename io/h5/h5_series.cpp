// raceway HDF5 series writer (see h5_series.hpp for the contract, docs/output_layout.md for the
// file conventions).
#include "io/h5/h5_series.hpp"

#include <hdf5.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <type_traits>

#include <fmt/format.h>

#include "io/h5/h5_handle.hpp"

namespace raceway::io {

static_assert(std::is_same_v<hid_t, std::int64_t>, "raceway needs HDF5 >= 1.10 (64-bit hid_t)");
static_assert(std::is_same_v<hsize_t, unsigned long long>, "unexpected hsize_t");

namespace {

constexpr std::size_t kChunkTargetBytes = 64 * 1024;

// The first (API-level) and the last (innermost) message of the current HDF5 error stack.
std::string hdf5_error_text() {
  struct Collected {
    std::string first, last;
    unsigned count = 0;
  } c;
  auto walk = [](unsigned, const H5E_error2_t* e, void* data) -> herr_t {
    auto* col = static_cast<Collected*>(data);
    std::string msg = fmt::format("{}(): {}", e->func_name ? e->func_name : "?", e->desc ? e->desc : "");
    if (col->count++ == 0) col->first = msg;
    col->last = std::move(msg);
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, walk, &c);
  if (c.count == 0) return "no HDF5 error message";
  if (c.count == 1) return c.first;
  return c.first + " <- " + c.last;
}

// The error stack of the first failed HDF5 call of the current writer operation. Helpers save it
// (failed()) before their cleanup calls (H5?close) clear the stack; fail() reports it.
thread_local std::string t_saved_error;

bool failed() {
  if (t_saved_error.empty()) t_saved_error = hdf5_error_text();
  return false;
}

hid_t failed_id() {
  failed();
  return -1;
}

// HDF5's error printing off for a writer operation, which starts with no saved error.
class ErrorSilencer : public h5::QuietErrors {
 public:
  ErrorSilencer() { t_saved_error.clear(); }
};

using h5::Handle;

// "/a//b/" -> {"a", "b"}
std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  std::size_t pos = 0;
  while (pos <= path.size()) {
    const std::size_t next = std::min(path.find('/', pos), path.size());
    if (next > pos) parts.push_back(path.substr(pos, next - pos));
    pos = next + 1;
  }
  return parts;
}

std::string join_path(const std::vector<std::string>& parts, std::size_t count) {
  std::string out;
  for (std::size_t i = 0; i < count; ++i) out += "/" + parts[i];
  return out.empty() ? "/" : out;
}

std::string normalize(const std::string& path) {
  const auto parts = split_path(path);
  return join_path(parts, parts.size());
}

// Variable-length UTF-8 string type: h5py reads attributes of this type as str.
hid_t make_vlen_string_type() {
  const hid_t t = H5Tcopy(H5T_C_S1);
  if (t < 0) return failed_id();
  if (H5Tset_size(t, H5T_VARIABLE) < 0 || H5Tset_cset(t, H5T_CSET_UTF8) < 0) {
    failed();
    H5Tclose(t);
    return -1;
  }
  return t;
}

hid_t make_dataspace(const std::vector<hsize_t>& dims, const std::vector<hsize_t>* max_dims = nullptr) {
  if (dims.empty()) return H5Screate(H5S_SCALAR);
  return H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max_dims ? max_dims->data() : nullptr);
}

// Durability before the rename: without it a power loss could leave final_path pointing at an
// incompletely written file. Best effort (a failure here does not make the data wrong).
void fsync_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return;
  (void)::fsync(fd);
  (void)::close(fd);
}

// Pointers to the strings' characters, for HDF5's variable-length string writes (valid while
// `values` lives).
std::vector<const char*> c_strings(const std::vector<std::string>& values) {
  std::vector<const char*> ptrs;
  ptrs.reserve(values.size());
  for (const auto& v : values) ptrs.push_back(v.c_str());
  return ptrs;
}

std::size_t product(const std::vector<std::size_t>& shape) {
  std::size_t n = 1;
  for (const std::size_t d : shape) n *= d;
  return n;
}

}  // namespace

// ---- the one place where the file access property list is made ----
// Now: the default sec2 driver. Later (parallel output): H5Pset_fapl_mpio(fapl, comm, info) here,
// and H5Pset_dxpl_mpio(dxpl_, H5FD_MPIO_COLLECTIVE) where dxpl_ is made in create().
// The library version bounds are left at the default (earliest), so any HDF5 >= 1.8 reader and
// h5py can read the files.
static hid_t make_file_access_plist() {
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl < 0) return fapl;
  if (H5Pset_fapl_sec2(fapl) < 0) {
    failed();
    H5Pclose(fapl);
    return -1;
  }
  return fapl;
}

H5SeriesWriter::H5SeriesWriter(std::string final_path)
    : final_path_(std::move(final_path)), partial_path_(final_path_ + ".partial") {}

H5SeriesWriter H5SeriesWriter::create(const std::string& final_path) {
  ErrorSilencer quiet;
  H5SeriesWriter w(final_path);
  const Handle fapl(make_file_access_plist(), H5Pclose);
  if (!fapl.ok()) w.fail("making the file access property list", "/");
  w.file_ = H5Fcreate(w.partial_path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  if (w.file_ < 0) w.fail("H5Fcreate", "/");
  w.dxpl_ = H5Pcreate(H5P_DATASET_XFER);  // collective transfer mode goes here later
  if (w.dxpl_ < 0) w.fail("making the data transfer property list", "/");
  return w;
}

H5SeriesWriter::H5SeriesWriter(H5SeriesWriter&& other) noexcept
    : final_path_(std::move(other.final_path_)),
      partial_path_(std::move(other.partial_path_)),
      file_(std::exchange(other.file_, -1)),
      dxpl_(std::exchange(other.dxpl_, -1)),
      series_(std::move(other.series_)) {
  other.series_.clear();
}

H5SeriesWriter& H5SeriesWriter::operator=(H5SeriesWriter&& other) noexcept {
  if (this != &other) {
    close_uncommitted();  // as if destroyed: our .partial file stays
    final_path_ = std::move(other.final_path_);
    partial_path_ = std::move(other.partial_path_);
    file_ = std::exchange(other.file_, -1);
    dxpl_ = std::exchange(other.dxpl_, -1);
    series_ = std::move(other.series_);
    other.series_.clear();
  }
  return *this;
}

H5SeriesWriter::~H5SeriesWriter() { close_uncommitted(); }

void H5SeriesWriter::close_uncommitted() noexcept {
  if (!is_open()) return;
  ErrorSilencer quiet;
  try {
    write_all_buffers();
    H5Fflush(file_, H5F_SCOPE_LOCAL);
  } catch (...) {
    // Destructors must not throw; the .partial file keeps what was written.
  }
  close_all();
}

void H5SeriesWriter::require_open(const char* what) const {
  if (!is_open()) {
    throw std::logic_error(fmt::format("H5SeriesWriter::{}: the writer for '{}' is closed (committed or moved from)",
                                       what, final_path_));
  }
}

void H5SeriesWriter::fail(const std::string& what, const std::string& object) const {
  throw std::runtime_error(fmt::format("H5SeriesWriter: {} failed for '{}' in file '{}': {}", what, object,
                                       partial_path_, t_saved_error.empty() ? hdf5_error_text() : t_saved_error));
}

namespace {

// Creates the groups parts[0..count) that do not exist yet (no timestamps: reproducible files).
// Returns false (with the HDF5 error stack set) on failure.
bool ensure_groups(hid_t file, const std::vector<std::string>& parts, std::size_t count) {
  const Handle gcpl(H5Pcreate(H5P_GROUP_CREATE), H5Pclose);
  if (!gcpl.ok() || H5Pset_obj_track_times(gcpl.get(), false) < 0) return failed();
  for (std::size_t i = 1; i <= count; ++i) {
    const std::string prefix = join_path(parts, i);
    const htri_t exists = H5Lexists(file, prefix.c_str(), H5P_DEFAULT);
    if (exists < 0) return failed();
    if (exists == 0) {
      const Handle g(H5Gcreate2(file, prefix.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT), H5Gclose);
      if (!g.ok()) return failed();
    }
  }
  return true;
}

// Replaces attribute `name` on obj: created with file_type, written from buf of mem_type
// (buf == nullptr: zero elements, nothing to write).
bool write_attribute(hid_t obj, const std::string& name, hid_t file_type, hid_t mem_type, hid_t space,
                     const void* buf) {
  const htri_t exists = H5Aexists(obj, name.c_str());
  if (exists < 0) return failed();
  if (exists > 0 && H5Adelete(obj, name.c_str()) < 0) return failed();
  const Handle attr(H5Acreate2(obj, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!attr.ok()) return failed();
  return buf == nullptr || H5Awrite(attr.get(), mem_type, buf) >= 0 || failed();
}

bool write_string_attribute(hid_t obj, const std::string& name, const std::string& value) {
  const Handle type(make_vlen_string_type(), H5Tclose);
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  if (!type.ok() || !space.ok()) return failed();
  const char* p = value.c_str();
  return write_attribute(obj, name, type.get(), type.get(), space.get(), &p);
}

bool write_units_description(hid_t obj, const std::string& units, const std::string& description) {
  return write_string_attribute(obj, "units", units) && write_string_attribute(obj, "description", description);
}

// A dataset creation property list without timestamps (reproducible files).
hid_t make_dcpl() {
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  if (dcpl >= 0 && H5Pset_obj_track_times(dcpl, false) < 0) {
    failed();
    H5Pclose(dcpl);
    return -1;
  }
  return dcpl;
}

}  // namespace

void H5SeriesWriter::define_series(const std::string& path, std::vector<std::size_t> row_shape,
                                   const std::string& units, const std::string& description) {
  require_open("define_series");
  ErrorSilencer quiet;
  const auto parts = split_path(path);
  const std::string key = join_path(parts, parts.size());
  if (parts.empty()) throw std::invalid_argument("H5SeriesWriter::define_series: empty dataset path");
  if (series_.contains(key)) {
    throw std::invalid_argument(fmt::format("H5SeriesWriter::define_series: series '{}' already defined in '{}'",
                                            key, partial_path_));
  }
  if (std::find(row_shape.begin(), row_shape.end(), std::size_t{0}) != row_shape.end()) {
    throw std::invalid_argument(fmt::format("H5SeriesWriter::define_series: series '{}' has a zero row dimension", key));
  }

  Series s;
  s.row_shape.assign(row_shape.begin(), row_shape.end());
  s.row_size = product(row_shape);

  // Chunk of about kChunkTargetBytes: fill the trailing (row) dimensions first, whole rows if they
  // fit, then as many rows as the remaining budget allows.
  std::size_t budget = std::max<std::size_t>(1, kChunkTargetBytes / sizeof(double));
  std::vector<hsize_t> chunk(row_shape.size() + 1);
  for (std::size_t d = row_shape.size(); d-- > 0;) {
    chunk[d + 1] = std::min<std::size_t>(row_shape[d], budget);
    budget = std::max<std::size_t>(1, budget / static_cast<std::size_t>(chunk[d + 1]));
  }
  chunk[0] = budget;
  s.chunk_rows = budget;

  std::vector<hsize_t> dims{0};
  std::vector<hsize_t> max_dims{H5S_UNLIMITED};
  dims.insert(dims.end(), s.row_shape.begin(), s.row_shape.end());
  max_dims.insert(max_dims.end(), s.row_shape.begin(), s.row_shape.end());

  if (!ensure_groups(file_, parts, parts.size() - 1)) fail("creating the parent groups", key);
  const Handle space(make_dataspace(dims, &max_dims), H5Sclose);
  if (!space.ok()) fail("H5Screate_simple", key);
  const Handle dcpl(make_dcpl(), H5Pclose);
  const double nan = std::numeric_limits<double>::quiet_NaN();  // unwritten rows read as NaN, not 0
  if (!dcpl.ok() || H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()) < 0 ||
      H5Pset_fill_value(dcpl.get(), H5T_NATIVE_DOUBLE, &nan) < 0) {
    fail("setting the dataset creation properties", key);
  }
  s.dataset = H5Dcreate2(file_, key.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT);
  if (s.dataset < 0) fail("H5Dcreate2", key);
  auto [it, inserted] = series_.emplace(key, std::move(s));  // the map owns the open dataset now
  (void)inserted;
  it->second.buffer.reserve(it->second.chunk_rows * it->second.row_size);
  if (!write_units_description(it->second.dataset, units, description)) fail("writing units/description", key);
}

void H5SeriesWriter::append(const std::string& path, std::span<const double> row) {
  require_open("append");
  auto it = series_.find(path);
  if (it == series_.end()) it = series_.find(normalize(path));
  if (it == series_.end()) {
    throw std::invalid_argument(fmt::format("H5SeriesWriter::append: series '{}' is not defined in '{}'", path,
                                            partial_path_));
  }
  Series& s = it->second;
  if (row.size() != s.row_size) {
    throw std::invalid_argument(fmt::format("H5SeriesWriter::append: series '{}' in '{}' takes rows of {} values, got {}",
                                            it->first, partial_path_, s.row_size, row.size()));
  }
  s.buffer.insert(s.buffer.end(), row.begin(), row.end());
  if (s.buffer.size() >= s.chunk_rows * s.row_size) {
    ErrorSilencer quiet;
    write_buffer(it->first, s);
  }
}

std::size_t H5SeriesWriter::rows(const std::string& path) const {
  auto it = series_.find(normalize(path));
  if (it == series_.end()) {
    throw std::invalid_argument(fmt::format("H5SeriesWriter::rows: series '{}' is not defined", path));
  }
  return it->second.rows_written + it->second.buffer.size() / it->second.row_size;
}

void H5SeriesWriter::write_buffer(const std::string& path, Series& s) {
  const std::size_t n = s.buffer.size() / s.row_size;
  if (n == 0) return;
  std::vector<hsize_t> new_dims{static_cast<hsize_t>(s.rows_written + n)};
  new_dims.insert(new_dims.end(), s.row_shape.begin(), s.row_shape.end());
  if (H5Dset_extent(s.dataset, new_dims.data()) < 0) fail("H5Dset_extent", path);

  std::vector<hsize_t> start(new_dims.size(), 0);
  start[0] = s.rows_written;
  std::vector<hsize_t> count = new_dims;
  count[0] = n;
  const Handle file_space(H5Dget_space(s.dataset), H5Sclose);
  if (!file_space.ok() ||
      H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr) < 0) {
    fail("selecting the rows to write", path);
  }
  const Handle mem_space(make_dataspace(count), H5Sclose);
  if (!mem_space.ok()) fail("H5Screate_simple", path);
  if (H5Dwrite(s.dataset, H5T_NATIVE_DOUBLE, mem_space.get(), file_space.get(), dxpl_, s.buffer.data()) < 0) {
    fail("H5Dwrite", path);
  }
  s.rows_written += n;
  s.buffer.clear();
}

void H5SeriesWriter::write_all_buffers() {
  for (auto& [path, s] : series_) write_buffer(path, s);
}

void H5SeriesWriter::flush() {
  require_open("flush");
  ErrorSilencer quiet;
  write_all_buffers();
  if (H5Fflush(file_, H5F_SCOPE_LOCAL) < 0) fail("H5Fflush", "/");
}

void H5SeriesWriter::close_all() noexcept {
  for (auto& [path, s] : series_) {
    if (s.dataset >= 0) H5Dclose(s.dataset);
    s.dataset = -1;
  }
  series_.clear();
  if (dxpl_ >= 0) H5Pclose(dxpl_);
  dxpl_ = -1;
  if (file_ >= 0) H5Fclose(file_);
  file_ = -1;
}

void H5SeriesWriter::commit() {
  require_open("commit");
  {
    ErrorSilencer quiet;
    write_all_buffers();
    for (auto& [path, s] : series_) {
      if (H5Dclose(s.dataset) < 0) fail("H5Dclose", path);
      s.dataset = -1;
    }
    series_.clear();
    H5Pclose(dxpl_);
    dxpl_ = -1;
    const herr_t closed = H5Fclose(file_);
    file_ = -1;
    if (closed < 0) fail("H5Fclose", "/");
  }
  fsync_file(partial_path_);
  std::error_code ec;
  std::filesystem::rename(partial_path_, final_path_, ec);
  if (ec) {
    throw std::runtime_error(fmt::format("H5SeriesWriter::commit: renaming '{}' to '{}' failed: {}", partial_path_,
                                         final_path_, ec.message()));
  }
}

namespace {

// Opens the object at path (root, group or dataset), creating it and missing parents as groups.
hid_t open_or_create_object(hid_t file, const std::string& path) {
  const auto parts = split_path(path);
  if (parts.empty()) return H5Oopen(file, "/", H5P_DEFAULT);
  if (!ensure_groups(file, parts, parts.size())) return failed_id();
  return H5Oopen(file, join_path(parts, parts.size()).c_str(), H5P_DEFAULT);
}

}  // namespace

void H5SeriesWriter::put_attribute(const std::string& object_path, const std::string& name, Hid file_type,
                                   Hid mem_type, Hid space, const void* buf) {
  const std::string where = fmt::format("{} (attribute '{}')", normalize(object_path), name);
  if (space < 0 || file_type < 0 || mem_type < 0) fail("making the attribute type/dataspace", where);
  const Handle obj(open_or_create_object(file_, object_path), H5Oclose);
  if (!obj.ok()) fail("opening the object", where);
  if (!write_attribute(obj.get(), name, file_type, mem_type, space, buf)) fail("writing the attribute", where);
}

void H5SeriesWriter::set_attribute(const std::string& object_path, const std::string& name, const std::string& value) {
  require_open("set_attribute");
  ErrorSilencer quiet;
  const Handle type(make_vlen_string_type(), H5Tclose);
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  const char* p = value.c_str();
  put_attribute(object_path, name, type.get(), type.get(), space.get(), &p);
}

void H5SeriesWriter::set_attribute(const std::string& object_path, const std::string& name, double value) {
  require_open("set_attribute");
  ErrorSilencer quiet;
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  put_attribute(object_path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space.get(), &value);
}

void H5SeriesWriter::set_attribute(const std::string& object_path, const std::string& name, long long value) {
  require_open("set_attribute");
  ErrorSilencer quiet;
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  put_attribute(object_path, name, H5T_STD_I64LE, H5T_NATIVE_LLONG, space.get(), &value);
}

void H5SeriesWriter::set_attribute(const std::string& object_path, const std::string& name,
                                   const std::vector<double>& value) {
  require_open("set_attribute");
  ErrorSilencer quiet;
  const Handle space(make_dataspace({static_cast<hsize_t>(value.size())}), H5Sclose);
  put_attribute(object_path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space.get(),
                value.empty() ? nullptr : value.data());
}

void H5SeriesWriter::set_attribute(const std::string& object_path, const std::string& name, const char* value) {
  set_attribute(object_path, name, std::string(value));
}

void H5SeriesWriter::set_attribute(const std::string& object_path, const std::string& name,
                                   const std::vector<std::string>& value) {
  require_open("set_attribute");
  ErrorSilencer quiet;
  const std::vector<const char*> ptrs = c_strings(value);
  const Handle type(make_vlen_string_type(), H5Tclose);
  const Handle space(make_dataspace({static_cast<hsize_t>(value.size())}), H5Sclose);
  put_attribute(object_path, name, type.get(), type.get(), space.get(), ptrs.empty() ? nullptr : ptrs.data());
}

namespace {

// The normalized dataset path of a write_array; an empty path is an error.
std::string array_key(const std::string& path) {
  const auto parts = split_path(path);
  if (parts.empty()) throw std::invalid_argument("H5SeriesWriter::write_array: empty dataset path");
  return join_path(parts, parts.size());
}

}  // namespace

H5SeriesWriter::Hid H5SeriesWriter::create_array(const std::string& key, Hid type, Hid space) {
  const auto parts = split_path(key);
  if (!ensure_groups(file_, parts, parts.size() - 1)) fail("creating the parent groups", key);
  const Handle dcpl(make_dcpl(), H5Pclose);
  if (type < 0 || space < 0 || !dcpl.ok()) fail("making the type/dataspace", key);
  const hid_t dset = H5Dcreate2(file_, key.c_str(), type, space, H5P_DEFAULT, dcpl.get(), H5P_DEFAULT);
  if (dset < 0) fail("H5Dcreate2", key);
  return dset;
}

void H5SeriesWriter::write_array(const std::string& path, std::vector<std::size_t> shape,
                                 std::span<const double> data, const std::string& units,
                                 const std::string& description) {
  require_open("write_array");
  ErrorSilencer quiet;
  const std::string key = array_key(path);
  if (product(shape) != data.size()) {
    throw std::invalid_argument(fmt::format("H5SeriesWriter::write_array: '{}' has shape of {} values but {} given",
                                            key, product(shape), data.size()));
  }
  const Handle space(make_dataspace(std::vector<hsize_t>(shape.begin(), shape.end())), H5Sclose);
  const Handle dset(create_array(key, H5T_IEEE_F64LE, space.get()), H5Dclose);
  if (!data.empty() && H5Dwrite(dset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, dxpl_, data.data()) < 0) {
    fail("H5Dwrite", key);
  }
  if (!write_units_description(dset.get(), units, description)) fail("writing units/description", key);
}

void H5SeriesWriter::write_array(const std::string& path, const std::vector<std::string>& values,
                                 const std::string& description) {
  require_open("write_array");
  ErrorSilencer quiet;
  const std::string key = array_key(path);
  const std::vector<const char*> ptrs = c_strings(values);
  const Handle type(make_vlen_string_type(), H5Tclose);
  const Handle space(make_dataspace({static_cast<hsize_t>(values.size())}), H5Sclose);
  const Handle dset(create_array(key, type.get(), space.get()), H5Dclose);
  if (!ptrs.empty() && H5Dwrite(dset.get(), type.get(), H5S_ALL, H5S_ALL, dxpl_, ptrs.data()) < 0) {
    fail("H5Dwrite", key);
  }
  if (!write_units_description(dset.get(), "", description)) fail("writing units/description", key);
}

}  // namespace raceway::io
