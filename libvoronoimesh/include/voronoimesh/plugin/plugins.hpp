#pragma once
/// @file plugin/plugins.hpp
/// Loading pass plugins (shared libraries speaking plugin/plugin_abi.h) into a
/// PassRegistry, and finding them: files named by the user, the folders of
/// VORONOIMESH_PLUGIN_PATH, and the installed plugin folder. A loaded plugin's
/// passes are ordinary PassInfo entries: `passes` lists them, pipelines use them
/// by name, and the library stays loaded as long as any copy of them exists.

#include "voronoimesh/improve/registry.hpp"

#include <string>
#include <vector>

namespace vm {

/// What happened to one plugin file.
struct PluginRecord {
  std::string file;                ///< the path as found
  std::string found_by;            ///< "--plugin", "VORONOIMESH_PLUGIN_PATH" or "installed folder"
  /// The plugin's name, as it names itself (empty if refused early).
  std::string name, version;       ///< the plugin's version, as it names itself (empty if refused early)
  std::vector<std::string> passes; ///< the passes it added
  /// Empty when loaded; otherwise the one-line reason it was not ("path: problem").
  std::string refused;
  /// True when it was skipped because a plugin of the same name was loaded before
  /// (the same plugin found twice, e.g. in the build tree and installed).
  bool shadowed = false;
  /// With `shadowed`: the file of the plugin of that name that was loaded.
  std::string shadowed_by;
  /// Empty, or a reason to doubt a plugin that was loaded all the same: its file or
  /// folder can be written by anyone, so anyone could have put it there.
  std::string warning;
};

/// Loads the plugin at `path` and adds its passes to `registry`, all or none.
/// @param path     the plugin's shared library
/// @param registry the registry to add its passes to; unchanged if the plugin is refused
/// @return what was loaded: the file, the plugin's name and version, and its passes (found_by is left
///         empty)
/// @throws InvalidInput with a one-line message naming the file, if it is not a shared library, has no
///         voronoimesh_plugin_v1 entry point, was built for another plugin ABI version
///         (plugin/plugin_abi.h), fails to register, or adds a pass whose name is taken
/// @throws IoError if the file cannot be read
PluginRecord load_plugin(const std::string& path, PassRegistry& registry);

/// The folder of installed plugins: "voronoimesh/plugins" beside the shared
/// library that holds this function (PREFIX/lib/voronoimesh/plugins once
/// installed, BUILD/lib/voronoimesh/plugins in the build tree), found at run time
/// so that an installed tree works wherever it is moved. If the library cannot
/// find its own file, the folder configured at build time
/// (CMAKE_INSTALL_PREFIX/lib/voronoimesh/plugins). The folder may not exist.
/// Never throws.
/// @return the folder's path
std::string installed_plugin_dir();

/// The folders searched for plugins, in order: each entry of the colon-separated
/// VORONOIMESH_PLUGIN_PATH, then installed_plugin_dir().
/// @return the folders; empty entries of VORONOIMESH_PLUGIN_PATH are skipped
std::vector<std::string> plugin_search_path();

/// Loads every file in `files` (a failure throws, as load_plugin), then, if
/// `search`, every shared library (*.so) in plugin_search_path(), in name order
/// per folder. A discovered file that fails is recorded with its reason, not
/// thrown; one whose plugin name was already loaded is recorded as shadowed.
/// Missing folders are skipped.
/// @param registry the registry to add the plugins' passes to
/// @param files    plugin files named by the user (found_by "--plugin"), loaded first
/// @param search   also load the plugins of plugin_search_path()
/// @return one record per file, loaded, shadowed or refused, in the order they were met
/// @throws InvalidInput as load_plugin(), for a file of `files`
/// @throws IoError      as load_plugin(), for a file of `files`
std::vector<PluginRecord> load_plugins(PassRegistry& registry, const std::vector<std::string>& files,
                                       bool search = true);

} // namespace vm
