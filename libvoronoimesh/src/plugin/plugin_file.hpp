#pragma once
/// @file plugin_file.hpp
/// The two steps of loading a plugin, apart so that discovery can look at a
/// plugin's name before adding its passes (to skip a plugin found twice).

#include "voronoimesh/plugin/plugins.hpp"

#include <string>
#include <vector>

namespace vm::detail {

/// A plugin whose entry point has run, with the passes it described.
struct OpenedPlugin {
  std::string name, version;
  std::vector<PassInfo> passes; ///< each keeps the library loaded
};

/// dlopens `path`, checks its ABI version and runs its entry point. Throws as
/// load_plugin (plugin/plugins.hpp) does, except for name clashes.
OpenedPlugin open_plugin(const std::string& path);

/// Adds the passes of `plugin` (opened from `path`) to `registry`, all or none,
/// and fills `record`'s name, version and passes. Throws InvalidInput naming the
/// file if a pass name is taken.
void add_plugin_passes(const OpenedPlugin& plugin, const std::string& path, PassRegistry& registry,
                       PluginRecord& record);

} // namespace vm::detail
