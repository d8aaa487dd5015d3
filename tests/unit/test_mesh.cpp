#include "fixtures.hpp"

#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/outside_phase.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include "mesh/node_rings.hpp"

#include <OpenMesh/Tools/Utils/MeshCheckerT.hh>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <sstream>

using namespace vm;

namespace {

void expect_same(const NodeMesh& a, const NodeMesh& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i) EXPECT_EQ(a.points[i], b.points[i]) << "node " << i;
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.pairs, b.pairs);
  EXPECT_EQ(a.phase_names, b.phase_names);
  EXPECT_EQ(a.phase_labels, b.phase_labels);
  EXPECT_EQ(a.domain.min, b.domain.min);
  EXPECT_EQ(a.domain.max, b.domain.max);
}

size_t boundary_edges(const OMesh& om) {
  size_t n = 0;
  for (auto e : om.edges()) n += om.is_boundary(e);
  return n;
}

bool mesh_checker_ok(const OMesh& om) {
  std::ostringstream log;
  return OpenMesh::Utils::MeshCheckerT<OMesh>(om).check(OpenMesh::Utils::MeshCheckerT<OMesh>::CHECK_ALL, log);
}

/// A random triangle soup of a few nodes on a small integer grid, with random
/// pairs of three phases: most are refused, the rest are odd meshes.
NodeMesh random_soup(std::mt19937& rng) {
  NodeMesh m;
  const int nodes = 4 + int(rng() % 4);
  for (int i = 0; i < nodes; ++i) m.points.emplace_back(double(rng() % 7), double(rng() % 7), double(rng() % 7));
  const int tris = 1 + int(rng() % 14);
  for (int t = 0; t < tris; ++t) {
    std::array<int32_t, 3> tri{};
    for (auto& v : tri) v = int32_t(rng() % uint32_t(nodes));
    const int32_t p = int32_t(rng() % 3);
    m.triangles.push_back(tri);
    m.pairs.push_back({p, p + 1 + int32_t(rng() % 2)});
  }
  return m;
}

/// Expects `om` to be linked as OpenMesh's add_face() links the same faces on
/// the same vertices, added in face order: the same edges, each face's
/// halfedges with the same opposite faces, every vertex as much on a boundary
/// and with as many neighbours. Returns false on the first difference.
bool linked_as_add_face_links(const OMesh& om) {
  OMesh ref;
  for (auto v : om.vertices()) ref.add_vertex(om.point(v));
  for (auto f : om.faces()) {
    std::vector<OMesh::VertexHandle> corners(om.fv_range(f).begin(), om.fv_range(f).end());
    if (!ref.add_face(corners).is_valid()) return false;
  }
  if (ref.n_edges() != om.n_edges() || !mesh_checker_ok(om)) return false;
  for (auto f : om.faces()) {
    OMesh::HalfedgeHandle h = om.halfedge_handle(f), r = ref.halfedge_handle(OMesh::FaceHandle(f.idx()));
    for (int k = 0; k < 3; ++k, h = om.next_halfedge_handle(h), r = ref.next_halfedge_handle(r))
      if (om.to_vertex_handle(h) != ref.to_vertex_handle(r) ||
          om.opposite_face_handle(h).idx() != ref.opposite_face_handle(r).idx())
        return false;
  }
  for (auto v : om.vertices())
    if (om.is_boundary(v) != ref.is_boundary(OMesh::VertexHandle(v.idx())) ||
        om.valence(v) != ref.valence(OMesh::VertexHandle(v.idx())))
      return false;
  return true;
}

std::string topology_error(const NodeMesh& m) {
  try {
    InterfaceMesh::from_node_mesh(m);
  } catch (const TopologyError& e) {
    return e.what();
  }
  return "";
}

} // namespace

TEST(InterfaceMesh, closed_surface_has_one_copy_per_node_and_no_boundary) {
  const auto im = InterfaceMesh::from_node_mesh(test::tetrahedron());
  EXPECT_EQ(im.num_nodes(), 4u);
  EXPECT_EQ(im.num_triangles(), 4u);
  EXPECT_EQ(im.omesh().n_vertices(), 4u);
  EXPECT_EQ(im.omesh().n_edges(), 6u);
  EXPECT_EQ(boundary_edges(im.omesh()), 0u);
  for (int32_t n = 0; n < 4; ++n) {
    ASSERT_EQ(im.copies(n).size(), 1u);
    EXPECT_EQ(im.node(OMesh::VertexHandle(im.copies(n)[0])), n);
    EXPECT_EQ(phase_count(im.phases()[size_t(n)]), 2);
    EXPECT_EQ(im.phases()[size_t(n)], (PhaseSet{0, 1, -1, -1, -1, -1, -1, -1}));
  }
  EXPECT_TRUE(mesh_checker_ok(im.omesh()));
  EXPECT_TRUE(validate(im).ok()) << validate(im).summary();
}

