#pragma once
/// @file detail/problem_log.hpp
/// Collects validation problems into a ValidationReport: every problem is
/// counted and its nodes listed (create() unsnaps them and retries), only the
/// first few are formatted (a broken 1M-triangle mesh may
/// have millions, and formatting them all would dominate the check).

#include "voronoimesh/validate.hpp"

#include "detail/text.hpp"

#include <algorithm>
#include <initializer_list>
#include <string>
#include <utility>

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

private:
  ValidationReport& report_;
};

} // namespace vm::detail
