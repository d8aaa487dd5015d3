#include "mpi/memory.hpp"

#include "core/memory.hpp"
#include "voronoimesh/core/errors.hpp"

#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace vm::mpi::detail {

namespace {

/// "1.50 GiB", or MiB below a GiB.
std::string size_text(double bytes) {
  const bool gib = bytes >= double(1ull << 30);
  char text[32];
  std::snprintf(text, sizeof text, "%.2f %s", bytes / double(1ull << (gib ? 30 : 20)), gib ? "GiB" : "MiB");
  return text;
}

/// Bytes from "<digits>[K|M|G|T]"; InvalidInput naming the variable otherwise.
double parse_bytes(std::string_view text) {
  size_t digits = 0;
  while (digits < text.size() && text[digits] >= '0' && text[digits] <= '9') ++digits;
  double bytes = 0;
  for (size_t i = 0; i < digits; ++i) bytes = bytes * 10 + (text[i] - '0');
  const std::string_view suffix = text.substr(digits);
  int shift = -1;
  if (suffix.empty()) shift = 0;
  else if (suffix.size() == 1)
    for (int s = 0; s < 4; ++s)
      if (suffix[0] == "KMGT"[s]) shift = 10 * (s + 1);
  if (digits == 0 || shift < 0 || bytes == 0)
    throw InvalidInput(std::string(kNodeMemoryVariable) + ": expected a positive number of bytes, optionally with K, " +
                       "M, G or T (e.g. 64G), got '" + std::string(text) + "'");
  return bytes * double(1ull << shift);
}

} // namespace

MemoryShare memory_share(Comm& comm) {
  MemoryShare share;
  share.node_ranks = comm.ranks_on_node();
  if (const char* limit = std::getenv(kNodeMemoryVariable)) {
    share.node_bytes = parse_bytes(limit);
    share.from_variable = true;
  } else {
    share.node_bytes = double(vm::detail::available_memory());
  }
  return share;
}

void refuse_beyond_share(const MemoryShare& share, double bytes, const std::string& what) {
  if (bytes <= share.bytes()) return;
  throw InvalidInput(what + " needs about " + size_text(bytes) + " on this rank, its share of its node's memory is " +
                     size_text(share.bytes()) + " (" + size_text(share.node_bytes) + " " +
                     (share.from_variable ? kNodeMemoryVariable : "available") + ", " +
                     std::to_string(share.node_ranks) + " ranks)");
}

} // namespace vm::mpi::detail