TEST(InterfaceMesh, junction_nodes_get_one_copy_per_patch) {
  const NodeMesh m = test::two_cubes(1);
  const auto im = InterfaceMesh::from_node_mesh(m);
  // 4 nodes on the shared square carry the patches (0,1), (0,2), (1,2).
  size_t triple = 0;
  for (size_t n = 0; n < m.points.size(); ++n) {
    const bool shared = m.points[n].x() == 1.0;
    EXPECT_EQ(im.copies(int32_t(n)).size(), shared ? 3u : 1u) << "node " << n;
    EXPECT_EQ(phase_count(im.phases()[n]), shared ? 3 : 2);
    triple += shared;
  }
  EXPECT_EQ(triple, 4u);
  EXPECT_EQ(im.omesh().n_vertices(), 8u + 3u * 4u);
  // Each of the 4 junction node-edges is a boundary edge in each of its 3 patches.
  EXPECT_EQ(boundary_edges(im.omesh()), 12u);
  for (auto v : im.omesh().vertices()) EXPECT_TRUE(im.omesh().is_manifold(v));
  EXPECT_TRUE(mesh_checker_ok(im.omesh()));
  EXPECT_TRUE(validate(im).ok()) << validate(im).summary();
}

TEST(InterfaceMesh, quadruple_point_gets_a_copy_per_incident_pair) {
  const NodeMesh m = test::four_phase_point();
  const auto im = InterfaceMesh::from_node_mesh(m);
  for (size_t n = 0; n < m.points.size(); ++n) {
    EXPECT_EQ(phase_count(im.phases()[n]), 4) << "node " << n;
    EXPECT_EQ(im.copies(int32_t(n)).size(), 6u) << "node " << n; // every triangle is its own patch
  }
  EXPECT_TRUE(validate(im).ok()) << validate(im).summary();
}

TEST(InterfaceMesh, round_trip_keeps_node_and_triangle_order) {
  NodeMesh m = test::four_phase_point();
  m.phase_names = {"out", "a", "b", "c", "d"};
  m.phase_labels = {0, 3, 4, 8, 100};
  // Rotate some triangles' corners and scramble triangle order: both must survive.
  std::mt19937 rng(3);
  for (auto& t : m.triangles) std::rotate(t.begin(), t.begin() + rng() % 3, t.end());
  for (size_t i = m.triangles.size() - 1; i > 0; --i) {
    const size_t j = rng() % (i + 1);
    std::swap(m.triangles[i], m.triangles[j]);
    std::swap(m.pairs[i], m.pairs[j]);
  }
  expect_same(InterfaceMesh::from_node_mesh(m).to_node_mesh(), m);
  for (const NodeMesh& f : {test::two_cubes(2), test::box_t_junction(4), test::block_grains(2, 2)})
    expect_same(InterfaceMesh::from_node_mesh(f).to_node_mesh(), f);
}

TEST(InterfaceMesh, points_mirror_node_positions) {
  const auto im = InterfaceMesh::from_node_mesh(test::box_t_junction(2));
  for (auto v : im.omesh().vertices()) {
    const auto& p = im.omesh().point(v);
    EXPECT_EQ(Vec3(p[0], p[1], p[2]), im.positions()[size_t(im.node(v))]);
  }
  // Face pair property matches the input.
  const NodeMesh m = test::box_t_junction(2);
  for (auto f : im.omesh().faces()) EXPECT_EQ(im.pair(f), m.pairs[size_t(f.idx())]);
}

