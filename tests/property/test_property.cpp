// The quick tier of the property tests: a few hundred random scenes of every
// kind (random_scenes.hpp), each created and improved for a few iterations with
// every check of check_case(). The long tier runs the same cases by the
// hundred thousand: scripts/property_tests.sh.

#include "case_checks.hpp"

#include <gtest/gtest.h>

#include <array>

namespace {

using namespace vm::test;

constexpr uint64_t kSeed = 1;
constexpr int kShards = 8;
constexpr int kCasesPerShard = 36; // 288 cases: each kind 36 times
/// Every this many cases are also meshed on 1 and 2 threads and compared.
constexpr uint64_t kThreadsEvery = 6;

/// Triangles against their pair's direction after the last iteration, per shard,
/// over its closed-form cases (CaseResult::against_field), as of this commit: a
/// statistic (coarse grids and junctions closer than a cell have them
/// legitimately) that may only shrink. Cases and improvement are deterministic.
/// Since create quantizes over the range of the lattice's nodes alone (not every
/// grid node's), some cases mesh differently: 4792 -> 4802 in all, shards 0, 4, 7
/// up by 3, 16, 2, shards 1, 2, 3, 6 down by 3, 1, 5, 2. Since corner triangles at
/// quadruple points are no ears (they flipped back and forth), 4802 -> 4791:
/// shards 0, 4, 5 down by 12, 9, 3, shards 1, 2, 3, 7 up by 3, 2, 5, 3. Since
/// collapses below q 0.15 (not 0.05) leave better triangles and merge close
/// corners, 4791 -> 4767: shard 6 up by 3, the others down by 0 to 8. Since
/// junction nodes huddled round a collapse's target merge with it, 4767 -> 4756:
/// shard 5 up by 1, the others down by 1 to 3. Since no node may leave the
/// domain box (clamp), 4756 -> 4759: shards 1 and 3 up by 1 and 2, nodes near a
/// box face being held inside it. Since a sliver no edge of which may collapse
/// can lose a curve node beside it, 4759 -> 4757: shards 3, 4, 6 up by 5, 5, 1,
/// shards 0, 1 down by 11, 2. Since the crossing guard puts back only the
/// farthest mover of a crossing pair in each round, 4757 -> 4810: shards 0, 1,
/// 3, 5, 6 up by 14, 7, 11, 7, 22, shards 2, 4, 7 down by 2, 4, 2; nearly all
/// in thin slabs at grids of 5 to 12, where nodes that now keep their moves
/// fold the slab's sheets. Since eq. 4's steps are cut to the node's mean
/// edge length, 4810 -> 4831: shards 2, 3, 4 up by 2, 22, 2, shard 0 down by 5
/// (nodes far off their interface take more iterations to reach it; after 20
/// iterations the same cases have 4807 against 4756 before both changes).
/// Since pairs of phases that part slower than 0.2 per unit length snap only
/// within a cell (create/node_values.hpp), 4831 -> 4834: shard 3 up by 3.
/// Since junction-sliver collapses that fold a surface are refused, 4834 ->
/// 4864: shards 0, 1, 2, 4, 6, 7 up by 8, 4, 6, 11, 1, 1, shard 3 down by 1;
/// the slivers kept stand against their pair in thin slabs (seed 1, case 165:
/// 386 -> 396), while 187 fewer surface edges fold (kFoldsAtMost). Since the
/// flip pass undoes only the flips that crossed (and the later ones sharing a
/// node with them) and flips again around them, instead of undoing every flip
/// and starting over, 4864 -> 4788: shards 0, 1 up by 1, 1, shards 2-6 down by
/// 1, 12, 28, 3, 34. Since the nodes where an interface meets a box face of a
/// closed mesh are smoothed along their curve (improve/smooth.hpp), bounds
/// 4788 -> 4780: shard 7 up by 1, shards 1, 2, 4, 5 down by 1, 1, 4, 3.
constexpr std::array<size_t, kShards> kAgainstAtMost = {668, 875, 104, 1333, 766, 192, 546, 296};

/// Surface edges that fold after the last iteration, per shard, over all its
/// cases (CaseResult::folds, MeshStats::folds): like the triangles against their
/// pair, a statistic that may only shrink (thin slabs and faces thinner than a
/// cell at coarse grids fold legitimately). Since slow pairs snap only within a
/// cell, 5091 -> 5140: 43 of the 49 in one case of random grid values (seed 1,
/// case 274: 2 -> 45; a grid of 4x14x10 over a box 1,000 wide, whose values, of
/// order 1, part at about 0.01 per unit length: snapping by value, within 0.5 h or
/// about 50, tied every pair at every node),
/// shards 0, 5, 7 up by 7, 2, 44, shards 1, 4 down by 3, 1. Since
/// junction-sliver collapses that fold a surface are refused (and a call makes
/// up to an eighth as many collapses as it has candidates), 5140 -> 4953, every
/// shard down: by 56, 14, 1, 15, 53, 22, 1, 25. Since the flip pass undoes only
/// the flips that crossed and their dependents (above), 4953 -> 4802: shards 0,
/// 1 up by 7, 6, shards 2-7 down by 70, 20, 17, 33, 6, 18. Since create snaps
/// closed triple curves far smaller than a cell away (create/tiny_loops.hpp),
/// 4802 -> 4804: shard 3 up by 2 (seed 1, case 108, a label field at grid 10:
/// 29 -> 32, 50 more triangles; case 130 152 -> 151). Since the nodes of closed
/// triple curves of three nodes spread round their loop (improve/smooth.hpp),
/// 4804 -> 4798: shards 1, 3 up by 1 (case 43, tied values at grid 10:
/// 22 -> 23; case 130: 151 -> 152), shards 0, 4, 5, 6 down by 1, 3, 1, 1, and
/// the bounds of shards 4 and 7 without the 1 they had to spare (the triangles
/// against their pair unchanged in every case). Since those loops close by
/// raising their third phase alone where they have one window, instead of
/// tying every phase near it (create/tiny_loops.hpp), 4798 -> 4795: shard 3
/// down by 4 (case 108, labels at grid 10: 32 -> 29; case 130: 152 -> 151),
/// shard 4 up by 1 (random grid values at grid 12, case 146: 228 -> 229), the
/// triangles against their pair unchanged in every case. Since the nodes where
/// an interface meets a box face of a closed mesh are smoothed along their
/// curve, bounds 4795 -> 4834: shard 2 up by 39 (case 91, tied values at grid
/// 12 with --close, every phase flat: 176 -> 216; case 83 6 -> 4), shards 0, 5, 6
/// up by 3, 5, 6, shards 1, 3, 4, 7 down by 6, 1, 5, 2.
constexpr std::array<size_t, kShards> kFoldsAtMost = {906, 1024, 252, 664, 691, 505, 345, 447};

/// What checking a run of cases found.
struct Tally {
  int failed = 0;
  size_t against = 0; // triangles against their pair's direction, over the closed-form cases
  size_t folds = 0;   // surface edges that fold, over all the cases
};

/// Checks cases `index(0)` .. `index(count - 1)` of kSeed (read voxel-faithful
/// if asked) with `o`, on 1 and 2 threads too for every kThreadsEvery-th, and
/// reports the first three that fail with the property_runner arguments
/// (`flags` after the case) that reproduce them.
template <class Index>
Tally check_cases(int count, Index index, CheckOptions o, bool voxel_faithful, const std::string& flags) {
  Tally tally;
  for (int i = 0; i < count; ++i) {
    const uint64_t id = index(i);
    const RandomCase c = random_case(kSeed, id, voxel_faithful);
    EXPECT_EQ(c.voxel_faithful, voxel_faithful) << "case " << id;
    o.compare_threads = i % kThreadsEvery == 0;
    const CaseResult r = check_case(c, o);
    tally.against += r.against_field;
    tally.folds += r.folds;
    if (!r.ok() && ++tally.failed <= 3)
      ADD_FAILURE() << c.description() << "\n  " << r.failures.front() << "\n  reproduce: property_runner --seed "
                    << kSeed << " --case " << id << flags << " --verbose";
  }
  return tally;
}

class PropertyQuickTier : public testing::TestWithParam<int> {};

// Each shard is its own test so that ctest spreads them over the cores.
TEST_P(PropertyQuickTier, random_cases_stay_valid_through_create_and_improve) {
  const Tally t = check_cases(kCasesPerShard, [](int i) { return uint64_t(GetParam() * kCasesPerShard + i); },
                              CheckOptions{}, false, "");
  EXPECT_EQ(t.failed, 0);
  EXPECT_LE(t.against, kAgainstAtMost[size_t(GetParam())]) << "more triangles against their pair's direction";
  EXPECT_LE(t.folds, kFoldsAtMost[size_t(GetParam())]) << "more surface edges folding";
}

INSTANTIATE_TEST_SUITE_P(Shards, PropertyQuickTier, testing::Range(0, kShards));

// The label cases again, read voxel-faithful: kept points at voxel centres,
// which create's snapping, the remesh pass's merges and the guard must keep in
// their phase, on every lattice and snap the options draw. The long tier:
// VOXEL_FAITHFUL=1 scripts/property_tests.sh.
TEST(PropertyQuickTier, label_cases_read_voxel_faithful_stay_valid) {
  const Tally t = check_cases(
      24, [](int i) { return uint64_t(i) * kSceneKinds + uint64_t(SceneKind::labels); }, CheckOptions{}, true,
      " --voxel-faithful");
  EXPECT_EQ(t.failed, 0);
}

// The cases meshed whole as `voronoimesh mesh` meshes them: their default
// pipeline (the remesh pass, the flip pass's collapses, polish and floor, on
// their schedules), checked after every iteration, which the shards above (the
// paper's passes) never run. The long tier: WHOLE=1 ITERATIONS=8
// scripts/property_tests.sh.
TEST(PropertyQuickTier, cases_meshed_whole_with_the_default_pipeline_stay_valid) {
  CheckOptions o;
  o.iterations = 8; // polish from the sixth
  o.whole = true;
  const Tally t = check_cases(3 * kSceneKinds, [](int i) { return uint64_t(i); }, o, false, " --whole --iterations 8");
  EXPECT_EQ(t.failed, 0);
}

/// Cases the long tier found failing, as {seed, case}, each fixed since: they
/// must keep passing. Seed 1, cases 5412 and 5570: a triangle 10^-6 of the
/// mesh size turned by 93 degrees in the moving passes, clamping's planes
/// being round-off at that size; the crossing guard now undoes such moves.
/// Cases 9020, 24525, 24940, 26940 and 40138: snapped label fields and thin slabs whose
/// pinches moved on with every local repair; create now repairs every node
/// after kLocalRepairRounds. Cases 10559 and 24719: planes through lattice
/// nodes, where an ear flipped into a zero-area triangle; ears now flip only
/// into triangles validate() accepts. Case 33466: moving passes shrank a
/// triangle 10^-4 across to area 9e-13 x L^2; the guard undoes that too.
/// Seed 6, case 2004 (a 3-label volume on cube6): the crossing check's search
/// near a few flagged triangles, far smaller than the rest, counted a box's grid
/// cells in int64 and the count wrapped round: it never ended. Counted in
/// doubles now (check/intersections.cpp).
constexpr std::array<std::array<uint64_t, 2>, 11> kLongTierRegressions = {
    {{1, 5412}, {1, 5570}, {1, 9020}, {1, 10559}, {1, 24525}, {1, 24719}, {1, 24940}, {1, 26940}, {1, 33466},
     {1, 40138}, {6, 2004}}};

TEST(PropertyLongTier, cases_it_found_failing_pass) {
  for (const auto& [seed, index] : kLongTierRegressions) {
    const RandomCase c = random_case(seed, index);
    const CaseResult r = check_case(c, CheckOptions{});
    EXPECT_TRUE(r.ok()) << c.description() << "\n  " << (r.ok() ? "" : r.failures.front());
  }
}

// Found by `property_runner --remesh remesh:size=1:merge_corners=0.1` (seed 11):
// on a grid-values scene's flat interfaces, splitting edges after collapses put
// a rounded midpoint a hair off a coplanar neighbour's plane, and 4 triangle
// pairs crossed; splits are now checked and undone where they cross.
TEST(PropertyRemesh, a_case_where_splits_crossed_passes) {
  const RandomCase c = random_case(11, 290);
  CheckOptions o;
  o.remesh = "remesh:size=1:merge_corners=0.1";
  const CaseResult r = check_case(c, o);
  EXPECT_TRUE(r.ok()) << c.description() << "\n  " << (r.ok() ? "" : r.failures.front());
}

// The generator is a pure function of (seed, case): the long tier's failing
// case ids reproduce anywhere.
TEST(PropertyGenerator, cases_are_reproducible_and_cover_every_kind) {
  for (uint64_t index = 0; index < uint64_t(2 * kSceneKinds); ++index) {
    const RandomCase a = random_case(7, index), b = random_case(7, index);
    EXPECT_EQ(a.description(), b.description());
    EXPECT_EQ(a.scene_json, b.scene_json);
    EXPECT_EQ(int(a.kind), int(index % kSceneKinds));
    EXPECT_EQ(a.closed_form, !a.scene_json.empty());
  }
  EXPECT_NE(random_case(7, 0).description(), random_case(8, 0).description());
}

} // namespace
