/// @file core/version.cpp
/// library_version(): the version of the library a program runs with.

#include "voronoimesh/core/version.hpp"

namespace vm {

std::string library_version() { return VORONOIMESH_VERSION_STRING; }

} // namespace vm
