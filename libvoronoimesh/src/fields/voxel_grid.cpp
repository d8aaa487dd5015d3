#include "fields/voxel_grid.hpp"

#include "voronoimesh/core/errors.hpp"

#include "core/scale_limits.hpp"
#include "core/text.hpp"

#include <algorithm>
#include <cmath>

namespace vm::detail {

void require_resolvable(const GridSpec& grid, const std::string& source) {
  for (int a = 0; a < 3; ++a) {
    const std::string axis(1, "xyz"[a]);
    const double lo = grid.domain.min[a], hi = grid.domain.max[a];
    if (!(std::isfinite(lo) && std::isfinite(hi)))
      throw InvalidInput(located(source, cat("the domain along ", axis, " is not finite (from ", lo, " to ", hi, ")")));
    const double reach = std::max(std::abs(lo), std::abs(hi)), cell = (hi - lo) / grid.cells[size_t(a)];
    if (reach > kFarthestCoordinate)
      throw InvalidInput(located(source, cat("the domain reaches ", reach, " along ", axis, "; it must lie within -",
                                             kFarthestCoordinate, " and ", kFarthestCoordinate)));
    // Cells rounded away to nothing (a 1 mm voxel at 1e20) are too fine as well.
    if (!(cell >= std::ldexp(reach, -40)))
      throw InvalidInput(located(source, cat("cells of ", cell, " along ", axis, " at coordinates up to ", reach,
                                             " are finer than doubles resolve there (a cell must be at least 1e-12 "
                                             "of its coordinates): place the data nearer the origin")));
    if (!(cell >= kFinestLength))
      throw InvalidInput(located(source, cat("cells of ", cell, " along ", axis, " are smaller than ", kFinestLength,
                                             ", the finest length voronoimesh works at: give the input in larger "
                                             "units")));
  }
}

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
  require_resolvable(grid, source);
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
