#include "voronoimesh/guard.hpp"

#include "voronoimesh/intersections.hpp"

#include "detail/parallel.hpp"

#include <limits>

namespace vm {

GuardReport commit_without_crossings(InterfaceMesh& mesh, std::vector<Vec3>& delta) {
  GuardReport report;
  const std::vector<Vec3> before = mesh.positions();
  mesh.move_nodes(delta);
  NodeMesh m = mesh.to_node_mesh();
  std::vector<uint8_t> moved(mesh.num_nodes());
  detail::parallel_for_each_index(moved.size(), [&](size_t n) { moved[n] = !delta[n].isZero(0); });
  std::vector<uint8_t> involved(m.triangles.size());
  while (true) {
    detail::parallel_for_each_index(involved.size(), [&](size_t t) {
      const auto& tri = m.triangles[t];
      involved[t] = moved[size_t(tri[0])] | moved[size_t(tri[1])] | moved[size_t(tri[2])];
    });
    ++report.rounds;
    const IntersectionReport crossings =
        find_self_intersections(m, std::numeric_limits<size_t>::max(), involved, false);
    if (crossings.ok()) break;
    std::vector<int32_t> undo;
    for (const auto& pair : crossings.pairs)
      for (int32_t t : pair)
        for (int32_t n : m.triangles[size_t(t)])
          if (moved[size_t(n)]) {
            moved[size_t(n)] = 0;
            undo.push_back(n);
          }
    std::vector<Vec3> back(undo.size());
    for (size_t i = 0; i < undo.size(); ++i) {
      back[i] = before[size_t(undo[i])];
      m.points[size_t(undo[i])] = back[i];
      delta[size_t(undo[i])].setZero();
    }
    mesh.place_nodes(undo, back);
    report.undone_nodes += undo.size();
  }
  return report;
}

} // namespace vm
