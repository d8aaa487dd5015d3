#pragma once
/// @file interrupt.hpp
/// Ctrl-C (SIGINT) and SIGTERM stop a run cleanly: the first one is noted and
/// the run stops at the next iteration or stage boundary, writing nothing; a
/// second one ends the process at once (the default action), as users expect.

#include <stdexcept>

namespace vmcli {

/// Thrown where a run notices an interrupt; run_guarded() reports it.
struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted; nothing was written") {}
};

/// Installs the SIGINT and SIGTERM handlers (main() calls it once).
void install_interrupt_handlers();
/// True once SIGINT or SIGTERM has arrived.
bool interrupted();
/// Throws Interrupted if interrupted().
void stop_if_interrupted();

} // namespace vmcli
