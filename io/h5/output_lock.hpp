// The output paths of a run, checked before any work is done, and the lock that keeps two runs off
// the same output (docs/output_layout.md, "One file per run").
//
// OutputLock: a POSIX record lock (fcntl F_SETLK) on "<output>.lock", held while a run writes
// "<output>.partial", its checkpoint and finally renames over "<output>". The kernel releases it
// when the process ends in any way (also SIGKILL), so a lock file left by a killed run does not
// block the next one. It is independent of HDF5's own file locking, which clusters often switch
// off (HDF5_USE_FILE_LOCKING=FALSE): the second run fails before it opens, truncates or renames
// anything. On a file system without record locks (ENOLCK), the lock file is created exclusively
// (O_EXCL) instead and holds "pid host"; a lock left by a dead process of the same host is removed.
#pragma once

#include <stdexcept>
#include <string>

namespace raceway::h5 {

/// An output path that cannot be written (a directory, "", a missing folder, no permission, held by
/// another run). Bad input: the driver exits with 2 before any work is done.
class OutputPathError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Checks that `path` can be created or replaced: not empty, not a directory, its folder exists and
/// is writable (and so is an existing file at it). `what` names the option in the message
/// ("output file (-o)"). Throws OutputPathError.
void check_output_path(const std::string& path, const std::string& what);

class OutputLock {
 public:
  /// Locks the output `path` (its "<path>.lock" file). Throws OutputPathError naming the path and
  /// the holder ("pid N on host H") if another run holds it.
  explicit OutputLock(const std::string& path);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  const std::string& lock_path() const { return lock_path_; }

 private:
  bool try_record_lock();    // fcntl lock; false: held by another process
  bool try_exclusive_file(); // O_EXCL fallback; false: held by a live process
  std::string output_path_, lock_path_;
  int fd_ = -1;
};

}  // namespace raceway::h5
