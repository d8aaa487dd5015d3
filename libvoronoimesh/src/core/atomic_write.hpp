#pragma once
/// @file core/atomic_write.hpp
/// Writing an output file so that a failure never leaves a partial one behind.

#include <functional>
#include <ostream>
#include <string>

namespace vm::detail {

/// Writes `path` through `path`.tmp-<pid>: `body` writes the content to the stream,
/// then the temporary file is renamed into place. On any failure (including an
/// exception from `body`) the temporary file is removed; failures to create,
/// write or rename throw IoError "<path>: cannot write (<reason>)". After a
/// success, the `path`.tmp-<pid> files that killed runs left (their pid no longer
/// runs) are removed.
void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& body);

} // namespace vm::detail
