#include "image_scene.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <span>
#include <type_traits>
#include <utility>

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

/// The labels of an array of integers that fit in 32 bits, or of reals that
/// are all whole numbers that do (as volume files of reals are read: a label
/// map loaded from a float NIfTI, or resampled, holds floats).
template <class T>
void copy_labels(const T* values, vtkIdType count, std::vector<int32_t>& out, const std::string& name) {
  out.resize(size_t(count));
  for (vtkIdType n = 0; n < count; ++n) {
    const T v = values[n];
    if constexpr (std::is_floating_point_v<T>) {
      const double d = double(v); // compared as doubles: float(INT32_MAX) is 2^31, beyond the range
      if (!(d >= std::numeric_limits<int32_t>::min() && d <= std::numeric_limits<int32_t>::max() &&
            d == std::trunc(d))) {
        std::ostringstream value;
        value << std::setprecision(std::numeric_limits<T>::max_digits10) << v;
        throw vm::InvalidInput("label array '" + name + "': value " + value.str() + " at tuple " + std::to_string(n) +
                               " is not a label (a real array is read as labels when every value is a whole 32-bit "
                               "number: resampled with linear interpolation? resample it with nearest neighbour; "
                               "name phase arrays to mesh real values as phase functions)");
      }
    } else if constexpr (sizeof(T) >= sizeof(int32_t)) {
      // std::cmp_*: T(INT32_MIN) of an unsigned T is 2^31, which every small label is below.
      if (std::cmp_less(v, std::numeric_limits<int32_t>::min()) ||
          std::cmp_greater(v, std::numeric_limits<int32_t>::max()))
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
  switch (labels.GetDataType()) {
    vtkTemplateMacro(copy_labels(static_cast<const VTK_TT*>(labels.GetVoidPointer(0)), labels.GetNumberOfTuples(),
                                 values, name));
  default:
    throw vm::InvalidInput("label array '" + name + "': an array of numbers expected, it holds " +
                           std::string(labels.GetDataTypeAsString()) + " values");
  }
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
