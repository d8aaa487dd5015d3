/// @file create/coincident_triangles.cpp

#include "create/coincident_triangles.hpp"

#include <algorithm>

namespace vm::detail {

namespace {

/// Drops the vertices of `e` that no triangle uses and renumbers the rest in
/// order, in the triangles and in the lists that match vertices across ranks.
/// Unused vertices are rare (corners of cancelled pairs): none, nothing moves.
void drop_unused_vertices(SlabsMesh& e) {
  std::vector<int32_t> id(e.points.size(), -1);
  for (const auto& tri : e.triangles)
    for (const int32_t v : tri) id[size_t(v)] = 0;
  if (std::find(id.begin(), id.end(), -1) == id.end()) return;
  int32_t kept = 0;
  for (size_t v = 0; v < id.size(); ++v) {
    if (id[v] < 0) continue;
    id[v] = kept;
    e.points[size_t(kept)] = e.points[v];
    e.keys[size_t(kept)] = e.keys[v];
    e.where[size_t(kept)] = e.where[v];
    ++kept;
  }
  e.points.resize(size_t(kept));
  e.keys.resize(size_t(kept));
  e.where.resize(size_t(kept));
  for (auto& tri : e.triangles)
    for (int32_t& v : tri) v = id[size_t(v)];
  for (std::vector<int32_t>* list : {&e.first_owned_slab, &e.slab_above}) {
    auto& l = *list;
    l.erase(std::remove_if(l.begin(), l.end(), [&](int32_t v) { return id[size_t(v)] < 0; }), l.end());
    for (int32_t& v : l) v = id[size_t(v)];
  }
}

} // namespace

void resolve_coincident_triangles(SlabsMesh& e, CreateStats& stats) {
  auto& tris = e.triangles;
  auto& pairs = e.pairs;
  // Two polygons from different tets can only coincide on the face between them,
  // so only triangles whose corners all lie in one lattice face (three lattice
  // nodes between them) are candidates: a small fraction.
  auto in_one_face = [&](const std::array<int32_t, 3>& tri) {
    std::array<int64_t, 12> nodes;
    int n = 0;
    for (int32_t v : tri) {
      const LimitKey& k = e.keys[size_t(v)];
      for (int c = 0; c < k.count; ++c)
        if (std::find(nodes.begin(), nodes.begin() + n, k.nodes[c]) == nodes.begin() + n) nodes[n++] = k.nodes[c];
    }
    return n <= 3;
  };
  std::vector<std::array<int32_t, 3>> sorted(tris.size());
  std::vector<uint32_t> order;
  for (size_t t = 0; t < tris.size(); ++t)
    if (in_one_face(tris[t])) {
      sorted[t] = tris[t];
      std::sort(sorted[t].begin(), sorted[t].end());
      order.push_back(uint32_t(t));
    }
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return sorted[a] != sorted[b] ? sorted[a] < sorted[b] : a < b;
  });
  std::vector<char> removed(tris.size(), 0);
  for (size_t g = 0; g < order.size();) {
    size_t end = g + 1;
    while (end < order.size() && sorted[order[end]] == sorted[order[g]]) ++end;
    if (end - g == 2) {
      const uint32_t a = order[g], b = order[g + 1];
      bool same_orientation = false;
      for (int r = 0; r < 3; ++r)
        if (tris[b][r] == tris[a][0] && tris[b][(r + 1) % 3] == tris[a][1]) same_orientation = true;
      const int32_t a_back = pairs[a][0], a_front = pairs[a][1];
      const int32_t b_back = same_orientation ? pairs[b][0] : pairs[b][1];
      const int32_t b_front = same_orientation ? pairs[b][1] : pairs[b][0];
      int32_t back = -1, front = -1;
      if (a_front == b_back) back = a_back, front = b_front; // a below b
      else if (a_back == b_front) back = b_back, front = a_front; // b below a
      if (back >= 0) {
        ++stats.coincident_pairs;
        removed[b] = 1;
        removed[a] = back == front;
        if (back > front) std::swap(tris[a][1], tris[a][2]);
        pairs[a] = {std::min(back, front), std::max(back, front)};
      }
    }
    g = end;
  }
  size_t w = 0, owned_begin = 0, owned_end = 0;
  for (size_t t = 0; t < tris.size(); ++t) {
    if (t == e.owned_begin) owned_begin = w;
    if (t == e.owned_end) owned_end = w;
    if (!removed[t]) {
      tris[w] = tris[t];
      pairs[w] = pairs[t];
      ++w;
    }
  }
  e.owned_begin = e.owned_begin < tris.size() ? owned_begin : w;
  e.owned_end = e.owned_end < tris.size() ? owned_end : w;
  tris.resize(w);
  pairs.resize(w);
  drop_unused_vertices(e);
}

} // namespace vm::detail
