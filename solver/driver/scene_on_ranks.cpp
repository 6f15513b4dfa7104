#include "solver/driver/scene_on_ranks.hpp"

#include "solver/driver/parallel_output.hpp"

#include <spdlog/spdlog.h>

#include <fmt/format.h>
#include <hwloc.h>
#include <hwloc/glibc-sched.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "io/h5/output_lock.hpp"
#include "io/scene/scene_parser.hpp"
#include "solver/bearing/model.hpp"
#include "solver/numerics/newton_backends.hpp"
#include "solver/run/output_writer.hpp"
#include "solver/run/checkpoint.hpp"
#include "solver/run/run.hpp"

namespace raceway::driver {

namespace {

void broadcast_string(MPI_Comm comm, int rank, std::string& s) {
  long long size = static_cast<long long>(s.size());
  MPI_Bcast(&size, 1, MPI_LONG_LONG, 0, comm);
  if (rank != 0) s.resize(static_cast<std::size_t>(size));
  MPI_Bcast(s.data(), static_cast<int>(size), MPI_CHAR, 0, comm);
}

}  // namespace

int exit_code_for(const std::exception& e) {
  if (dynamic_cast<const scene::SceneError*>(&e) ||
      dynamic_cast<const numerics::OptionsError*>(&e) || dynamic_cast<const h5::OutputPathError*>(&e) ||
      dynamic_cast<const run::ResumeRefused*>(&e))
    return 2;
  if (dynamic_cast<const numerics::IntegrationFailure*>(&e)) return 3;
  if (dynamic_cast<const run::RunInterrupted*>(&e)) return 4;
  return 1;
}

int exit_code_of(const std::function<int()>& command) {
  try {
    return command();
  } catch (const run::RunInterrupted& e) {
    spdlog::warn("{}", e.what());
    return exit_code_for(e);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return exit_code_for(e);
  }
}

std::string mpi_library_version() {
  char text[MPI_MAX_LIBRARY_VERSION_STRING] = {};
  int length = 0;
  MPI_Get_library_version(text, &length);
  std::string s(text, static_cast<std::size_t>(length));
  return s.substr(0, s.find_first_of(",\n"));
}

namespace {

/// The logical CPUs the job may use on this node: its cgroup's cpuset and the online CPUs, as hwloc
/// reads them (cgroup v1 or v2), not this process's affinity, which mpirun's binding narrows.
/// Empty if hwloc cannot tell.
cpu_set_t cpus_the_job_may_use() {
  cpu_set_t set;
  CPU_ZERO(&set);
  hwloc_topology_t topology = nullptr;
  if (hwloc_topology_init(&topology) != 0) return set;
  if (hwloc_topology_load(topology) == 0)
    hwloc_cpuset_to_glibc_sched_affinity(topology, hwloc_topology_get_allowed_cpuset(topology), &set, sizeof set);
  hwloc_topology_destroy(topology);
  return set;
}

/// The first CPU of `allowed` that no mask of `ranks` holds; -1 if none.
int first_cpu_free_of(const cpu_set_t& allowed, const std::vector<cpu_set_t>& ranks) {
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
    if (CPU_ISSET(cpu, &allowed) &&
        std::none_of(ranks.begin(), ranks.end(), [&](const cpu_set_t& r) { return CPU_ISSET(cpu, &r) != 0; }))
      return cpu;
  return -1;
}

}  // namespace

// Finding a core that no rank of the job is bound to is written here by hand: MPI says nothing
// about its ranks' bindings, and hwloc knows the machine and this process but not the other ranks;
// each rank's affinity is gathered over the node (the ranks of other jobs on a shared node are not
// seen: their cores are outside this job's cgroup when the batch system confines jobs).
OutputThreadPlace place_output_thread(const std::string& mode, MPI_Comm world, bool may_bind) {
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(world, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int ranks_on_node = 1, world_rank = 0;
  MPI_Comm_size(node, &ranks_on_node);
  MPI_Comm_rank(world, &world_rank);
  cpu_set_t mine;
  CPU_ZERO(&mine);
  const bool known = sched_getaffinity(0, sizeof mine, &mine) == 0;
  const int my_cores = known ? CPU_COUNT(&mine) : 1;
  std::vector<cpu_set_t> masks(static_cast<std::size_t>(ranks_on_node));
  if (may_bind)
    MPI_Allgather(&mine, sizeof mine, MPI_BYTE, masks.data(), sizeof mine, MPI_BYTE, node);
  MPI_Comm_free(&node);
  // Only world rank 0 runs an output thread in `raceway run`; the others keep the plain rule. A
  // process that may run on every online CPU is not bound: then the cgroup cannot allow more, and
  // hwloc's topology (3-12 ms at every start here) is not read.
  const bool narrowed = known && my_cores < sysconf(_SC_NPROCESSORS_ONLN);
  const cpu_set_t allowed =
      may_bind && narrowed && world_rank == 0 && mode != "off" ? cpus_the_job_may_use() : cpu_set_t{};
  const int allowed_cores = CPU_COUNT(&allowed);
  const long node_cores = allowed_cores > 0 ? allowed_cores : sysconf(_SC_NPROCESSORS_ONLN);
  const bool bound = known && allowed_cores > 0 && my_cores < allowed_cores;
  OutputThreadPlace place;
  std::string where;
  if (bound) {
    place.core = first_cpu_free_of(allowed, masks);
    place.on = mode == "on" || (mode == "auto" && place.core >= 0);
    where = place.core >= 0 ? fmt::format("; core {} is free of ranks{}", place.core, place.on ? ": the thread is bound there" : "")
                            : std::string("; every core the job may use here has a rank bound to it");
    if (!place.on) place.core = -1;
  } else {
    place.on = mode == "on" || (mode == "auto" && my_cores > 1 && node_cores > ranks_on_node);
  }
  place.why = fmt::format("output thread {} ({}: {} core(s) on this node, {} rank(s) on it, this rank may use {}{})",
                          place.on ? "on" : "off", mode == "auto" ? "auto" : "--output-thread " + mode, node_cores,
                          ranks_on_node, my_cores, where);
  return place;
}

int use_every_core_of_the_job() {
  cpu_set_t mine;
  CPU_ZERO(&mine);
  const cpu_set_t allowed = cpus_the_job_may_use();
  if (sched_getaffinity(0, sizeof mine, &mine) != 0 || CPU_COUNT(&allowed) <= CPU_COUNT(&mine)) return CPU_COUNT(&mine);
  return sched_setaffinity(0, sizeof allowed, &allowed) == 0 ? CPU_COUNT(&allowed) : CPU_COUNT(&mine);
}

bool broadcast_scene(MPI_Comm comm, SceneSource& scene, bool ok) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  int go = ok ? 1 : 0;
  MPI_Bcast(&go, 1, MPI_INT, 0, comm);
  if (go == 0) return false;
  broadcast_string(comm, rank, scene.text);
  broadcast_string(comm, rank, scene.source);
  long long count = static_cast<long long>(scene.overrides.size());
  MPI_Bcast(&count, 1, MPI_LONG_LONG, 0, comm);
  scene.overrides.resize(static_cast<std::size_t>(count));
  for (std::string& o : scene.overrides) broadcast_string(comm, rank, o);
  return true;
}

void serve_scene_tasks(const SceneSource& source, scheduler::MpiExecutor& executor, MPI_Comm comm,
                       bool parallel_output) {
  try {
    const scene::Scene scene = scene::parse_scene(source.text, source.source, source.overrides);
    if (!executor.await_start()) return;  // rank 0 failed before it had a model and says why
    run::serve_scene(scene, [&](const scheduler::TaskCatalogue& c, const std::map<std::string, run::SegmentSeries>& s) {
      if (!parallel_output) return executor.serve(c);  // no handler: no records kept per evaluation
      WorkerOutput output(comm, s);  // the parallel output's samples and writes
      executor.serve(c, [&](std::span<const double> payload, std::span<const int> tasks, std::span<const double> records) {
        output(payload, tasks, records);
      });
    });
  } catch (const std::exception& e) {
    std::fprintf(stderr, "[raceway] rank %d: error: %s\n", executor.rank(), e.what());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
}

}  // namespace raceway::driver
