#pragma once
/// @file interrupt.hpp
/// Ctrl-C (SIGINT) and SIGTERM stop a run cleanly: the first one is noted and
/// the run stops at the next iteration or stage boundary (Report asks the
/// library to stop; it throws vm::Cancelled), writing nothing; a second one
/// ends the process at once (the default action), as users expect.

namespace vmcli {

/// Installs the SIGINT and SIGTERM handlers (main() calls it once).
void install_interrupt_handlers();
/// True once SIGINT or SIGTERM has arrived.
bool interrupted();

} // namespace vmcli
