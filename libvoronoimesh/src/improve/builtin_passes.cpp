/// @file improve/builtin_passes.cpp
/// Thin adapters from the pass interface to the algorithms (improve/smooth.hpp,
/// improve/project.hpp, improve/clamp.hpp, improve/flip.hpp, check/stats.hpp).
/// Defaults are the paper's. smooth, project, clamp and flip also run on a part
/// of a distributed mesh (PassContext::parts, improve/part_agreement.hpp).

#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/improve/clamp.hpp"
#include "voronoimesh/improve/flip.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/improve/polish.hpp"
#include "voronoimesh/improve/project.hpp"
#include "voronoimesh/improve/registry.hpp"
#include "voronoimesh/improve/remesh.hpp"
#include "voronoimesh/improve/smooth.hpp"

#include "core/memory.hpp"
#include "core/text.hpp"
#include "improve/part_agreement.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vm {
namespace {

/// The flip pass collapses every junction sliver up to this iteration, and
/// after it only the worst: those within kWorstMargin of the worst triangle
/// when the iteration began. Slivers come from create and the remesh calls of
/// the first iterations; later collapses of the rest (still about 60 an
/// iteration on 1,000 grains at grid 128, the triangles falling by 180 an
/// iteration without end) erode the same crowded junctions: a third of a
/// steady iteration there, and the worst triangle stayed 0.007. But a late
/// collapse of the worst one can raise it (voronoi30 at grid 48, the paper's
/// passes: 0.134 -> 0.193 in iteration 12).
constexpr double kLastCollapseIteration = 5;
constexpr double kWorstMargin = 0.01;
/// After kLastCollapseIteration, the slivers within kWorstMargin of the worst
/// collapse every this many iterations (counted from it) and in the run's
/// last, not in each: a batch rebuilds the mesh whatever its size (0.25-0.3 s on 1,000
/// grains at grid 128, and the guard's fans and filing after it), and the
/// slivers that smoothing makes near the worst wait for the next batch. In the
/// iterations between, only slivers worse than the worst when the iteration
/// began collapse: what an ear flip made (100 grains at grid 48: 0.111 -> 0.073
/// in iteration 18, which waiting for the batch left at 0.079). Collapsing only
/// when the worst sliver itself could go was tried: as fast, but 571 triangles
/// below q 0.1 stayed on 1,000 grains against 445 (this way 452).
constexpr double kLateCollapsePeriod = 5;

/// A pass whose body is a function of the context and its parameters.
class FunctionPass : public Pass {
public:
  using Body = std::function<void(PassContext&, const ParamValues&)>;
  FunctionPass(Body body, ParamValues params) : body_(std::move(body)), params_(std::move(params)) {}
  void run(PassContext& context) override { body_(context, params_); }

private:
  Body body_;
  ParamValues params_;
};

/// The remesh pass: its lengths are multiples of the mesh's RMS edge length when
/// it first runs (for a created mesh, about the lattice's), kept for the run so
/// that the target does not shrink or grow with the mesh it makes; so is the
/// most triangles its splits may make. With `length` they are multiples of that
/// length in world units instead, and the target is that length: the same
/// whatever mesh the pass is given (a mesh read back from a file is not
/// coarsened again).
class RemeshPass : public Pass {
public:
  explicit RemeshPass(const ParamValues& p)
      : params_{p.at("length") > 0 ? 1.0 : p.at("size"), p.at("tolerance"), p.at("min_size"), p.at("merge_corners"),
                p.at("merge_digons"), false, p.at("min_quality")},
        length_(p.at("length")), last_(int(p.at("last"))), split_first_(int(p.at("split_first"))),
        merge_overshoots_(p.at("merge_overshoots") > 0) {
    params_.merge_islands = p.at("merge_islands");
  }
  void run(PassContext& c) override {
    if (c.iteration > last_) return;
    // Curvature comes from the phase functions: without them the target would
    // silently be uniform.
    if (params_.tolerance > 0 && !c.field)
      throw InvalidInput(located("pipeline", "remesh.tolerance needs the phase functions: give the input the mesh was "
                                             "made from (--field)"));
    if (reference_ == 0) {
      const double rms = rms_edge_length(c.mesh);
      reference_ = length_ > 0 ? length_ : rms;
      // Uniform refinement to a target `ratio` times the edges multiplies the
      // triangles by 1/ratio^2; four times that (at least 4x) is the most a run may make.
      const double ratio = std::min(1.0, params_.size * reference_ / rms);
      refuse_beyond_memory(c.mesh.num_triangles(), ratio);
      max_triangles_ = c.mesh.num_triangles() * size_t(std::ceil(4 / (ratio * ratio)));
    }
    RemeshParams params = params_;
    params.max_triangles = max_triangles_;
    // From the second iteration: the created mesh's curves overshoot by
    // snapping, which its first projection mends (improve/curve_overshoots.hpp).
    params.merge_overshoots = merge_overshoots_ && c.iteration > 1;
    params.guard_crossings = c.guard_crossings;
    params.split_first = c.iteration <= split_first_;
    const RemeshStats done = remesh_edges(c.mesh, c.field, reference_, params);
    if (!done.old_triangles.empty()) c.guard.renumbered(c.mesh, done.old_triangles, done.old_nodes);
  }

private:
  /// Peak bytes of an improvement run per triangle (the demo remeshed to
  /// 336k triangles: 201 MB, 600 bytes each), with some room.
  static constexpr double kBytesPerTriangle = 700;

