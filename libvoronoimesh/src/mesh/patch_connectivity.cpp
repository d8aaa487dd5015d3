#include "mesh/patch_connectivity.hpp"

#include "core/parallel.hpp"

#include <algorithm>

namespace vm::detail {

namespace {

/// Corner c = 3t + k is corner k of triangle t, and halfedge h = 3t + k starts
/// there (mesh/topology.hpp), so a halfedge's vertices are those of its corners.
struct CornerVertices {
  const std::vector<int32_t>& of_corner;
  int32_t from(int32_t h) const { return of_corner[size_t(h)]; }
  int32_t to(int32_t h) const { return of_corner[size_t(3 * (h / 3) + (h % 3 + 1) % 3)]; }
};

/// True when two of the unglued halfedges of node-edge e join the same two
/// vertices: add_face() would glue or refuse them, which needs its lookups.
bool joins_vertices_twice(const EdgeTable& et, size_t e, const CornerVertices& v) {
  const auto hs = et.halfedges(e);
  auto ends = [&](int32_t h) { // as values: std::minmax would keep references to temporaries
    const int32_t from = v.from(h), to = v.to(h);
    return std::pair{std::min(from, to), std::max(from, to)};
  };
  for (size_t i = 0; i < hs.size(); ++i)
    for (size_t j = i + 1; j < hs.size(); ++j)
      if (ends(hs[i]) == ends(hs[j])) return true;
  return false;
}

} // namespace

bool connect_patch_faces(OMesh& mesh, const Triangles& tris, const std::vector<int32_t>& vertex_of_corner,
                         const EdgeTable& et, const std::vector<uint8_t>& glued) {
  const CornerVertices v{vertex_of_corner};
  const size_t num_halfedges = 3 * tris.size(), num_vertices = mesh.n_vertices();
  std::vector<int32_t> edge_of(num_halfedges);
  std::vector<uint8_t> twice(et.size(), 0);
  parallel_for_each_index(et.size(), [&](size_t e) {
    for (int32_t h : et.halfedges(e)) edge_of[size_t(h)] = int32_t(e);
    twice[e] = !glued[e] && joins_vertices_twice(et, e, v);
  });
  if (std::find(twice.begin(), twice.end(), 1) != twice.end()) return false;

  // OpenMesh halfedge of each triangle halfedge: add_face() makes a triangle's
  // missing edges in corner order, the first halfedge running its way, so a
  // glued edge's second triangle takes the opposite one.
  std::vector<int32_t> om_halfedge(num_halfedges), om_edge_of(et.size(), -1), first_halfedge;
  first_halfedge.reserve(num_halfedges);
  for (size_t h = 0; h < num_halfedges; ++h) {
    int32_t& edge = om_edge_of[size_t(edge_of[h])];
    if (glued[size_t(edge_of[h])] && edge >= 0) {
      om_halfedge[h] = 2 * edge + 1;
      continue;
    }
    edge = int32_t(first_halfedge.size());
    om_halfedge[h] = 2 * edge;
    first_halfedge.push_back(int32_t(h));
  }

  // Boundary halfedges run opposite the unglued ones. A vertex whose fan is
  // open has one going out, where its boundary loop continues; a second one
  // means a second gap, which only add_face() can link; so does one coming in
  // without one going out.
  std::vector<int32_t> boundary_out(num_vertices, -1);
  std::vector<uint8_t> boundary_in(num_vertices, 0);
  for (size_t h = 0; h < num_halfedges; ++h) {
    if (glued[size_t(edge_of[h])]) continue;
    int32_t& out = boundary_out[size_t(v.to(int32_t(h)))];
    if (out >= 0 || boundary_in[size_t(v.from(int32_t(h)))]++) return false;
    out = om_halfedge[h] + 1;
  }
  for (size_t h = 0; h < num_halfedges; ++h)
    if (!glued[size_t(edge_of[h])] && boundary_out[size_t(v.from(int32_t(h)))] < 0) return false;

  for (int32_t h : first_halfedge)
    mesh.new_edge(OMesh::VertexHandle(v.from(h)), OMesh::VertexHandle(v.to(h)));
  for (size_t t = 0; t < tris.size(); ++t) mesh.new_face();
  auto he = [](int32_t h) { return OMesh::HalfedgeHandle(h); };
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
    if (glued[size_t(edge_of[h])]) return;
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

} // namespace vm::detail
