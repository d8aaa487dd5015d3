#pragma once
/// @file io/volume.hpp
/// Voxel volumes as scanners, segmenters, grain-map and level-set codes write
/// them: NRRD (.nrrd/.nhdr, 3D Slicer's .seg.nrrd), NIfTI-1 (.nii/.nii.gz),
/// MetaImage (.mha/.mhd), INR (.inr/.inr.gz), DREAM.3D (.dream3d) and TIFF
/// stacks (.tif/.tiff). One reader per format; read_volume() picks by extension.

#include "voronoimesh/core/types.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vm::io {

/// The anatomical frame of a file's world coordinates, where its format says
/// one: NIfTI is RAS+ (+x right, +y anterior, +z superior), NRRD says it in its
/// `space` field, MetaImage is ITK's physical space, LPS+ (+x left, +y
/// posterior). INR and NRRD without (or with another) `space` are `unknown`.
enum class WorldFrame { unknown, ras, lps };

/// A named label: a segment of a 3D Slicer segmentation (`.seg.nrrd`), a label
/// value in one layer of the file; or a grain of a DREAM.3D file.
struct Segment {
  std::string name;  ///< SegmentN_Name (SegmentN_ID when it has none)
  int32_t label = 1; ///< its voxels' value in its layer (SegmentN_LabelValue; 1 in files older than Slicer 4.11)
  int layer = 0;     ///< the layer holding it (SegmentN_Layer; N in files older than Slicer 4.11, one layer each)
  /// Display colour, red, green, blue in [0, 1] (SegmentN_Color), when the file gives one.
  std::optional<Rgb> color;
};

/// A voxel volume in physical space. Voxel (i, j, k) has its centre at
/// origin + direction * (spacing .* (i, j, k)); i runs fastest in memory.
struct Volume {
  std::array<int64_t, 3> size{0, 0, 0}; ///< voxels per axis
  int components = 1;                  ///< values per voxel (e.g. one per phase of a distance grid)
  Vec3 spacing = Vec3::Ones();         ///< voxel size along each axis, > 0
  /// False when the file says no voxel size along some axis (a NRRD axis without
  /// spacing, MetaImage without ElementSpacing or ElementSize, INR without VX,
  /// VY or VZ, a TIFF not written by ImageJ): `spacing` is then 1 along it.
  bool spacing_stated = true;
  Vec3 origin = Vec3::Zero();          ///< centre of voxel (0, 0, 0)
  /// Unit axis directions as columns (identity where the format has none).
  Eigen::Matrix3d direction = Eigen::Matrix3d::Identity();
  /// True when the file stores integers (labels); then `labels` holds the data,
  /// otherwise `values` does. Components are interleaved per voxel:
  /// index = c + components * (i + size[0] * (j + size[1] * k)).
  bool integer = false;
  std::vector<int32_t> labels; ///< the data when `integer`: components x voxel_count() values, else empty
  std::vector<float> values;   ///< the data unless `integer`: components x voxel_count() values, else empty
  WorldFrame world = WorldFrame::unknown; ///< the frame of `origin` and `direction`
  /// The named labels: a 3D Slicer segmentation's segments, in file order, or
  /// a DREAM.3D file's grains (empty for any other file). Its layers are flattened into one label volume on reading
  /// (`components` is then 1; flatten_segment_layers()), and each segment's
  /// `label` is its value there.
  std::vector<Segment> segments;
  /// What reading resolved and a user should hear of, one line each (segments
  /// overlapping in a layered segmentation).
  std::vector<std::string> notes;

  /// Voxels in all, the product of `size`.
  int64_t voxel_count() const { return size[0] * size[1] * size[2]; }
};

/// Reads a volume, choosing the format by the file's extension.
/// @param path the file to read; its extension (case-insensitive) chooses the format
/// @return the volume
/// @throws InvalidInput naming the file and the problem for a malformed, truncated or unsupported file
///         (e.g. 64-bit integers beyond int32, more than 3 dimensions apart from a component axis), or an
///         extension read_volume() does not know
/// @throws IoError      if it cannot be read
Volume read_volume(const std::string& path);

/// @name Per-format readers
/// Per-format readers (read_volume dispatches to these). Each throws as read_volume().
/// @{

/// Reads an NRRD volume (.nrrd, or a detached header .nhdr).
/// @param path the file to read
/// @return the volume
/// @throws InvalidInput for a malformed, truncated or unsupported file
/// @throws IoError      if it cannot be read
Volume read_nrrd(const std::string& path);
/// Reads a NIfTI volume (.nii, .nii.gz, or the .hdr of a .hdr/.img pair).
/// @param path the file to read
/// @return the volume
/// @throws InvalidInput for a malformed, truncated or unsupported file
/// @throws IoError      if it cannot be read
Volume read_nifti(const std::string& path);
/// Reads a MetaImage volume (.mha, or a .mhd header with its data file).
/// @param path the file to read
/// @return the volume
/// @throws InvalidInput for a malformed, truncated or unsupported file
/// @throws IoError      if it cannot be read
Volume read_metaimage(const std::string& path);
/// Reads an INR volume (.inr, .inr.gz).
/// @param path the file to read
/// @return the volume
/// @throws InvalidInput for a malformed, truncated or unsupported file
/// @throws IoError      if it cannot be read
Volume read_inr(const std::string& path);
/// Reads the grain map (FeatureIds) of a DREAM.3D file (.dream3d: DREAM.3D 6's
/// SIMPL layout or DREAM3D-NX 7's) as a label volume of grain ids, each grain a
/// segment named grain<id>, or grain<id>-phase<p> where the file gives the
/// grains' phases (docs/inputs.md).
/// @param path the file to read
/// @return the volume
/// @throws InvalidInput for a file that is not HDF5, has no grain map or several, or malformed geometry
/// @throws IoError      if it cannot be read
Volume read_dream3d(const std::string& path);
/// Reads a TIFF stack (.tif, .tiff: one page per z slice, as Fiji/ImageJ and
/// micro-CT and FIB-SEM software save volumes) with libtiff. The voxel size is
/// ImageJ's (its X/YResolution tags and `spacing=`); another writer's TIFF has
/// voxels of 1 x 1 x 1 and Volume::spacing_stated false.
/// @param path the file to read
/// @return the volume
/// @throws InvalidInput for a file that is not a TIFF, has one page, pages unlike the first, more than one
///         sample per pixel (RGB), or samples other than 8/16/32-bit integers and 32/64-bit reals
/// @throws IoError      if it cannot be read
Volume read_tiff(const std::string& path);

/// @}

/// True when `path` has an extension read_volume() knows.
/// @param path a file name; only its extension (case-insensitive) is looked at
bool is_volume_file(const std::string& path);

} // namespace vm::io
