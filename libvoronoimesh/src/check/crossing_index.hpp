#pragma once
/// @file check/crossing_index.hpp
/// Repeated exact crossing checks on a mesh that changes a little at a time.
///
/// find_self_intersections() builds its grid of triangle boxes anew on every
/// call and sorts it: right for one check, but the improvement loop checks the
/// same mesh several times an iteration (each commit of moves, each round of
/// undoing them, each batch of flips) while its nodes move by a fraction of an
/// edge. CrossingIndex keeps, as molecular dynamics keeps Verlet lists, every
/// triangle's box grown by a skin (its "filing box") and, for each triangle,
/// the triangles whose filing boxes meet its own and that share no fan with it
/// (pairs in a fan, 70% of those on a smooth surface, are found through the
/// fan itself, and most are decided by its certificate). While every
/// triangle's box stays inside its filing box, two triangles whose boxes
/// overlap are in one fan or on each other's lists: a check tests the fans and
/// lists of the triangles that changed and searches nothing. A triangle that
/// leaves its filing box is filed again, and the lists it is on are mended
/// through a hash of grid cells; one that changes nodes (a flip) but still
/// lies in its filing box keeps it, and its list is mended from its old list
/// and its old fans. A check after a few flips costs little more than those
/// few triangles.
/// Where most triangles change between calls (the first iterations), mending
/// the index would cost more than checking anew, so those calls are one-off
/// checks: no index is built until the mesh has settled (a sixth or less
/// changed, twice in a row), and one is dropped only when more than half of
/// the triangles changed.
///
/// The answers are find_self_intersections()'s (the same exact pair test,
/// check/triangle_pair.hpp, and certificates made of the same predicates,
/// check/embedded_fans.hpp), so the guard keeps its guarantees; they do not
/// depend on the thread count.

#include "check/box_pairs.hpp"
#include "check/embedded_fans.hpp"
#include "check/triangle_pair.hpp"
#include "core/unset_vector.hpp"
#include "voronoimesh/core/pooled_lists.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace vm::detail {

class CrossingIndex {
public:
  /// The pairs {t, s}, t < s, of triangles that intersect improperly and of
  /// which at least one is flagged in `involved` (one flag per triangle; empty:
  /// all), sorted. The mesh is given whole each time (node ids into `points`);
  /// the index brings itself up to date with it first, so any change since the
  /// last call (moves, flips, a renumbered mesh) is seen. Points must be finite.
  ///
  /// With `corner_fans` (a fan id per corner of each triangle, as
  /// InterfaceMesh::triangle_copies(): triangles with the same id at a common
  /// corner lie in one fan of one patch), pairs in a fan certified embedded are
  /// not tested one by one. On a smooth surface that is almost every pair
  /// whose boxes overlap.
  std::vector<BoxPair> crossings(std::span<const Vec3> points, std::span<const Triangle> triangles,
                                 std::span<const uint8_t> involved = {}, std::span<const Triangle> corner_fans = {});

  /// crossings() where the caller knows what changed since the last call on
  /// this mesh: only the triangles flagged in `involved` moved or have other
  /// nodes (no renumbering, no other fan ids), as between the rounds of the
  /// guard's commit, which put some nodes back, and of the flip pass's repairs.
  /// The index is then brought up to date from those triangles alone and only
  /// their pairs are searched: the call costs time in the triangles it
  /// involves, not in the mesh. Without an index kept, or with most triangles
  /// involved, it is crossings(). The answer is crossings()'s.
  std::vector<BoxPair> crossings_after_changes(std::span<const Vec3> points, std::span<const Triangle> triangles,
                                               std::span<const uint8_t> involved,
                                               std::span<const Triangle> corner_fans = {});

  /// Carries the index over to a mesh rebuilt from this one (a collapse
  /// renumbers triangles and nodes; a remesh also makes new ones): `old_triangle[t]`
  /// and `old_node[n]` are the old ids of new triangle t and node n, each once
  /// in any order, or -1, which marks a new one; `corner_fans` are the new mesh's.
  /// Triangles that lost a node and new ones are filed at the next call;
  /// the others keep their filing, so no rebuild is needed.
  void renumber(std::span<const int32_t> old_triangle, std::span<const int32_t> old_node,
                std::span<const Triangle> corner_fans);

