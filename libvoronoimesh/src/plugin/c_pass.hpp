#pragma once
/// @file c_pass.hpp
/// The adapter from a pass a plugin describes in C (plugin/plugin_abi.h) to a PassInfo
/// of the registry: it copies the description, and on every run lays the mesh
/// out as the C arrays of vm_mesh_view and turns a failure into InvalidInput.

#include "voronoimesh/improve/pass.hpp"
#include "voronoimesh/plugin/plugin_abi.h"

#include <memory>
#include <string>

namespace vm::detail {

/// A PassInfo that runs `desc` (copied; its strings may go away afterwards).
/// `library` is kept alive by every copy of the result and of the passes it
/// makes, so the plugin's code stays loaded while it can be called. `origin`
/// names the plugin in error messages. Throws InvalidInput if `desc` lacks a
/// name, summary or run function, or a parameter lacks a name.
PassInfo adapt_c_pass(const vm_pass_desc& desc, std::shared_ptr<void> library, const std::string& origin);

} // namespace vm::detail
