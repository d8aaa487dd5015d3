/// @file io/msh.cpp
/// Gmsh MSH 4.1 (ASCII). The model Gmsh builds from the file:
///  - a point entity at each quadruple point (holding its node and a point
///    element) and at each end of an open triple curve on the domain box
///    (holding its node only: a model vertex, not a physical point);
///  - a curve entity per triple curve, holding its inner nodes and its edges as
///    line elements, bounded by the point entities at its ends;
///  - a surface entity per phase pair, holding the remaining nodes of its
///    triangles and the triangles, bounded by the curves along its edge;
/// so each node is written once, in the entity of lowest dimension holding it.
/// Physical groups: a surface per phase pair (tag = its number, as the MEDIT
/// reference), a curve per phase triple, a point per phase set of quadruple
/// points, each named after its phases.

#include "core/text.hpp"
#include "io/output_buffer.hpp"
#include "io/phase_names.hpp"
#include "io/writers.hpp"
#include "voronoimesh/mesh/junctions.hpp"

#include <algorithm>
#include <unordered_map>

namespace vm::io::detail {

namespace {

using vm::detail::cat;
using vm::detail::ChunkedOutput;
using vm::detail::put_int;

/// Gmsh element types.
constexpr int kLine = 1, kTriangle = 2, kPoint = 15;

/// One model entity of the file.
struct Entity {
  int dim = 0;
  std::vector<int32_t> physical;     ///< physical group tags (0 or 1)
  std::vector<int32_t> bounding;     ///< signed tags of the entities one dimension down
  std::vector<int32_t> nodes;        ///< nodes classified on it, ascending
  std::vector<int32_t> elements;     ///< node ids, `element_size` per element
  int element_type = kPoint;
  size_t element_size() const { return element_type == kPoint ? 1 : element_type == kLine ? 2 : 3; }
  size_t num_elements() const { return elements.size() / element_size(); }
};

/// Physical groups, each a named phase set; tags run from 1 over all dimensions.
struct Physicals {
  std::vector<std::pair<int, std::string>> names; ///< (dim, name) by tag - 1

  void add(int dim, std::string name) { names.emplace_back(dim, std::move(name)); }
};

class MshModel {
public:
  explicit MshModel(const NodeMesh& m) : m_(m), junctions_(find_junctions(m)) {
    make_physical_surfaces();
    make_points();
    make_curves();
    make_surfaces();
    classify_nodes();
  }

  void write(ChunkedOutput& out) const {
    std::string& buf = out.text();
    buf += "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
    buf += cat("$PhysicalNames\n", physicals_.names.size(), "\n");
    for (size_t i = 0; i < physicals_.names.size(); ++i)
      buf += cat(physicals_.names[i].first, " ", i + 1, " \"", physicals_.names[i].second, "\"\n");
    buf += "$EndPhysicalNames\n";
    write_entities(buf);
    write_nodes(out);
    write_elements(out);
  }

private:
  void make_physical_surfaces() {
    pairs_ = distinct_pairs(m_);
    for (const PhasePair& p : pairs_) physicals_.add(2, phases_token(m_, p));
  }

  void make_points() {
    std::vector<int32_t> nodes = junctions_.quadruple_points;
    for (const TripleCurve& c : junctions_.curves)
      if (!c.closed() || junctions_.order(size_t(c.nodes.front())) != 3) {
        nodes.push_back(c.nodes.front());
        nodes.push_back(c.nodes.back());
      }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    // A physical point per phase set of quadruple points, in the order of the sets.
    std::vector<std::vector<int32_t>> sets;
    for (int32_t n : junctions_.quadruple_points) sets.emplace_back(phases_of(n));
    std::sort(sets.begin(), sets.end());
    sets.erase(std::unique(sets.begin(), sets.end()), sets.end());
    const int32_t first = int32_t(physicals_.names.size()) + 1;
    for (const auto& s : sets) physicals_.add(0, phases_token(m_, s));
    for (int32_t n : nodes) {
      Entity e;
      e.dim = 0;
      e.nodes = {n};
      // Only quadruple points get a point element (and a physical group): a
      // curve's end on the box is a model vertex only. (meshio also needs every
      // element block to carry a physical group once any does.)
      if (junctions_.order(size_t(n)) >= 4) {
        e.physical.push_back(first + int32_t(std::lower_bound(sets.begin(), sets.end(), phases_of(n)) - sets.begin()));
        e.elements = {n};
      }
      point_tag_.emplace(n, int32_t(points_.size()) + 1);
      points_.push_back(std::move(e));
    }
  }