  /// Carries the index over an edit in place that removed triangles and moved
  /// others into their indices (swap-removal; InterfaceMesh::edit_in_place()),
  /// and may have given some other nodes or fans: `removed` are the old ids of
  /// the triangles that went, `moved` (old id, new id) those that moved
  /// (moved_by()). Costs the edit, not the mesh. Triangles with other nodes or
  /// fans (the edit's, and those at nodes and fans that moved) are filed again
  /// at the next call, as after renumber().
  void renumber_after_removal(std::span<const int32_t> removed, std::span<const std::pair<int32_t, int32_t>> moved);

  /// Brings the index up to date with the mesh, as crossings() does first,
  /// where it keeps one and few triangles changed: then true, and
  /// crossings_with() may be asked about edits to this mesh. False where
  /// crossings() would check the mesh anew (the index is left as it was).
  bool refresh(std::span<const Vec3> points, std::span<const Triangle> triangles,
               std::span<const Triangle> corner_fans);

  /// A triangle of a trial of edits: its nodes (ids of the mesh's nodes, so
  /// that what it shares with a mesh triangle is known) and where its corners
  /// are in the trial, which may differ from the mesh's at nodes the trial moves.
  struct TrialTriangle {
    Triangle nodes;
    std::array<Vec3, 3> corners;
  };
  /// Crossings of a trial of edits (improve/node_merge.hpp) with the mesh the
  /// last refresh() saw (`points` and `triangles` as it saw them): `extra` are
  /// the trial's triangles at the edits, `left_out` the mesh's triangles they
  /// replace (ascending; every mesh triangle at a node the trial moves). Each
  /// extra triangle is tested, exactly, against every mesh triangle not left
  /// out whose box overlaps its own, and against the other extra ones: the
  /// pairs find_self_intersections() would report on the trial with the extra
  /// triangles involved, in the time of a search around them, and without a
  /// copy of the trial's whole mesh. Pairs are {extra index, mesh triangle}
  /// and {extra index, extra index}.
  struct TrialCrossings {
    std::vector<BoxPair> with_mesh, among_extra;
  };
  TrialCrossings crossings_with(std::span<const Vec3> points, std::span<const Triangle> triangles,
                                std::span<const TrialTriangle> extra, std::span<const int32_t> left_out) const;

