#pragma once
/// @file text_file.hpp
/// Reading a whole file, with the system's reason in the error.

#include <string>

namespace vm::detail {

/// The contents of the file at `path`. Throws IoError
/// "<path>: cannot open (<reason>)" or "<path>: cannot read (<reason>)".
std::string read_text_file(const std::string& path);

} // namespace vm::detail
