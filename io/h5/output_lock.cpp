#include "io/h5/output_lock.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

namespace raceway::h5 {

namespace fs = std::filesystem;

void check_output_path(const std::string& path, const std::string& what) {
  auto error = [&](const std::string& reason) {
    return OutputPathError(fmt::format("{} '{}': {}", what, path, reason));
  };
  if (path.empty()) throw OutputPathError(fmt::format("{}: the path is empty", what));
  std::error_code ec;
  const fs::path p(path);
  if (fs::is_directory(p, ec)) throw error("is a directory; give a file name, e.g. " + (p / "run.h5").string());
  if (!p.has_filename()) throw error("names a folder (ends with '/'); give a file name");
  const fs::path folder = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::exists(folder, ec)) throw error(fmt::format("the folder '{}' does not exist", folder.string()));
  if (!fs::is_directory(folder, ec)) throw error(fmt::format("'{}' is not a folder", folder.string()));
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    throw error(fmt::format("cannot create files in '{}': {}", folder.string(), std::strerror(errno)));
  if (fs::exists(p, ec) && ::access(p.c_str(), W_OK) != 0)
    throw error(fmt::format("the existing file is not writable: {}", std::strerror(errno)));
}

namespace {

std::string host_name() {
  char buf[256] = {};
  return ::gethostname(buf, sizeof buf - 1) == 0 ? std::string(buf) : std::string("unknown");
}

std::string read_holder(const std::string& lock_path) {
  std::ifstream in(lock_path);
  std::string pid, host;
  in >> pid >> host;
  return pid.empty() ? std::string("another process") : fmt::format("pid {} on host {}", pid, host);
}

void write_holder(int fd) {
  const std::string who = fmt::format("{} {}\n", ::getpid(), host_name());
  if (::ftruncate(fd, 0) == 0) (void)!::write(fd, who.data(), who.size());
}

}  // namespace

OutputLock::OutputLock(const std::string& path) : output_path_(path), lock_path_(path + ".lock") {
  // A holder that unlinks the lock file as we open it leaves us a lock on a dead inode: retry.
  for (int attempt = 0; attempt < 10; ++attempt) {
    fd_ = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw OutputPathError(fmt::format("output '{}': cannot create the lock file '{}': {}", output_path_, lock_path_,
                                        std::strerror(errno)));
    const bool locked = try_record_lock();
    if (!locked && fd_ < 0 && try_exclusive_file()) return;  // no record locks here: O_EXCL file
    if (!locked && fd_ >= 0) {
      const std::string holder = read_holder(lock_path_);
      ::close(fd_), fd_ = -1;
      throw OutputPathError(fmt::format("output '{}' is being written by another raceway run ({}; lock file '{}'); "
                                        "choose another -o or wait for that run to end",
                                        output_path_, holder, lock_path_));
    }
    if (!locked) break;
    struct stat held {}, named {};
    if (::fstat(fd_, &held) == 0 && ::stat(lock_path_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev) {
      write_holder(fd_);
      return;
    }
    ::close(fd_), fd_ = -1;
  }
  throw OutputPathError(fmt::format("output '{}': the lock file '{}' is being held by another raceway run",
                                    output_path_, lock_path_));
}

bool OutputLock::try_record_lock() {
  struct flock fl {};
  fl.l_type = F_WRLCK;
  fl.l_whence = SEEK_SET;
  if (::fcntl(fd_, F_SETLK, &fl) == 0) return true;
  if (errno == EACCES || errno == EAGAIN) return false;  // held: fd_ stays open for the message
  ::close(fd_), fd_ = -1;                                // ENOLCK, ENOSYS...: no record locks here
  return false;
}

bool OutputLock::try_exclusive_file() {
  for (int attempt = 0; attempt < 2; ++attempt) {
    fd_ = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd_ >= 0) {
      write_holder(fd_);
      return true;
    }
    std::ifstream in(lock_path_);
    long pid = 0;
    std::string host;
    in >> pid >> host;
    // Empty: the file our record-lock attempt created. A dead process of this host: left by a kill.
    const bool stale = pid <= 0 || (host == host_name() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH);
    if (!stale)
      throw OutputPathError(fmt::format("output '{}' is being written by another raceway run ({}; lock file '{}')",
                                        output_path_, read_holder(lock_path_), lock_path_));
    ::unlink(lock_path_.c_str());
  }
  return false;
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  ::unlink(lock_path_.c_str());
  ::close(fd_);
}

}  // namespace raceway::h5
