#include "mesh/node_rings.hpp"

#include "core/parallel.hpp"

#include <algorithm>
#include <memory>

namespace vm::detail {

uint8_t box_faces_at(const Vec3& point, const Box& domain) {
  const double tol = 1e-9 * (domain.max - domain.min).norm();
  uint8_t box = 0;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(point[a] - domain.min[a]) <= tol) box |= uint8_t(1u << (2 * a));
    if (std::abs(point[a] - domain.max[a]) <= tol) box |= uint8_t(1u << (2 * a + 1));
  }
  return box;
}

std::vector<uint8_t> box_faces_of(const std::vector<Vec3>& points, const Box& domain) {
  std::vector<uint8_t> box(points.size(), 0);
  parallel_for_each_index(points.size(), [&](size_t n) { box[n] = box_faces_at(points[n], domain); });
  return box;
}

bool constraints_within(const PhaseSet& phases_a, uint8_t box_a, const PhaseSet& phases_b, uint8_t box_b) {
  if (box_a & ~box_b) return false;
  return std::includes(phases_b.begin(), phases_b.begin() + phase_count(phases_b), phases_a.begin(),
                       phases_a.begin() + phase_count(phases_a));
}

NodeRings::NodeRings(const NodeMesh& m)
    : m_(m), at_(node_triangles(m.num_nodes(), m.triangles)), box_(box_faces_of(m.points, m.domain)) {
  const size_t n = m.num_nodes();
  // Each node's ring, sorted and made unique in parallel in room for two new
  // nodes per triangle at it (left uninitialised: each node writes its room
  // before it reads it), then packed in parallel. The remesh pass builds these
  // tables after every round of collapses.
  const auto room = std::make_unique_for_overwrite<int32_t[]>(2 * m.triangles.size() * 3);
  std::vector<int32_t> count(n);
  parallel_for_each_index(n, [&](size_t v) {
    int32_t* out = room.get() + 2 * size_t(at_.off[v]);
    int32_t* end = out;
    for_each_triangle_at(int32_t(v), [&](int32_t a, int32_t b) { *end++ = a, *end++ = b; });
    std::sort(out, end);
    count[v] = int32_t(std::unique(out, end) - out);
  });
  adj_off_.assign(n + 1, 0);
  for (size_t v = 0; v < n; ++v) adj_off_[v + 1] = adj_off_[v] + count[v];
  adj_.resize(size_t(adj_off_[n]));
  phases_.resize(n);
  const NodePhases np = node_phases(at_, m.pairs);
  parallel_for_each_index(n, [&](size_t v) {
    const int32_t* ring = room.get() + 2 * size_t(at_.off[v]);
    std::copy(ring, ring + count[v], adj_.begin() + adj_off_[v]);
    phases_[v].fill(-1);
    const auto ph = np.of(v);
    std::copy(ph.begin(), ph.begin() + std::min(ph.size(), phases_[v].size()), phases_[v].begin());
  });
}

bool NodeRings::has_phase(int32_t n, int32_t p) const {
  const PhaseSet& s = phases_[size_t(n)];
  return std::find(s.begin(), s.end(), int16_t(p)) != s.end();
}

bool NodeRings::along_curve(int32_t a, int32_t b) const {
  if (std::popcount(unsigned(box_[size_t(a)] & box_[size_t(b)])) >= 2) return true;
  std::vector<PhasePair> pairs;
  for (int32_t t : at_.of(size_t(a))) {
    const auto& tri = m_.triangles[size_t(t)];
    if (std::find(tri.begin(), tri.end(), b) != tri.end()) pairs.push_back(m_.pairs[size_t(t)]);
  }
  return pairs.size() != 2 || pairs[0] != pairs[1];
}

} // namespace vm::detail
