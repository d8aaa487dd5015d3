#pragma once
/// @file registry.hpp
/// The registry of pass types, shared by the library API, the CLI and plugins.

#include "voronoimesh/pass.hpp"

#include <string>
#include <vector>

namespace vm {

/// The pass types a pipeline may name: the built-ins, and whatever a program or plugin adds.
class PassRegistry {
public:
  /// Adds a pass type. Throws InvalidInput if the name is taken or malformed, or
  /// a default lies outside its range.
  void add(PassInfo info);
  /// The pass type called `name`; throws InvalidInput naming the known passes.
  const PassInfo& get(const std::string& name) const;
  /// All pass types, by name.
  std::vector<const PassInfo*> all() const;
  /// `given` checked against the schema of `pass` (unknown names, values out of
  /// range or not integers throw InvalidInput) and completed with defaults.
  ParamValues resolve(const std::string& pass, const ParamValues& given) const;

private:
  std::vector<PassInfo> passes_;
};

/// Registers smooth, project, clamp, flip and stats.
void register_builtin_passes(PassRegistry& registry);

/// A registry with the built-in passes.
PassRegistry builtin_registry();

} // namespace vm