  void make_curves() {
    const std::vector<int32_t>* previous = nullptr;
    for (const TripleCurve& c : junctions_.curves) {
      if (!previous || *previous != c.phases) physicals_.add(1, phases_token(m_, c.phases));
      previous = &c.phases;
      Entity e;
      e.dim = 1;
      e.element_type = kLine;
      e.physical.push_back(int32_t(physicals_.names.size()));
      for (const auto& [end, sign] : {std::pair{c.nodes.front(), 1}, std::pair{c.nodes.back(), -1}})
        if (auto it = point_tag_.find(end); it != point_tag_.end()) e.bounding.push_back(sign * it->second);
      for (size_t i = 0; i < c.num_edges(); ++i) {
        e.elements.push_back(c.nodes[i]);
        e.elements.push_back(c.nodes[i + 1]);
      }
      curves_.push_back(std::move(e));
    }
  }

  /// Surfaces, and the curves bounding them: a curve bounds the surface of each
  /// triangle along its first edge, positively when the triangle runs along the
  /// edge in the curve's direction.
  void make_surfaces() {
    const std::vector<int32_t> index = pair_indices(m_, pairs_);
    surfaces_.resize(pairs_.size());
    for (size_t i = 0; i < pairs_.size(); ++i) {
      surfaces_[i].dim = 2;
      surfaces_[i].element_type = kTriangle;
      surfaces_[i].physical.push_back(int32_t(i) + 1);
    }
    auto key = [](int32_t a, int32_t b) { return uint64_t(uint32_t(std::min(a, b))) << 32 | uint32_t(std::max(a, b)); };
    std::unordered_map<uint64_t, int32_t> first_edge; // of each curve
    for (size_t c = 0; c < junctions_.curves.size(); ++c)
      first_edge.emplace(key(junctions_.curves[c].nodes[0], junctions_.curves[c].nodes[1]), int32_t(c));
    for (size_t t = 0; t < m_.triangles.size(); ++t) {
      const auto& tri = m_.triangles[t];
      Entity& s = surfaces_[size_t(index[t])];
      s.elements.insert(s.elements.end(), tri.begin(), tri.end());
      for (size_t k = 0; k < 3; ++k) {
        const int32_t a = tri[k], b = tri[(k + 1) % 3];
        const auto it = first_edge.find(key(a, b));
        if (it == first_edge.end()) continue;
        const int32_t tag = it->second + 1;
        const int32_t signed_tag = junctions_.curves[size_t(it->second)].nodes[0] == a ? tag : -tag;
        if (std::find(s.bounding.begin(), s.bounding.end(), signed_tag) == s.bounding.end() &&
            std::find(s.bounding.begin(), s.bounding.end(), -signed_tag) == s.bounding.end())
          s.bounding.push_back(signed_tag);
      }
    }
  }

  /// Each node goes to the entity of lowest dimension holding it: its point,
  /// else its first curve, else the surface of its first triangle.
  void classify_nodes() {
    std::vector<char> placed(m_.points.size(), 0);
    for (const Entity& e : points_) placed[size_t(e.nodes[0])] = 1;
    for (std::vector<Entity>* group : {&curves_, &surfaces_})
      for (Entity& e : *group) {
        for (int32_t n : e.elements)
          if (!placed[size_t(n)]) {
            placed[size_t(n)] = 1;
            e.nodes.push_back(n);
          }
        std::sort(e.nodes.begin(), e.nodes.end());
      }
  }

  std::vector<int32_t> phases_of(int32_t n) const {
    const auto s = junctions_.phases_at(size_t(n));
    return {s.begin(), s.end()};
  }

  /// The bounding box of the nodes of a curve's or surface's elements, as
  /// "minx miny minz maxx maxy maxz".
  std::string box_of(const Entity& e) const {
    Vec3 lo = m_.points[size_t(e.elements[0])], hi = lo;
    for (int32_t n : e.elements) {
      lo = lo.cwiseMin(m_.points[size_t(n)]);
      hi = hi.cwiseMax(m_.points[size_t(n)]);
    }
    std::string s;
    vm::detail::put_point(s, lo);
    s += ' ';
    vm::detail::put_point(s, hi);
    return s;
  }

