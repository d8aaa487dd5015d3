#include "mesh/patch_connectivity.hpp"

#include "core/parallel.hpp"
#include "core/text.hpp"
#include "voronoimesh/core/errors.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <string>

namespace vm::detail {

namespace {

/// Corner c = 3t + k is corner k of triangle t, and halfedge h = 3t + k starts
/// there (mesh/topology.hpp), so a halfedge's vertices are those of its corners.
struct CornerVertices {
  const std::vector<int32_t>& of_corner;
  int32_t from(int32_t h) const { return of_corner[size_t(h)]; }
  int32_t to(int32_t h) const { return of_corner[size_t(3 * (h / 3) + (h % 3 + 1) % 3)]; }
};

/// Numbers the flagged items in order in parallel (blocks of a fixed size,
/// counted, then numbered from their block's start): number[i] is the count
/// of flagged items before i. Returns the count of all.
int32_t number_flagged(const std::vector<uint8_t>& flagged, std::vector<int32_t>& number) {
  constexpr size_t kBlock = 1 << 14;
  const size_t n = flagged.size(), blocks = (n + kBlock - 1) / kBlock;
  std::vector<int32_t> start(blocks + 1, 0);
  parallel_for_each_index(
      blocks,
      [&](size_t b) {
        start[b + 1] = int32_t(std::count(flagged.begin() + ptrdiff_t(b * kBlock),
                                          flagged.begin() + ptrdiff_t(std::min(n, (b + 1) * kBlock)), 1));
      },
      1);
  for (size_t b = 0; b < blocks; ++b) start[b + 1] += start[b];
  number.resize(n);
  parallel_for_each_index(
      blocks,
      [&](size_t b) {
        int32_t next = start[b];
        for (size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) number[i] = next, next += flagged[i];
      },
      1);
  return start[blocks];
}

const char* const kSource = "interface mesh";

std::string describe(size_t t, const std::array<int32_t, 3>& tri) {
  return cat("triangle ", t, " (", tri[0], ", ", tri[1], ", ", tri[2], ")");
}

} // namespace

void check_node_mesh(const NodeMesh& m) {
  if (m.pairs.size() != m.triangles.size())
    throw TopologyError(located(kSource, cat(m.triangles.size(), " triangles but ", m.pairs.size(), " phase pairs")));
  if (m.points.size() > size_t(std::numeric_limits<int32_t>::max()) ||
      m.triangles.size() > size_t(std::numeric_limits<int32_t>::max() / 3))
    throw TopologyError(located(kSource, "too many nodes or triangles for 32-bit ids"));
  const auto n = int64_t(m.points.size());
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    for (int32_t v : tri)
      if (v < 0 || v >= n)
        throw TopologyError(located(kSource, cat(describe(t, tri), ": node ", v, " out of range (", n, " nodes)")));
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      throw TopologyError(located(kSource, cat(describe(t, tri), ": repeated node")));
    const auto& p = m.pairs[t];
    if (p[0] < 0 || p[0] >= p[1] || p[1] > std::numeric_limits<int16_t>::max())
      throw TopologyError(located(kSource, cat(describe(t, tri), ": bad phase pair (", p[0], ", ", p[1], ")")));
  }
}

void check_phase_count(size_t n, size_t count) {
  if (count > PhaseSet{}.size())
    throw TopologyError(
        located(kSource, cat("node ", n, ": ", count, " phases meet (at most ", PhaseSet{}.size(), " supported)")));
}

std::vector<int32_t> glued_partners(const EdgeTable& et, const Triangles& tris, const std::vector<PhasePair>& pairs) {
  std::vector<int32_t> partner(3 * tris.size(), -1);
  parallel_for_each_index(et.size(), [&](size_t e) {
    if (!is_patch_interior(et, e, tris, pairs)) return;
    const auto hs = et.halfedges(e);
    partner[size_t(hs[0])] = hs[1];
    partner[size_t(hs[1])] = hs[0];
  });
  return partner;
}

