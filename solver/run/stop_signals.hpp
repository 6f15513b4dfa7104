// The stop signals, SIGINT, SIGTERM and SIGUSR1 (what a batch scheduler sends before a time limit):
// the first asks a run for a checkpoint and a stop at its next output time, a second ends the
// process at once.
//
// They are taken by one thread that waits for them (sigwait), never by a signal handler: every
// other thread of the process blocks them. A handler would run in whichever thread the kernel
// picks, under whatever disposition is in place at that moment, and METIS replaces the handler of
// SIGTERM (and SIGABRT) for the length of every partitioning call with its own, which jumps
// (longjmp) back into METIS's error exit. A SIGTERM arriving then was swallowed (METIS returned an
// error, the run went on to the end and exited 0) or, landing on one of MPI's threads, jumped
// into another thread's stack (the process ended on SIGABRT). Blocked signals wait for the
// watching thread whatever METIS, MPI or PETSc do with the dispositions. (A signal mask is inherited
// across fork and exec: child processes are started with an empty one, io/report/process.hpp.)
#pragma once

#include <atomic>

namespace raceway::run {

/// Blocks the stop signals in the calling thread, which every thread it creates afterwards
/// inherits, and starts the thread that takes them. Call it first in main(), before any library
/// starts a thread (MPI_Init does); once per process. With `accept_requests` (a run, a campaign)
/// a stop signal is a stop request from this moment on: a batch scheduler may send its warning
/// within a second of the job's start, while MPI starts or the scene loads, and the run then
/// stops at its first output time (exit 4). Without it, until accept_stop_requests, a stop signal
/// ends the process as it would without raceway (a `check` or a `report` is not asked to stop).
void take_stop_signals(bool accept_requests = false);

/// From now on the first stop signal asks for a stop (stop_request() names it) and a second ends
/// the process.
void accept_stop_requests();

/// The signal that asked for a stop, 0 for none: rank 0's run loop reads it at every output time.
const std::atomic<int>& stop_request();

}  // namespace raceway::run
