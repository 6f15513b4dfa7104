// raceway HDF5 series writer: attributes, fixed arrays and the time dimension scale (see
// h5_series.hpp for the contract).
#include <hdf5.h>
#include <hdf5_hl.h>

#include <fmt/format.h>

#include "io/h5/h5_series.hpp"
#include "io/h5/h5_support.hpp"

namespace raceway::h5 {

using h5::ErrorSilencer;
using h5::Handle;

namespace {

// Pointers to the strings' characters, for HDF5's variable-length string writes (valid while
// `values` lives).
std::vector<const char*> c_strings(const std::vector<std::string>& values) {
  std::vector<const char*> ptrs;
  ptrs.reserve(values.size());
  for (const auto& v : values) ptrs.push_back(v.c_str());
  return ptrs;
}

// Opens the object at path (root, group or dataset), creating it and missing parents as groups.
hid_t open_or_create_object(hid_t file, const std::string& path) {
  const auto parts = h5::split_path(path);
  if (parts.empty()) return H5Oopen(file, "/", H5P_DEFAULT);
  if (!h5::ensure_groups(file, parts, parts.size())) return h5::failed_id();
  return H5Oopen(file, h5::join_path(parts, parts.size()).c_str(), H5P_DEFAULT);
}

// The normalized dataset path of a write_array; an empty path is an error.
std::string array_key(const std::string& path) {
  const std::string key = h5::normalize(path);
  if (key == "/") throw std::invalid_argument("H5SeriesWriter::write_array: empty dataset path");
  return key;
}

}  // namespace

void H5SeriesWriter::put_attribute(const std::string& object_path, const std::string& name, Hid file_type,
                                   Hid mem_type, Hid space, const void* buf) {
  const std::string where = fmt::format("{} (attribute '{}')", h5::normalize(object_path), name);
  if (space < 0 || file_type < 0 || mem_type < 0) fail("making the attribute type/dataspace", where);
  const Handle obj(open_or_create_object(file_, object_path), H5Oclose);
  if (!obj.ok()) fail("opening the object", where);
  if (!h5::write_attribute(obj.get(), name, file_type, mem_type, space, buf)) fail("writing the attribute", where);
}

void H5SeriesWriter::set_attribute(const std::string& object_path, const std::string& name, const std::string& value) {
  require_open("set_attribute");
  ErrorSilencer quiet;
  const Handle type(h5::make_vlen_string_type(), H5Tclose);
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
  const Handle space(h5::make_dataspace({static_cast<hsize_t>(value.size())}), H5Sclose);
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
  const Handle type(h5::make_vlen_string_type(), H5Tclose);
  const Handle space(h5::make_dataspace({static_cast<hsize_t>(value.size())}), H5Sclose);
  put_attribute(object_path, name, type.get(), type.get(), space.get(), ptrs.empty() ? nullptr : ptrs.data());
}

H5SeriesWriter::Hid H5SeriesWriter::create_array(const std::string& key, Hid type, Hid space) {
  if (series_.contains(key))
    throw std::runtime_error(fmt::format("H5SeriesWriter::write_array: '{}' in '{}' is a time series of this file; a "
                                         "fixed array cannot replace it", key, partial_path_));
  const auto parts = h5::split_path(key);
  if (!h5::ensure_groups(file_, parts, parts.size() - 1)) fail("creating the parent groups", key);
  const int exists = h5::link_exists(file_, key);
  if (exists < 0 || (exists > 0 && H5Ldelete(file_, key.c_str(), H5P_DEFAULT) < 0)) fail("replacing the dataset", key);
  const Handle dcpl(h5::make_dcpl(), H5Pclose);
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
  std::size_t n = 1;
  for (const std::size_t d : shape) n *= d;
  if (n != data.size()) {
    throw std::invalid_argument(fmt::format("H5SeriesWriter::write_array: '{}' has shape of {} values but {} given",
                                            key, n, data.size()));
  }
  const Handle space(h5::make_dataspace(std::vector<hsize_t>(shape.begin(), shape.end())), H5Sclose);
  const Handle dset(create_array(key, H5T_IEEE_F64LE, space.get()), H5Dclose);
  if (!data.empty() && H5Dwrite(dset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, dxpl_, data.data()) < 0) {
    fail("H5Dwrite", key);
  }
  if (!h5::write_units_description(dset.get(), units, description)) fail("writing units/description", key);
}

void H5SeriesWriter::write_array(const std::string& path, const std::vector<std::string>& values,
                                 const std::string& description) {
  require_open("write_array");
  ErrorSilencer quiet;
  const std::string key = array_key(path);
  const std::vector<const char*> ptrs = c_strings(values);
  const Handle type(h5::make_vlen_string_type(), H5Tclose);
  const Handle space(h5::make_dataspace({static_cast<hsize_t>(values.size())}), H5Sclose);
  const Handle dset(create_array(key, type.get(), space.get()), H5Dclose);
  if (!ptrs.empty() && H5Dwrite(dset.get(), type.get(), H5S_ALL, H5S_ALL, dxpl_, ptrs.data()) < 0) {
    fail("H5Dwrite", key);
  }
  if (!h5::write_units_description(dset.get(), "", description)) fail("writing units/description", key);
}

void H5SeriesWriter::set_time_scale(const std::string& scale_path, const std::string& scale_name) {
  require_open("set_time_scale");
  ErrorSilencer quiet;
  const auto scale = series_.find(h5::normalize(scale_path));
  if (scale == series_.end() || !scale->second.row_shape.empty())
    throw std::invalid_argument(fmt::format("H5SeriesWriter::set_time_scale: '{}' is not a defined [T] series", scale_path));
  const hid_t ds = scale->second.dataset;
  const htri_t is_scale = H5DSis_scale(ds);
  if (is_scale < 0 || (is_scale == 0 && H5DSset_scale(ds, scale_name.c_str()) < 0)) fail("H5DSset_scale", scale->first);
  for (const auto& [path, s] : series_) {
    if (s.dataset == ds || s.stride != scale->second.stride) continue;
    const htri_t attached = H5DSis_attached(s.dataset, ds, 0);
    if (attached < 0 || (attached == 0 && H5DSattach_scale(s.dataset, ds, 0) < 0)) fail("H5DSattach_scale", path);
  }
}

}  // namespace raceway::h5
