/// @file io/phase_names.cpp
/// Phase, pair and junction names shared by the writers (io/phase_names.hpp).

#include "io/phase_names.hpp"

#include <algorithm>

namespace vm::io::detail {

size_t phase_count(const NodeMesh& m) {
  size_t n = std::max(m.phase_names.size(), m.phase_labels.size());
  for (const PhasePair& p : m.pairs) n = std::max(n, size_t(std::max(p[1], p[0])) + 1);
  return n;
}

std::string phase_name(const NodeMesh& m, int32_t p) {
  return size_t(p) < m.phase_names.size() ? m.phase_names[size_t(p)] : std::string();
}

std::optional<Rgb> phase_color(const NodeMesh& m, int32_t p) {
  return size_t(p) < m.phase_colors.size() ? m.phase_colors[size_t(p)] : std::nullopt;
}

bool has_phase_colors(const NodeMesh& m) {
  return std::any_of(m.phase_colors.begin(), m.phase_colors.end(), [](const auto& c) { return c.has_value(); });
}

std::string phase_token(const NodeMesh& m, int32_t p) {
  std::string token = std::to_string(m.label_of(p));
  const std::string name = phase_name(m, p);
  if (name.empty()) return token;
  token += '-';
  for (char c : name) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                      c == '+' || c == '-';
    token += keep ? c : '-';
  }
  return token;
}

std::string phases_token(const NodeMesh& m, std::span<const int32_t> phases) {
  std::string s;
  for (int32_t p : phases) {
    if (!s.empty()) s += '_';
    s += phase_token(m, p);
  }
  return s;
}

std::vector<PhasePair> distinct_pairs(const NodeMesh& m) {
  std::vector<PhasePair> pairs = m.pairs;
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

std::vector<int32_t> pair_indices(const NodeMesh& m, const std::vector<PhasePair>& pairs) {
  std::vector<int32_t> index(m.pairs.size());
  for (size_t t = 0; t < m.pairs.size(); ++t)
    index[t] = int32_t(std::lower_bound(pairs.begin(), pairs.end(), m.pairs[t]) - pairs.begin());
  return index;
}

} // namespace vm::io::detail
