/// @file improve/phase_islands.cpp
/// Finding the pieces of phases that the phase functions do not have
/// (improve/phase_islands.hpp).

#include "improve/phase_islands.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <span>

namespace vm::detail {
namespace {

/// Triangles of a piece beyond which it is no pocket: the lattice makes up to
/// 48 round one node where a phase leads alone (its 24 tetrahedra, two
/// triangles each where another interface crosses them).
constexpr size_t kMostTriangles = 64;

/// The pieces of phase boundaries reached from junction and box nodes, each
/// flooded through the edges it shares (at most kMostTriangles triangles),
/// every triangle side in one flood at most.
class PieceFinder {
public:
  explicit PieceFinder(const NodeRings& mesh) : mesh_(mesh), flood_(2 * mesh.mesh().num_triangles(), -1) {}

  /// The triangles of the piece of `phase` that holds triangle t, ascending
  /// (valid until the next call); empty where it has more than kMostTriangles,
  /// a corner farther than `reach` from `centre` (then it is wider than
  /// `reach`) or meets a side flooded before. Most calls on a large piece
  /// end at once, at a side an earlier flood reached.
  std::span<const int32_t> piece(int32_t t, int32_t phase, const Vec3& centre, double reach) {
    int32_t& first = flood_[side(t, phase)];
    if (first >= 0) return {};
    first = ++floods_;
    walk_.assign(1, t);
    found_.assign(1, t);
    while (!walk_.empty()) {
      const int32_t at = walk_.back();
      walk_.pop_back();
      const auto& tri = mesh_.mesh().triangles[size_t(at)];
      for (size_t k = 0; k < 3; ++k) {
        const int32_t a = tri[k], b = tri[(k + 1) % 3];
        for (int32_t u : mesh_.triangles_at(a)) {
          if (u == at || !has(u, phase) || !has_node(u, b)) continue;
          int32_t& flood = flood_[side(u, phase)];
          if (flood == floods_) continue;
          // Flooded before: one piece with a flood that found it too large (a
          // flood that ends takes its whole piece). Sides not flooded yet stay
          // open: a later flood from them meets these.
          if (flood >= 0 || found_.size() == kMostTriangles || !within(u, centre, reach)) return {};
          flood = floods_;
          found_.push_back(u);
          walk_.push_back(u);
        }
      }
    }
    std::sort(found_.begin(), found_.end());
    return found_;
  }

private:
  bool has(int32_t t, int32_t phase) const {
    const PhasePair& pair = mesh_.mesh().pairs[size_t(t)];
    return pair[0] == phase || pair[1] == phase;
  }
  bool has_node(int32_t t, int32_t n) const {
    const auto& tri = mesh_.mesh().triangles[size_t(t)];
    return tri[0] == n || tri[1] == n || tri[2] == n;
  }
  bool within(int32_t t, const Vec3& centre, double reach) const {
    const auto& tri = mesh_.mesh().triangles[size_t(t)];
    return std::all_of(tri.begin(), tri.end(), [&](int32_t n) {
      return (mesh_.positions()[size_t(n)] - centre).squaredNorm() <= reach * reach;
    });
  }
  size_t side(int32_t t, int32_t phase) const {
    return 2 * size_t(t) + (mesh_.mesh().pairs[size_t(t)][0] == phase ? 0 : 1);
  }

