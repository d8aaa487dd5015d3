#include "fixtures.hpp"

#include "voronoimesh/check/history.hpp"
#include "voronoimesh/core/errors.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <sstream>

using namespace vm;
namespace fs = std::filesystem;

namespace {

constexpr Measure kAll[] = {Measure::inradius, Measure::circumradius, Measure::edge_length,
                            Measure::quality,  Measure::angle,        Measure::degree};

/// The regular tetrahedron: four equilateral triangles.
NodeMesh regular_tetrahedron() {
  test::Builder b;
  test::add_tetrahedron(b, {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)}, 1, 0);
  return b.mesh;
}

/// The regular icosahedron (edge length 2), outward-oriented, phase 1 inside 0.
NodeMesh icosahedron() {
  const double g = (1 + std::sqrt(5.0)) / 2;
  NodeMesh m;
  for (double s : {-1.0, 1.0})
    for (double t : {-1.0, 1.0}) {
      m.points.emplace_back(0, s, t * g);
      m.points.emplace_back(s, t * g, 0);
      m.points.emplace_back(t * g, 0, s);
    }
  const int n = int(m.points.size());
  auto edge = [&](int i, int j) { return std::abs((m.points[size_t(i)] - m.points[size_t(j)]).norm() - 2) < 1e-9; };
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k)
        if (edge(i, j) && edge(j, k) && edge(i, k)) {
          const Vec3 &a = m.points[size_t(i)], &b = m.points[size_t(j)], &c = m.points[size_t(k)];
          if ((b - a).cross(c - a).dot(a) > 0)
            m.triangles.push_back({i, j, k});
          else
            m.triangles.push_back({i, k, j});
          m.pairs.push_back({0, 1});
        }
  return m;
}

/// Splits every triangle into four, pushing new nodes onto the unit sphere.
NodeMesh subdivide_on_sphere(const NodeMesh& in) {
  NodeMesh m = in;
  m.triangles.clear();
  m.pairs.clear();
  for (Vec3& p : m.points) p.normalize();
  std::map<std::pair<int32_t, int32_t>, int32_t> mid;
  auto midpoint = [&](int32_t a, int32_t b) {
    auto [it, added] = mid.try_emplace({std::min(a, b), std::max(a, b)}, int32_t(m.points.size()));
    if (added) m.points.push_back((m.points[size_t(a)] + m.points[size_t(b)]).normalized());
    return it->second;
  };
  for (const auto& t : in.triangles) {
    const int32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
    for (const std::array<int32_t, 3>& s :
         {std::array{t[0], ab, ca}, std::array{ab, t[1], bc}, std::array{ca, bc, t[2]}, std::array{ab, bc, ca}}) {
      m.triangles.push_back(s);
      m.pairs.push_back({0, 1});
    }
  }
  return m;
}

/// Flips up to `count` random edges of a closed oriented manifold mesh, keeping
/// every node degree >= 4 and never creating a duplicate edge.
void random_flips(NodeMesh& m, int count, std::mt19937& rng) {
  std::uniform_int_distribution<size_t> pick_tri(0, m.triangles.size() - 1);
  std::uniform_int_distribution<int> pick_corner(0, 2);
  for (int done = 0, tries = 0; done < count && tries < 20 * count; ++tries) {
    std::map<std::pair<int32_t, int32_t>, size_t> halfedge; // (from, to) -> triangle
    std::vector<int> degree(m.points.size(), 0);
    for (size_t t = 0; t < m.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        halfedge[{m.triangles[t][size_t(k)], m.triangles[t][size_t((k + 1) % 3)]}] = t;
        ++degree[size_t(m.triangles[t][size_t(k)])];
      }
    const size_t t1 = pick_tri(rng);
    const int k = pick_corner(rng);
    const int32_t a = m.triangles[t1][size_t(k)], b = m.triangles[t1][size_t((k + 1) % 3)],
                  c = m.triangles[t1][size_t((k + 2) % 3)];
    const size_t t2 = halfedge.at({b, a});
    int32_t d = -1;
    for (int32_t v : m.triangles[t2])
      if (v != a && v != b) d = v;
    if (d == c || halfedge.count({c, d}) || degree[size_t(a)] <= 4 || degree[size_t(b)] <= 4) continue;
    m.triangles[t1] = {a, d, c};
    m.triangles[t2] = {d, b, c};
    ++done;
  }
}

