// The flip pass's flips (improve/flip_log.hpp) leave OpenMesh's handles as its
// own flip() does, and their undo gives back the mesh bit for bit, face numbers
// and ring order included; and its later attempts, which test only
// what may differ from the last check (improve/flip_recheck.hpp), find every
// crossing a check of all flipped triangles finds, on meshes that crossed
// before the pass too.

#include "improve/flip_log.hpp"
#include "improve/flip_recheck.hpp"
#include "voronoimesh/improve/guard.hpp"
#include "voronoimesh/mesh/triangle_quality.hpp"

#include "fixtures.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace {

using namespace vm;
using detail::FlipLog;
using detail::FlipRecheck;
using Pairs = std::vector<std::array<int32_t, 2>>;

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

/// Flips the edges of `order` that OpenMesh and the patch-split mesh allow
/// (no edge that exists elsewhere), each `times` times, as the flip rounds do.
void flip_some(InterfaceMesh& mesh, FlipLog& log, const std::vector<int32_t>& order, int times = 1) {
  const OMesh& om = mesh.omesh();
  for (int32_t e : order)
    for (int k = 0; k < times; ++k) {
      const OMesh::EdgeHandle eh(e);
      if (om.is_boundary(eh) || !om.is_flip_ok(eh)) break;
      const auto h = om.halfedge_handle(eh, 0), o = om.halfedge_handle(eh, 1);
      const int32_t k0 = mesh.node(om.to_vertex_handle(om.next_halfedge_handle(h)));
      const int32_t k1 = mesh.node(om.to_vertex_handle(om.next_halfedge_handle(o)));
      if (k0 == k1 || mesh.adjacent(k0, k1)) break;
      log.flip(mesh, eh, {mesh.node(om.from_vertex_handle(h)), mesh.node(om.to_vertex_handle(h))});
    }
  mesh.faces_changed(log.faces());
}

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
    log.undo(mesh);
    EXPECT_TRUE(log.empty());
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
    if (step != 1) log.undo(mesh);
    ASSERT_EQ(mesh.qualities(), fresh_qualities(mesh));
  }
  mesh.topology_changed();
  EXPECT_EQ(mesh.qualities(), fresh_qualities(mesh));
}

/// The crossing pairs with a face in `flipped`, sorted.
Pairs with_flipped(Pairs pairs, const std::vector<uint8_t>& flipped) {
  std::erase_if(pairs, [&](const auto& p) { return !flipped[size_t(p[0])] && !flipped[size_t(p[1])]; });
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

TEST(FlipRecheck, later_attempts_find_every_crossing_of_the_flipped_triangles) {
  // Random flips fold quads over, and shaken nodes make crossings the pass did
  // not make: each attempt flips most of one set of edges, in one order, as an
  // attempt after banning culprits does.
  size_t crossings = 0, skipped = 0;
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE(seed);
    std::mt19937_64 rng(seed);
    InterfaceMesh mesh = InterfaceMesh::from_node_mesh(test::four_spheres(12));
    std::vector<Vec3> delta(mesh.num_nodes(), Vec3::Zero());
    std::uniform_real_distribution<double> u(-1, 1);
    for (size_t n = 0; n < delta.size(); n += 7) delta[n] = 0.08 * Vec3(u(rng), u(rng), u(rng));
    mesh.move_nodes(delta);
    auto edges = shuffled_edges(mesh, rng);
    edges.resize(edges.size() / 4);
    CrossingGuard restricted, full;
    FlipRecheck recheck;
    for (int attempt = 0; attempt < 5; ++attempt) {
      std::vector<int32_t> now;
      std::bernoulli_distribution keep(0.9);
      for (int32_t e : edges)
        if (keep(rng)) now.push_back(e);
      FlipLog log;
      flip_some(mesh, log, now);
      std::vector<uint8_t> flipped(mesh.num_triangles(), 0);
      for (int32_t f : log.faces()) flipped[size_t(f)] = 1;
      const auto test = recheck.faces_to_test(mesh, flipped);
      const Pairs found = restricted.crossings(mesh, test);
      const Pairs wanted = with_flipped(full.crossings(mesh, flipped), flipped);
      EXPECT_EQ(with_flipped(found, flipped), wanted) << "attempt " << attempt;
      crossings += wanted.size();
      skipped += size_t(std::count(flipped.begin(), flipped.end(), 1) - std::count(test.begin(), test.end(), 1));
      recheck.checked(mesh, flipped, found);
      log.undo(mesh);
    }
  }
  EXPECT_GT(crossings, 0u); // there was something to find
  EXPECT_GT(skipped, 0u);   // and the later attempts tested less than every flipped triangle
}

} // namespace
