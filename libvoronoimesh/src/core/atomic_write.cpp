#include "core/atomic_write.hpp"

#include "core/text.hpp"
#include "voronoimesh/core/errors.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <vector>

namespace vm::detail {

namespace {

/// The `<name>.tmp-<pid>` files in `folder` whose process no longer runs, by
/// <name>: what killed runs (kill -9, a crash, a power cut) left instead of
/// their output.
std::map<std::string, std::vector<std::filesystem::path>> stale_temporaries(const std::filesystem::path& folder) {
  std::map<std::string, std::vector<std::filesystem::path>> found;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const size_t mark = name.rfind(".tmp-");
    if (mark == std::string::npos || mark == 0) continue;
    const std::string digits = name.substr(mark + 5);
    if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const pid_t pid = pid_t(std::stol(digits));
    if (pid > 0 && ::kill(pid, 0) != 0 && errno == ESRCH) found[name.substr(0, mark)].push_back(it->path());
  }
  return found;
}

/// Removes the stale temporaries of `path` (only names of exactly that form,
/// only when no process has the pid). Each folder is listed once per process,
/// at its first write: a run writing one file per phase into a folder must not
/// list it once per file. (A run killed while this one goes on leaves its file
/// for the next process.)
void remove_stale_temporaries(const std::string& path) {
  static std::mutex mutex;
  static std::map<std::filesystem::path, std::map<std::string, std::vector<std::filesystem::path>>> by_folder;
  const std::filesystem::path target(path);
  const std::filesystem::path folder = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  const std::lock_guard<std::mutex> lock(mutex);
  auto listed = by_folder.find(folder);
  if (listed == by_folder.end()) listed = by_folder.emplace(folder, stale_temporaries(folder)).first;
  const auto stale = listed->second.find(target.filename().string());
  if (stale == listed->second.end()) return;
  std::error_code ec;
  for (const auto& file : stale->second) std::filesystem::remove(file, ec);
  listed->second.erase(stale);
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
