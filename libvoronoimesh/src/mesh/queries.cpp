#include "voronoimesh/mesh/queries.hpp"


#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <tuple>

namespace vm {

namespace {

Vec3 corner(const NodeMesh& m, size_t t, int c) { return m.points[size_t(m.triangles[t][size_t(c)])]; }

} // namespace

std::vector<Surface> surfaces(const NodeMesh& m) {
  std::map<PhasePair, Surface> by_pair;
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    Surface& s = by_pair[m.pairs[t]];
    s.pair = m.pairs[t];
    s.triangles.push_back(int32_t(t));
    s.area += 0.5 * (corner(m, t, 1) - corner(m, t, 0)).cross(corner(m, t, 2) - corner(m, t, 0)).norm();
  }
  std::vector<Surface> out;
  for (auto& [pair, s] : by_pair) out.push_back(std::move(s));
  return out;
}

std::vector<std::optional<double>> phase_volumes(const NodeMesh& m) {
  size_t phases = m.phase_names.size();
  for (const PhasePair& p : m.pairs) phases = std::max(phases, size_t(p[1]) + 1);
  // Tetrahedra against the centroid of the points rather than the origin, so
  // that meshes far from the origin keep their digits.
  const Vec3 centre = m.points.empty() ? Vec3::Zero()
                                       : Vec3(std::accumulate(m.points.begin(), m.points.end(), Vec3(Vec3::Zero())) /
                                              double(m.points.size()));
  std::vector<double> volume(phases, 0.0);
  std::vector<bool> has_triangles(phases, false);
  // Every edge of a phase's outward boundary, +1 one way and -1 the other: the
  // boundary is closed when each edge's signs cancel.
  std::vector<std::tuple<int32_t, int32_t, int32_t, int>> edges;
  edges.reserve(m.triangles.size() * 6);
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const double six_v = (corner(m, t, 0) - centre).dot((corner(m, t, 1) - centre).cross(corner(m, t, 2) - centre));
    const auto& tri = m.triangles[t];
    for (int side = 0; side < 2; ++side) {
      // The right-hand normal points from pairs[t][0] into pairs[t][1]: outward for the first phase.
      const int32_t phase = m.pairs[t][size_t(side)];
      const int sign = side == 0 ? 1 : -1;
      volume[size_t(phase)] += sign * six_v / 6;
      has_triangles[size_t(phase)] = true;
      for (int e = 0; e < 3; ++e) {
        const int32_t a = tri[size_t(e)], b = tri[size_t((e + 1) % 3)];
        edges.emplace_back(phase, std::min(a, b), std::max(a, b), a < b ? sign : -sign);
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<bool> closed(has_triangles);
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    int net = 0;
    for (; j < edges.size() && std::get<0>(edges[j]) == std::get<0>(edges[i]) && std::get<1>(edges[j]) == std::get<1>(edges[i]) &&
           std::get<2>(edges[j]) == std::get<2>(edges[i]);
         ++j)
      net += std::get<3>(edges[j]);
    if (net != 0) closed[size_t(std::get<0>(edges[i]))] = false;
    i = j;
  }
  // The exterior of a closed mesh is the whole space outside the box.
  if (m.outside_phase >= 0) closed[size_t(m.outside_phase)] = false;
  const Vec3 box = m.domain.max - m.domain.min;
  std::vector<std::optional<double>> out(phases);
  for (size_t p = 0; p < phases; ++p)
    if (closed[p]) out[p] = volume[p] >= 0 ? volume[p] : box.prod() + volume[p]; // header: a phase around the others
  return out;
}

std::vector<Vec3> curve_points(const NodeMesh& m, const TripleCurve& curve) {
  std::vector<Vec3> out;
  out.reserve(curve.nodes.size());
  for (int32_t n : curve.nodes) out.push_back(m.points[size_t(n)]);
  return out;
}

double curve_length(const NodeMesh& m, const TripleCurve& curve) {
  double length = 0;
  for (size_t i = 1; i < curve.nodes.size(); ++i)
    length += (m.points[size_t(curve.nodes[i])] - m.points[size_t(curve.nodes[i - 1])]).norm();
  return length;
}

int32_t phase_of_label(const NodeMesh& m, int32_t label) {
  if (m.phase_labels.empty()) return label >= 0 && (m.phase_names.empty() || size_t(label) < m.phase_names.size()) ? label : -1;
  const auto it = std::lower_bound(m.phase_labels.begin(), m.phase_labels.end(), label);
  return it != m.phase_labels.end() && *it == label ? int32_t(it - m.phase_labels.begin()) : -1;
}

} // namespace vm
