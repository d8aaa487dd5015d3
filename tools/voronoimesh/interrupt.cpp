/// @file interrupt.cpp
/// The signal handlers of interrupt.hpp.

#include "interrupt.hpp"

#include <csignal>

namespace vmcli {
namespace {

volatile std::sig_atomic_t g_interrupted = 0;

extern "C" void on_interrupt(int signal) {
  g_interrupted = 1;
  std::signal(signal, SIG_DFL); // a second Ctrl-C ends the process at once
}

} // namespace

void install_interrupt_handlers() {
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
}

bool interrupted() { return g_interrupted != 0; }

} // namespace vmcli
