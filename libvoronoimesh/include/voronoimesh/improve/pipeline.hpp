#pragma once
/// @file improve/pipeline.hpp
/// An ordered list of configured passes repeated for a number of iterations
/// (paper Algorithm 1).

#include "voronoimesh/improve/registry.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vm {

/// The paper's pipeline: smoothing, projection, clamping, then flipping.
inline constexpr const char* kDefaultPipeline = "smooth,project,clamp,flip";

/// The passes after the remesh pass in the remeshing defaults below: the paper's,
/// with junction slivers below q 0.15 collapsed (flip:collapse_below). After
/// remeshing, curve nodes bunch where a triple curve turns tightly and leave
/// triangles with three corners on the curve: 0.15 lifts the worst triangle of
/// the liver at 2 mm edges from 0.084 to 0.226, of a 60-grain polycrystal from
/// 0.052 to 0.158. The remeshing defaults collapse below 0.7 for label volumes
/// (kLabelVolumePipeline) and below 0.5 for scenes (kScenePipeline).
inline constexpr const char* kPassesAfterRemesh = "smooth,project,clamp,flip:collapse_below=0.15";

/// The default for label volumes (run/meshing.hpp, pipeline_for()): their grid
/// is the voxel grid, finer than their surfaces need, so the remesh pass first
/// coarsens the mesh to edges 1.4 times the lattice's (about half the triangles),
/// then the paper's passes, with junction slivers below q 0.7 collapsed. Against
/// 0.5 (the default until 2026-12-03, and the scenes'), measured 2026-12-03 on 12
/// volume and cell-size pairs (docs/benchmarks.md, stopping when converged): the
/// worst triangle rose on 7 (the liver 0.592 -> 0.695, above CGAL's bound of
/// 0.600; at 3 voxels per cell 0.569 -> 0.665; the CT-like volume at 2.4 voxels
/// per cell 0.531 -> 0.589; 128^3 ellipsoids 0.611 -> 0.701; 20 grains 0.528 ->
/// 0.600, at 1.4 voxels per cell 0.508 -> 0.592), fell on 1 (the liver at 2 voxels
/// per cell 0.547 -> 0.542) and was the same on the 60 and 150 grains, whose worst
/// triangles no collapse reaches; the liver's voxel centres stay 99.867% in
/// their label. Where a curve turns tightly, a triangle with three corners on it
/// is below 0.7 but above 0.5. 0.8 lowered 20 grains to 0.496. Against 0.3 (the
/// default from 2026-11-27, when it beat
/// 0.15 on the 60 grains), measured 2026-12-02 on 33 volume and cell-size pairs
/// (the liver at its default cells and 1, 1.4, 2 and 3 voxels per cell, the
/// CT-like volume at its default, 1.5, 2, 2.4 and 3, seven 60-grain and three
/// 150-grain polycrystals, 20 and 30 grains, two ellipsoid volumes, random and
/// tiny volumes): the worst triangle rose on 17 (the liver 0.424 -> 0.511, at 3
/// voxels per cell 0.339 -> 0.551; the 60 grains 0.293 -> 0.335, at 1.4 voxels
/// per cell 0.220 -> 0.315; 20 grains at 1.4 0.331 -> 0.527), fell on 2 (128^3
/// ellipsoids 0.573 -> 0.561, 150 grains 0.169 -> 0.168) and was the same on the
/// rest, for about 0.06 s more flipping on the liver (the collapses of
/// iterations 2 to 6). 0.3 came before curve ends past their quadruple point
/// merged into it, which is when the scenes went to 0.5. The polish pass ends
/// each iteration from the sixth on, as in kScenePipeline (measured there).
inline constexpr const char* kLabelVolumePipeline = "remesh:size=1.4,smooth,project,clamp,flip:collapse_below=0.7,polish,floor";

