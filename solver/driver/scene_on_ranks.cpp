#include "solver/driver/scene_on_ranks.hpp"

#include "solver/driver/parallel_output.hpp"

#include <spdlog/spdlog.h>

#include <fmt/format.h>
#include <sched.h>
#include <unistd.h>

#include <cstdio>

#include "io/h5/output_lock.hpp"
#include "io/scene/scene_parser.hpp"
#include "solver/bearing/model.hpp"
#include "solver/numerics/newton_backends.hpp"
#include "solver/run/output_writer.hpp"
#include "solver/run/checkpoint.hpp"
#include "solver/run/run.hpp"

namespace raceway::driver {

volatile std::sig_atomic_t g_stop_signal = 0;

namespace {

extern "C" void on_stop_signal(int signal) { g_stop_signal = signal; }

void broadcast_string(MPI_Comm comm, int rank, std::string& s) {
  long long size = static_cast<long long>(s.size());
  MPI_Bcast(&size, 1, MPI_LONG_LONG, 0, comm);
  if (rank != 0) s.resize(static_cast<std::size_t>(size));
  MPI_Bcast(s.data(), static_cast<int>(size), MPI_CHAR, 0, comm);
}

}  // namespace

void install_stop_signals() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  action.sa_flags = SA_RESTART | SA_RESETHAND;
  sigemptyset(&action.sa_mask);
  for (const int signal : {SIGINT, SIGTERM, SIGUSR1}) sigaction(signal, &action, nullptr);
}

int exit_code_for(const std::exception& e) {
  if (dynamic_cast<const io::SceneError*>(&e) ||
      dynamic_cast<const solver::OptionsError*>(&e) || dynamic_cast<const io::OutputPathError*>(&e) ||
      dynamic_cast<const solver::ResumeRefused*>(&e))
    return 2;
  if (dynamic_cast<const solver::IntegrationFailure*>(&e)) return 3;
  if (dynamic_cast<const solver::RunInterrupted*>(&e)) return 4;
  return 1;
}

int exit_code_of(const std::function<int()>& command) {
  try {
    return command();
  } catch (const solver::RunInterrupted& e) {
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

bool output_thread_wanted(const std::string& mode, MPI_Comm world, std::string& why) {
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(world, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int ranks_on_node = 1;
  MPI_Comm_size(node, &ranks_on_node);
  MPI_Comm_free(&node);
  cpu_set_t mine;
  CPU_ZERO(&mine);
  const int my_cores = sched_getaffinity(0, sizeof mine, &mine) == 0 ? CPU_COUNT(&mine) : 1;
  const long node_cores = sysconf(_SC_NPROCESSORS_ONLN);
  const bool spare = my_cores > 1 && node_cores > ranks_on_node;
  const bool on = mode == "on" || (mode == "auto" && spare);
  why = fmt::format("output thread {} ({}: {} core(s) on this node, {} rank(s) on it, this rank may use {})",
                    on ? "on" : "off", mode == "auto" ? "auto" : "--output-thread " + mode, node_cores,
                    ranks_on_node, my_cores);
  return on;
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
    const io::Scene scene = io::parse_scene(source.text, source.source, source.overrides);
    if (!executor.await_start()) return;  // rank 0 failed before it had a model and says why
    solver::serve_scene(scene, [&](const scheduler::TaskCatalogue& c, const std::map<std::string, solver::SegmentSeries>& s) {
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
