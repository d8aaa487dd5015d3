// paraview/filter/image_scene.h: the scene of a VTK image (labels or phase
// functions on its points or cells), in the image's index-aligned frame, and
// the map from that frame to the image's world frame (its direction matrix).
#pragma once

#include <voronoimesh/voronoimesh.hpp>

#include <array>
#include <string>
#include <vector>

class vtkDataArray;
class vtkImageData;

namespace vmpv {

/// Where an image's data lies: a value per point, or per cell (voxel).
enum class Association { points, cells };

/// The frame a scene built from an image lies in: node positions are
/// `origin + spacing * index` along the image axes; the world position of a
/// point p of that frame is origin + direction * (p - origin).
struct ImageFrame {
  vm::GridSpec grid;                  ///< the nodes the data lies on
  vm::Vec3 origin;                    ///< the image's origin
  std::array<double, 9> direction{};  ///< the image's direction matrix, row-major
  bool axis_aligned = true;           ///< direction is the identity

  /// `p` (of the index-aligned frame) in the image's world frame.
  vm::Vec3 to_world(const vm::Vec3& p) const;
};

/// The frame of `image`'s point data, or of its cell data (voxel centres as nodes).
ImageFrame image_frame(vtkImageData& image, Association where);

/// The label volume scene of an integer array (one component): a label per
/// node of `frame.grid`, read as `voronoimesh mesh` reads a label volume.
/// Throws vm::InvalidInput naming `labels` for a non-integer array or a label
/// outside 32 bits.
vm::Scene labels_scene(const ImageFrame& frame, vtkDataArray& labels, const vm::InputOptions& options);

/// The scene of one phase function per array (point data, one component each),
/// the phases named after the arrays.
vm::Scene phase_values_scene(const ImageFrame& frame, const std::vector<vtkDataArray*>& phases, int top_k);

} // namespace vmpv
