#include "fields/point_cloud.hpp"

#include "voronoimesh/core/errors.hpp"

#include "core/text.hpp"
#include "core/input_file.hpp"
#include "core/parallel.hpp"
#include "fields/top_k.hpp"

#include <nanoflann.hpp>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <sstream>
#include <tuple>

namespace vm::detail {

namespace {

/// The points nanoflann indexes.
struct Points {
  std::vector<Vec3> p;
  size_t kdtree_get_point_count() const { return p.size(); }
  double kdtree_get_pt(size_t i, size_t dim) const { return p[i][int(dim)]; }
  template <class Box> bool kdtree_get_bbox(Box&) const { return false; }
};
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Points>, Points, 3, uint32_t>;

/// A k-d tree over its own copy of the points. A single point (a grain of one
/// seed) gets no tree: nanoflann's would take 8 KB, 80 MB for 10,000 grains.
struct Indexed {
  Points points;
  std::unique_ptr<Tree> tree;
  explicit Indexed(std::vector<Vec3> p)
      : points{std::move(p)}, tree(points.p.size() > 1 ? std::make_unique<Tree>(3, points) : nullptr) {}
  /// The nearest point to x.
  const Vec3& nearest(const Vec3& x) const {
    if (!tree) return points.p[0];
    uint32_t i = 0;
    double d2 = 0;
    tree->knnSearch(x.data(), 1, &i, &d2);
    return points.p[i];
  }
};

class PointCloudField final : public PhaseField {
public:
  PointCloudField(std::vector<Vec3> points, const std::vector<int32_t>& phase_of_point, std::vector<int32_t> labels)
      : labels_(std::move(labels)), phase_of_point_(phase_of_point), all_(points) {
    std::vector<std::vector<Vec3>> split(labels_.size());
    for (size_t i = 0; i < points.size(); ++i) split[size_t(phase_of_point[i])].push_back(points[i]);
    for (auto& s : split) regions_.push_back(std::make_unique<Indexed>(std::move(s)));
  }
  int num_phases() const override { return int(labels_.size()); }
  std::string phase_name(int i) const override { return cat("label", labels_.at(size_t(i))); }
  int32_t phase_label(int i) const override { return labels_.at(size_t(i)); }
  double value(int i, const Vec3& x) const override { return -(x - nearest(i, x)).norm(); }
  /// -(x - p) / |x - p| for the nearest p of the region; 0 on p.
  Vec3 gradient(int i, const Vec3& x) const override {
    const Vec3 d = x - nearest(i, x);
    const double n = d.norm();
    return n > 0 ? Vec3(-d / n) : Vec3::Zero();
  }
  void values(const Vec3& x, std::span<double> out) const override {
    for (int i = 0; i < num_phases(); ++i) out[size_t(i)] = value(i, x);
  }
  /// The k nearest distinct regions. Where regions are many and mixed, the
  /// nearest points of all regions together give them (the first point met of
  /// each region is its nearest). A region not met among the first few hundred
  /// points is far away; asking each such region's own tree is then far cheaper
  /// than growing the search towards the whole cloud, which nanoflann's sorted
  /// result set makes quadratic in the points asked for (minutes for a 32^3
  /// grid over 8000 points in four regions). With few regions, asking each
  /// one's tree straight away is cheapest of all.
  void top_values(const Vec3& x, std::span<int32_t> ids, std::span<double> vals) const override {
    thread_local std::vector<uint32_t> idx;
    thread_local std::vector<double> d2;
    thread_local std::vector<std::pair<double, int32_t>> best; // (value, phase)
    best.clear();
    const auto met = [&](int32_t phase) {
      return std::any_of(best.begin(), best.end(), [&](const auto& b) { return b.second == phase; });
    };
    const size_t total = all_.points.p.size(), k = ids.size();
    constexpr size_t max_want = 256;
    for (size_t want = 2 * k; size_t(num_phases()) > 2 * k; want *= 4) {
      want = std::min(want, total);
      idx.resize(want), d2.resize(want);
      const size_t got = all_.tree->knnSearch(x.data(), want, idx.data(), d2.data());
      best.clear();
      for (size_t j = 0; j < got && best.size() < k; ++j)
        if (const int32_t phase = phase_of_point_[idx[j]]; !met(phase)) best.emplace_back(-std::sqrt(d2[j]), phase);
      if (best.size() == k || want == total || want >= max_want) break;
    }
    if (best.size() < k)
      for (int32_t phase = 0; phase < num_phases(); ++phase)
        if (!met(phase)) best.emplace_back(value(phase, x), phase);
    // Equal distances: lower id first, as everywhere else.
    std::sort(best.begin(), best.end(), [](auto& a, auto& b) { return ranks_before(a.first, a.second, b.first, b.second); });
    for (size_t s = 0; s < k; ++s) ids[s] = best[s].second, vals[s] = best[s].first;
  }

private:
  /// The nearest point of region i to x. A grain of one seed needs no search.
  /// Projection asks for the value and then the gradient of each phase at one
  /// point, so each thread keeps its last answer: one search serves both.
  const Vec3& nearest(int i, const Vec3& x) const {
    const Indexed& region = *regions_[size_t(i)];
    if (!region.tree) return region.points.p[0];
    struct Last {
      uint64_t field = 0; // serial_ of the field asked; 0 for none
      int phase = -1;
      Vec3 x;
      const Vec3* nearest = nullptr;
    };
    thread_local Last last;
    if (last.field == serial_ && last.phase == i && last.x == x) return *last.nearest;
    const Vec3& p = region.nearest(x);
    last = {serial_, i, x, &p};
    return p;
  }

