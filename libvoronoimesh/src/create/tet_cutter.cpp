#include "create/tet_cutter.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace vm::detail {
namespace {

/// For each sign pattern (bit c set = corner c on the winning side of the pair),
/// the tet edges the cut polygon crosses, in the cyclic order whose right-hand
/// normal points from the winning side into the losing side of a positively
/// oriented tet. Found once on a reference tet: the order does not change under
/// any orientation-preserving affine map, nor with where on the edges the cuts lie.
struct CutTable {
  std::array<std::array<std::array<uint8_t, 2>, 4>, 16> edges{};
  std::array<uint8_t, 16> size{};

  CutTable() {
    const Vec3 ref[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int pattern = 1; pattern < 15; ++pattern) {
      std::vector<int> plus, minus;
      for (int c = 0; c < 4; ++c) (pattern >> c & 1 ? plus : minus).push_back(c);
      std::vector<std::array<uint8_t, 2>> cyc;
      if (plus.size() == 1 || minus.size() == 1) {
        int apex = plus.size() == 1 ? plus[0] : minus[0];
        for (int c = 0; c < 4; ++c)
          if (c != apex) cyc.push_back({uint8_t(apex), uint8_t(c)});
      } else {
        int a = plus[0], b = plus[1], c = minus[0], d = minus[1];
        cyc = {{uint8_t(a), uint8_t(c)}, {uint8_t(a), uint8_t(d)}, {uint8_t(b), uint8_t(d)}, {uint8_t(b), uint8_t(c)}};
      }
      Vec3 normal = Vec3::Zero(), from = Vec3::Zero(), to = Vec3::Zero();
      std::vector<Vec3> mid;
      for (auto& e : cyc) mid.push_back(0.5 * (ref[e[0]] + ref[e[1]]));
      for (size_t m = 0; m < mid.size(); ++m) normal += mid[m].cross(mid[(m + 1) % mid.size()]);
      for (int c : plus) from += ref[c] / double(plus.size());
      for (int c : minus) to += ref[c] / double(minus.size());
      if (normal.dot(to - from) < 0) std::reverse(cyc.begin(), cyc.end());
      size[pattern] = uint8_t(cyc.size());
      for (size_t m = 0; m < cyc.size(); ++m) edges[pattern][m] = cyc[m];
    }
  }
};

const CutTable& cut_table() {
  static const CutTable table;
  return table;
}

using Matrix = std::array<std::array<i128, 4>, 4>;

} // namespace

void TetCutter::collect_phases(const std::array<int64_t, 4>& nodes) {
  ids_.clear();
  for (int c = 0; c < 4; ++c)
    for (int32_t p : values_.ids(nodes[c]))
      if (std::find(ids_.begin(), ids_.end(), p) == ids_.end()) ids_.push_back(p);
  std::sort(ids_.begin(), ids_.end());
  vals_.resize(ids_.size());
  for (size_t p = 0; p < ids_.size(); ++p)
    for (int c = 0; c < 4; ++c) vals_[p][c] = values_.value(nodes[c], ids_[p]);

  // A phase can be dropped only when one single other phase beats it at all four
  // corners: then it loses everywhere in the tet. Losing to different phases at
  // different corners is not enough (DESIGN.md, "Which phases a tet needs").
  // The corners' winners are the likeliest to beat a phase everywhere, so they
  // are tried first.
  candidates_.clear();
  for (int c = 0; c < 4; ++c) {
    const size_t q = size_t(std::find(ids_.begin(), ids_.end(), values_.label(nodes[c])) - ids_.begin());
    if (std::find(candidates_.begin(), candidates_.end(), q) == candidates_.end()) candidates_.push_back(q);
  }
  for (size_t q = 0; q < ids_.size(); ++q)
    if (std::find(candidates_.begin(), candidates_.end(), q) == candidates_.end()) candidates_.push_back(q);
  std::vector<char>& keep = keep_;
  keep.assign(ids_.size(), 1);
  for (size_t p = 0; p < ids_.size(); ++p)
    for (size_t q : candidates_) {
      if (q == p) continue;
      bool all = true;
      for (int c = 0; c < 4 && all; ++c) all = beats(vals_[q][c], ids_[q], vals_[p][c], ids_[p]);
      if (all) {
        keep[p] = 0;
        break;
      }
    }
  size_t w = 0;
  for (size_t p = 0; p < ids_.size(); ++p)
    if (keep[p]) {
      ids_[w] = ids_[p];
      vals_[w] = vals_[p];
      ++w;
    }
  ids_.resize(w);
  vals_.resize(w);
}

int TetCutter::perturbed_sign_at_node(int a, int b, int corner) const {
  return beats(vals_[a][corner], ids_[a], vals_[b][corner], ids_[b]) ? 1 : -1;
}

