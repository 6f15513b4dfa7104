// Waits on words in the node's shared-memory window (scheduler/node_window.hpp): atomic loads and
// stores of the words, and the spin-then-yield loop the command channel and the replies wait in.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>

namespace raceway::scheduler {

inline std::int64_t load_word(const std::int64_t& word) {
  return std::atomic_ref<const std::int64_t>(word).load(std::memory_order_acquire);
}
inline void store_word(std::int64_t& word, std::int64_t value) {
  std::atomic_ref<std::int64_t>(word).store(value, std::memory_order_release);
}

// A waiting rank spins on the words while the wait is short (the ranks finish within a task of each
// other, and rank 0 comes back between two evaluations within tens of us), then gives its core away
// between looks: oversubscribed (more ranks than cores) a spinning rank would hold the core another
// rank needs. The clock is read every looks_per_clock_reading looks.
inline constexpr double spin_seconds = 50e-6;
inline constexpr unsigned looks_per_clock_reading = 64;

// Inside a spin: x86's PAUSE, the processor makers' advice for spin-wait loops (the loop's exit
// when the word changes is not taken for a memory-order violation that flushes the pipeline; less
// power; an SMT sibling keeps the core's execution units).
inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

/// Looks until done() is true: spinning for spin_seconds, then yielding every `looks_per_yield`
/// looks; past the spin, on_clock(now) at every clock reading (a bounded wait fails from there).
template <class Done, class OnClock>
void spin_then_yield(unsigned looks_per_yield, Done done, OnClock on_clock) {
  using clock_type = std::chrono::steady_clock;
  const auto spin_until = clock_type::now() + std::chrono::duration<double>(spin_seconds);
  bool spinning = true;
  for (unsigned look = 1; !done(); ++look) {  // unsigned: a long wait wraps
    relax();
    if (look % looks_per_clock_reading == 0) {
      const auto now = clock_type::now();
      spinning = spinning && now < spin_until;
      if (!spinning) on_clock(now);
    }
    if (!spinning && look % looks_per_yield == 0) std::this_thread::yield();
  }
}

}  // namespace raceway::scheduler
