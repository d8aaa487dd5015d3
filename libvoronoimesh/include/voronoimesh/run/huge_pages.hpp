#pragma once
/// @file run/huge_pages.hpp
/// Large buffers on huge pages, for executables.
///
/// A run touches a few large buffers once each (a label volume's voxels, the
/// phase values at the grid nodes, the lattice's cut tetrahedra), and where
/// the kernel gives 4 KiB pages only on request of madvise (transparent huge
/// pages in "madvise" mode, as on Debian 12), faulting them in one 4 KiB page
/// at a time was a third of creating the liver's mesh. glibc (2.35 and later)
/// asks for huge pages for its large allocations under the tunable
/// glibc.malloc.hugetlb=1, which it reads only when a process starts: so an
/// executable restarts itself with it, once, before doing anything else. The
/// meshes are the same; the liver's whole run took 14% less time, the CT-like
/// volume's 22%, 1,000 grains at grid 64 16%, at about the same peak memory.
/// On a fresh VM whose first touches of memory were slow (2026-12-04) the
/// liver ran 4-24% faster without it and the 1M case 3% faster with it
/// (docs/benchmarks.md, "Huge pages"): the gain depends on the machine.
/// A library cannot do this for its host (Python, ParaView): set
/// GLIBC_TUNABLES=glibc.malloc.hugetlb=1 before starting it instead.

#include <optional>
#include <string>

namespace vm {

/// The value GLIBC_TUNABLES should have for huge pages, given its value now
/// (null: unset) and the first line of
/// /sys/kernel/mm/transparent_hugepage/enabled; nullopt when nothing is to be
/// done: the kernel's mode is not "madvise" (with "always" every large
/// allocation gets huge pages anyway, with "never" none can), or the tunables
/// say glibc.malloc.hugetlb already (set by an earlier restart, or by the
/// user, who may set it to 0 to turn this off).
std::optional<std::string> tunables_for_huge_pages(const char* tunables, const std::string& kernel_mode);

/// Restarts this process (execv of /proc/self/exe with `argv`) with the
/// tunables of tunables_for_huge_pages(), if there are any to add; returns,
/// changing nothing, when there are none, after a restart, or when the
/// restart fails. Call it first in main(), before any thread starts or
/// anything is printed.
void restart_with_huge_pages(char** argv);

} // namespace vm
