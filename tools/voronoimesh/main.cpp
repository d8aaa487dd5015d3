#include "commands.hpp"
#include "interrupt.hpp"

#include "voronoimesh/errors.hpp"
#include "voronoimesh/install_dirs.hpp"

#include <iostream>

namespace vmcli {

int run_guarded(const std::function<int()>& body, bool report) {
  try {
    return body();
  } catch (const vm::InvalidInput& e) {
    if (report) std::cerr << "voronoimesh: " << e.what() << "\n";
    return kInvalidInput;
  } catch (const vm::IoError& e) {
    if (report) std::cerr << "voronoimesh: " << e.what() << "\n";
    return kIoError;
  } catch (const vm::TopologyError& e) {
    if (report) std::cerr << "voronoimesh: " << e.what() << "\n";
    return kTopology;
  } catch (const Interrupted& e) {
    if (report) std::cerr << "voronoimesh: " << e.what() << "\n";
    return kInterrupted;
  } catch (const std::bad_alloc&) {
    if (report) std::cerr << "voronoimesh: out of memory (try a smaller --grid)\n";
    return kInternal;
  } catch (const std::exception& e) {
    if (report) std::cerr << "voronoimesh: internal error: " << e.what() << "\n";
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
  vmcli::add_mesh_command(app, exit_code);
  vmcli::add_create_command(app, exit_code);
  vmcli::add_smooth_commands(app, exit_code);
  vmcli::add_passes_command(app, exit_code);
  vmcli::add_stats_command(app, exit_code);
  vmcli::add_plugins_command(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e); // --help, --version
    // One line and exit 2, as for every other bad input (CLI11 prints two and
    // exits with its own codes, 105 to 109).
    std::fprintf(stderr, "voronoimesh: %s (see --help)\n", e.what());
    return 2;
  }
  return exit_code;
}
