// paraview/filter/vtkVoronoiMeshFilter.h: voronoimesh as a VTK filter, the
// algorithm behind ParaView's "Voronoi Mesh" (VoronoiMeshFilter.xml).
//
// Input: image data with an integer label array (point data: a label per
// point; cell data: a label per voxel, its centre the node) or, when phase
// arrays are named, one scalar point array per phase (larger = more inside).
// Outputs: 0 the interface mesh (triangles; cell arrays phase0, phase1 with the
// label values of the phases on either side; field data naming each phase),
// 1 the triple curves (polylines; cell arrays phase0..phase2, phases, closed),
// 2 the quality history (a table, one row per improvement iteration).
// The mesh is the one `voronoimesh mesh` makes of the same data and options.
#pragma once

#include "vtkPolyDataAlgorithm.h"
#include "vtkVoronoiMeshFiltersModule.h"

#include <string>
#include <vector>

class VTKVORONOIMESHFILTERS_EXPORT vtkVoronoiMeshFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkVoronoiMeshFilter* New();
  vtkTypeMacro(vtkVoronoiMeshFilter, vtkPolyDataAlgorithm)
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Improvement iterations (mesh --iterations); 0 keeps the initial mesh.
  vtkSetMacro(Iterations, int)
  vtkGetMacro(Iterations, int)
  /// Passes per iteration (mesh --pipeline); empty: the input's default.
  vtkSetStdStringFromCharMacro(Pipeline)
  vtkGetCharFromStdStringMacro(Pipeline)
  /// Target edge length in world units (mesh --size); 0: the default sizing.
  vtkSetMacro(Size, double)
  vtkGetMacro(Size, double)
  /// With Size: largest distance off a curved surface, world units (mesh --tolerance); 0: none.
  vtkSetMacro(Tolerance, double)
  vtkGetMacro(Tolerance, double)
  /// Close the box: its faces become surfaces against a phase "exterior" (mesh --close).
  vtkSetMacro(Close, bool)
  vtkGetMacro(Close, bool)
  /// Snapping threshold in grid spacings (mesh --snap).
  vtkSetMacro(Snap, double)
  vtkGetMacro(Snap, double)
  /// Labels: Gaussian sigma in voxels of the smoothed indicators (mesh --smoothing).
  vtkSetMacro(Smoothing, double)
  vtkGetMacro(Smoothing, double)
  /// Labels: banded signed distances instead of smoothed indicators (mesh --signed-distance).
  vtkSetMacro(SignedDistance, bool)
  vtkGetMacro(SignedDistance, bool)
  /// Worker threads, 0 = all cores (mesh --threads); the mesh does not depend on it.
  vtkSetMacro(Threads, int)
  vtkGetMacro(Threads, int)

  /// Point arrays holding one phase function each; none: the label array
  /// (input array 0) is meshed.
  void AddPhaseArray(const char* name);
  void ClearPhaseArrays();

protected:
  vtkVoronoiMeshFilter();
  ~vtkVoronoiMeshFilter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs) override;

private:
  vtkVoronoiMeshFilter(const vtkVoronoiMeshFilter&) = delete;
  void operator=(const vtkVoronoiMeshFilter&) = delete;

  int Iterations = 20;
  std::string Pipeline;
  double Size = 0;
  double Tolerance = 0;
  bool Close = false;
  double Snap = 0.2;
  double Smoothing = 1.0;
  bool SignedDistance = false;
  int Threads = 0;
  std::vector<std::string> PhaseArrays;
};