int TetCutter::sign_at(const PolyVertex& v, int a, int b, CutCounters& counters) const {
  // The vertex solves phi'_{s0} = phi'_{sm} (m = 1..d) on its element of d+1
  // corners. With those d rows r_m and g = phi_a - phi_b, the value of g' at the
  // vertex is det[r'; g'] / det[r'; 1] (Cramer's rule).
  //
  // The perturbation phi'_p = phi_p - eps_p adds (eps_q - eps_p) times a row of
  // ones to the row of a pair (p, q). A row of ones added to rows of det[r'; 1]
  // changes nothing; det[r'; g'] is multilinear and two rows of ones make it
  // vanish, so it is N0 + sum_p eps_p C_p, exactly. The eps_p are infinitesimals of
  // different orders, growing with the phase id, so the sign is that of N0, else
  // of C_p for the largest id p with C_p != 0. C_b = +-det[r'; 1] != 0 because b
  // (the phase chopped against) is not tied at the vertex: never zero.
  int cols[4], n = 0;
  for (int c = 0; c < 4; ++c)
    if (v.mask >> c & 1) cols[n++] = c;
  const int d = n - 1;
  const int s0 = v.phases[0];
  Matrix m{};
  auto fill_row = [&](int row, int p, int q) {
    for (int c = 0; c < n; ++c) m[row][c] = vals_[p][cols[c]] - vals_[q][cols[c]];
  };
  for (int r = 0; r < d; ++r) fill_row(r, s0, v.phases[r + 1]);
  fill_row(d, a, b);
  const i128 n0 = det(m, n);
  for (int c = 0; c < n; ++c) m[d][c] = 1;
  const i128 d1 = det(m, n);
  if (d1 == 0) { // cannot happen for a vertex that exists; be safe, not sorry
    ++counters.degenerate;
    return 0;
  }
  if (n0 != 0) return sign(n0) * sign(d1);

  // Coefficients C_p of the phases involved (local indices), largest id last.
  std::array<std::pair<int, i128>, 6> coeff;
  int nc = 0;
  auto add = [&](int p, i128 amount) {
    for (int e = 0; e < nc; ++e)
      if (coeff[e].first == p) {
        coeff[e].second += amount;
        return;
      }
    coeff[nc++] = {p, amount};
  };
  add(b, d1); // g' = g + (eps_b - eps_a)
  add(a, -d1);
  fill_row(d, a, b);
  for (int r = 0; r < d; ++r) {
    auto saved = m[r];
    for (int c = 0; c < n; ++c) m[r][c] = 1;
    const i128 minor = det(m, n); // row r of pair (s0, s_{r+1}) gains eps_{s_{r+1}} - eps_{s0}
    add(v.phases[r + 1], minor);
    add(s0, -minor);
    m[r] = saved;
  }
  int best = -1;
  for (int e = 0; e < nc; ++e)
    if (coeff[e].second != 0 && (best < 0 || coeff[e].first > coeff[best].first)) best = e;
  if (best < 0) {
    ++counters.degenerate;
    return 0;
  }
  return sign(coeff[best].second) * sign(d1);
}

LimitKey TetCutter::limit_key(const PolyVertex& v) const {
  int cols[4], n = 0;
  for (int c = 0; c < 4; ++c)
    if (v.mask >> c & 1) cols[n++] = c;
  if (n == 2) return edge_limit_key(v, cols[0], cols[1]);
  const int d = n - 1;
  Matrix m{};
  for (int r = 0; r < d; ++r)
    for (int c = 0; c < n; ++c) m[r][c] = vals_[v.phases[0]][cols[c]] - vals_[v.phases[r + 1]][cols[c]];
  // Barycentric weight of corner c is det[r; e_c] / det[r; 1]; the weights of
  // the limit point do not depend on the perturbation.
  std::array<std::pair<int64_t, i128>, 4> w;
  int count = 0;
  i128 total = 0;
  for (int c = 0; c < n; ++c) {
    for (int k = 0; k < n; ++k) m[d][k] = (k == c);
    i128 wc = det(m, n);
    total += wc;
    if (wc != 0) w[count++] = {nodes_[cols[c]], wc};
  }
  for (int c = 1; c < count; ++c) // insertion sort by node: at most four entries
    for (int e = c; e > 0 && w[e].first < w[e - 1].first; --e) std::swap(w[e], w[e - 1]);
  unsigned __int128 g = 0;
  for (int c = 0; c < count && g != 1; ++c) g = gcd(g, abs_u(w[c].second));
  LimitKey key;
  key.count = count;
  for (int c = 0; c < count; ++c) {
    key.nodes[c] = w[c].first;
    i128 weight = w[c].second / i128(g);
    key.weights[c] = total < 0 ? -weight : weight;
  }
  return key;
}

