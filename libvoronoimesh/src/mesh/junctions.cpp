/// @file mesh/junctions.cpp
/// Triple curves and quadruple points from the incidence tables of
/// mesh/topology.hpp (mesh/junctions.hpp).

#include "voronoimesh/mesh/junctions.hpp"

#include "mesh/junction_tables.hpp"

#include <algorithm>

namespace vm {

namespace detail {

namespace {

/// Walks the junction edges: a node continues a chain when exactly three phases
/// meet there and exactly two junction edges touch it.
class ChainWalker {
public:
  ChainWalker(const EdgeTable& et, const NodePhases& np) : et_(et), np_(np) {
    const size_t num_nodes = np.off.size() - 1;
    off_.assign(num_nodes + 1, 0);
    for (size_t e = 0; e < et.size(); ++e)
      if (is_junction(e))
        for (int32_t n : et.nodes[e]) ++off_[size_t(n) + 1];
    for (size_t n = 0; n < num_nodes; ++n) off_[n + 1] += off_[n];
    at_.resize(size_t(off_[num_nodes]));
    std::vector<int32_t> fill(off_.begin(), off_.end() - 1);
    for (size_t e = 0; e < et.size(); ++e)
      if (is_junction(e))
        for (int32_t n : et.nodes[e]) at_[size_t(fill[size_t(n)]++)] = int32_t(e);
  }

  bool is_junction(size_t e) const { return et_.halfedges(e).size() >= 3; }

  /// The node chain through junction edge `e`, marking its edges in `done`.
  std::vector<int32_t> chain(int32_t e, std::vector<char>& done) const {
    // Back up to one end (or once round a loop), then walk forward from there.
    int32_t edge = e, node = et_.nodes[size_t(e)][0];
    while (continues(node)) {
      const int32_t next = other_edge(node, edge);
      if (next == e) break; // a closed chain
      edge = next;
      node = other_node(edge, node);
    }
    std::vector<int32_t> nodes{node};
    for (;;) {
      done[size_t(edge)] = 1;
      node = other_node(edge, node);
      nodes.push_back(node);
      if (!continues(node)) break;
      edge = other_edge(node, edge);
      if (done[size_t(edge)]) break; // back at the start of a closed chain
    }
    const bool loop = continues(nodes.front());
    return canonical(std::move(nodes), loop);
  }

private:
  bool continues(int32_t n) const { return np_.count(size_t(n)) == 3 && off_[size_t(n) + 1] - off_[size_t(n)] == 2; }
  int32_t other_edge(int32_t n, int32_t e) const {
    const int32_t* a = &at_[size_t(off_[size_t(n)])];
    return a[0] == e ? a[1] : a[0];
  }
  int32_t other_node(int32_t e, int32_t n) const {
    const auto& ab = et_.nodes[size_t(e)];
    return ab[0] == n ? ab[1] : ab[0];
  }

  /// Open: start at the smaller end. Closed (`loop`: no node ends it): start at
  /// the smallest node. A chain that leaves an end and comes back to it keeps
  /// that end. Either closed kind then runs towards the smaller neighbour of its
  /// start, so the result does not depend on where the walk began.
  static std::vector<int32_t> canonical(std::vector<int32_t> nodes, bool loop) {
    if (nodes.front() != nodes.back()) {
      if (nodes.back() < nodes.front()) std::reverse(nodes.begin(), nodes.end());
      return nodes;
    }
    if (loop) std::rotate(nodes.begin(), std::min_element(nodes.begin(), nodes.end() - 1), nodes.end() - 1);
    nodes.back() = nodes.front();
    if (nodes[nodes.size() - 2] < nodes[1]) std::reverse(nodes.begin(), nodes.end());
    return nodes;
  }

  const EdgeTable& et_;
  const NodePhases& np_;
  std::vector<int32_t> off_, at_; // junction edges at each node (CSR)
};

/// The phases of the triangles on edge `e`, ascending.
std::vector<int32_t> edge_phases(const std::vector<PhasePair>& pairs, const EdgeTable& et, size_t e) {
  std::vector<int32_t> phases;
  for (int32_t h : et.halfedges(e)) {
    const PhasePair& p = pairs[size_t(he_triangle(h))];
    phases.insert(phases.end(), p.begin(), p.end());
  }
  std::sort(phases.begin(), phases.end());
  phases.erase(std::unique(phases.begin(), phases.end()), phases.end());
  return phases;
}

} // namespace

Junctions junctions_from(const std::vector<PhasePair>& pairs, const EdgeTable& et, const NodePhases& np) {
  Junctions j;
  j.phase_offsets = np.off;
  j.phase_ids = np.phase;
  const ChainWalker walker(et, np);
  std::vector<char> done(et.size(), 0);
  for (size_t e = 0; e < et.size(); ++e)
    if (walker.is_junction(e) && !done[e])
      j.curves.push_back(TripleCurve{edge_phases(pairs, et, e), walker.chain(int32_t(e), done)});
  std::sort(j.curves.begin(), j.curves.end(), [](const TripleCurve& a, const TripleCurve& b) {
    return std::tie(a.phases, a.nodes) < std::tie(b.phases, b.nodes);
  });
  for (size_t n = 0; n + 1 < np.off.size(); ++n)
    if (np.count(n) >= 4) j.quadruple_points.push_back(int32_t(n));
  return j;
}

} // namespace detail

Junctions find_junctions(const NodeMesh& m) {
  std::vector<char> usable(m.triangles.size());
  for (size_t t = 0; t < m.triangles.size(); ++t)
    usable[t] = t < m.pairs.size() && detail::well_formed(m.triangles[t], m.points.size());
  const detail::NodeTriangles nt = detail::node_triangles(m.points.size(), m.triangles, &usable);
  const detail::EdgeTable et = detail::edge_table(m.triangles, nt);
  return detail::junctions_from(m.pairs, et, detail::node_phases(nt, m.pairs));
}

} // namespace vm
