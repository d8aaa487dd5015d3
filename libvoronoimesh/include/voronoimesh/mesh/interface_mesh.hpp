#pragma once
/// @file mesh/interface_mesh.hpp
/// InterfaceMesh: the patch-split OpenMesh representation of DESIGN.md ("The mesh
/// structure", and shared/notes/openmesh-probe.md "Recommended representation").
/// Every surface patch (triangles of one phase pair, connected through edges that
/// carry exactly two triangles of that pair) is its own OpenMesh component, so a
/// junction node has one OpenMesh vertex ("copy") per incident patch and fan. Node
/// arrays hold the authoritative positions and the phase sets.

#include "voronoimesh/core/pooled_lists.hpp"
#include "voronoimesh/core/types.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"
#include "voronoimesh/mesh/omesh.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace vm {

namespace detail {

/// An OMesh on the heap: copied deeply, moved by its pointer. OpenMesh's
/// kernels declare destructors, so an OMesh has no move operations: held by
/// value, every move of an InterfaceMesh (each `mesh = rebuilt` after an edit)
/// copied all of OpenMesh's arrays, 18 ms at 1.4M triangles.
class HeapMesh {
public:
  HeapMesh() : mesh_(std::make_unique<OMesh>()) {}
  HeapMesh(const HeapMesh& other) : mesh_(std::make_unique<OMesh>(*other.mesh_)) {}
  HeapMesh(HeapMesh&&) noexcept = default;
  HeapMesh& operator=(const HeapMesh& other) {
    if (this != &other) mesh_ = std::make_unique<OMesh>(*other.mesh_);
    return *this;
  }
  HeapMesh& operator=(HeapMesh&&) noexcept = default;
  ~HeapMesh() = default;
  OMesh& operator*() const { return *mesh_; }
  OMesh* operator->() const { return mesh_.get(); }

private:
  std::unique_ptr<OMesh> mesh_;
};

} // namespace detail

/// Sorted phase ids of a node, -1 padded. Nodes where more than
/// kMaxPhasesAtNode phases meet are refused (TopologyError).
using PhaseSet = std::array<int16_t, kMaxPhasesAtNode>;

/// Number of phases in a PhaseSet.
/// @param s the phase set
/// @return the entries that are not -1 padding
int phase_count(const PhaseSet& s);

/// A local change of an InterfaceMesh's triangles (InterfaceMesh::edit_in_place()).
struct LocalEdit {
  std::vector<int32_t> removed_faces;                ///< OpenMesh faces that go, distinct
  /// OpenMesh faces that change corners but keep their index (a flip, a node
  /// renamed by a merge): added[i] takes the place of rewritten_faces[i].
  /// Distinct, none among removed_faces, at most as many as `added`.
  std::vector<int32_t> rewritten_faces;
  std::vector<std::array<int32_t, 3>> added;         ///< triangles that come, node ids in orientation order
  std::vector<PhasePair> added_pairs;                ///< the phase pair of each added triangle
  std::vector<Vec3> new_nodes;                       ///< nodes num_nodes(), num_nodes() + 1, ... that come
  std::vector<int32_t> removed_nodes;                ///< nodes the edit leaves without a triangle that go, distinct
  /// Nodes the edit puts elsewhere (a collapse target moved onto the box),
  /// distinct, none removed; their box faces follow as a build finds them.
  std::vector<int32_t> placed_nodes;
  std::vector<Vec3> placed_at; ///< where each of placed_nodes goes
};

/// How edit_in_place() renumbered: each removed face's (node's) slot taken by
/// the last one (SlotMoves; a rewritten face counts as kept and moves when it
/// is the last), then the added faces past the rewritten ones (new nodes)
/// appended in order. Arrays by face (node) follow by replaying the moves,
/// then appending.
struct EditMoves {
  std::vector<SlotMove> faces; ///< moves of faces, in the order made
  std::vector<SlotMove> nodes; ///< moves of nodes, in the order made
};

