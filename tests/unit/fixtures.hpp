#pragma once
/// @file fixtures.hpp
/// Tiny procedural interface meshes for the unit tests.

#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/sampled_field.hpp"
#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace vm::test {

/// Assembles a NodeMesh from triangles given by position; positions equal up
/// to rounding (to multiples of 2^-40) become one node.
class Builder {
public:
  explicit Builder(Box domain = {Vec3(-10, -10, -10), Vec3(10, 10, 10)}) { mesh.domain = domain; }

  int32_t node(const Vec3& p) {
    auto key = [](double x) { return std::llround(std::ldexp(x, 40)); };
    auto [it, added] = ids_.try_emplace({key(p.x()), key(p.y()), key(p.z())}, int32_t(mesh.points.size()));
    if (added) mesh.points.push_back(p);
    return it->second;
  }

  /// Triangle (a, b, c) whose right-hand normal points from phase `from` into
  /// phase `to`; stored with the pair sorted and the orientation to match.
  void tri(const Vec3& a, const Vec3& b, const Vec3& c, int from, int to) {
    std::array<int32_t, 3> t{node(a), node(b), node(c)};
    if (from > to) {
      std::swap(t[1], t[2]);
      std::swap(from, to);
    }
    mesh.triangles.push_back(t);
    mesh.pairs.push_back({from, to});
  }

  /// As tri(), with the orientation chosen so the normal points towards `toward`.
  void tri_towards(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& toward, int from, int to) {
    if ((b - a).cross(c - a).dot(toward - a) >= 0)
      tri(a, b, c, from, to);
    else
      tri(a, c, b, from, to);
  }

  /// The parallelogram o + [0,1] u + [0,1] v in n x n cells, two triangles each;
  /// the normal u x v points from `from` into `to`.
  void rect(const Vec3& o, const Vec3& u, const Vec3& v, int n, int from, int to) {
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        auto at = [&](int a, int b) -> Vec3 { return o + u * (double(a) / n) + v * (double(b) / n); };
        tri(at(i, j), at(i + 1, j), at(i + 1, j + 1), from, to);
        tri(at(i, j), at(i + 1, j + 1), at(i, j + 1), from, to);
      }
  }

  /// The six faces of the box [lo, hi] except those whose `skip` flag is set
  /// (order -x, +x, -y, +y, -z, +z), normals pointing out of `inside` into `outside`.
  void cuboid(const Vec3& lo, const Vec3& hi, int n, int inside, int outside, std::array<bool, 6> skip = {}) {
    const Vec3 d = hi - lo;
    const Vec3 ex(d.x(), 0, 0), ey(0, d.y(), 0), ez(0, 0, d.z());
    if (!skip[0]) rect(lo, ez, ey, n, inside, outside);
    if (!skip[1]) rect(lo + ex, ey, ez, n, inside, outside);
    if (!skip[2]) rect(lo, ex, ez, n, inside, outside);
    if (!skip[3]) rect(lo + ey, ez, ex, n, inside, outside);
    if (!skip[4]) rect(lo, ey, ex, n, inside, outside);
    if (!skip[5]) rect(lo + ez, ex, ey, n, inside, outside);
  }

  NodeMesh mesh;

private:
  std::map<std::array<long long, 3>, int32_t> ids_;
};

/// The surface of the tetrahedron v, normals pointing out of `inside` into `outside`.
inline void add_tetrahedron(Builder& b, const std::array<Vec3, 4>& v, int inside, int outside) {
  const Vec3 centre = (v[0] + v[1] + v[2] + v[3]) / 4;
  for (size_t i = 0; i < 4; ++i) {
    const Vec3 &a = v[(i + 1) % 4], &c = v[(i + 2) % 4], &d = v[(i + 3) % 4];
    b.tri_towards(a, c, d, 2 * a - centre, inside, outside);
  }
}

