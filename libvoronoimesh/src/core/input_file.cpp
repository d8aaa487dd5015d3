/// @file core/input_file.cpp
/// require_regular_file() and read_text_file() (core/input_file.hpp).

#include "core/input_file.hpp"

#include "core/memory.hpp"
#include "core/text.hpp"
#include "voronoimesh/core/errors.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

namespace vm::detail {

namespace {

/// What a file that is not a regular one is, for messages.
const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a pipe";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

} // namespace

uint64_t require_regular_file(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw IoError(located(path, cat("cannot open (", std::strerror(errno), ")")));
  if (!S_ISREG(st.st_mode))
    throw IoError(located(path, cat("cannot read: it is ", kind_of(st.st_mode), ", not a regular file")));
  return uint64_t(st.st_size);
}

std::string read_text_file(const std::string& path, uint64_t max_bytes, const std::string& what) {
  const uint64_t size = require_regular_file(path);
  if (size > max_bytes)
    throw InvalidInput(located(path, cat(size, " bytes; ", what, " of more than ", max_bytes, " bytes is refused")));
  refuse_beyond_memory(double(size), path, cat("reading ", size, " bytes"));
  // stdio rather than iostreams: it keeps errno, which gives the reason.
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) throw IoError(located(path, cat("cannot open (", std::strerror(errno), ")")));
  std::string text;
  text.reserve(size_t(size));
  char buf[1 << 16];
  size_t n;
  // Reads no more than the size it had: a file that grows meanwhile is not followed.
  while (text.size() < size &&
         (n = std::fread(buf, 1, std::min<size_t>(sizeof buf, size_t(size) - text.size()), f.get())) > 0)
    text.append(buf, n);
  if (std::ferror(f.get())) throw IoError(located(path, cat("cannot read (", std::strerror(errno), ")")));
  return text;
}

} // namespace vm::detail
