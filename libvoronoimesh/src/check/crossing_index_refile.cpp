/// @file check/crossing_index_refile.cpp
/// CrossingIndex::refile(): filing again the triangles that changed since the
/// index last saw them, and mending the lists they are on.

#include "check/crossing_index.hpp"

#include "core/parallel.hpp"
#include "core/unset_vector.hpp"

#include <algorithm>

namespace vm::detail {

void CrossingIndex::kept_box_candidates(int32_t slot, std::vector<int32_t>& out) const {
  const auto listed = near_.at(size_t(slot));
  out.assign(listed.begin(), listed.end());
  for (int32_t fan : filed_[size_t(slot)].fans)
    if (fan >= 0 && size_t(fan) < fans_.count())
      for (int32_t corner : fans_.corners(size_t(fan))) out.push_back(slot_of_[size_t(corner / 3)]);
}

void CrossingIndex::refile(std::span<const int32_t> stale_by_id, std::span<const Triangle> triangles,
                           std::span<const Triangle> corner_fans) {
  // After a flip pass a tenth of the triangles are stale, each near ~20 others
  // (on the liver 17, of which 5 share no fan with it and are on its list).
  // Most of what they touch only changes in place: a cell the new filing keeps.
  // That is done in parallel (each entry is written by the task of its own
  // triangle); what comes and goes is collected per triangle and applied in
  // order, so the index never depends on the threads.
  // Taken in space order, one triangle's search through the cells finds the
  // cells, entries and filings the last one read still in cache: on 1,000
  // grains, searching for the 56-355k flipped triangles' new neighbours took
  // a quarter less time than in the order of their ids.
  const std::vector<int32_t> stale = in_space_order(stale_by_id);
  const size_t m = stale.size();
  // Kept between calls (all -1 then), so that a call costs its stale triangles, not the mesh.
  if (stale_index_.size() < filed_.size()) stale_index_.resize(filed_.size(), -1);
  for (size_t i = 0; i < m; ++i) stale_index_[size_t(slot_of_[size_t(stale[i])])] = int32_t(i);
  // A triangle that got other nodes or fans but still lies in its filing box
  // (half of those a flip pass changes on 1,000 grains) keeps that box, and
  // with it its cells and the slots its box meets: only which of those share
  // a fan with it changes, and they are on its old list or in its old fans.
  // Its list is mended from those, without a search through the cells.
  const bool fans_known = !fans_stale_ && !corner_fans.empty();
  std::vector<uint8_t> keeps_box(m);
  UnsetVector<Filing> fresh(m); // each written below
  struct Edits {
    std::vector<uint64_t> left, entered; // cells
    std::vector<int32_t> lost, gained;   // slots that stay
  };
  std::vector<Edits> edits(m);
  std::vector<std::vector<int32_t>> found(m); // each stale triangle's list
  detail::parallel_for_each_index(m, [&](size_t i) {
    const int32_t t = stale[i], slot = slot_of_[size_t(t)];
    const Filing& old = filed_[size_t(slot)];
    const Triangle fans = corner_fans.empty() ? Triangle{-1, -1, -1} : corner_fans[size_t(t)];
    keeps_box[i] = fans_known && old.level >= 0 && old.box.contains(boxes_[size_t(t)]);
    if (keeps_box[i]) {
      kept_box_candidates(slot, found[i]); // read before any list or fan changes
      fresh[i] = old;
      fresh[i].nodes = triangles[size_t(t)];
      fresh[i].fans = fans;
      return;
    }
    fresh[i] = filing_for(boxes_[size_t(t)], triangles[size_t(t)], fans);
    // The cells both filings have (none across levels, none for a triangle
    // not filed yet, level -1) keep the entry, renewed.
    const bool same_level = old.level >= 0 && old.level == fresh[i].level;
    std::array<int64_t, 3> lo{}, hi{};
    if (same_level) {
      const auto old_last = cell_of(old.box.bounds().hi, old.level),
                 new_last = cell_of(fresh[i].box.bounds().hi, fresh[i].level);
      for (size_t a = 0; a < 3; ++a)
        lo[a] = std::max(old.first[a], fresh[i].first[a]), hi[a] = std::min(old_last[a], new_last[a]);
    }
    auto kept = [&](uint64_t k) {
      const auto c = key_cell(k);
      return same_level && c[0] >= lo[0] && c[0] <= hi[0] && c[1] >= lo[1] && c[1] <= hi[1] && c[2] >= lo[2] &&
             c[2] <= hi[2];
    };
    for_cells(old, [&](uint64_t k) {
      if (!kept(k)) edits[i].left.push_back(k);
    });
    for_cells(fresh[i], [&](uint64_t k) {
      if (!kept(k)) {
        edits[i].entered.push_back(k);
        return;
      }
      // Other tasks read only the ids of the entries this one renews.
      for (CellEntry& e : cells_.at(size_t(find(k))))
        if (e.id == slot) e.first = cell_entry(slot, fresh[i]).first;
    });
  });
  std::vector<int32_t> changed; // other nodes or fans: the fans around them change
  std::vector<Triangle> old_fans;
  for (size_t i = 0; i < m; ++i) {
    const int32_t t = stale[i], slot = slot_of_[size_t(t)];
    const Filing& old = filed_[size_t(slot)];
    if (!same(fresh[i].fans, old.fans) || !same(fresh[i].nodes, old.nodes))
      changed.push_back(t), old_fans.push_back(old.fans);
    for (uint64_t k : edits[i].left) cells_.erase_id(size_t(find(k)), slot);
    if (old.level >= 0) --level_count_[size_t(old.level)];
    ++level_count_[size_t(fresh[i].level)];
    filed_[size_t(slot)] = fresh[i];
    for (uint64_t k : edits[i].entered) cells_.push(find_or_add(k), cell_entry(slot, fresh[i]));
  }
  if (fans_known) fans_.update(changed, old_fans, triangles, corner_fans);

  // The lists as the filings are now: searched through the cells, or, for a
  // kept box, its candidates whose filing meets it and that share no fan with it.
  std::vector<std::vector<int32_t>> meets_kept(m); // the kept boxes a search found
  detail::parallel_for_each_index(
      m,
      [&](size_t i) {
        const int32_t slot = slot_of_[size_t(stale[i])];
        std::vector<int32_t>& list = found[i];
        if (!keeps_box[i]) {
          near(slot, list);
          for (int32_t s : list)
            if (const int32_t j = stale_index_[size_t(s)]; j >= 0 && keeps_box[size_t(j)]) meets_kept[i].push_back(j);
          return;
        }
        const Filing& f = filed_[size_t(slot)];
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
        std::erase_if(list, [&](int32_t s) {
          return s == slot || !f.box.overlaps(filed_[size_t(s)].box) || share_a_fan(f.fans, filed_[size_t(s)].fans);
        });
      },
      16);
  // A triangle filed anew may meet a kept box that none of that box's
  // candidates' filings did; its search found the box, and the box gets it.
  std::vector<int32_t> grown;
  for (size_t i = 0; i < m; ++i)
    for (int32_t j : meets_kept[i]) found[size_t(j)].push_back(slot_of_[size_t(stale[i])]), grown.push_back(j);
  std::sort(grown.begin(), grown.end());
  grown.erase(std::unique(grown.begin(), grown.end()), grown.end());
  detail::parallel_for_each_index(grown.size(), [&](size_t g) {
    std::vector<int32_t>& list = found[size_t(grown[g])];
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  });

  // The old list against the new, both sorted; stale neighbours write their
  // own lists, the others gain or lose this slot below.
  detail::parallel_for_each_index(
      m,
      [&](size_t i) {
        const auto old = near_.at(size_t(slot_of_[size_t(stale[i])]));
        size_t o = 0;
        for (int32_t s : found[i]) {
          for (; o < old.size() && old[o] < s; ++o)
            if (stale_index_[size_t(old[o])] < 0) edits[i].lost.push_back(old[o]);
          const bool kept = o < old.size() && old[o] == s;
          o += kept;
          if (!kept && stale_index_[size_t(s)] < 0) edits[i].gained.push_back(s);
        }
        for (; o < old.size(); ++o)
          if (stale_index_[size_t(old[o])] < 0) edits[i].lost.push_back(old[o]);
      },
      16);
  for (size_t i = 0; i < m; ++i) {
    const int32_t slot = slot_of_[size_t(stale[i])];
    for (int32_t s : edits[i].lost) near_.erase_id(size_t(s), slot);
    for (int32_t s : edits[i].gained) near_.insert_by_id(size_t(s), slot);
    near_.reserve(size_t(slot), found[i].size());
  }
  detail::parallel_for_each_index(m, [&](size_t i) {
    const auto slot = size_t(slot_of_[size_t(stale[i])]);
    near_.resize(slot, found[i].size());
    std::copy(found[i].begin(), found[i].end(), near_.at(slot).begin());
  });
  for (int32_t t : stale) stale_index_[size_t(slot_of_[size_t(t)])] = -1;
}

} // namespace vm::detail