  /// Tells fields apart in the per-thread cache of nearest(): an address can be
  /// reused by a later field, a serial is not.
  static uint64_t next_serial() {
    static std::atomic<uint64_t> counter{0};
    return ++counter;
  }

  uint64_t serial_ = next_serial();
  std::vector<int32_t> labels_;
  std::vector<int32_t> phase_of_point_;
  Indexed all_;
  std::vector<std::unique_ptr<Indexed>> regions_;
};

/// The fields of one line split at whitespace and commas.
std::vector<std::string> fields_of(const std::string& line) {
  std::string s = line.substr(0, line.find('#'));
  std::replace(s.begin(), s.end(), ',', ' ');
  std::istringstream in(s);
  std::vector<std::string> out;
  for (std::string f; in >> f;) out.push_back(f);
  return out;
}

template <class T> bool parse(const std::string& s, T& v) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return ec == std::errc() && end == s.data() + s.size();
}

} // namespace

bool is_point_file(const std::string& path) {
  const std::string p = lower(path);
  return p.ends_with(".xyz") || p.ends_with(".txt") || p.ends_with(".pts") || p.ends_with(".csv") || p.ends_with(".ply");
}

namespace {

/// "x y z label" lines (point_cloud_scene).
LabelledPoints read_text_points(const std::string& path) {
  // Bounded by the memory the points will take (read_text_file checks it).
  std::string contents = read_text_file(path, UINT64_MAX, "a point file");
  // Spreadsheets and Windows editors start UTF-8 text with a byte order mark,
  // which would otherwise make the first point a malformed line.
  if (contents.starts_with("\xEF\xBB\xBF")) contents.erase(0, 3);
  std::istringstream text(std::move(contents));
  LabelledPoints out;
  int line_no = 0;
  bool first = true;
  for (std::string line; std::getline(text, line);) {
    ++line_no;
    const auto f = fields_of(line);
    if (f.empty()) continue;
    Vec3 p;
    int64_t label = 0; // wider than a label, to say "out of range" rather than "not a number"
    const bool ok = f.size() == 4 && parse(f[0], p.x()) && parse(f[1], p.y()) && parse(f[2], p.z()) && parse(f[3], label);
    if (!ok && first && lower(path).ends_with(".csv")) { first = false; continue; } // a header row
    first = false;
    if (!ok)
      throw InvalidInput(located(path, cat("line ", line_no, ": expected 'x y z label' (three numbers and an integer), got '", line, "'")));
    if (!p.allFinite()) throw InvalidInput(located(path, cat("line ", line_no, ": coordinates must be finite")));
    if (label != int32_t(label)) throw InvalidInput(located(path, cat("line ", line_no, ": label ", label, " is not a 32-bit integer")));
    out.points.push_back(p);
    out.labels.push_back(int32_t(label));
  }
  return out;
}

} // namespace

