// The flip pass's flips (improve/flip_log.hpp) leave OpenMesh's handles as its
// own flip() does; their undo gives back the mesh bit for bit, face numbers
// and ring order included; and undoing some of them with the later ones that
// share a node gives the mesh the others alone make, bit for bit.

#include "improve/flip_log.hpp"
#include "voronoimesh/mesh/triangle_quality.hpp"

#include "fixtures.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace {

using namespace vm;
using detail::FlipLog;

/// Everything OpenMesh keeps about the connectivity, and what InterfaceMesh
/// derives from it.
struct Connectivity {
  std::vector<int> halfedges, faces, vertices;
  std::vector<std::array<int32_t, 3>> triangles, copies;
  std::vector<std::vector<int32_t>> rings;
  bool operator==(const Connectivity&) const = default;
};

Connectivity connectivity(const InterfaceMesh& mesh) {
  const OMesh& om = mesh.omesh();
  Connectivity c;
  for (auto h : om.halfedges())
    c.halfedges.insert(c.halfedges.end(), {om.next_halfedge_handle(h).idx(), om.prev_halfedge_handle(h).idx(),
                                           om.to_vertex_handle(h).idx(), om.face_handle(h).idx()});
  for (auto f : om.faces()) c.faces.push_back(om.halfedge_handle(f).idx());
  for (auto v : om.vertices()) c.vertices.push_back(om.halfedge_handle(v).idx());
  c.triangles = mesh.triangles();
  c.copies = mesh.triangle_copies();
  for (size_t n = 0; n < mesh.num_nodes(); ++n) {
    const auto ring = mesh.neighbours(int32_t(n));
    c.rings.emplace_back(ring.begin(), ring.end());
  }
  return c;
}

/// Flips edge `e` of `mesh` into `log` if OpenMesh and the patch-split mesh
/// allow it (no edge that exists elsewhere), as the flip rounds do; returns
/// whether it did. triangles() is not updated.
bool flip_if_allowed(InterfaceMesh& mesh, FlipLog& log, int32_t e) {
  const OMesh& om = mesh.omesh();
  const OMesh::EdgeHandle eh(e);
  if (om.is_boundary(eh) || !om.is_flip_ok(eh)) return false;
  const auto h = om.halfedge_handle(eh, 0), o = om.halfedge_handle(eh, 1);
  const int32_t k0 = mesh.node(om.to_vertex_handle(om.next_halfedge_handle(h)));
  const int32_t k1 = mesh.node(om.to_vertex_handle(om.next_halfedge_handle(o)));
  if (k0 == k1 || mesh.adjacent(k0, k1)) return false;
  log.flip(mesh, eh, {mesh.node(om.from_vertex_handle(h)), mesh.node(om.to_vertex_handle(h)), k0, k1});
  return true;
}

/// Flips the edges of `order` that may flip, each `times` times.
void flip_some(InterfaceMesh& mesh, FlipLog& log, const std::vector<int32_t>& order, int times = 1) {
  for (int32_t e : order)
    for (int k = 0; k < times && flip_if_allowed(mesh, log, e); ++k) {
    }
  mesh.faces_changed(log.faces());
}

/// One flag a logged flip, every one set.
std::vector<uint8_t> all_of(const FlipLog& log) { return std::vector<uint8_t>(log.size(), 1); }

std::vector<int32_t> shuffled_edges(const InterfaceMesh& mesh, std::mt19937_64& rng) {
  std::vector<int32_t> edges(mesh.omesh().n_edges());
  for (size_t e = 0; e < edges.size(); ++e) edges[e] = int32_t(e);
  std::shuffle(edges.begin(), edges.end(), rng);
  return edges;
}

// FlipLog flips without OpenMesh's flip() (Debian builds it with assertions,
// which ask is_flip_ok() again every time), so it must move every handle as
// that does: faces, corners' outgoing halfedges and cycles alike.
TEST(FlipLog, flips_move_every_handle_as_openmesh_flip_does) {
  InterfaceMesh ours = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  InterfaceMesh theirs = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  std::mt19937_64 rng(11);
  FlipLog log;
  auto edges = shuffled_edges(ours, rng);
  edges.resize(edges.size() / 3);
  flip_some(ours, log, edges, 2); // twice too: a flipped edge flips again
  ASSERT_GT(log.size(), 100u);
  for (int32_t e : log.edges()) theirs.omesh_for_topology().flip(OMesh::EdgeHandle(e));
  theirs.faces_changed(log.faces());
  EXPECT_EQ(connectivity(ours), connectivity(theirs));
}

