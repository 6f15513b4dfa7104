// Test support for the solver suite: scenes from jobs/scenes, temporary output files, HDF5 readers
// (HDF5 C API, read-only), angle helpers, wall time, and the central-difference Jacobian of
// Equations::rhs that the Jacobian tests compare Equations::jacobian with. Nothing here computes an
// expected physical result.
#pragma once

#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/scene/scene.hpp"
#include "io/scene/scene_parser.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"

namespace raceway::test {

inline constexpr double pi = std::numbers::pi;
inline constexpr double deg = pi / 180.0;

/// A scene file of the repository (jobs/scenes/NAME).
inline scene::Scene load_job_scene(const std::string& name) {
  return scene::load_scene(std::string(RACEWAY_SOURCE_DIR) + "/jobs/scenes/" + name);
}

/// jobs/scenes/seed002_40hz.toml's text with the solver it had before it took its converged pocket
/// settings: the rollers' velocities in the bearing frame, no pocket factor, rtol 1e-5. The tests that
/// read its states in the bearing frame, or whose bounds were measured at those settings, run it so;
/// a spatial copy needs it (the orbital frame is the planar rollers' and the balls' only). Throws if
/// the scene's [solver] lines are no longer the ones replaced here.
inline std::string seed002_former_solver_text() {
  std::string text = load_job_scene("seed002_40hz.toml").text;
  const std::string shipped =
      "rtol = 2e-5\nelement_velocity_frame = \"orbital\"\npocket_tolerance_factor = 10\npocket_tolerance_cage = true\n";
  const std::size_t at = text.find(shipped);
  if (at == std::string::npos) throw std::runtime_error("seed002_40hz.toml: its [solver] lines changed");
  return text.replace(at, shipped.size(), "rtol = 1e-5\n");
}

/// Seed 002 at 40 Hz with its former solver (seed002_former_solver_text).
inline scene::Scene load_seed002_former_solver() {
  return scene::parse_scene(seed002_former_solver_text(), "seed002_40hz.toml (former solver)");
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

/// One dataset of an HDF5 file opened read-only, with its file; both closed on destruction. The
/// errors name the reader, the file and the dataset.
class OpenDataset {
 public:
  OpenDataset(const char* reader, const std::string& file, const std::string& path)
      : where_(std::string(reader) + "(" + file + ", " + path + "): ") {
    file_ = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file_ < 0) throw error("H5Fopen failed");
    dataset_ = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
    if (dataset_ < 0) {
      H5Fclose(file_);
      throw error("H5Dopen2 failed");
    }
  }
  ~OpenDataset() {
    H5Dclose(dataset_);
    H5Fclose(file_);
  }
  OpenDataset(const OpenDataset&) = delete;
  OpenDataset& operator=(const OpenDataset&) = delete;
  hid_t id() const { return dataset_; }
  std::runtime_error error(const char* what) const { return std::runtime_error(where_ + what); }

 private:
  std::string where_;
  hid_t file_ = -1, dataset_ = -1;
};

/// Reads one double dataset of an HDF5 file. Throws std::runtime_error naming file and dataset.
inline Dataset read_dataset(const std::string& file, const std::string& path) {
  const OpenDataset d("read_dataset", file, path);
  const hid_t space = H5Dget_space(d.id());
  const int rank = H5Sget_simple_extent_ndims(space);
  Dataset out;
  out.shape.resize(static_cast<std::size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space, out.shape.data(), nullptr);
  std::size_t n = 1;
  for (hsize_t s : out.shape) n *= static_cast<std::size_t>(s);
  out.values.resize(n);
  const herr_t st = n > 0 ? H5Dread(d.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.values.data()) : 0;
  H5Sclose(space);
  if (st < 0) throw d.error("H5Dread failed");
  return out;
}

/// A 1-D dataset of variable-length strings (e.g. /segments/KIND/names).
inline std::vector<std::string> read_strings(const std::string& file, const std::string& path) {
  const OpenDataset d("read_strings", file, path);
  const hid_t space = H5Dget_space(d.id());
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space, &n, nullptr);
  const hid_t mtype = H5Tcopy(H5T_C_S1);
  H5Tset_size(mtype, H5T_VARIABLE);
  H5Tset_cset(mtype, H5T_CSET_UTF8);
  std::vector<char*> raw(static_cast<std::size_t>(n), nullptr);
  const herr_t st = n > 0 ? H5Dread(d.id(), mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()) : 0;
  std::vector<std::string> out;
  if (st >= 0) {
    for (char* p : raw) out.emplace_back(p ? p : "");
    H5Dvlen_reclaim(mtype, space, H5P_DEFAULT, raw.data());
  }
  H5Tclose(mtype);
  H5Sclose(space);
  if (st < 0) throw d.error("H5Dread failed");
  return out;
}

