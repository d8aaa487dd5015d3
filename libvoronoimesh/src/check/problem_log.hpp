#pragma once
/// @file check/problem_log.hpp
/// Collects validation problems into a ValidationReport: every problem is
/// counted and its nodes listed (create() unsnaps them and retries), only the
/// first few are formatted (a broken 1M-triangle mesh may
/// have millions, and formatting them all would dominate the check).

#include "voronoimesh/check/validate.hpp"

#include "core/text.hpp"

#include <algorithm>
#include <array>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "core/parallel.hpp"

namespace vm::detail {

class ProblemLog {
public:
  static constexpr size_t kKept = 20;

  explicit ProblemLog(ValidationReport& report) : report_(report) {}
  /// Sorts and deduplicates the report's node list.
  ~ProblemLog() {
    auto& n = report_.nodes;
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  ProblemLog(const ProblemLog&) = delete;
  ProblemLog& operator=(const ProblemLog&) = delete;

  /// Records one problem at `nodes` (ids outside the mesh are left out by the
  /// caller); `describe()` returns its line and runs only if the line is kept.
  template <class Describe>
  void add(std::initializer_list<int32_t> nodes, Describe&& describe) {
    report_.nodes.insert(report_.nodes.end(), nodes.begin(), nodes.end());
    if (report_.problems.size() < kKept) report_.problems.push_back(std::forward<Describe>(describe)());
    ++report_.problem_count;
  }

  /// Adds the problems of `later`, found after all those logged so far, as if
  /// they had been add()ed here one by one. (Only `later`'s kept lines are
  /// known, but it kept its first kKept: all that this log can take.)
  void append(ValidationReport&& later) {
    for (size_t i = 0; i < later.problems.size() && report_.problems.size() < kKept; ++i)
      report_.problems.push_back(std::move(later.problems[i]));
    report_.problem_count += later.problem_count;
    report_.nodes.insert(report_.nodes.end(), later.nodes.begin(), later.nodes.end());
  }

private:
  ValidationReport& report_;
};

/// Runs `check(begin, end, reports)` over [0, n) cut into chunks of `grain`
/// items, in parallel. The check sorts the problems it finds into `Kinds`
/// kinds, logging kind k into reports[k] (through its own ProblemLog); all
/// chunks' problems of kind 0 are then appended to `log` in chunk order, then
/// those of kind 1, and so on. So when the check handles each item on its own,
/// the report is the one of serial passes over [0, n), one pass per kind, for
/// any number of threads: the chunks depend on n and grain only.
template <size_t Kinds, class Check>
void check_in_chunks(size_t n, size_t grain, ProblemLog& log, const Check& check) {
  const size_t chunks = (n + grain - 1) / grain;
  std::vector<std::array<ValidationReport, Kinds>> parts(chunks);
  detail::parallel_for(size_t(0), chunks,
                       [&](size_t c) { check(c * grain, std::min(n, (c + 1) * grain), parts[c]); });
  for (size_t k = 0; k < Kinds; ++k)
    for (auto& part : parts) log.append(std::move(part[k]));
}

} // namespace vm::detail