TEST(InterfaceMesh, faces_changed_after_flips_leaves_the_tables_a_rebuild_would) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  const InterfaceMesh before = mesh;
  OMesh& om = mesh.omesh_for_topology();
  // Flip every tenth flippable patch edge whose new diagonal is not an edge yet.
  std::vector<int32_t> faces;
  size_t flips = 0;
  for (auto e : om.edges()) {
    if (e.idx() % 10 != 0 || om.is_boundary(e) || !om.is_flip_ok(e)) continue;
    const auto h = om.halfedge_handle(e, 0);
    const int32_t k = mesh.node(om.to_vertex_handle(om.next_halfedge_handle(h)));
    const int32_t l = mesh.node(om.to_vertex_handle(om.next_halfedge_handle(om.opposite_halfedge_handle(h))));
    if (mesh.adjacent(k, l)) continue;
    om.flip(e);
    ++flips;
    for (int side = 0; side < 2; ++side) faces.push_back(om.face_handle(om.halfedge_handle(e, side)).idx());
  }
  ASSERT_GT(flips, 100u);
  mesh.faces_changed(faces);
  InterfaceMesh rebuilt = mesh;
  rebuilt.topology_changed();
  EXPECT_EQ(mesh.triangles(), rebuilt.triangles());
  EXPECT_EQ(mesh.triangle_copies(), rebuilt.triangle_copies());
  size_t changed_rings = 0;
  for (size_t v = 0; v < mesh.num_nodes(); ++v) {
    const auto kept = mesh.neighbours(int32_t(v)), anew = rebuilt.neighbours(int32_t(v)),
               old = before.neighbours(int32_t(v));
    ASSERT_TRUE(std::equal(kept.begin(), kept.end(), anew.begin(), anew.end())) << "node " << v;
    changed_rings += !std::equal(kept.begin(), kept.end(), old.begin(), old.end());
  }
  EXPECT_GE(changed_rings, flips); // each flip changes four rings, some flips the same nodes' rings
}

TEST(InterfaceMesh, eight_phases_at_a_node_are_accepted) {
  const auto im = InterfaceMesh::from_node_mesh(test::block_grains(2, 1));
  int most = 0;
  for (const auto& s : im.phases()) most = std::max(most, phase_count(s));
  EXPECT_EQ(most, 8);
  EXPECT_TRUE(validate(im).ok()) << validate(im).summary();
}

TEST(InterfaceMesh, more_than_eight_phases_at_a_node_is_a_topology_error) {
  test::Builder b;
  // Nine triangles fanned around the origin, each with its own pair.
  for (int i = 0; i < 9; ++i) {
    const double a = 2 * 3.141592653589793 * i / 9, c = 2 * 3.141592653589793 * (i + 1) / 9;
    b.tri(Vec3::Zero(), Vec3(std::cos(a), std::sin(a), 0), Vec3(std::cos(c), std::sin(c), 0), 2 * i, 2 * i + 1);
  }
  EXPECT_NE(topology_error(b.mesh).find("node 0: 18 phases meet"), std::string::npos) << topology_error(b.mesh);
}

TEST(InterfaceMesh, malformed_triangles_are_refused_before_openmesh_sees_them) {
  NodeMesh m = test::tetrahedron();
  m.triangles[2] = {1, 1, 3}; // would abort inside libOpenMeshCore
  EXPECT_NE(topology_error(m).find("interface mesh: triangle 2 (1, 1, 3): repeated node"), std::string::npos)
      << topology_error(m);
  m = test::tetrahedron();
  m.triangles[3][1] = 4;
  EXPECT_NE(topology_error(m).find("triangle 3"), std::string::npos);
  EXPECT_NE(topology_error(m).find("out of range"), std::string::npos);
  m = test::tetrahedron();
  m.pairs[0] = {1, 0};
  EXPECT_NE(topology_error(m).find("triangle 0"), std::string::npos);
  EXPECT_NE(topology_error(m).find("bad phase pair (1, 0)"), std::string::npos);
  m = test::tetrahedron();
  m.pairs.pop_back();
  EXPECT_NE(topology_error(m).find("4 triangles but 3 phase pairs"), std::string::npos);
}

TEST(InterfaceMesh, pinched_surface_builds_and_fails_validation) {
  test::Builder b;
  test::add_tetrahedron(b, test::corner_tet(Vec3::Zero(), 1), 1, 0);
  test::add_tetrahedron(b, {Vec3(0, 0, 0), Vec3(-1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)}, 1, 0);
  const auto im = InterfaceMesh::from_node_mesh(b.mesh);
  const auto report = validate(im);
  EXPECT_FALSE(report.ok());
  EXPECT_NE(report.summary().find("non-manifold edge"), std::string::npos) << report.summary();
}

TEST(InterfaceMesh, random_soups_never_crash_openmesh) {
  // Any input either builds or is refused with a TopologyError: OpenMesh's own
  // assertions (which abort the process) must never be reached.
  std::mt19937 rng(12345);
  size_t built = 0, refused = 0;
  for (int iter = 0; iter < 3000; ++iter) {
    const NodeMesh m = random_soup(rng);
    try {
      const auto im = InterfaceMesh::from_node_mesh(m);
      (void)validate(im);
      ++built;
    } catch (const TopologyError&) {
      ++refused;
    }
  }
  EXPECT_GT(built, 100u);
  EXPECT_GT(refused, 100u);
}

