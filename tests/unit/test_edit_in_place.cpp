// InterfaceMesh::edit_in_place(): random local edits (refills, flips, edge
// splits on surfaces and junctions, node merges; faces rewritten in place or
// removed and added) in sequence, each checked against from_node_mesh() of the
// same triangles.
#include "fixtures.hpp"

#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"
#include "voronoimesh/mesh/triangle_quality.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

using namespace vm;
using namespace vm::test;

namespace {

/// A triangle with its pair, turned so its smallest node comes first
/// (orientation kept): equal for the same oriented triangle in any mesh
/// numbered alike.
using Key = std::array<int32_t, 5>;
Key key_of(std::array<int32_t, 3> t, const PhasePair& p) {
  std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  return {t[0], t[1], t[2], p[0], p[1]};
}

/// What from_node_mesh() fixes about a mesh, in terms that do not depend on
/// face or vertex numbers: its triangles, each node's copies (as the sets of
/// triangles around each), phases, neighbours, box faces and position, and
/// which triangles are glued.
struct Shape {
  std::vector<Key> triangles;
  std::vector<std::vector<std::vector<Key>>> copies;
  std::vector<PhaseSet> phases;
  std::vector<std::vector<int32_t>> neighbours;
  std::vector<uint8_t> box;
  std::vector<Vec3> points;
  std::vector<std::pair<Key, Key>> glued;
  bool operator==(const Shape&) const = default;
};

Shape shape_of(const InterfaceMesh& m) {
  const OMesh& om = m.omesh();
  auto key = [&](OMesh::FaceHandle f) { return key_of(m.face_nodes(f), m.pair(f)); };
  Shape s;
  for (auto f : om.faces()) {
    s.triangles.push_back(key(f));
    for (auto h : om.fh_range(f))
      if (const auto g = om.opposite_face_handle(h); g.is_valid()) s.glued.emplace_back(key(f), key(g));
  }
  std::sort(s.triangles.begin(), s.triangles.end());
  std::sort(s.glued.begin(), s.glued.end());
  for (size_t n = 0; n < m.num_nodes(); ++n) {
    std::vector<std::vector<Key>> fans;
    for (int32_t c : m.copies(int32_t(n))) {
      std::vector<Key> fan;
      for (auto f : om.vf_range(OMesh::VertexHandle(c))) fan.push_back(key(f));
      std::sort(fan.begin(), fan.end());
      fans.push_back(fan);
    }
    std::sort(fans.begin(), fans.end());
    s.copies.push_back(fans);
    const auto ring = m.neighbours(int32_t(n));
    s.neighbours.emplace_back(ring.begin(), ring.end());
  }
  s.phases = m.phases();
  s.box = m.box_faces();
  s.points = m.positions();
  return s;
}

/// The edited mesh's own arrays agree with its OpenMesh mesh: triangles(),
/// triangle_copies(), qualities(), every copy naming its node once.
void expect_consistent(const InterfaceMesh& m) {
  const OMesh& om = m.omesh();
  ASSERT_EQ(m.triangles().size(), om.n_faces());
  ASSERT_EQ(m.triangle_copies().size(), om.n_faces());
  const auto& q = m.qualities();
  for (auto f : om.faces()) {
    const auto i = size_t(f.idx());
    EXPECT_EQ(m.triangles()[i], m.face_nodes(f)) << "face " << i;
    auto h = om.halfedge_handle(f);
    for (size_t k = 0; k < 3; ++k, h = om.next_halfedge_handle(h))
      EXPECT_EQ(m.triangle_copies()[i][k], om.to_vertex_handle(h).idx()) << "face " << i;
    const auto& t = m.triangles()[i];
    EXPECT_EQ(q[i], triangle_quality(m.positions()[size_t(t[0])], m.positions()[size_t(t[1])], m.positions()[size_t(t[2])]));
  }
  size_t copies = 0;
  for (size_t n = 0; n < m.num_nodes(); ++n)
    for (int32_t c : m.copies(int32_t(n))) {
      ++copies;
      EXPECT_EQ(m.node(OMesh::VertexHandle(c)), int32_t(n));
      EXPECT_EQ(om.point(OMesh::VertexHandle(c)), OMesh::Point(m.positions()[n].x(), m.positions()[n].y(), m.positions()[n].z()));
    }
  EXPECT_EQ(copies, om.n_vertices());
}

/// `edit` made on the node level: faces out (by id), triangles in, new nodes
/// appended, removed nodes swap-removed from the highest (as edit_in_place()).
NodeMesh edited(NodeMesh m, const LocalEdit& edit) {
  std::vector<char> gone(m.triangles.size(), 0);
  for (int32_t f : edit.removed_faces) gone[size_t(f)] = 1;
  for (int32_t f : edit.rewritten_faces) gone[size_t(f)] = 1;
  NodeMesh out = m;
  out.triangles.clear();
  out.pairs.clear();
  for (size_t t = 0; t < m.triangles.size(); ++t)
    if (!gone[t]) out.triangles.push_back(m.triangles[t]), out.pairs.push_back(m.pairs[t]);
  out.triangles.insert(out.triangles.end(), edit.added.begin(), edit.added.end());
  out.pairs.insert(out.pairs.end(), edit.added_pairs.begin(), edit.added_pairs.end());
  out.points.insert(out.points.end(), edit.new_nodes.begin(), edit.new_nodes.end());
  std::vector<int32_t> removed = edit.removed_nodes;
  std::sort(removed.rbegin(), removed.rend());
  for (int32_t n : removed) {
    const auto last = int32_t(out.points.size() - 1);
    out.points[size_t(n)] = out.points.back();
    out.points.pop_back();
    for (auto& t : out.triangles)
      for (int32_t& v : t)
        if (v == last) v = n;
  }
  return out;
}

/// The faces on node-edge a-b.
std::vector<int32_t> faces_on(const InterfaceMesh& m, int32_t a, int32_t b) {
  std::vector<int32_t> on;
  for (int32_t f : m.faces_at(std::array{a}))
    if (std::count(m.triangles()[size_t(f)].begin(), m.triangles()[size_t(f)].end(), b)) on.push_back(f);
  return on;
}

/// Where element `id` is after `moves` (it must not be one removed).
int32_t position_after(const std::vector<SlotMove>& moves, int32_t id) {
  for (const SlotMove& m : moves)
    if (m.from == id) id = m.to;
  return id;
}

/// `e` with its first `count` removed faces rewritten by its first added
/// triangles instead (the faces then keep their indices).
LocalEdit rewriting(LocalEdit e, size_t count) {
  e.rewritten_faces.assign(e.removed_faces.begin(), e.removed_faces.begin() + ptrdiff_t(count));
  e.removed_faces.erase(e.removed_faces.begin(), e.removed_faces.begin() + ptrdiff_t(count));
  return e;
}

/// A random local edit of `m`, or nothing where the one drawn does not apply.
/// Faces that change corners are rewritten in place or removed and added, at
/// random.
std::optional<LocalEdit> random_edit(const InterfaceMesh& m, std::mt19937& rng) {
  const bool rewrite = rng() % 2;
  LocalEdit e;
  const auto f = int32_t(rng() % m.num_triangles());
  const auto& tri = m.triangles()[size_t(f)];
  const size_t k = rng() % 3;
  const int32_t a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
  const PhasePair p = m.pair(OMesh::FaceHandle(f));
  switch (rng() % 4) {
  case 0: // every face at a, out and in again
    e.removed_faces = m.faces_at(std::array{a});
    for (int32_t g : e.removed_faces) e.added.push_back(m.triangles()[size_t(g)]), e.added_pairs.push_back(m.pair(OMesh::FaceHandle(g)));
    return rewriting(e, rewrite ? e.removed_faces.size() : 0);
  case 1: { // flip a-b inside its patch: (a, b, c) and (b, a, d) become (a, d, c) and (d, b, c)
    const auto on = faces_on(m, a, b);
    if (on.size() != 2 || m.pair(OMesh::FaceHandle(on[0])) != m.pair(OMesh::FaceHandle(on[1]))) return {};
    const int32_t g = on[0] == f ? on[1] : on[0];
    const auto& other = m.triangles()[size_t(g)];
    const int32_t d = other[0] + other[1] + other[2] - a - b;
    if (d == c || m.adjacent(c, d)) return {};
    e.removed_faces = {f, g};
    e.added = {{a, d, c}, {d, b, c}};
    e.added_pairs = {p, p};
    return rewriting(e, rewrite ? 2 : 0);
  }
  case 2: { // a new node halfway along a-b, in every face on it (surface or junction)
    const auto mid = int32_t(m.num_nodes());
    e.new_nodes = {(m.positions()[size_t(a)] + m.positions()[size_t(b)]) / 2};
    e.removed_faces = faces_on(m, a, b);
    std::vector<std::array<int32_t, 3>> second_halves;
    for (int32_t g : e.removed_faces) {
      auto t = m.triangles()[size_t(g)];
      while (!((t[0] == a && t[1] == b) || (t[0] == b && t[1] == a))) std::rotate(t.begin(), t.begin() + 1, t.end());
      e.added.push_back({t[0], mid, t[2]});
      second_halves.push_back({mid, t[1], t[2]});
    }
    e.added.insert(e.added.end(), second_halves.begin(), second_halves.end());
    for (int half = 0; half < 2; ++half)
      for (int32_t g : e.removed_faces) e.added_pairs.push_back(m.pair(OMesh::FaceHandle(g)));
    return rewriting(e, rewrite ? e.removed_faces.size() : 0);
  }
  default: { // b merged into a: b's faces renamed, those on a-b gone, b gone
    std::vector<int32_t> renamed, dropped;
    for (int32_t g : m.faces_at(std::array{b})) {
      auto t = m.triangles()[size_t(g)];
      if (std::count(t.begin(), t.end(), a)) {
        dropped.push_back(g);
        continue;
      }
      renamed.push_back(g);
      std::replace(t.begin(), t.end(), b, a);
      e.added.push_back(t);
      e.added_pairs.push_back(m.pair(OMesh::FaceHandle(g)));
    }
    e.removed_faces = renamed;
    e.removed_faces.insert(e.removed_faces.end(), dropped.begin(), dropped.end());
    e.removed_nodes = {b};
    return rewriting(e, rewrite ? renamed.size() : 0);
  }
  }
}

struct Outcome {
  size_t made = 0, declined = 0, invalid = 0;
};

/// Random edits in sequence on `start`, each compared with from_node_mesh().
Outcome run_edits(const NodeMesh& start, int edits, uint32_t seed) {
  Outcome out;
  std::mt19937 rng(seed);
  InterfaceMesh m = InterfaceMesh::from_node_mesh(start);
  (void)m.qualities(); // kept current through the edits
  for (int i = 0; i < edits; ++i) {
    const auto edit = random_edit(m, rng);
    if (!edit) continue;
    const NodeMesh expected_nodes = edited(m.to_node_mesh(), *edit);
    if (!validate(expected_nodes).ok()) {
      ++out.invalid; // a merge that folds or duplicates: not an edit a pass would make
      continue;
    }
    const InterfaceMesh expected = InterfaceMesh::from_node_mesh(expected_nodes);
    InterfaceMesh trial = m;
    EditMoves moves;
    if (!trial.edit_in_place(*edit, moves)) {
      ++out.declined;
      EXPECT_EQ(shape_of(trial), shape_of(m)) << "a declined edit changed the mesh";
      continue;
    }
    ++out.made;
    SCOPED_TRACE(testing::Message() << "edit " << i << " of seed " << seed);
    for (size_t r = 0; r < edit->rewritten_faces.size(); ++r) { // in its old slot, or where the moves took it
      auto tri = edit->added[r];
      for (int32_t& n : tri) n = position_after(moves.nodes, n);
      const auto f = OMesh::FaceHandle(position_after(moves.faces, edit->rewritten_faces[r]));
      EXPECT_EQ(key_of(trial.face_nodes(f), trial.pair(f)), key_of(tri, edit->added_pairs[r])) << "rewrite " << r;
    }
    expect_consistent(trial);
    EXPECT_TRUE(validate(trial).ok());
    const Shape got = shape_of(trial), want = shape_of(expected);
    EXPECT_EQ(got.triangles, want.triangles);
    EXPECT_EQ(got.copies, want.copies);
    EXPECT_EQ(got.phases, want.phases);
    EXPECT_EQ(got.neighbours, want.neighbours);
    EXPECT_EQ(got.box, want.box);
    EXPECT_EQ(got.points, want.points);
    EXPECT_EQ(got.glued, want.glued);
    if (testing::Test::HasFailure()) return out;
    m = std::move(trial);
  }
  return out;
}

} // namespace

