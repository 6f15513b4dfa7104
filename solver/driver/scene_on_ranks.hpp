// One scene run on the ranks of a communicator (the run driver's MPI side, shared by `raceway run`
// on MPI_COMM_WORLD and by `raceway campaign` on each group's communicator): the scene from the
// communicator's rank 0 to every rank, rank 0 integrating and the others serving contact tasks;
// the exit codes of errors (the stop signals: solver/run/stop_signals.hpp).
#pragma once

#include <mpi.h>

#include <exception>
#include <functional>
#include <string>
#include <vector>

#include "scheduler/mpi_executor.hpp"

namespace raceway::driver {

/// The documented exit code of an error: bad input 2, failed integration 3, stopped by a signal 4,
/// anything else 1.
int exit_code_for(const std::exception& e);

/// Runs a command and maps what it throws to its exit code, logging the message.
int exit_code_of(const std::function<int()>& command);

/// The MPI library's own version line (e.g. "Open MPI v4.1.4"), for the build attributes.
std::string mpi_library_version();

/// Where rank 0 runs the output's work (diagnostics at output times, rows, summary sums).
struct OutputThreadPlace {
  bool on = false;  ///< on a thread of its own
  int core = -1;    ///< the logical CPU that thread (and the chunk compressor) is bound to; -1: not bound
  std::string why;  ///< what was decided and why, for the log
};

/// Decides whether rank 0 runs the output's work on a thread of its own and where. `mode` "off"
/// decides off; "on" and "auto" look for a core no rank uses:
/// - rank 0 bound to fewer cores than the node lets the job use (mpirun binds a rank to a core):
///   the node's cores that no rank of `world` on it is bound to; the first of them, if any, takes
///   the output thread (bound there; auto turns it on). `may_bind` false (a campaign, whose group
///   leaders would all want it) skips this: no binding, and auto stays off.
/// - not bound: auto turns it on when this process may run on more than one core and the node has
///   more cores than ranks of `world` on it; the thread runs where the process may.
/// Otherwise the thread would take its time from a rank (measured: np = 2 on 2 cores 18 % slower
/// with it). Collective on `world`.
OutputThreadPlace place_output_thread(const std::string& mode, MPI_Comm world, bool may_bind = true);

/// Lets this process, and the processes it starts from here on, run on every core the job may use
/// on this node (its cgroup's cpuset, as hwloc reads it), not only the core mpirun bound it to: for
/// work after the ranks are done (a campaign's table and plots, drawn by a pool of processes).
/// Returns the number of cores it may now use.
int use_every_core_of_the_job();

/// What every rank of a run parses: the scene text, its source name and the --set overrides.
struct SceneSource {
  std::string text, source;
  std::vector<std::string> overrides;
};

/// Rank 0's scene to every rank of `comm`. Returns false on every rank when rank 0 could not read
/// one (`ok` false on rank 0: it reports why).
bool broadcast_scene(MPI_Comm comm, SceneSource& scene, bool ok);

/// A worker rank: builds the model of the scene and evaluates tasks until rank 0 stops it; with
/// `parallel_output` (every rank has the same command line) it keeps its diagnostics at output
/// times and takes part in the parallel output's writes on `comm` (the executor's). Any error here
/// ends the whole job (MPI_Abort) with this rank's message.
void serve_scene_tasks(const SceneSource& scene, scheduler::MpiExecutor& executor, MPI_Comm comm,
                       bool parallel_output = false);

}  // namespace raceway::driver
