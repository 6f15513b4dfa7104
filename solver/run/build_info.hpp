// What built this raceway: version, git commit, compiler, build type and the libraries' versions.
// Stored as root attributes of every output file (docs/output_layout.md) and, as one string, in the
// fingerprint a checkpoint is resumed against.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace raceway::run {

/// The output file's layout version: increased when a reader of the file would need to change
/// (3: one dataset name per quantity in planar and spatial runs, the bearing attributes always).
inline constexpr long long kOutputLayoutVersion = 3;

/// (attribute name, value) pairs: raceway_version, raceway_commit, build_type, compiler,
/// hdf5_version, sundials_version, petsc_version, mpi_library (the given text; "" when not run
/// under the MPI driver: "not used").
std::vector<std::pair<std::string, std::string>> build_info(const std::string& mpi_library);

/// The build as one line, for fingerprints: the values of build_info, joined.
std::string build_fingerprint(const std::string& mpi_library);

}  // namespace raceway::run
