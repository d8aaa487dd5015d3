#pragma once
/// @file plugin/plugin_helpers.hpp
/// Header-only C++ helpers for writing pass plugins against plugin/plugin_abi.h: a
/// small vector type, a read-only view of the C mesh arrays, the tangential
/// constraints every node-moving pass must respect, and a guard that turns
/// exceptions into the C status code and message. Uses only the C++ standard
/// library (no Eigen, no OpenMesh, no libvoronoimesh), so a plugin built with it
/// links against nothing of ours.

#include "voronoimesh/plugin/plugin_abi.h"

#include <cmath>
#include <cstdio>
#include <exception>
#include <span>
#include <vector>

namespace vm::plugin {

/// A 3-vector of doubles.
struct V3 {
  /// The x component.
  double x = 0, y = 0, z = 0; ///< the z component
  /// @var y
  /// The y component.

  /// The sum with `o`.
  /// @param o the other vector
  V3 operator+(const V3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  /// The difference from `o` (this - o).
  /// @param o the vector subtracted
  V3 operator-(const V3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  /// This vector scaled by `s`.
  /// @param s the factor
  V3 operator*(double s) const { return {x * s, y * s, z * s}; }
  /// Adds `o` to this vector.
  /// @param o the vector added
  /// @return this vector
  V3& operator+=(const V3& o) { return *this = *this + o; }
  /// The dot product with `o`.
  /// @param o the other vector
  double dot(const V3& o) const { return x * o.x + y * o.y + z * o.z; }
  /// The cross product with `o` (this x o).
  /// @param o the other vector
  V3 cross(const V3& o) const { return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x}; }
  /// The Euclidean length.
  double norm() const { return std::sqrt(dot(*this)); }
};

/// Read access to a vm_mesh_view, plus the triangles at every node.
class Mesh {
public:
  /// Reads `v` and finds the triangles at every node.
  /// @param v the mesh the pass was given; not copied: it must outlive this Mesh (the call of `run`)
  explicit Mesh(const vm_mesh_view& v) : v_(v), tri_off_(v.num_nodes + 1, 0) {
    for (size_t t = 0; t < 3 * v.num_triangles; ++t) ++tri_off_[size_t(v.triangles[t]) + 1];
    for (size_t i = 0; i < v.num_nodes; ++i) tri_off_[i + 1] += tri_off_[i];
    tri_.resize(3 * v.num_triangles);
    std::vector<int32_t> fill(tri_off_.begin(), tri_off_.end() - 1);
    for (size_t t = 0; t < v.num_triangles; ++t)
      for (int k = 0; k < 3; ++k) tri_[size_t(fill[size_t(v.triangles[3 * t + size_t(k)])]++)] = int32_t(t);
  }

  /// Number of nodes.
  size_t num_nodes() const { return v_.num_nodes; }
  /// Position of node i.
  /// @param i a node id, in [0, num_nodes())
  V3 pos(int32_t i) const { return {v_.positions[3 * i], v_.positions[3 * i + 1], v_.positions[3 * i + 2]}; }
  /// Junction order of node i: its phases plus its box faces (2 a surface node, 3 a curve, 4 and more a point).
  /// @param i a node id, in [0, num_nodes())
  int order(int32_t i) const { return v_.junction_order[i]; }
  /// Neighbouring nodes of node i, sorted.
  /// @param i a node id, in [0, num_nodes())
  std::span<const int32_t> neighbours(int32_t i) const {
    return {v_.neighbours + v_.neighbour_offsets[i], size_t(v_.neighbour_offsets[i + 1] - v_.neighbour_offsets[i])};
  }
  /// Triangles containing node i.
  /// @param i a node id, in [0, num_nodes())
  std::span<const int32_t> triangles_at(int32_t i) const {
    return {tri_.data() + tri_off_[size_t(i)], size_t(tri_off_[size_t(i) + 1] - tri_off_[size_t(i)])};
  }
  /// The three node ids of triangle t, in its orientation order.
  /// @param t a triangle id, in [0, num_triangles)
  const int32_t* triangle(int32_t t) const { return v_.triangles + 3 * t; }
  /// Twice the area vector of triangle t (along its oriented normal).
  /// @param t a triangle id, in [0, num_triangles)
  V3 area_vector(int32_t t) const {
    const int32_t* n = triangle(t);
    return (pos(n[1]) - pos(n[0])).cross(pos(n[2]) - pos(n[0]));
  }
  /// True when every phase and box face of node a is also one of node b's: b
  /// lies on every surface, curve and box face a lies on.
  /// @param a the node whose constraints are looked for
  /// @param b the node that must have them all
  bool constraints_within(int32_t a, int32_t b) const {
    if ((v_.box_faces[a] & ~v_.box_faces[b]) != 0) return false;
    const int16_t *pa = v_.phases + 8 * a, *pb = v_.phases + 8 * b;
    for (int i = 0; i < 8 && pa[i] >= 0; ++i) {
      bool found = false;
      for (int j = 0; j < 8 && pb[j] >= 0; ++j) found = found || pa[i] == pb[j];
      if (!found) return false;
    }
    return true;
  }

