#pragma once
/// @file core/memory.hpp
/// Refusing work that cannot fit in this machine's memory before allocating it,
/// with the estimate in the message (a corrupt header or a typo in --grid should
/// fail at once, not after minutes of swapping or in an allocator).

#include "core/text.hpp"
#include "voronoimesh/core/errors.hpp"

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

namespace vm::detail {

/// Physical memory of this machine, in bytes.
inline uint64_t physical_memory() {
  return uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE));
}

/// Memory that new allocations can get on this machine now, in bytes:
/// MemAvailable of /proc/meminfo (free memory and what the kernel can
/// reclaim without swapping), or the physical memory where it is not known.
inline uint64_t available_memory() {
  std::ifstream meminfo("/proc/meminfo");
  const std::string key = "MemAvailable:";
  for (std::string line; std::getline(meminfo, line);)
    if (line.compare(0, key.size(), key) == 0) return std::strtoull(line.c_str() + key.size(), nullptr, 10) * 1024;
  return physical_memory();
}

/// "<what> needs about X GiB, this machine has Y GiB" when `bytes` exceeds 80%
/// of the physical memory; empty when it does not.
inline std::string beyond_memory(double bytes, const std::string& what) {
  const double physical = double(physical_memory());
  if (bytes <= 0.8 * physical) return {};
  char msg[160];
  std::snprintf(msg, sizeof msg, "%s needs about %.1f GiB, this machine has %.1f GiB", what.c_str(),
                bytes / double(1ull << 30), physical / double(1ull << 30));
  return msg;
}

/// Throws InvalidInput "<source>: <what> needs about X GiB, this machine has Y GiB"
/// when `bytes` exceeds 80% of the physical memory.
inline void refuse_beyond_memory(double bytes, const std::string& source, const std::string& what) {
  if (const std::string problem = beyond_memory(bytes, what); !problem.empty())
    throw InvalidInput(located(source, problem));
}

} // namespace vm::detail
