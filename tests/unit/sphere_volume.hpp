#pragma once
/// @file sphere_volume.hpp
/// The input tests' volume (test_input.cpp, test_grid_inputs.cpp): a sphere of
/// radius 10 voxels in 32^3 voxels 0.5 apart from (1, 2, 3), as labels or
/// distances, and what the tests do with a scene (create, improve, read its
/// labels, catch its error).

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/sampled_field.hpp"
#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vm::test::sphere_volume {

inline constexpr int n = 32;                     // voxels per axis
inline constexpr double voxel = 0.5;             // spacing
inline const Vec3 origin(1, 2, 3);               // centre of voxel 0
inline const Vec3 centre_vox(15.3, 15.6, 15.8);  // sphere centre, voxel units
inline constexpr double radius_vox = 10.0;

inline Vec3 world(const Vec3& vox) { return origin + voxel * vox; }

/// Labels of a 32^3 volume: `inside` within the sphere, 0 elsewhere, and
/// `more(i, j, k)` may override (returning -1 keeps the sphere's label).
inline std::vector<uint16_t> sphere_labels(uint16_t inside, const std::function<int(int, int, int)>& more = {}) {
  std::vector<uint16_t> v;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        int l = (Vec3(i, j, k) - centre_vox).norm() < radius_vox ? inside : 0;
        if (more && more(i, j, k) >= 0) l = more(i, j, k);
        v.push_back(uint16_t(l));
      }
  return v;
}

inline const std::string sphere_header = "type: ushort\ndimension: 3\nsizes: 32 32 32\nspace: left-posterior-superior\n"
                                  "space directions: (0.5,0,0) (0,0.5,0) (0,0,0.5)\nspace origin: (1,2,3)\n";

inline NodeMesh create(const Scene& scene) {
  SampledField field = SampledField::sample(*scene.field, grid_for_lattice(scene.grid, Lattice::bcc));
  NodeMesh mesh;
  create_initial_mesh(field, {}, mesh);
  return mesh;
}

inline std::vector<int32_t> labels_of(const PhaseField& f) {
  std::vector<int32_t> out;
  for (int i = 0; i < f.num_phases(); ++i) out.push_back(f.phase_label(i));
  return out;
}

/// What f throws, or "no error".
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

/// Largest distance, in voxels, from a vertex of the sphere's surface to the true sphere.
inline double sphere_error_voxels(const NodeMesh& mesh) {
  double worst = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int32_t node : mesh.triangles[t])
      worst = std::max(worst, std::abs((mesh.points[size_t(node)] - world(centre_vox)).norm() / voxel - radius_vox));
  return worst;
}

inline void improve(NodeMesh& node_mesh, const PhaseField& field) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(node_mesh);
  RunOptions run;
  run.iterations = 10;
  Pipeline::parse(kDefaultPipeline, builtin_registry()).run(mesh, &field, run);
  node_mesh = mesh.to_node_mesh();
}

} // namespace vm::test::sphere_volume
