// make_merges() (improve/merges_made.hpp): merges made in place in one process
// and rebuilt in a distributed run must give one mesh in one order, the order
// swap-removal gives, since the passes break ties by node and triangle ids.
#include "fixtures.hpp"

#include "improve/collapse_peers.hpp"
#include "improve/merges_made.hpp"
#include "improve/mesh_part.hpp"
#include "improve/node_merge.hpp"

#include "voronoimesh/check/validate.hpp"
#include "voronoimesh/improve/collapse.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>

using namespace vm;
using namespace vm::test;

namespace {

/// A distributed run of one rank: every gather returns this rank's own.
class OneRank : public detail::CollapsePeers {
public:
  bool answers_for(int32_t) override { return true; }
  std::vector<detail::SliverCollapse> all(const std::vector<detail::SliverCollapse>& mine) override { return mine; }
  std::vector<int64_t> all(const std::vector<int64_t>& mine) override {
    std::vector<int64_t> ids = mine;
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    return ids;
  }
  bool any(bool mine) override { return mine; }
};

/// Points, triangles and pairs in order.
void expect_same_in_order(const InterfaceMesh& a, const InterfaceMesh& b) {
  const NodeMesh x = a.to_node_mesh(), y = b.to_node_mesh();
  ASSERT_EQ(x.points, y.points);
  ASSERT_EQ(x.triangles, y.triangles);
  ASSERT_EQ(x.pairs, y.pairs);
  EXPECT_EQ(a.box_faces(), b.box_faces());
  EXPECT_EQ(a.phases(), b.phases());
}

} // namespace

TEST(SwapRemoval, renames_as_removing_from_the_end_of_an_array_does) {
  std::mt19937 rng(7);
  for (int round = 0; round < 2000; ++round) {
    // Ids with gaps, ascending with the position; some removed.
    const size_t n = 1 + rng() % 30;
    std::vector<int64_t> ids;
    for (int64_t id = 0; ids.size() < n; id += 1 + int64_t(rng() % 3)) ids.push_back(id);
    std::vector<int32_t> removed_at;
    for (size_t i = 0; i < n; ++i)
      if (rng() % 3 == 0) removed_at.push_back(int32_t(i));
    // The array way: each removed slot, highest first, takes the last element.
    std::vector<int32_t> element_at(n);
    std::iota(element_at.begin(), element_at.end(), 0);
    for (auto it = removed_at.rbegin(); it != removed_at.rend(); ++it) {
      element_at[size_t(*it)] = element_at.back();
      element_at.pop_back();
    }
    std::map<int64_t, int64_t> expected; // old id -> new id, of those that moved
    for (size_t slot = 0; slot < element_at.size(); ++slot)
      if (size_t(element_at[slot]) != slot) expected[ids[size_t(element_at[slot])]] = ids[slot];
    // The ids way, given the live ids as two ranks would: each its k highest.
    std::vector<int64_t> gone, live;
    for (int32_t i : removed_at) gone.push_back(ids[size_t(i)]);
    for (size_t i = 0; i < n; ++i)
      if (!std::binary_search(removed_at.begin(), removed_at.end(), int32_t(i))) live.push_back(ids[i]);
    std::vector<int64_t> top;
    for (int rank = 0; rank < 2; ++rank) {
      std::vector<int64_t> mine;
      for (size_t i = 0; i < live.size(); ++i)
        if (i % 2 == size_t(rank) || rng() % 4 == 0) mine.push_back(live[i]); // ranks share some
      const size_t k = std::min(gone.size(), mine.size());
      top.insert(top.end(), mine.end() - ptrdiff_t(k), mine.end());
    }
    const auto renames = detail::swap_removal_renames(gone, top);
    const std::map<int64_t, int64_t> got(renames.begin(), renames.end());
    ASSERT_EQ(got, expected) << "round " << round;
  }
}

// The sparse form of an edit's moves (moved_by()) against the whole map that
// replaying them gives, through random swap-removals.
TEST(SlotMoves, moved_by_names_every_element_replaying_puts_elsewhere) {
  std::mt19937 rng(13);
  for (int round = 0; round < 500; ++round) {
    const auto n = int32_t(1 + rng() % 40);
    std::vector<SlotMove> moves;
    for (int32_t size = n; size > 0 && rng() % 5 != 0; --size) {
      const auto at = int32_t(rng() % uint32_t(size)); // remove what is at `at`: the last moves in
      moves.push_back({size - 1, at});
    }
    const std::vector<int32_t> old = replayed(size_t(n), moves);
    std::vector<std::pair<int32_t, int32_t>> expected;
    for (size_t now = 0; now < old.size(); ++now)
      if (old[now] != int32_t(now)) expected.emplace_back(old[now], int32_t(now));
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(moved_by(moves), expected) << "round " << round;
  }
}