  /// Whether the last call answered through the index (or, while the mesh
  /// changed too much between calls to keep one, with a one-off check);
  /// triangles it filed again, and whether it built the index anew (for tests
  /// and benchmarks).
  bool indexed() const { return !filed_.empty(); }
  /// The filed slots whose kept list differs from a search through the cells
  /// now (for tests: none, in an index kept right through rebuilds and refiling).
  std::vector<int32_t> lists_unlike_search() const;
  size_t refiled() const { return refiled_; }
  /// The triangles of the mesh the index last saw (renumber()'s old ids must be among them).
  size_t triangles_seen() const { return slot_of_.size(); }
  bool rebuilt() const { return rebuilt_; }

private:
  /// A filing box in single precision, rounded outwards: it holds the box it
  /// was made from, and every test (overlap, containment, cells) reads it, so
  /// the index sees one box whatever the rounding. With it a filing is one
  /// cache line (64 bytes, 104 with a box of doubles): the searches through
  /// the cells read a filing for every triangle they meet (on 1,000 grains,
  /// 5% less time in near() and 66 MB less peak memory).
  struct FilingBox {
    std::array<float, 3> lo, hi;
    static FilingBox around(const Bounds& b);
    Bounds bounds() const {
      return {Vec3(double(lo[0]), double(lo[1]), double(lo[2])), Vec3(double(hi[0]), double(hi[1]), double(hi[2]))};
    }
    bool overlaps(const FilingBox& o) const {
      return lo[0] <= o.hi[0] && lo[1] <= o.hi[1] && lo[2] <= o.hi[2] && o.lo[0] <= hi[0] && o.lo[1] <= hi[1] &&
             o.lo[2] <= hi[2];
    }
    bool overlaps(const Bounds& o) const {
      return double(lo[0]) <= o.hi[0] && double(lo[1]) <= o.hi[1] && double(lo[2]) <= o.hi[2] &&
             o.lo[0] <= double(hi[0]) && o.lo[1] <= double(hi[1]) && o.lo[2] <= double(hi[2]);
    }
    bool contains(const Bounds& inner) const {
      return double(lo[0]) <= inner.lo[0] && double(lo[1]) <= inner.lo[1] && double(lo[2]) <= inner.lo[2] &&
             inner.hi[0] <= double(hi[0]) && inner.hi[1] <= double(hi[1]) && inner.hi[2] <= double(hi[2]);
    }
  };
  /// Where a triangle is filed: its grown box, the grid level it is filed in
  /// and the first cell of the box there, and the nodes and fans it had.
  /// none(), level -1: not filed yet (a triangle renumber() was given as new)
  /// or a free slot, in no cell. Trivial to make (no member initializers), so
  /// that a rebuild's filings (64 MB on 1M triangles) are first touched by
  /// the threads that fill them.
  struct alignas(64) Filing {
    FilingBox box;
    std::array<int32_t, 3> first;
    Triangle nodes, fans;
    int8_t level;
    static Filing none() { return {{{0, 0, 0}, {0, 0, 0}}, {}, {-1, -1, -1}, {-1, -1, -1}, -1}; }
  };
  static_assert(sizeof(Filing) == 64);
  /// A triangle filed in a cell, with the first cell of its filing (a search
  /// takes it in one cell only). Its filing box is read from filed_, and only
  /// in that one cell: keeping a copy here made every entry 64 bytes instead
  /// of 16, a third of the index's memory.
  struct CellEntry {
    int32_t id;
    std::array<int32_t, 3> first;
  };
  /// Whether `fan` (not -1) is among the corner fans `fans`.
  static bool has_fan(const Triangle& fans, int32_t fan) {
    return fan >= 0 && (fan == fans[0] || fan == fans[1] || fan == fans[2]);
  }
  /// a == b, inline (std::array's == calls memcmp: 4% of a steady-state iteration on 1M triangles).
  static bool same(const Triangle& a, const Triangle& b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }
  static bool contains(const Bounds& outer, const Bounds& inner) {
    return (outer.lo.array() <= inner.lo.array()).all() && (inner.hi.array() <= outer.hi.array()).all();
  }
  /// Whether triangles with corner fans `a` and `b` have a fan in common.
  /// Listed pairs had none when listed; should two fans become one without
  /// either triangle filed again, crossings() leaves the pair to the fan.
  static bool share_a_fan(const Triangle& a, const Triangle& b);

  void rebuild(std::span<const Triangle> triangles, std::span<const Triangle> corner_fans);
  void refile(std::span<const int32_t> stale_by_id, std::span<const Triangle> triangles,
              std::span<const Triangle> corner_fans);
  /// The slots a stale triangle that keeps its filing box (refile()) may have
  /// on its list: those on its old list and those in its old fans.
  void kept_box_candidates(int32_t slot, std::vector<int32_t>& out) const;
  /// `triangles` in the Morton order of their boxes' centres (boxes_), ties by id.
  std::vector<int32_t> in_space_order(std::span<const int32_t> triangles) const;
  void set_grid();
  Filing filing_for(const Bounds& box, const Triangle& nodes, const Triangle& fans) const;
  bool fits_grid(const Bounds& b) const;
  int level_of(const Bounds& b) const;
  std::array<int64_t, 3> cell_of(const Vec3& x, int level) const;
  static uint64_t key(int level, int64_t i, int64_t j, int64_t k);
  static std::array<int64_t, 3> key_cell(uint64_t key); ///< the cell of a key, without its level
  static size_t key_level(uint64_t key);                 ///< the level of a key
  template <class F> void for_cells(const Filing& f, F&& f_of_key) const;
  static CellEntry cell_entry(int32_t t, const Filing& f); ///< t's entry in each cell of its filing f
  int64_t find(uint64_t key) const; ///< the cell's list, -1 if it has none
  size_t find_or_add(uint64_t key);
  void grow_table(size_t cells); ///< room in keys_ for `cells` cells at a quarter load at most
  /// The pairs crossings() answers, from an index up to date with the mesh:
  /// searched from every triangle, or only from those of `only` (the involved
  /// ones, all of them; then fewer than half of the triangles).
  std::vector<BoxPair> search(std::span<const Vec3> points, std::span<const Triangle> triangles,
                              std::span<const uint8_t> involved, std::span<const Triangle> corner_fans,
                              std::span<const int32_t> only) const;
  /// find_self_intersections() on the mesh as it is; drops the index.
  std::vector<BoxPair> one_off(std::span<const Vec3> points, std::span<const Triangle> triangles,
                               std::span<const uint8_t> involved);
  /// Appends the list of the triangle in `slot`: the slots whose filing
  /// boxes meet its own and that share no fan with it, sorted.
  void near(int32_t slot, std::vector<int32_t>& out) const;
  /// Calls f(s) once for each filed slot s but `skip` whose filing box meets `box`.
  template <class F> void for_filed_meeting(const Bounds& box, int32_t skip, F&& f) const;
  /// Takes a slot's triangle out of its cells and its neighbours' lists and
  /// marks the slot free (a triangle renumber() was told is gone).
  void free_slot(int32_t slot);
  /// Appends the filed slots whose filing box meets `box`.
  void filed_meeting(const Bounds& box, std::vector<int32_t>& out) const;
  /// Sets boxes_ for the mesh now and returns the triangles whose filing is
  /// stale (in stale_, valid until the next call); `anew` when the index cannot
  /// be mended (none kept, another triangle count, or a stale box beyond the grid).
  /// With `only`, just those triangles can have changed since the last call
  /// (crossings_after_changes()): only their boxes are set and judged.
  const std::vector<int32_t>& find_stale(std::span<const Vec3> points, std::span<const Triangle> triangles,
                                         std::span<const Triangle> corner_fans, bool& anew,
                                         std::span<const int32_t> only = {});

