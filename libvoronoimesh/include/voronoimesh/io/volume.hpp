#pragma once
/// @file io/volume.hpp
/// Voxel volumes as scanners, segmenters and level-set codes write them: NRRD
/// (.nrrd/.nhdr), NIfTI-1 (.nii/.nii.gz), MetaImage (.mha/.mhd) and INR
/// (.inr/.inr.gz). One reader per format; read_volume() picks by extension.

#include "voronoimesh/types.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vm::io {

/// A voxel volume in physical space. Voxel (i, j, k) has its centre at
/// origin + direction * (spacing .* (i, j, k)); i runs fastest in memory.
struct Volume {
  std::array<int64_t, 3> size{0, 0, 0}; ///< voxels per axis
  int components = 1;                  ///< values per voxel (e.g. one per phase of a distance grid)
  Vec3 spacing = Vec3::Ones();         ///< voxel size along each axis, > 0
  Vec3 origin = Vec3::Zero();          ///< centre of voxel (0, 0, 0)
  /// Unit axis directions as columns (identity where the format has none).
  Eigen::Matrix3d direction = Eigen::Matrix3d::Identity();
  /// True when the file stores integers (labels); then `labels` holds the data,
  /// otherwise `values` does. Components are interleaved per voxel:
  /// index = c + components * (i + size[0] * (j + size[1] * k)).
  bool integer = false;
  std::vector<int32_t> labels;
  std::vector<float> values;

  /// Voxels in all, the product of `size`.
  int64_t voxel_count() const { return size[0] * size[1] * size[2]; }
};

/// Reads a volume, choosing the format by the file's extension. Throws
/// InvalidInput naming the file and the problem for a malformed, truncated or
/// unsupported file (e.g. 64-bit integers beyond int32, more than 3 dimensions
/// apart from a component axis), IoError if it cannot be read.
Volume read_volume(const std::string& path);

/// Per-format readers (read_volume dispatches to these).
Volume read_nrrd(const std::string& path);
Volume read_nifti(const std::string& path);
Volume read_metaimage(const std::string& path);
Volume read_inr(const std::string& path);

/// True when `path` has an extension read_volume() knows.
bool is_volume_file(const std::string& path);

} // namespace vm::io