/// The mesh the improvement passes work on (see the file comment); NodeMesh in, NodeMesh out.
class InterfaceMesh {
public:
  /// Builds the patch-split mesh.
  /// @param m the node-level mesh
  /// @return the patch-split mesh, with the same nodes, triangles and phases
  /// @throws TopologyError if OpenMesh refuses a face (which means the input is not a valid interface
  ///         mesh), naming the triangle; also for a node id out of range, a repeated node, a bad phase
  ///         pair, a pair count that differs from the triangle count, or more than 8 phases at a node
  static InterfaceMesh from_node_mesh(const NodeMesh& m);
  /// Makes this mesh the patch-split mesh of `m`, an edit of it (merged,
  /// dropped and added nodes and triangles, as the collapses and the remesh
  /// pass make on to_node_mesh()): what from_node_mesh(m) returns, with the
  /// work for the nodes whose triangles did not change carried over (their
  /// phases, corner classes, glued edges and neighbours) instead of done again,
  /// in OpenMesh's arrays of this mesh, which stay allocated: a mesh built
  /// beside it in fresh memory spent most of its linking on page faults (on
  /// 10,000 grains, 4.2M triangles: 0.4-0.9 s of a 0.9-1.6 s rebuild) and
  /// held both meshes at once. This mesh's triangles() and triangle_copies()
  /// must be current. Where more than a third of the nodes changed, or the
  /// maps are no edit of this mesh, it is built as from_node_mesh(m) builds it.
  /// @param m            the edited mesh
  /// @param triangle_was the triangle of this mesh each triangle of `m` was, -1 for a new one
  /// @param node_was     the node of this mesh each node of `m` was, -1 for a new one; increasing where
  ///                     not -1 (the order of the nodes kept is kept)
  /// @throws TopologyError as from_node_mesh(m); the mesh is then unusable
  void apply_edit(const NodeMesh& m, std::span<const int32_t> triangle_was, std::span<const int32_t> node_was);
  /// Makes a local edit in place (docs/edits-in-place.md): the removed faces
  /// go from OpenMesh by swap-removal, the added ones come through
  /// add_face(), the rewritten ones into their old slots, and every node they
  /// touch gets the copies, phases and
  /// neighbours from_node_mesh() would give it, by the same rule (the corner
  /// classes of its triangles); nodes the edit leaves untouched keep theirs.
  /// The mesh is then what from_node_mesh() makes of the edited triangles,
  /// with other face and node numbers (`moves`).
  /// @param edit  the change; new nodes are numbered from num_nodes() before the removed ones go
  /// @param moves receives the renumbering
  /// @return false, with the mesh untouched, where an edit would join two copies of a node into
  ///         one fan or split one copy's fan in two (OpenMesh cannot follow in place: rebuild)
  /// @throws TopologyError for an added triangle with a repeated or unknown node (the mesh
  ///         untouched), for a node with more phases than a PhaseSet holds or a triangle
  ///         OpenMesh refuses (the mesh then unusable); std::invalid_argument, the mesh
  ///         untouched, for a removed node that is none or keeps a triangle.
  bool edit_in_place(const LocalEdit& edit, EditMoves& moves);
  /// The node-level mesh back (node order and triangle order preserved).
  NodeMesh to_node_mesh() const;
  /// The node-level mesh of some faces only: they are its triangles, in the
  /// order given, and their corners its nodes, numbered in the order of their
  /// ids here (a part of the mesh to try edits on without a copy of all of it).
  /// @param faces OpenMesh face indices, ascending, each once
  /// @param nodes receives the node here of each node of the part, ascending
  NodeMesh to_node_mesh(std::span<const int32_t> faces, std::vector<int32_t>& nodes) const;

  size_t num_nodes() const { return pos_.size(); }         ///< nodes (geometric points)
  size_t num_triangles() const { return mesh_->n_faces(); } ///< triangles of every patch

  /// The patch-split OpenMesh mesh, read-only.
  const OMesh& omesh() const { return *mesh_; }
  /// Node of an OpenMesh vertex (copy).
  /// @param v an OpenMesh vertex of omesh()
  int32_t node(OMesh::VertexHandle v) const { return mesh_->property(node_, v); }
  /// Phase pair of an OpenMesh face.
  /// @param f an OpenMesh face of omesh()
  PhasePair pair(OMesh::FaceHandle f) const;
  /// OpenMesh vertices (copies) of node n.
  /// @param n a node id, in [0, num_nodes())
  /// @return the indices of its OpenMesh vertices
  std::span<const int32_t> copies(int32_t n) const { return copies_.at(size_t(n)); }

