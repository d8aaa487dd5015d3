#include "commands.hpp"

#include "voronoimesh/improve/registry.hpp"

#include <cstdio>
#include <map>
#include <memory>

namespace vmcli {

void add_passes_command(CLI::App& app, int& exit_code) {
  auto files = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd = app.add_subcommand(
      "passes", "List the passes a pipeline can use (built-in and from plugins), with their parameters and defaults.");
  add_plugin_option(cmd, *files);
  cmd->callback([files, &exit_code] {
    exit_code = run_guarded([&] {
      std::vector<vm::PluginRecord> plugins;
      const vm::PassRegistry registry = pass_registry(*files, false, &plugins);
      std::map<std::string, std::string> origin; // pass name -> "plugin NAME VERSION"
      for (const vm::PluginRecord& r : plugins)
        for (const std::string& p : r.passes) origin[p] = "  [plugin " + r.name + " " + r.version + "]";
      std::printf("Passes (use as --pipeline name,name:param=value,...; default: %s; for label volumes: %s; for a "
                  "mesh read from a file and under --mpi: %s)\n\n",
                  vm::kScenePipeline, vm::kLabelVolumePipeline, vm::kDefaultPipeline);
      for (const vm::PassInfo* p : registry.all()) {
        std::printf("%s%s%s\n  %s\n", p->name.c_str(), origin[p->name].c_str(),
                    p->needs_field ? "  [needs the phase functions]" : "", p->summary.c_str());
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
