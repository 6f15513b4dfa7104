#include "solver/run/build_info.hpp"

#include <hdf5.h>
#include <petscversion.h>
#include <sundials/sundials_config.h>

#include <fmt/format.h>

#include "raceway/version.hpp"

namespace raceway::run {

namespace {

std::string compiler() {
#if defined(__clang__)
  return fmt::format("clang {}", __clang_version__);
#elif defined(__GNUC__)
  return fmt::format("gcc {}", __VERSION__);
#else
  return "unknown compiler";
#endif
}

std::string hdf5_version() {
  unsigned major = 0, minor = 0, release = 0;
  H5get_libversion(&major, &minor, &release);
  return fmt::format("{}.{}.{}", major, minor, release);
}

}  // namespace

std::vector<std::pair<std::string, std::string>> build_info(const std::string& mpi_library) {
  return {{"raceway_version", std::string(kVersion)},
          {"raceway_commit", std::string(kGitCommit)},
          {"build_type", RACEWAY_BUILD_TYPE},
          {"compiler", compiler()},
          {"hdf5_version", hdf5_version()},
          {"sundials_version", SUNDIALS_VERSION},
          {"petsc_version", fmt::format("{}.{}.{}", PETSC_VERSION_MAJOR, PETSC_VERSION_MINOR, PETSC_VERSION_SUBMINOR)},
          {"mpi_library", mpi_library.empty() ? std::string("not used") : mpi_library}};
}

std::string build_fingerprint(const std::string& mpi_library) {
  std::string out;
  for (const auto& [name, value] : build_info(mpi_library)) out += fmt::format("{}={}; ", name, value);
  return out;
}

}  // namespace raceway::run
