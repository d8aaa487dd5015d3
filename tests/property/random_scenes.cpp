#include "random_scenes.hpp"

#include "voronoimesh/fields/array_input.hpp"

#include "json_numbers.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <span>
#include <sstream>
#include <vector>

namespace vm::test {

namespace {

/// splitmix64's finaliser: spreads (seed, index) over the engine's seed so
/// that neighbouring cases share nothing.
uint64_t mix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// Portable random numbers: only the engine's raw output is used.
class Rng {
public:
  Rng(uint64_t seed, uint64_t index) : engine_(mix(mix(seed) ^ index)) {}
  /// In [0, 1), 53 random bits.
  double uniform() { return double(engine_() >> 11) * 0x1p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// In [lo, hi].
  int integer(int lo, int hi) { return lo + int(engine_() % uint64_t(hi - lo + 1)); }
  bool chance(double p) { return uniform() < p; }
  template <class T, size_t N> T pick(const std::array<T, N>& from) { return from[size_t(integer(0, int(N) - 1))]; }
  Vec3 unit_vector() {
    for (;;) {
      const Vec3 v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
      if (v.norm() > 0.1 && v.norm() <= 1) return v.normalized();
    }
  }

private:
  std::mt19937_64 engine_;
};

/// The box of a case: a cube of side `size` at `origin` (sizes from 1e-3 to
/// 1e3, away from the origin), cut into cells (not always cubic) per axis.
/// Scenes are drawn in unit coordinates u in [0, 1]^3 and placed by world().
struct Frame {
  Vec3 origin;
  double size = 1;
  std::array<int, 3> cells{8, 8, 8};

