#pragma once
/// @file core/types.hpp
/// Small value types shared by every part of voronoimesh.

#include <Eigen/Core>
#include <Eigen/Geometry> // cross products on Vec3

#include <array>
#include <cstddef>
#include <cstdint>

namespace vm {

/// Most phases any input may have: meshes keep phase ids as int16 (PhaseSet, mesh/interface_mesh.hpp).
inline constexpr size_t kMaxPhases = 32767;
/// Most phases that may meet at one node of a mesh (PhaseSet holds them;
/// validate() reports a node with more).
inline constexpr size_t kMaxPhasesAtNode = 8;

/// A point or vector in 3-space, double precision.
using Vec3 = Eigen::Vector3d;

/// An axis-aligned box, the meshing domain.
struct Box {
  Vec3 min = Vec3::Zero(); ///< the corner with the smallest coordinates
  Vec3 max = Vec3::Ones(); ///< the corner with the largest coordinates
};

/// A Cartesian background grid: `cells` cells per axis over `domain`,
/// so (cells+1) nodes per axis with spacing (max-min)/cells.
struct GridSpec {
  Box domain;                           ///< the box the grid covers
  std::array<int, 3> cells{64, 64, 64}; ///< cells per axis (x, y, z)

  /// Spacing along each axis.
  Vec3 spacing() const {
    return (domain.max - domain.min).cwiseQuotient(Vec3(cells[0], cells[1], cells[2]));
  }
  /// Nodes per axis.
  std::array<int64_t, 3> nodes() const { return {cells[0] + 1, cells[1] + 1, cells[2] + 1}; }
  /// Nodes in all.
  int64_t node_count() const {
    auto n = nodes();
    return n[0] * n[1] * n[2];
  }
  /// Linear index of grid node (i, j, k): i fastest.
  /// @param i node along x, in [0, cells[0]]
  /// @param j node along y, in [0, cells[1]]
  /// @param k node along z, in [0, cells[2]]
  int64_t node_index(int64_t i, int64_t j, int64_t k) const {
    auto n = nodes();
    return i + n[0] * (j + n[1] * k);
  }
  /// Position of grid node (i, j, k).
  /// @param i node along x, in [0, cells[0]]
  /// @param j node along y, in [0, cells[1]]
  /// @param k node along z, in [0, cells[2]]
  Vec3 node_position(int64_t i, int64_t j, int64_t k) const {
    Vec3 h = spacing();
    return domain.min + Vec3(double(i) * h.x(), double(j) * h.y(), double(k) * h.z());
  }
  /// The typical cell size h: the largest spacing.
  double h() const { return spacing().maxCoeff(); }
};

/// An ordered phase pair of a triangle: first < second; the right-hand normal of
/// the triangle points from phase `first` into phase `second`.
using PhasePair = std::array<int32_t, 2>;

/// A phase's display colour: red, green, blue, each in [0, 1] (as 3D Slicer
/// stores a segment's colour).
using Rgb = std::array<float, 3>;

} // namespace vm
