// A program that holds its own data meshes it with voronoimesh: a label per
// voxel (a ball of grain 1 in a block split into grains 2 and 3), meshed,
// measured and written, then the file read back and checked.
#include <voronoimesh/io/ply.hpp>
#include <voronoimesh/voronoimesh.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  const std::string out = argc > 1 ? argv[1] : "grains.ply";
  try {
    // The program's own array: 40^3 voxels over the unit box, one label each.
    // Voxel centres are the grid's nodes, node (i, j, k) at i + 40 (j + 40 k).
    vm::GridSpec grid;
    grid.cells = {39, 39, 39};
    grid.domain = {vm::Vec3(0, 0, 0), vm::Vec3(1, 1, 1)};
    std::vector<int32_t> labels;
    for (int k = 0; k < 40; ++k)
      for (int j = 0; j < 40; ++j)
        for (int i = 0; i < 40; ++i) {
          const vm::Vec3 x = grid.node_position(i, j, k);
          labels.push_back((x - vm::Vec3(0.5, 0.5, 0.5)).norm() < 0.3 ? 1 : x.x() < 0.5 ? 2 : 3);
        }

    // Create and improve in one call (the CLI's `voronoimesh mesh`).
    const vm::Scene scene = vm::scene_from_labels(grid, labels);
    vm::MeshOptions options;
    options.iterations = 10;
    const vm::NodeMesh mesh = vm::mesh_scene(scene, options);

    // Ask the mesh what it holds.
    for (const vm::Surface& s : vm::surfaces(mesh))
      std::printf("surface %s|%s: %zu triangles, area %.4f\n", mesh.phase_names[s.pair[0]].c_str(),
                  mesh.phase_names[s.pair[1]].c_str(), s.triangles.size(), s.area);
    for (const vm::TripleCurve& c : vm::find_junctions(mesh).curves)
      std::printf("triple curve of %zu edges, length %.4f\n", c.num_edges(), vm::curve_length(mesh, c));
    const std::optional<double> ball = vm::phase_volumes(mesh)[vm::phase_of_label(mesh, 1)];
    std::printf("grain 1 encloses %.5f\n", ball.value_or(0));

    vm::io::write_mesh(mesh, out);

    // Check the result: the file holds a valid mesh of every triangle, and the
    // ball's volume is the true one's within 3%.
    const vm::NodeMesh back = vm::io::read_ply(out);
    const double truth = 4.0 / 3 * std::numbers::pi * std::pow(0.3, 3);
    if (back.num_triangles() != mesh.num_triangles() || !vm::validate(back).ok() || !ball ||
        std::abs(*ball - truth) > 0.03 * truth) {
      std::fprintf(stderr, "grains: wrong result in %s\n", out.c_str());
      return 1;
    }
    std::printf("wrote %s: %zu nodes, %zu triangles\n", out.c_str(), back.num_nodes(), back.num_triangles());
    return 0;
  } catch (const vm::Error& e) { // every library failure, one line naming the problem
    std::fprintf(stderr, "grains: %s\n", e.what());
    return 2;
  }
}
