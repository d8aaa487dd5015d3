#pragma once
/// @file commands.hpp
/// The subcommands of the voronoimesh tool. Each registers itself on the app
/// and runs through run_guarded(), which turns library exceptions into a one-line
/// message and the exit codes below.

#include <CLI/CLI.hpp>

#include <functional>

namespace vmcli {

enum ExitCode : int {
  kOk = 0,
  kInvalidInput = 2, ///< bad scene, bad option value
  kIoError = 3,      ///< a file could not be read or written
  kTopology = 4,     ///< the mesh failed validation
  kInternal = 5,     ///< anything else (a bug)
};

/// Runs `body`, printing "voronoimesh: <message>" for any exception and
/// returning the matching exit code.
int run_guarded(const std::function<int()>& body);

void add_create_command(CLI::App& app, int& exit_code);
void add_stats_command(CLI::App& app, int& exit_code);

} // namespace vmcli
