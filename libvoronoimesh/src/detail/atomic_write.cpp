#include "detail/atomic_write.hpp"

#include "detail/text.hpp"
#include "voronoimesh/errors.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace vm::detail {

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& body) {
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  auto failure = [&](const std::string& reason) { return IoError(located(path, cat("cannot write (", reason, ")"))); };
  std::error_code ec;
  try {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw failure(std::strerror(errno != 0 ? errno : EIO));
    body(f);
    f.close();
    if (!f) throw failure(std::strerror(errno != 0 ? errno : EIO));
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw failure(ec.message());
  } catch (...) {
    std::filesystem::remove(tmp, ec);
    throw;
  }
}

} // namespace vm::detail