// The build links faces itself where every corner class is a fan it can
// link alone (mesh/patch_connectivity.hpp), and through add_face() where not
// (two unglued halfedges on the same two vertices, as in odd soups): either
// way the mesh must be the one add_face() makes.
TEST(InterfaceMesh, faces_are_linked_as_openmesh_add_face_links_them) {
  std::mt19937 rng(2026);
  size_t built = 0;
  for (int iter = 0; iter < 20000; ++iter) {
    const NodeMesh m = random_soup(rng);
    if (!topology_error(m).empty()) continue;
    ++built;
    ASSERT_TRUE(linked_as_add_face_links(InterfaceMesh::from_node_mesh(m).omesh())) << "soup " << iter;
  }
  EXPECT_GT(built, 1000u);
  for (const NodeMesh& m : {test::two_cubes(2), test::four_phase_point(), test::box_t_junction(4),
                            test::block_grains(2, 2), test::four_spheres(12)})
    EXPECT_TRUE(linked_as_add_face_links(InterfaceMesh::from_node_mesh(m).omesh()));
}

// The remesh pass asks NodeRings between rebuilds what it asked the
// InterfaceMesh before: every answer must be the same, on an open mesh (box
// faces on its surfaces' borders) and a closed one (an outside phase).
TEST(NodeRings, answers_as_the_interface_mesh_does) {
  const Scene scene = test::example_scene("voronoi7.json", 16);
  CreateParams closed;
  closed.close = true;
  for (const NodeMesh& m : {test::created_mesh(scene),
                            test::created_mesh(scene, closed, with_outside_phase(scene.field, scene.grid.domain).get())}) {
    const InterfaceMesh im = InterfaceMesh::from_node_mesh(m);
    const detail::NodeRings rings(m);
    ASSERT_EQ(rings.num_nodes(), im.num_nodes());
    EXPECT_EQ(rings.phases(), im.phases());
    EXPECT_EQ(rings.box_faces(), im.box_faces());
    EXPECT_EQ(rings.outside_phase(), im.outside_phase());
    size_t box_nodes = 0;
    for (int32_t n = 0; n < int32_t(m.num_nodes()); ++n) {
      const auto a = rings.neighbours(n), b = im.neighbours(n);
      ASSERT_EQ(std::vector<int32_t>(a.begin(), a.end()), std::vector<int32_t>(b.begin(), b.end())) << "node " << n;
      std::vector<std::array<int32_t, 2>> from_rings, from_mesh;
      rings.for_each_triangle_at(n, [&](int32_t x, int32_t y) { from_rings.push_back({x, y}); });
      im.for_each_triangle_at(n, [&](int32_t x, int32_t y) { from_mesh.push_back({x, y}); });
      std::sort(from_rings.begin(), from_rings.end());
      std::sort(from_mesh.begin(), from_mesh.end());
      EXPECT_EQ(from_rings, from_mesh) << "node " << n;
      for (int32_t w : b) EXPECT_EQ(rings.constraints_within(n, w), im.constraints_within(n, w)) << n << "-" << w;
      for (int32_t p = -1; p <= int32_t(scene.field->num_phases()); ++p) EXPECT_EQ(rings.has_phase(n, p), im.has_phase(n, p));
      box_nodes += im.box_faces()[size_t(n)] != 0;
    }
    EXPECT_GT(box_nodes, 0u); // the box faces were compared where they are set
  }
}

// The box faces a node lies on follow its moves and placements, as a mesh
// built from the moved positions finds them (distributed improvement builds its
// windows afresh every iteration and must make the one-process mesh).
TEST(InterfaceMesh, box_faces_follow_the_nodes) {
  InterfaceMesh im = InterfaceMesh::from_node_mesh(test::created_mesh(test::example_scene("four_spheres.json", 12)));
  const Box box = im.domain();
  int32_t inner = -1;
  for (int32_t n = 0; n < int32_t(im.num_nodes()) && inner < 0; ++n)
    if (im.box_faces()[size_t(n)] == 0) inner = n;
  ASSERT_GE(inner, 0);
  std::vector<Vec3> delta(im.num_nodes(), Vec3::Zero());
  delta[size_t(inner)].x() = box.min.x() - im.positions()[size_t(inner)].x(); // onto the min-x face
  im.move_nodes(delta);
  EXPECT_EQ(im.box_faces()[size_t(inner)], 1u);
  const Vec3 inside = (box.min + box.max) / 2;
  im.place_nodes(std::vector<int32_t>{inner}, std::vector<Vec3>{inside});
  EXPECT_EQ(im.box_faces()[size_t(inner)], 0u);
  const InterfaceMesh rebuilt = InterfaceMesh::from_node_mesh(im.to_node_mesh());
  EXPECT_EQ(rebuilt.box_faces(), im.box_faces());
}