TEST(FlipLog, undo_gives_back_the_mesh_bit_for_bit) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  std::mt19937_64 rng(7);
  const Connectivity before = connectivity(mesh);
  for (int times : {1, 2, 3}) { // an edge flipped twice comes back to its diagonal with its faces swapped
    SCOPED_TRACE(times);
    FlipLog log;
    auto edges = shuffled_edges(mesh, rng);
    edges.resize(edges.size() / 3);
    flip_some(mesh, log, edges, times);
    ASSERT_GT(log.size(), 100u);
    EXPECT_NE(connectivity(mesh), before);
    log.undo(mesh, all_of(log));
    EXPECT_EQ(connectivity(mesh), before);
  }
}

/// triangle_quality() of every face, computed anew.
std::vector<double> fresh_qualities(const InterfaceMesh& mesh) {
  std::vector<double> q;
  for (const auto& t : mesh.triangles())
    q.push_back(triangle_quality(mesh.positions()[size_t(t[0])], mesh.positions()[size_t(t[1])],
                                 mesh.positions()[size_t(t[2])]));
  return q;
}

// The qualities the mesh keeps (InterfaceMesh::qualities()) are those of its
// faces now after every kind of change: moves, nodes put back, flips and their undo.
TEST(FlipLog, the_mesh_keeps_its_face_qualities_current_through_moves_flips_and_undo) {
  InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(16));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int step = 0; step < 3; ++step) {
    SCOPED_TRACE(step);
    ASSERT_EQ(mesh.qualities(), fresh_qualities(mesh));
    const std::vector<Vec3> before = mesh.positions();
    std::vector<Vec3> delta(mesh.num_nodes());
    for (auto& d : delta) d = 0.2 / 16 * Vec3(u(rng), u(rng), u(rng));
    mesh.move_nodes(delta);
    ASSERT_EQ(mesh.qualities(), fresh_qualities(mesh));
    std::vector<int32_t> back;
    for (int32_t n = 0; n < int32_t(mesh.num_nodes()); n += 7) back.push_back(n);
    std::vector<Vec3> where;
    for (int32_t n : back) where.push_back(before[size_t(n)]);
    mesh.place_nodes(back, where);
    ASSERT_EQ(mesh.qualities(), fresh_qualities(mesh));
    FlipLog log;
    auto edges = shuffled_edges(mesh, rng);
    edges.resize(edges.size() / 4);
    flip_some(mesh, log, edges);
    ASSERT_GT(log.size(), 100u);
    ASSERT_EQ(mesh.qualities(), fresh_qualities(mesh));
    if (step != 1) log.undo(mesh, all_of(log));
    ASSERT_EQ(mesh.qualities(), fresh_qualities(mesh));
  }
  mesh.topology_changed();
  EXPECT_EQ(mesh.qualities(), fresh_qualities(mesh));
}

// The flip pass undoes the flips that made a crossing and, so that the undo is
// exact, every later flip that shares a node with one (with_dependents()); the
// mesh is then the one the other flips alone make, handles and all, whichever
// flips are undone and however often an edge flipped.
TEST(FlipLog, undoing_some_flips_with_their_dependents_leaves_the_mesh_the_others_make) {
  size_t dependents = 0;
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE(seed);
    std::mt19937_64 rng(seed);
    InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(12));
    FlipLog log;
    auto edges = shuffled_edges(mesh, rng);
    edges.resize(edges.size() / 3);
    flip_some(mesh, log, edges, int(seed % 3) + 1);
    ASSERT_GT(log.size(), 100u);
    // Culprits in two calls, as the pass finds more after an undo.
    std::vector<uint8_t> undone(log.size(), 0);
    std::bernoulli_distribution culprit(0.02);
    for (int call = 0; call < 2; ++call) {
      std::vector<uint8_t> undo(log.size(), 0);
      for (size_t i = 0; i < undo.size(); ++i) undo[i] = !undone[i] && culprit(rng);
      const auto flagged = std::count(undo.begin(), undo.end(), 1);
      log.with_dependents(undo, undone, mesh.num_nodes());
      dependents += size_t(std::count(undo.begin(), undo.end(), 1) - flagged);
      for (size_t i = 0; i < undo.size(); ++i) {
        ASSERT_FALSE(undo[i] && undone[i]);
        undone[i] = undone[i] || undo[i];
      }
      log.undo(mesh, undo);
    }
    ASSERT_GT(std::count(undone.begin(), undone.end(), 0), 0);
    InterfaceMesh others = InterfaceMesh::from_node_mesh(test::four_spheres(12));
    FlipLog replay;
    for (size_t i = 0; i < log.size(); ++i)
      if (!undone[i]) ASSERT_TRUE(flip_if_allowed(others, replay, log.edges()[i])) << "flip " << i;
    others.faces_changed(replay.faces());
    EXPECT_EQ(connectivity(mesh), connectivity(others));
  }
  EXPECT_GT(dependents, 0u); // some undo was exact only with its dependents
}

} // namespace