/// A realistic improvement run: a subdivided icosahedron (642 nodes) whose
/// connectivity is scrambled by random flips and whose nodes are jittered, both
/// decaying with the iteration, as smoothing and flipping would repair them.
QualityHistory example_history(int iterations) {
  const NodeMesh regular = subdivide_on_sphere(subdivide_on_sphere(subdivide_on_sphere(icosahedron())));
  QualityHistory h;
  std::mt19937 rng(12345);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int it = 0; it <= iterations; ++it) {
    NodeMesh m = regular;
    random_flips(m, int(std::lround(260 * std::pow(0.72, it))), rng);
    const double jitter = 0.045 * std::pow(0.8, it) + 0.004; // edge length ~0.1
    for (Vec3& p : m.points) p = (p + jitter * Vec3(normal(rng), normal(rng), normal(rng))).normalized();
    h.record(it, m);
  }
  return h;
}

std::string read_all(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

/// A fresh empty directory for one test.
fs::path scratch_dir(const std::string& name) {
  const fs::path d = fs::path(testing::TempDir()) / ("vm_history_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

size_t count_of(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}

} // namespace

TEST(MeasureBins, fixed_bins_and_edges) {
  const MeasureBins& len = measure_bins(Measure::edge_length);
  EXPECT_EQ(len.size(), 51u);
  EXPECT_TRUE(std::isinf(len.hi.back()));
  EXPECT_EQ(len.bin_of(1.0), 20u);
  EXPECT_EQ(len.bin_of(2.0), 40u);
  EXPECT_EQ(len.bin_of(7.0), 50u);
  EXPECT_EQ(len.bin_of(INFINITY), 50u);
  EXPECT_EQ(measure_bins(Measure::quality).size(), 40u);
  EXPECT_EQ(measure_bins(Measure::quality).bin_of(1.0), 39u);
  EXPECT_EQ(measure_bins(Measure::quality).bin_of(0.0), 0u);
  const MeasureBins& angle = measure_bins(Measure::angle);
  EXPECT_EQ(angle.size(), 36u);
  EXPECT_EQ(angle.bin_of(60.0 - 1e-12), 12u); // rounding below an edge counts above
  EXPECT_EQ(angle.bin_of(180.0), 35u);
  const MeasureBins& deg = measure_bins(Measure::degree);
  EXPECT_EQ(deg.size(), 16u);
  EXPECT_EQ(deg.bin_of(5), 5u);
  EXPECT_EQ(deg.bin_of(15), 15u);
  EXPECT_EQ(deg.bin_of(40), 15u);
}

TEST(QualityHistory, percentages_sum_to_100_per_measure_and_iteration) {
  const QualityHistory h = example_history(6);
  ASSERT_EQ(h.size(), 7u);
  for (size_t r = 0; r < h.size(); ++r)
    for (Measure m : kAll) {
      const std::vector<double> p = h.percent(r, m);
      EXPECT_NEAR(std::accumulate(p.begin(), p.end(), 0.0), 100.0, 1e-9) << int(m) << " at " << r;
      EXPECT_GT(h.total(r, m), 0u);
    }
  // Features: 1280 triangles (x3 angles), 1920 edges, 642 nodes.
  EXPECT_EQ(h.total(0, Measure::quality), 1280u);
  EXPECT_EQ(h.total(0, Measure::angle), 3840u);
  EXPECT_EQ(h.total(0, Measure::edge_length), 1920u);
  EXPECT_EQ(h.total(0, Measure::degree), 642u);
  // The example improves: fewer triangles below q = 0.5 at the end.
  auto below_half = [&](size_t r) {
    const std::vector<double> p = h.percent(r, Measure::quality);
    return std::accumulate(p.begin(), p.begin() + 20, 0.0);
  };
  EXPECT_LT(below_half(6), below_half(0));
}

TEST(QualityHistory, equilateral_mesh_is_in_the_top_quality_and_60_degree_bins) {
  QualityHistory h;
  h.record(0, regular_tetrahedron());
  EXPECT_DOUBLE_EQ(h.percent(0, Measure::quality).back(), 100.0);
  EXPECT_DOUBLE_EQ(h.percent(0, Measure::angle)[measure_bins(Measure::angle).bin_of(60)], 100.0);
  EXPECT_EQ(measure_bins(Measure::angle).lo[measure_bins(Measure::angle).bin_of(60)], 60.0);
  EXPECT_DOUBLE_EQ(h.percent(0, Measure::degree)[3], 100.0);
}

TEST(QualityHistory, icosahedron_has_degree_5_everywhere) {
  QualityHistory h;
  h.record(0, icosahedron());
  EXPECT_EQ(h.total(0, Measure::degree), 12u);
  const std::vector<double> p = h.percent(0, Measure::degree);
  for (size_t d = 0; d < p.size(); ++d) EXPECT_DOUBLE_EQ(p[d], d == 5 ? 100.0 : 0.0) << d;
}

TEST(QualityHistory, initial_mesh_fixes_the_length_scale) {
  NodeMesh m = icosahedron();
  QualityHistory h;
  h.record(0, m);
  EXPECT_NEAR(h.length_scale(), 2.0, 1e-12);
  for (Vec3& p : m.points) p *= 2;
  h.record(1, m);
  EXPECT_NEAR(h.length_scale(), 2.0, 1e-12); // not re-fixed
  const MeasureBins& len = measure_bins(Measure::edge_length);
  EXPECT_DOUBLE_EQ(h.percent(0, Measure::edge_length)[len.bin_of(1.0)], 100.0);
  EXPECT_DOUBLE_EQ(h.percent(1, Measure::edge_length)[len.bin_of(2.0)], 100.0);
  // Circumradius of an equilateral triangle: L / sqrt(3), relative 1/sqrt(3), then twice that.
  const MeasureBins& circ = measure_bins(Measure::circumradius);
  EXPECT_DOUBLE_EQ(h.percent(0, Measure::circumradius)[circ.bin_of(1 / std::sqrt(3.0))], 100.0);
  EXPECT_DOUBLE_EQ(h.percent(1, Measure::circumradius)[circ.bin_of(2 / std::sqrt(3.0))], 100.0);
  // Inradius L / (2 sqrt(3)).
  const MeasureBins& in = measure_bins(Measure::inradius);
  EXPECT_DOUBLE_EQ(h.percent(1, Measure::inradius)[in.bin_of(1 / std::sqrt(3.0))], 100.0);
  // Quality and angles do not depend on scale.
  EXPECT_EQ(h.counts(0, Measure::quality), h.counts(1, Measure::quality));
  EXPECT_EQ(h.counts(0, Measure::angle), h.counts(1, Measure::angle));
}

TEST(QualityHistory, degenerate_and_malformed_triangles) {
  NodeMesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(5, 5, 5)};
  m.triangles = {{0, 1, 2}, {0, 0, 1}, {0, 1, 9}};
  m.pairs = {{0, 1}, {0, 1}, {0, 1}};
  QualityHistory h;
  h.record(0, m);
  EXPECT_EQ(h.total(0, Measure::quality), 1u); // the malformed two are skipped
  EXPECT_DOUBLE_EQ(h.percent(0, Measure::quality)[0], 100.0);
  EXPECT_DOUBLE_EQ(h.percent(0, Measure::inradius)[0], 100.0);
  EXPECT_DOUBLE_EQ(h.percent(0, Measure::circumradius).back(), 100.0); // flat: R = inf, overflow
  EXPECT_DOUBLE_EQ(h.percent(0, Measure::degree)[0], 25.0);            // node 3 is unused
}

TEST(QualityHistory, iterations_must_increase) {
  QualityHistory h;
  h.record(0, icosahedron());
  EXPECT_THROW(h.record(0, icosahedron()), InvalidInput);
  EXPECT_THROW(QualityHistory().record(-1, icosahedron()), InvalidInput);
  h.record(5, icosahedron());
  EXPECT_EQ(h.iterations(), (std::vector<int>{0, 5}));
}

TEST(QualityHistory, csv_has_header_and_one_row_per_measure_iteration_and_bin) {
  const QualityHistory h = example_history(3);
  const fs::path d = scratch_dir("csv");
  h.write((d / "h.csv").string());
  const std::string text = read_all(d / "h.csv");
  std::istringstream in(text);
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line, "measure,iteration,bin_lo,bin_hi,percent");
  size_t rows = 0, bins = 0;
  double edge_sum_it2 = 0;
  while (std::getline(in, line)) {
    ++rows;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 4) << line;
    if (line.rfind("edge_length,2,", 0) == 0) edge_sum_it2 += std::stod(line.substr(line.rfind(',') + 1));
  }
  for (Measure m : kAll) bins += measure_bins(m).size();
  EXPECT_EQ(rows, 4 * bins);
  EXPECT_NEAR(edge_sum_it2, 100.0, 1e-5);
  EXPECT_NE(text.find("\nedge_length,0,2.5,inf,"), std::string::npos);
  EXPECT_NE(text.find("\ndegree,3,15,inf,"), std::string::npos);
  EXPECT_NE(text.find("\nangle,1,60,65,"), std::string::npos);
}

