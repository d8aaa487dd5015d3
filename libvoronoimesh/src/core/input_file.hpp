#pragma once
/// @file core/input_file.hpp
/// Opening what a user names as input. Every input the library reads must be a
/// regular file: a device, a pipe or a folder (/dev/zero, /dev/stdin) could be
/// read without end. Whole-file reads have a size bound, checked before reading.

#include <cstdint>
#include <string>

namespace vm::detail {

/// The size in bytes of the file at `path`, which must be a regular file (or a
/// link to one). Throws IoError "<path>: cannot open (<reason>)" when it does
/// not exist or cannot be looked at, "<path>: cannot read: it is a directory (a
/// character device, a pipe...), not a regular file" when it is not one.
uint64_t require_regular_file(const std::string& path);

/// The contents of the regular file at `path` (require_regular_file()), which
/// `what` names in messages ("a scene"). Throws InvalidInput "<path>: N bytes;
/// <what> of more than M bytes is refused" beyond `max_bytes`, or when it would
/// not fit in this machine's memory; IoError "<path>: cannot open (<reason>)" or
/// "<path>: cannot read (<reason>)".
std::string read_text_file(const std::string& path, uint64_t max_bytes, const std::string& what);

} // namespace vm::detail
