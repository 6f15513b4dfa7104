#include "scheduler/campaign_dispatch.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <numeric>

namespace raceway::scheduler {

namespace {

constexpr int kResultTag = 71, kDiagnosisTag = 72, kAssignTag = 73;

double now() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace

CampaignGroups split_campaign_groups(MPI_Comm world, int ranks_per_group) {
  CampaignGroups g;
  MPI_Comm_rank(world, &g.world_rank);
  MPI_Comm_size(world, &g.world_size);
  g.ranks_per_group = std::clamp(ranks_per_group, 1, g.world_size);
  g.group_count = g.world_size / g.ranks_per_group;
  g.group_index = std::min(g.world_rank / g.ranks_per_group, g.group_count - 1);
  MPI_Comm_dup(world, &g.dispatch);
  MPI_Comm_split(world, g.group_index, g.world_rank, &g.group);
  MPI_Comm_rank(g.group, &g.group_rank);
  MPI_Comm_size(g.group, &g.group_size);
  return g;
}

void free_campaign_groups(CampaignGroups& g) {
  if (g.group != MPI_COMM_NULL) MPI_Comm_free(&g.group);
  if (g.dispatch != MPI_COMM_NULL) MPI_Comm_free(&g.dispatch);
}

CampaignDispatcher::CampaignDispatcher(const CampaignGroups& groups, std::vector<double> costs, std::vector<int> jobs,
                                       DispatchEvents events)
    : groups_(groups), costs_(std::move(costs)), queue_(std::move(jobs)), events_(std::move(events)) {
  // Longest predicted first (ties: the campaign's order), so that the long scenes do not end up
  // alone at the end.
  std::stable_sort(queue_.begin(), queue_.end(), [&](int a, int b) { return costs_[a] > costs_[b]; });
  thread_ = std::thread([this] { loop(); });
}

CampaignDispatcher::~CampaignDispatcher() {
  if (thread_.joinable()) thread_.join();
}

DispatchRecord CampaignDispatcher::join() {
  thread_.join();
  return record_;
}

void CampaignDispatcher::loop() {
  const double start = now();
  std::deque<JobAssignment> queue;
  for (const int j : queue_) queue.push_back({j, 0});
  std::vector<double> assigned_at(static_cast<std::size_t>(groups_.world_size), -1), released;
  int active = groups_.group_count;
  while (active > 0) {
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, kResultTag, groups_.dispatch, &flag, &status);
    if (!flag) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    const double asked = now();
    const int leader = status.MPI_SOURCE;
    double message[4];
    MPI_Recv(message, 4, MPI_DOUBLE, leader, kResultTag, groups_.dispatch, MPI_STATUS_IGNORE);
    JobResult result{static_cast<int>(message[0]), static_cast<int>(message[1]), static_cast<int>(message[2]),
                     message[3], {}};
    const int group = std::min(leader / groups_.ranks_per_group, groups_.group_count - 1);
    if (result.job >= 0) {
      MPI_Status diag;
      MPI_Probe(leader, kDiagnosisTag, groups_.dispatch, &diag);
      int length = 0;
      MPI_Get_count(&diag, MPI_CHAR, &length);
      result.diagnosis.resize(static_cast<std::size_t>(length));
      MPI_Recv(result.diagnosis.data(), length, MPI_CHAR, leader, kDiagnosisTag, groups_.dispatch, MPI_STATUS_IGNORE);
      record_.group_busy += asked - assigned_at[static_cast<std::size_t>(leader)];
      // Retried once: an error or an integration failure (exit 1, 3). Not: a stop (4), bad input (2),
      // which fails again the same way.
      const bool retry = (result.code == 1 || result.code == 3) && result.attempt == 0;
      if (retry) queue.push_front({result.job, 1});
      if (events_.on_finish) events_.on_finish(result, group, retry);
    }
    JobAssignment next;
    if (!queue.empty() && !(events_.stop_requested && events_.stop_requested())) {
      next = queue.front();
      queue.pop_front();
    }
    int reply[2] = {next.job, next.attempt};
    MPI_Send(reply, 2, MPI_INT, leader, kAssignTag, groups_.dispatch);
    record_.group_waiting += now() - asked;
    if (next.job >= 0) {
      assigned_at[static_cast<std::size_t>(leader)] = now();
      ++record_.assignments;
      if (events_.on_start) events_.on_start(next, group);
    } else {
      released.push_back(now());
      --active;
    }
  }
  record_.wall = now() - start;
  for (const double r : released) record_.group_idle_at_end += (start + record_.wall) - r;
}

JobAssignment request_job(const CampaignGroups& g, const JobResult& last) {
  double message[4] = {double(last.job), double(last.code), double(last.attempt), last.wall_seconds};
  MPI_Send(message, 4, MPI_DOUBLE, 0, kResultTag, g.dispatch);
  if (last.job >= 0)
    MPI_Send(last.diagnosis.data(), static_cast<int>(last.diagnosis.size()), MPI_CHAR, 0, kDiagnosisTag, g.dispatch);
  int reply[2];
  MPI_Recv(reply, 2, MPI_INT, 0, kAssignTag, g.dispatch, MPI_STATUS_IGNORE);
  return {reply[0], reply[1]};
}

void broadcast_waiting_idle(int& value, MPI_Comm comm) {
  MPI_Request request;
  MPI_Ibcast(&value, 1, MPI_INT, 0, comm, &request);
  for (int done = 0; MPI_Test(&request, &done, MPI_STATUS_IGNORE), !done;)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

JobAssignment share_job(const CampaignGroups& g, JobAssignment job) {
  int values[2] = {job.job, job.attempt};
  MPI_Bcast(values, 2, MPI_INT, 0, g.group);
  return {values[0], values[1]};
}

}  // namespace raceway::scheduler