  double cell_size_ = 0;                   ///< level 0; level l has cells 2^l times as large
  std::vector<double> inverse_cell_size_;  ///< by level
  Vec3 origin_ = Vec3::Zero();
  // The index keeps each triangle in a slot, its id in filed_, cells_ and
  // near_ for as long as the triangle lives: a collapse or a remesh renumbers
  // the mesh's triangles, and only the slot maps follow (mapping every
  // list entry cost 63 ms per collapse on 493k triangles, grains100).
  std::vector<int32_t> slot_of_;     ///< by triangle
  std::vector<int32_t> triangle_of_; ///< by slot; -1 for a free one
  UnsetVector<Filing> filed_;        ///< by slot
  // Arrays of every call, kept so that their memory is reused (fresh memory
  // is first touched one page at a time) and, where they grow, left unset for
  // the parallel loops that fill them.
  UnsetVector<Bounds> boxes_;          ///< each triangle's box now
  std::vector<int32_t> stale_;         ///< find_stale()'s answer
  std::vector<int32_t> stale_index_;   ///< by slot: its place among refile()'s triangles; -1 between calls
  std::vector<int32_t> level_count_;   ///< triangles filed in each level
  std::vector<uint64_t> keys_;         ///< open addressing, kFreeSlot where free (core/key_set.hpp)
  std::vector<uint32_t> cell_of_key_; ///< the cells_ list of each key in keys_
  PooledLists<CellEntry> cells_;             ///< the triangles filed in each cell
  PooledLists<int32_t> near_;                ///< by slot: near(), kept up to date
  CornerFans fans_;                    ///< as of the last call that changed them
  bool fans_stale_ = false;            ///< fans_ must be built anew at the next call
  /// Without an index: the triangles and boxes of the last call, to see
  /// whether the mesh has settled enough to build one.
  std::vector<Triangle> last_triangles_;
  UnsetVector<Bounds> last_boxes_;
  int settled_calls_ = 0; ///< calls in a row without an index that found few changes
  size_t refiled_ = 0;
  bool rebuilt_ = false;
};

template <class F> void CrossingIndex::for_cells(const Filing& f, F&& f_of_key) const {
  if (f.level < 0) return;
  const auto last = cell_of(f.box.bounds().hi, f.level);
  for (int64_t i = f.first[0]; i <= last[0]; ++i)
    for (int64_t j = f.first[1]; j <= last[1]; ++j)
      for (int64_t k = f.first[2]; k <= last[2]; ++k) f_of_key(key(f.level, i, j, k));
}

} // namespace vm::detail