// Batches of random merges (b into a neighbour on all of b's constraints, no
// two sharing a ring) in sequence on a 30-cell Voronoi mesh: each made in place
// from the part of the mesh at the merges and rebuilt from the whole mesh as a
// distributed run rebuilds gives the same mesh in the same order, a valid one,
// with the same maps of what was kept; and the part's merges put back into
// the whole mesh are the whole mesh's merges.
TEST(MergesMade, in_place_from_a_part_and_rebuilt_give_one_mesh_in_one_order) {
  InterfaceMesh in_place = initial_mesh(example_scene("voronoi30.json", 20));
  InterfaceMesh rebuilt = in_place;
  std::mt19937 rng(11);
  OneRank peers;
  size_t merges = 0;
  for (int batch = 0; batch < 12; ++batch) {
    const detail::MeshPart whole = detail::whole_part(rebuilt);
    const NodeMesh& before = whole.mesh;
    std::vector<int32_t> into(before.num_nodes(), -1), seeds;
    std::vector<uint8_t> claimed(before.num_nodes(), 0);
    for (int draw = 0; draw < 40; ++draw) {
      const auto b = int32_t(rng() % before.num_nodes());
      const auto ring = in_place.neighbours(b);
      if (ring.empty()) continue;
      const int32_t a = ring[rng() % ring.size()];
      if (!in_place.constraints_within(b, a) || claimed[size_t(a)] || claimed[size_t(b)] ||
          std::any_of(ring.begin(), ring.end(), [&](int32_t w) { return claimed[size_t(w)]; }) ||
          std::any_of(in_place.neighbours(a).begin(), in_place.neighbours(a).end(),
                      [&](int32_t w) { return claimed[size_t(w)]; }))
        continue;
      into[size_t(b)] = a;
      for (int32_t n : {a, b}) claimed[size_t(n)] = 1, seeds.push_back(n);
      for (int32_t w : ring) claimed[size_t(w)] = 1, seeds.push_back(w);
      for (int32_t w : in_place.neighbours(a)) claimed[size_t(w)] = 1, seeds.push_back(w);
    }
    NodeMesh merged;
    std::vector<int32_t> turned, kept_triangles;
    detail::merge_nodes(before, into, merged, turned, kept_triangles);
    NodeMesh compact = merged;
    std::vector<int32_t> kept_nodes;
    detail::drop_unused_nodes(compact, kept_nodes);
    if (!validate(compact).ok()) continue; // not a mesh to make (turned triangles do not matter here)
    merges += size_t(std::count_if(into.begin(), into.end(), [](int32_t a) { return a >= 0; }));
    // The same merges on the part at the claimed nodes.
    const detail::MeshPart part = detail::part_at(in_place, seeds);
    ASSERT_LT(part.mesh.num_triangles(), before.num_triangles() / 2);
    std::vector<int32_t> part_into(part.mesh.num_nodes(), -1), part_turned, part_kept;
    for (size_t n = 0; n < part.nodes.size(); ++n)
      if (const int32_t a = into[size_t(part.nodes[n])]; a >= 0) part_into[n] = part.part_node(a);
    NodeMesh part_merged, put_back;
    detail::merge_nodes(part.mesh, part_into, part_merged, part_turned, part_kept);
    std::vector<int32_t> put_back_kept;
    detail::put_back(part, part_merged, part_kept, before, put_back, put_back_kept);
    EXPECT_EQ(put_back.points, merged.points);
    EXPECT_EQ(put_back.triangles, merged.triangles);
    EXPECT_EQ(put_back.pairs, merged.pairs);
    EXPECT_EQ(put_back_kept, kept_triangles);
    const auto node_ids = identity<int64_t>(before.num_nodes());
    const auto triangle_ids = identity<int64_t>(before.num_triangles());
    detail::CollapseKept kept_in_place, kept_rebuilt;
    detail::make_merges(in_place, part, part_merged, part_kept, nullptr, node_ids, triangle_ids, kept_in_place);
    detail::make_merges(rebuilt, whole, merged, kept_triangles, &peers, node_ids, triangle_ids, kept_rebuilt);
    expect_same_in_order(in_place, rebuilt);
    ASSERT_TRUE(kept_in_place.in_place); // the edit declined no batch here
    EXPECT_EQ(replayed(before.num_nodes(), kept_in_place.moves.nodes), kept_rebuilt.nodes);
    EXPECT_EQ(replayed(before.num_triangles(), kept_in_place.moves.faces), kept_rebuilt.triangles);
    EXPECT_EQ(kept_rebuilt.node_ids, identity<int64_t>(rebuilt.num_nodes())); // one rank: ids are indices, no gaps
    EXPECT_EQ(kept_rebuilt.triangle_ids, identity<int64_t>(rebuilt.num_triangles()));
    EXPECT_TRUE(validate(in_place.to_node_mesh()).ok()) << "batch " << batch;
    if (HasFailure()) return;
  }
  EXPECT_GT(merges, 100u); // the test made enough merges to mean something
}

// The junction-sliver collapse itself, in one process (in place) and as one
// rank of a distributed run (rebuilt): the same collapses, the same mesh in the
// same order.
TEST(MergesMade, a_collapse_call_in_one_process_and_on_one_rank_agree) {
  InterfaceMesh one = initial_mesh(example_scene("voronoi30.json", 24));
  InterfaceMesh rank = one;
  CollapseParams params;
  params.below_quality = 0.3;
  params.guard_crossings = false;
  OneRank peers;
  size_t made = 0;
  for (int call = 0; call < 3; ++call) {
    const auto node_ids = identity<int64_t>(rank.num_nodes());
    const auto triangle_ids = identity<int64_t>(rank.num_triangles());
    detail::CollapseKept kept;
    const size_t in_one = collapse_junction_slivers(one, params);
    const size_t on_rank = detail::collapse_junction_slivers(rank, params, peers, node_ids, triangle_ids, kept);
    ASSERT_EQ(in_one, on_rank) << "call " << call;
    made += in_one;
    expect_same_in_order(one, rank);
  }
  EXPECT_GT(made, 10u);
}
