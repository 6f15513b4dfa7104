// Placing one of the output's threads (the output thread, the chunk compressor) on a core of its
// own: the run driver finds a core no rank of the job is bound to (solver/driver/scene_on_ranks.cpp)
// and these threads are bound there, the rest of the process staying where mpirun put it.
#pragma once

#include <string>
#include <thread>

namespace raceway::h5 {

/// Binds `thread` alone to the logical CPU `core` (pthread_setaffinity_np: the C++ library has no
/// affinity call, and for one thread of our own the system call is all there is to it). Returns
/// the thread's affinity read back afterwards as a CPU list ("1", "0-3,6"), or "" when the system
/// refused (the thread then keeps the process's affinity).
std::string bind_thread_to_core(std::thread& thread, int core);

/// A CPU set as a list: "0-3,6" ("" when empty). `is_set(cpu)` says whether cpu < `count` is in it.
template <class IsSet>
std::string cpu_list(int count, IsSet is_set) {
  std::string list;
  for (int cpu = 0; cpu < count; ++cpu) {
    if (!is_set(cpu)) continue;
    int last = cpu;
    while (last + 1 < count && is_set(last + 1)) ++last;
    if (!list.empty()) list += ',';
    list += std::to_string(cpu);
    if (last > cpu) list.append(1, '-').append(std::to_string(last));
    cpu = last;
  }
  return list;
}

}  // namespace raceway::h5