  static void put_tags(std::string& buf, const std::vector<int32_t>& tags) {
    buf += cat(" ", tags.size());
    for (int32_t t : tags) buf += cat(" ", t);
  }

  void write_entities(std::string& buf) const {
    buf += cat("$Entities\n", points_.size(), " ", curves_.size(), " ", surfaces_.size(), " 0\n");
    for (size_t i = 0; i < points_.size(); ++i) {
      buf += cat(i + 1, " ");
      vm::detail::put_point(buf, m_.points[size_t(points_[i].nodes[0])]);
      put_tags(buf, points_[i].physical);
      buf += '\n';
    }
    for (const std::vector<Entity>* group : {&curves_, &surfaces_})
      for (size_t i = 0; i < group->size(); ++i) {
        const Entity& e = (*group)[i];
        // An entity without elements (a pair no triangle has) cannot occur: pairs come from the triangles.
        buf += cat(i + 1, " ", box_of(e));
        put_tags(buf, e.physical);
        put_tags(buf, e.bounding);
        buf += '\n';
      }
    buf += "$EndEntities\n";
  }

  template <class Visit>
  void for_each_entity(Visit visit) const {
    for (const std::vector<Entity>* group : {&points_, &curves_, &surfaces_})
      for (size_t i = 0; i < group->size(); ++i) visit((*group)[i], i + 1);
  }

  void write_nodes(ChunkedOutput& out) const {
    size_t count = 0, blocks = 0;
    int32_t min_tag = 0, max_tag = 0;
    for_each_entity([&](const Entity& e, size_t) {
      blocks += 1;
      if (e.nodes.empty()) return;
      min_tag = count == 0 ? e.nodes.front() + 1 : std::min(min_tag, e.nodes.front() + 1);
      max_tag = std::max(max_tag, e.nodes.back() + 1);
      count += e.nodes.size();
    });
    std::string& buf = out.text();
    buf += cat("$Nodes\n", blocks, " ", count, " ", min_tag, " ", max_tag, "\n");
    for_each_entity([&](const Entity& e, size_t tag) {
      buf += cat(e.dim, " ", tag, " 0 ", e.nodes.size(), "\n");
      for (int32_t n : e.nodes) {
        put_int(buf, n + 1);
        buf += '\n';
      }
      for (int32_t n : e.nodes) {
        vm::detail::put_point(buf, m_.points[size_t(n)]);
        buf += '\n';
        out.maybe_flush();
      }
    });
    buf += "$EndNodes\n";
  }

  void write_elements(ChunkedOutput& out) const {
    size_t count = 0, blocks = 0;
    for_each_entity([&](const Entity& e, size_t) {
      count += e.num_elements();
      blocks += e.num_elements() > 0;
    });
    std::string& buf = out.text();
    buf += cat("$Elements\n", blocks, " ", count, " ", count ? 1 : 0, " ", count, "\n");
    size_t next = 1;
    for_each_entity([&](const Entity& e, size_t tag) {
      if (e.num_elements() == 0) return;
      buf += cat(e.dim, " ", tag, " ", e.element_type, " ", e.num_elements(), "\n");
      for (size_t i = 0; i < e.elements.size(); i += e.element_size()) {
        put_int(buf, (long long)next++);
        for (size_t k = 0; k < e.element_size(); ++k) {
          buf += ' ';
          put_int(buf, e.elements[i + k] + 1);
        }
        buf += '\n';
        out.maybe_flush();
      }
    });
    buf += "$EndElements\n";
  }

  const NodeMesh& m_;
  const Junctions junctions_;
  std::vector<PhasePair> pairs_;
  Physicals physicals_;
  std::unordered_map<int32_t, int32_t> point_tag_; // node -> point entity tag
  std::vector<Entity> points_, curves_, surfaces_;
};

} // namespace

void write_msh(vm::detail::StagedOutputs& staged, const NodeMesh& m, const std::string& path) {
  const MshModel model(m);
  vm::detail::write_in_chunks(staged, path, [&](ChunkedOutput& out) { model.write(out); });
}

} // namespace vm::io::detail
