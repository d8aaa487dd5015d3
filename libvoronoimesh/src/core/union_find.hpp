#pragma once
/// @file core/union_find.hpp
/// Disjoint sets over 0..n-1 (path halving, union by smaller index so the
/// representative of a class is its smallest member: results do not depend on
/// the order unions are made in).

#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace vm::detail {

class UnionFind {
public:
  explicit UnionFind(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), int32_t(0)); }

  int32_t find(int32_t x) {
    while (parent_[size_t(x)] != x) {
      parent_[size_t(x)] = parent_[size_t(parent_[size_t(x)])];
      x = parent_[size_t(x)];
    }
    return x;
  }

  void unite(int32_t a, int32_t b) {
    a = find(a);
    b = find(b);
    if (a < b)
      parent_[size_t(b)] = a;
    else if (b < a)
      parent_[size_t(a)] = b;
  }

private:
  std::vector<int32_t> parent_;
};

} // namespace vm::detail