  /// A target far below the edges (a typo in --size) would split until memory
  /// ran out: --size 1e-9 on the demo took the machine's 24 GB and was killed.
  /// Refused with the estimate, before any split.
  void refuse_beyond_memory(size_t triangles, double ratio) const {
    const double expected = double(triangles) / (ratio * ratio);
    char what[200];
    std::snprintf(what, sizeof what,
                  "edges of %.2g times the mesh's (%s) make about %.2g triangles from its %zu, which", ratio,
                  length_ > 0 ? "--size or remesh:length" : "remesh:size", expected, triangles);
    if (const std::string problem = detail::beyond_memory(expected * kBytesPerTriangle, what); !problem.empty())
      throw InvalidInput(located("remesh", problem));
  }

  RemeshParams params_;
  double length_;
  int last_;
  int split_first_;
  bool merge_overshoots_;
  double reference_ = 0;
  size_t max_triangles_ = 0;
};

PassInfo make_info(std::string name, std::string summary, std::vector<ParamSpec> params, bool moves, bool field,
                   bool distributed, FunctionPass::Body body) {
  PassInfo info{std::move(name), std::move(summary), std::move(params), moves, field, distributed, {}, {}};
  info.make = [body](const ParamValues& p) { return std::make_unique<FunctionPass>(body, p); };
  return info;
}

/// `info` with PassInfo::scheduled_until.
PassInfo scheduled(PassInfo info, std::function<int(const ParamValues&)> until) {
  info.scheduled_until = std::move(until);
  return info;
}

} // namespace

