// The command header (scheduler/command_header.hpp): every field survives the round trip through the
// wire buffer; what no rank 0 sends is refused with a protocol error.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <vector>

#include "scheduler/command_header.hpp"

using namespace raceway::scheduler;

namespace {
void expect_same(const CommandHeader& a, const CommandHeader& b) {
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.phase, b.phase);
  EXPECT_EQ(a.task_count, b.task_count);
  EXPECT_EQ(a.record_size, b.record_size);
  EXPECT_EQ(a.number, b.number);
  EXPECT_EQ(a.context_size, b.context_size);
  EXPECT_EQ(a.tail, b.tail);
  EXPECT_EQ(a.shared_exchange, b.shared_exchange);
}
}  // namespace

TEST(CommandHeader, EveryFieldSurvivesTheRoundTrip) {
  const CommandHeader headers[] = {
      {.kind = CommandKind::start, .task_count = 1234, .record_size = 57, .context_size = 301, .tail = true,
       .shared_exchange = false},
      {.kind = CommandKind::start, .task_count = 7, .record_size = 3, .context_size = 1, .tail = false,
       .shared_exchange = true},
      {.kind = CommandKind::evaluate, .phase = 1, .task_count = 99, .record_size = 40, .number = 123456789012L},
      {.kind = CommandKind::plan, .phase = 2, .task_count = 99, .number = 17},
      {.kind = CommandKind::output},
      {.kind = CommandKind::stop},
  };
  for (const auto& h : headers) {
    std::vector<double> buffer(command_header_size + 5, -1.0);
    write_header(h, buffer);
    EXPECT_EQ(buffer[command_header_size], -1.0) << "the payload after the header is left alone";
    expect_same(read_header(buffer, 3), h);
  }
}

TEST(CommandHeader, DistinctFieldsLandInDistinctSlots) {
  // A start with every field different: each value must come back from its own slot.
  CommandHeader h{.kind = CommandKind::start, .phase = 0, .task_count = 11, .record_size = 13, .number = 17,
                  .context_size = 19, .tail = true, .shared_exchange = true};
  std::vector<double> buffer(command_header_size);
  write_header(h, buffer);
  std::vector<double> sorted = buffer;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin() + 4, sorted.end()), sorted.end());  // 11, 13, 17, 19 once each
  expect_same(read_header(buffer, 3), h);
}

TEST(CommandHeader, WhatNoRankZeroSendsIsAProtocolError) {
  std::vector<double> buffer(command_header_size);
  write_header({.kind = CommandKind::evaluate, .phase = 1, .task_count = 3, .record_size = 2, .number = 5}, buffer);
  auto bad = buffer;
  bad[0] = 9;  // unknown kind
  EXPECT_THROW(read_header(bad, 3), CommandError);
  bad = buffer;
  bad[0] = 2.5;  // not an integer
  EXPECT_THROW(read_header(bad, 3), CommandError);
  EXPECT_THROW(read_header(buffer, 1), CommandError);  // phase 1 of a single phase
  bad = buffer;
  bad[2] = -3;  // negative task count
  EXPECT_THROW(read_header(bad, 3), CommandError);
  bad = buffer;
  bad[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(read_header(bad, 3), CommandError);
  EXPECT_THROW(read_header(std::vector<double>(command_header_size - 1, 0.0), 3), CommandError);
  std::vector<double> short_buffer(3);
  EXPECT_THROW(write_header({}, short_buffer), std::invalid_argument);
}
