#pragma once
/// @file mesh.hpp
/// InterfaceMesh: the patch-split OpenMesh representation of DESIGN.md ("The mesh
/// structure", and shared/notes/openmesh-probe.md "Recommended representation").
/// Every surface patch (triangles of one phase pair, connected through edges that
/// carry exactly two triangles of that pair) is its own OpenMesh component, so a
/// junction node has one OpenMesh vertex ("copy") per incident patch and fan. Node
/// arrays hold the authoritative positions and the phase sets.

#include "voronoimesh/node_mesh.hpp"
#include "voronoimesh/types.hpp"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace vm {

/// OpenMesh traits: double-precision points.
struct MeshTraits : public OpenMesh::DefaultTraitsDouble {};
using OMesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;

/// Sorted phase ids of a node, -1 padded. Nodes where more than 8 phases meet
/// are refused (TopologyError).
using PhaseSet = std::array<int16_t, 8>;

/// Number of phases in a PhaseSet.
int phase_count(const PhaseSet& s);

class InterfaceMesh {
public:
  /// Builds the patch-split mesh. Throws TopologyError if OpenMesh refuses a face
  /// (which means the input is not a valid interface mesh), naming the triangle.
  static InterfaceMesh from_node_mesh(const NodeMesh& m);
  /// The node-level mesh back (node order and triangle order preserved).
  NodeMesh to_node_mesh() const;

  size_t num_nodes() const { return pos_.size(); }
  size_t num_triangles() const { return mesh_.n_faces(); }

  const OMesh& omesh() const { return mesh_; }
  /// Node of an OpenMesh vertex (copy).
  int32_t node(OMesh::VertexHandle v) const { return mesh_.property(node_, v); }
  /// Phase pair of an OpenMesh face.
  PhasePair pair(OMesh::FaceHandle f) const;
  /// OpenMesh vertices (copies) of node n.
  std::span<const int32_t> copies(int32_t n) const {
    return {copy_v_.data() + copy_off_[n], size_t(copy_off_[n + 1] - copy_off_[n])};
  }

  const std::vector<Vec3>& positions() const { return pos_; }
  const std::vector<PhaseSet>& phases() const { return phases_; }
  const Box& domain() const { return domain_; }
  const std::vector<std::string>& phase_names() const { return names_; }

private:
  OMesh mesh_;
  OpenMesh::VPropHandleT<int32_t> node_;
  OpenMesh::FPropHandleT<OpenMesh::Vec2s> pair_;
  std::vector<Vec3> pos_;
  std::vector<PhaseSet> phases_;
  std::vector<int32_t> copy_off_, copy_v_;
  Box domain_;
  std::vector<std::string> names_;
};

} // namespace vm
