// A small reader of the HDF5 files raceway writes (checkpoints, an interrupted run's output): double
// datasets and scalar attributes by path. Every failure throws std::runtime_error naming the file,
// the object and the reason.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace raceway::h5 {

class H5Reader {
 public:
  /// Opens `path` read-only; throws if it is missing or not an HDF5 file.
  explicit H5Reader(const std::string& path);
  ~H5Reader();
  H5Reader(const H5Reader&) = delete;
  H5Reader& operator=(const H5Reader&) = delete;

  /// Whether the object (group or dataset) exists.
  bool has(const std::string& object) const;
  /// A numeric dataset as doubles, row-major; its shape in *shape if given.
  std::vector<double> doubles(const std::string& dataset, std::vector<std::size_t>* shape = nullptr) const;
  /// A scalar string attribute of a group or dataset ("/" the root).
  std::string string_attribute(const std::string& object, const std::string& name) const;
  /// A scalar numeric attribute.
  double number_attribute(const std::string& object, const std::string& name) const;
  /// The names of an object's attributes, in name order.
  std::vector<std::string> attribute_names(const std::string& object) const;

 private:
  [[noreturn]] void fail(const std::string& what, const std::string& object) const;
  std::int64_t open_attribute(const std::string& object, const std::string& name) const;  // caller closes
  std::string path_;
  std::int64_t file_ = -1;
};

}  // namespace raceway::h5