  /// The Laplacian of node i over positions `x` (one per node): the mean of
  /// x_w - x_i over the neighbours w that lie on everything i lies on (as the
  /// built-in smooth's half-Laplacian chooses them); zero if there are none.
  /// @param i a node id, in [0, num_nodes())
  /// @param x a position per node
  V3 laplacian(int32_t i, std::span<const V3> x) const {
    V3 sum;
    int count = 0;
    for (int32_t w : neighbours(i))
      if (constraints_within(i, w)) sum += x[size_t(w)] - x[size_t(i)], ++count;
    return count ? sum * (1.0 / count) : V3{};
  }

  /// `move` reduced to what node i may do without leaving its constraints: on
  /// a surface (order 2), its tangent plane (normal from the node's triangles);
  /// on a curve (order 3), the curve's direction through its two neighbours on
  /// the same curve, and only if `along_curves`; points (order 4 and more) stay.
  /// Components that would leave a box face are always removed.
  /// @param i            a node id, in [0, num_nodes())
  /// @param move         the move wanted for node i
  /// @param along_curves let triple-curve nodes move along their curve (else they stay)
  /// @return the move node i may make
  V3 constrain(int32_t i, V3 move, bool along_curves) const {
    if (order(i) == 2) {
      V3 n;
      for (int32_t t : triangles_at(i)) n += area_vector(t);
      const double len = n.norm();
      if (len > 0) move = move - n * (move.dot(n) / (len * len));
    } else if (order(i) == 3 && along_curves) {
      int32_t ends[2] = {0, 0};
      int count = 0;
      for (int32_t w : neighbours(i))
        if (constraints_within(i, w)) {
          if (count < 2) ends[count] = w;
          ++count;
        }
      if (count != 2) return {};
      const V3 dir = pos(ends[1]) - pos(ends[0]);
      const double len2 = dir.dot(dir);
      move = len2 > 0 ? dir * (move.dot(dir) / len2) : V3{};
    } else {
      return {};
    }
    const uint8_t box = v_.box_faces[i];
    if (box & 3u) move.x = 0;
    if (box & 12u) move.y = 0;
    if (box & 48u) move.z = 0;
    return move;
  }

private:
  const vm_mesh_view& v_;
  std::vector<int32_t> tri_off_, tri_;
};

/// The parameter that gives Mesh::constrain()'s `along_curves`, for passes that
/// offer the choice (relax and cvt do).
inline constexpr vm_param_spec kJunctionsParam = {"junctions", 1, 0, 1, 1,
                                                  "1: move triple-curve nodes along their curve; 0: keep them fixed"};

/// Adds `d` to node i's pending displacement.
/// @param v the mesh the pass was given; its displacement must not be NULL (a pass that moves nodes)
/// @param i a node id, in [0, v.num_nodes)
/// @param d the move to add
inline void add_displacement(const vm_mesh_view& v, int32_t i, const V3& d) {
  v.displacement[3 * i] += d.x;
  v.displacement[3 * i + 1] += d.y;
  v.displacement[3 * i + 2] += d.z;
}

/// Runs `body`, turning any exception into status 1 and its message in `error`:
/// exceptions must never cross the C boundary.
/// @param error      receives the message (the `error` of vm_pass_run)
/// @param error_size bytes of `error`, with the terminating 0
/// @param body       the pass's work, called with no arguments
/// @return 0 if `body` returned, 1 if it threw ("unknown error" for what is not a std::exception)
template <class F> int guarded(char* error, size_t error_size, F&& body) {
  try {
    body();
    return 0;
  } catch (const std::exception& e) {
    std::snprintf(error, error_size, "%s", e.what());
  } catch (...) {
    std::snprintf(error, error_size, "unknown error");
  }
  return 1;
}

} // namespace vm::plugin

/// Defines the two functions a plugin exports (plugin/plugin_abi.h): the ABI version
/// and an entry point that names the plugin NAME (version VERSION) and adds
/// every vm_pass_desc of the array PASSES. Use once, at namespace scope.
#define VM_PLUGIN_DEFINE(NAME, VERSION, PASSES)                                                          \
  extern "C" VM_PLUGIN_EXPORT uint32_t voronoimesh_plugin_abi_version(void) { return VM_PLUGIN_ABI_VERSION; } \
  extern "C" VM_PLUGIN_EXPORT int voronoimesh_plugin_v1(const vm_plugin_host* host) {                    \
    host->set_info(host->context, NAME, VERSION);                                                        \
    for (const vm_pass_desc& pass : PASSES)                                                              \
      if (host->add_pass(host->context, &pass) != 0) return 1;                                           \
    return 0;                                                                                            \
  }