LimitKey TetCutter::edge_limit_key(const PolyVertex& v, int ca, int cb) const {
  // The common case, in 64 bits: on edge (a, b) the tie psi = 0 of psi(a) > 0 >
  // psi(b) (or the reverse) has weights -psi(b) at a and psi(a) at b.
  const int64_t pa = vals_[v.phases[0]][ca] - vals_[v.phases[1]][ca];
  const int64_t pb = vals_[v.phases[0]][cb] - vals_[v.phases[1]][cb];
  int64_t wa = -pb, wb = pa;
  if (wa < 0 || wb < 0) wa = -wa, wb = -wb; // same sign by construction (or one is 0)
  LimitKey key;
  if (wa == 0 || wb == 0) { // the limit point is a lattice node
    key.count = 1;
    key.nodes[0] = nodes_[wa == 0 ? cb : ca];
    key.weights[0] = 1;
    return key;
  }
  const int64_t g = int64_t(gcd(uint64_t(wa), uint64_t(wb)));
  key.count = 2;
  const bool a_first = nodes_[ca] < nodes_[cb];
  key.nodes[0] = nodes_[a_first ? ca : cb];
  key.nodes[1] = nodes_[a_first ? cb : ca];
  key.weights[0] = (a_first ? wa : wb) / g;
  key.weights[1] = (a_first ? wb : wa) / g;
  return key;
}

Vec3 TetCutter::position(const LimitKey& key) const {
  auto node_pos = [&](int64_t node) {
    const GridPoint g = lattice_.grid_point(node);
    return grid_.node_position(g[0], g[1], g[2]);
  };
  // Base the sum on the first node so points on a box face stay on it exactly.
  Vec3 base = node_pos(key.nodes[0]);
  if (key.count == 1) return base;
  double total = 0;
  for (int c = 0; c < key.count; ++c) total += double(key.weights[c]);
  Vec3 p = base;
  for (int c = 1; c < key.count; ++c) p += (double(key.weights[c]) / total) * (node_pos(key.nodes[c]) - base);
  return p;
}

void TetCutter::initial_polygon(int a, int b, Polygon& poly) const {
  poly.clear();
  int pattern = 0;
  for (int c = 0; c < 4; ++c)
    if (perturbed_sign_at_node(a, b, c) > 0) pattern |= 1 << c;
  const CutTable& table = cut_table();
  for (int e = 0; e < table.size[pattern]; ++e) {
    PolyVertex v;
    v.mask = uint8_t(1 << table.edges[pattern][e][0] | 1 << table.edges[pattern][e][1]);
    v.size = 2;
    v.phases = {uint8_t(a), uint8_t(b), 0, 0};
    poly.push_back(v);
  }
}

bool TetCutter::chop(Polygon& poly, int a, int b, int k, CutCounters& counters) {
  (void)b; // on the polygon phi'_a == phi'_b, so testing a against k suffices
  const size_t n = poly.size();
  std::vector<int>& signs = signs_;
  signs.resize(n);
  bool any_out = false;
  for (size_t v = 0; v < n; ++v) {
    signs[v] = sign_at(poly[v], a, k, counters);
    any_out |= signs[v] < 0;
  }
  if (!any_out) return true;
  scratch_.clear();
  for (size_t v = 0; v < n; ++v) {
    const PolyVertex& u = poly[v];
    const PolyVertex& w = poly[(v + 1) % n];
    const int su = signs[v], sw = signs[(v + 1) % n];
    if (su >= 0) scratch_.push_back(u);
    if (su * sw < 0) {
      // The new vertex lies on the polygon edge u-w, whose line is cut out by the
      // phases tied at both ends, in the smallest element holding both.
      PolyVertex x;
      x.mask = u.mask | w.mask;
      for (int p = 0; p < u.size; ++p)
        for (int q = 0; q < w.size; ++q)
          if (u.phases[p] == w.phases[q]) x.phases[x.size++] = u.phases[p];
      const int dim = std::popcount(x.mask) - 1;
      // Tied phases at a vertex are one more than its element's dimension; on
      // the edge both ends share, one fewer (on a box face's boundary, the
      // face's own phase alone along a lattice edge).
      if (x.size != dim || dim < 1) { // a tie the perturbation did not separate
        ++counters.degenerate;
        return false;
      }
      // Keep the pair's first phase first: rows are built against phases[0].
      x.phases[x.size++] = uint8_t(k);
      scratch_.push_back(x);
    }
  }
  poly.swap(scratch_);
  return poly.size() >= 3;
}

