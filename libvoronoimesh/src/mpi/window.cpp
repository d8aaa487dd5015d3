/// @file mpi/window.cpp
/// Bands and windows of distributed improvement (window.hpp).

#include "mpi/window.hpp"


#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace vm::mpi::detail {

Bands::Bands(Comm& comm, std::vector<double> own_z) {
    std::sort(own_z.begin(), own_z.end());
    constexpr size_t kSamples = 1024;
    struct Sample {
      double z, weight;
    };
    std::vector<Sample> mine;
    const size_t step = std::max<size_t>(1, own_z.size() / kSamples);
    for (size_t i = 0; i < own_z.size(); i += step)
      mine.push_back({own_z[i], double(std::min(step, own_z.size() - i))});
    std::vector<Sample> all = comm.all_gather(std::span<const Sample>(mine));
    std::sort(all.begin(), all.end(), [](const Sample& a, const Sample& b) { return a.z < b.z; });
    double total = 0;
    for (const Sample& s : all) total += s.weight;
    cuts_.assign(size_t(comm.size()) + 1, -std::numeric_limits<double>::infinity());
    cuts_.back() = std::numeric_limits<double>::infinity();
    double seen = 0;
    size_t next = 1;
    for (const Sample& s : all) {
      while (next < size_t(comm.size()) && seen >= total * double(next) / comm.size()) cuts_[next++] = s.z;
      seen += s.weight;
    }
    for (; next < size_t(comm.size()); ++next) cuts_[next] = cuts_[next - 1];
  }

int Bands::owner(double z) const {
  return int(std::upper_bound(cuts_.begin() + 1, cuts_.end() - 1, z) - (cuts_.begin() + 1));
}

int32_t Window::local(int64_t id) const {
  const auto at = std::lower_bound(vertex_ids.begin(), vertex_ids.end(), id);
  return at != vertex_ids.end() && *at == id ? int32_t(at - vertex_ids.begin()) : -1;
}

Window build_window(std::vector<TriangleRecord> records, const MeshPart& part) {
  std::sort(records.begin(), records.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  Window w;
  std::vector<std::pair<int64_t, Vec3>> vertices;
  for (const TriangleRecord& t : records)
    for (int c = 0; c < 3; ++c) vertices.push_back({t.corners[c], Vec3(t.xyz[c][0], t.xyz[c][1], t.xyz[c][2])});
  std::sort(vertices.begin(), vertices.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  vertices.erase(std::unique(vertices.begin(), vertices.end(),
                             [](const auto& a, const auto& b) { return a.first == b.first; }),
                 vertices.end());
  std::unordered_map<int64_t, int32_t> local;
  for (const auto& [id, p] : vertices) {
    local.emplace(id, int32_t(w.vertex_ids.size()));
    w.vertex_ids.push_back(id);
    w.mesh.points.push_back(p);
  }
  for (const TriangleRecord& t : records) {
    w.mesh.triangles.push_back({local.at(t.corners[0]), local.at(t.corners[1]), local.at(t.corners[2])});
    w.mesh.pairs.push_back(t.pair);
    w.triangle_ids.push_back(t.id);
  }
  w.mesh.domain = part.domain;
  w.mesh.grid_spacing = part.grid_spacing;
  w.mesh.phase_names = part.phase_names;
  w.mesh.phase_labels = part.phase_labels;
  w.mesh.phase_colors = part.phase_colors;
  w.mesh.outside_phase = part.outside_phase;
  return w;
}

double longest_edge(const std::vector<TriangleRecord>& records) {
  double longest = 0;
  for (const TriangleRecord& t : records)
    for (int c = 0; c < 3; ++c) {
      const double* a = t.xyz[c];
      const double* b = t.xyz[(c + 1) % 3];
      longest = std::max(longest, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
    }
  return longest;
}

/// The triangles' first window: each triangle is in exactly one created part.
std::vector<TriangleRecord> records_of(const MeshPart& part) {
  std::vector<TriangleRecord> out;
  for (size_t t = 0; t < part.triangles.size(); ++t) {
    TriangleRecord r{part.triangle_ids[t], {}, part.pairs[t], {}};
    for (int c = 0; c < 3; ++c) {
      const size_t v = size_t(part.triangles[t][size_t(c)]);
      r.corners[c] = part.global_ids[v];
      for (int a = 0; a < 3; ++a) r.xyz[c][a] = part.points[v][a];
    }
    out.push_back(r);
  }
  return out;
}

} // namespace vm::mpi::detail
