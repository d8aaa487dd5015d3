#include "detail/node_values.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace vm::detail {

NodeValues::NodeValues(const SampledField& field, double snap_eps, const std::vector<char>* unsnapped)
    : field_(field), k_(field.k()) {
  const int64_t n_nodes = field.grid().node_count();
  values_.resize(size_t(n_nodes) * k_);
  floor_.resize(size_t(n_nodes));
  label_.resize(size_t(n_nodes));

  // One global affine map to integers, so equal values stay equal everywhere
  // and every node's numbers mean the same thing in every tetrahedron.
  const double lo = field.min_value();
  const double range = field.max_value() - lo;
  const double scale = range > 0 ? std::ldexp(1.0, kValueBits) / range : 1.0;
  const int64_t eps = std::llround(snap_eps * scale);
  auto quantize = [&](double v) { return int32_t(std::llround((v - lo) * scale)); };

  snapped_nodes_ = tbb::parallel_reduce(
      tbb::blocked_range<int64_t>(0, n_nodes, 4096), uint64_t(0),
      [&](const tbb::blocked_range<int64_t>& r, uint64_t snapped) {
        std::vector<int> order(k_);
        for (int64_t n = r.begin(); n < r.end(); ++n) {
          auto ids = field.ids(n);
          auto vals = field.values(n);
          int32_t* q = values_.data() + n * k_;
          for (int s = 0; s < k_; ++s) q[s] = quantize(vals[s]);
          floor_[n] = quantize(field.floor_value(n));
          // Pairwise snapping in phase-id order (Algorithm 2, line 1): a later
          // phase takes the earlier phase's value, so earlier snaps are not undone.
          if (eps > 0 && !(unsnapped && (*unsnapped)[size_t(n)])) {
            std::iota(order.begin(), order.end(), 0);
            std::sort(order.begin(), order.end(), [&](int a, int b) { return ids[a] < ids[b]; });
            bool changed = false;
            for (int a = 0; a < k_; ++a)
              for (int b = a + 1; b < k_; ++b) {
                int32_t& vi = q[order[a]];
                int32_t& vj = q[order[b]];
                if (vi != vj && std::llabs(int64_t(vi) - vj) < eps) {
                  vj = vi;
                  changed = true;
                }
              }
            snapped += changed;
          }
          int best = 0;
          for (int s = 1; s < k_; ++s)
            if (beats(q[s], ids[s], q[best], ids[best])) best = s;
          label_[n] = ids[best];
        }
        return snapped;
      },
      std::plus<>());
}

} // namespace vm::detail
