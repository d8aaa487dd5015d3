#pragma once
/// @file fields/array_input.hpp
/// Scenes from data a program already holds in memory, no files involved: the
/// values of every phase function on a grid (a level-set or phase-field
/// simulation), a label per grid node (a segmentation, a grain map) or
/// labelled points (paper sect. 5, eq. 7). Each builds the same phase functions
/// as the matching file input of load_input() (fields/input.hpp, docs/inputs.md), so
/// a program and the CLI mesh the same data the same way.
///
/// Grid data lies on the nodes of a GridSpec, `grid.cells[a] + 1` nodes along
/// axis a, node (i, j, k) at index grid.node_index(i, j, k) (i fastest). The
/// returned Scene's grid is that grid with one more cell along an axis with an
/// odd cell count (the bcc lattice needs even counts to keep the data nodes as
/// lattice nodes; the field extends constantly over that cell). Every function
/// copies what it needs: the arrays may be freed once it returns.

#include "voronoimesh/core/types.hpp"
#include "voronoimesh/fields/input.hpp"
#include "voronoimesh/fields/scene.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace vm {

/// How phase values on a grid become phases.
struct PhaseValuesOptions {
  /// Display name of each phase (one per phase); empty: "phase0", "phase1"...
  std::vector<std::string> names;
  /// The id each phase shows in output files, strictly increasing (one per
  /// phase); empty: the phase index (PhaseField::phase_label).
  std::vector<int32_t> labels;
  /// Phases kept per grid node, in [1, 16]: memory is O(nodes x top_k) however
  /// many phases there are; 4 is exact wherever at most 4 phases compete.
  int top_k = 4;
  /// Names the data in error messages ("<source>: ...").
  std::string source = "phase values";
};

/// The scene of phase functions given by their values at the grid nodes, one
/// array per phase: phases[p][n] is phi_p at node n, larger = more inside phase
/// p (a signed distance positive inside, a phase-field order parameter...);
/// interpolated trilinearly between nodes.
/// @param grid    the grid the values lie on: cells in [1, 4096] per axis, a non-empty domain
/// @param phases  one array per phase, 2 to kMaxPhases of them; each holds grid.node_count() values,
///                finite as floats. Copied: they may be freed once the call returns.
/// @param options the phases' names and labels, top_k and the source named in errors
/// @return the scene; its grid is `grid` with one more cell along an axis with an odd cell count
/// @throws InvalidInput "<source>: ..." for fewer than 2 or more than kMaxPhases phases, an array of the
///         wrong length, a grid with a cell count outside [1, 4096] or an empty domain, a value that is not
///         finite as a float (naming phase and node), names or labels of the wrong count, labels not
///         strictly increasing, top_k outside [1, 16], or a grid too big for this machine's memory
Scene scene_from_phase_values(const GridSpec& grid, const std::vector<std::span<const double>>& phases,
                              const PhaseValuesOptions& options = {});

/// As scene_from_phase_values(), the values interleaved per node:
/// values[p + num_phases * n] is phi_p at node n (num_phases x node_count()
/// values), as a distance grid with one component per phase stores them.
/// @param grid       the grid the values lie on, as for scene_from_phase_values()
/// @param values     num_phases x grid.node_count() values, phase fastest. Copied.
/// @param num_phases the number of phases, 2 to kMaxPhases
/// @param options    the phases' names and labels, top_k and the source named in errors
/// @return the scene, as scene_from_phase_values() makes it
/// @throws InvalidInput "<source>: ..." as scene_from_phase_values(), and for an array whose length is
///         not num_phases x grid.node_count()
Scene scene_from_interleaved_values(const GridSpec& grid, std::span<const double> values, int num_phases,
                                    const PhaseValuesOptions& options = {});

/// The scene of a label per grid node (a segmented volume whose voxel centres
/// are the grid nodes): one phase per label, ordered by label value, each phase
/// showing its label in files, named "label<l>" ("background" for
/// options.background). The phase functions are those of a label volume:
/// smoothed indicators or banded signed distances, with every option of
/// InputOptions (drop and merge labels, background, smoothing, band, top_k;
/// ignore_direction does not apply).
/// @param grid    the grid the labels lie on, as for scene_from_phase_values()
/// @param labels  one label per grid node, grid.node_count() of them. Copied.
/// @param options how the labels' phase functions are made, as for a label volume
/// @param source  names the data in error messages ("<source>: ...")
/// @return the scene, one phase per label
/// @throws InvalidInput "<source>: ..." as scene_from_phase_values() for the grid and array length, for
///         fewer than 2 phases after the label options, an option naming a label not present, or an option
///         out of range (named as its CLI option, e.g. "--smoothing: ...")
Scene scene_from_labels(const GridSpec& grid, std::span<const int32_t> labels, const InputOptions& options = {},
                        const std::string& source = "labels");

/// The scene of labelled points: phi_l(x) = minus the distance from x to the
/// nearest point labelled l (paper eq. 7), one phase per label ordered by
/// label value. The domain is the points' bounding box grown by 5% of its
/// largest side, the grid 64 cells along the longest side and cells of the same
/// size along the others (set scene.grid.cells, or MeshOptions::grid, for
/// another resolution).
/// @param points the points. Copied.
/// @param labels the label of each point, one per point
/// @param source names the data in error messages ("<source>: ...")
/// @return the scene, one phase per distinct label
/// @throws InvalidInput "<source>: ..." when points and labels differ in number, for no points, a
///         non-finite coordinate (naming the point), fewer than 2 or more than kMaxPhases labels
Scene scene_from_points(std::span<const Vec3> points, std::span<const int32_t> labels,
                        const std::string& source = "points");

} // namespace vm
