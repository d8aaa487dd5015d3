#include "voronoimesh/meshing.hpp"

#include "voronoimesh/closed_domain.hpp"
#include "voronoimesh/errors.hpp"
#include "voronoimesh/mesh.hpp"
#include "voronoimesh/sampled_field.hpp"
#include "voronoimesh/validate.hpp"

#include "detail/memory.hpp"
#include "detail/text.hpp"

#include <tbb/global_control.h>

#include <optional>

namespace vm {

namespace {

using detail::cat;

/// Limits TBB to options.threads while alive (none when 0).
std::optional<tbb::global_control> thread_limit(const MeshOptions& o) {
  if (o.threads < 0) throw InvalidInput(cat("threads: must be 0 (all cores) or more, got ", o.threads));
  std::optional<tbb::global_control> limit;
  if (o.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(o.threads));
  return limit;
}

void require_field(const Scene& scene) {
  if (!scene.field) throw InvalidInput("scene: no phase field");
}

} // namespace

GridSpec create_grid(const Scene& scene, const MeshOptions& o) {
  require_field(scene);
  GridSpec grid = scene.grid;
  if (o.grid != std::array<int, 3>{0, 0, 0}) {
    for (int n : o.grid)
      if (n < 1 || n > 4096) throw InvalidInput(cat("grid: cells per axis must be between 1 and 4096, got ", n));
    grid.cells = o.grid;
  }
  if (o.top_k < 1 || o.top_k > 16) throw InvalidInput(cat("top_k: must be between 1 and 16, got ", o.top_k));
  return grid_for_lattice(grid, o.lattice);
}

CreateParams create_params(const MeshOptions& o) {
  CreateParams params;
  params.lattice = o.lattice;
  params.snap = o.snap;
  params.close = o.close;
  return params;
}

void name_phases(NodeMesh& mesh, const Scene& scene, const MeshOptions& o) {
  name_phases(mesh, *(o.close ? with_outside_phase(scene.field, mesh.domain) : scene.field));
}

NodeMesh create_mesh(const Scene& scene, const MeshOptions& o) {
  require_field(scene);
  const auto limit = thread_limit(o);
  const GridSpec grid = create_grid(scene, o);
  const CreateParams params = create_params(o);
  detail::refuse_beyond_memory(double(estimate_create_memory(grid, o.top_k, params.lattice)), "grid",
                               cat("a ", grid.cells[0], "x", grid.cells[1], "x", grid.cells[2], " grid"));
  const SampledField samples = SampledField::sample(*scene.field, grid, o.top_k);
  NodeMesh mesh;
  const CreateStats stats = create_initial_mesh(samples, params, mesh);
  name_phases(mesh, scene, o);
  if (o.validate && !stats.validated) require_valid(mesh, "the created mesh");
  return mesh;
}

int improve_mesh(NodeMesh& mesh, const Scene& scene, const MeshOptions& o) {
  require_field(scene);
  const auto limit = thread_limit(o);
  if (o.iterations < 0) throw InvalidInput(cat("iterations: must be 0 or more, got ", o.iterations));
  const PassRegistry builtin = o.passes ? PassRegistry() : builtin_registry();
  const Pipeline pipeline = Pipeline::parse(o.pipeline, o.passes ? *o.passes : builtin);
  // A closed mesh has one more phase, outside the box; the passes need its function too.
  const auto field = is_closed_mesh(mesh, scene.field->num_phases()) ? with_outside_phase(scene.field, mesh.domain)
                                                                     : scene.field;
  InterfaceMesh im = InterfaceMesh::from_node_mesh(mesh);
  RunOptions run;
  run.iterations = o.iterations;
  run.stop_when_converged = o.stop_when_converged;
  run.guard_crossings = o.guard_crossings;
  const int done = pipeline.run(im, field.get(), run);
  mesh = im.to_node_mesh();
  if (o.validate) require_valid(mesh, "the improved mesh");
  return done;
}

NodeMesh mesh_scene(const Scene& scene, const MeshOptions& options) {
  NodeMesh mesh = create_mesh(scene, options);
  improve_mesh(mesh, scene, options);
  return mesh;
}

} // namespace vm
