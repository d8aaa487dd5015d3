/// @file main.cpp
/// The voronoimesh tool: its subcommands (commands.hpp) and how failures become exit codes.

#include "commands.hpp"
#include "interrupt.hpp"

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/core/version.hpp"

#include <csignal>
#include <cstdio>
#include <string>

namespace vmcli {

namespace {

/// The command line's name of a library option: "top_k" -> "--top-k".
std::string flag(std::string option) {
  for (char& c : option)
    if (c == '_') c = '-';
  return "--" + option;
}

} // namespace

int run_guarded(const std::function<int()>& body, bool report) {
  auto say = [&](const std::string& message) {
    if (report) std::fprintf(stderr, "voronoimesh: %s\n", message.c_str());
  };
  try {
    return body();
  } catch (const vm::InvalidOption& e) {
    say(vm::located(flag(e.option()), e.problem()));
    return kInvalidInput;
  } catch (const vm::InvalidInput& e) {
    say(e.what());
    return kInvalidInput;
  } catch (const vm::IoError& e) {
    say(e.what());
    return kIoError;
  } catch (const vm::TopologyError& e) {
    say(e.what());
    return kTopology;
  } catch (const vm::PluginError& e) {
    say(e.what());
    return kPlugin;
  } catch (const vm::Cancelled&) {
    say("interrupted; nothing was written");
    return kInterrupted;
  } catch (const std::bad_alloc&) {
    say("out of memory (try a smaller --grid)");
    return kInternal;
  } catch (const std::exception& e) {
    say(std::string("internal error: ") + e.what());
    return kInternal;
  }
}

} // namespace vmcli

int main(int argc, char** argv) {
  CLI::App app{"voronoimesh: meshes of interconnected surfaces via the Voronoi interface.\n"
               "Every interface between N phases becomes one triangle mesh whose surfaces meet\n"
               "along triple curves and at quadruple points by sharing edges (after R. I. Saye)."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "voronoimesh " + vm::library_version());
  int exit_code = 0;
  vmcli::install_interrupt_handlers();
  // Beyond a file-size limit (ulimit -f) a write fails with EFBIG, which the run
  // reports (removing its temporary files), instead of the signal killing it.
  std::signal(SIGXFSZ, SIG_IGN);
  vmcli::add_mesh_command(app, exit_code);
  vmcli::add_create_command(app, exit_code);
  vmcli::add_smooth_command(app, exit_code);
  vmcli::add_flip_command(app, exit_code);
  vmcli::add_passes_command(app, exit_code);
  vmcli::add_stats_command(app, exit_code);
  vmcli::add_plugins_command(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e); // --help, --version
    // One line and exit 2, as for every other bad input (CLI11 prints two and
    // exits with its own codes, 105 to 109). CLI11 checks required options
    // before it looks for unknown ones, so a misspelt option would be answered
    // with "--output is required"; the misspelling is named instead.
    const std::vector<std::string> unknown = app.remaining(true);
    const bool misspelt = dynamic_cast<const CLI::RequiredError*>(&e) && !unknown.empty();
    std::fprintf(stderr, "voronoimesh: %s (see --help)\n", misspelt ? CLI::ExtrasError(unknown).what() : e.what());
    return 2;
  }
  return exit_code;
}
