// The clock the executor times its tasks with: one reading per task (a task's seconds run from the
// previous task's end to its own), 1,381 readings per right-hand side on the heavy spatial roller
// scene. steady_clock costs 26-30 ns a reading on the development machine's VM (its vDSO reads the
// TSC and scales it through the hypervisor's page): 38 us of a 258 us right-hand side at one rank
// went to reading it (perf/studies/results/parallel_notes.md, "The exchange after the tail"). The
// processor's time-stamp counter read directly costs 11 ns there; its ticks become seconds through
// the ratio of steady_clock to ticks since the first use, renewed at every lap() of a list
// (two steady_clock readings per list, not per task). Elsewhere than x86 it is steady_clock.
#pragma once

#include <chrono>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

namespace raceway::scheduler {

class TaskClock {
 public:
  /// Starts a list of tasks: the scale renewed, the first lap from now.
  TaskClock() : scale_(renew_scale()), last_(ticks()) {}
  /// Seconds since the previous lap (or the start), and a new lap from now.
  double lap() {
    const std::uint64_t now = ticks();
    const double s = static_cast<double>(now - last_) * scale_;
    last_ = now;
    return s;
  }

 private:
#if defined(__x86_64__) || defined(__i386__)
  static std::uint64_t ticks() { return __rdtsc(); }
  /// Seconds per tick: steady_clock against the counter since this process's first list (at the
  /// first, the two compared over 100 us).
  static double renew_scale() {
    using clock = std::chrono::steady_clock;
    static const clock::time_point wall0 = clock::now();
    static const std::uint64_t ticks0 = ticks();
    clock::time_point wall = clock::now();
    while (wall - wall0 < std::chrono::microseconds(100)) wall = clock::now();  // the first list only
    return std::chrono::duration<double>(wall - wall0).count() / static_cast<double>(ticks() - ticks0);
  }
#else
  static std::uint64_t ticks() {
    return static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  }
  static double renew_scale() {
    return std::chrono::duration<double>(std::chrono::steady_clock::duration(1)).count();
  }
#endif
  double scale_;
  std::uint64_t last_;
};

}  // namespace raceway::scheduler
