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

#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

namespace vm::detail {

/// One triangle of a fan around a node: its corners after the node, in the
/// triangle's order.
struct Sector {
  int32_t a = -1, b = -1;
};

/// The fans of a mesh as chains of sectors: built from a fan id per corner of
/// each triangle (as InterfaceMesh::triangle_copies()); depends on topology only.
class CornerFans {
public:
  CornerFans() = default;
  CornerFans(std::span<const Triangle> triangles, std::span<const Triangle> corner_fans);
  size_t count() const { return node_.size(); }
  /// The node a fan is around.
  int32_t node(size_t fan) const { return node_[fan]; }
  /// Its sectors, each one's b the next one's a; empty where they form no
  /// single chain (such a fan is never certified).
  std::span<const Sector> sectors(size_t fan) const {
    return {sectors_.data() + offset_[fan], size_t(offset_[fan + 1] - offset_[fan])};
  }
  /// The chain closes (its last b is its first a).
  bool closed(size_t fan) const { return closed_[fan] != 0; }

private:
  std::vector<uint32_t> offset_{0};
  std::vector<Sector> sectors_;
  std::vector<int32_t> node_;
  std::vector<uint8_t> closed_;
};

/// Which fans are embedded now, each decided once, when first asked, from any
/// thread. Lives for one check: the positions must not change meanwhile.
class FanCertificates {
public:
  FanCertificates(std::span<const Vec3> points, const CornerFans& fans);
  /// True when the triangles of `fan` meet only where they share corners
  /// (false says nothing).
  bool embedded(int32_t fan) const;

private:
  std::span<const Vec3> points_;
  const CornerFans& fans_;
  mutable std::vector<std::atomic<int8_t>> state_; ///< -1 not yet decided, else 0 or 1
};

} // namespace vm::detail
