#pragma once
/// @file io/slicer_segments.hpp
/// 3D Slicer segmentations (`.seg.nrrd`): the segments their NRRD header lists
/// as key/value pairs (Segment<i>_ID, _Name, _LabelValue, _Layer, _Color), and
/// their layers, where segments overlap, flattened into one label volume.

#include "voronoimesh/io/volume.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace vm::io::slicer {

/// Looks up a key of the header: its value, or nothing when absent.
using HeaderValue = std::function<std::optional<std::string>(const std::string& key)>;

/// The segments of a header (none unless it has Segment0_ID), in file order,
/// for a file of `layers` layers (its components). Files older than Slicer 4.11
/// give neither label values nor layers: each segment is then the voxels of
/// value 1 in its own layer. Throws InvalidInput naming `path` for a field that
/// does not parse, a layer beyond the file's, a label value of 0 (no segment)
/// or two segments on one value of one layer.
std::vector<Segment> read_segments(const HeaderValue& value_of, int layers, const std::string& path);

/// Makes `v` (with v.segments from read_segments, v.components its layers)
/// one label volume: each voxel takes the label of the segment it lies in,
/// 0 where none. Where segments of different layers overlap, the smallest (by
/// voxels; the first in the file on a tie) keeps the voxel, so a structure
/// segmented inside another (a tumour in an organ) stays; v.notes says how many
/// voxels that decided. Segment labels stay their label values when those
/// differ (always so in one layer); otherwise segment i is relabelled i + 1.
/// Throws InvalidInput naming `path` for a layer holding a value that no
/// segment has.
void flatten_segment_layers(Volume& v, const std::string& path);

} // namespace vm::io::slicer
