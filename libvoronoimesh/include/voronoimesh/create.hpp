#pragma once
/// @file create.hpp
/// The initial mesh of the Voronoi interface (paper sect. 4.1, Algorithm 2).

#include "voronoimesh/node_mesh.hpp"
#include "voronoimesh/sampled_field.hpp"

#include <cstdint>

namespace vm {

/// Background tessellation of the grid.
enum class Lattice {
  bcc,  ///< body-centred cubic lattice over every second grid point (paper Fig. 2 right)
  cube6 ///< every grid cell split into six tetrahedra (paper Fig. 2 left)
};

struct CreateParams {
  Lattice lattice = Lattice::bcc;
  /// Snapping threshold eps in units of the grid spacing h: phase values closer
  /// than eps*h at a lattice node are made equal (Algorithm 2, line 1). The paper
  /// found 0.2 h good for distance-like functions (sect. 4.1). 0 turns it off.
  double snap = 0.2;
};

/// What create did, for benchmarks and logs.
struct CreateStats {
  uint64_t tets_visited = 0;   ///< tetrahedra of the lattice
  uint64_t tets_cut = 0;       ///< tetrahedra with more than one phase after the drop rule
  uint64_t polygons = 0;       ///< non-empty chopped polygons
  uint64_t merged_vertices = 0; ///< vertices that coincided with another in the limit
  uint64_t dropped_triangles = 0; ///< zero-size triangles removed
  uint64_t cancelled_triangles = 0; ///< coincident triangles merged or removed
  uint64_t snapped_nodes = 0;  ///< lattice nodes whose values snapping changed
  double seconds = 0;          ///< wall time of create (sampling excluded)
};

/// Extracts the Voronoi interface of the piecewise-linear interpolant of `field`
/// on the chosen lattice, after snapping. The result is consistent by construction:
/// each vertex is made once per lattice point it lies on (exact, no tolerance).
CreateStats create_initial_mesh(const SampledField& field, const CreateParams& params,
                                NodeMesh& out);

} // namespace vm
