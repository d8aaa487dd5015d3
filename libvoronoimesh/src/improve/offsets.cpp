/// @file improve/offsets.cpp
/// How far the nodes of a mesh lie from the interface of its phase functions.

#include "voronoimesh/improve/offsets.hpp"

#include "core/parallel.hpp"
#include "core/text.hpp"
#include "mesh/node_rings.hpp"
#include "mesh/topology.hpp"

#include "voronoimesh/improve/project.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

namespace vm {

namespace {

constexpr std::array<const char*, 3> kClassNames = {"surface", "triple_curve", "quadruple_point"};
constexpr std::array<const char*, 3> kClassTexts = {"surface nodes", "triple-curve nodes", "quadruple points"};

/// The class of a node where `phases` meet: 0 surface, 1 triple curve, 2 quadruple or higher point; -1 none.
int class_of(size_t phases) { return phases < 2 ? -1 : int(std::min<size_t>(phases, 4)) - 2; }

/// Newton steps a junction node may take on its way to where its phases meet.
constexpr int kJunctionSteps = 50;

/// Where Newton's method (least-squares steps on the node's box faces) leads a
/// junction node at x with `phases`: its junction, if the steps settle within
/// the domain and no other phase leads there; else none (the phase functions
/// have no such junction near: a topology finer than the grid made the mesh's).
std::optional<Vec3> junction_of(const PhaseField& field, const Vec3& x, std::span<const int32_t> phases,
                                uint8_t box_faces, const Box& domain) {
  const double size = (domain.max - domain.min).norm(), settled = 1e-12 * size;
  Vec3 y = x;
  for (int k = 0;; ++k) {
    if (k == kJunctionSteps) return std::nullopt;
    const Vec3 step = least_squares_step_on_faces(field, y, phases, box_faces);
    y += step;
    if (!y.allFinite() || (y - x).norm() > size) return std::nullopt;
    if (step.norm() <= settled) break;
  }
  for (int a = 0; a < 3; ++a)
    if (y[a] < domain.min[a] - settled || y[a] > domain.max[a] + settled) return std::nullopt;
  // The node's phases must be the largest there, and the next one below them.
  const size_t n = phases.size();
  std::vector<int32_t> ids(std::min(n + 1, size_t(field.num_phases())));
  std::vector<double> values(ids.size());
  field.top_values(y, ids, values);
  for (size_t k = 0; k < n; ++k)
    if (std::find(phases.begin(), phases.end(), ids[k]) == phases.end()) return std::nullopt;
  if (ids.size() > n && values[n] >= values[n - 1] - 1e-9 * (1 + std::abs(values[n - 1]))) return std::nullopt;
  return y;
}

} // namespace

InterfaceOffsets interface_offsets(const NodeMesh& m, const PhaseField& field) {
  const std::vector<char> usable = detail::measured_triangles(m.triangles, m.pairs.size(), m.points.size());
  const detail::NodePhases np = detail::node_phases(detail::node_triangles(m.points.size(), m.triangles, &usable),
                                                    m.pairs);
  // A surface node's offset is its Newton step (taken as the least-squares one,
  // which for one pair is eq. 4's); a junction node's the distance to its
  // junction, or -1 where there is none near.
  ProjectParams nearest;
  nearest.least_squares_from = 2;
  std::vector<double> offset(m.points.size(), 0.0);
  detail::parallel_for_each_index(m.points.size(), [&](size_t n) {
    const auto phases = np.of(n);
    const Vec3& x = m.points[n];
    if (phases.size() == 2) {
      offset[n] = projection_step(field, x, phases, nearest).norm();
    } else if (phases.size() > 2) {
      const std::optional<Vec3> at = junction_of(field, x, phases, detail::box_faces_at(x, m.domain), m.domain);
      offset[n] = at ? (*at - x).norm() : -1;
    }
  });
  // Summed in node order, so the result does not depend on the thread count.
  InterfaceOffsets out;
  for (size_t n = 0; n < m.points.size(); ++n) {
    const int c = class_of(np.count(n));
    if (c < 0) continue;
    NodeOffsets& o = out[size_t(c)];
    ++o.nodes;
    if (offset[n] < 0) {
      ++o.unresolved;
      continue;
    }
    o.rms += offset[n] * offset[n];
    if (o.farthest < 0 || offset[n] > o.max) o.max = offset[n], o.farthest = int32_t(n);
  }
  for (NodeOffsets& o : out)
    if (o.nodes > o.unresolved) o.rms = std::sqrt(o.rms / double(o.nodes - o.unresolved));
  return out;
}

std::string to_text(const InterfaceOffsets& offsets, const NodeMesh& m, double spacing) {
  std::string out;
  char buf[256];
  for (size_t c = 0; c < offsets.size(); ++c) {
    const NodeOffsets& o = offsets[c];
    if (o.nodes == 0) continue;
    std::snprintf(buf, sizeof buf, "  %-19s%8zu:", kClassTexts[c], o.nodes);
    out += buf;
    if (o.farthest >= 0) {
      const Vec3& p = m.points[size_t(o.farthest)];
      std::snprintf(buf, sizeof buf, " rms %.3g h, max %.3g h (node %d at (%g, %g, %g))", o.rms / spacing,
                    o.max / spacing, o.farthest, p.x(), p.y(), p.z());
      out += buf;
    }
    if (o.unresolved > 0)
      out += detail::cat(o.farthest >= 0 ? ";" : "", " ", o.unresolved,
                         " whose phases meet nowhere near them (finer than the grid), not in rms and max");
    out += "\n";
  }
  return out;
}

std::string to_json(const InterfaceOffsets& offsets, const NodeMesh& m, double spacing) {
  nlohmann::ordered_json j = {{"spacing", spacing}};
  for (size_t c = 0; c < offsets.size(); ++c) {
    const NodeOffsets& o = offsets[c];
    nlohmann::ordered_json k = {{"nodes", o.nodes}, {"rms", o.rms},           {"max", o.max},
                                {"rms_h", o.rms / spacing}, {"max_h", o.max / spacing}};
    if (c > 0) k["unresolved"] = o.unresolved;
    if (o.farthest >= 0) {
      const Vec3& p = m.points[size_t(o.farthest)];
      k["farthest"] = {{"node", o.farthest}, {"position", {p.x(), p.y(), p.z()}}};
    }
    j[kClassNames[c]] = k;
  }
  return j.dump(2);
}

} // namespace vm
