#pragma once
/// @file check/validate.hpp
/// Topological consistency checks of an interface mesh (DESIGN.md "Pitfalls",
/// openmesh-probe.md "Invariants").

#include "voronoimesh/mesh/node_mesh.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace vm {

class InterfaceMesh;

/// What validate() found. `ok()` is true when `problems` is empty.
struct ValidationReport {
  std::vector<std::string> problems; ///< one line each, at most 20 kept
  size_t problem_count = 0;          ///< all problems found, kept or not
  std::vector<int32_t> nodes;        ///< nodes involved in any problem, sorted, no repeats
  /// True when validate() found nothing.
  bool ok() const { return problem_count == 0; }
  /// Problems joined into one multi-line text, for test output.
  std::string summary() const;
};

/// True when triangle (a, b, c) is what validate() calls zero-area: area at most
/// 1e-12 times its longest edge squared, or a coordinate not finite. Passes
/// that make triangles (flips) refuse to make such a one.
/// @param a first corner
/// @param b second corner
/// @param c third corner
bool has_zero_area(const Vec3& a, const Vec3& b, const Vec3& c);

/// Checks a node-level interface mesh:
///  - node ids in range; no triangle with a repeated node; no zero-area triangle
///    (area <= 1e-12 x longest edge squared); no two triangles on the same three nodes;
///  - every node is a corner of a triangle;
///  - every pair (p, q) has p < q, both in [0, num_phases);
///  - for every phase, its boundary (its triangles, oriented outward) is closed
///    and 2-manifold: each edge is used once in each direction, except edges on
///    the domain box, and the triangles around each node form one fan;
///  - every junction edge (3 or more triangles) is carried by one cycle of
///    distinct pairs (each incident phase on exactly two of its triangles).
/// @param m the mesh to check
/// @return the problems found; ok() when there are none
ValidationReport validate(const NodeMesh& m);

/// Throws TopologyError unless validate(m) finds nothing.
/// @param m    the mesh to check
/// @param what names the mesh in the message ("the created mesh")
/// @throws TopologyError "<what> failed validation (N problems; please report this with the input),
///         first: <problem>" unless validate(m) finds nothing
void require_valid(const NodeMesh& m, const std::string& what);

/// validate() on the node-level mesh, plus the patch-split invariants: every
/// OpenMesh vertex manifold; an OpenMesh edge is boundary exactly when its
/// node-edge is a junction or domain-boundary edge; point() mirrors the node position.
/// @param m the patch-split mesh to check
/// @return the problems found; ok() when there are none
ValidationReport validate(const InterfaceMesh& m);

} // namespace vm