int32_t corner_classes_at(int32_t n, std::span<const int32_t> ts, const Triangles& tris,
                          const std::vector<int32_t>& partner, std::vector<int32_t>& parent, int32_t* corner_at,
                          int32_t* class_at) {
  // A union-find over the node's triangles (ascending, so a class's smallest
  // index is its first triangle), joined where a halfedge at the node is glued.
  parent.resize(ts.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int32_t i) {
    while (parent[size_t(i)] != i) i = parent[size_t(i)] = parent[size_t(parent[size_t(i)])];
    return i;
  };
  for (size_t i = 0; i < ts.size(); ++i) {
    const auto& tri = tris[size_t(ts[i])];
    const int32_t c = 3 * ts[i] + int32_t(std::find(tri.begin(), tri.end(), n) - tri.begin());
    corner_at[i] = c;
    // The halfedges out of and into the node in this triangle.
    for (const int32_t h : {c, c - c % 3 + (c % 3 + 2) % 3}) {
      if (partner[size_t(h)] < 0) continue;
      const auto j = int32_t(std::lower_bound(ts.begin(), ts.end(), partner[size_t(h)] / 3) - ts.begin());
      const int32_t a = find(int32_t(i)), b = find(j);
      parent[size_t(std::max(a, b))] = std::min(a, b);
    }
  }
  int32_t classes = 0;
  for (size_t i = 0; i < ts.size(); ++i) {
    const int32_t r = find(int32_t(i));
    class_at[i] = size_t(r) == i ? classes++ : class_at[size_t(r)];
  }
  return classes;
}

void number_corner_classes(const NodeTriangles& nt, const Triangles& tris, const std::vector<int32_t>& partner,
                           std::vector<int32_t>& vertex_of_corner, std::vector<int32_t>& copy_off) {
  const size_t num_nodes = nt.off.size() - 1;
  // Node by node; each corner's class within its node is kept beside the
  // node's triangle (corner_at, class_at), so that numbering them afterwards
  // reads in order.
  std::vector<int32_t> corner_at(nt.tri.size()), class_at(nt.tri.size());
  copy_off.assign(num_nodes + 1, 0);
  detail::parallel_for(tbb::blocked_range<size_t>(0, num_nodes, 1024), [&](const tbb::blocked_range<size_t>& range) {
    std::vector<int32_t> parent;
    for (size_t n = range.begin(); n != range.end(); ++n) {
      const auto at = size_t(nt.off[n]);
      copy_off[n + 1] =
          corner_classes_at(int32_t(n), nt.of(n), tris, partner, parent, &corner_at[at], &class_at[at]);
    }
  });
  for (size_t n = 0; n < num_nodes; ++n) copy_off[n + 1] += copy_off[n];
  vertex_of_corner.resize(3 * tris.size());
  parallel_for_each_index(num_nodes, [&](size_t n) {
    for (auto i = size_t(nt.off[n]); i < size_t(nt.off[n + 1]); ++i)
      vertex_of_corner[size_t(corner_at[i])] = copy_off[n] + class_at[i];
  });
}

bool joins_vertices_twice(std::span<const int32_t> halfedges, const std::vector<int32_t>& vertex_of_corner) {
  const CornerVertices v{vertex_of_corner};
  auto ends = [&](int32_t h) { // as values: std::minmax would keep references to temporaries
    const int32_t from = v.from(h), to = v.to(h);
    return std::pair{std::min(from, to), std::max(from, to)};
  };
  for (size_t i = 0; i < halfedges.size(); ++i)
    for (size_t j = i + 1; j < halfedges.size(); ++j)
      if (ends(halfedges[i]) == ends(halfedges[j])) return true;
  return false;
}

bool some_edge_joins_vertices_twice(const EdgeTable& et, const std::vector<int32_t>& vertex_of_corner,
                                    const std::vector<int32_t>& partner) {
  std::vector<uint8_t> twice(et.size(), 0);
  parallel_for_each_index(et.size(), [&](size_t e) {
    twice[e] = partner[size_t(et.halfedges(e)[0])] < 0 && joins_vertices_twice(et.halfedges(e), vertex_of_corner);
  });
  return std::find(twice.begin(), twice.end(), 1) != twice.end();
}

