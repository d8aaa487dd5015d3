#pragma once
/// @file meshing.hpp
/// One call from a scene to a finished interface mesh, for programs that mesh
/// their own data (a simulation remeshing at every time step): sample the
/// phase functions, create the initial mesh (paper sect. 4.1), improve it with
/// a pipeline of passes (paper Algorithm 1) and check it, as the CLI's `mesh`
/// command does. create_mesh() and improve_mesh() are the two halves.
///
/// Scenes come from files (load_input, input.hpp), from arrays in memory
/// (array_input.hpp), from closed forms (parse_scene, scene.hpp) or from any
/// PhaseField of your own: Scene{grid, field}.

#include "voronoimesh/create.hpp"
#include "voronoimesh/node_mesh.hpp"
#include "voronoimesh/pipeline.hpp"
#include "voronoimesh/registry.hpp"
#include "voronoimesh/scene.hpp"

#include <array>
#include <string>

namespace vm {

/// Options of create_mesh(), improve_mesh() and mesh_scene(); the defaults
/// are the CLI's.
struct MeshOptions {
  // --- create ---------------------------------------------------------------
  /// Grid cells per axis, each in [1, 4096]; {0, 0, 0} keeps the scene's grid.
  /// The domain stays the scene's. Finer grids resolve thinner features; time
  /// and memory grow with the cube.
  std::array<int, 3> grid{0, 0, 0};
  /// Background tetrahedra (create.hpp); bcc rounds each cell count up to even.
  Lattice lattice = Lattice::bcc;
  /// Snapping threshold in grid spacings, in [0, 0.5] (paper sect. 4.1: 0.2).
  double snap = 0.2;
  /// Phases kept per grid node when sampling, in [1, 16] (sampled_field.hpp).
  int top_k = 4;
  /// Close the domain: box faces become surfaces against an extra phase
  /// "exterior", so every phase is a closed volume (closed_domain.hpp).
  bool close = false;
  /// Check the mesh after create and after improve (validate.hpp) and throw
  /// TopologyError if it fails. Off saves a linear-time check.
  bool validate = true;

  // --- improve --------------------------------------------------------------
  /// Iterations of the pipeline; 0 leaves the initial mesh as created.
  int iterations = 20;
  /// Passes per iteration, "name,name:key=value,..." (pipeline.hpp); the
  /// paper's smoothing, projection, clamping and flipping by default.
  std::string pipeline = kDefaultPipeline;
  /// The passes `pipeline` may name (e.g. built-ins plus a plugin's); null:
  /// the built-in passes. Not owned; must outlive the call.
  const PassRegistry* passes = nullptr;
  /// Stop early once quality stops improving (RunOptions::stop_when_converged).
  bool stop_when_converged = false;
  /// Undo moves and flips that make surfaces cross (guard.hpp).
  bool guard_crossings = true;

  // --- both -----------------------------------------------------------------
  /// Worker threads, 0 = all cores. Results do not depend on it.
  int threads = 0;
};

/// The grid create_mesh() samples: the scene's, or options.grid, with the cell
/// counts the lattice needs (grid_for_lattice()). Throws InvalidInput for a null
/// field, a grid or top_k out of range.
GridSpec create_grid(const Scene& scene, const MeshOptions& options);

/// The CreateParams of `options`.
CreateParams create_params(const MeshOptions& options);

/// Sets the phase names and labels of a mesh create_mesh() made from `scene`
/// (name_phases(), with the extra phase of a closed domain if options.close).
void name_phases(NodeMesh& mesh, const Scene& scene, const MeshOptions& options);

/// Samples `scene.field` on the scene's grid (or options.grid) and creates the
/// initial mesh, with the phases' names and labels (NodeMesh::phase_names,
/// phase_labels) for writers. Throws InvalidInput for a null field or an
/// option out of range (naming the option, e.g. "grid: ..."), or a grid too
/// big for this machine's memory; InvalidInput from sampling for a NaN or
/// infinite phase value; TopologyError if options.validate and the mesh fails
/// validation (a bug, or unusable input).
NodeMesh create_mesh(const Scene& scene, const MeshOptions& options = {});

/// Runs options.pipeline for options.iterations on `mesh` (made by
/// create_mesh() from the same scene, possibly closed), moving its nodes and
/// flipping its edges in place. Returns the iterations done (fewer than asked
/// when stop_when_converged stops early). Throws InvalidInput for a bad
/// pipeline or option, TopologyError if `mesh` is not a valid interface mesh or
/// (with options.validate) the result fails validation.
int improve_mesh(NodeMesh& mesh, const Scene& scene, const MeshOptions& options = {});

/// create_mesh() then improve_mesh(): the CLI's `voronoimesh mesh` without the
/// files. Everything it throws is a vm::Error (errors.hpp); it never exits.
NodeMesh mesh_scene(const Scene& scene, const MeshOptions& options = {});

} // namespace vm
