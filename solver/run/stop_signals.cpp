#include "solver/run/stop_signals.hpp"

#include <pthread.h>

#include <csignal>
#include <cstdlib>
#include <thread>

namespace raceway::run {

namespace {

std::atomic<int> g_stop_request{0};
std::atomic<bool> g_accepting{false};

sigset_t stop_signal_set() {
  sigset_t set;
  sigemptyset(&set);
  for (const int signal : {SIGINT, SIGTERM, SIGUSR1}) sigaddset(&set, signal);
  return set;
}

/// Ends the process by `signal` as its default action does (the exit status says which signal).
[[noreturn]] void end_process_by(int signal) {
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  sigaction(signal, &default_action, nullptr);
  sigset_t one;
  sigemptyset(&one);
  sigaddset(&one, signal);
  pthread_sigmask(SIG_UNBLOCK, &one, nullptr);  // this thread only: the signal below is for it
  raise(signal);
  std::_Exit(128 + signal);  // not reached: the default action of the three ends the process
}

void watch_stop_signals(sigset_t set) {
  pthread_setname_np(pthread_self(), "raceway-signals");
  while (true) {
    int signal = 0;
    if (sigwait(&set, &signal) != 0) continue;
    int none = 0;
    if (g_accepting.load() && g_stop_request.compare_exchange_strong(none, signal)) continue;
    end_process_by(signal);
  }
}

}  // namespace

void take_stop_signals(bool accept_requests) {
  // Before the watching thread exists: no signal can find it not yet accepting.
  g_accepting.store(accept_requests);
  const sigset_t set = stop_signal_set();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  // Detached: it waits until the process ends (nothing to join; exit() does not wait for it).
  std::thread(watch_stop_signals, set).detach();
}

void accept_stop_requests() { g_accepting.store(true); }

const std::atomic<int>& stop_request() { return g_stop_request; }

}  // namespace raceway::run
