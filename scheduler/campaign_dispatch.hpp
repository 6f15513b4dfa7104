// A campaign's ranks: MPI_COMM_WORLD split into groups that each run one scene at a time, and a
// dispatcher on world rank 0 (a thread beside that rank's own group work) that hands the scenes to
// free groups, longest predicted first, and retries a failed one once. Knows jobs, costs and exit
// codes, never physics; the run driver (solver/driver/campaign_command.cpp) runs the scenes.
//
// Protocol, on a duplicate of the world communicator: a group's leader (its rank 0) sends the
// result of its last job (none at first) to world rank 0 and receives its next job (or none left);
// the leader shares the job with its group. Exit code 4 (stopped by a signal after a checkpoint) is
// never retried: the job is left for --resume.
#pragma once

#include <mpi.h>

#include <functional>
#include <string>
#include <thread>
#include <vector>

namespace raceway::scheduler {

struct CampaignGroups {
  MPI_Comm dispatch = MPI_COMM_NULL;  ///< duplicate of the world: leaders <-> dispatcher
  MPI_Comm group = MPI_COMM_NULL;     ///< this rank's group: one scene's ranks
  int world_rank = 0, world_size = 1, group_index = 0, group_count = 1, group_rank = 0, group_size = 1;
  int ranks_per_group = 1;  ///< world rank r is in group min(r / ranks_per_group, group_count - 1)
  bool leader() const { return group_rank == 0; }
};

/// Groups of `ranks_per_group` consecutive world ranks (the last group takes the remainder, so
/// every rank works); collective over `world`. Free with free_campaign_groups.
CampaignGroups split_campaign_groups(MPI_Comm world, int ranks_per_group);
void free_campaign_groups(CampaignGroups& groups);

/// A job's outcome, from the leader of the group that ran it.
struct JobResult {
  int job = -1;      ///< -1: no job (a leader's first request)
  int code = 0;      ///< the run's exit code
  int attempt = 0;   ///< 0 first, 1 retry
  double wall_seconds = 0;
  std::string diagnosis;  ///< the error, when code != 0
};

/// A job handed to a group: index, attempt; job -1: none left, stop.
struct JobAssignment {
  int job = -1, attempt = 0;
};

struct DispatchEvents {
  std::function<void(const JobAssignment&, int group)> on_start;
  /// `retry`: a failed first attempt, queued again.
  std::function<void(const JobResult&, int group, bool retry)> on_finish;
  /// Checked before every assignment: true (a stop signal) hands out no new job.
  std::function<bool()> stop_requested;
};

/// Time accounting of a campaign, in seconds of wall clock.
struct DispatchRecord {
  double wall = 0;               ///< from start() to the last group's release
  double group_busy = 0;         ///< summed over groups: between receiving a job and reporting it
  double group_waiting = 0;      ///< summed over groups: between a request and its answer
  double group_idle_at_end = 0;  ///< summed over groups: released before the last one (no job left)
  long assignments = 0;
};

/// World rank 0: runs the dispatch loop on its own thread (MPI_THREAD_MULTIPLE), so that this
/// rank's group works too. It polls for requests (MPI_Iprobe every 2 ms) rather than blocking in
/// MPI_Recv, which would keep a core busy in Open MPI.
class CampaignDispatcher {
 public:
  CampaignDispatcher(const CampaignGroups& groups, std::vector<double> costs, std::vector<int> jobs, DispatchEvents events);
  ~CampaignDispatcher();
  /// Waits until every group has been released; the record of the campaign.
  DispatchRecord join();

 private:
  void loop();
  const CampaignGroups& groups_;
  std::vector<double> costs_;
  std::vector<int> queue_;  ///< jobs in dispatch order, retries in front
  DispatchEvents events_;
  DispatchRecord record_;
  std::thread thread_;
};

/// A group leader: reports `last` (job -1: nothing yet) and receives the next assignment.
JobAssignment request_job(const CampaignGroups& groups, const JobResult& last);
/// `value` from rank 0 of `comm` to all its ranks, waiting by polling every 5 ms (MPI_Ibcast,
/// MPI_Test) instead of in MPI_Bcast, which spins a core in Open MPI: a rank whose group has no
/// scene left waits so for the others without taking their CPU.
void broadcast_waiting_idle(int& value, MPI_Comm comm);

/// Every rank of a group: the leader's assignment.
JobAssignment share_job(const CampaignGroups& groups, JobAssignment job);

}  // namespace raceway::scheduler
