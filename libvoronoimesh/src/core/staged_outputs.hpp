#pragma once
/// @file core/staged_outputs.hpp
/// Writing output files so that a run's outputs appear all or none, never over
/// one of its inputs, never through a link someone planted.
///
/// Each file is written to a temporary beside it, `<name>.tmp-<pid>-<k>`, created
/// new (O_CREAT | O_EXCL | O_NOFOLLOW: an existing file or link of that name is
/// never opened, another name is taken), with the permissions of the file it
/// will replace (or, for a new one, what the umask leaves of 0666), and flushed
/// to disk (fsync). commit() renames every temporary into place; a StagedOutputs
/// destroyed without commit() (a failure, an interruption) removes them all.

#include <sys/types.h>

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace vm::detail {

/// What identifies a file: its device and inode when it exists, else its
/// absolute, normalised path (a file about to be made).
struct FileIdentity {
  dev_t device = 0;
  ino_t inode = 0;
  std::string path; ///< set only when the file does not exist
  bool operator==(const FileIdentity&) const = default;
};
/// The identity of `path` (following links, so a link and its target are one file).
FileIdentity file_identity(const std::string& path);

class StagedOutputs {
public:
  /// `inputs`: the files the run reads, which no output may be (by identity).
  explicit StagedOutputs(std::vector<std::string> inputs = {});
  ~StagedOutputs();
  StagedOutputs(const StagedOutputs&) = delete;
  StagedOutputs& operator=(const StagedOutputs&) = delete;

  /// Writes what `body` writes to the stream as the content of `path`, to its
  /// temporary. Throws InvalidInput "<path>: is also an input of this run" or
  /// "<path>: is written twice by this run (as <other>)"; IoError "<path>: cannot
  /// write (<reason>)" when the temporary cannot be made or written (a full disk,
  /// a file-size limit) or `body` fails.
  void write(const std::string& path, const std::function<void(std::ostream&)>& body);

  /// Renames every temporary into place, in the order written, and removes the
  /// temporaries killed runs left beside them. Throws IoError naming the file
  /// that could not be renamed (the ones before it are in place).
  void commit();

  /// The files written so far, in order.
  std::vector<std::string> paths() const;

private:
  struct Staged {
    std::string path, temporary;
    FileIdentity identity;
  };
  std::vector<FileIdentity> inputs_;
  std::vector<Staged> staged_;
  bool committed_ = false;
};

/// One file through StagedOutputs: written whole or not at all.
void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& body);

} // namespace vm::detail
