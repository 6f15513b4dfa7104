#include "io/h5/thread_core.hpp"

#include <pthread.h>
#include <sched.h>

namespace raceway::h5 {

std::string bind_thread_to_core(std::thread& thread, int core) {
  if (core < 0 || core >= CPU_SETSIZE) return "";
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(core, &set);
  if (pthread_setaffinity_np(thread.native_handle(), sizeof set, &set) != 0) return "";
  CPU_ZERO(&set);
  if (pthread_getaffinity_np(thread.native_handle(), sizeof set, &set) != 0) return "";
  return cpu_list(CPU_SETSIZE, [&](int cpu) { return CPU_ISSET(cpu, &set) != 0; });
}

}  // namespace raceway::h5
