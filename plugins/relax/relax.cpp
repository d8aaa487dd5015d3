/// @file relax.cpp
/// The `relax` plugin: tangential Taubin lambda|mu smoothing (Taubin 1995). One
/// pass adds to every movable node x the move of a shrinking Laplacian step with
/// weight lambda followed by an inflating one with weight mu < -lambda, both
/// computed from the current positions (double-buffered, so the result does not
/// depend on node order). Unlike plain Laplacian smoothing it does not shrink
/// curved surfaces and short curves, and unlike the built-in `smooth` it needs
/// no phase functions: the move is made tangential with the mesh's own normals,
/// so it works on a mesh alone (`voronoimesh smooth` without --field).
///
/// Each node averages only over neighbours that lie on everything it lies on
/// (its surface, curve, box faces), as smooth's half-Laplacian does; surface
/// nodes move in their tangent plane, curve nodes along their curve (or not at
/// all with junctions=0), points never. The move is added to the displacement
/// buffer, so the pipeline's clamp and crossing guard apply to it as to smooth.

#include "voronoimesh/plugin/plugin_helpers.hpp"

#include <vector>

namespace {

using vm::plugin::Mesh;
using vm::plugin::V3;

int run(void*, const vm_mesh_view* view, const double* params, char* error, size_t error_size) {
  return vm::plugin::guarded(error, error_size, [&] {
    const double lambda = params[0], mu = params[1];
    const bool along_curves = params[2] != 0;
    const Mesh m(*view);
    const size_t n = m.num_nodes();
    // Only nodes that may move take part; the others are fixed anchors.
    std::vector<V3> x(n), y(n);
    std::vector<char> movable(n);
    for (size_t i = 0; i < n; ++i) {
      x[i] = m.pos(int32_t(i));
      movable[i] = m.order(int32_t(i)) == 2 || (m.order(int32_t(i)) == 3 && along_curves);
    }
    for (size_t i = 0; i < n; ++i)
      y[i] = movable[i] ? x[i] + m.constrain(int32_t(i), m.laplacian(int32_t(i), x), along_curves) * lambda : x[i];
    for (size_t i = 0; i < n; ++i) {
      if (!movable[i]) continue;
      const V3 z = y[i] + m.constrain(int32_t(i), m.laplacian(int32_t(i), y), along_curves) * mu;
      // Both steps are constrained with the current mesh's tangents, so z - x is too.
      vm::plugin::add_displacement(*view, int32_t(i), z - x[i]);
    }
  });
}

const vm_param_spec kParams[] = {
    {"lambda", 0.5, 0.0, 1.0, 0, "weight of the shrinking Laplacian step (Taubin's lambda)"},
    {"mu", -0.53, -1.0, 0.0, 0, "weight of the inflating step, below -lambda (Taubin's mu)"},
    vm::plugin::kJunctionsParam,
};

const vm_pass_desc kPasses[] = {{
    "relax",
    "tangential Taubin lambda|mu smoothing: surface nodes in their tangent plane, curve nodes along the curve "
    "(plugin; needs no phase functions)",
    kParams, sizeof kParams / sizeof kParams[0], 1, 0, run, nullptr}};

} // namespace

VM_PLUGIN_DEFINE("relax", "1.0", kPasses)
