#include "image_scene.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"

#include <limits>
#include <span>
#include <type_traits>

namespace vmpv {

vm::Vec3 ImageFrame::to_world(const vm::Vec3& p) const {
  if (axis_aligned) return p;
  const vm::Vec3 d = p - origin;
  const auto& m = direction;
  return origin + vm::Vec3(m[0] * d[0] + m[1] * d[1] + m[2] * d[2], m[3] * d[0] + m[4] * d[1] + m[5] * d[2],
                           m[6] * d[0] + m[7] * d[1] + m[8] * d[2]);
}

ImageFrame image_frame(vtkImageData& image, Association where) {
  ImageFrame frame;
  int extent[6];
  image.GetExtent(extent);
  const double* spacing = image.GetSpacing();
  const double* origin = image.GetOrigin();
  const vtkMatrix3x3* d = image.GetDirectionMatrix();
  frame.origin = vm::Vec3(origin[0], origin[1], origin[2]);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      frame.direction[size_t(3 * r + c)] = d->GetElement(r, c);
      if (d->GetElement(r, c) != (r == c ? 1.0 : 0.0)) frame.axis_aligned = false;
    }
  // Cell data lies at the voxels' centres, half a voxel in from the points.
  const double shift = where == Association::cells ? 0.5 : 0.0;
  const int fewer = where == Association::cells ? 1 : 0;
  for (int a = 0; a < 3; ++a) {
    frame.grid.cells[size_t(a)] = extent[2 * a + 1] - extent[2 * a] - fewer;
    frame.grid.domain.min[a] = origin[a] + spacing[a] * (extent[2 * a] + shift);
    frame.grid.domain.max[a] = frame.grid.domain.min[a] + spacing[a] * frame.grid.cells[size_t(a)];
  }
  return frame;
}

namespace {

template <class T>
void copy_labels(const T* values, vtkIdType count, std::vector<int32_t>& out, const std::string& name) {
  out.resize(size_t(count));
  for (vtkIdType n = 0; n < count; ++n) {
    const T v = values[n];
    if constexpr (sizeof(T) >= sizeof(int32_t) && !std::is_same_v<T, int32_t>) {
      if (v < T(std::numeric_limits<int32_t>::min()) || v > T(std::numeric_limits<int32_t>::max()))
        throw vm::InvalidInput("label array '" + name + "': label " + std::to_string(v) +
                               " does not fit in 32 bits (voronoimesh keeps labels as 32-bit integers)");
    }
    out[size_t(n)] = int32_t(v);
  }
}

} // namespace

vm::Scene labels_scene(const ImageFrame& frame, vtkDataArray& labels, const vm::InputOptions& options) {
  const std::string name = labels.GetName() ? labels.GetName() : "labels";
  if (labels.GetNumberOfComponents() != 1)
    throw vm::InvalidInput("label array '" + name + "': one component expected, it has " +
                           std::to_string(labels.GetNumberOfComponents()));
  std::vector<int32_t> values;
  bool integral = true;
  switch (labels.GetDataType()) {
    vtkTemplateMacro(if constexpr (std::is_integral_v<VTK_TT>) copy_labels(
                         static_cast<const VTK_TT*>(labels.GetVoidPointer(0)), labels.GetNumberOfTuples(), values, name);
                     else integral = false);
  default: integral = false;
  }
  if (!integral)
    throw vm::InvalidInput("label array '" + name + "': an integer array expected, it holds " +
                           std::string(labels.GetDataTypeAsString()) +
                           " values (name phase arrays to mesh real values as phase functions)");
  return vm::scene_from_labels(frame.grid, values, options, name);
}

vm::Scene phase_values_scene(const ImageFrame& frame, const std::vector<vtkDataArray*>& phases, int top_k) {
  std::vector<std::vector<double>> values(phases.size());
  std::vector<std::span<const double>> spans;
  vm::PhaseValuesOptions options;
  options.top_k = top_k;
  options.source = "phase arrays";
  for (size_t p = 0; p < phases.size(); ++p) {
    vtkDataArray& a = *phases[p];
    const std::string name = a.GetName() ? a.GetName() : "phase" + std::to_string(p);
    if (a.GetNumberOfComponents() != 1)
      throw vm::InvalidInput("phase array '" + name + "': one component expected, it has " +
                             std::to_string(a.GetNumberOfComponents()));
    values[p].resize(size_t(a.GetNumberOfTuples()));
    for (vtkIdType n = 0; n < a.GetNumberOfTuples(); ++n) values[p][size_t(n)] = a.GetComponent(n, 0);
    spans.emplace_back(values[p]);
    options.names.push_back(name);
  }
  return vm::scene_from_phase_values(frame.grid, spans, options);
}

} // namespace vmpv
