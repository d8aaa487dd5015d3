#include "mesh_to_vtk.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include <string>

namespace vmpv {

namespace {

vtkNew<vtkIntArray> int_array(const char* name, vtkIdType count) {
  vtkNew<vtkIntArray> a;
  a->SetName(name);
  a->SetNumberOfTuples(count);
  return a;
}

} // namespace

void surfaces_to_polydata(const vm::NodeMesh& mesh, const ImageFrame& frame, vtkPolyData& out) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(vtkIdType(mesh.points.size()));
  for (size_t n = 0; n < mesh.points.size(); ++n) {
    const vm::Vec3 p = frame.to_world(mesh.points[n]);
    points->SetPoint(vtkIdType(n), p[0], p[1], p[2]);
  }
  out.SetPoints(points);
  const vtkIdType count = vtkIdType(mesh.triangles.size());
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfTuples(count + 1);
  connectivity->SetNumberOfTuples(3 * count);
  auto phase0 = int_array("phase0", count), phase1 = int_array("phase1", count);
  for (vtkIdType t = 0; t < count; ++t) {
    offsets->SetValue(t, 3 * t);
    for (int k = 0; k < 3; ++k) connectivity->SetValue(3 * t + k, mesh.triangles[size_t(t)][size_t(k)]);
    phase0->SetValue(t, mesh.label_of(mesh.pairs[size_t(t)][0]));
    phase1->SetValue(t, mesh.label_of(mesh.pairs[size_t(t)][1]));
  }
  offsets->SetValue(count, 3 * count);
  vtkNew<vtkCellArray> triangles;
  triangles->SetData(offsets, connectivity);
  out.SetPolys(triangles);
  out.GetCellData()->AddArray(phase0);
  out.GetCellData()->AddArray(phase1);
  out.GetCellData()->SetActiveScalars("phase1");
  for (size_t p = 0; p < mesh.phase_names.size(); ++p) {
    auto label = int_array(mesh.phase_names[p].c_str(), 1);
    label->SetValue(0, mesh.label_of(int32_t(p)));
    out.GetFieldData()->AddArray(label);
  }
}

void junctions_to_polydata(const vm::NodeMesh& mesh, vtkPolyData& surfaces, vtkPolyData& out) {
  out.SetPoints(surfaces.GetPoints());
  const vm::Junctions junctions = vm::find_junctions(mesh);
  const vtkIdType count = vtkIdType(junctions.curves.size());
  vtkNew<vtkCellArray> lines;
  auto closed = int_array("closed", count);
  vtkNew<vtkIntArray> phase[3];
  vtkNew<vtkStringArray> phases;
  phases->SetName("phases");
  phases->SetNumberOfValues(count);
  for (int k = 0; k < 3; ++k) {
    phase[k]->SetName(("phase" + std::to_string(k)).c_str());
    phase[k]->SetNumberOfTuples(count);
  }
  for (vtkIdType c = 0; c < count; ++c) {
    const vm::TripleCurve& curve = junctions.curves[size_t(c)];
    lines->InsertNextCell(vtkIdType(curve.nodes.size()));
    for (int32_t n : curve.nodes) lines->InsertCellPoint(n);
    std::string all;
    for (size_t k = 0; k < curve.phases.size(); ++k) {
      const int label = mesh.label_of(curve.phases[k]);
      if (k < 3) phase[k]->SetValue(c, label);
      all += (k ? " " : "") + std::to_string(label);
    }
    phases->SetValue(c, all);
    closed->SetValue(c, curve.closed() ? 1 : 0);
  }
  out.SetLines(lines);
  for (auto& a : phase) out.GetCellData()->AddArray(a);
  out.GetCellData()->AddArray(phases);
  out.GetCellData()->AddArray(closed);
}

void history_to_table(const std::vector<vm::IterationReport>& history, vtkTable& out) {
  const vtkIdType rows = vtkIdType(history.size());
  auto iteration = int_array("iteration", rows), flips = int_array("flips", rows),
       undone = int_array("undone_moves", rows);
  vtkNew<vtkDoubleArray> min_q, mean_q, seconds;
  min_q->SetName("min_quality");
  mean_q->SetName("mean_quality");
  seconds->SetName("seconds");
  for (auto* a : {min_q.Get(), mean_q.Get(), seconds.Get()}) a->SetNumberOfTuples(rows);
  for (vtkIdType r = 0; r < rows; ++r) {
    const vm::IterationReport& h = history[size_t(r)];
    iteration->SetValue(r, h.iteration);
    min_q->SetValue(r, h.min_quality);
    mean_q->SetValue(r, h.mean_quality);
    flips->SetValue(r, int(h.flips));
    undone->SetValue(r, int(h.undone_moves));
    seconds->SetValue(r, h.seconds);
  }
  out.AddColumn(iteration);
  out.AddColumn(min_q);
  out.AddColumn(mean_q);
  out.AddColumn(flips);
  out.AddColumn(undone);
  out.AddColumn(seconds);
}

} // namespace vmpv
