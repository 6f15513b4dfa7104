// Internal helpers of io/h5 (h5_support.hpp).
#include "io/h5/h5_support.hpp"

#include <cstring>

#include <cerrno>

#include <unistd.h>

#include <sys/stat.h>

#include <fcntl.h>

#include <fmt/format.h>

#include <algorithm>

namespace raceway::h5 {

std::string error_text() {
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

std::string& saved_error() {
  thread_local std::string saved;
  return saved;
}

bool failed() {
  if (saved_error().empty()) saved_error() = error_text();
  return false;
}

hid_t failed_id() {
  failed();
  return -1;
}

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

hid_t make_dataspace(const std::vector<hsize_t>& dims, const std::vector<hsize_t>* max_dims) {
  if (dims.empty()) return H5Screate(H5S_SCALAR);
  return H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max_dims ? max_dims->data() : nullptr);
}

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

hid_t make_dcpl() {
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  if (dcpl >= 0 && H5Pset_obj_track_times(dcpl, false) < 0) {
    failed();
    H5Pclose(dcpl);
    return -1;
  }
  return dcpl;
}

int link_exists(hid_t file, const std::string& path) {
  const auto parts = split_path(path);
  for (std::size_t i = 1; i <= parts.size(); ++i) {
    const htri_t e = H5Lexists(file, join_path(parts, i).c_str(), H5P_DEFAULT);
    if (e < 0) {
      failed();
      return -1;
    }
    if (e == 0) return 0;
  }
  return 1;
}

// Reserves `bytes` of disk after the end of `path` (fallocate, FALLOC_FL_KEEP_SIZE: the size does not
// change), so that a flush finds a full disk before it writes anything rather than half-way through
// rewriting the file's metadata. "" when reserved or when the file system cannot reserve (then the
// flush itself reports a full disk); else the system's reason.
std::string reserve_disk(const std::string& path, std::size_t bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return "";
  struct stat st {};
  std::string error;
  if (::fstat(fd, &st) == 0 &&
      ::fallocate(fd, FALLOC_FL_KEEP_SIZE, st.st_size, static_cast<off_t>(bytes)) != 0 && errno != EOPNOTSUPP &&
      errno != ENOSYS)
    error = std::strerror(errno);
  (void)::close(fd);
  return error;
}

}  // namespace raceway::h5
