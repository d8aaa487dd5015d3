/// @file fields/ply_points.cpp
/// Labelled point clouds stored as PLY: the vertex element's x, y, z and an
/// integer label, read through the same PLY container code as meshes.

#include "fields/point_cloud.hpp"

#include "voronoimesh/core/errors.hpp"

#include "core/text.hpp"
#include "io/ply_format.hpp"

#include <algorithm>
#include <array>

namespace vm::detail {

LabelledPoints read_ply_points(const std::string& path) {
  io::ply::File file(path);
  const io::ply::Element* vertex = file.header().element("vertex");
  if (!vertex) throw InvalidInput(located(path, "no vertex element (a labelled point cloud stores its points there)"));
  auto scalar_property = [&](std::string_view name) {
    const io::ply::Property* p = vertex->find(name);
    return p && !p->count ? p : nullptr;
  };
  std::array<const io::ply::Property*, 3> xyz{};
  for (int a = 0; a < 3; ++a) {
    const char* name = a == 0 ? "x" : a == 1 ? "y" : "z";
    xyz[size_t(a)] = scalar_property(name);
    if (!xyz[size_t(a)]) throw InvalidInput(located(path, cat("no vertex property '", name, "'")));
  }
  // Segmentation tools name the per-point id variously; the first present wins.
  const io::ply::Property* label = nullptr;
  for (const char* name : {"label", "phase", "region"})
    if (!label) label = scalar_property(name);
  if (!label) throw InvalidInput(located(path, "no vertex property 'label' (a labelled point cloud needs one)"));

  LabelledPoints out;
  file.read_body([&](const io::ply::Element& e) {
    if (&e != vertex) return false;
    out.points.resize(size_t(e.count));
    out.labels.resize(size_t(e.count));
    for (uint64_t i = 0; i < e.count; ++i) {
      const auto what = [&] { return cat("vertex ", i); };
      Vec3& p = out.points[size_t(i)];
      for (const auto& prop : e.props) {
        if (&prop == label) {
          // Float labels are fine when integral (many tools store every property as float).
          const double l = file.scalar(prop.type, what);
          if (!io::ply::is_int32(l))
            throw InvalidInput(located(path, cat("vertex ", i, ": label ", l, " is not a 32-bit integer")));
          out.labels[size_t(i)] = int32_t(l);
        } else if (const auto slot = std::find(xyz.begin(), xyz.end(), &prop); slot != xyz.end()) {
          p[slot - xyz.begin()] = file.scalar(prop.type, what);
        } else {
          file.skip(e, i, prop);
        }
      }
      if (!p.allFinite()) throw InvalidInput(located(path, cat("vertex ", i, ": coordinates must be finite")));
    }
    return true;
  });
  return out;
}

} // namespace vm::detail
