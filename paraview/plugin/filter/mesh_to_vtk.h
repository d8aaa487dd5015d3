// paraview/filter/mesh_to_vtk.h: a voronoimesh mesh as VTK data: the surfaces
// as polydata, the triple curves as polylines, the quality history as a table.
#pragma once

#include "image_scene.h"

#include <voronoimesh/voronoimesh.hpp>

#include <vector>

class vtkPolyData;
class vtkTable;

namespace vmpv {

/// Triangles of `mesh` (points through frame.to_world()) with cell arrays
/// phase0 and phase1 (label values; the normal points from phase0 into
/// phase1), and one field-data array per phase, named as the phase, holding
/// its label (as the VTU writer stores them).
void surfaces_to_polydata(const vm::NodeMesh& mesh, const ImageFrame& frame, vtkPolyData& out);

/// One polyline per triple curve of `mesh` on the points of `surfaces` (made
/// by surfaces_to_polydata(), shared, not copied), with cell arrays phase0,
/// phase1, phase2 (the labels of its first three phases), phases (all of
/// them, "0 3 7") and closed (1 for a loop).
void junctions_to_polydata(const vm::NodeMesh& mesh, vtkPolyData& surfaces, vtkPolyData& out);

/// One row per improvement iteration (0: the initial mesh): iteration,
/// min_quality, mean_quality, flips, undone_moves, seconds.
void history_to_table(const std::vector<vm::IterationReport>& history, vtkTable& out);

} // namespace vmpv
