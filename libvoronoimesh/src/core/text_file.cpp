#include "core/text_file.hpp"

#include "voronoimesh/core/errors.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

namespace vm::detail {

std::string read_text_file(const std::string& path) {
  // stdio rather than iostreams: it keeps errno, which gives the reason.
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) throw IoError(located(path, std::string("cannot open (") + std::strerror(errno) + ")"));
  std::string text;
  char buf[1 << 16];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f.get())) > 0) text.append(buf, n);
  // A directory opens fine on Linux and fails here with EISDIR.
  if (std::ferror(f.get()))
    throw IoError(located(path, std::string("cannot read (") + std::strerror(errno) + ")"));
  return text;
}

} // namespace vm::detail
