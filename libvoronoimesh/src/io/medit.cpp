/// @file io/medit.cpp
/// MEDIT .mesh (the INRIA mesh format MMG, TetGen and Medit read):
/// triangles with a reference per phase pair, the triple curves as Edges with
/// a reference per phase triple, and the quadruple points as Corners and
/// RequiredVertices, so a remesher keeps them. The tables from references to
/// phases are comments at the top.

#include "core/text.hpp"
#include "io/output_buffer.hpp"
#include "io/phase_names.hpp"
#include "io/writers.hpp"
#include "voronoimesh/mesh/junctions.hpp"

namespace vm::io::detail {

namespace {

using vm::detail::cat;
using vm::detail::ChunkedOutput;
using vm::detail::put_int;

/// A keyword block: "Keyword\ncount\n" then `row(i)` for each item; none if empty.
template <class Row>
void block(ChunkedOutput& out, const char* keyword, size_t count, Row row) {
  if (count == 0) return;
  out.text() += cat(keyword, "\n", count, "\n");
  for (size_t i = 0; i < count; ++i) {
    row(out.text(), i);
    out.text() += '\n';
    out.maybe_flush();
  }
}

} // namespace

void write_medit(vm::detail::StagedOutputs& staged, const NodeMesh& m, const std::string& path) {
  const std::vector<PhasePair> pairs = distinct_pairs(m);
  const std::vector<int32_t> pair_ref = pair_indices(m, pairs);
  const Junctions junctions = find_junctions(m);
  // Edge references: one per phase set of the triple curves (curves come sorted by it).
  std::vector<std::pair<int32_t, int32_t>> edges; // (curve, position of its first node)
  std::vector<int32_t> curve_ref(junctions.curves.size());
  std::vector<const std::vector<int32_t>*> triples;
  for (size_t c = 0; c < junctions.curves.size(); ++c) {
    const TripleCurve& curve = junctions.curves[c];
    if (triples.empty() || *triples.back() != curve.phases) triples.push_back(&curve.phases);
    curve_ref[c] = int32_t(triples.size());
    for (size_t i = 0; i < curve.num_edges(); ++i) edges.emplace_back(int32_t(c), int32_t(i));
  }
  vm::detail::write_in_chunks(staged, path, [&](ChunkedOutput& out) {
    std::string& buf = out.text();
    buf += "MeshVersionFormatted 2\nDimension 3\n"
           "# voronoimesh interface mesh. Phases are named <label>-<name>.\n"
           "# Triangles: reference = surface of a phase pair; normals point from its first phase into its second.\n";
    for (size_t i = 0; i < pairs.size(); ++i) buf += cat("#   triangle ref ", i + 1, ": ", phases_token(m, pairs[i]), "\n");
    buf += "# Edges: the triple curves; reference = the phases meeting along them.\n";
    for (size_t i = 0; i < triples.size(); ++i) buf += cat("#   edge ref ", i + 1, ": ", phases_token(m, *triples[i]), "\n");
    buf += "# Corners, RequiredVertices: the quadruple points (4 or more phases meet).\n";
    block(out, "Vertices", m.points.size(), [&](std::string& b, size_t n) {
      vm::detail::put_point(b, m.points[n]);
      b += " 0";
    });
    block(out, "Edges", edges.size(), [&](std::string& b, size_t e) {
      const auto [c, i] = edges[e];
      const auto& nodes = junctions.curves[size_t(c)].nodes;
      b += cat(nodes[size_t(i)] + 1, " ", nodes[size_t(i) + 1] + 1, " ", curve_ref[size_t(c)]);
    });
    block(out, "Triangles", m.triangles.size(), [&](std::string& b, size_t t) {
      for (int32_t v : m.triangles[t]) {
        put_int(b, v + 1);
        b += ' ';
      }
      put_int(b, pair_ref[t] + 1);
    });
    for (const char* keyword : {"Corners", "RequiredVertices"})
      block(out, keyword, junctions.quadruple_points.size(),
            [&](std::string& b, size_t q) { put_int(b, junctions.quadruple_points[q] + 1); });
    buf += "End\n";
  });
}

} // namespace vm::io::detail
