#include "voronoimesh/run/huge_pages.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fstream>

namespace vm {

namespace {

/// Set in the restarted process: glibc may rewrite GLIBC_TUNABLES as it reads
/// it, so the tunables alone cannot be trusted to stop a second restart.
constexpr const char* kRestarted = "VORONOIMESH_HUGE_PAGES_RESTARTED";

} // namespace

std::optional<std::string> tunables_for_huge_pages(const char* tunables, const std::string& kernel_mode) {
  if (kernel_mode.find("[madvise]") == std::string::npos) return std::nullopt;
  const std::string now = tunables ? tunables : "";
  if (now.find("glibc.malloc.hugetlb") != std::string::npos) return std::nullopt;
  return now.empty() ? "glibc.malloc.hugetlb=1" : now + ":glibc.malloc.hugetlb=1";
}

void restart_with_huge_pages(char** argv) {
  if (std::getenv(kRestarted)) {
    unsetenv(kRestarted); // not passed on to what this process starts
    return;
  }
  std::ifstream mode_file("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string mode;
  std::getline(mode_file, mode);
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string before = tunables ? tunables : "";
  const std::optional<std::string> wanted = tunables_for_huge_pages(tunables, mode);
  if (!wanted || setenv("GLIBC_TUNABLES", wanted->c_str(), 1) != 0 || setenv(kRestarted, "1", 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Not restarted (no /proc, say): go on as before, the environment as it was.
  unsetenv(kRestarted);
  if (tunables) setenv("GLIBC_TUNABLES", before.c_str(), 1);
  else unsetenv("GLIBC_TUNABLES");
}

} // namespace vm
