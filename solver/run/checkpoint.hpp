// A run's checkpoint: what `raceway run SCENE -o OUT.h5 --resume` needs to continue OUT.h5.partial
// (docs/output_layout.md, "Checkpoints and resume"). A small HDF5 file OUT.h5.checkpoint, written
// atomically (OUT.h5.checkpoint.partial, fsync, rename) after the output file was flushed, so it
// never names rows that are not on disk. Sealed (h5::sealed_file_problem: the CRC-32 of all its
// bytes, checked before HDF5 reads it), with a CRC-32 of its payload and of the .partial file's
// rows up to it: a damaged checkpoint or .partial is refused, never resumed with other results.
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace raceway::run {

/// --resume refused: the checkpoint belongs to another scene, build or set of options, or its
/// output is missing. Bad input: exit code 2, nothing is written.
class ResumeRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Why a checkpoint was written. Periodic ones sit where every run restarts CVODE, so a resume from
/// one repeats the uninterrupted run bitwise; the others are taken at the next output time without
/// a restart in the running run, and a resume from one restarts CVODE there.
enum class CheckpointKind { periodic, wall_clock, signal };
const char* checkpoint_kind_name(CheckpointKind kind);

/// What identifies a run's results: the scene text, the build (solver/run/build_info.hpp) and the
/// command-line options that change them.
struct RunFingerprint {
  std::string scene_text, build, options;
};

struct Checkpoint {
  CheckpointKind kind = CheckpointKind::periodic;
  long sample = 0;      ///< output index of the checkpoint's time: the file holds samples 0..sample
  double time = 0;      ///< s
  std::vector<double> state;
  std::map<std::string, double> values;  ///< the run's accumulators and counters, by name
  std::vector<double> restart_times;     ///< s: CVODE restarts off the periodic grid (resumes from other kinds)
  /// Rows of each output series not yet in OUT.h5.partial (its last, partly filled chunk: the
  /// writer writes whole chunks only until the end), by series path, row-major.
  std::map<std::string, std::vector<double>> unwritten_rows;
  RunFingerprint fingerprint;
  /// Per series of OUT.h5.partial, the CRC-32 of its rows appended so far, file and unwritten
  /// (h5::H5SeriesWriter::row_checksums): a resume checks the .partial file against them.
  std::map<std::string, double> partial_crc;
};

/// The checkpoint file of an output path: OUT.h5 -> OUT.h5.checkpoint.
std::string checkpoint_path(const std::string& output_path);

/// Writes `cp` to `path` atomically (write, fsync, rename). Throws std::runtime_error naming the file.
void write_checkpoint(const std::string& path, const Checkpoint& cp);

/// The checkpoint at `path`; nullopt when there is none. Throws ResumeRefused when the file exists
/// but cannot be read as a checkpoint.
std::optional<Checkpoint> read_checkpoint(const std::string& path);

/// Throws ResumeRefused with the reason when `cp` cannot continue a run of `state_size` states and
/// output samples 0..`samples` every `dt` seconds: a state of another size or not finite, a sample
/// outside the run, a time that is not the sample's, restart times outside [0, time]. Checked
/// after require_same_run, before anything is integrated or written.
void require_fits(const Checkpoint& cp, std::size_t state_size, long samples, double dt, const std::string& path);

/// Throws ResumeRefused with the reason (the first differing scene line, or the two builds or
/// option sets) when `now` is not the fingerprint the checkpoint was written with.
void require_same_run(const RunFingerprint& checkpoint, const RunFingerprint& now, const std::string& path);

}  // namespace raceway::run
