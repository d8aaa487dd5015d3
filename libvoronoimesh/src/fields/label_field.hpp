#pragma once
/// @file fields/label_field.hpp
/// Smooth phase functions for a segmented (label) volume: one per label, kept
/// only in a narrow band around its region and only among the K largest per
/// voxel, so memory and time grow with the voxels, not with the labels.

#include "core/unset_vector.hpp"
#include "fields/top_k_grid_field.hpp"

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vm::detail {

/// How each label's phase function is made from its voxels.
struct LabelFieldParams {
  bool signed_distance = false; ///< false: Gaussian-smoothed indicator; true: banded signed distance
  double smoothing = 1.0;       ///< Gaussian sigma in voxels (indicator)
  /// Indicator: at every voxel centre its own label leads every other by at
  /// least kVoxelCentreLead (raised where smoothing leaves it behind), so
  /// every voxel centre lies in its own label's phase (InputOptions::voxel_faithful).
  /// The centres of voxels one voxel thin along an axis are kept points
  /// (PhaseField::kept_points()), which improvement leaves in their phase.
  bool voxel_faithful = false;
  double band = 3.0;            ///< half-width of the band in voxels (signed distance)
  int k = 4;                    ///< phases kept per voxel
};

/// How far, in units of the smallest voxel spacing, a voxel's own label leads
/// at its centre with LabelFieldParams::voxel_faithful. A flat boundary puts it
/// 0.5 ahead (sigma sqrt(2 pi) / 2 times the kernel's centre weight), so only
/// the centres smoothing leaves behind (corners, edges, structures a voxel or
/// two thin) are raised. Measured (docs/inputs.md): 0.5 raised most centres of
/// the liver's curved surfaces and made them bumpy; 0.2 is create's snapping
/// threshold on isotropic voxels, which then tied a one-voxel sheet's centres.
constexpr double kVoxelCentreLead = 0.3;

/// The voxels of a label volume, already mapped to phases.
struct PhaseVoxels {
  std::array<int64_t, 3> size{};
  Vec3 spacing = Vec3::Ones();
  Vec3 origin = Vec3::Zero();
  /// Phase per voxel (x fastest); -1 = not a phase (left to the others). Left
  /// unset when sized, so that the threads mapping labels to phases touch its
  /// pages first (zeroed by one thread, its 50 MB on the liver were a serial
  /// stretch of fresh memory).
  UnsetVector<int16_t> phase;
  std::vector<std::string> names;
  std::vector<int32_t> labels; ///< label value of each phase, strictly increasing
  std::vector<std::optional<Rgb>> colors; ///< display colour of each phase, when known (may be shorter)
};

/// The field on the voxel grid (nodes at voxel centres), computed only in the
/// bricks of voxels within reach (3 sigma, or the band) of a label change;
/// elsewhere each node holds its own phase alone at the value it has deep
/// inside a region (TopKGridField's uniform bricks). Indicator: phi_i =
/// Gaussian-smoothed indicator of phase i (normalised by the smoothed weight of
/// the voxels that are a phase), scaled by sigma sqrt(2 pi) / 2 voxel sizes so
/// that phi_i - phi_j grows at about 1 per unit length across a flat boundary;
/// voxel_faithful then raises each voxel's own label at its centre where it
/// does not lead by kVoxelCentreLead.
/// Signed distance: exact Euclidean distance to the region's boundary, halfway
/// between voxel centres, positive inside, clamped to +-band. Throws
/// InvalidInput naming `source` if some voxel is farther than the band from
/// every phase (possible only with voxels that are not a phase).
std::shared_ptr<const TopKGridField> label_field(const PhaseVoxels& voxels, const LabelFieldParams& params,
                                                 const std::string& source);

} // namespace vm::detail
