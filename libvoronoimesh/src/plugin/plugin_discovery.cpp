/// @file plugin/plugin_discovery.cpp
/// Where plugins are looked for, and loading all of them: a file the user names
/// must load, a file found in a folder is reported if it does not.

#include "plugin/plugin_file.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/plugin/plugins.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>

namespace vm {
namespace {

constexpr const char* kPathVariable = "VORONOIMESH_PLUGIN_PATH";

/// Shared libraries directly in `dir`, by name; none if it is missing.
std::vector<std::string> libraries_in(const std::string& dir) {
  namespace fs = std::filesystem;
  std::vector<std::string> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().extension() == ".so" && it->is_regular_file(ec)) out.push_back(it->path().string());
  std::sort(out.begin(), out.end());
  return out;
}

/// Why a plugin at `path` could have been put there by anyone (its file or folder
/// writable by all, a folder without the sticky bit), or "".
std::string writable_by_anyone(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && (st.st_mode & S_IWOTH))
    return located(path, "loaded, but anyone may write this file");
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (::stat(folder.empty() ? "." : folder.c_str(), &st) == 0 && (st.st_mode & S_IWOTH) && !(st.st_mode & S_ISVTX))
    return located(path, "loaded, but anyone may write its folder " + folder.string());
  return {};
}

} // namespace

std::vector<std::string> plugin_search_path() {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv(kPathVariable)) {
    const std::string list = env;
    for (size_t start = 0, colon = 0; colon != std::string::npos; start = colon + 1) {
      colon = list.find(':', start);
      std::string dir = list.substr(start, colon == std::string::npos ? std::string::npos : colon - start);
      if (!dir.empty()) dirs.push_back(std::move(dir));
    }
  }
  dirs.push_back(installed_plugin_dir());
  return dirs;
}

std::vector<PluginRecord> load_plugins(PassRegistry& registry, const std::vector<std::string>& files, bool search) {
  std::vector<PluginRecord> records;
  std::map<std::string, std::string> loaded; // plugin name -> its file
  auto load = [&](const std::string& path, const std::string& found_by) {
    PluginRecord record;
    record.file = path;
    record.found_by = found_by;
    record.warning = writable_by_anyone(path);
    const detail::OpenedPlugin plugin = detail::open_plugin(path);
    if (const auto first = loaded.find(plugin.name); first != loaded.end()) {
      record.name = plugin.name;
      record.version = plugin.version;
      record.shadowed = true;
      record.shadowed_by = first->second;
    } else {
      detail::add_plugin_passes(plugin, path, registry, record);
      loaded.emplace(plugin.name, path);
    }
    records.push_back(std::move(record));
  };
  for (const std::string& f : files) load(f, "--plugin");
  if (!search) return records;
  const std::vector<std::string> dirs = plugin_search_path();
  for (size_t d = 0; d < dirs.size(); ++d)
    for (const std::string& f : libraries_in(dirs[d])) {
      const std::string found_by = d + 1 < dirs.size() ? kPathVariable : "installed folder";
      try {
        load(f, found_by);
      } catch (const Error& e) {
        PluginRecord refused;
        refused.file = f;
        refused.found_by = found_by;
        refused.refused = e.what();
        records.push_back(std::move(refused));
      }
    }
  return records;
}

} // namespace vm
