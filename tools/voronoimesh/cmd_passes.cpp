#include "commands.hpp"

#include "voronoimesh/registry.hpp"

#include <cstdio>

namespace vmcli {

void add_passes_command(CLI::App& app, int& exit_code) {
  CLI::App* cmd = app.add_subcommand("passes", "List the passes a pipeline can use, with their parameters and defaults.");
  cmd->callback([&exit_code] {
    exit_code = run_guarded([] {
      const vm::PassRegistry registry = vm::builtin_registry();
      std::printf("Passes (use as --pipeline name,name:param=value,...; default: %s)\n\n", vm::kDefaultPipeline);
      for (const vm::PassInfo* p : registry.all()) {
        std::printf("%s%s\n  %s\n", p->name.c_str(), p->needs_field ? "  [needs the phase functions]" : "",
                    p->summary.c_str());
        for (const vm::ParamSpec& s : p->params)
          std::printf("    %-18s %-10g %s [%g, %g]%s\n", s.name.c_str(), s.default_value, s.help.c_str(), s.min, s.max,
                      s.integer ? ", integer" : "");
        std::printf("\n");
      }
      return kOk;
    });
  });
}

} // namespace vmcli
