#include "voronoimesh/improve/smooth.hpp"

#include "core/parallel.hpp"
#include "improve/field_checks.hpp"
#include "improve/edge_lengths.hpp"
#include "improve/tangential.hpp"
#include "mesh/node_rings.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

namespace vm {

int junction_order(const InterfaceMesh& mesh, int32_t n) {
  return detail::junction_order(mesh.phases()[size_t(n)], mesh.box_faces()[size_t(n)]);
}

void constrain_to_box(Vec3& d, uint8_t box_faces) {
  for (int a = 0; a < 3; ++a)
    if (box_faces >> (2 * a) & 3u) d[a] = 0;
}

namespace detail {

SquaredEdgeLengths squared_edge_lengths(const InterfaceMesh& mesh, std::span<const uint8_t> counted) {
  // The box faces of a closed mesh are not interfaces: their triangles are the
  // lattice's faces, about twice the interface edges, and would set l0 too long.
  const int32_t outside = mesh.outside_phase();
  auto on_box_surface = [&](int32_t v, int32_t w) {
    return outside >= 0 && mesh.has_phase(v, outside) && mesh.has_phase(w, outside);
  };
  // Fixed-point partial sums over chunks of nodes: the total does not depend on
  // the chunks, the threads or the node numbering (core/fixed_point_sum.hpp).
  const double unit = (mesh.domain().max - mesh.domain().min).squaredNorm();
  const size_t n = mesh.num_nodes(), chunk = 4096, chunks = (n + chunk - 1) / chunk;
  std::vector<FixedPointSum> sum(chunks, FixedPointSum(unit));
  std::vector<uint64_t> count(chunks, 0);
  const auto& pos = mesh.positions();
  // One chunk a task (grain 1): under the default grain of 512 items, a mesh of
  // fewer than 2M nodes had all its chunks in one task, on one thread (18 ms a
  // smoothing pass on 1M triangles, the other core idle).
  parallel_for_each_index(chunks, [&](size_t c) {
    FixedPointSum chunk_sum(unit); // in locals, stored once (as quality_summary())
    uint64_t edges = 0;
    for (size_t v = c * chunk; v < std::min(n, (c + 1) * chunk); ++v) {
      if (!counted.empty() && !counted[v]) continue;
      for (int32_t w : mesh.neighbours(int32_t(v)))
        if (size_t(w) > v && !on_box_surface(int32_t(v), w)) {
          chunk_sum.add((pos[v] - pos[size_t(w)]).squaredNorm());
          ++edges;
        }
    }
    sum[c] = chunk_sum;
    count[c] = edges;
  }, 1);
  SquaredEdgeLengths total{FixedPointSum(unit), 0};
  for (size_t c = 0; c < chunks; ++c) total.sum.add_raw(sum[c].raw()), total.edges += count[c];
  return total;
}

} // namespace detail

double rms_edge_length(const InterfaceMesh& mesh) {
  const detail::SquaredEdgeLengths s = detail::squared_edge_lengths(mesh, {});
  return s.edges ? std::sqrt(s.sum.total() / double(s.edges)) : 0.0;
}

double mean_edge_length_at(const InterfaceMesh& mesh, int32_t n) {
  const auto ring = mesh.neighbours(n);
  const Vec3& x = mesh.positions()[size_t(n)];
  double sum = 0;
  for (int32_t m : ring) sum += (mesh.positions()[size_t(m)] - x).norm();
  return ring.empty() ? 0.0 : sum / double(ring.size());
}

void add_smoothing_forces(const InterfaceMesh& mesh, const PhaseField& field, const SmoothParams& params,
                          std::vector<Vec3>& delta) {
  add_smoothing_forces_with_rest_length(mesh, field, params.rest_factor * rms_edge_length(mesh), delta);
}

namespace {

/// The nodes joined to curve node v by edges of its curve (edges on the
/// boundary of a patch, for a node of three phases off the box) and how many
/// there are: the first three in `out`, 4 for more.
int curve_neighbours(const InterfaceMesh& mesh, int32_t v, std::array<int32_t, 3>& out) {
  const OMesh& om = mesh.omesh();
  int count = 0;
  for (int32_t copy : mesh.copies(v))
    for (const auto h : om.voh_range(OMesh::VertexHandle(copy))) {
      if (!om.is_boundary(om.edge_handle(h))) continue;
      const int32_t w = mesh.node(om.to_vertex_handle(h));
      if (std::find(out.begin(), out.begin() + count, w) != out.begin() + count) continue;
      if (count == 3) return 4;
      out[size_t(count++)] = w;
    }
  return count;
}

/// For a node of a closed triple curve of three nodes: its move along the
/// curve toward the farther of the other two, by a quarter of how much
/// farther, so that the three spread evenly round the loop; false for any
/// other node. The Laplacian bunches them: kept along the curve, it moves nodes
/// down the sum of squared chords, which on a loop of k evenly spread nodes is
/// least for k >= 5, flat for k = 4, and largest for k = 3 (1 - cos of the
/// 120 degrees between them is concave there). On a 64^3 label volume a
/// loop's nodes sat 0.10, 0.57 and 0.60 apart, their neighbours' triangles at
/// q 0.18. (Loops of four spread too lowered as many label volumes' worst
/// triangles as they raised.)
bool loop_spreading(const InterfaceMesh& mesh, const PhaseField& field, int32_t v, Vec3& force) {
  auto on_a_curve = [&](int32_t n) {
    return phase_count(mesh.phases()[size_t(n)]) == 3 && mesh.box_faces()[size_t(n)] == 0;
  };
  std::array<int32_t, 3> ends{}, theirs{};
  if (!on_a_curve(v) || curve_neighbours(mesh, v, ends) != 2) return false;
  // Both ends alike, each a curve node whose other curve neighbour is the other
  // end: not a curve's end on the box or at a junction point with a chord back
  // to v. Asked of one end only, the answer depended on which came first, the
  // order of v's copies, which a rank's window builds otherwise than one process.
  for (int e = 0; e < 2; ++e)
    if (!on_a_curve(ends[size_t(e)]) || curve_neighbours(mesh, ends[size_t(e)], theirs) != 2 ||
        (theirs[0] != ends[size_t(1 - e)] && theirs[1] != ends[size_t(1 - e)]))
      return false;
  const auto& pos = mesh.positions();
  const Vec3 &x = pos[size_t(v)], &a = pos[size_t(ends[0])], &b = pos[size_t(ends[1])];
  // The tangent's sense toward b: the sense the chord from a to b has along it,
  // which a turn tighter than the chords does not hide (its length does).
  Vec3 along = b - a;
  if (!detail::keep_tangential(mesh, field, v, x, along) || along.norm() == 0) return false;
  force = 0.25 * ((b - x).norm() - (a - x).norm()) * along.normalized();
  return true;
}

} // namespace

void add_smoothing_forces_with_rest_length(const InterfaceMesh& mesh, const PhaseField& field, double l0,
                                           std::vector<Vec3>& delta) {
  const auto& pos = mesh.positions();
  std::vector<uint8_t> not_finite(mesh.num_nodes(), 0);
  detail::parallel_for_each_index(mesh.num_nodes(), [&](size_t vi) {
    const int32_t v = int32_t(vi);
    const int order = detail::constraint_order(mesh, v);
    if (order > 3) return;
    auto ring = mesh.neighbours(v);
    if (ring.empty()) return;
    bool near_junction = order == 3;
    for (int32_t w : ring) near_junction = near_junction || detail::constraint_order(mesh, w) >= 3;

    Vec3 force = Vec3::Zero();
    const Vec3& x = pos[vi];
    if (near_junction) {
      if (!loop_spreading(mesh, field, v, force)) {
        // Laplacian smoothing works on and next to junctions, where flips cannot
        // help and repulsion pushes nodes off their curves (sect. 4.2.1).
        int same = 0;
        for (int32_t w : ring)
          if (mesh.constraints_within(v, w)) {
            force += 0.5 * (pos[size_t(w)] - x);
            ++same;
          }
        if (same) force /= double(same);
      }
    } else {
      for (int32_t w : ring) {
        const Vec3 d = x - pos[size_t(w)];
        const double len = d.norm();
        if (len > 0 && len < l0) force += d * ((l0 - len) / len);
      }
      force /= double(ring.size());
    }
    // Along its surface or curve only: a component across it would fight the
    // projection (sect. 4.2.4). The paper restricts surface nodes; on a curve the
    // Laplacian's pull toward the curve's centre of curvature is such a
    // component too, and would hold curve nodes off their curve by O(h) in
    // balance with the projection.
    if (!detail::keep_tangential(mesh, field, v, x, force)) {
      not_finite[vi] = 1;
      return;
    }
    constrain_to_box(force, mesh.box_faces()[vi]);
    delta[vi] += force;
  });
  detail::refuse_not_finite(mesh, field, not_finite);
}

} // namespace vm
