/// @file plugin/plugin_dirs.cpp
/// installed_plugin_dir(): where the running library's plugins are installed.

#include "voronoimesh/plugin/plugins.hpp"

#include <dlfcn.h>

#include <filesystem>

namespace vm {

std::string installed_plugin_dir() {
  // dladdr names the file the dynamic loader mapped this function from: the
  // shared library itself, wherever the installed tree has been moved.
  Dl_info info{};
  if (dladdr(reinterpret_cast<const void*>(&installed_plugin_dir), &info) != 0 && info.dli_fname &&
      *info.dli_fname) {
    std::error_code ec;
    const std::filesystem::path library = std::filesystem::absolute(info.dli_fname, ec);
    if (!ec) return (library.parent_path() / VORONOIMESH_PLUGIN_SUBDIR).lexically_normal().string();
  }
  return VORONOIMESH_INSTALLED_PLUGIN_DIR;
}

} // namespace vm
