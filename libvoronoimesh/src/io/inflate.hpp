#pragma once
/// @file io/inflate.hpp
/// Decompressing zlib or gzip data held in memory.

#include <string>
#include <string_view>

namespace vm::detail {

/// Inflates `compressed`, a zlib or gzip stream (told apart by its header),
/// which must hold exactly `expected` bytes. Throws InvalidInput "<path>: ..."
/// for corrupt or truncated data and for a stream holding more or fewer bytes.
/// Call check_inflatable() (voxel_data.hpp) first: `expected` is allocated.
std::string inflate_exactly(const std::string& path, std::string_view compressed, size_t expected);

} // namespace vm::detail
