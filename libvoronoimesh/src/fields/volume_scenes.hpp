#pragma once
/// @file fields/volume_scenes.hpp
/// The scenes of gridded inputs, whether read from a file (load_input) or
/// handed over in memory by a program (fields/array_input.hpp): one code path, so the
/// same data meshes the same way whichever door it came in by.

#include "voronoimesh/fields/input.hpp"
#include "voronoimesh/io/volume.hpp"

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace vm::detail {

/// Throws InvalidInput, naming the option as the CLI spells it, for an option
/// of `o` out of range (smoothing, band, top_k, a merge group of one label).
void check_input_options(const InputOptions& o);

/// The scene of a label volume (`v.integer`, one component): one phase per
/// label left after the drop, merge and background options of `o`, ordered by
/// label value, its phase function as LabelFunction says. Throws InvalidInput
/// naming `source` for more components, fewer than 2 or more than kMaxPhases
/// phases, an option naming a label not in the volume, or a volume too big for
/// this machine's memory.
Scene label_volume_scene(io::Volume v, const InputOptions& o, const std::string& source);

/// Writes the value of every phase at grid node n (i fastest) into `out`.
using NodeValues = std::function<void(int64_t n, std::span<float> out)>;

/// The scene of `num_phases` phase functions given by their values on the
/// nodes of `grid` (larger = inside), interpolated trilinearly in between and
/// kept as the `top_k` largest per node. Phase i is named names[i] ("phase<i>"
/// when `names` is empty) and shows labels[i] in files (identity when empty).
/// The scene's grid is `grid` with one more cell along an axis with an odd
/// count (even_scene_grid). Throws InvalidInput naming `source` for fewer than
/// 2 or more than kMaxPhases phases, names or labels of the wrong count, labels
/// not strictly increasing, a value that is not finite as a float (naming the
/// phase and node), or a grid too big for this machine's memory.
Scene phase_values_scene(const GridSpec& grid, int num_phases, const NodeValues& fill, std::vector<std::string> names,
                         std::vector<int32_t> labels, int top_k, const std::string& source);

} // namespace vm::detail
