// Huge pages for executables (run/huge_pages.hpp): which GLIBC_TUNABLES a
// restart sets, for each kernel mode and what the user set. The restart itself
// is checked on the built tool (tests/cli/cli_tests.sh).

#include "voronoimesh/run/huge_pages.hpp"

#include <gtest/gtest.h>

namespace vm {
namespace {

const std::string kMadvise = "always [madvise] never";

TEST(HugePages, asked_for_only_where_the_kernel_gives_them_on_request) {
  EXPECT_EQ(tunables_for_huge_pages(nullptr, kMadvise), "glibc.malloc.hugetlb=1");
  EXPECT_EQ(tunables_for_huge_pages(nullptr, "[always] madvise never"), std::nullopt);
  EXPECT_EQ(tunables_for_huge_pages(nullptr, "always madvise [never]"), std::nullopt);
  EXPECT_EQ(tunables_for_huge_pages(nullptr, ""), std::nullopt); // no such file
}

TEST(HugePages, the_users_tunables_are_kept) {
  EXPECT_EQ(tunables_for_huge_pages("", kMadvise), "glibc.malloc.hugetlb=1");
  EXPECT_EQ(tunables_for_huge_pages("glibc.malloc.arena_max=2", kMadvise),
            "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1");
  // Set already, by a restart or by the user (0 turns it off): nothing to do.
  EXPECT_EQ(tunables_for_huge_pages("glibc.malloc.hugetlb=1", kMadvise), std::nullopt);
  EXPECT_EQ(tunables_for_huge_pages("glibc.malloc.arena_max=2:glibc.malloc.hugetlb=0", kMadvise), std::nullopt);
}

} // namespace
} // namespace vm
