#pragma once
/// @file io/voxel_data.hpp
/// What the volume readers share once a header is parsed: the size of the
/// voxel data it promises, the conversion of raw voxel bytes into a Volume's
/// labels or values, and the split of an index-to-space matrix into spacing
/// and unit directions.

#include "voronoimesh/io/volume.hpp"

#include <cstdint>
#include <string>

namespace vm::detail {

/// The scalar types the readers accept. 64-bit integers are not among them: a
/// label volume's labels are int32.
enum class VoxelType { u8, i8, u16, i16, u32, i32, f32, f64 };

/// Bytes per value of `type`.
int voxel_type_bytes(VoxelType type);

/// True for the integer types (the file stores labels).
bool voxel_type_is_integer(VoxelType type);

/// Bytes of voxel data `volume.size` x `volume.components` values of `type`
/// take. Throws InvalidInput "<path>: ..." when a size or the component count
/// is below 1 or the product overflows 64 bits, so that no reader allocates
/// from a corrupt header before checking the bytes it has against this.
uint64_t voxel_data_bytes(const std::string& path, const io::Volume& volume, VoxelType type);

/// Throws InvalidInput "<path>: ..." unless `available` bytes of voxel data
/// are exactly the `needed` ones: fewer is a truncated file, more means the
/// header does not describe the data (a wrong size or type).
void check_voxel_data_length(const std::string& path, uint64_t needed, uint64_t available);

/// The most bytes `compressed` bytes of deflate data (zlib, gzip) can inflate
/// to: deflate's best ratio is about 1032:1, plus the stream's header and trailer.
uint64_t max_inflated_bytes(uint64_t compressed);

/// Throws InvalidInput "<path>: ..." when `needed` bytes cannot come out of
/// `compressed` bytes of deflate data (max_inflated_bytes()): a corrupt header
/// then asks for more memory than the file could ever fill.
void check_inflatable(const std::string& path, uint64_t needed, uint64_t compressed);

/// "voxel (i, j, k)" (plus " component c" when there are several) of value `n`
/// of the volume's data (components fastest, then i, j, k), for messages.
std::string voxel_name(const io::Volume& volume, size_t n);

/// Fills volume.labels (integer types, volume.integer = true) or volume.values
/// from `data`, which holds voxel_data_bytes() bytes in the volume's order
/// (components fastest, then i, j, k) with the given byte order. Throws
/// InvalidInput "<path>: ..." naming the voxel for an unsigned 32-bit label
/// beyond int32, a NaN, or a double beyond float range.
void decode_voxels(io::Volume& volume, const unsigned char* data, VoxelType type, bool big_endian,
                   const std::string& path);

/// Sets volume.spacing (column norms of `steps`), volume.direction (its unit
/// columns) and volume.origin from the index-to-space map
/// x = origin + steps * (i, j, k). Throws InvalidInput "<path>: ..." when a
/// step is zero or not finite, or the axes are (nearly) linearly dependent.
void set_voxel_axes(io::Volume& volume, const Eigen::Matrix3d& steps, const Vec3& origin,
                    const std::string& path);

} // namespace vm::detail
