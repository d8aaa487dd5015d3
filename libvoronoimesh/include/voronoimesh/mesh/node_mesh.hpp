#pragma once
/// @file mesh/node_mesh.hpp
/// The node-level form of an interface mesh: one vertex per geometric point,
/// triangles as node triples, one phase pair per triangle. This is what files
/// hold and what create produces; InterfaceMesh (mesh/interface_mesh.hpp) is built from it.

#include "voronoimesh/core/types.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vm {

/// The name of the phase outside the box of a closed mesh (NodeMesh::outside_phase):
/// what files call it ("outside" is a common name of a scene's own background phase).
inline const std::string kOutsidePhaseName = "exterior";

/// Triangles of every interface, sharing vertices at junctions.
struct NodeMesh {
  /// Node positions.
  std::vector<Vec3> points;
  /// Node ids of each triangle, oriented so that the right-hand normal points
  /// from pairs[t][0] into pairs[t][1].
  std::vector<std::array<int32_t, 3>> triangles;
  /// Phase pair of each triangle, pairs[t][0] < pairs[t][1].
  std::vector<PhasePair> pairs;
  /// Phase names by id, when known (may be empty).
  std::vector<std::string> phase_names;
  /// The id each phase shows in files (a label volume's label value), by phase
  /// id; strictly increasing, so orientation conventions survive the mapping.
  /// Empty: files show the phase ids themselves.
  std::vector<int32_t> phase_labels;
  /// Display colours by phase id, when the input gives them (a 3D Slicer
  /// segment's colour); a phase beyond the end, or without a value, has none.
  std::vector<std::optional<Rgb>> phase_colors;
  /// The domain box; edges lying on it may bound a single triangle.
  Box domain;
  /// The spacing h of the grid the mesh was created on, the unit in which its
  /// nodes' offsets from the interface are told (`voronoimesh stats --field`);
  /// 0: not known (a mesh from a file that does not say).
  double grid_spacing = 0;
  /// The phase outside the box of a closed mesh (CreateParams::close: the box
  /// faces are surfaces between the phases inside and this one, the last), or -1
  /// when the mesh is not closed.
  int32_t outside_phase = -1;

  /// A mesh with the same domain, grid spacing and phases (names, labels, colours, outside phase) and
  /// no points or triangles: where a new mesh is made from this one.
  NodeMesh empty_like() const {
    NodeMesh m;
    m.phase_names = phase_names;
    m.phase_labels = phase_labels;
    m.phase_colors = phase_colors;
    m.domain = domain;
    m.grid_spacing = grid_spacing;
    m.outside_phase = outside_phase;
    return m;
  }

  /// The label phase `phase` shows in files: phase_labels[phase], or the id
  /// itself when the mesh has no labels.
  /// @param phase a phase id of the mesh
  int32_t label_of(int32_t phase) const {
    return size_t(phase) < phase_labels.size() ? phase_labels[size_t(phase)] : phase;
  }

  size_t num_nodes() const { return points.size(); }         ///< points.size()
  size_t num_triangles() const { return triangles.size(); } ///< triangles.size()
};

} // namespace vm
