#pragma once
/// @file check/embedded_fans.hpp
/// Certificates that a fan of triangles around a node cannot meet itself.
///
/// Almost every pair of triangles whose boxes overlap shares a node: on a
/// smooth patch, a node's fan holds about fifteen such pairs, each costing a
/// few exact predicates (check/triangle_pair.hpp). One look at the fan decides
/// them all at once: seen along one coordinate axis, if every triangle of the
/// fan turns the same way and together they go around the node once (or, for
/// a fan that ends at a boundary, less than once), the fan is the graph of a
/// function over that plane, and its triangles meet only where they share
/// corners. The test uses the same exact orientation predicate as the pair
/// test, so a certified pair is one the pair test would pass.

#include "check/triangle_pair.hpp"
#include "voronoimesh/core/pooled_lists.hpp"

#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

namespace vm::detail {

/// What the corners of a fan make when ordered one after another around its
/// node: no single chain, a chain with two ends, or one that closes.
enum class ChainShape : uint8_t { none, open, closed };

/// The fans of a mesh, each as its corners (3 t + k: corner k of triangle t)
/// ordered into a chain around its node (each triangle's last corner the next
/// one's first after the node), from a fan id per corner of each triangle (as
/// InterfaceMesh::triangle_copies()). Depends on topology only, and is kept up
/// to date one changed triangle at a time.
class CornerFans {
public:
  /// Every fan anew.
  void build(std::span<const Triangle> triangles, std::span<const Triangle> corner_fans);
  /// After the triangles `changed` got other nodes or fans (`old_fans`: theirs
  /// before, one per changed triangle): only the fans they left or joined are
  /// ordered again.
  void update(std::span<const int32_t> changed, std::span<const Triangle> old_fans,
              std::span<const Triangle> triangles, std::span<const Triangle> corner_fans);
  size_t count() const { return corners_.count(); }
  /// The node a fan is around.
  int32_t node(size_t fan) const { return node_[fan]; }
  /// Its corners in chain order.
  std::span<const int32_t> corners(size_t fan) const { return corners_.at(fan); }
  /// Its corners form one chain (else it is never certified), and it closes.
  bool chained(size_t fan) const { return shape_[fan] != ChainShape::none; }
  bool closed(size_t fan) const { return shape_[fan] == ChainShape::closed; }

private:
  void order(size_t fan, std::span<const Triangle> triangles);

  PooledLists<int32_t> corners_;
  std::vector<int32_t> node_;
  std::vector<ChainShape> shape_;
};

/// Which fans are embedded now, each decided once, when first asked, from any
/// thread. Lives for one check: the positions must not change meanwhile.
class FanCertificates {
public:
  FanCertificates(std::span<const Vec3> points, std::span<const Triangle> triangles, const CornerFans& fans);
  /// True when the triangles of `fan` meet only where they share corners
  /// (false says nothing).
  bool embedded(int32_t fan) const;

private:
  std::span<const Vec3> points_;
  std::span<const Triangle> triangles_;
  const CornerFans& fans_;
  mutable std::vector<std::atomic<int8_t>> state_; ///< -1 not yet decided, else 0 or 1
};

/// Per node (of `points`), 1 when the node's triangles, all of them, make one
/// fan (its star) that is certified embedded as FanCertificates certifies a
/// fan: two of them meet only where they share corners. A check of a mesh
/// without fan ids (find_self_intersections) leaves such pairs untested; on a
/// smooth surface they are almost all the pairs whose boxes overlap.
std::vector<uint8_t> embedded_stars(std::span<const Vec3> points, std::span<const Triangle> triangles);

} // namespace vm::detail
