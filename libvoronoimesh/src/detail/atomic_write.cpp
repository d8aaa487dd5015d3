#include "detail/atomic_write.hpp"

#include "detail/text.hpp"
#include "voronoimesh/errors.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace vm::detail {

namespace {

/// Removes `path`.tmp-<pid> files of processes that no longer run: what a
/// killed run (kill -9, a crash, a power cut) left instead of its output. Only
/// names of exactly that form are touched, and only when no process has the pid.
void remove_stale_temporaries(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string prefix = target.filename().string() + ".tmp-";
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!name.starts_with(prefix) || name.size() == prefix.size() || name.size() > prefix.size() + 9) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const pid_t pid = pid_t(std::stol(digits));
    if (pid > 0 && ::kill(pid, 0) != 0 && errno == ESRCH) fs::remove(it->path(), ec);
  }
}

} // namespace

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
    remove_stale_temporaries(path);
  } catch (...) {
    std::filesystem::remove(tmp, ec);
    throw;
  }
}

} // namespace vm::detail