void TetCutter::emit(const Polygon& poly, const PhasePair& pair, std::vector<CutTriangle>& out, CutCounters& counters) {
  // Distinct limit points in cyclic order.
  std::vector<LimitKey>& keys = keys_;
  std::vector<Vec3>& pos = pos_;
  keys.resize(poly.size());
  pos.resize(poly.size());
  int m = 0;
  for (const PolyVertex& v : poly) {
    LimitKey key = limit_key(v);
    if (m > 0 && key == keys[m - 1]) continue;
    keys[m] = key;
    pos[m] = position(key);
    ++m;
  }
  while (m > 1 && keys[m - 1] == keys[0]) --m;
  if (m < 3) {
    ++counters.collapsed;
    return;
  }
  ++counters.polygons;
  // Fan from the corner that makes the smallest triangle largest; the choice
  // depends only on the limit points, so a polygon computed twice (from either
  // side of a face) is triangulated the same way.
  int apex = 0;
  double best = -1;
  for (int s = 0; s < m; ++s) {
    double worst = INFINITY;
    for (int t = 1; t + 1 < m; ++t)
      worst = std::min(worst, (pos[(s + t) % m] - pos[s]).cross(pos[(s + t + 1) % m] - pos[s]).squaredNorm());
    if (worst > best || (worst == best && keys[s] < keys[apex])) {
      best = worst;
      apex = s;
    }
  }
  for (int t = 1; t + 1 < m; ++t)
    out.push_back({{keys[apex], keys[(apex + t) % m], keys[(apex + t + 1) % m]}, pair});
}

bool TetCutter::cut(const std::array<int64_t, 4>& nodes, std::vector<CutTriangle>& out, CutCounters& counters) {
  const int32_t l0 = values_.label(nodes[0]);
  if (values_.label(nodes[1]) == l0 && values_.label(nodes[2]) == l0 && values_.label(nodes[3]) == l0) return false;
  nodes_ = nodes;
  collect_phases(nodes);
  if (ids_.size() < 2) return false;
  ++counters.tets_cut;
  Polygon& poly = poly_;
  const int np = int(ids_.size());
  for (int a = 0; a < np; ++a)
    for (int b = a + 1; b < np; ++b) {
      initial_polygon(a, b, poly);
      if (poly.empty()) continue;
      bool alive = true;
      for (int k = 0; k < np && alive; ++k)
        if (k != a && k != b) alive = chop(poly, a, b, k, counters);
      if (alive) emit(poly, {ids_[a], ids_[b]}, out, counters);
    }
  return true;
}

void TetCutter::cut_box_faces(const std::array<int64_t, 4>& nodes, int32_t outside, std::vector<CutTriangle>& out,
                              CutCounters& counters) {
  std::array<GridPoint, 4> g;
  for (int c = 0; c < 4; ++c) g[size_t(c)] = lattice_.grid_point(nodes[size_t(c)]);
  bool collected = false;
  for (int opposite = 0; opposite < 4; ++opposite) {
    std::array<int, 3> face;
    for (int c = 0, n = 0; c < 4; ++c)
      if (c != opposite) face[size_t(n++)] = c;
    // The box plane holding all three corners, if any, and its outward side.
    int axis = -1, side = 0;
    for (int a = 0; a < 3 && axis < 0; ++a)
      for (int s : {0, 1}) {
        const int32_t plane = s ? grid_.cells[size_t(a)] : 0;
        if (g[size_t(face[0])][size_t(a)] == plane && g[size_t(face[1])][size_t(a)] == plane &&
            g[size_t(face[2])][size_t(a)] == plane) {
          axis = a;
          side = s ? 1 : -1;
        }
      }
    if (axis < 0) continue;
    if (!collected) {
      nodes_ = nodes;
      // Only nodes near interfaces and on the box hold values, so the corner
      // off the box may hold none (asking for them read from before the start
      // of NodeValues' arrays). The face's phases are decided at its own
      // corners: one of them stands in for it.
      std::array<int64_t, 4> held = nodes;
      for (int64_t& n : held)
        if (!values_.held(n)) n = nodes[size_t(face[0])];
      collect_phases(held);
      collected = true;
    }
    // Corner order whose right-hand normal points out of the box.
    auto at = [&](int c) { return Vec3(g[size_t(c)][0], g[size_t(c)][1], g[size_t(c)][2]); };
    const Vec3 normal = (at(face[1]) - at(face[0])).cross(at(face[2]) - at(face[0]));
    if (normal[axis] * side < 0) std::swap(face[1], face[2]);
    const int np = int(ids_.size());
    for (int a = 0; a < np; ++a) {
      Polygon& poly = poly_;
      poly.clear();
      for (int c : face) {
        PolyVertex v;
        v.mask = uint8_t(1 << c);
        v.size = 1;
        v.phases = {uint8_t(a), 0, 0, 0};
        poly.push_back(v);
      }
      bool alive = true;
      for (int k = 0; k < np && alive; ++k)
        if (k != a) alive = chop(poly, a, a, k, counters);
      if (alive) emit(poly, {ids_[a], outside}, out, counters);
    }
  }
}

} // namespace vm::detail
