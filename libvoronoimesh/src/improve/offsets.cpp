/// @file improve/offsets.cpp
/// How far the nodes of a mesh lie from the interface of its phase functions.

#include "voronoimesh/improve/offsets.hpp"

#include "core/parallel.hpp"
#include "mesh/topology.hpp"

#include "voronoimesh/improve/project.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

namespace vm {

namespace {

constexpr std::array<const char*, 3> kClassNames = {"surface", "triple_curve", "quadruple_point"};
constexpr std::array<const char*, 3> kClassTexts = {"surface nodes", "triple-curve nodes", "quadruple points"};

/// The class of a node where `phases` meet: 0 surface, 1 triple curve, 2 quadruple or higher point; -1 none.
int class_of(size_t phases) { return phases < 2 ? -1 : int(std::min<size_t>(phases, 4)) - 2; }

} // namespace

InterfaceOffsets interface_offsets(const NodeMesh& m, const PhaseField& field) {
  const std::vector<char> usable = detail::measured_triangles(m.triangles, m.pairs.size(), m.points.size());
  const detail::NodePhases np = detail::node_phases(detail::node_triangles(m.points.size(), m.triangles, &usable),
                                                    m.pairs);
  // The least-squares step takes every pair of the node's phases at once: the
  // paper's eq. 4 (a mean of pairwise steps) is a good move but not a distance.
  ProjectParams nearest;
  nearest.least_squares_from = 2;
  std::vector<double> offset(m.points.size(), 0.0);
  detail::parallel_for_each_index(m.points.size(), [&](size_t n) {
    const auto phases = np.of(n);
    if (phases.size() >= 2) offset[n] = projection_step(field, m.points[n], phases, nearest).norm();
  });
  // Summed in node order, so the result does not depend on the thread count.
  InterfaceOffsets out;
  for (size_t n = 0; n < m.points.size(); ++n) {
    const int c = class_of(np.count(n));
    if (c < 0) continue;
    NodeOffsets& o = out[size_t(c)];
    ++o.nodes;
    o.rms += offset[n] * offset[n];
    if (o.farthest < 0 || offset[n] > o.max) o.max = offset[n], o.farthest = int32_t(n);
  }
  for (NodeOffsets& o : out)
    if (o.nodes > 0) o.rms = std::sqrt(o.rms / double(o.nodes));
  return out;
}

std::string to_text(const InterfaceOffsets& offsets, const NodeMesh& m, double spacing) {
  std::string out;
  char buf[256];
  for (size_t c = 0; c < offsets.size(); ++c) {
    const NodeOffsets& o = offsets[c];
    if (o.nodes == 0) continue;
    const Vec3& p = m.points[size_t(o.farthest)];
    std::snprintf(buf, sizeof buf, "  %-19s%8zu: rms %.3g h, max %.3g h (node %d at (%g, %g, %g))\n", kClassTexts[c],
                  o.nodes, o.rms / spacing, o.max / spacing, o.farthest, p.x(), p.y(), p.z());
    out += buf;
  }
  return out;
}

std::string to_json(const InterfaceOffsets& offsets, const NodeMesh& m, double spacing) {
  nlohmann::ordered_json j = {{"spacing", spacing}};
  for (size_t c = 0; c < offsets.size(); ++c) {
    const NodeOffsets& o = offsets[c];
    nlohmann::ordered_json k = {{"nodes", o.nodes}, {"rms", o.rms},           {"max", o.max},
                                {"rms_h", o.rms / spacing}, {"max_h", o.max / spacing}};
    if (o.farthest >= 0) {
      const Vec3& p = m.points[size_t(o.farthest)];
      k["farthest"] = {{"node", o.farthest}, {"position", {p.x(), p.y(), p.z()}}};
    }
    j[kClassNames[c]] = k;
  }
  return j.dump(2);
}

} // namespace vm
