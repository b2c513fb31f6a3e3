#include "cli/interrupt.hpp"

#include <csignal>
#include <cstdlib>

namespace mastrom::cli {
namespace {

// Only a lock-free atomic flag may be written from a signal handler (C++17 [support.signal]).
volatile std::sig_atomic_t g_interrupted = 0;

extern "C" void onInterrupt(int signal_number) {
  if (g_interrupted != 0) {
    // Second signal: the user insists; end now with the default action.
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
    return;
  }
  g_interrupted = 1;
}

bool underMultiRankLauncher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* value = std::getenv(name); value != nullptr && std::atoi(value) > 1)
      return true;
  return false;
}

}  // namespace

void installInterruptHandlers() {
  if (underMultiRankLauncher()) return;
  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
}

bool interruptRequested() { return g_interrupted != 0; }

}  // namespace mastrom::cli