  Vec3 world(const Vec3& u) const { return origin + size * u; }
  /// The smallest and largest grid spacing.
  double h_min() const { return size / *std::max_element(cells.begin(), cells.end()); }
  double h_max() const { return size / *std::min_element(cells.begin(), cells.end()); }
  GridSpec grid() const { return GridSpec{Box{origin, world(Vec3::Ones())}, cells}; }
  /// A grid node in unit coordinates.
  Vec3 node(Rng& rng) const {
    return Vec3(double(rng.integer(0, cells[0])) / cells[0], double(rng.integer(0, cells[1])) / cells[1],
                double(rng.integer(0, cells[2])) / cells[2]);
  }
};

Frame random_frame(Rng& rng) {
  Frame f;
  f.size = rng.pick(std::array{1.0, 1.0, 1.0, 1.0, 1e-3, 1e3});
  f.origin = f.size * Vec3(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
  const int n = rng.integer(4, 14);
  f.cells = {n, n, n};
  if (rng.chance(0.3)) f.cells = {rng.integer(3, 14), rng.integer(3, 14), rng.integer(3, 14)};
  return f;
}

MeshOptions random_options(Rng& rng) {
  MeshOptions o;
  o.lattice = rng.chance(0.25) ? Lattice::cube6 : Lattice::bcc;
  // From off through round-off-sized to the largest allowed, the paper's 0.2 most often.
  o.snap = rng.pick(std::array{0.0, 1e-12, 1e-4, 0.2, 0.2, 0.35, 0.5});
  o.top_k = rng.chance(0.15) ? rng.integer(2, 3) : 4;
  o.close = rng.chance(0.25);
  return o;
}

/// The JSON text of a scene with the given phase objects.
class SceneText {
public:
  explicit SceneText(const Frame& f) : frame_(f) {}
  void add(const std::string& phase_object) { phases_.push_back(phase_object); }
  void constant(double value) { add(R"({"kind": "constant", "value": )" + num(value) + "}"); }
  /// A sphere of radius `r` (unit coordinates) at unit point `c`.
  void sphere(const Vec3& c, double r) {
    add(R"({"kind": "sphere", "center": )" + point(frame_.world(c)) + R"(, "radius": )" + num(r * frame_.size) + "}");
  }
  void seeds(const std::vector<Vec3>& unit_points) {
    std::string list;
    for (const Vec3& p : unit_points) list += (list.empty() ? "" : ", ") + point(frame_.world(p));
    add(R"({"kind": "seeds", "points": [)" + list + "]}");
  }
  /// Signed distance to the plane through unit point `p`, positive along `n`.
  void plane(const Vec3& p, const Vec3& n) {
    add(R"({"kind": "plane", "point": )" + point(frame_.world(p)) + R"(, "normal": )" + point(n) + "}");
  }
  /// The slab of half thickness `t` (world units) around the plane through
  /// unit point `p` with unit normal `n`: t - |n . (x - p)|.
  void slab(const Vec3& p, const Vec3& n, double t) {
    const Vec3 q = frame_.world(p);
    std::string d;
    const char* axis[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a)
      d += (a ? " + " : "") + num(n[a]) + " * (" + axis[a] + " - " + num(q[a]) + ")";
    add(R"({"kind": "expr", "expr": ")" + num(t) + " - abs(" + d + ")\"}");
  }
  size_t count() const { return phases_.size(); }
  std::string json() const {
    const Vec3 hi = frame_.world(Vec3::Ones());
    std::string s = R"({"domain": {"min": )" + point(frame_.origin) + R"(, "max": )" + point(hi) + "}, \"grid\": [" +
                    std::to_string(frame_.cells[0]) + ", " + std::to_string(frame_.cells[1]) + ", " +
                    std::to_string(frame_.cells[2]) + "], \"phases\": [\n";
    for (size_t i = 0; i < phases_.size(); ++i) s += "  " + phases_[i] + (i + 1 < phases_.size() ? ",\n" : "\n");
    return s + "]}";
  }

private:
  const Frame& frame_;
  std::vector<std::string> phases_;
};

Vec3 unit_point(Rng& rng, double lo = 0, double hi = 1) {
  return Vec3(rng.uniform(lo, hi), rng.uniform(lo, hi), rng.uniform(lo, hi));
}

void spheres(Rng& rng, SceneText& s) {
  s.constant(0);
  Vec3 c(0.5, 0.5, 0.5);
  double r = 0.3;
  for (int i = 0, n = rng.integer(2, 6); i < n; ++i) {
    // Some repeat the previous sphere exactly (tied everywhere) or up to round-off.
    if (i > 0 && rng.chance(0.2))
      r += rng.chance(0.5) ? 0.0 : 1e-14;
    else
      c = unit_point(rng, -0.1, 1.1), r = rng.uniform(0.03, 0.45);
    s.sphere(c, r);
  }
}

void seeds(Rng& rng, const Frame& f, SceneText& s) {
  const bool on_nodes = rng.chance(0.5);
  std::vector<Vec3> all;
  for (int i = 0, n = rng.integer(2, 7); i < n; ++i) {
    std::vector<Vec3> points;
    for (int k = 0, m = rng.integer(1, 3); k < m; ++k) {
      // Now and then a point another phase already has: both tie around it.
      if (!all.empty() && rng.chance(0.1))
        points.push_back(all[size_t(rng.integer(0, int(all.size()) - 1))]);
      else
        points.push_back(on_nodes ? f.node(rng) : unit_point(rng));
      all.push_back(points.back());
    }
    s.seeds(points);
  }
}

void thin_slabs(Rng& rng, const Frame& f, SceneText& s) {
  s.constant(0);
  for (int i = 0, n = rng.integer(1, 3); i < n; ++i) {
    const Vec3 normal = rng.chance(0.3) ? Vec3::Unit(rng.integer(0, 2)) : rng.unit_vector();
    // Thinner than every grid spacing: the full thickness 2t is below h_min.
    s.slab(unit_point(rng, 0.2, 0.8), normal, f.h_min() * rng.uniform(0.02, 0.45));
  }
  if (rng.chance(0.5)) s.sphere(unit_point(rng, 0.2, 0.8), rng.uniform(0.1, 0.35));
}

void vanishing(Rng& rng, const Frame& f, SceneText& s) {
  s.constant(0);
  for (int i = 0, n = rng.integer(1, 3); i < n; ++i) s.sphere(unit_point(rng, 0.15, 0.85), rng.uniform(0.1, 0.3));
  for (int i = 0, n = rng.integer(1, 3); i < n; ++i) switch (rng.integer(0, 4)) {
    case 0: s.constant(-f.size); break;                                    // always below phase 0
    case 1: s.sphere(unit_point(rng), 0); break;                           // ties phase 0 at one point only
    case 2: s.sphere(unit_point(rng, 1.6, 2.0), 0.2); break;               // wholly outside the box
    case 3: s.sphere(unit_point(rng), 0.1 * f.h_min() / f.size); break;    // smaller than a cell
    default: s.seeds({unit_point(rng, 3, 4)}); break;                      // far outside: below phase 0
    }
}

void lattice_ties(Rng& rng, const Frame& f, SceneText& s) {
  s.constant(0);
  for (int i = 0, n = rng.integer(2, 4); i < n; ++i) {
    const Vec3 node = f.node(rng);
    switch (rng.integer(0, 2)) {
    case 0: s.plane(node, (rng.chance(0.5) ? 1.0 : -1.0) * Vec3::Unit(rng.integer(0, 2))); break;
    case 1: s.plane(node, rng.pick(std::array{Vec3(1, 1, 0), Vec3(1, -1, 1), Vec3(0, 1, 1)})); break;
    default: s.sphere(node, rng.integer(1, 4) * f.h_max() / f.size); break;
    }
  }
}

/// Per phase, one value per grid node.
using Values = std::vector<std::vector<double>>;

Scene from_values(const Frame& f, const Values& values, int top_k) {
  std::vector<std::span<const double>> spans(values.begin(), values.end());
  PhaseValuesOptions o;
  o.top_k = top_k;
  return scene_from_phase_values(f.grid(), spans, o);
}

/// Each phase a blend of minus the distance to its own centre and noise; the
/// blend runs from smooth cells to pure noise.
Scene grid_values(Rng& rng, const Frame& f, int top_k) {
  const GridSpec grid = f.grid();
  const double smooth = rng.pick(std::array{0.0, 0.5, 0.9, 1.0});
  Values values(size_t(rng.integer(2, 6)), std::vector<double>(size_t(grid.node_count())));
  for (auto& phase : values) {
    const Vec3 centre = f.world(unit_point(rng));
    for (int k = 0; k <= f.cells[2]; ++k)
      for (int j = 0; j <= f.cells[1]; ++j)
        for (int i = 0; i <= f.cells[0]; ++i)
          phase[size_t(grid.node_index(i, j, k))] =
              -smooth * (grid.node_position(i, j, k) - centre).norm() / f.size + (1 - smooth) * rng.uniform();
  }
  return from_values(f, values, top_k);
}

/// Values from {0, 1} or {0, 1, 2}: ties of two and more phases at most nodes;
/// some phases copies of another (tied everywhere), some absent (-1 everywhere).
Scene tied_values(Rng& rng, const Frame& f, int top_k) {
  const size_t nodes = size_t(f.grid().node_count());
  const int levels = rng.integer(2, 3);
  Values values(size_t(rng.integer(2, 6)), std::vector<double>(nodes));
  for (size_t p = 0; p < values.size(); ++p) {
    if (p > 0 && rng.chance(0.15))
      values[p] = values[size_t(rng.integer(0, int(p) - 1))];
    else if (rng.chance(0.2))
      std::fill(values[p].begin(), values[p].end(), -1.0);
    else
      for (double& v : values[p]) v = rng.integer(0, levels - 1);
  }
  return from_values(f, values, top_k);
}

/// A label per node from a few label values: noise, or grains (the label of
/// the nearest of a few seeds), as label volumes or as signed distances.
Scene labels(Rng& rng, const Frame& f, int top_k, bool voxel_faithful) {
  const GridSpec grid = f.grid();
  std::vector<int32_t> names;
  for (int l = 0, n = rng.integer(2, 5); l < n; ++l) names.push_back(int32_t(l * 3 + rng.integer(0, 2)));
  std::vector<Vec3> seeds;
  std::vector<int32_t> seed_labels;
  if (rng.chance(0.6))
    for (int s = 0, n = rng.integer(3, 9); s < n; ++s) {
      seeds.push_back(f.world(unit_point(rng)));
      seed_labels.push_back(names[size_t(rng.integer(0, int(names.size()) - 1))]);
    }
  std::vector<int32_t> labels(size_t(grid.node_count()));
  for (int k = 0; k <= f.cells[2]; ++k)
    for (int j = 0; j <= f.cells[1]; ++j)
      for (int i = 0; i <= f.cells[0]; ++i) {
        int32_t& l = labels[size_t(grid.node_index(i, j, k))];
        if (seeds.empty()) {
          l = names[size_t(rng.integer(0, int(names.size()) - 1))];
          continue;
        }
        const Vec3 x = grid.node_position(i, j, k);
        size_t best = 0;
        for (size_t s = 1; s < seeds.size(); ++s)
          if ((x - seeds[s]).norm() < (x - seeds[best]).norm()) best = s;
        l = seed_labels[best];
      }
  // Every label value must occur (an option naming an absent label is an error).
  for (size_t l = 0; l < names.size(); ++l) labels[l] = names[l];
  InputOptions o;
  o.background = names[0];
  o.label_function = rng.chance(0.5) ? LabelFunction::smoothed_indicator : LabelFunction::signed_distance;
  // Both drawn, so the random stream (and every later case) stays as it was; only
  // the label function's own option is given (the other is refused, not ignored).
  const double smoothing = rng.pick(std::array{0.5, 1.0, 2.0});
  const double band = rng.pick(std::array{1.0, 3.0});
  if (o.label_function == LabelFunction::signed_distance) o.band = band;
  else o.smoothing = smoothing;
  o.top_k = top_k;
  o.voxel_faithful = voxel_faithful;
  return scene_from_labels(grid, labels, o);
}

} // namespace

const char* scene_kind_name(SceneKind kind) {
  switch (kind) {
  case SceneKind::spheres: return "spheres";
  case SceneKind::seeds: return "seeds";
  case SceneKind::grid_values: return "grid_values";
  case SceneKind::tied_values: return "tied_values";
  case SceneKind::labels: return "labels";
  case SceneKind::thin_slabs: return "thin_slabs";
  case SceneKind::vanishing: return "vanishing";
  case SceneKind::lattice_ties: return "lattice_ties";
  }
  return "?";
}

std::string RandomCase::description() const {
  const GridSpec& g = scene.grid;
  std::ostringstream s;
  s << "seed " << seed << " case " << index << ": " << scene_kind_name(kind) << ", " << scene.field->num_phases()
    << " phases, domain " << point(g.domain.min) << " to " << point(g.domain.max) << ", grid " << g.cells[0] << "x"
    << g.cells[1] << "x" << g.cells[2] << ", " << (options.lattice == Lattice::bcc ? "bcc" : "cube6") << ", snap "
    << options.snap << ", top_k " << options.top_k << (options.close ? ", close" : "")
    << (voxel_faithful ? ", voxel-faithful" : "");
  return s.str();
}

RandomCase random_case(uint64_t seed, uint64_t index, bool voxel_faithful) {
  RandomCase c;
  c.seed = seed;
  c.index = index;
  c.kind = SceneKind(index % kSceneKinds);
  Rng rng(seed, index);
  const Frame f = random_frame(rng);
  c.options = random_options(rng);
  SceneText text(f);
  switch (c.kind) {
  case SceneKind::spheres: spheres(rng, text); break;
  case SceneKind::seeds: seeds(rng, f, text); break;
  case SceneKind::thin_slabs: thin_slabs(rng, f, text); break;
  case SceneKind::vanishing: vanishing(rng, f, text); break;
  case SceneKind::lattice_ties: lattice_ties(rng, f, text); break;
  case SceneKind::grid_values: c.scene = grid_values(rng, f, c.options.top_k); break;
  case SceneKind::tied_values: c.scene = tied_values(rng, f, c.options.top_k); break;
  case SceneKind::labels:
    c.scene = labels(rng, f, c.options.top_k, voxel_faithful);
    c.voxel_faithful = voxel_faithful;
    break;
  }
  if (text.count() > 0) {
    c.scene_json = text.json();
    c.scene = parse_scene(c.scene_json, "seed " + std::to_string(seed) + " case " + std::to_string(index));
    c.closed_form = true;
  }
  return c;
}

} // namespace vm::test
