#pragma once
/// @file improve/registry.hpp
/// The registry of pass types, shared by the library API, the CLI and plugins.

#include "voronoimesh/improve/pass.hpp"

#include <string>
#include <vector>

namespace vm {

/// The pass types a pipeline may name: the built-ins, and whatever a program or plugin adds.
class PassRegistry {
public:
  /// Adds a pass type.
  /// @param info the pass type; its name (a-z, 0-9, _ and -) must not be registered yet
  /// @throws InvalidInput if the name is taken or malformed, or a default lies outside its range
  void add(PassInfo info);
  /// The pass type called `name`.
  /// @param name the pass type's name
  /// @return the pass type, valid while the registry is alive and unchanged
  /// @throws InvalidInput naming the known passes, if there is none called `name`
  const PassInfo& get(const std::string& name) const;
  /// All pass types, by name.
  /// @return pointers into the registry, sorted by name
  std::vector<const PassInfo*> all() const;
  /// `given` checked against the schema of `pass` and completed with defaults.
  /// @param pass  the pass type's name
  /// @param given the parameter values given, by name
  /// @return a value for every parameter of the pass
  /// @throws InvalidInput for an unknown pass, an unknown parameter name, or a value out of range or not
  ///         an integer where one is needed
  ParamValues resolve(const std::string& pass, const ParamValues& given) const;

private:
  std::vector<PassInfo> passes_;
};

/// Registers smooth, project, clamp, flip and stats.
/// @param registry the registry to add them to; none of their names may be taken
/// @throws InvalidInput if a name is taken (PassRegistry::add())
void register_builtin_passes(PassRegistry& registry);

/// A registry with the built-in passes.
/// @return a new registry holding smooth, project, clamp, flip and stats
PassRegistry builtin_registry();

} // namespace vm