TEST(EditInPlace, matches_a_rebuild_through_random_edits_in_sequence) {
  Outcome total;
  uint32_t seed = 1;
  for (const NodeMesh& start : {two_cubes(3), box_t_junction(4), block_grains(3, 2), four_spheres(12)}) {
    const Outcome o = run_edits(start, 300, seed++);
    total.made += o.made, total.declined += o.declined, total.invalid += o.invalid;
    if (testing::Test::HasFailure()) return;
  }
  RecordProperty("made", int(total.made));
  RecordProperty("declined", int(total.declined));
  std::printf("%zu edits made in place, %zu declined, %zu not valid meshes\n", total.made, total.declined,
              total.invalid);
  EXPECT_GT(total.made, 600u); // most edits are made, not declined
}

namespace {

/// Three triangles of one pair in a fan around node 0 (nodes 1 to 4 round it),
/// without the middle one when `gap`: node 0 then has two copies in one patch.
NodeMesh fan(bool gap) {
  NodeMesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0), Vec3(-1, 0, 0)};
  m.triangles = {{0, 1, 2}, {0, 3, 4}};
  if (!gap) m.triangles.push_back({0, 2, 3});
  m.pairs.assign(m.triangles.size(), PhasePair{0, 1});
  return m;
}

} // namespace

