#pragma once
/// @file pass.hpp
/// A pass is one step of mesh improvement with named, typed parameters (smooth,
/// project, clamp, flip, stats, and any a plugin adds). Passes that move nodes
/// only add to a shared displacement buffer; the pipeline commits it at one point
/// (before a pass that does not move nodes, and at the end of every iteration),
/// so results never depend on thread count or scheduling.

#include "voronoimesh/field.hpp"
#include "voronoimesh/mesh.hpp"
#include "voronoimesh/stats.hpp"

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vm {

/// One parameter of a pass: its schema generates the CLI help, the `passes`
/// listing and the validation of pipelines, so they can never disagree.
struct ParamSpec {
  std::string name;
  double default_value = 0;
  double min = 0, max = 0; ///< accepted range, inclusive
  bool integer = false;
  std::string help;        ///< one line, with the paper's section or equation
};

/// Parameter values by name.
using ParamValues = std::map<std::string, double>;

/// What passes work on during one run of a pipeline.
struct PassContext {
  InterfaceMesh& mesh;
  const PhaseField* field = nullptr; ///< the original (unsnapped) phases; null if none given
  std::vector<Vec3> delta;           ///< pending displacement of every node
  bool pending = false;              ///< delta holds moves not yet committed
  int iteration = 0;
  size_t flips = 0;                  ///< flips in the current iteration
  /// Commit through the crossing guard (guard.hpp), so that no move makes two
  /// triangles intersect.
  bool guard_crossings = true;
  size_t undone_moves = 0;           ///< moves the guard undid in the current iteration
  std::optional<MeshStats> stats;    ///< set by the stats pass

  explicit PassContext(InterfaceMesh& m, const PhaseField* f = nullptr) : mesh(m), field(f) {}
  /// The displacement buffer, zeroed if nothing is pending.
  std::vector<Vec3>& displacement();
  /// Applies the pending displacement to the mesh (through the guard if on).
  void commit();
};

/// One configured pass, made by PassInfo::make from its parameters.
class Pass {
public:
  virtual ~Pass() = default;
  /// Does the pass's work on context.mesh for one iteration.
  virtual void run(PassContext& context) = 0;
};

/// A pass type: its name, summary, schema and how to make one.
struct PassInfo {
  std::string name;
  std::string summary;
  std::vector<ParamSpec> params;
  bool moves_nodes = false; ///< adds to the displacement buffer
  bool needs_field = false; ///< needs the phase functions
  std::function<std::unique_ptr<Pass>(const ParamValues&)> make;
};

} // namespace vm
