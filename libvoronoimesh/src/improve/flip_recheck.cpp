#include "improve/flip_recheck.hpp"

#include "core/parallel.hpp"

namespace vm::detail {

std::vector<uint8_t> FlipRecheck::faces_to_test(const InterfaceMesh& mesh, const std::vector<uint8_t>& flipped) const {
  if (triangles_.empty()) return flipped;
  const auto& triangles = mesh.triangles();
  std::vector<uint8_t> test(triangles.size());
  detail::parallel_for_each_index(test.size(), [&](size_t f) {
    test[f] = triangles[f] != triangles_[f] || crossing_[f] || (flipped[f] && !flipped_[f]);
  });
  return test;
}

void FlipRecheck::checked(const InterfaceMesh& mesh, std::vector<uint8_t> flipped,
                          const std::vector<std::array<int32_t, 2>>& crossings) {
  triangles_ = mesh.triangles();
  flipped_ = std::move(flipped);
  crossing_.assign(triangles_.size(), 0);
  for (const auto& pair : crossings)
    for (int32_t f : pair) crossing_[size_t(f)] = 1;
}

} // namespace vm::detail