namespace {

/// Refuses two points at the same place with different labels: each label's
/// phase ties with the other's there, and a label whose every point is such a
/// pair leads nowhere (the cloud "meshed to nothing" with no word of why).
/// Points are named by their place in the file, counting from 1.
void refuse_points_with_two_labels(const std::vector<Vec3>& points, const std::vector<int32_t>& labels,
                                   const std::string& path) {
  std::vector<size_t> order(points.size());
  std::iota(order.begin(), order.end(), size_t{0});
  auto before = [&](size_t a, size_t b) {
    const Vec3 &p = points[a], &q = points[b];
    return std::tie(p.x(), p.y(), p.z(), a) < std::tie(q.x(), q.y(), q.z(), b);
  };
  detail::parallel_sort(order.begin(), order.end(), before);
  for (size_t i = 1; i < order.size(); ++i) {
    const size_t a = order[i - 1], b = order[i];
    if (points[a] != points[b] || labels[a] == labels[b]) continue;
    const Vec3& p = points[a];
    throw InvalidInput(located(path, cat("points ", a + 1, " and ", b + 1, " lie at the same place (", p.x(), ", ",
                                         p.y(), ", ", p.z(), ") with different labels (", labels[a], " and ",
                                         labels[b], "): each point needs one label")));
  }
}

} // namespace

Scene point_cloud_scene(const std::string& path, const InputOptions&) {
  return point_cloud_scene(lower(path).ends_with(".ply") ? read_ply_points(path) : read_text_points(path), path);
}

Scene point_cloud_scene(LabelledPoints cloud, const std::string& path) {
  auto& [points, point_labels] = cloud;
  if (points.size() != point_labels.size())
    throw InvalidInput(located(path, cat(points.size(), " points but ", point_labels.size(), " labels")));
  for (size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) throw InvalidInput(located(path, cat("point ", i, ": coordinates must be finite")));
  if (points.empty()) throw InvalidInput(located(path, "has no points"));
  refuse_points_with_two_labels(points, point_labels, path);
  std::vector<int32_t> labels = point_labels;
  std::sort(labels.begin(), labels.end());
  labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
  if (labels.size() < 2)
    throw InvalidInput(located(path, cat("has ", labels.size(), " label(s); a labelled point cloud needs 2 or more")));
  if (labels.size() > kMaxPhases)
    throw InvalidInput(located(path, cat("has ", labels.size(), " distinct labels; at most ", kMaxPhases)));
  std::vector<int32_t> phase_of_point(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    phase_of_point[i] = int32_t(std::lower_bound(labels.begin(), labels.end(), point_labels[i]) - labels.begin());

  Box box{points[0], points[0]};
  for (const Vec3& p : points) box.min = box.min.cwiseMin(p), box.max = box.max.cwiseMax(p);
  const double side = std::max((box.max - box.min).maxCoeff(), 1e-9 * std::max(1.0, box.max.cwiseAbs().maxCoeff()));
  const double margin = 0.05 * side, h = (side + 2 * margin) / 64;
  // Finite points can still lie further apart than a double holds (|x| > 8e307).
  if (!std::isfinite(side + 2 * margin))
    throw InvalidInput(located(path, cat("the points span more than ", std::numeric_limits<double>::max() / 1.1,
                                         " along an axis; rescale them")));
  Scene scene;
  for (int a = 0; a < 3; ++a) {
    // Cells of size h (at least 2), centred on the points.
    const int cells = std::max(2, int(std::ceil((box.max[a] - box.min[a] + 2 * margin) / h - 1e-9)));
    const double mid = (box.min[a] + box.max[a]) / 2;
    scene.grid.cells[size_t(a)] = cells;
    scene.grid.domain.min[a] = mid - cells * h / 2;
    scene.grid.domain.max[a] = mid + cells * h / 2;
  }
  scene.field = std::make_shared<PointCloudField>(std::move(points), phase_of_point, std::move(labels));
  return scene;
}

} // namespace vm::detail
