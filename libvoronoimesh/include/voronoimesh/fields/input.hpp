#pragma once
/// @file fields/input.hpp
/// Every input voronoimesh meshes: JSON scenes, label volumes, signed-distance
/// grids and labelled point clouds (format and options: docs/inputs.md).

#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/io/volume.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vm {

/// How a label volume's phase functions are made (docs/inputs.md).
enum class LabelFunction {
  smoothed_indicator, ///< Gaussian-smoothed indicator of each label (default)
  signed_distance,    ///< exact Euclidean signed distance, clamped to a band
};

/// A label of a label volume, by value or, where the file names its labels (a
/// 3D Slicer segmentation's segments), by name.
struct LabelRef {
  LabelRef(int32_t value) : value(value) {}                 ///< the label of this value
  LabelRef(std::string name) : name(std::move(name)) {}     ///< the label of this segment name
  LabelRef(const char* name) : name(name) {}                ///< the label of this segment name
  std::optional<int32_t> value; ///< the label's value, when given by value
  std::string name;             ///< the segment's name, when given by name
  bool operator==(const LabelRef&) const = default; ///< the same value, or the same name
};

/// The world frame a volume's mesh is put in (--world), docs/inputs.md.
enum class World {
  file, ///< the file's own coordinates, as they are
  lps,  ///< LPS+ (+x left, +y posterior: DICOM, ITK, 3D Slicer's files)
  ras,  ///< RAS+ (+x right, +y anterior: NIfTI, 3D Slicer's views)
};

/// Options for reading inputs other than JSON scenes.
struct InputOptions {
  // Label volumes.
  std::vector<LabelRef> drop_labels;               ///< these labels become background
  std::vector<std::vector<LabelRef>> merge_labels; ///< each group becomes its smallest label
  /// When not empty, only these labels (and the background) become phases:
  /// the voxels of every other label become background.
  std::vector<LabelRef> keep_labels;
  int32_t background = 0;                         ///< the background label
  bool no_background = false;                     ///< background voxels are no phase: the labels around fill them
  LabelFunction label_function = LabelFunction::smoothed_indicator; ///< how each label's phase function is made
  double smoothing = 1.0;        ///< Gaussian sigma in voxels (smoothed indicator), in (0, 8]
  /// Opt-in: each voxel's own label leads at the voxel's centre (the smoothed
  /// indicator is raised there where smoothing leaves it behind; signed
  /// distances lead there already), and the scene asks for every grid node
  /// (Scene::needs_every_grid_node) where the bcc lattice would lose more than
  /// 1% of a label. Keeps labels a voxel or two thin that the default loses,
  /// at a cost: on CGAL's liver (cube6 for its 2-voxel label) about 5x the time
  /// and min q 0.165 instead of 0.695, with folds along the rims of its
  /// one-voxel structures (docs/inputs.md), hence off by default.
  bool voxel_faithful = false;
  double band = 3.0;             ///< band half-width in voxels (signed distance), in [1, 64]
  bool ignore_direction = false; ///< take an oblique direction matrix as the identity
  /// The frame of the mesh's coordinates: the file's own, or LPS or RAS
  /// converted from the frame the file states (refused where it states none).
  World world = World::file;
  int top_k = 4;                 ///< phases kept per voxel, in [1, 16]
  /// Create's snapping threshold in grid spacings (MeshOptions::snap, which
  /// the run functions copy here): with voxel_faithful, a voxel centre bcc has
  /// no node for is lost unless its label leads by more than it.
  double snap = 0.2;
  // Volumes (labels and distance grids).
  /// The scene's grid: cells of about this many voxels (of the smallest
  /// spacing) along each axis, in [1, 64]; 1 = the voxel grid itself. A
  /// coarser grid gives a coarser mesh (2: about a quarter of the triangles)
  /// of the same phase functions, still evaluated at voxel resolution by the
  /// improvement's projection. 0, the default: the voxel grid, unless the
  /// voxels are flat (longest side over 1.2 times the shortest, as CT and MR
  /// slices thicker than their pixels): then cubic cells of the voxels' volume,
  /// about as many as the voxels (with voxel_faithful, the voxel grid always).
  double voxels_per_cell = 0;
  /// The voxel size along the file's axes, instead of the file's (for a file
  /// that says none, such as a TIFF not written by ImageJ, or a wrong one);
  /// each > 0 and finite. Unset: the file's.
  std::optional<Vec3> voxel_size;
};

/// Reads `path` as whatever it is, by extension: .json a scene (load_scene);
/// a volume (io::is_volume_file): integers are a label volume, one phase per
/// label ordered by label value, reals a signed-distance grid with one component
/// per phase (larger = inside). The scene's grid is the voxel grid, nodes at
/// voxel centres (one voxel more along an axis with an odd number of cells, so
/// the bcc lattice keeps them), or with `voxels_per_cell` > 1 a grid of
/// coarser, nearly cubic cells over the same box. Errors are one line naming the file.
/// @param path    the input: a scene (.json), a volume (io::is_volume_file()) or a labelled point file
///                (.xyz, .txt, .pts, .csv, .ply; docs/inputs.md)
/// @param options how the input is read; an option that does not apply to this kind of input must keep
///                its default (refuse_options_that_do_not_apply())
/// @return the scene of the input
/// @throws InvalidInput for bad content or a bad option, or an unknown extension
/// @throws IoError      if the file cannot be read
Scene load_input(const std::string& path, const InputOptions& options = {});

/// Reads a volume file and places its voxels as load_input() does: in the frame
/// InputOptions::world asks for, its axes made the identity (flipped and
/// permuted voxels keeping their world positions), so that voxel (i, j, k) lies
/// at origin + spacing .* (i, j, k) in the coordinates of a mesh made from it.
/// @param path    a volume (io::is_volume_file())
/// @param options read for `world` and `ignore_direction`
/// @param world   if given, set to the frame of the coordinates as Scene::world says it
/// @return the volume, its direction the identity
/// @throws InvalidInput for an oblique direction (unless ignore_direction), or a frame the file does not state
/// @throws IoError      if the file cannot be read
io::Volume read_placed_volume(const std::string& path, const InputOptions& options, std::string* world = nullptr);

/// Throws InvalidInput "<what>: --smoothing, ... apply only to volumes, and
/// this is <kind>" when an option that only volumes (or label volumes) use differs
/// from its default, so that none is silently ignored. load_input() checks its
/// inputs with it; a program meshing a scene of its own (the CLI's demo) can too.
/// @param options the options to check
/// @param volume  whether the options for volumes apply
/// @param labels  whether the options for label volumes apply
/// @param kind    names the kind of input in the message ("a scene")
/// @param what    names the input in the message (the file name, "the built-in demo")
/// @throws InvalidInput when an option that does not apply differs from its default
void refuse_options_that_do_not_apply(const InputOptions& options, bool volume, bool labels, const std::string& kind,
                                      const std::string& what);

} // namespace vm