/// The default for every other input created from phase functions (scenes,
/// distance grids, point clouds; run/meshing.hpp, pipeline_for()): the remesh
/// pass first evens out the created mesh at about its own edge length, which
/// the paper's passes cannot (they move nodes, never add or remove them, so
/// curve nodes stay bunched where create left them), then the paper's passes.
/// Measured (20 iterations, bench/junction_scenes.sh and the shipped scenes):
/// min q of seven Voronoi cells 0.354 -> 0.652, of six random four-ball scenes
/// 0.323 -> 0.531 on average, of twelve random seed scenes 0.155 -> 0.180; mean
/// q 0.92 -> 0.95 on all; about as many triangles, 30% more time. Junction
/// slivers below q 0.3 collapse (the flip pass's default is 0.15): with
/// collapse targets moving onto the box (improve/collapse.hpp), the worst
/// triangle of twelve random seed scenes rose on 8 and fell on none (mean 0.193
/// -> 0.235; 0.206 without those moves; 0.250 since slivers that cannot
/// collapse lose a curve node beside them), of voronoi30 at grid 64 0.218 -> 0.416,
/// of seven cells 0.652 -> 0.643. Below q 0.5 since 2026-11-27 (after curve
/// nodes past their quadruple point merged into it): seed scenes' mean 0.232 ->
/// 0.248 at grid 32, 0.282 -> 0.305 at 48, 0.238 -> 0.266 at 64; four-ball
/// scenes' 0.477 -> 0.523 at 32, the same at 48 and 64; voronoi30 at 64 0.400 ->
/// 0.431, seven cells the same, four spheres 0.651 -> 0.646; no slower (100
/// grains at grid 128 15.9 against 17 s). Not the paper's default too: there the
/// quality floor then held a curve node of eight spheres 0.15 h off its curve
/// (tests/unit/test_improve.cpp, triple curves converge).
/// The polish pass (improve/polish.hpp) ends each iteration from the sixth on
/// (since 2026-12-02): over 38 scenes (12 + 16 random seed scenes at grid 48,
/// six of four random balls, the four shipped) the worst triangle rose on 15
/// and fell on none (mean 0.364 -> 0.380, 25 at q 0.3 or more either way; 30
/// cells at grid 64 0.370 -> 0.393), over 23 label volumes and cell sizes on
/// 16 and on none (mean 0.394 -> 0.446; the liver 0.511 -> 0.543), for about
/// 4 ms an iteration on the liver (146k triangles) and 0.05 s on 1M. From the
/// first iteration it raised more (the liver to 0.654, the mean over the
/// volumes to 0.471) but lowered 5 scenes and the 60 grains: polished nodes
/// change what the remesh pass and the collapses of iterations 1 to 5 make.
/// Quadruple and higher points take the least-squares Newton step onto all
/// their pairs at once (project:least_squares_from=4, since 2026-12-05; eq. 4's
/// mean of the pairs' steps stalls where their gradient differences nearly
/// share a plane): over 28 random seed scenes at grid 48 the worst triangle's
/// mean rose 0.306 -> 0.331 (17 at q 0.3 or more instead of 16; up on 13,
/// down on 10), over six of four random balls 0.593 -> 0.599, on the shipped
/// scenes it rose or stayed (30 cells at grid 64 0.487 -> 0.492), and points
/// came to their exact place (the seven cells' from 0.013 h to 1e-14 h off, the
/// 30 cells' farthest 0.46 -> 0.20 h). Where junctions crowd it costs the
/// triangles just above the worst: 1,000 grains at grid 64 (point cloud) 1% q
/// 0.584 -> 0.537, q < 0.1 231 -> 253, min q the same; three 150-cell seed
/// scenes at grid 36 1% q 0.665 -> 0.636 on average, q < 0.1 62 -> 40.
inline constexpr const char* kScenePipeline =
    "remesh:size=1,smooth,project:least_squares_from=4,clamp,flip:collapse_below=0.5,polish,floor";

/// What happened in one iteration, for progress lines and stopping rules.
struct IterationReport {
  int iteration = 0;          ///< 1-based
  double min_quality = 0;     ///< smallest triangle quality q after the iteration (quality_summary())
  double mean_quality = 0;    ///< mean triangle quality q after the iteration
  size_t flips = 0;           ///< edges flipped in the iteration
  size_t undone_moves = 0;    ///< node moves the crossing guard undid
  double seconds = 0;         ///< wall time of the iteration
  std::optional<MeshStats> stats; ///< when the pipeline has a stats pass
  /// Wall time of each step, in pipeline order; committing the moves is charged
  /// to the moving pass before it.
  std::vector<double> pass_seconds;
  /// The run's last iteration as known now: RunOptions::iterations, or, once
  /// quality converged (RunOptions::stop_when_converged), the next one; for
  /// progress that reaches its end when the run does.
  int last_iteration = 0;
  /// Crossings were left to a whole check at the end of a window of iterations
  /// (RunOptions::check_crossings_every), not looked for in this one.
  bool crossings_deferred = false;
  /// The check at the end of the window this iteration closed found a
  /// crossing: the window's iterations run again, checked, and are reported again.
  bool runs_again = false;
};