TEST(EditInPlace, declines_to_join_two_fans_of_a_node_or_split_one) {
  // Joining the two copies of node 0, or splitting its one, would take a
  // vertex merge or split OpenMesh cannot make in place: declined, untouched.
  InterfaceMesh two = InterfaceMesh::from_node_mesh(fan(true));
  ASSERT_EQ(two.copies(0).size(), 2u);
  const Shape before = shape_of(two);
  EditMoves moves;
  EXPECT_FALSE(two.edit_in_place(LocalEdit{.added = {{0, 2, 3}}, .added_pairs = {{0, 1}}}, moves));
  EXPECT_EQ(shape_of(two), before);

  InterfaceMesh one = InterfaceMesh::from_node_mesh(fan(false));
  ASSERT_EQ(one.copies(0).size(), 1u);
  EXPECT_FALSE(one.edit_in_place(LocalEdit{.removed_faces = {2}}, moves));
  EXPECT_EQ(shape_of(one), shape_of(InterfaceMesh::from_node_mesh(fan(false))));
}

TEST(EditInPlace, refuses_to_remove_a_node_that_keeps_a_triangle_before_changing_anything) {
  InterfaceMesh m = InterfaceMesh::from_node_mesh(two_cubes(3));
  const auto& face = m.triangles()[0];
  // The node farthest from face 0: the edit, which removes face 0, neither
  // touches it nor sees its triangles.
  int32_t far = 0;
  for (size_t n = 0; n < m.num_nodes(); ++n)
    if ((m.positions()[n] - m.positions()[size_t(face[0])]).norm() >
        (m.positions()[size_t(far)] - m.positions()[size_t(face[0])]).norm())
      far = int32_t(n);
  const Shape before = shape_of(m);
  EditMoves moves;
  for (int32_t node : {face[1], far, int32_t(m.num_nodes())}) { // kept triangles seen, unseen; no node
    EXPECT_THROW(m.edit_in_place(LocalEdit{.removed_faces = {0}, .removed_nodes = {node}}, moves), std::invalid_argument)
        << node;
    EXPECT_EQ(shape_of(m), before) << node;
  }
}
