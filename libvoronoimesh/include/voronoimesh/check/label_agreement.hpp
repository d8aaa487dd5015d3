#pragma once
/// @file check/label_agreement.hpp
/// Whether a closed mesh made from a label volume keeps every voxel in its own
/// label's phase: what users of segmentations check first (issue 19).

#include "voronoimesh/check/locate.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace vm {

/// Voxel centres of a label volume located in a closed mesh made from it
/// (label_agreement()). Every centre counts: those of the volume's outer layer
/// of voxels, which lie on the box faces, are located a thousandth of a spacing
/// inside (on the faces no ray tells a phase from the outside).
struct LabelAgreement {
  /// One label's voxel centres, and how many of them lie in a phase of that label.
  struct Label {
    int32_t label = 0;    ///< the label
    int64_t voxels = 0;   ///< its voxel centres counted
    int64_t in_phase = 0; ///< of those, the ones in a phase of this label
  };
  int64_t voxels = 0;            ///< voxel centres counted (location decided)
  int64_t in_phase = 0;          ///< of those, the ones in a phase of their own label
  int64_t interior = 0;          ///< voxel centres whose neighbours within the margin share their label
  int64_t interior_in_phase = 0; ///< of those, the ones in a phase of their own label
  int64_t undecided = 0;         ///< centres whose phase the location could not decide (locate_grid_points())
  std::vector<Label> labels;     ///< per label, ascending

  /// The label with the smallest share of its voxel centres in its phase (the
  /// lowest such label), or null when no voxel centre was counted.
  const Label* worst() const;
  /// The labels none of whose voxel centres lie in their phase: lost by the mesh, or merged into another.
  std::vector<int32_t> lost() const;
};

/// Locates every voxel centre of a label volume in `closed` (locate_grid_points())
/// and compares its phase's label (NodeMesh::label_of()) with the voxel's own.
/// @param closed  a closed mesh (NodeMesh::outside_phase >= 0) made from the volume, with its phases' labels
/// @param centres the voxel centres, placed as the mesh's input was (read_placed_volume(): origin, spacing, size)
/// @param labels  the label of each voxel, in the order of `centres`
/// @param margin  a voxel is interior when every voxel up to this many steps away along each axis
///                shares its label (1: its 26 neighbours)
/// @return the counts
/// @throws InvalidInput if the mesh is not closed, the labels do not fit the grid or the margin is negative
LabelAgreement label_agreement(const NodeMesh& closed, const PointGrid& centres, std::span<const int32_t> labels,
                               int margin = 1);

/// The counts as text: a line of the shares, the worst label and the labels with no voxel centre in their phase.
std::string to_text(const LabelAgreement& a);

/// The counts as one JSON object.
std::string to_json(const LabelAgreement& a);

} // namespace vm
