// Ctrl-C and SIGTERM as a request to stop (stop_signal.hpp).

#include "stop_signal.hpp"

#include <csignal>

namespace comply::app {
namespace {

std::atomic<bool> stop_requested{false};  // lock-free: set from a signal handler

extern "C" void onStopSignal(int /*signal*/) {
  stop_requested.store(true);
}

}  // namespace

std::atomic<bool>& stopOnSignals() {
  stop_requested = false;
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  return stop_requested;
}

}  // namespace comply::app