/// How Pipeline::run() iterates.
struct RunOptions {
  int iterations = 20; ///< iterations to run, at most
  /// Stop early once neither the minimum quality has risen by more than
  /// `tolerance` nor the mean by more than `mean_tolerance` for `patience`
  /// iterations in a row: one more iteration then runs, told that it is the
  /// run's last (PassContext::iterations), so that passes which end a run with
  /// work of their own (the flip pass's last collapse batch) do it.
  bool stop_when_converged = false;
  double tolerance = 1e-3;      ///< rise of the minimum quality that counts as an improvement (stop_when_converged)
  double mean_tolerance = 2e-3; ///< rise of the mean quality that counts as an improvement (stop_when_converged)
  int patience = 2; ///< iterations in a row without improvement before the last one (stop_when_converged)
  /// Undo any move that would make two triangles intersect (improve/guard.hpp). Off
  /// saves the exact intersection check of every iteration.
  bool guard_crossings = true;
  /// With the guard on: look for crossings once every this many iterations,
  /// in the whole mesh, instead of after every commit of moves and batch of
  /// flips (the guard's other checks stay in every iteration). Where such a
  /// check finds a crossing, the iterations since the last one run again from
  /// the mesh as it was, every move and flip checked, so no crossing is left
  /// in any mesh checked, and the output is checked. On meshes where the guard
  /// never finds a crossing the result is the same as with 1; elsewhere it may
  /// differ where a crossing came and went between two checks. 1: every
  /// iteration. The observer then hears of iterations run again twice
  /// (IterationReport::runs_again), and passes run them again from the mesh
  /// as it was: a plugin pass that keeps state between iterations should
  /// not count on seeing each iteration once.
  int check_crossings_every = 1;
  /// Called after every iteration (and with iteration 0 before the first).
  std::function<void(const IterationReport&, const InterfaceMesh&)> observer;
  /// Asked before every iteration: true ends the run there, leaving the mesh as
  /// the last complete iteration made it (the CLI's Ctrl-C).
  std::function<bool()> stop_requested;
};

/// Configured passes in order, parsed from a spec string and run for some iterations.
class Pipeline {
public:
  /// One configured pass: its type and its parameter values.
  struct Step {
    PassInfo info; ///< a copy: the pipeline does not depend on the registry afterwards
    ParamValues params; ///< every parameter of the pass, defaults filled in (PassRegistry::resolve())
  };

  /// Parses "name,name:key=value:key=value,..." against `registry`.
  /// @param spec     the passes in order, separated by commas, each with its parameters after colons
  /// @param registry the pass types the spec may name; the pipeline keeps copies of them
  /// @return the pipeline, every parameter resolved (PassRegistry::resolve())
  /// @throws InvalidInput naming the bad pass or parameter (an unknown pass or parameter, a value that is
  ///         not a number or out of range, an empty pass name, no passes)
  static Pipeline parse(const std::string& spec, const PassRegistry& registry);

  /// The configured passes, in order.
  const std::vector<Step>& steps() const { return steps_; }
  /// True when some pass evaluates the phase functions (run() then needs a field).
  bool needs_field() const;
  /// True when every pass runs on a part of a distributed mesh too
  /// (PassInfo::distributed), so a distributed run can run the pipeline.
  bool distributes() const;
  /// "smooth(rest_factor=1.2), project(...), ..." with every parameter.
  std::string describe() const;
  /// The first iteration whose quality a run that stops once converged
  /// judges: the one after every pass's schedule settled (PassInfo::scheduled_until), or 1.
  int settled_from() const;

  /// Runs the pipeline on `mesh` (paper Algorithm 1).
  /// @param mesh    the mesh to improve, changed in place
  /// @param field   the phase functions (unsnapped); may be null when no pass needs them (needs_field())
  /// @param options iterations, stopping rules, the crossing guard and the observer
  /// @return the number of iterations done
  /// @throws InvalidInput if a pass needs the phase functions and `field` is null
  ///         or lacks a phase of the mesh (a closed mesh's outside phase: phases_of_mesh())
  int run(InterfaceMesh& mesh, const PhaseField* field, const RunOptions& options) const;

  /// The configured passes, made once for a run of iterate() calls.
  /// @return one Pass per step, in order (PassInfo::make with the step's parameters)
  std::vector<std::unique_ptr<Pass>> make_passes() const;
  /// One iteration on context.mesh: `passes` (make_passes()) in order, pending
  /// moves committed at one point, before every pass that does not move nodes
  /// and at the end, so that nothing looks at half-moved positions. run() calls
  /// it for each iteration; a distributed run calls it on each rank's part, with
  /// context.parts set.
  /// @param context the mesh, field and displacement buffer the passes work on
  /// @param passes  the passes of make_passes(), one per step
  /// @return the wall time of each pass, in seconds, in pipeline order; committing the moves is charged
  ///         to the moving pass before it
  std::vector<double> iterate(PassContext& context, const std::vector<std::unique_ptr<Pass>>& passes) const;

private:
  std::vector<Step> steps_;
};

/// Minimum and mean triangle quality, summed in a fixed order.
/// @param mesh the mesh, its InterfaceMesh::triangles() current
/// @return {minimum, mean} of the triangle quality q (triangle_quality()); {0, 0} without triangles
std::pair<double, double> quality_summary(const InterfaceMesh& mesh);

} // namespace vm
