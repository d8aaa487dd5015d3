#include "vtkVoronoiMeshFilter.h"

#include "image_scene.h"
#include "mesh_to_vtk.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include <voronoimesh/voronoimesh.hpp>

#include <algorithm>

vtkStandardNewMacro(vtkVoronoiMeshFilter);

namespace {

/// A run watched from the filter: stages and iterations as the algorithm's
/// progress, notes (e.g. a label the mesh lost) as warnings, ParaView's abort
/// as the run's stop, and every iteration's report kept for the history table.
class FilterObserver : public vm::RunObserver {
public:
  explicit FilterObserver(vtkVoronoiMeshFilter& filter) : filter_(filter) {}

  void stage(vm::Stage stage, const std::string& what) override {
    // Sampling and creating are a tenth of a default run; improving the rest.
    const double at[] = {0.0, 0.02, 0.05, 0.1, 1.0};
    filter_.SetProgressText(what.c_str());
    filter_.UpdateProgress(at[int(stage)]);
  }
  void iteration(const vm::IterationReport& report, const vm::InterfaceMesh&) override {
    history.push_back(report);
    // To the run's last iteration as it knows it: one that converged ends at 1.
    if (report.last_iteration > 0) filter_.UpdateProgress(0.1 + 0.9 * report.iteration / report.last_iteration);
  }
  void note(const std::string& line) override { vtkWarningWithObjectMacro(&filter_, << line); }
  bool stop_requested() override { return filter_.GetAbortExecute() != 0; }

  std::vector<vm::IterationReport> history;

private:
  vtkVoronoiMeshFilter& filter_;
};

} // namespace

vtkVoronoiMeshFilter::vtkVoronoiMeshFilter() {
  // The library's defaults, which are the CLI's.
  const vm::MeshOptions mesh;
  const vm::InputOptions input;
  Iterations = mesh.iterations;
  Snap = mesh.snap;
  Close = mesh.close;
  Threads = mesh.threads;
  Smoothing = input.smoothing;
  SignedDistance = input.label_function == vm::LabelFunction::signed_distance;
  SetNumberOfOutputPorts(3);
  // The labels: the input's active point scalars until the panel picks an array.
  SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

void vtkVoronoiMeshFilter::AddPhaseArray(const char* name) {
  if (!name) return;
  PhaseArrays.emplace_back(name);
  Modified();
}

void vtkVoronoiMeshFilter::ClearPhaseArrays() {
  if (PhaseArrays.empty()) return;
  PhaseArrays.clear();
  Modified();
}

int vtkVoronoiMeshFilter::FillInputPortInformation(int, vtkInformation* info) {
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkVoronoiMeshFilter::FillOutputPortInformation(int port, vtkInformation* info) {
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 2 ? "vtkTable" : "vtkPolyData");
  return 1;
}

int vtkVoronoiMeshFilter::RequestData(vtkInformation*, vtkInformationVector** inputs, vtkInformationVector* outputs) {
  vtkImageData* image = vtkImageData::GetData(inputs[0]);
  vtkPolyData* surfaces = vtkPolyData::GetData(outputs, 0);
  vtkPolyData* junctions = vtkPolyData::GetData(outputs, 1);
  vtkTable* history = vtkTable::GetData(outputs, 2);
  if (!image || !surfaces || !junctions || !history) return 0;

  vm::MeshOptions options;
  options.iterations = Iterations;
  options.pipeline = Pipeline;
  options.size = Size;
  options.tolerance = Tolerance;
  options.close = Close;
  options.snap = Snap;
  options.threads = Threads;
  vm::InputOptions input;
  input.smoothing = Smoothing;
  if (SignedDistance) input.label_function = vm::LabelFunction::signed_distance;
  input.top_k = options.top_k;
  input.snap = options.snap;

  FilterObserver observer(*this);
  try {
    vmpv::ImageFrame frame;
    vm::Scene scene;
    if (PhaseArrays.empty()) {
      int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
      vtkDataArray* labels = GetInputArrayToProcess(0, image, association);
      if (!labels) {
        vtkErrorMacro("no label array: pick one (Labels) or name phase arrays (Phase Arrays)");
        return 0;
      }
      if (association != vtkDataObject::FIELD_ASSOCIATION_POINTS &&
          association != vtkDataObject::FIELD_ASSOCIATION_CELLS) {
        vtkErrorMacro("label array '" << labels->GetName() << "': point or cell data expected");
        return 0;
      }
      frame = vmpv::image_frame(*image, association == vtkDataObject::FIELD_ASSOCIATION_CELLS
                                            ? vmpv::Association::cells : vmpv::Association::points);
      scene = vmpv::labels_scene(frame, *labels, input);
    } else {
      std::vector<vtkDataArray*> phases;
      for (const std::string& name : PhaseArrays) {
        vtkDataArray* a = image->GetPointData()->GetArray(name.c_str());
        if (!a) {
          vtkErrorMacro("no point array '" << name << "' to use as a phase function");
          return 0;
        }
        phases.push_back(a);
      }
      frame = vmpv::image_frame(*image, vmpv::Association::points);
      scene = vmpv::phase_values_scene(frame, phases, options.top_k);
    }
    const vm::NodeMesh mesh = vm::mesh_scene(scene, options, &observer);
    vmpv::surfaces_to_polydata(mesh, frame, *surfaces);
    vmpv::junctions_to_polydata(mesh, *surfaces, *junctions);
    vmpv::history_to_table(observer.history, *history);
  } catch (const vm::Cancelled&) {
    return 1; // aborted from ParaView: empty outputs, no error
  } catch (const std::exception& e) {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  UpdateProgress(1.0);
  return 1;
}

void vtkVoronoiMeshFilter::PrintSelf(ostream& os, vtkIndent indent) {
  Superclass::PrintSelf(os, indent);
  os << indent << "Iterations: " << Iterations << "\n"
     << indent << "Pipeline: " << (Pipeline.empty() ? "(the input's default)" : Pipeline) << "\n"
     << indent << "Size: " << Size << "\n"
     << indent << "Tolerance: " << Tolerance << "\n"
     << indent << "Close: " << Close << "\n"
     << indent << "Snap: " << Snap << "\n"
     << indent << "Smoothing: " << Smoothing << "\n"
     << indent << "SignedDistance: " << SignedDistance << "\n"
     << indent << "Threads: " << Threads << "\n"
     << indent << "PhaseArrays: " << PhaseArrays.size() << "\n";
}
