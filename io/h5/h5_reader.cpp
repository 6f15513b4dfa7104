#include "io/h5/h5_reader.hpp"

#include <hdf5.h>

#include <stdexcept>

#include <fmt/format.h>

#include "io/h5/h5_support.hpp"

namespace raceway::h5 {

using h5::Handle;

H5Reader::H5Reader(const std::string& path) : path_(path) {
  h5::ErrorSilencer quiet;
  if (H5Fis_hdf5(path.c_str()) <= 0) throw std::runtime_error(fmt::format("'{}' is missing or not an HDF5 file", path));
  file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file_ < 0) fail("opening the file", "/");
}

H5Reader::~H5Reader() {
  if (file_ >= 0) H5Fclose(file_);
}

void H5Reader::fail(const std::string& what, const std::string& object) const {
  throw std::runtime_error(fmt::format("reading '{}' of '{}': {} failed: {}", object, path_, what,
                                       h5::saved_error().empty() ? h5::error_text() : h5::saved_error()));
}

bool H5Reader::has(const std::string& object) const {
  h5::ErrorSilencer quiet;
  const int e = h5::link_exists(file_, object);
  if (e < 0) fail("H5Lexists", object);
  return e > 0 || h5::normalize(object) == "/";
}

std::vector<double> H5Reader::doubles(const std::string& dataset, std::vector<std::size_t>* shape) const {
  h5::ErrorSilencer quiet;
  if (!has(dataset)) throw std::runtime_error(fmt::format("'{}' has no dataset '{}'", path_, dataset));
  const Handle d(H5Dopen2(file_, dataset.c_str(), H5P_DEFAULT), H5Dclose);
  const Handle space(d.ok() ? H5Dget_space(d.get()) : -1, H5Sclose);
  const int rank = space.ok() ? H5Sget_simple_extent_ndims(space.get()) : -1;
  if (rank < 0) fail("H5Dopen2", dataset);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  std::vector<double> data(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.get())));
  if (!data.empty() && H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0)
    fail("H5Dread", dataset);
  if (shape) shape->assign(dims.begin(), dims.end());
  return data;
}

hid_t H5Reader::open_attribute(const std::string& object, const std::string& name) const {
  const Handle obj(H5Oopen(file_, object.c_str(), H5P_DEFAULT), H5Oclose);
  if (!obj.ok() || H5Aexists(obj.get(), name.c_str()) <= 0)
    throw std::runtime_error(fmt::format("'{}' has no attribute '{}' on {}", path_, name, object));
  const hid_t attr = H5Aopen(obj.get(), name.c_str(), H5P_DEFAULT);
  if (attr < 0) fail("H5Aopen", object + " attribute " + name);
  return attr;
}

std::string H5Reader::string_attribute(const std::string& object, const std::string& name) const {
  h5::ErrorSilencer quiet;
  const Handle attr(open_attribute(object, name), H5Aclose);
  const Handle type(H5Aget_type(attr.get()), H5Tclose);
  if (!type.ok() || H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) <= 0)
    throw std::runtime_error(fmt::format("'{}': attribute '{}' of {} is not a variable-length string", path_, name, object));
  const Handle mem(h5::make_vlen_string_type(), H5Tclose);
  char* s = nullptr;
  if (H5Aread(attr.get(), mem.get(), &s) < 0) fail("H5Aread", object + " attribute " + name);
  std::string value = s ? s : "";
  H5free_memory(s);
  return value;
}

double H5Reader::number_attribute(const std::string& object, const std::string& name) const {
  h5::ErrorSilencer quiet;
  const Handle attr(open_attribute(object, name), H5Aclose);
  const Handle type(H5Aget_type(attr.get()), H5Tclose);
  const H5T_class_t cls = type.ok() ? H5Tget_class(type.get()) : H5T_NO_CLASS;
  if (cls != H5T_FLOAT && cls != H5T_INTEGER)
    throw std::runtime_error(fmt::format("'{}': attribute '{}' of {} is not a number", path_, name, object));
  double v = 0;
  if (H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &v) < 0) fail("H5Aread", object + " attribute " + name);
  return v;
}

std::vector<std::string> H5Reader::attribute_names(const std::string& object) const {
  h5::ErrorSilencer quiet;
  const Handle obj(H5Oopen(file_, object.c_str(), H5P_DEFAULT), H5Oclose);
  if (!obj.ok()) fail("H5Oopen", object);
  std::vector<std::string> names;
  auto collect = [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
  };
  hsize_t index = 0;
  if (H5Aiterate2(obj.get(), H5_INDEX_NAME, H5_ITER_INC, &index, collect, &names) < 0) fail("H5Aiterate2", object);
  return names;
}

}  // namespace raceway::h5
