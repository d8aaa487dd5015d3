#include "voronoimesh/pass.hpp"

#include "voronoimesh/guard.hpp"

namespace vm {

std::vector<Vec3>& PassContext::displacement() {
  if (!pending) {
    delta.assign(mesh.num_nodes(), Vec3::Zero());
    pending = true;
  }
  return delta;
}

void PassContext::commit() {
  if (!pending) return;
  if (guard_crossings) undone_moves += commit_without_crossings(mesh, delta, field).undone_nodes;
  else mesh.move_nodes(delta);
  pending = false;
}

} // namespace vm