TEST(QualityHistory, json_parses_and_matches) {
  const QualityHistory h = example_history(2);
  const fs::path d = scratch_dir("json");
  h.write((d / "h.JSON").string()); // extension is case-insensitive
  const nlohmann::json j = nlohmann::json::parse(read_all(d / "h.JSON"));
  EXPECT_NEAR(j.at("length_scale").get<double>(), h.length_scale(), 1e-15);
  EXPECT_EQ(j.at("iterations"), nlohmann::json({0, 1, 2}));
  ASSERT_EQ(j.at("measures").size(), 6u);
  for (size_t k = 0; k < 6; ++k) {
    const auto& mj = j["measures"][k];
    const MeasureBins& bins = measure_bins(kAll[k]);
    EXPECT_EQ(mj.at("key"), bins.key);
    EXPECT_EQ(mj.at("bin_lo").size(), bins.size());
    EXPECT_EQ(mj.at("bin_hi").back().is_null(), std::isinf(bins.hi.back()));
    ASSERT_EQ(mj.at("percent").size(), 3u);
    for (size_t r = 0; r < 3; ++r) {
      EXPECT_EQ(mj["total"][r].get<size_t>(), h.total(r, kAll[k]));
      EXPECT_EQ(mj["count"][r].get<std::vector<size_t>>(), h.counts(r, kAll[k]));
      const auto p = mj["percent"][r].get<std::vector<double>>();
      EXPECT_NEAR(std::accumulate(p.begin(), p.end(), 0.0), 100.0, 1e-9);
    }
  }
}

