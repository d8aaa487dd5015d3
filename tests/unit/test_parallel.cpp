/// core/parallel.hpp: each call does what its TBB call does, on one thread
/// and on four; in ThreadSanitizer builds a race between the tasks of a call
/// is still reported (the annotations order only what TBB orders).

#include "core/indices_where.hpp"
#include "core/parallel.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace vm;

namespace {

constexpr size_t kThreadCounts[] = {1, 4};

TEST(Parallel, loops_visit_every_index_once) {
  for (size_t threads : kThreadCounts) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const size_t n = 10000;
    std::vector<int> over_range(n, 0), over_indices(n, 0), each_index(n, 0);
    detail::parallel_for(tbb::blocked_range<size_t>(0, n, 64), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i) ++over_range[i];
    });
    detail::parallel_for(size_t(0), n, [&](size_t i) { ++over_indices[i]; });
    detail::parallel_for_each_index(n, [&](size_t i) { ++each_index[i]; }, 16);
    const std::vector<int> once(n, 1);
    EXPECT_EQ(over_range, once) << threads << " threads";
    EXPECT_EQ(over_indices, once) << threads << " threads";
    EXPECT_EQ(each_index, once) << threads << " threads";
  }
}

TEST(Parallel, reduce_joins_every_partial_result) {
  std::vector<uint64_t> values(100000);
  std::iota(values.begin(), values.end(), uint64_t(1));
  for (size_t threads : kThreadCounts) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    const uint64_t sum = detail::parallel_reduce(
        tbb::blocked_range<size_t>(0, values.size(), 16), uint64_t(0),
        [&](const tbb::blocked_range<size_t>& r, uint64_t partial) {
          for (size_t i = r.begin(); i != r.end(); ++i) partial += values[i];
          return partial;
        },
        [](uint64_t a, uint64_t b) { return a + b; });
    EXPECT_EQ(sum, values.size() * (values.size() + 1) / 2) << threads << " threads";
  }
}

TEST(Parallel, sort_orders_as_std_sort) {
  for (size_t threads : kThreadCounts) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    std::vector<uint32_t> items(50000);
    for (size_t i = 0; i < items.size(); ++i) items[i] = uint32_t(i * 2654435761u);
    std::vector<uint32_t> expected = items;
    std::sort(expected.begin(), expected.end(), std::greater<>());
    detail::parallel_sort(items.begin(), items.end(), std::greater<>());
    EXPECT_EQ(items, expected) << threads << " threads";
  }
}

TEST(Parallel, indices_where_lists_what_a_serial_scan_finds_in_order) {
  // Sizes around the block of 2^14 indices, so that blocks end mid-list and
  // some blocks keep nothing; every fifth-or-so index kept, in a pattern with no period.
  for (size_t threads : kThreadCounts) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    // A list given to fill is reused: what it held before (longer, shorter, or
    // other indices) must not show.
    std::vector<int32_t> reused(70000, -7);
    for (size_t n : {size_t(100003), size_t(0), size_t(1), size_t(16383), size_t(16384), size_t(16385)}) {
      auto keep = [](size_t i) { return (i * 2654435761u >> 7) % 5 == 0 || (i >= 40000 && i < 60000 && i % 2); };
      std::vector<int32_t> expected;
      for (size_t i = 0; i < n; ++i)
        if (keep(i)) expected.push_back(int32_t(i));
      EXPECT_EQ(detail::indices_where(n, keep), expected) << n << " indices, " << threads << " threads";
      detail::indices_where(n, keep, reused);
      EXPECT_EQ(reused, expected) << n << " indices into a list in use, " << threads << " threads";
    }
    EXPECT_TRUE(detail::indices_where(50000, [](size_t) { return false; }).empty());
  }
}

TEST(Parallel, invoke_runs_every_function) {
  for (size_t threads : kThreadCounts) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    std::vector<int> ran(3, 0);
    detail::parallel_invoke([&] { ran[0] = 1; }, [&] { ran[1] = 2; }, [&] { ran[2] = 3; });
    EXPECT_EQ(ran, (std::vector<int>{1, 2, 3})) << threads << " threads";
  }
}

TEST(Parallel, an_exception_in_a_task_reaches_the_caller_and_the_next_call_runs) {
  for (size_t threads : kThreadCounts) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    EXPECT_THROW(detail::parallel_for(size_t(0), size_t(1000),
                                      [](size_t i) {
                                        if (i == 500) throw std::runtime_error("task failed");
                                      }),
                 std::runtime_error);
    std::vector<int> after(1000, 0);
    detail::parallel_for(size_t(0), after.size(), [&](size_t i) { after[i] = int(i); });
    EXPECT_EQ(after[999], 999);
  }
}

#ifdef VM_TSAN_TBB

/// Tasks that each write the same variable, slowly enough for several threads
/// to run them, then a normal exit: TSan exits with its code 66 once it has
/// reported something (at once where TSAN_OPTIONS says halt_on_error=1).
void race_between_tasks() {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 4);
  int shared = 0;
  detail::parallel_for(size_t(0), size_t(64), [&](size_t i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    shared += int(i);
  });
  std::exit(shared > 0 ? 0 : 1);
}

TEST(ParallelThreadSanitizer, a_race_between_tasks_is_still_reported) {
  // "threadsafe": the child runs the test binary again instead of going on
  // from a fork of this process, whose TBB threads it would not have.
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(race_between_tasks(), testing::ExitedWithCode(66), "ThreadSanitizer: data race");
}

#endif

} // namespace
