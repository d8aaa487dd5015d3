#include "voronoimesh/pass.hpp"

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
  mesh.move_nodes(delta);
  pending = false;
}

} // namespace vm
