#pragma once
/// @file improve/pass.hpp
/// A pass is one step of mesh improvement with named, typed parameters (smooth,
/// project, clamp, flip, stats, and any a plugin adds). Passes that move nodes
/// only add to a shared displacement buffer; the pipeline commits it at one point
/// (before a pass that does not move nodes, and at the end of every iteration),
/// so results never depend on thread count or scheduling.

#include "voronoimesh/check/stats.hpp"
#include "voronoimesh/fields/phase_field.hpp"
#include "voronoimesh/improve/guard.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vm {

namespace detail {
class PartAgreement; // the agreement of a distributed run's parts (voronoimesh_mpi)
}

/// One parameter of a pass: its schema generates the CLI help, the `passes`
/// listing and the validation of pipelines, so they can never disagree.
struct ParamSpec {
  std::string name;         ///< the key in a pipeline spec ("name:key=value")
  double default_value = 0; ///< the value when none is given; must lie in [min, max]
  /// Smallest value accepted: the range [min, max] is inclusive.
  double min = 0, max = 0; ///< largest value accepted (accepted range, inclusive)
  bool integer = false;    ///< only whole numbers are accepted
  std::string help;        ///< one line, with the paper's section or equation
};

/// Parameter values by name.
using ParamValues = std::map<std::string, double>;

/// What passes work on during one run of a pipeline.
struct PassContext {
  InterfaceMesh& mesh;               ///< the mesh being improved (in a distributed run, this rank's part)
  const PhaseField* field = nullptr; ///< the original (unsnapped) phases; null if none given
  std::vector<Vec3> delta;           ///< pending displacement of every node
  bool pending = false;              ///< delta holds moves not yet committed
  int iteration = 0;                 ///< the current iteration, 1-based
  int iterations = 0;                ///< the run's last iteration (0: not known)
  size_t flips = 0;                  ///< flips in the current iteration
  /// Commit through the crossing guard (improve/guard.hpp), so that no move makes two
  /// triangles intersect.
  bool guard_crossings = true;
  /// The guard, kept for the whole run so that its index of the mesh carries
  /// over from one check to the next (commits and flips).
  CrossingGuard guard;
  size_t undone_moves = 0;           ///< moves the guard undid in the current iteration
  /// The worst triangle quality at the start of the iteration (0: none). With the
  /// guard on, no committed move leaves a triangle below it and flips only raise
  /// the smaller quality of their pair, so only an ear flip (improve/flip.hpp),
  /// the one cure for a triangle whose corners all lie on one curve, can make
  /// the worst triangle worse within an iteration.
  double quality_floor = 0;
  /// The pipeline has the floor pass, which may take back the moves the quality
  /// floor let through this iteration (take_back_floor_exceptions()): the flip
  /// pass then leaves their nodes' triangles as they are, so that the way back
  /// is the one they left. Flipped, the way back could leave a triangle below
  /// the floor, and the guard refused it (the liver's worst triangle fell
  /// 0.616 -> 0.528 in its 5th iteration so).
  bool floor_pass = false;
  std::optional<MeshStats> stats;    ///< set by the stats pass
  /// In a distributed run (voronoimesh_mpi), how the passes agree across the
  /// parts of the mesh, each run on one part (PassInfo::distributed); null in one
  /// process.
  detail::PartAgreement* parts = nullptr;

  /// A context for passes on `m`, nothing pending.
  /// @param m the mesh to improve; not owned, must outlive the context
  /// @param f the original (unsnapped) phase functions, or null if none are given; not owned
  explicit PassContext(InterfaceMesh& m, const PhaseField* f = nullptr) : mesh(m), field(f) {}
  /// The displacement buffer, zeroed if nothing is pending.
  /// @return `delta`, one entry per node, now pending: passes add their moves to it
  std::vector<Vec3>& displacement();
  /// Applies the pending displacement to the mesh (through the guard if on;
  /// in a distributed run each node takes its owner's move first).
  void commit();
  /// Takes back the moves the quality floor let through this iteration (their
  /// nodes closing in on their interface, CrossingGuard::commit()) where they
  /// left a triangle below it, each committed again with the floor holding for
  /// it: what the floor pass does when the iteration would end below the worst
  /// quality it began with, so that more iterations never make the worst
  /// triangle worse for the sake of accuracy.
  void take_back_floor_exceptions();

private:
  void commit_pending(bool floor_holds_all);
};

/// One configured pass, made by PassInfo::make from its parameters.
class Pass {
public:
  virtual ~Pass() = default;
  /// Does the pass's work on context.mesh for one iteration.
  /// @param context the mesh, field and displacement buffer of the run; a pass that moves nodes adds to
  ///                context.displacement() and does not move them itself
  virtual void run(PassContext& context) = 0;
};

/// A pass type: its name, summary, schema and how to make one.
struct PassInfo {
  std::string name;              ///< the name pipelines use: a-z, 0-9, _ and - (PassRegistry::add())
  std::string summary;           ///< one line, shown by the `passes` listing
  std::vector<ParamSpec> params; ///< its parameters' schema
  bool moves_nodes = false; ///< adds to the displacement buffer
  bool needs_field = false; ///< needs the phase functions
  /// Runs on a part of a distributed mesh too, agreeing with the other parts
  /// through PassContext::parts (the built-in smooth, project, clamp and flip).
  bool distributed = false;
  /// Makes a configured pass from a value for every parameter (PassRegistry::resolve()).
  std::function<std::unique_ptr<Pass>(const ParamValues&)> make;
  /// For a pass whose work changes on a schedule (one that stops after some
  /// iteration, or starts at one): given its parameters, the last iteration in
  /// which it works otherwise than in every later one. A run that stops once
  /// quality converges (RunOptions::stop_when_converged) judges only the
  /// iterations after it. Empty: the pass works alike in every iteration.
  std::function<int(const ParamValues&)> scheduled_until;
};

} // namespace vm
