// Uses only the installed headers and library: meshes the built-in demo (the paper's
// four overlapping spheres) through the public API, checks what it got, and writes
// the mesh to the PLY file named on the command line. Exit code 0 only if every
// check passes; install_test.sh checks the written file again with the installed CLI.

#include <voronoimesh/create/create.hpp>
#include <voronoimesh/core/errors.hpp>
#include <voronoimesh/plugin/plugins.hpp>
#include <voronoimesh/io/write_mesh.hpp>
#include <voronoimesh/mesh/junctions.hpp>
#include <voronoimesh/mesh/interface_mesh.hpp>
#include <voronoimesh/improve/pipeline.hpp>
#include <voronoimesh/fields/scene.hpp>
#include <voronoimesh/check/validate.hpp>
#include <voronoimesh/core/version.hpp>

#include <cstdio>
#include <set>
#include <string>
#include <vector>

namespace {

int failures = 0;

void check(bool ok, const std::string& what) {
  if (!ok) {
    std::fprintf(stderr, "consumer: FAILED: %s\n", what.c_str());
    ++failures;
  }
}

} // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer OUT.ply\n");
    return 2;
  }
  try {
    check(vm::library_version() == VORONOIMESH_VERSION_STRING,
          "headers " VORONOIMESH_VERSION_STRING " but library " + vm::library_version());

    // A coarser grid than the demo's 64 keeps the test fast; the structure survives.
    vm::Scene scene = vm::demo_scene();
    scene.grid.cells = {32, 32, 32};
    const vm::SampledField field =
        vm::SampledField::sample(*scene.field, vm::grid_for_lattice(scene.grid, vm::Lattice::bcc));
    vm::NodeMesh initial;
    vm::create_initial_mesh(field, vm::CreateParams{}, initial);

    vm::InterfaceMesh mesh = vm::InterfaceMesh::from_node_mesh(initial);
    const vm::Pipeline pipeline = vm::Pipeline::parse(vm::kDefaultPipeline, vm::builtin_registry());
    vm::RunOptions run;
    run.iterations = 5;
    const auto [min_before, mean_before] = vm::quality_summary(mesh);
    check(pipeline.run(mesh, scene.field.get(), run) == 5, "5 iterations run");
    const auto [min_after, mean_after] = vm::quality_summary(mesh);
    check(mean_after > mean_before, "improving raises the mean triangle quality");

    const vm::NodeMesh result = mesh.to_node_mesh();
    const vm::ValidationReport report = vm::validate(result);
    check(report.ok(), "valid mesh: " + report.summary());

    std::set<std::pair<int, int>> surfaces;
    for (const auto& p : result.pairs) surfaces.insert({p[0], p[1]});
    const vm::Junctions junctions = vm::find_junctions(result);
    std::set<std::vector<int32_t>> triples;
    for (const auto& c : junctions.curves) triples.insert(c.phases);
    // The demo: 5 phases, 10 surfaces, 10 triple curves, 5 quadruple points.
    check(surfaces.size() == 10, "10 surfaces, got " + std::to_string(surfaces.size()));
    check(triples.size() == 10, "10 phase triples on triple curves, got " + std::to_string(triples.size()));
    check(junctions.quadruple_points.size() == 5,
          "5 quadruple points, got " + std::to_string(junctions.quadruple_points.size()));

    vm::io::write_mesh(result, argv[1]);
    std::printf("consumer: voronoimesh %s, %zu nodes, %zu triangles, %zu surfaces, %zu triple curves, "
                "%zu quadruple points, min q %.3f -> %.3f, mean q %.3f -> %.3f\n",
                vm::library_version().c_str(), result.num_nodes(), result.num_triangles(), surfaces.size(),
                junctions.curves.size(), junctions.quadruple_points.size(), min_before, min_after, mean_before,
                mean_after);
    std::printf("consumer: plugin folder %s\n", vm::installed_plugin_dir().c_str());
  } catch (const vm::Error& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
  return failures == 0 ? 0 : 1;
}