  const NodeRings& mesh_;
  std::vector<int32_t> flood_; ///< by triangle side: the flood that reached it, -1 for none
  int32_t floods_ = -1;
  std::vector<int32_t> walk_, found_; // kept between floods: most floods are one side long
};

/// How far inside its phase's side a triangle's centre is sampled, in targets.
constexpr double kInward = 0.1;

/// The mean of the nodes' positions.
Vec3 mean_of(const NodeRings& mesh, const std::vector<int32_t>& nodes) {
  Vec3 sum = Vec3::Zero();
  for (int32_t n : nodes) sum += mesh.positions()[size_t(n)];
  return sum / double(nodes.size());
}

/// True where `phase` leads nowhere the piece's triangles enclose: at `centre`
/// (the mean of their nodes), and a little inside each triangle's centre (on its
/// side of `phase`), where a piece the phase functions have is led by its phase
/// (exactly at the centre, on the interface, either may lead).
bool led_by_others(const NodeRings& mesh, std::span<const int32_t> triangles, const Vec3& centre, int32_t phase,
                   const PhaseField& field, double inward) {
  const auto& pos = mesh.positions();
  std::vector<Vec3> samples{centre};
  for (int32_t t : triangles) {
    const auto& tri = mesh.mesh().triangles[size_t(t)];
    const Vec3 &a = pos[size_t(tri[0])], &b = pos[size_t(tri[1])], &c = pos[size_t(tri[2])];
    // Triangles are oriented from the pair's first phase into its second.
    const Vec3 normal = (b - a).cross(c - a);
    const double into_phase = mesh.mesh().pairs[size_t(t)][0] == phase ? -inward : inward;
    const double area2 = normal.norm();
    samples.push_back((a + b + c) / 3 + (area2 > 0 ? into_phase / area2 : 0.0) * normal);
  }
  std::array<int32_t, 1> id;
  std::array<double, 1> value;
  return std::none_of(samples.begin(), samples.end(), [&](const Vec3& x) {
    field.top_values(x, id, value);
    return id[0] == phase;
  });
}

/// The merge of a piece's nodes: into the first node that lies on every box
/// face any of them lies on, at `centre` (their mean) held on those faces; none
/// where no node lies on all of them.
std::optional<PointMerge> merge_of(const NodeRings& mesh, const std::vector<int32_t>& nodes, const Vec3& centre) {
  uint8_t faces = 0;
  for (int32_t n : nodes) faces |= mesh.box_faces()[size_t(n)];
  const auto keep =
      std::find_if(nodes.begin(), nodes.end(), [&](int32_t n) { return mesh.box_faces()[size_t(n)] == faces; });
  if (keep == nodes.end()) return std::nullopt;
  Vec3 to = centre;
  for (int a = 0; a < 3; ++a)
    if (faces >> (2 * a) & 3u) to[a] = mesh.positions()[size_t(*keep)][a];
  PointMerge merge{*keep, {}, to};
  for (int32_t n : nodes)
    if (n != *keep) merge.merged.push_back(n);
  return merge;
}

} // namespace

std::vector<PointMerge> phase_islands(const NodeRings& mesh, std::span<const double> target, const PhaseField& field,
                                      double widest) {
  const NodeMesh& m = mesh.mesh();
  // A phase the functions do not have (the outside of a closed mesh, given
  // the scene's functions without it) is left alone.
  const auto phases = size_t(field.num_phases());
  std::vector<size_t> triangles_of(phases, 0);
  for (const PhasePair& pair : m.pairs)
    for (int32_t p : pair)
      if (size_t(p) < phases) ++triangles_of[size_t(p)];
  struct Piece {
    int32_t phase;
    size_t triangles;
    PointMerge merge;
  };
  std::vector<Piece> pieces;
  PieceFinder finder(mesh);
  for (int32_t n = 0; n < int32_t(mesh.num_nodes()); ++n) {
    if (junction_order(mesh.phases()[size_t(n)], mesh.box_faces()[size_t(n)]) < 3) continue;
    for (int32_t t : mesh.triangles_at(n))
      for (int32_t phase : m.pairs[size_t(t)]) {
        if (size_t(phase) >= phases) continue;
        // A piece that qualifies is at most widest x target[n] across, n one of its nodes.
        const std::span<const int32_t> piece = finder.piece(t, phase, m.points[size_t(n)], widest * target[size_t(n)]);
        if (piece.empty()) continue;
        std::vector<int32_t> nodes;
        for (int32_t u : piece) nodes.insert(nodes.end(), m.triangles[size_t(u)].begin(), m.triangles[size_t(u)].end());
        std::sort(nodes.begin(), nodes.end());
        nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
        double size = target[size_t(nodes[0])], across = 0;
        for (int32_t a : nodes) {
          size = std::min(size, target[size_t(a)]);
          for (int32_t b : nodes) across = std::max(across, (m.points[size_t(a)] - m.points[size_t(b)]).norm());
        }
        if (across > widest * size) continue;
        const Vec3 centre = mean_of(mesh, nodes);
        if (!led_by_others(mesh, piece, centre, phase, field, kInward * size)) continue;
        if (auto merge = merge_of(mesh, nodes, centre)) pieces.push_back({phase, piece.size(), std::move(*merge)});
      }
  }
  // A phase keeps the triangles of its other pieces: never all of them go.
  std::vector<size_t> going(phases, 0);
  for (const Piece& p : pieces) going[size_t(p.phase)] += p.triangles;
  std::vector<PointMerge> merges;
  for (Piece& p : pieces)
    if (going[size_t(p.phase)] < triangles_of[size_t(p.phase)]) merges.push_back(std::move(p.merge));
  std::sort(merges.begin(), merges.end(), [](const PointMerge& x, const PointMerge& y) { return x.keep < y.keep; });
  return merges;
}

} // namespace vm::detail
