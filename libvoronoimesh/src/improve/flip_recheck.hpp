#pragma once
/// @file improve/flip_recheck.hpp
/// Which triangles the crossing check after each attempt of the flip pass must
/// test.
///
/// The flip pass flips, checks the flipped triangles for crossings, and, if
/// any flip crossed, undoes every flip and tries again without the culprits.
/// The new attempt mostly makes the same flips: testing every flipped triangle
/// again costs as much as the first check, for the few triangles that differ.
/// A crossing is a property of two triangles' nodes (flips move none), so a
/// pair of triangles both present, unchanged, at the last check was tested
/// then, or is older than the pass. FlipRecheck keeps what the last check saw
/// and names the triangles whose pairs may be new.

#include "voronoimesh/mesh/interface_mesh.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace vm::detail {

class FlipRecheck {
public:
  /// The faces (one flag each) whose pairs the check of the mesh as it is must
  /// test, given the faces the flips of this attempt changed. The first
  /// attempt: those. Later ones: faces that differ from the last check, faces
  /// in a crossing found then (they may still cross), and faces flipped now
  /// that were not then. The last are a guard for a face whose flips brought
  /// back the very triangle it had before the pass, which random flips in the
  /// tests never make: its crossings with triangles as old as the pass were
  /// never tested, and the mesh need not have been free of crossings before.
  /// The check then finds every crossing pair with a face flipped in this
  /// attempt, as a check of all of them would, so the culprits are the same.
  std::vector<uint8_t> faces_to_test(const InterfaceMesh& mesh, const std::vector<uint8_t>& flipped) const;
  /// Records the check just made: the mesh, the faces flipped in this attempt,
  /// and the crossing pairs found.
  void checked(const InterfaceMesh& mesh, std::vector<uint8_t> flipped,
               const std::vector<std::array<int32_t, 2>>& crossings);

private:
  std::vector<std::array<int32_t, 3>> triangles_; ///< by face, as checked (empty: no check yet)
  std::vector<uint8_t> flipped_;                  ///< faces a flip of that attempt changed
  std::vector<uint8_t> crossing_;                 ///< faces in a crossing pair found then
};

} // namespace vm::detail
