/// @file improve/digon_faces.cpp
/// Finding small digon faces (improve/digon_faces.hpp).

#include "improve/digon_faces.hpp"

#include "core/union_find.hpp"

#include <algorithm>
#include <optional>

namespace vm::detail {
namespace {

/// Nodes of a digon face beyond its corners: more, and it is no small face.
constexpr size_t kMostNodes = 48;
/// How close (in targets) the two corners' meeting points must come.
constexpr double kSamePoint = 0.1;

/// A triple curve from a corner: its three phases, its nodes between the
/// corners, the corner it ends at and its length.
struct Curve {
  PhaseSet phases;
  std::vector<int32_t> inner;
  int32_t end;
  double length;
};

/// The curve that leaves corner `from` through its neighbour `next`, followed
/// to the next corner; none where `next` does not go along a curve, the curve
/// branches or reaches the box, or it is longer than `longest`.
std::optional<Curve> follow_curve(const NodeRings& mesh, int32_t from, int32_t next, double longest) {
  const auto& pos = mesh.positions();
  if (!mesh.constraints_within(next, from) || !mesh.along_curve(from, next)) return std::nullopt;
  Curve curve{mesh.phases()[size_t(next)], {}, -1, (pos[size_t(from)] - pos[size_t(next)]).norm()};
  int32_t previous = from, at = next;
  while (!is_corner(mesh, at)) {
    if (!is_curve_node(mesh, at) || curve.inner.size() == kMostNodes) return std::nullopt;
    curve.inner.push_back(at);
    int32_t ahead = -1, ways = 0;
    for (int32_t n : mesh.neighbours(at))
      if (n != previous && mesh.constraints_within(at, n) && mesh.along_curve(at, n)) ahead = n, ++ways;
    if (ways != 1) return std::nullopt;
    curve.length += (pos[size_t(at)] - pos[size_t(ahead)]).norm();
    if (curve.length > longest) return std::nullopt;
    previous = at, at = ahead;
  }
  if (curve.inner.empty()) { // one edge between the corners: its phases are its triangles'
    curve.phases.fill(-1);
    std::vector<int16_t> phases;
    for (int32_t t : mesh.triangles_at(from)) {
      const auto& tri = mesh.mesh().triangles[size_t(t)];
      if (std::find(tri.begin(), tri.end(), at) == tri.end()) continue;
      for (int32_t p : mesh.mesh().pairs[size_t(t)]) phases.push_back(int16_t(p));
    }
    std::sort(phases.begin(), phases.end());
    phases.erase(std::unique(phases.begin(), phases.end()), phases.end());
    if (phases.size() != 3) return std::nullopt;
    std::copy(phases.begin(), phases.end(), curve.phases.begin());
  }
  curve.end = at;
  return curve;
}

/// The two phases that two triple curves share.
PhasePair shared_pair(const PhaseSet& a, const PhaseSet& b) {
  std::vector<int32_t> common;
  std::set_intersection(a.begin(), a.begin() + 3, b.begin(), b.begin() + 3, std::back_inserter(common));
  return common.size() == 2 ? PhasePair{common[0], common[1]} : PhasePair{-1, -1};
}

/// The nodes inside the face of `pair` that the inner nodes of two curves
/// bound (appended to `inside`); false if that face reaches beyond the two
/// curves (another junction, the box) or holds too many nodes.
bool face_inside(const NodeRings& mesh, const PhasePair& pair, const std::vector<int32_t>& boundary,
                 std::vector<int32_t>& inside) {
  // Flooded from the curves' inner nodes, not the corners: at a corner of a
  // digon, the same pair also has a face outside it.
  std::vector<int32_t> walk;
  for (int32_t n : boundary)
    if (is_curve_node(mesh, n)) walk.push_back(n);
  auto known = [&](int32_t n) {
    return std::find(boundary.begin(), boundary.end(), n) != boundary.end() ||
           std::find(inside.begin(), inside.end(), n) != inside.end();
  };
  while (!walk.empty()) {
    const int32_t at = walk.back();
    walk.pop_back();
    for (int32_t t : mesh.triangles_at(at)) {
      if (mesh.mesh().pairs[size_t(t)] != pair) continue;
      for (int32_t n : mesh.mesh().triangles[size_t(t)]) {
        if (known(n)) continue;
        const PhaseSet& s = mesh.phases()[size_t(n)];
        if (phase_count(s) != 2 || s[0] != pair[0] || s[1] != pair[1] || mesh.box_faces()[size_t(n)] != 0 ||
            inside.size() == kMostNodes)
          return false;
        inside.push_back(n);
        walk.push_back(n);
      }
    }
  }
  return true;
}

} // namespace

std::vector<PointMerge> small_digon_faces(const NodeRings& mesh, std::span<const double> target,
                                          const PhaseField& field, double longest) {
  struct Found {
    double span;
    PointMerge face;
  };
  std::vector<Found> found;
  const auto& pos = mesh.positions();
  for (int32_t c = 0; c < int32_t(mesh.num_nodes()); ++c) {
    if (!is_corner(mesh, c)) continue;
    std::vector<Curve> curves;
    for (int32_t n : mesh.neighbours(c))
      if (auto curve = follow_curve(mesh, c, n, longest * target[size_t(c)])) curves.push_back(std::move(*curve));
    for (size_t i = 0; i < curves.size(); ++i)
      for (size_t j = i + 1; j < curves.size(); ++j) {
        const Curve &a = curves[i], &b = curves[j];
        const int32_t other = a.end;
        if (other != b.end || other <= c || mesh.phases()[size_t(other)] != mesh.phases()[size_t(c)] ||
            a.phases == b.phases || std::max(a.length, b.length) > longest * target[size_t(other)])
          continue;
        const PhasePair pair = shared_pair(a.phases, b.phases);
        if (pair[0] < 0) continue;
        std::vector<int32_t> boundary{c, other}, inside;
        boundary.insert(boundary.end(), a.inner.begin(), a.inner.end());
        boundary.insert(boundary.end(), b.inner.begin(), b.inner.end());
        if (!face_inside(mesh, pair, boundary, inside)) continue;
        const double size = std::min(target[size_t(c)], target[size_t(other)]);
        const PhaseSet& phases = mesh.phases()[size_t(c)];
        const auto here = meeting_point(field, phases, pos[size_t(c)], size);
        const auto there = meeting_point(field, phases, pos[size_t(other)], size);
        if (!here || !there || (*here - *there).norm() > kSamePoint * size) continue;
        PointMerge face{c, {}, 0.5 * (*here + *there)};
        face.merged.assign(boundary.begin() + 1, boundary.end());
        face.merged.insert(face.merged.end(), inside.begin(), inside.end());
        std::sort(face.merged.begin(), face.merged.end());
        found.push_back({std::max(a.length, b.length), std::move(face)});
      }
  }
  // The smallest first; a face next to one already taken waits for the next call.
  std::stable_sort(found.begin(), found.end(), [](const Found& x, const Found& y) { return x.span < y.span; });
  std::vector<PointMerge> faces;
  for (Found& f : found) faces.push_back(std::move(f.face));
  return faces;
}

std::vector<PointMerge> digon_chains(std::span<const PointMerge> faces, size_t num_nodes) {
  // Faces of a chain share a corner; faces of two chains share no node.
  UnionFind chains(faces.size());
  std::vector<int32_t> face_at(num_nodes, -1);
  for (size_t i = 0; i < faces.size(); ++i) {
    auto join = [&](int32_t n) {
      if (face_at[size_t(n)] >= 0) chains.unite(face_at[size_t(n)], int32_t(i));
      face_at[size_t(n)] = int32_t(i);
    };
    join(faces[i].keep);
    for (int32_t n : faces[i].merged) join(n);
  }
  std::vector<std::vector<size_t>> members(faces.size());
  for (size_t i = 0; i < faces.size(); ++i) members[size_t(chains.find(int32_t(i)))].push_back(i);
  std::vector<PointMerge> joined;
  for (const std::vector<size_t>& chain : members) {
    if (chain.size() < 2) continue;
    // Every face's corners are led to the one vertex: the chain goes where its first face goes.
    PointMerge merge{faces[chain[0]].keep, {}, faces[chain[0]].to};
    for (size_t i : chain) {
      merge.keep = std::min(merge.keep, faces[i].keep); // each face keeps its lowest corner
      merge.merged.push_back(faces[i].keep);
      merge.merged.insert(merge.merged.end(), faces[i].merged.begin(), faces[i].merged.end());
    }
    std::sort(merge.merged.begin(), merge.merged.end());
    merge.merged.erase(std::unique(merge.merged.begin(), merge.merged.end()), merge.merged.end());
    std::erase(merge.merged, merge.keep);
    joined.push_back(std::move(merge));
  }
  return joined;
}

} // namespace vm::detail