void register_builtin_passes(PassRegistry& registry) {
  registry.add(make_info(
      "smooth", "DistMesh repulsion on surfaces, half-Laplacian on and next to junctions (Alg. 4, sect. 4.2.1)",
      {{"rest_factor", SmoothParams{}.rest_factor, 0.5, 3.0, false,
        "rest length l0 = rest_factor x RMS edge length (eq. 3)"}},
      true, true, true, [](PassContext& c, const ParamValues& p) {
        // The rest length comes from the whole mesh, in a distributed run too.
        const double rms = c.parts ? c.parts->rms_edge_length(c.mesh) : rms_edge_length(c.mesh);
        add_smoothing_forces_with_rest_length(c.mesh, *c.field, p.at("rest_factor") * rms, c.displacement());
      }));
  registry.add(scheduled(make_info(
      "polish",
      "move nodes of the worst triangles (surface nodes in their plane, curve nodes along their curve) where the "
      "smallest quality around them rises most, back onto their interface by Newton steps (not in the paper)",
      {{"below", PolishParams{}.below, 0.0, 1.0, false, "polish the nodes of triangles below this quality"},
       {"first", kLastCollapseIteration + 1, 1, 1000000, true,
        "the first iteration it runs in: by default once the flip pass collapses only the slivers near the worst "
        "(before that, polished nodes change what the remesh pass and the collapses make, which lowered the worst "
        "triangle of 5 of 38 scenes)"}},
      true, true, false, [](PassContext& c, const ParamValues& p) {
        if (c.iteration >= p.at("first")) add_polish_moves(c.mesh, *c.field, PolishParams{p.at("below")}, c.displacement());
      }), [](const ParamValues& p) { return int(p.at("first")) - 1; }));
  registry.add(make_info(
      "floor",
      "if the iteration's worst triangle is now worse than when it began, take back the moves that brought nodes "
      "onto their interface at that cost (not in the paper)",
      {}, false, false, false, [](PassContext& c, const ParamValues&) {
        if (quality_summary(c.mesh).first < c.quality_floor) c.take_back_floor_exceptions();
      }));
  registry.add(make_info(
      "project", "Newton steps onto surfaces, triple curves and quadruple points with the original phases (eq. 4)",
      {{"min_gradient_gap", ProjectParams{}.min_gradient_gap, 0.0, 1.0, false,
        "skip phase pairs whose gradients differ by less (sect. 4.2.2)"},
       {"least_squares_from", double(ProjectParams{}.least_squares_from), 0, 8, true,
        "nodes of this many phases or more (0: none; 4: quadruple points) take a least-squares Newton step onto "
        "all their pairs at once instead of eq. 4's mean: junctions exact where eq. 4 converges slowly (not in the "
        "paper; the scenes' default pipeline takes 4, which raised their worst triangles; 3 lowers them)"},
       {"max_step", ProjectParams{}.max_step, 0, 100, false,
        "cut each step to this many times the node's mean edge length (0: uncut, the paper's): where gradients "
        "nearly agree, a Newton step can ask for tens of edges (not in the paper)"}},
      true, true, true, [](PassContext& c, const ParamValues& p) {
        add_projection(c.mesh, *c.field,
                       ProjectParams{p.at("min_gradient_gap"), int(p.at("least_squares_from")), p.at("max_step")},
                       c.displacement());
      }));
  registry.add(make_info(
      "clamp", "scale each pending move so that no triangle can invert (Alg. 3, eq. 5)",
      {{"factor", ClampParams{}.factor, 0.0, 1.0, false, "fraction of the largest safe step (eq. 5: 1/2)"}}, true,
      false, true, [](PassContext& c, const ParamValues& p) {
        if (c.pending) clamp_displacements(c.mesh, ClampParams{p.at("factor")}, c.delta);
      }));
  registry.add(scheduled(make_info(
      "flip", "flip edges inside a surface when it raises the pair's smaller quality (Alg. 5, sect. 4.3)",
      {{"skip_quality", FlipParams{}.skip_quality, 0.0, 1.0, false, "leave pairs of at least this quality (Alg. 5, line 7)"},
       {"max_rounds", double(FlipParams{}.max_rounds), 1, 1000, true, "rounds of node-disjoint flips per iteration"},
       {"ear_below", FlipParams{}.ear_below, 0.0, 1.0, false,
        "flip ears (all corners on one curve) below this quality even into a worse pair (not in the paper)"},
       {"collapse_below", FlipParams{}.collapse_below, 0.0, 1.0, false,
        "then collapse junction triangles below this quality that flips cannot remove (0: off; not in the paper)"},
       {"collapse_last", kLastCollapseIteration, 0, 1000000, true,
        detail::cat("the last iteration it collapses every sliver in; later only those within ", kWorstMargin,
                    " of the worst triangle (on 1,000 grains the others, 60 an iteration, took a third of it and "
                    "never raised the worst)")},
       {"collapse_every", kLateCollapsePeriod, 1, 1000000, true,
        "after collapse_last, the slivers near the worst collapse every this many iterations and in the run's "
        "last (each batch rebuilds the mesh; 1: every iteration), between them only those worse than the worst "
        "when the iteration began"}},
      false, false, true, [](PassContext& c, const ParamValues& p) {
        double collapse_below = p.at("collapse_below");
        if (c.iteration > p.at("collapse_last")) {
          // Counted on from collapse_last, and in the run's last iteration, so
          // that a run ends with a batch and one stopped when converged
          // (RunOptions::stop_when_converged) makes the mesh of as many
          // iterations asked for; where the last is not known, every iteration.
          const int after_last = c.iteration - int(p.at("collapse_last"));
          const bool batch = c.iterations <= 0 || c.iteration == c.iterations ||
                             after_last % int(p.at("collapse_every")) == 0;
          collapse_below = std::min(collapse_below, c.quality_floor + (batch ? kWorstMargin : 0));
        }
        // Flips and collapses are checked with the moves: not while those wait (defer_crossings()).
        FlipParams params{p.at("skip_quality"),
                          int(p.at("max_rounds")),
                          collapse_below,
                          c.guard_crossings && !c.guard.defers_crossings(),
                          c.field,
                          &c.guard,
                          p.at("ear_below")};
        const std::vector<int32_t> let_through =
            c.floor_pass ? c.guard.floor_exception_nodes() : std::vector<int32_t>{};
        params.keep_triangles_at = let_through;
        c.flips += (c.parts ? detail::flip_edges(c.mesh, params, *c.parts) : flip_edges(c.mesh, params)).flips;
      }), [](const ParamValues& p) { return p.at("collapse_below") > 0 ? int(p.at("collapse_last")) : 0; }));
  const RemeshParams remesh;
  registry.add(PassInfo{
      "remesh",
      "split long and collapse short edges toward a target length, junctions kept (not in the paper)",
      {{"size", remesh.size, 0.25, 8.0, false,
        "target edge length, x the RMS edge length when the run began (with tolerance: the largest)"},
       {"length", 0, 0, 1e12, false,
        "target edge length in world units instead (0: size decides); tolerance and min_size are then x it"},
       {"tolerance", remesh.tolerance, 0.0, 1.0, false,
        "largest distance from a curved surface, same unit: shorter edges where surfaces curve (0: uniform)"},
       {"min_size", remesh.min_size, 0.1, 8.0, false, "shortest target edge length with tolerance, same unit"},
       {"merge_corners", remesh.merge_corners, 0.0, 0.5, false,
        "neighbouring quadruple points closer than this x the target merge into one point (0: never)"},
       {"merge_digons", remesh.merge_digons, 0.0, 16.0, false,
        "a face bounded by two curves between quadruple points of the same phases, each at most this x the target "
        "long, merges into one point where the phase functions lead both corners to one (0: never)"},
       {"merge_overshoots", 1, 0, 1, true,
        "from the second iteration, a curve node next to a quadruple point where the point's fourth phase is larger "
        "(the curve runs past it) merges into the point, which goes where its phases meet (0: never)"},
       {"merge_islands", remesh.merge_islands, 0.0, 16.0, false,
        "a closed piece of a phase's boundary at most this x the target across, where the phase functions make "
        "another phase lead inside it (a pocket the lattice made; the phase has other pieces), merges into one "
        "node (0: never)"},
       {"min_quality", remesh.min_quality, 0.0, 1.0, false,
        "collapses leave no triangle below this or the worst they replace"},
       {"last", 3, 0, 1000000, true, "the last iteration it runs in (each run rebuilds the mesh)"},
       {"split_first", 1, 0, 1000000, true,
        "up to this iteration it splits long edges before collapsing short ones, not after (on the mesh as "
        "created, collapsing first leaves short edges beside long ones and splits the long: a surplus of "
        "triangles, half as many again on 1,000 grains, that the next call collapses; 0: collapse first)"}},
      false, false, false, [](const ParamValues& p) { return std::make_unique<RemeshPass>(p); },
      [](const ParamValues& p) { return int(p.at("last")); }});
  registry.add(make_info("stats", "measure the current mesh: counts, quality, angles, edge lengths (check/stats.hpp)", {},
                         false, false, false,
                         [](PassContext& c, const ParamValues&) { c.stats = compute_stats(c.mesh.to_node_mesh()); }));
}

} // namespace vm
