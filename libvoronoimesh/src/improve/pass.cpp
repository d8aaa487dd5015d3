#include "voronoimesh/improve/pass.hpp"

#include "voronoimesh/improve/guard.hpp"

#include "improve/part_agreement.hpp"

namespace vm {

std::vector<Vec3>& PassContext::displacement() {
  if (!pending) {
    delta.assign(mesh.num_nodes(), Vec3::Zero());
    pending = true;
  }
  return delta;
}

void PassContext::commit() { commit_pending(false); }

void PassContext::take_back_floor_exceptions() {
  if (!guard_crossings) return;
  guard.floor_exception_reverts(mesh, quality_floor, displacement());
  commit_pending(true);
}

void PassContext::commit_pending(bool floor_holds_all) {
  if (!pending) return;
  AgreeOnUndone agree;
  if (parts) {
    parts->share_moves(delta);
    agree = [this](std::vector<int32_t>& undone) { return parts->agree_on_undone(undone); };
  }
  if (guard_crossings) undone_moves += guard.commit(mesh, delta, field, agree, quality_floor, floor_holds_all).undone_nodes;
  else mesh.move_nodes(delta);
  pending = false;
}

} // namespace vm