TEST(QualityHistory, svg_is_well_formed_with_six_panels) {
  const QualityHistory h = example_history(30);
  const fs::path d = scratch_dir("svg");
  h.write((d / "h.svg").string());
  const std::string s = read_all(d / "h.svg");
  EXPECT_EQ(s.rfind("<svg", 0), 0u);
  EXPECT_EQ(s.substr(s.size() - 7), "</svg>\n");
  EXPECT_EQ(count_of(s, "<svg"), 1u);
  for (const char* tag : {"text", "g"}) EXPECT_EQ(count_of(s, std::string("<") + tag + " "), count_of(s, std::string("</") + tag + ">")) << tag;
  for (Measure m : kAll) EXPECT_EQ(count_of(s, std::string(">") + measure_bins(m).title + "<"), 1u) << measure_bins(m).title;
  EXPECT_NE(s.find("x RMS edge length (initial)"), std::string::npos);
  EXPECT_NE(s.find(">iteration<"), std::string::npos);
  EXPECT_NE(s.find("20\u201350%"), std::string::npos); // the legend
  EXPECT_EQ(s.find("nan"), std::string::npos);
  EXPECT_EQ(s.find("inf"), std::string::npos);

  // For a visual check: VM_HISTORY_EXAMPLE=/some/dir writes the example there.
  if (const char* dir = std::getenv("VM_HISTORY_EXAMPLE")) {
    for (const char* name : {"history.svg", "history.csv", "history.json"}) h.write((fs::path(dir) / name).string());
    QualityHistory empty;
    empty.write((fs::path(dir) / "history_empty.svg").string());
  }
}

TEST(QualityHistory, empty_history_still_writes) {
  const QualityHistory h;
  EXPECT_EQ(h.csv(), "measure,iteration,bin_lo,bin_hi,percent\n");
  EXPECT_EQ(nlohmann::json::parse(h.json()).at("measures").size(), 6u);
  EXPECT_NE(h.svg().find("no data"), std::string::npos);
}

TEST(QualityHistory, bad_extension_is_invalid_input_and_writes_nothing) {
  QualityHistory h;
  h.record(0, icosahedron());
  const fs::path d = scratch_dir("ext");
  for (const char* name : {"h.txt", "h", "dir.svg/h", "h.svg.bak"})
    EXPECT_THROW(h.write((d / name).string()), InvalidInput) << name;
  EXPECT_TRUE(fs::is_empty(d));
}

TEST(QualityHistory, unwritable_path_is_io_error_and_leaves_no_file) {
  QualityHistory h;
  h.record(0, icosahedron());
  const fs::path d = scratch_dir("io");
  // Missing directory: the temporary file cannot be created.
  const std::string missing = (d / "no_such_dir" / "h.svg").string();
  try {
    h.write(missing);
    ADD_FAILURE() << "no exception";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(missing + ": cannot write (", 0), 0u) << e.what();
  }
  // The target is a directory: the rename fails and the temporary file is removed.
  fs::create_directory(d / "taken.csv");
  EXPECT_THROW(h.write((d / "taken.csv").string()), IoError);
  std::set<std::string> left;
  for (const auto& e : fs::directory_iterator(d)) left.insert(e.path().filename().string());
  EXPECT_EQ(left, std::set<std::string>{"taken.csv"});
  EXPECT_TRUE(fs::is_empty(d / "taken.csv"));
  // A successful write replaces an existing file and leaves nothing else.
  std::ofstream(d / "h.json") << "old";
  h.write((d / "h.json").string());
  EXPECT_NE(read_all(d / "h.json"), "old");
  left.clear();
  for (const auto& e : fs::directory_iterator(d)) left.insert(e.path().filename().string());
  EXPECT_EQ(left, (std::set<std::string>{"h.json", "taken.csv"}));
}
