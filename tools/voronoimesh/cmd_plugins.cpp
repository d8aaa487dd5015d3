/// @file cmd_plugins.cpp
/// --plugin, the registry with plugin passes every pipeline command uses, and
/// `voronoimesh plugins`, which says what was found, loaded and refused.

#include "commands.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>

namespace vmcli {

void add_plugin_option(CLI::App* cmd, std::vector<std::string>& files) {
  cmd->add_option("--plugin", files,
                  "Load the pass plugin FILE (repeatable); plugins are also loaded from the folders of "
                  "VORONOIMESH_PLUGIN_PATH (colon-separated) and the installed plugin folder "
                  "(see 'voronoimesh plugins')")
      ->type_name("FILE")
      ->take_all()
      ->allow_extra_args(false);
}

vm::PassRegistry pass_registry(const std::vector<std::string>& files, bool quiet,
                               std::vector<vm::PluginRecord>* records) {
  vm::PassRegistry registry = vm::builtin_registry();
  std::vector<vm::PluginRecord> found = vm::load_plugins(registry, files);
  if (!quiet)
    for (const vm::PluginRecord& r : found) {
      if (!r.refused.empty()) std::fprintf(stderr, "voronoimesh: plugin skipped: %s\n", r.refused.c_str());
      if (r.shadowed)
        std::fprintf(stderr, "voronoimesh: plugin skipped: %s: a plugin named '%s' was loaded before, from %s\n",
                     r.file.c_str(), r.name.c_str(), r.shadowed_by.c_str());
      if (!r.warning.empty()) std::fprintf(stderr, "voronoimesh: warning: plugin %s\n", r.warning.c_str());
    }
  if (records) *records = std::move(found);
  return registry;
}

void add_plugins_command(CLI::App& app, int& exit_code) {
  auto files = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd = app.add_subcommand(
      "plugins", "List the plugin folders and the plugins found in them: what was loaded, with its passes, and what "
                 "was refused and why.");
  add_plugin_option(cmd, *files);
  cmd->callback([files, &exit_code] {
    exit_code = run_guarded([&] {
      std::vector<vm::PluginRecord> records;
      pass_registry(*files, true, &records);
      std::printf("Plugin folders (VORONOIMESH_PLUGIN_PATH, then the installed folder):\n");
      for (const std::string& dir : vm::plugin_search_path()) {
        std::error_code ec;
        std::printf("  %s%s\n", dir.c_str(), std::filesystem::is_directory(dir, ec) ? "" : "  (missing)");
      }
      size_t loaded = 0, refused = 0;
      std::printf("\n");
      for (const vm::PluginRecord& r : records) {
        if (!r.refused.empty()) {
          ++refused;
          std::printf("refused  %s (%s)\n         %s\n", r.file.c_str(), r.found_by.c_str(), r.refused.c_str());
        } else if (r.shadowed) {
          std::printf("skipped  %s %s  %s (%s): a plugin named '%s' was loaded before, from %s\n", r.name.c_str(),
                      r.version.c_str(), r.file.c_str(), r.found_by.c_str(), r.name.c_str(), r.shadowed_by.c_str());
        } else {
          ++loaded;
          std::string passes;
          for (const std::string& p : r.passes) passes += (passes.empty() ? "" : ", ") + p;
          std::printf("loaded   %s %s  %s (%s)\n         passes: %s\n", r.name.c_str(), r.version.c_str(),
                      r.file.c_str(), r.found_by.c_str(), passes.empty() ? "none" : passes.c_str());
          if (!r.warning.empty()) std::printf("         warning: %s\n", r.warning.c_str());
        }
      }
      std::printf("%s%zu loaded, %zu refused\n", records.empty() ? "" : "\n", loaded, refused);
      return kOk;
    });
  });
}

} // namespace vmcli
