#include "io/report/process.hpp"

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include <fmt/format.h>

extern char** environ;  // NOLINT: POSIX, for posix_spawn

namespace raceway::report {

int run_process(const std::vector<std::string>& args, std::string& error,
                const std::function<void(pid_t)>& while_waiting) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, argv[0], nullptr, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  if (rc != 0) {
    error = std::strerror(rc);
    return -1;
  }
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(pid, &status, while_waiting ? WNOHANG : 0);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) {
      error = std::strerror(errno);
      return -1;
    }
    if (done == 0) {  // still running (WNOHANG)
      while_waiting(pid);
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  error = WIFSIGNALED(status) ? fmt::format("killed by signal {}", WTERMSIG(status)) : "ended abnormally";
  return -1;
}

}  // namespace raceway::report
