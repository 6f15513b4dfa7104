#include "scheduler/command_header.hpp"

#include <cmath>

namespace raceway::scheduler {

namespace {

// Where each field lies in the buffer.
enum Slot : std::size_t { kind_slot, phase_slot, tasks_slot, record_slot, number_slot, context_slot, tail_slot,
                          exchange_slot, slot_count };
static_assert(slot_count == command_header_size);

/// An integer field back from its double; CommandError when it is none.
long integer(double value, const char* field) {
  if (!(std::isfinite(value) && value == std::floor(value) && std::fabs(value) < 9e15))
    throw CommandError(std::string("protocol error: the command's ") + field + " is not an integer");
  return static_cast<long>(value);
}

}  // namespace

const char* command_kind_name(CommandKind kind) {
  switch (kind) {
    case CommandKind::start: return "start";
    case CommandKind::evaluate: return "evaluate";
    case CommandKind::plan: return "plan";
    case CommandKind::stop: return "stop";
    case CommandKind::output: return "output";
  }
  return "?";
}

void write_header(const CommandHeader& h, std::span<double> buffer) {
  if (buffer.size() < command_header_size) throw std::invalid_argument("write_header: buffer shorter than a header");
  buffer[kind_slot] = static_cast<double>(static_cast<int>(h.kind));
  buffer[phase_slot] = h.phase;
  buffer[tasks_slot] = h.task_count;
  buffer[record_slot] = h.record_size;
  buffer[number_slot] = static_cast<double>(h.number);
  buffer[context_slot] = h.context_size;
  buffer[tail_slot] = h.tail ? 1.0 : 0.0;
  buffer[exchange_slot] = h.shared_exchange ? 1.0 : 0.0;
}

CommandHeader read_header(std::span<const double> buffer, int phases) {
  if (buffer.size() < command_header_size) throw CommandError("protocol error: a command shorter than its header");
  CommandHeader h;
  const long kind = integer(buffer[kind_slot], "kind");
  if (kind < static_cast<int>(CommandKind::start) || kind > static_cast<int>(CommandKind::output))
    throw CommandError("protocol error: unknown command " + std::to_string(kind) + " from rank 0");
  h.kind = static_cast<CommandKind>(kind);
  h.phase = static_cast<int>(integer(buffer[phase_slot], "phase"));
  if ((h.kind == CommandKind::evaluate || h.kind == CommandKind::plan) && (h.phase < 0 || h.phase >= phases))
    throw CommandError("protocol error: bad phase " + std::to_string(h.phase) + " from rank 0");
  h.task_count = static_cast<int>(integer(buffer[tasks_slot], "task count"));
  h.record_size = static_cast<int>(integer(buffer[record_slot], "record size"));
  h.number = integer(buffer[number_slot], "number");
  h.context_size = static_cast<int>(integer(buffer[context_slot], "context size"));
  if (h.task_count < 0 || h.record_size < 0 || h.context_size < 0 || h.number < 0)
    throw CommandError(std::string("protocol error: a negative count in a ") + command_kind_name(h.kind) + " command");
  const double tail = buffer[tail_slot], exchange = buffer[exchange_slot];
  if ((tail != 0 && tail != 1) || (exchange != 0 && exchange != 1))
    throw CommandError("protocol error: a command flag is neither 0 nor 1");
  h.tail = tail == 1;
  h.shared_exchange = exchange == 1;
  return h;
}

}  // namespace raceway::scheduler