bool connect_patch_faces(OMesh& mesh, const Triangles& tris, const std::vector<int32_t>& vertex_of_corner,
                         const std::vector<int32_t>& partner) {
  const CornerVertices v{vertex_of_corner};
  const size_t num_halfedges = 3 * tris.size(), num_vertices = mesh.n_vertices();

  // OpenMesh halfedge of each triangle halfedge: add_face() makes a triangle's
  // missing edges in corner order, the first halfedge running its way, so a
  // glued edge belongs to its first halfedge and its partner takes the opposite.
  std::vector<uint8_t> makes_edge(num_halfedges);
  parallel_for_each_index(num_halfedges, [&](size_t h) { makes_edge[h] = partner[h] < 0 || int32_t(h) < partner[h]; });
  std::vector<int32_t> edge_number, om_halfedge(num_halfedges);
  const int32_t num_edges = number_flagged(makes_edge, edge_number);
  parallel_for_each_index(num_halfedges, [&](size_t h) {
    om_halfedge[h] = makes_edge[h] ? 2 * edge_number[h] : 2 * edge_number[size_t(partner[h])] + 1;
  });

  // Boundary halfedges run opposite the unglued ones. A vertex whose fan is
  // open has one going out, where its boundary loop continues; a second one
  // means a second gap, which only add_face() can link; so does one coming in
  // without one going out.
  std::vector<int32_t> boundary_out(num_vertices, -1);
  std::vector<uint8_t> boundary_in(num_vertices, 0);
  for (size_t h = 0; h < num_halfedges; ++h) {
    if (partner[h] >= 0) continue;
    int32_t& out = boundary_out[size_t(v.to(int32_t(h)))];
    if (out >= 0 || boundary_in[size_t(v.from(int32_t(h)))]++) return false;
    out = om_halfedge[h] + 1;
  }
  for (size_t h = 0; h < num_halfedges; ++h)
    if (partner[h] < 0 && boundary_out[size_t(v.from(int32_t(h)))] < 0) return false;

  // Edges and faces made all at once (one by one, each resized every property).
  mesh.resize(num_vertices, size_t(num_edges), tris.size());
  auto he = [](int32_t h) { return OMesh::HalfedgeHandle(h); };
  parallel_for_each_index(num_halfedges, [&](size_t h) {
    if (!makes_edge[h]) return;
    mesh.set_vertex_handle(he(om_halfedge[h]), OMesh::VertexHandle(v.to(int32_t(h))));
    mesh.set_vertex_handle(he(om_halfedge[h] + 1), OMesh::VertexHandle(v.from(int32_t(h))));
  });
  parallel_for_each_index(tris.size(), [&](size_t t) {
    const auto face = OMesh::FaceHandle(int(t));
    const int32_t* hs = &om_halfedge[3 * t];
    mesh.set_halfedge_handle(face, he(hs[2]));
    for (size_t k = 0; k < 3; ++k) {
      mesh.set_face_handle(he(hs[k]), face);
      mesh.set_next_halfedge_handle(he(hs[k]), he(hs[(k + 1) % 3]));
    }
  });
  parallel_for_each_index(num_halfedges, [&](size_t h) {
    if (partner[h] >= 0) return;
    // The boundary halfedge ends at corner h's vertex and goes on out of it.
    mesh.set_next_halfedge_handle(he(om_halfedge[h] + 1), he(boundary_out[size_t(v.from(int32_t(h)))]));
  });
  // A vertex's halfedge goes out along its boundary if it has one (OpenMesh's
  // rule for boundary vertices), else out of its first triangle.
  std::vector<int32_t> vertex_halfedge = std::move(boundary_out);
  for (size_t h = 0; h < num_halfedges; ++h) {
    int32_t& out = vertex_halfedge[size_t(v.from(int32_t(h)))];
    if (out < 0) out = om_halfedge[h];
  }
  parallel_for_each_index(num_vertices, [&](size_t i) {
    mesh.set_halfedge_handle(OMesh::VertexHandle(int(i)), he(vertex_halfedge[i]));
  });
  return true;
}

void add_faces_one_by_one(OMesh& mesh, const NodeMesh& m, const std::vector<int32_t>& vertex_of_corner) {
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    auto fh =
        mesh.add_face(OMesh::VertexHandle(vertex_of_corner[3 * t]), OMesh::VertexHandle(vertex_of_corner[3 * t + 1]),
                      OMesh::VertexHandle(vertex_of_corner[3 * t + 2]));
    if (!fh.is_valid())
      throw TopologyError(located(kSource, cat("OpenMesh refused ", describe(t, m.triangles[t]),
                                               " (non-manifold or inconsistently oriented surface)")));
  }
}

} // namespace vm::detail
