#include "fields/axis_align.hpp"

#include "voronoimesh/core/errors.hpp"

#include <array>
#include <cmath>

namespace vm::detail {

namespace {

/// Moves the samples of `data` (components interleaved) from the old voxel
/// order to the new one, where new axis j reads old axis from[j], flipped if flip[j].
template <class T>
void reorder(std::vector<T>& data, const io::Volume& v, const std::array<int, 3>& from,
             const std::array<bool, 3>& flip) {
  if (data.empty()) return;
  std::vector<T> out(data.size());
  const size_t c = size_t(v.components);
  const auto& s = v.size;
  std::array<int64_t, 3> ns{s[size_t(from[0])], s[size_t(from[1])], s[size_t(from[2])]};
  std::array<int64_t, 3> old{};
  for (int64_t k = 0; k < ns[2]; ++k)
    for (int64_t j = 0; j < ns[1]; ++j)
      for (int64_t i = 0; i < ns[0]; ++i) {
        const std::array<int64_t, 3> now{i, j, k};
        for (int a = 0; a < 3; ++a) old[size_t(from[size_t(a)])] = flip[size_t(a)] ? ns[size_t(a)] - 1 - now[size_t(a)] : now[size_t(a)];
        const size_t src = size_t(old[0] + s[0] * (old[1] + s[1] * old[2])) * c;
        const size_t dst = size_t(i + ns[0] * (j + ns[1] * k)) * c;
        for (size_t comp = 0; comp < c; ++comp) out[dst + comp] = data[src + comp];
      }
  data.swap(out);
}

} // namespace

void axis_align(io::Volume& v, const std::string& source, bool ignore_direction) {
  if (ignore_direction) {
    v.direction.setIdentity();
    return;
  }
  // World axis j comes from volume axis from[j], whose direction is +-e_j.
  std::array<int, 3> from{-1, -1, -1};
  std::array<bool, 3> flip{};
  constexpr double tol = 1e-6;
  for (int a = 0; a < 3; ++a) {
    const Vec3 d = v.direction.col(a);
    int j = 0;
    d.cwiseAbs().maxCoeff(&j);
    if (std::abs(std::abs(d[j]) - 1) > tol || (d.cwiseAbs().sum() - std::abs(d[j])) > tol || from[size_t(j)] >= 0)
      throw InvalidInput(located(source, "its direction matrix is oblique (not a permutation of the axes); "
                                         "voronoimesh meshes axis-aligned boxes: give --ignore-direction to use "
                                         "the voxel axes as they are"));
    from[size_t(j)] = a;
    flip[size_t(j)] = d[j] < 0;
  }
  if (v.direction == Eigen::Matrix3d::Identity()) return;
  reorder(v.labels, v, from, flip);
  reorder(v.values, v, from, flip);
  const auto size = v.size;
  const Vec3 spacing = v.spacing;
  for (size_t j = 0; j < 3; ++j) {
    const size_t a = size_t(from[j]);
    v.size[j] = size[a];
    v.spacing[int(j)] = spacing[int(a)];
    // The lowest world coordinate along j is the new voxel 0.
    if (flip[j]) v.origin[int(j)] -= spacing[int(a)] * double(size[a] - 1);
  }
  v.direction.setIdentity();
}

} // namespace vm::detail
