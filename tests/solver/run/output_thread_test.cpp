// The output thread (solver/run/output_thread.hpp): samples are worked in the order given with the
// states they were given, across the ring's wrap-around and while the run's thread waits on a full
// queue, with the rows handed with each; a failure reaches the run's thread; queued samples are
// worked before the thread ends.
#include "solver/run/output_thread.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace raceway::run {
namespace {

struct Seen {
  double t;
  long sample;
  std::vector<double> z, rows;
};

std::vector<double> state_of(long i) { return {static_cast<double>(i), -0.5 * static_cast<double>(i), 1e-3}; }
/// Rows of varying length (the ring's slots are reused with other lengths).
std::vector<double> rows_of(long i) {
  return std::vector<double>(static_cast<std::size_t>(i % 3), 2.0 * static_cast<double>(i));
}

TEST(OutputThread, WorksEverySampleInOrderWithItsState) {
  std::vector<Seen> seen;  // written by the output thread only, read after drain()
  OutputThread thread(
      3, [&](double t, long sample, const std::vector<double>& z, const std::vector<double>& rows) {
        seen.push_back({t, sample, z, rows});
      },
      /*capacity=*/4, /*batch=*/3);
  // The rows handed with a sample vary in length (the ring's slots are reused).
  for (long i = 0; i < 101; ++i)
    thread.submit(0.25 * static_cast<double>(i), i, state_of(i), rows_of(i));
  thread.drain();
  ASSERT_EQ(seen.size(), 101U);
  for (long i = 0; i < 101; ++i) {
    EXPECT_EQ(seen[static_cast<std::size_t>(i)].sample, i);
    EXPECT_EQ(seen[static_cast<std::size_t>(i)].t, 0.25 * static_cast<double>(i));
    EXPECT_EQ(seen[static_cast<std::size_t>(i)].z, state_of(i));
    EXPECT_EQ(seen[static_cast<std::size_t>(i)].rows, rows_of(i));
  }
  EXPECT_GE(thread.busy_seconds(), 0.0);
}

TEST(OutputThread, RunThreadWaitsOnAFullQueueAndLosesNothing) {
  std::vector<long> seen;
  OutputThread thread(1, [&](double, long sample, const std::vector<double>& z, const std::vector<double>&) {
    std::this_thread::sleep_for(std::chrono::microseconds(200));  // slower than the submitting thread
    EXPECT_EQ(z[0], static_cast<double>(sample));
    seen.push_back(sample);
  }, /*capacity=*/2, /*batch=*/2);
  for (long i = 0; i < 40; ++i) thread.submit(0, i, {static_cast<double>(i)}, {});
  thread.drain();
  ASSERT_EQ(seen.size(), 40U);
  for (long i = 0; i < 40; ++i) EXPECT_EQ(seen[static_cast<std::size_t>(i)], i);
}

TEST(OutputThread, AFailureReachesTheRunThreadAndStopsTheWork) {
  std::vector<long> seen;
  OutputThread thread(1, [&](double, long sample, const std::vector<double>&, const std::vector<double>&) {
    if (sample == 5) throw std::runtime_error("disk full at sample 5");
    seen.push_back(sample);
  }, 8, 4);
  for (long i = 0; i < 8; ++i) {
    try {
      thread.submit(0, i, {0.0}, {});
    } catch (const std::runtime_error&) {  // the failure may already be known at a later submit
      EXPECT_GT(i, 5);
      break;
    }
  }
  try {
    thread.drain();
    FAIL() << "drain() did not rethrow the failure";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "disk full at sample 5");
  }
  EXPECT_EQ(seen, (std::vector<long>{0, 1, 2, 3, 4}));  // nothing after the failed sample
  EXPECT_THROW(thread.submit(0, 8, {0.0}, {}), std::runtime_error);
  EXPECT_NO_THROW(thread.drain(/*rethrow=*/false));
}

TEST(OutputThread, QueuedSamplesAreWorkedBeforeTheThreadEnds) {
  std::vector<long> seen;
  {
    OutputThread thread(
        1, [&](double, long sample, const std::vector<double>&, const std::vector<double>&) { seen.push_back(sample); },
        64, 16);
    for (long i = 0; i < 5; ++i) thread.submit(0, i, {0.0}, {});  // fewer than a batch: never woken by submit
  }
  EXPECT_EQ(seen, (std::vector<long>{0, 1, 2, 3, 4}));
}

}  // namespace
}  // namespace raceway::run
