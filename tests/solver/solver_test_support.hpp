// Test support for the solver suite: scenes from jobs/scenes, temporary output files, HDF5 readers
// (HDF5 C API, read-only), angle helpers. Nothing here computes an expected result.
#pragma once

#include <hdf5.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/scene/scene.hpp"
#include "io/scene/scene_parser.hpp"

namespace raceway::solver::test {

inline constexpr double pi = std::numbers::pi;
inline constexpr double deg = pi / 180.0;

/// A scene file of the repository (jobs/scenes/NAME).
inline io::Scene load_job_scene(const std::string& name) {
  return io::load_scene(std::string(RACEWAY_SOURCE_DIR) + "/jobs/scenes/" + name);
}

/// A directory under the system temp dir, removed with everything in it on destruction.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("raceway_solver_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

/// A whole double dataset: its shape and values (row-major).
struct Dataset {
  std::vector<hsize_t> shape;
  std::vector<double> values;
  double at(std::size_t i, std::size_t j) const { return values[i * shape.at(1) + j]; }
  double at(std::size_t i, std::size_t j, std::size_t k) const {
    return values[(i * shape.at(1) + j) * shape.at(2) + k];
  }
};

/// Reads one double dataset of an HDF5 file. Throws std::runtime_error naming file and dataset.
inline Dataset read_dataset(const std::string& file, const std::string& path) {
  auto fail = [&](const char* what) {
    return std::runtime_error("read_dataset(" + file + ", " + path + "): " + what);
  };
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw fail("H5Fopen failed");
  const hid_t d = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
  if (d < 0) {
    H5Fclose(f);
    throw fail("H5Dopen2 failed");
  }
  const hid_t space = H5Dget_space(d);
  const int rank = H5Sget_simple_extent_ndims(space);
  Dataset out;
  out.shape.resize(static_cast<std::size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space, out.shape.data(), nullptr);
  std::size_t n = 1;
  for (hsize_t s : out.shape) n *= static_cast<std::size_t>(s);
  out.values.resize(n);
  const herr_t st = n > 0 ? H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.values.data()) : 0;
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
  if (st < 0) throw fail("H5Dread failed");
  return out;
}

/// A 1-D dataset of variable-length strings (e.g. /segments/KIND/names).
inline std::vector<std::string> read_strings(const std::string& file, const std::string& path) {
  auto fail = [&](const char* what) {
    return std::runtime_error("read_strings(" + file + ", " + path + "): " + what);
  };
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw fail("H5Fopen failed");
  const hid_t d = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
  if (d < 0) {
    H5Fclose(f);
    throw fail("H5Dopen2 failed");
  }
  const hid_t space = H5Dget_space(d);
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space, &n, nullptr);
  const hid_t mtype = H5Tcopy(H5T_C_S1);
  H5Tset_size(mtype, H5T_VARIABLE);
  H5Tset_cset(mtype, H5T_CSET_UTF8);
  std::vector<char*> raw(static_cast<std::size_t>(n), nullptr);
  const herr_t st = n > 0 ? H5Dread(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()) : 0;
  std::vector<std::string> out;
  if (st >= 0) {
    for (char* p : raw) out.emplace_back(p ? p : "");
    H5Dvlen_reclaim(mtype, space, H5P_DEFAULT, raw.data());
  }
  H5Tclose(mtype);
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
  if (st < 0) throw fail("H5Dread failed");
  return out;
}

/// Angle wrapped to (-pi, pi].
inline double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * pi);
  return a <= -pi ? a + 2.0 * pi : a;
}

}  // namespace raceway::solver::test
