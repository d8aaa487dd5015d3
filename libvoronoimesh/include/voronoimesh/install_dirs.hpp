#pragma once
/// @file install_dirs.hpp
/// Where the running library lives and where its plugins go, found at run time
/// so that an installed tree works wherever it is moved.

#include <string>

namespace vm {

/// The version of the library the program runs with, "MAJOR.MINOR.PATCH"
/// (VORONOIMESH_VERSION_STRING in version.hpp is the version it was compiled with).
std::string library_version();

/// The folder of installed plugins: "voronoimesh/plugins" beside the shared
/// library that holds this function (PREFIX/lib/voronoimesh/plugins once
/// installed, BUILD/lib/voronoimesh/plugins in the build tree). If the library
/// cannot find its own file, the folder configured at build time
/// (CMAKE_INSTALL_PREFIX/lib/voronoimesh/plugins). The folder may not exist.
/// Never throws.
std::string installed_plugin_dir();

} // namespace vm
