/// @file io/obj.cpp
/// Wavefront OBJ: every node once as `v`, then the triangles group by group,
/// one group `g <pair>` per phase pair (io/write_mesh.hpp).

#include "core/text.hpp"
#include "io/output_buffer.hpp"
#include "io/phase_names.hpp"
#include "io/writers.hpp"

#include <numeric>

namespace vm::io::detail {

void write_obj(vm::detail::StagedOutputs& staged, const NodeMesh& m, const std::string& path) {
  const std::vector<PhasePair> pairs = distinct_pairs(m);
  const std::vector<int32_t> index = pair_indices(m, pairs);
  // Triangles grouped by pair, in their own order within a group.
  std::vector<int32_t> order(m.triangles.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int32_t a, int32_t b) { return index[size_t(a)] < index[size_t(b)]; });
  vm::detail::write_in_chunks(staged, path, [&](vm::detail::ChunkedOutput& out) {
    std::string& buf = out.text();
    buf += vm::detail::cat("# voronoimesh interface mesh: ", m.points.size(), " vertices, ", m.triangles.size(),
                           " triangles, ", pairs.size(), " phase pairs\n",
                           "# one group per phase pair <a>_<b> (phase label, then -name); the normal of each face\n"
                           "# (counter-clockwise order) points from phase a into phase b\n");
    for (const Vec3& p : m.points) {
      buf += "v ";
      vm::detail::put_point(buf, p);
      buf += '\n';
      out.maybe_flush();
    }
    int32_t group = -1;
    for (int32_t t : order) {
      if (index[size_t(t)] != group) {
        group = index[size_t(t)];
        buf += "g " + phases_token(m, pairs[size_t(group)]) + "\n";
      }
      buf += 'f';
      for (int32_t v : m.triangles[size_t(t)]) {
        buf += ' ';
        vm::detail::put_int(buf, v + 1);
      }
      buf += '\n';
      out.maybe_flush();
    }
  });
}

} // namespace vm::io::detail