  /// Node positions (authoritative; OpenMesh points mirror them).
  const std::vector<Vec3>& positions() const { return pos_; }
  /// A number that every change of the positions or the triangles replaces
  /// (moves, placed nodes, a build or an edit, the OpenMesh mesh handed out for
  /// topology changes), never the same for two states in one process (a copy
  /// keeps it): what a check found at version v still holds while version() is v
  /// (CrossingGuard::checked_at()).
  uint64_t version() const { return version_; }
  /// triangle_quality() of every face (by OpenMesh face index), as of the
  /// positions now and the faces as triangles() has them. The guard's commit,
  /// the flip pass and the pipeline's stopping rule each ask it every
  /// iteration: it is computed in full only after moves (move_nodes()) or a
  /// rebuild of the adjacency, and kept up to date through place_nodes() and
  /// faces_changed(). Not to be asked from two threads at once.
  const std::vector<double>& qualities() const;

  // --- For the improvement passes ---------------------------------------------

  /// Moves every node by `delta` (one entry per node) and mirrors the new
  /// positions into the OpenMesh points, in parallel. The only way positions
  /// change, so point() can never go stale (openmesh-probe.md, pitfall 4).
  /// @param delta the displacement of every node, one entry per node
  void move_nodes(const std::vector<Vec3>& delta);
  /// Puts each node nodes[i] exactly at positions[i] (to undo a move bit for bit).
  /// @param nodes     the nodes to place
  /// @param positions their new positions, one per entry of `nodes`
  void place_nodes(std::span<const int32_t> nodes, std::span<const Vec3> positions);
  /// The faces with a corner at one of `nodes`, each once, in ascending order.
  /// @param nodes node ids, in [0, num_nodes())
  /// @return OpenMesh face indices
  std::vector<int32_t> faces_at(std::span<const int32_t> nodes) const;
  /// The OpenMesh mesh, for topology changes (flips). Call faces_changed() or
  /// topology_changed() afterwards.
  OMesh& omesh_for_topology() {
    version_ = next_version();
    return *mesh_;
  }
  /// Rebuilds the node adjacency and triangles() after topology changes.
  void topology_changed() {
    version_ = next_version();
    build_adjacency();
  }
  /// After local topology changes (flips) that changed only `faces`: updates
  /// triangles(), triangle_copies() and the adjacency of the nodes those faces
  /// had or have, where topology_changed() rebuilds them all.
  /// @param faces the OpenMesh faces changed since the last update, in any order (repeats allowed)
  void faces_changed(std::span<const int32_t> faces);

