// The stop signals (solver/run/stop_signals.hpp): each case runs in a child process of its own
// (a gtest death test, "threadsafe" style: the test binary started again), since taking the
// signals changes the process for good.
//
// The first case is the one that failed before: a SIGTERM arriving while METIS partitions (METIS
// puts its own SIGTERM handler in place for the length of every call) was swallowed by METIS,
// which then returned an error, and the run never learnt of it.
#include <gtest/gtest.h>
#include <metis.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "io/report/process.hpp"
#include "solver/run/stop_signals.hpp"

namespace {

using namespace std::chrono_literals;
using raceway::run::accept_stop_requests;
using raceway::run::stop_request;
using raceway::run::take_stop_signals;

/// A 2-way METIS partition of a ring of 400 vertices of unequal weights (about 0.1 ms): whether
/// METIS returned METIS_OK with every vertex in part 0 or 1.
bool partition_a_ring() {
  constexpr idx_t n = 400;
  std::vector<idx_t> xadj{0}, adjncy, vwgt;
  for (idx_t v = 0; v < n; ++v) {
    adjncy.push_back((v + n - 1) % n), adjncy.push_back((v + 1) % n);
    xadj.push_back(static_cast<idx_t>(adjncy.size()));
    vwgt.push_back(1 + (v * 37) % 11);
  }
  idx_t nv = n, ncon = 1, parts = 2, cut = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;
  std::vector<idx_t> part(n, -1);
  const int status = METIS_PartGraphKway(&nv, &ncon, xadj.data(), adjncy.data(), vwgt.data(), nullptr, nullptr,
                                         &parts, nullptr, nullptr, options, &cut, part.data());
  if (status != METIS_OK) return false;
  for (const idx_t p : part)
    if (p != 0 && p != 1) return false;
  return true;
}

/// The child of the first case: METIS partitions over and over while another thread sends `signal`
/// to the process; exits 0 if every partition succeeded and the signal was taken as a stop request.
[[noreturn]] void partition_while_signalled(int signal) {
  take_stop_signals();
  accept_stop_requests();
  std::thread sender([signal] {
    std::this_thread::sleep_for(30ms);
    kill(getpid(), signal);
  });
  int failed = 0, calls = 0, calls_after_request = 0;
  const auto start = std::chrono::steady_clock::now();
  while (calls_after_request < 200 && std::chrono::steady_clock::now() - start < 10s) {
    failed += partition_a_ring() ? 0 : 1;
    ++calls;
    if (stop_request().load() != 0) ++calls_after_request;
  }
  sender.join();
  std::fprintf(stderr, "%d partitions, %d failed; stop request %d (signal sent %d)\n", calls, failed,
               stop_request().load(), signal);
  std::exit(failed == 0 && stop_request().load() == signal ? 0 : 1);
}

class StopSignals : public testing::Test {
 protected:
  void SetUp() override { GTEST_FLAG_SET(death_test_style, "threadsafe"); }
};

TEST_F(StopSignals, SigtermWhileMetisPartitionsIsAStopRequest) {
  EXPECT_EXIT(partition_while_signalled(SIGTERM), testing::ExitedWithCode(0), "");
}

TEST_F(StopSignals, SigintAndSigusr1WhileMetisPartitionsAreStopRequests) {
  EXPECT_EXIT(partition_while_signalled(SIGINT), testing::ExitedWithCode(0), "");
  EXPECT_EXIT(partition_while_signalled(SIGUSR1), testing::ExitedWithCode(0), "");
}

/// Waits (at most 5 s) for a stop request; exits 3 if none comes.
void wait_for_request() {
  for (int i = 0; i < 500 && stop_request().load() == 0; ++i) std::this_thread::sleep_for(10ms);
  if (stop_request().load() == 0) std::exit(3);
}

TEST_F(StopSignals, ASecondSignalEndsTheProcess) {
  EXPECT_EXIT(
      {
        take_stop_signals();
        accept_stop_requests();
        kill(getpid(), SIGINT);
        wait_for_request();
        kill(getpid(), SIGINT);
        std::this_thread::sleep_for(5s);
        std::exit(0);
      },
      testing::KilledBySignal(SIGINT), "");
}

TEST_F(StopSignals, ARunAcceptsRequestsFromTheFirstMoment) {
  // `raceway run` and `raceway campaign` accept them as the signals are taken: Slurm's SIGUSR1 may
  // come within a second of the job's start, before MPI or the scene is ready.
  EXPECT_EXIT(
      {
        take_stop_signals(true);
        kill(getpid(), SIGUSR1);
        wait_for_request();
        std::exit(stop_request().load() == SIGUSR1 ? 0 : 1);
      },
      testing::ExitedWithCode(0), "");
}

TEST_F(StopSignals, BeforeRequestsAreAcceptedASignalEndsTheProcess) {
  // `raceway check` and `raceway report` never accept them: Ctrl-C ends them as usual.
  EXPECT_EXIT(
      {
        take_stop_signals();
        kill(getpid(), SIGTERM);
        std::this_thread::sleep_for(5s);
        std::exit(0);
      },
      testing::KilledBySignal(SIGTERM), "");
}

TEST_F(StopSignals, ChildProcessesStartWithTheSignalsUnblocked) {
  // A shell that sends itself SIGTERM: killed by it, unless it inherited the signal blocked (then
  // it sleeps and exits 0).
  EXPECT_EXIT(
      {
        take_stop_signals();
        accept_stop_requests();
        std::string error;
        const int status = raceway::report::run_process({"/bin/sh", "-c", "kill -TERM $$; sleep 5"}, error);
        std::fprintf(stderr, "status %d, %s\n", status, error.c_str());
        std::exit(status == -1 && error == "killed by signal 15" && stop_request().load() == 0 ? 0 : 1);
      },
      testing::ExitedWithCode(0), "");
}

}  // namespace
