#pragma once
/// @file create/create.hpp
/// The initial mesh of the Voronoi interface (paper sect. 4.1, Algorithm 2).

#include "voronoimesh/fields/sampled_field.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <cstdint>
#include <functional>

namespace vm {

/// Background tessellation of the grid.
enum class Lattice {
  bcc,  ///< body-centred cubic lattice over every second grid point (paper Fig. 2 right)
  cube6 ///< every grid cell split into six tetrahedra (paper Fig. 2 left)
};

/// Parameters of create_initial_mesh().
struct CreateParams {
  Lattice lattice = Lattice::bcc; ///< the background tetrahedra
  /// Snapping threshold eps in units of the grid spacing h: phase values closer
  /// than eps*h at a lattice node are made equal (Algorithm 2, line 1). The paper
  /// found 0.2 h good for distance-like functions (sect. 4.1). 0 turns it off.
  double snap = 0.2;
  /// Close the domain: the box faces become surfaces between each phase and an
  /// extra phase "exterior" (id = the field's phase count, NodeMesh::outside_phase),
  /// so that every phase is a closed volume (phases_of_mesh() in
  /// fields/outside_phase.hpp gives the phase functions for improving such a
  /// mesh). Not in the paper.
  bool close = false;
};

/// What create did, for benchmarks and logs.
struct CreateStats {
  uint64_t tets_visited = 0;       ///< tetrahedra of the lattice
  uint64_t tets_cut = 0;           ///< tetrahedra where more than one phase can win
  uint64_t polygons = 0;           ///< non-empty chopped polygons emitted
  uint64_t collapsed_polygons = 0; ///< polygons that shrink to a point or segment in the limit
  uint64_t dropped_triangles = 0;  ///< triangles with two corners at one point
  uint64_t coincident_pairs = 0;   ///< couples of triangles on the same three points, resolved
  uint64_t degenerate_cuts = 0;    ///< ties the perturbation could not order (should stay 0)
  uint64_t box_triangles = 0;      ///< triangles on the box faces (with close)
  uint64_t snapped_nodes = 0;      ///< lattice nodes near interfaces whose values snapping changed
  uint64_t unsnapped_nodes = 0;    ///< nodes where snapping was undone because it pinched a phase
  uint64_t untied_nodes = 0;       ///< nodes whose ties in the data were broken because they pinched a phase
  /// Nodes around closed triple curves far smaller than a cell (around a
  /// lattice edge where a third phase nearly ties the two crossing it), at
  /// which the third phase rose to close them: no improvement could make their
  /// triangles better than slivers.
  uint64_t tiny_loop_nodes = 0;
  int repair_rounds = 0;           ///< extra extractions that undoing snapping and ties needed
  double seconds = 0;              ///< wall time of create (sampling excluded)
  /// Wall time of sampling the field, where create samples it itself (create_initial_mesh() from a PhaseField).
  double sampling_seconds = 0;
  /// Lattice nodes whose values create held: those near interfaces (a distributed create: every node
  /// of each rank's window, summed over the ranks).
  uint64_t held_nodes = 0;
  double check_seconds = 0;        ///< of which validating the result and undoing pinches
  /// The mesh returned passed validate() inside create (which validates every
  /// mesh it makes, to find pinches): callers need not validate it again.
  bool validated = false;
};

/// Most extra extractions create makes to undo snapping, and break ties in the
/// data, where they pinch a phase.
constexpr int kMaxRepairRounds = 12;
/// Extractions after which create stops repairing around the problems it finds
/// and repairs every lattice node once (create/create.cpp).
constexpr int kLocalRepairRounds = 6;

/// How far create breaks a tie in the data that pinches a phase, in grid
/// spacings h of phase value (detail::NodeValues::Repair::untie): small against the grid, far
/// above round-off. Not in the paper, whose perturbation is symbolic only.
constexpr double kUntieFraction = 1e-3;

/// The grid create needs for `lattice`: bcc uses every second grid node, so each
/// cell count is rounded up to an even number (the domain stays the same).
/// @param grid    the grid asked for
/// @param lattice the background tetrahedra
/// @return `grid`, with even cell counts for bcc; unchanged for cube6
GridSpec grid_for_lattice(const GridSpec& grid, Lattice lattice);

/// Bytes that create_initial_mesh() from a PhaseField on `grid` will need at
/// least: each lattice node's winner and lead over the second phase while it
/// finds the nodes near interfaces. The values of those nodes (8 B per phase
/// kept, k per node) and the mesh, both far smaller on most inputs, depend on
/// the field and are not counted. Used to refuse impossible sizes before starting.
/// @param grid    the grid to sample (from grid_for_lattice())
/// @param lattice the background tetrahedra
/// @return the bytes, saturated at UINT64_MAX
uint64_t estimate_create_memory(const GridSpec& grid, Lattice lattice);

/// Bytes that sampling grid layers layers[0]..layers[1] of `grid` with `k`
/// phases per node takes (SampledField::sample()), for one rank's block of a
/// distributed create.
/// @param grid   the whole grid
/// @param k      phases kept per grid node
/// @param layers the first and last grid layer (along z) of the block, inclusive
/// @return the bytes, saturated at UINT64_MAX
uint64_t estimate_sample_memory(const GridSpec& grid, int k, std::array<int32_t, 2> layers);

/// Extracts the Voronoi interface of the piecewise-linear interpolant of `field`
/// on the chosen lattice, after snapping, into `out`. The result is consistent by
/// construction: each vertex is made once per point it lies on, identified exactly
/// (no tolerance).
/// @param field  the samples of the phase functions; their grid must come from grid_for_lattice()
/// @param params the lattice, snapping threshold and whether to close the domain
/// @param out    receives the mesh (replaced); its domain is the grid's, its outside_phase set with
///               params.close. Phase names, labels and colours are left empty (name_phases()).
/// @return what create did
/// @throws InvalidInput for a snap outside [0, 0.5] (InvalidOption "snap") or an odd grid with bcc
CreateStats create_initial_mesh(const SampledField& field, const CreateParams& params,
                                NodeMesh& out);

/// As create_initial_mesh() from samples, sampling `field` on `grid` itself with
/// `k` phases per node (SampledField::sample()), the same mesh without holding
/// the samples of every node: it reads the field once at every lattice node for
/// the winning phase, and again near interfaces for the values it cuts (memory:
/// about 8 B per lattice node, and k, ids and values, near interfaces only).
/// @param field   the phase functions
/// @param grid    the grid to sample them on (from grid_for_lattice())
/// @param k       phases kept per node, in [1, 16]
/// @param params  the lattice, snapping threshold and whether to close the domain
/// @param out     receives the mesh, as create_initial_mesh() from samples
/// @param sampled if given, called once the field is sampled, before the mesh is cut (progress)
/// @return what create did, with sampling_seconds set
/// @throws InvalidInput as create_initial_mesh() from samples and SampledField::sample()
CreateStats create_initial_mesh(const PhaseField& field, const GridSpec& grid, int k, const CreateParams& params,
                                NodeMesh& out, const std::function<void()>& sampled = {});

/// Sets mesh.phase_names, mesh.phase_labels (left empty when every label is
/// the phase id) and mesh.phase_colors (empty when no phase has a colour) from
/// `field`, so writers show them. For a closed mesh pass
/// phases_of_mesh(mesh, field) (fields/outside_phase.hpp), which has the extra phase.
/// @param mesh  the mesh to name the phases of; its phase_names, phase_labels and phase_colors are replaced
/// @param field the phase functions the mesh was created from, one phase per phase id of the mesh
void name_phases(NodeMesh& mesh, const PhaseField& field);

} // namespace vm
