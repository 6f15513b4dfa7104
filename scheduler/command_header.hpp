// What rank 0's commands say: the header in front of every command buffer, with named fields.
// Pure (no MPI): the command channel (scheduler/command_channel.hpp) carries the buffer; the header
// round trip is unit-tested in tests/scheduler/command_header_test.cpp.
//
// A command is one fixed-size buffer of doubles (header, then the context or output payload), so a
// worker never needs to know in advance which command comes. Every field is an integer or a flag,
// exact in a double. Both ends run the same build, so the layout is private to this file.
#pragma once

#include <span>
#include <stdexcept>
#include <string>

namespace raceway::scheduler {

enum class CommandKind { start = 1, evaluate = 2, plan = 3, stop = 4, output = 5 };
const char* command_kind_name(CommandKind kind);

struct CommandHeader {
  CommandKind kind = CommandKind::stop;
  int phase = 0;        ///< evaluate, plan: the phase (Phase as int)
  int task_count = 0;   ///< start, evaluate, plan: the catalogue's tasks
  int record_size = 0;  ///< evaluate: the phase's record size; start: the largest phase's
  long number = 0;      ///< evaluate: the evaluation (all phases, from 1); plan: the plan's version
  int context_size = 0; ///< start: doubles of the context that follows every later command's header
  bool tail = false;             ///< start: the plans have a tail claimed on demand
  bool shared_exchange = false;  ///< start: commands and replies through the node window
};

/// Doubles of a header on the wire.
inline constexpr std::size_t command_header_size = 8;

/// Writes `header` into the first command_header_size doubles of `buffer`.
void write_header(const CommandHeader& header, std::span<double> buffer);
/// The header of `buffer`. Throws CommandError on what no rank 0 of this build sends (an unknown
/// kind, a phase out of range, a negative count).
CommandHeader read_header(std::span<const double> buffer, int phases);

struct CommandError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace raceway::scheduler
