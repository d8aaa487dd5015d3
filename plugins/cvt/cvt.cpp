/// @file cvt.cpp
/// The `cvt` plugin: a tangential, CVT-style (Lloyd) relaxation. Every surface
/// node moves toward the area-weighted centroid of the triangles around it, the
/// centroid of its surface Voronoi-like cell, which evens out triangle *areas*
/// (where Laplacian smoothing evens out edge lengths and leaves large and small
/// triangles side by side at irregular valences). Curve nodes move toward the
/// centre of their 1-D cell, (a + 2x + b)/4 for curve neighbours a and b, or stay
/// with junctions=0; points never move. Moves are tangential (mesh normals, no
/// phase functions needed) and go to the displacement buffer, so the pipeline's
/// clamp and crossing guard apply as for the built-in smooth.

#include "voronoimesh/plugin/plugin_helpers.hpp"

#include <vector>

namespace {

using vm::plugin::Mesh;
using vm::plugin::V3;

/// Area-weighted mean of the centroids of the triangles at node i.
V3 cell_centroid(const Mesh& m, int32_t i) {
  V3 sum;
  double area = 0;
  for (int32_t t : m.triangles_at(i)) {
    const int32_t* n = m.triangle(t);
    const double a = m.area_vector(t).norm();
    sum += (m.pos(n[0]) + m.pos(n[1]) + m.pos(n[2])) * (a / 3);
    area += a;
  }
  return area > 0 ? sum * (1 / area) : m.pos(i);
}

int run(void*, const vm_mesh_view* view, const double* params, char* error, size_t error_size) {
  return vm::plugin::guarded(error, error_size, [&] {
    const double step = params[0];
    const bool along_curves = params[1] != 0;
    const Mesh m(*view);
    std::vector<V3> x(m.num_nodes());
    for (size_t i = 0; i < x.size(); ++i) x[i] = m.pos(int32_t(i));
    for (size_t i = 0; i < x.size(); ++i) {
      const auto v = int32_t(i);
      V3 target;
      if (m.order(v) == 2) target = cell_centroid(m, v) - x[i];
      else if (m.order(v) == 3 && along_curves) target = m.laplacian(v, x) * 0.5;
      else continue;
      vm::plugin::add_displacement(*view, v, m.constrain(v, target * step, along_curves));
    }
  });
}

const vm_param_spec kParams[] = {
    {"step", 0.5, 0.0, 1.0, 0, "fraction of the way to the cell centroid moved per iteration (1: a full Lloyd step)"},
    vm::plugin::kJunctionsParam,
};

const vm_pass_desc kPasses[] = {{
    "cvt",
    "tangential Lloyd (CVT-style) relaxation toward area-weighted cell centroids: evens out triangle areas "
    "(plugin; needs no phase functions)",
    kParams, sizeof kParams / sizeof kParams[0], 1, 0, run, nullptr}};

} // namespace

VM_PLUGIN_DEFINE("cvt", "1.0", kPasses)
