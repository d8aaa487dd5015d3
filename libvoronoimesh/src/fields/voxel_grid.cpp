#include "fields/voxel_grid.hpp"

#include "voronoimesh/core/errors.hpp"

#include "core/text.hpp"

#include <algorithm>
#include <cmath>

namespace vm::detail {

GridSpec voxel_grid(const std::array<int64_t, 3>& size, const Vec3& spacing, const Vec3& origin,
                    const std::string& source, const std::string& what) {
  GridSpec grid;
  for (int a = 0; a < 3; ++a) {
    if (size[size_t(a)] < 2)
      throw InvalidInput(located(source, cat("has ", size[size_t(a)], " voxel(s) along axis ", std::string(1, "xyz"[a]),
                                             "; ", what, " needs at least 2")));
    grid.cells[size_t(a)] = int(size[size_t(a)] - 1);
  }
  grid.domain.min = origin;
  grid.domain.max = origin + spacing.cwiseProduct(Vec3(double(grid.cells[0]), double(grid.cells[1]), double(grid.cells[2])));
  return grid;
}

GridSpec even_scene_grid(const GridSpec& voxel_grid, const std::string& source) {
  GridSpec g = voxel_grid;
  const Vec3 h = voxel_grid.spacing();
  for (int a = 0; a < 3; ++a) {
    if (g.cells[size_t(a)] % 2) ++g.cells[size_t(a)], g.domain.max[a] += h[a];
    if (g.cells[size_t(a)] > 4096)
      throw InvalidInput(located(source, cat("has ", g.cells[size_t(a)], " voxels along an axis; give a coarser grid (--grid, or \"grid\" in a scene; at most 4096 cells)")));
  }
  return g;
}

double resolved_voxels_per_cell(double voxels_per_cell, const Vec3& spacing) {
  if (voxels_per_cell > 0) return voxels_per_cell;
  if (spacing.maxCoeff() <= kFlatVoxels * spacing.minCoeff()) return 1;
  return std::cbrt(spacing.prod()) / spacing.minCoeff();
}

GridSpec volume_scene_grid(const GridSpec& voxel_grid, double voxels_per_cell, const std::string& source,
                           std::vector<std::string>& notes) {
  const Vec3 h = voxel_grid.spacing();
  const double per_cell = resolved_voxels_per_cell(voxels_per_cell, h);
  if (per_cell == 1) return even_scene_grid(voxel_grid, source);
  GridSpec g = voxel_grid;
  const double cell = per_cell * h.minCoeff();
  if (voxels_per_cell == 0)
    notes.push_back(cat("voxels of ", h[0], " x ", h[1], " x ", h[2], " are flat: the grid has cubic cells of ", cell,
                        " instead (--voxels-per-cell 1: the voxel grid; --grid overrides both)"));
  const Vec3 extent = voxel_grid.domain.max - voxel_grid.domain.min;
  for (int a = 0; a < 3; ++a) g.cells[size_t(a)] = 2 * std::max(1, int(std::lround(extent[a] / (2 * cell))));
  return g;
}

} // namespace vm::detail
