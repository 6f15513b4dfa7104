// Child processes (the Python report, the campaign table): started without a shell, with the
// default signal mask, waited for.
#pragma once

#include <sys/types.h>

#include <functional>
#include <string>
#include <vector>

namespace raceway::report {

/// Runs args[0] with args (no shell; args[0] looked up in PATH unless it has a slash) and waits
/// for it: its exit status, or -1 with `error` saying why (could not start, killed by a signal).
/// The child starts with no signal blocked: raceway blocks its stop signals in every thread
/// (solver/run/stop_signals.hpp) and a mask is inherited across exec, so a child started as it is
/// would ignore Ctrl-C.
/// `while_waiting`, when given, is called with the child's pid about every 100 ms until it ends
/// (e.g. to pass a stop request on to it); without it the wait blocks.
int run_process(const std::vector<std::string>& args, std::string& error,
                const std::function<void(pid_t)>& while_waiting = {});

}  // namespace raceway::report