/// Angle wrapped to (-pi, pi].
inline double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * pi);
  return a <= -pi ? a + 2.0 * pi : a;
}

/// Wall-clock seconds since `start` (for the printouts of long runs).
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Central-difference steps per variable class, from the contact physics rather than from the
/// solver settings, for both bearings. Positions 1e-11 m: about 1e-5 of the loaded approaches (the
/// rollers' ~1 um deflections in seed 002; the ball bearing's cage land and pockets, ~1 um, and
/// ball-race contacts, 10-20 um) and ~2e-3 of the lightest closed contact (a roller bearing's cage
/// on its land under its own weight, ~5 nm), so the O(h^2) truncation error is <= 1e-5 relative
/// (~1e-10 for the ball bearing's um approaches). Velocities 1e-7 m/s: ~2e-6 of the traction slip
/// scale (0.05 m/s). Angles and angular velocities: the same surface displacement and speed at the
/// pitch and rolling-element radii.
inline double central_step(const bearing::Model& m, bearing::VariableClass c) {
  switch (c) {
    case bearing::VariableClass::position: return 1e-11;
    case bearing::VariableClass::angle: return 1e-11 / m.pitch_radius;
    case bearing::VariableClass::velocity: return 1e-7;
    case bearing::VariableClass::angular_velocity: return 1e-7 / m.element_radius;
  }
  return 0;
}

/// One step of the classic fourth-order Runge-Kutta method for dz/dt = f(t, z), in place; f(t, y, out)
/// writes the rates of y into out. The free-vibration tests integrate with it (explicit, with no
/// error control to hide an energy leak).
template <class Rates>
void runge_kutta_step(Rates&& f, double t, double dt, std::vector<double>& z) {
  const std::size_t n = z.size();
  std::vector<double> k1(n), k2(n), k3(n), k4(n), tmp(n);
  f(t, z, k1);
  for (std::size_t i = 0; i < n; ++i) tmp[i] = z[i] + 0.5 * dt * k1[i];
  f(t + 0.5 * dt, tmp, k2);
  for (std::size_t i = 0; i < n; ++i) tmp[i] = z[i] + 0.5 * dt * k2[i];
  f(t + 0.5 * dt, tmp, k3);
  for (std::size_t i = 0; i < n; ++i) tmp[i] = z[i] + dt * k3[i];
  f(t + dt, tmp, k4);
  for (std::size_t i = 0; i < n; ++i) z[i] += dt / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
}

/// The Jacobian of eq.rhs at (t, z) by central differences over ALL states (steps: central_step),
/// independent of Equations::jacobian and of its segment-by-segment assembly.
inline Eigen::MatrixXd central_difference_jacobian(bearing::Equations& eq, const bearing::Model& m, double t,
                                                   const std::vector<double>& z) {
  const int n = m.state_size;
  Eigen::MatrixXd jac(n, n);
  std::vector<double> zp = z, fp(z.size()), fm(z.size());
  for (int j = 0; j < n; ++j) {
    const auto jj = static_cast<std::size_t>(j);
    const double h = central_step(m, m.state_class[jj]);
    zp[jj] = z[jj] + h;
    EXPECT_EQ(eq.rhs(t, zp.data(), fp.data()), 0);
    zp[jj] = z[jj] - h;
    EXPECT_EQ(eq.rhs(t, zp.data(), fm.data()), 0);
    zp[jj] = z[jj];
    const double h2 = (z[jj] + h) - (z[jj] - h);  // the step actually taken in floating point
    for (int i = 0; i < n; ++i) jac(i, j) = (fp[static_cast<std::size_t>(i)] - fm[static_cast<std::size_t>(i)]) / h2;
  }
  return jac;
}

}  // namespace raceway::test
