// InterfaceMesh::edit_in_place(): a local edit that costs what it changes
// (docs/edits-in-place.md, step 3).
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/mesh/interface_mesh.hpp"

#include "mesh/node_rings.hpp"
#include "mesh/patch_connectivity.hpp"
#include "mesh/topology.hpp"

#include <algorithm>
#include <cassert>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace vm {

namespace {

/// The triangles at the nodes an edit touches, after it: the faces kept there
/// (first) and the added triangles, on local node ids.
struct CutOut {
  std::vector<int32_t> nodes;       ///< the global id of each local node, ascending
  std::vector<int32_t> kept_faces;  ///< OpenMesh faces kept at the touched nodes, ascending
  detail::Triangles triangles;      ///< kept faces, then added triangles
  std::vector<PhasePair> pairs;     ///< of `triangles`
  int32_t local(int32_t n) const {
    return int32_t(std::lower_bound(nodes.begin(), nodes.end(), n) - nodes.begin());
  }
};

std::vector<int32_t> sorted(std::vector<int32_t> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

/// Where each old element named by `moves` is after them: -1 for one removed.
std::unordered_map<int32_t, int32_t> where_now(const std::vector<SlotMove>& moves) {
  std::unordered_map<int32_t, int32_t> held; // slot -> the old element there, where moves changed it
  std::unordered_map<int32_t, int32_t> now;
  auto old_at = [&](int32_t slot) {
    const auto it = held.find(slot);
    return it == held.end() ? slot : it->second;
  };
  for (const SlotMove& m : moves) {
    now[old_at(m.to)] = -1;
    const int32_t moved = old_at(m.from);
    held.erase(m.from);
    if (m.from != m.to) held[m.to] = moved;
  }
  for (const auto& [slot, old] : held) now[old] = slot;
  return now;
}

} // namespace

bool InterfaceMesh::edit_in_place(const LocalEdit& edit, EditMoves& moves) {
  const size_t old_nodes = pos_.size(), all_nodes = old_nodes + edit.new_nodes.size();
  if (edit.added_pairs.size() != edit.added.size())
    throw TopologyError("in-place edit: " + std::to_string(edit.added.size()) + " triangles but " +
                        std::to_string(edit.added_pairs.size()) + " phase pairs");
  for (size_t i = 0; i < edit.added.size(); ++i)
    if (!detail::well_formed(edit.added[i], all_nodes))
      throw TopologyError("in-place edit: added triangle " + std::to_string(i) + " repeats a node or names none");
  if (edit.placed_at.size() != edit.placed_nodes.size())
    throw std::invalid_argument("in-place edit: " + std::to_string(edit.placed_nodes.size()) + " nodes placed at " +
                                std::to_string(edit.placed_at.size()) + " points");
  for (const int32_t n : edit.placed_nodes)
    if (n < 0 || size_t(n) >= old_nodes)
      throw std::invalid_argument("in-place edit: placed node " + std::to_string(n) + " is not a node");
  if (edit.rewritten_faces.size() > edit.added.size())
    throw TopologyError("in-place edit: " + std::to_string(edit.rewritten_faces.size()) + " faces rewritten by " +
                        std::to_string(edit.added.size()) + " triangles");
  std::vector<int32_t> going = edit.removed_faces; // every face whose corners go or change
  going.insert(going.end(), edit.rewritten_faces.begin(), edit.rewritten_faces.end());

  // The nodes the edit touches, and the triangles at them after it.
  std::vector<int32_t> touched;
  for (const int32_t f : going)
    for (const int32_t n : triangles_[size_t(f)]) touched.push_back(n);
  for (const auto& t : edit.added) touched.insert(touched.end(), t.begin(), t.end());
  touched = sorted(std::move(touched));
  CutOut cut;
  {
    const auto first_new = std::lower_bound(touched.begin(), touched.end(), int32_t(old_nodes));
    const std::vector<int32_t> at = faces_at(std::span(touched.begin(), first_new));
    const std::vector<int32_t> removed = sorted(going);
    std::set_difference(at.begin(), at.end(), removed.begin(), removed.end(), std::back_inserter(cut.kept_faces));
  }
  for (const int32_t f : cut.kept_faces) {
    cut.triangles.push_back(triangles_[size_t(f)]);
    cut.pairs.push_back(pair(OMesh::FaceHandle(f)));
  }
  cut.triangles.insert(cut.triangles.end(), edit.added.begin(), edit.added.end());
  cut.pairs.insert(cut.pairs.end(), edit.added_pairs.begin(), edit.added_pairs.end());
  for (const auto& t : cut.triangles) cut.nodes.insert(cut.nodes.end(), t.begin(), t.end());
  cut.nodes = sorted(std::move(cut.nodes));
  for (auto& t : cut.triangles)
    for (int32_t& n : t) n = cut.local(n);
  // A removed node must be left without triangles: none in the cut-out, and
  // none where the edit does not touch it. Checked before anything changes.
  for (const int32_t n : edit.removed_nodes) {
    if (n < 0 || size_t(n) >= all_nodes)
      throw std::invalid_argument("in-place edit: removed node " + std::to_string(n) + " is not a node");
    const bool untouched = !std::binary_search(touched.begin(), touched.end(), n);
    if (std::binary_search(cut.nodes.begin(), cut.nodes.end(), n) ||
        (untouched && size_t(n) < old_nodes && !copies(n).empty()))
      throw std::invalid_argument("in-place edit: removed node " + std::to_string(n) + " keeps a triangle");
  }

  // Each touched node's corner classes, as from_node_mesh() finds them: the
  // cut-out holds every triangle on each edge at a touched node, so the glue
  // there is as in the whole mesh. A class keeps the copy its kept faces share.
  const detail::NodeTriangles nt = detail::node_triangles(cut.nodes.size(), cut.triangles);
  const std::vector<int32_t> partner = detail::glued_partners(detail::edge_table(cut.triangles, nt), cut.triangles, cut.pairs);
  const auto num_kept = int32_t(cut.kept_faces.size());
  struct Class {
    int32_t node;
    int32_t copy; // the old copy it keeps, or -1 for a new one
  };
  std::vector<Class> classes;
  std::vector<int32_t> class_of_added_corner(3 * edit.added.size());
  std::vector<int32_t> parent, corner_at, class_at;
  std::unordered_map<int32_t, int32_t> class_of_copy;
  for (const int32_t n : touched) {
    if (!std::binary_search(cut.nodes.begin(), cut.nodes.end(), n)) continue; // left without triangles
    const int32_t ln = cut.local(n);
    const auto ts = nt.of(size_t(ln));
    corner_at.resize(ts.size());
    class_at.resize(ts.size());
    const int32_t count = detail::corner_classes_at(ln, ts, cut.triangles, partner, parent, corner_at.data(), class_at.data());
    const auto base = int32_t(classes.size());
    classes.resize(classes.size() + size_t(count), Class{n, -1});
    for (size_t i = 0; i < ts.size(); ++i) {
      const int32_t t = ts[i], k = corner_at[i] % 3, c = base + class_at[i];
      if (t >= num_kept) {
        class_of_added_corner[size_t(3 * (t - num_kept) + k)] = c;
        continue;
      }
      const int32_t copy = triangle_copies_[size_t(cut.kept_faces[size_t(t)])][size_t(k)];
      const auto [it, first] = class_of_copy.emplace(copy, c);
      if (!first && it->second != c) return false; // one copy's fan split in two
      Class& cls = classes[size_t(c)];
      if (cls.copy >= 0 && cls.copy != copy) return false; // two copies joined in one fan
      cls.copy = copy;
    }
  }

  // The edit: nodes placed (before the faces that come read their points),
  // faces out of OpenMesh, our arrays by face after them.
  version_ = next_version();
  for (size_t i = 0; i < edit.placed_nodes.size(); ++i) {
    const auto n = size_t(edit.placed_nodes[i]);
    pos_[n] = edit.placed_at[i];
    mirror_position(n); // and its box faces
  }
  std::vector<std::pair<int32_t, int32_t>> node_of_copy; // of the copies at removed faces
  for (const int32_t f : going)
    for (size_t k = 0; k < 3; ++k) node_of_copy.emplace_back(triangle_copies_[size_t(f)][k], triangles_[size_t(f)][k]);
  std::sort(node_of_copy.begin(), node_of_copy.end());
  SlotMoves removal;
  mesh_->remove_faces(edit.removed_faces, removal, edit.rewritten_faces);
  const bool qualities_kept = quality_current_ && quality_.size() == triangles_.size();
  for (const SlotMove& m : removal.faces) {
    triangles_[size_t(m.to)] = triangles_[size_t(m.from)];
    triangle_copies_[size_t(m.to)] = triangle_copies_[size_t(m.from)];
    triangles_.pop_back();
    triangle_copies_.pop_back();
    if (qualities_kept) {
      quality_[size_t(m.to)] = quality_[size_t(m.from)];
      quality_.pop_back();
    }
  }
  moves.faces = removal.faces;
  std::vector<int32_t> hole_at(edit.rewritten_faces); // where each rewritten face's slot went
  {
    const std::unordered_map<int32_t, int32_t> face_now = where_now(removal.faces);
    for (int32_t& f : hole_at)
      if (const auto it = face_now.find(f); it != face_now.end()) f = it->second;
  }
  // The copies follow the vertices: the ones gone leave their node's list
  // first, then the moved ones are renamed (a moved vertex's new index is
  // below every moved one's old index, so no renaming meets another).
  const std::unordered_map<int32_t, int32_t> copy_now = where_now(removal.vertices);
  for (const auto& [old, now] : copy_now)
    if (now < 0) {
      const auto at = std::lower_bound(node_of_copy.begin(), node_of_copy.end(), std::pair{old, INT32_MIN});
      copies_.erase_id(size_t(at->second), old);
    }
  for (const auto& [old, now] : copy_now)
    if (now >= 0) {
      const auto list = copies_.at(size_t(node(OMesh::VertexHandle(now))));
      *std::find(list.begin(), list.end(), old) = now;
      for (const auto f : mesh_->vf_range(OMesh::VertexHandle(now))) read_face(size_t(f.idx()));
    }

  // New nodes, then new copies, then the added faces on them.
  for (size_t i = 0; i < edit.new_nodes.size(); ++i) {
    pos_.push_back(edit.new_nodes[i]);
    phases_.emplace_back();
    box_.push_back(detail::box_faces_at(edit.new_nodes[i], domain_));
    adj_.add_list();
    copies_.add_list();
  }
  for (Class& cls : classes) {
    if (cls.copy >= 0) {
      if (const auto it = copy_now.find(cls.copy); it != copy_now.end()) cls.copy = it->second;
      continue;
    }
    const Vec3& p = pos_[size_t(cls.node)];
    const auto v = mesh_->add_vertex(OMesh::Point(p.x(), p.y(), p.z()));
    mesh_->property(node_, v) = cls.node;
    copies_.push(size_t(cls.node), v.idx());
    cls.copy = v.idx();
  }
  for (size_t i = 0; i < edit.added.size(); ++i) {
    std::array<OMesh::VertexHandle, 3> corners;
    for (size_t k = 0; k < 3; ++k) corners[k] = OMesh::VertexHandle(classes[size_t(class_of_added_corner[3 * i + k])].copy);
    const auto f = mesh_->add_face(corners.data(), 3);
    if (!f.is_valid())
      throw TopologyError("in-place edit: OpenMesh refused added triangle " + std::to_string(i) + " (nodes " +
                          std::to_string(edit.added[i][0]) + ", " + std::to_string(edit.added[i][1]) + ", " +
                          std::to_string(edit.added[i][2]) + ")");
    const PhasePair& p = edit.added_pairs[i];
    mesh_->property(pair_, f) = OpenMesh::Vec2s(int16_t(p[0]), int16_t(p[1]));
    if (i < hole_at.size()) {
      const auto slot = size_t(hole_at[i]);
      mesh_->fill_hole(int32_t(slot));
      read_face(slot);
      if (qualities_kept) quality_[slot] = quality_of(slot);
      continue;
    }
    triangles_.emplace_back();
    triangle_copies_.emplace_back();
    read_face(size_t(f.idx()));
    if (qualities_kept) quality_.push_back(quality_of(size_t(f.idx())));
  }
  quality_current_ = qualities_kept;
  if (qualities_kept && !edit.placed_nodes.empty()) update_qualities(faces_at(edit.placed_nodes));
  for (const int32_t n : touched) refresh_phases(size_t(n));
  refresh_rings(touched);

  // Nodes out, from the highest: the last one takes each slot.
  std::vector<int32_t> removed_nodes = sorted(edit.removed_nodes);
  std::reverse(removed_nodes.begin(), removed_nodes.end());
  for (const int32_t n : removed_nodes) moves.nodes.push_back({fill_node_slot(n), n});
  return true;
}

void InterfaceMesh::refresh_phases(size_t n) {
  std::vector<int32_t> phases;
  for (const int32_t c : copies(int32_t(n)))
    for (const auto f : mesh_->vf_range(OMesh::VertexHandle(c))) {
      const PhasePair p = pair(f);
      phases.insert(phases.end(), p.begin(), p.end());
    }
  phases = sorted(std::move(phases));
  detail::check_phase_count(n, phases.size());
  phases_[n] = detail::phase_set(phases);
}

int32_t InterfaceMesh::fill_node_slot(int32_t n) {
  const auto last = int32_t(pos_.size() - 1);
  assert(copies(n).empty()); // edit_in_place() checked it kept no triangle
  if (n != last) {
    pos_[size_t(n)] = pos_[size_t(last)];
    phases_[size_t(n)] = phases_[size_t(last)];
    box_[size_t(n)] = box_[size_t(last)];
    for (const int32_t w : adj_.at(size_t(last))) {
      const auto ring = adj_.at(size_t(w));
      *std::find(ring.begin(), ring.end(), last) = n;
      std::sort(ring.begin(), ring.end());
    }
    for (const int32_t c : copies(last)) {
      mesh_->property(node_, OMesh::VertexHandle(c)) = n;
      for (const auto f : mesh_->vf_range(OMesh::VertexHandle(c)))
        for (int32_t& corner : triangles_[size_t(f.idx())])
          if (corner == last) corner = n;
    }
  }
  copies_.take_last(size_t(n));
  adj_.take_last(size_t(n));
  pos_.pop_back();
  phases_.pop_back();
  box_.pop_back();
  return last;
}

} // namespace vm