  /// Neighbouring nodes of node n across all its copies, sorted (as of the last
  /// topology_changed()).
  /// @param n a node id, in [0, num_nodes())
  std::span<const int32_t> neighbours(int32_t n) const {
    return adj_.at(size_t(n));
  }
  /// True when nodes a and b share an edge in any patch (always current).
  /// @param a a node id
  /// @param b another node id
  bool adjacent(int32_t a, int32_t b) const;
  /// Faces of the domain box each node lies on: bit 2a for the min side of axis
  /// a, bit 2a+1 for the max side (within 1e-9 of the box diagonal).
  const std::vector<uint8_t>& box_faces() const { return box_; }
  /// The nodes of face f in its orientation order (node-level triangle f).
  /// @param f an OpenMesh face of omesh()
  std::array<int32_t, 3> face_nodes(OMesh::FaceHandle f) const;
  /// face_nodes() of every face, in one array for loops over all triangles (as
  /// of the last topology_changed(); between flips, ask face_nodes()).
  const std::vector<std::array<int32_t, 3>>& triangles() const { return triangles_; }
  /// The copy (OpenMesh vertex index, see copies()) at each corner of
  /// triangles(): two triangles with the same copy at a corner lie in one fan
  /// of one patch (as of the last topology_changed()).
  const std::vector<std::array<int32_t, 3>>& triangle_copies() const { return triangle_copies_; }
  /// True when node a's phases and box faces are all among node b's: b lies on
  /// every surface, curve and box face a lies on.
  /// @param a the node whose constraints are looked for
  /// @param b the node that must have them all
  bool constraints_within(int32_t a, int32_t b) const;
  /// Calls f(a, b) for every triangle at node n, with (n, a, b) in the
  /// triangle's orientation order.
  /// @param n a node id, in [0, num_nodes())
  /// @param f called as f(int32_t a, int32_t b) once per triangle at n
  template <class F> void for_each_triangle_at(int32_t n, F&& f) const;
  const std::vector<PhaseSet>& phases() const { return phases_; }          ///< phases meeting at each node
  const Box& domain() const { return domain_; }                            ///< the domain box
  const std::vector<std::string>& phase_names() const { return names_; } ///< as NodeMesh::phase_names
  /// The phase outside the box of a closed mesh, or -1 (NodeMesh::outside_phase).
  int32_t outside_phase() const { return outside_; }
  /// True when phase p is among node n's phases.
  /// @param n a node id, in [0, num_nodes())
  /// @param p a phase id
  bool has_phase(int32_t n, int32_t p) const;

private:
  /// A NodeMesh with this mesh's domain and phase tables, and no nodes or triangles.
  NodeMesh without_nodes() const;
  static uint64_t next_version(); ///< a version() no mesh of this process had
  /// The nodes, the OpenMesh vertices and faces of `m`: node n's copies are
  /// the vertices copy_off[n] to copy_off[n + 1] - 1, face t is triangle t,
  /// with the vertex of each corner (3t + k) and the glued partner of each
  /// halfedge as given; through add_face() one by one when `face_by_face`
  /// (detail::some_edge_joins_vertices_twice()) or when the classes cannot be
  /// linked otherwise.
  void link(const NodeMesh& m, const std::vector<int32_t>& copy_off, const std::vector<int32_t>& vertex_of_corner,
            const std::vector<int32_t>& partner, bool face_by_face);
  /// from_node_mesh(m) into this mesh: its OpenMesh arrays emptied, and
  /// refilled in the memory they had (link()).
  void build(const NodeMesh& m);
  void build_adjacency();
  size_t valence_of(size_t v) const; ///< summed over its copies
  /// The nodes next to node v over all its copies, sorted, written to `out`
  /// (room for valence_of(v)); returns how many.
  size_t ring_of(size_t v, int32_t* out) const;
  void read_face(size_t f);       ///< triangles_[f] and triangle_copies_[f] from OpenMesh
  /// The neighbours of `nodes` (distinct) from their faces now, in parallel.
  void refresh_rings(std::span<const int32_t> nodes);
  /// The phases of node n from its faces now.
  void refresh_phases(size_t n);
  /// The last node takes node n's id (n has no copies left); returns its old id.
  int32_t fill_node_slot(int32_t n);
  void mirror_position(size_t n); ///< node n's position into the points of its copies, and its box faces
  void find_box_faces();

  detail::HeapMesh mesh_;
  OpenMesh::VPropHandleT<int32_t> node_;
  OpenMesh::FPropHandleT<OpenMesh::Vec2s> pair_;
  std::vector<Vec3> pos_;
  std::vector<PhaseSet> phases_;
  /// Each node's OpenMesh vertices: lists that can grow and shrink, for
  /// edits that give a node copies or take them away (docs/edits-in-place.md).
  detail::PooledLists<int32_t> copies_;
  detail::PooledLists<int32_t> adj_; ///< each node's neighbours, sorted
  std::vector<std::array<int32_t, 3>> triangles_, triangle_copies_;
  mutable std::vector<double> quality_; ///< qualities(), when quality_current_
  mutable bool quality_current_ = false;
  void update_qualities(std::span<const int32_t> faces); ///< of these distinct faces, if the rest are current
  double quality_of(size_t f) const;                      ///< triangle_quality() of face f now
  std::vector<uint8_t> box_;
  Box domain_;
  double grid_spacing_ = 0; // NodeMesh::grid_spacing, kept for to_node_mesh()
  std::vector<std::string> names_;
  std::vector<int32_t> labels_; // NodeMesh::phase_labels, kept for to_node_mesh()
  std::vector<std::optional<Rgb>> colors_; // NodeMesh::phase_colors, likewise
  int32_t outside_ = -1;
  /// Linked by add_face() one by one (link()): apply_edit() then builds
  /// anew, as the flag of the edited mesh depends on all of it.
  bool face_by_face_ = false;
  uint64_t version_ = next_version();
};

template <class F> void InterfaceMesh::for_each_triangle_at(int32_t n, F&& f) const {
  for (int32_t c : copies(n)) {
    const auto v = OMesh::VertexHandle(c);
    for (auto h : mesh_->voh_range(v)) {
      if (mesh_->is_boundary(h)) continue;
      const auto next = mesh_->next_halfedge_handle(h);
      f(node(mesh_->to_vertex_handle(h)), node(mesh_->to_vertex_handle(next)));
    }
  }
}

} // namespace vm