/// The corner tetrahedron at `o` with legs `s` (negative s mirrors it).
inline std::array<Vec3, 4> corner_tet(const Vec3& o, double s) {
  return {o, o + Vec3(s, 0, 0), o + Vec3(0, s, 0), o + Vec3(0, 0, s)};
}

/// A tetrahedron of phase 1 inside phase 0: 4 nodes, 4 triangles, 1 surface.
inline NodeMesh tetrahedron() {
  Builder b;
  add_tetrahedron(b, corner_tet(Vec3::Zero(), 1), 1, 0);
  return b.mesh;
}

/// Cubes [0,1]^3 (phase 1) and [1,2]x[0,1]^2 (phase 2) inside phase 0, faces in
/// n x n cells: 3 surfaces, 1 closed triple curve (the square around x = 1).
inline NodeMesh two_cubes(int n = 1) {
  Builder b;
  b.cuboid(Vec3(0, 0, 0), Vec3(1, 1, 1), n, 1, 0, {false, true, false, false, false, false});
  b.cuboid(Vec3(1, 0, 0), Vec3(2, 1, 1), n, 2, 0, {true, false, false, false, false, false});
  b.rect(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), n, 1, 2); // normal +x: from 1 into 2
  return b.mesh;
}

/// A tetrahedron split from its centroid into 4 cells (phases 1..4) inside
/// phase 0: 10 single-triangle surfaces, 10 triple-curve pieces (4 centroid
/// spokes, 6 tetrahedron edges), 5 quadruple points (centroid and corners).
inline NodeMesh four_phase_point() {
  Builder b;
  const std::array<Vec3, 4> v{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const Vec3 o = (v[0] + v[1] + v[2] + v[3]) / 4;
  // Cell i (phase i+1) is the cone from o over the face opposite corner i.
  for (int i = 0; i < 4; ++i) {
    const Vec3 &a = v[size_t((i + 1) % 4)], &c = v[size_t((i + 2) % 4)], &d = v[size_t((i + 3) % 4)];
    b.tri_towards(a, c, d, 2 * a - o, i + 1, 0);
  }
  // Triangle (o, x, y) separates the cells opposite the two other corners z
  // and w; the cell opposite w (phase w+1) lies on z's side, so the normal
  // towards z points from phase z+1 into phase w+1.
  for (int x = 0; x < 4; ++x)
    for (int y = x + 1; y < 4; ++y) {
      int z = -1, w = -1;
      for (int k = 0; k < 4; ++k)
        if (k != x && k != y) (z < 0 ? z : w) = k;
      b.tri_towards(o, v[size_t(x)], v[size_t(y)], v[size_t(z)], z + 1, w + 1);
    }
  return b.mesh;
}

/// The unit box as domain, phase 0 where x < 1/2, phase 1 where x > 1/2 and
/// y < 1/2, phase 2 where x > 1/2 and y > 1/2; planes in n x n cells per unit
/// (n even). 3 surfaces ending on the box, 1 triple curve from z = 0 to z = 1.
inline NodeMesh box_t_junction(int n = 2) {
  Builder b(Box{Vec3(0, 0, 0), Vec3(1, 1, 1)});
  const double h = 1.0 / n;
  for (int j = 0; j < n; ++j) // plane x = 1/2, normal +x
    for (int k = 0; k < n; ++k) b.rect(Vec3(0.5, j * h, k * h), Vec3(0, h, 0), Vec3(0, 0, h), 1, 0, 2 * j < n ? 1 : 2);
  for (int i = 0; 2 * i < n; ++i) // plane y = 1/2 for x > 1/2, normal +y
    for (int k = 0; k < n; ++k) b.rect(Vec3(0.5 + i * h, 0.5, k * h), Vec3(0, 0, h), Vec3(h, 0, 0), 1, 1, 2);
  return b.mesh;
}

/// k^3 blocks of the unit box, each its own phase, block faces in n x n cells:
/// interior block edges carry 4 phases and interior block corners 8. Its size
/// is 6 (k-1) k^2 n^2 triangles; used for timing and the 8-phase limit.
inline NodeMesh block_grains(int k, int n) {
  Builder b(Box{Vec3(0, 0, 0), Vec3(1, 1, 1)});
  const double s = 1.0 / k;
  auto phase = [k](int i, int j, int l) { return i + k * (j + k * l); };
  const std::array<Vec3, 3> e{Vec3(s, 0, 0), Vec3(0, s, 0), Vec3(0, 0, s)};
  for (int a = 0; a < 3; ++a) // planes normal to axis a
    for (int i = 1; i < k; ++i)
      for (int j = 0; j < k; ++j)
        for (int l = 0; l < k; ++l) {
          std::array<int, 3> lo{}, hi{};
          lo[size_t(a)] = i - 1, hi[size_t(a)] = i;
          lo[size_t((a + 1) % 3)] = hi[size_t((a + 1) % 3)] = j;
          lo[size_t((a + 2) % 3)] = hi[size_t((a + 2) % 3)] = l;
          const Vec3 o =
              double(i) * e[size_t(a)] + double(j) * e[size_t((a + 1) % 3)] + double(l) * e[size_t((a + 2) % 3)];
          b.rect(o, e[size_t((a + 1) % 3)], e[size_t((a + 2) % 3)], n, phase(lo[0], lo[1], lo[2]),
                 phase(hi[0], hi[1], hi[2]));
        }
  return b.mesh;
}

/// A shipped scene (examples/NAME) at `grid` cells per axis.
inline Scene example_scene(const std::string& name, int grid) {
  Scene scene = load_scene(std::string(VM_EXAMPLES_DIR) + "/" + name);
  scene.grid.cells = {grid, grid, grid};
  return scene;
}

/// The initial mesh of `scene` on the bcc lattice, with `phases`' names (the
/// scene's by default).
inline NodeMesh created_mesh(const Scene& scene, const CreateParams& params = {}, const PhaseField* phases = nullptr) {
  const SampledField field = SampledField::sample(*scene.field, grid_for_lattice(scene.grid, Lattice::bcc));
  NodeMesh m;
  create_initial_mesh(field, params, m);
  if (!phases) phases = scene.field.get();
  for (int p = 0; p < phases->num_phases(); ++p) m.phase_names.push_back(phases->phase_name(p));
  return m;
}

/// created_mesh() as the passes take it.
inline InterfaceMesh initial_mesh(const Scene& scene) { return InterfaceMesh::from_node_mesh(created_mesh(scene)); }

/// 0, 1, ..., n - 1: each triangle or node of a mesh as itself (an edit or
/// renumbering that keeps everything), or the start of ids that moves follow.
template <class Index = int32_t> std::vector<Index> identity(size_t n) {
  std::vector<Index> ids(n);
  std::iota(ids.begin(), ids.end(), 0);
  return ids;
}

/// The index before of each element of an array of `count` after `moves`
/// (SlotMoves: `a[m.to] = a[m.from]; a.pop_back();` for each move m).
inline std::vector<int32_t> replayed(size_t count, std::span<const SlotMove> moves) {
  std::vector<int32_t> old = identity(count);
  for (const SlotMove& m : moves) {
    old[size_t(m.to)] = old[size_t(m.from)];
    old.pop_back();
  }
  return old;
}

/// Run options of `n` iterations, the rest the defaults.
inline RunOptions iterations(int n) {
  RunOptions o;
  o.iterations = n;
  return o;
}

/// The paper's four overlapping spheres (examples/four_spheres.json) created at
/// `grid` cells per axis, with the scene's phase names: 5 phases, 10 surfaces,
/// 10 triple curves and 5 quadruple points (1226 triangles at grid 16). Every
/// sphere lies inside the domain, so every phase's boundary is closed.
inline NodeMesh four_spheres(int grid = 16) { return created_mesh(example_scene("four_spheres.json", grid)); }

} // namespace vm::test
