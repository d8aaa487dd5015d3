#include "io/voxel_data.hpp"

#include "core/huge_pages.hpp"
#include "core/text.hpp"
#include "voronoimesh/core/errors.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

namespace vm::detail {

int voxel_type_bytes(VoxelType type) {
  switch (type) {
  case VoxelType::u8:
  case VoxelType::i8: return 1;
  case VoxelType::u16:
  case VoxelType::i16: return 2;
  case VoxelType::u32:
  case VoxelType::i32:
  case VoxelType::f32: return 4;
  case VoxelType::f64: return 8;
  }
  return 0;
}

bool voxel_type_is_integer(VoxelType type) { return type != VoxelType::f32 && type != VoxelType::f64; }

uint64_t voxel_data_bytes(const std::string& path, const io::Volume& volume, VoxelType type) {
  static const char* axis[] = {"x", "y", "z"};
  uint64_t bytes = uint64_t(voxel_type_bytes(type));
  for (int a = 0; a < 3; ++a) {
    if (volume.size[a] < 1)
      throw InvalidInput(located(path, cat("size along ", axis[a], " is ", volume.size[a], ", must be >= 1")));
    if (__builtin_mul_overflow(bytes, uint64_t(volume.size[a]), &bytes))
      throw InvalidInput(located(path, "the voxel data size overflows 64 bits (corrupt sizes?)"));
  }
  if (volume.components < 1)
    throw InvalidInput(located(path, cat("has ", volume.components, " components per voxel, must be >= 1")));
  if (__builtin_mul_overflow(bytes, uint64_t(volume.components), &bytes) ||
      bytes > uint64_t(std::numeric_limits<int64_t>::max()))
    throw InvalidInput(located(path, "the voxel data size overflows 64 bits (corrupt sizes?)"));
  return bytes;
}

void check_voxel_data_length(const std::string& path, uint64_t needed, uint64_t available) {
  if (available < needed)
    throw InvalidInput(located(path, cat("truncated: the header describes ", needed, " bytes of voxel data, the file holds ",
                                         available)));
  if (available > needed)
    throw InvalidInput(located(path, cat("holds ", available, " bytes of voxel data, the header describes ", needed,
                                         " (wrong sizes or type?)")));
}

uint64_t max_inflated_bytes(uint64_t compressed) {
  // zlib's deflate cannot compress better than about 1032:1 (258-byte matches
  // coded in 2 bits); 64 bytes cover the stream's header and trailer.
  return compressed > std::numeric_limits<uint64_t>::max() / 1032 - 64 ? std::numeric_limits<uint64_t>::max()
                                                                        : 1032 * compressed + 64;
}

void check_inflatable(const std::string& path, uint64_t needed, uint64_t compressed) {
  if (needed > max_inflated_bytes(compressed))
    throw InvalidInput(located(path, cat("the header describes ", needed, " bytes of voxel data, more than ", compressed,
                                         " compressed bytes can hold (corrupt sizes?)")));
}

namespace {

/// The value at `p`, stored with the given byte order.
template <class T>
T load(const unsigned char* p, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

} // namespace

std::string voxel_name(const io::Volume& volume, size_t n) {
  const auto c = int64_t(n % size_t(volume.components));
  const auto v = int64_t(n / size_t(volume.components));
  const int64_t i = v % volume.size[0], j = v / volume.size[0] % volume.size[1], k = v / volume.size[0] / volume.size[1];
  std::string s = cat("voxel (", i, ", ", j, ", ", k, ")");
  if (volume.components > 1) s += cat(" component ", c);
  return s;
}

namespace {

template <class T>
void decode_labels(io::Volume& volume, const unsigned char* data, bool swap, const std::string& path) {
  const size_t n = size_t(volume.voxel_count()) * size_t(volume.components);
  resize_on_huge_pages(volume.labels, n);
  for (size_t i = 0; i < n; ++i) {
    const T v = load<T>(data + i * sizeof(T), swap);
    if constexpr (std::is_same_v<T, uint32_t>)
      if (v > uint32_t(std::numeric_limits<int32_t>::max()))
        throw InvalidInput(located(path, cat("label ", v, " at ", voxel_name(volume, i), " is beyond the int32 range")));
    volume.labels[i] = int32_t(v);
  }
}

template <class T>
void decode_values(io::Volume& volume, const unsigned char* data, bool swap, const std::string& path) {
  const size_t n = size_t(volume.voxel_count()) * size_t(volume.components);
  resize_on_huge_pages(volume.values, n);
  for (size_t i = 0; i < n; ++i) {
    const T v = load<T>(data + i * sizeof(T), swap);
    if (std::isnan(v)) throw InvalidInput(located(path, cat("value NaN at ", voxel_name(volume, i))));
    if (std::isfinite(v) && std::abs(double(v)) > double(std::numeric_limits<float>::max()))
      throw InvalidInput(located(path, cat("value ", double(v), " at ", voxel_name(volume, i), " is beyond float range")));
    volume.values[i] = float(v);
  }
}

} // namespace

void decode_voxels(io::Volume& volume, const unsigned char* data, VoxelType type, bool big_endian,
                   const std::string& path) {
  const bool swap = big_endian != (std::endian::native == std::endian::big);
  volume.integer = voxel_type_is_integer(type);
  volume.labels.clear();
  volume.values.clear();
  switch (type) {
  case VoxelType::u8: return decode_labels<uint8_t>(volume, data, swap, path);
  case VoxelType::i8: return decode_labels<int8_t>(volume, data, swap, path);
  case VoxelType::u16: return decode_labels<uint16_t>(volume, data, swap, path);
  case VoxelType::i16: return decode_labels<int16_t>(volume, data, swap, path);
  case VoxelType::u32: return decode_labels<uint32_t>(volume, data, swap, path);
  case VoxelType::i32: return decode_labels<int32_t>(volume, data, swap, path);
  case VoxelType::f32: return decode_values<float>(volume, data, swap, path);
  case VoxelType::f64: return decode_values<double>(volume, data, swap, path);
  }
}

void set_voxel_axes(io::Volume& volume, const Eigen::Matrix3d& steps, const Vec3& origin, const std::string& path) {
  static const char* axis[] = {"i", "j", "k"};
  if (!origin.allFinite()) throw InvalidInput(located(path, "the origin is not finite"));
  for (int a = 0; a < 3; ++a) {
    const double length = steps.col(a).norm();
    if (!std::isfinite(length) || !(length > 0))
      throw InvalidInput(located(path, cat("voxel spacing along ", axis[a], " is ", length, ", must be > 0")));
    volume.spacing[a] = length;
    volume.direction.col(a) = steps.col(a) / length;
  }
  // Unit columns: |det| is the volume of the parallelepiped they span, 1 when
  // orthogonal; near 0 the map from voxels to space folds the volume flat.
  if (std::abs(volume.direction.determinant()) < 1e-6)
    throw InvalidInput(located(path, "the voxel axes are linearly dependent (degenerate orientation)"));
  volume.origin = origin;
}

} // namespace vm::detail
