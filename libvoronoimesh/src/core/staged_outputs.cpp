/// @file core/staged_outputs.cpp
/// StagedOutputs and write_atomically() (core/staged_outputs.hpp).

#include "core/staged_outputs.hpp"

#include "core/text.hpp"
#include "voronoimesh/core/errors.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <set>
#include <streambuf>

namespace vm::detail {

namespace fs = std::filesystem;

namespace {

/// An output stream's buffer over a file descriptor; remembers the first error.
class FdBuffer : public std::streambuf {
public:
  explicit FdBuffer(int fd) : fd_(fd) { setp(buffer_, buffer_ + sizeof buffer_); }
  /// 0, or the errno of the first failed write.
  int error() const { return error_; }
  bool flush_all() { return drain() && error_ == 0; }

protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) sputc(traits_type::to_char_type(c));
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }

private:
  bool drain() {
    const char* p = pbase();
    while (p < pptr() && error_ == 0) {
      const ssize_t n = ::write(fd_, p, size_t(pptr() - p));
      if (n > 0) p += n;
      else if (n < 0 && errno != EINTR) error_ = errno;
    }
    setp(buffer_, buffer_ + sizeof buffer_);
    return error_ == 0;
  }
  int fd_;
  int error_ = 0;
  char buffer_[1 << 16];
};

/// What the umask leaves of 0666: a new file's permissions, as an ofstream would
/// make it. (Reading the umask sets it: for the instant between, the library's
/// one writing thread is the only one making files.)
mode_t new_file_mode() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return mode_t(0666 & ~mask);
}

/// The pid a temporary's name carries after ".tmp-" ("<pid>" or "<pid>-<k>"), or 0.
pid_t pid_of_temporary(const std::string& suffix) {
  const size_t dash = suffix.find('-');
  const std::string digits = suffix.substr(0, dash);
  const std::string rest = dash == std::string::npos ? "" : suffix.substr(dash + 1);
  auto all_digits = [](const std::string& s) {
    return !s.empty() && s.size() <= 9 && s.find_first_not_of("0123456789") == std::string::npos;
  };
  if (!all_digits(digits) || (dash != std::string::npos && !all_digits(rest))) return 0;
  return pid_t(std::stol(digits));
}

/// The `<name>.tmp-<pid>[-<k>]` files in `folder` whose process no longer runs, by
/// <name>: what killed runs (kill -9, a crash, a power cut) left instead of their output.
std::map<std::string, std::vector<fs::path>> stale_temporaries(const fs::path& folder) {
  std::map<std::string, std::vector<fs::path>> found;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const size_t mark = name.rfind(".tmp-");
    if (mark == std::string::npos || mark == 0) continue;
    const pid_t pid = pid_of_temporary(name.substr(mark + 5));
    if (pid > 0 && ::kill(pid, 0) != 0 && errno == ESRCH) found[name.substr(0, mark)].push_back(it->path());
  }
  return found;
}

/// Removes the stale temporaries of `path` (only names of exactly that form, only
/// when no process has the pid; a link is removed, never what it points to). Each
/// folder is listed once per process, at its first write: a run writing one file
/// per phase into a folder must not list it once per file.
void remove_stale_temporaries(const std::string& path) {
  static std::mutex mutex;
  static std::map<fs::path, std::map<std::string, std::vector<fs::path>>> by_folder;
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::lock_guard<std::mutex> lock(mutex);
  auto listed = by_folder.find(folder);
  if (listed == by_folder.end()) listed = by_folder.emplace(folder, stale_temporaries(folder)).first;
  const auto stale = listed->second.find(target.filename().string());
  if (stale == listed->second.end()) return;
  std::error_code ec;
  for (const auto& file : stale->second) fs::remove(file, ec);
  listed->second.erase(stale);
}

/// Flushes a folder's entries (the renames in it) to disk; best effort.
void sync_folder(const fs::path& folder) {
  const int fd = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

IoError cannot_write(const std::string& path, const std::string& reason) {
  return IoError(located(path, cat("cannot write (", reason, ")")));
}

} // namespace

FileIdentity file_identity(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) return {st.st_dev, st.st_ino, {}};
  std::error_code ec;
  fs::path absolute = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return {0, 0, (ec ? fs::path(path).lexically_normal() : absolute).string()};
}

StagedOutputs::StagedOutputs(std::vector<std::string> inputs) {
  for (const std::string& input : inputs)
    if (!input.empty()) inputs_.push_back(file_identity(input));
}

StagedOutputs::~StagedOutputs() {
  if (committed_) return;
  for (const Staged& s : staged_) ::unlink(s.temporary.c_str());
}

void StagedOutputs::write(const std::string& path, const std::function<void(std::ostream&)>& body) {
  const FileIdentity identity = file_identity(path);
  if (std::find(inputs_.begin(), inputs_.end(), identity) != inputs_.end())
    throw InvalidInput(located(path, "is also an input of this run; an output may not replace what the run reads"));
  for (const Staged& s : staged_)
    if (s.identity == identity)
      throw InvalidInput(located(path, s.path == path ? std::string("is written twice by this run")
                                                      : cat("is written twice by this run (also as ", s.path, ")")));

  // A name no file or link has: never opened through a link someone planted.
  static std::atomic<unsigned> counter{0};
  std::string temporary;
  int fd = -1;
  for (int attempt = 0; fd < 0 && attempt < 100; ++attempt) {
    temporary = cat(path, ".tmp-", long(::getpid()), "-", counter++);
    fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (fd < 0 && errno != EEXIST) throw cannot_write(path, std::strerror(errno));
  }
  if (fd < 0) throw cannot_write(path, "no free name for its temporary file");

  // The permissions of the file it replaces, or a new file's.
  struct stat old {};
  const mode_t mode = ::stat(path.c_str(), &old) == 0 && S_ISREG(old.st_mode) ? mode_t(old.st_mode & 07777)
                                                                              : new_file_mode();
  FdBuffer buffer(fd);
  std::ostream out(&buffer);
  int error = ::fchmod(fd, mode) == 0 ? 0 : errno;
  try {
    if (error == 0) {
      body(out);
      out.flush();
      error = buffer.flush_all() ? 0 : buffer.error() ? buffer.error() : EIO;
    }
    if (error == 0 && ::fsync(fd) != 0) error = errno;
  } catch (...) {
    ::close(fd);
    ::unlink(temporary.c_str());
    throw;
  }
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) {
    ::unlink(temporary.c_str());
    throw cannot_write(path, std::strerror(error));
  }
  staged_.push_back({path, temporary, identity});
}

void StagedOutputs::commit() {
  std::set<fs::path> folders;
  for (const Staged& s : staged_) {
    if (::rename(s.temporary.c_str(), s.path.c_str()) != 0) throw cannot_write(s.path, std::strerror(errno));
    folders.insert(fs::path(s.path).parent_path());
  }
  committed_ = true;
  for (const fs::path& folder : folders) sync_folder(folder);
  for (const Staged& s : staged_) remove_stale_temporaries(s.path);
}

std::vector<std::string> StagedOutputs::paths() const {
  std::vector<std::string> out;
  for (const Staged& s : staged_) out.push_back(s.path);
  return out;
}

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& body) {
  StagedOutputs staged;
  staged.write(path, body);
  staged.commit();
}

} // namespace vm::detail
