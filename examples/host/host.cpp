// A plugin host in miniature: what an application embedding voronoimesh does
// to offer its users plugin passes. It creates the mesh of the built-in demo
// (four overlapping spheres), loads a pass plugin, runs a pipeline that uses the
// plugin's pass by name, checks the result and writes it.
//
// Usage: voronoimesh_host PLUGIN PIPELINE OUTPUT.ply
//   e.g. voronoimesh_host relax.so relax,project,clamp,flip out.ply
// Prints one line per loaded plugin and a summary; exit 1 on any error.

#include "voronoimesh/check/intersections.hpp"
#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/sampled_field.hpp"
#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/io/write_mesh.hpp"
#include "voronoimesh/plugin/plugins.hpp"

#include <cstdio>

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s PLUGIN PIPELINE OUTPUT.ply\n", argv[0]);
    return 1;
  }
  try {
    // The passes a host offers: the built-in ones plus the plugin's.
    vm::PassRegistry registry = vm::builtin_registry();
    const vm::PluginRecord plugin = vm::load_plugin(argv[1], registry);
    std::printf("loaded plugin %s %s with %zu pass(es)\n", plugin.name.c_str(), plugin.version.c_str(),
                plugin.passes.size());
    const vm::Pipeline pipeline = vm::Pipeline::parse(argv[2], registry);

    // The initial mesh of the demo scene on a coarse grid.
    vm::Scene scene = vm::demo_scene();
    scene.grid.cells = {20, 20, 20};
    const vm::CreateParams params;
    const vm::SampledField sampled =
        vm::SampledField::sample(*scene.field, vm::grid_for_lattice(scene.grid, params.lattice));
    vm::NodeMesh created;
    vm::create_initial_mesh(sampled, params, created);
    for (int p = 0; p < scene.field->num_phases(); ++p) created.phase_names.push_back(scene.field->phase_name(p));

    // Improve it with the pipeline: the plugin's pass runs like a built-in one.
    vm::InterfaceMesh mesh = vm::InterfaceMesh::from_node_mesh(created);
    vm::RunOptions run;
    run.iterations = 10;
    const auto [min_before, mean_before] = vm::quality_summary(mesh);
    pipeline.run(mesh, scene.field.get(), run);
    const auto [min_after, mean_after] = vm::quality_summary(mesh);

    // A host must not hand on a broken mesh.
    const vm::NodeMesh result = mesh.to_node_mesh();
    const vm::ValidationReport report = vm::validate(result);
    if (!report.ok()) throw vm::TopologyError("the improved mesh failed validation: " + report.problems.front());
    const size_t crossings = vm::find_self_intersections(result).count;
    if (crossings) throw vm::TopologyError(std::to_string(crossings) + " triangle pairs intersect");
    vm::io::write_mesh(result, argv[3]);
    std::printf("%s: %zu nodes, %zu triangles, valid, no intersections; min quality %.3f -> %.3f, mean %.3f -> %.3f\n",
                pipeline.describe().c_str(), result.num_nodes(), result.num_triangles(), min_before, min_after,
                mean_before, mean_after);
    return 0;
  } catch (const vm::Error& e) {
    std::fprintf(stderr, "voronoimesh_host: %s\n", e.what());
    return 1;
  }
}
