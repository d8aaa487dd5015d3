#pragma once
/// @file case_checks.hpp
/// The properties every generated case must have, from creation through a
/// few improvement iterations.

#include "random_scenes.hpp"

#include <string>
#include <vector>

namespace vm::test {

/// How much of a case to check.
struct CheckOptions {
  /// Improvement iterations (paper Algorithm 1 with the default pipeline).
  int iterations = 3;
  /// Also mesh the case (create and improve, as mesh_scene does) on 1 and on
  /// 2 threads and require identical results.
  bool compare_threads = false;
  /// A remesh pass spec ("remesh:size=2"), run first in every iteration and
  /// checked like the others (valid, nothing intersecting); empty: none.
  std::string remesh;
  /// Over 1: instead of checking pass by pass, mesh the case whole (as
  /// mesh_scene does) with crossings looked for every this many iterations
  /// (RunOptions::check_crossings_every), and require the mesh valid, free of
  /// crossings and inside the box (and the same on 1 and 2 threads, with
  /// compare_threads).
  int check_crossings_every = 1;
  /// Instead of checking the paper's passes stage by stage, mesh the case whole
  /// as `voronoimesh mesh` does (mesh_scene(): the case's default pipeline, with
  /// the remesh pass, the flip pass's collapses, polish and floor on their
  /// schedules, a label case stopping once converged) and check the mesh after
  /// every iteration whose crossings were looked for (with
  /// check_crossings_every over 1, those that end a clean window). The
  /// schedules reach polish from iteration 6: give 8 or so `iterations`.
  bool whole = false;
};

/// What check_case() found.
struct CaseResult {
  /// One line per broken property, naming the stage ("create", "iteration 2
  /// after moving"...); empty when the case passed.
  std::vector<std::string> failures;
  size_t triangles = 0; ///< of the created mesh
  /// Closed-form scenes: triangles against their pair's direction at the end.
  size_t against_field = 0;
  /// Surface edges that fold at the end (MeshStats::folds): good triangles laid
  /// onto each other, which the checks above do not see.
  size_t folds = 0;
  /// Meshed whole (CheckOptions::whole, check_crossings_every over 1): windows
  /// whose check at their end found a crossing, so that their iterations ran again.
  size_t windows_run_again = 0;
  bool ok() const { return failures.empty(); }
};

/// Meshes `c` on one thread and checks, after create and after each
/// iteration's halves (the moving passes smooth, project, clamp; then flip with
/// its collapses), stopping at the first stage that fails:
///  - validate() finds nothing: closed, 2-manifold phase boundaries, junction
///    edges carried by consistent cycles of pairs, oriented pairs, no repeated
///    or zero-area triangles, no duplicates;
///  - find_self_intersections() finds nothing;
///  - no triangle inverts in the moving passes: none turns its normal by 90
///    degrees or more (they keep the topology, so faces are followed by index);
/// and nothing throws. Improvement uses the crossing guard, as the CLI does.
/// For closed-form scenes it also counts, without failing, the triangles that
/// point against their phase pair's direction after the last iteration
/// (inverted_triangles(), mesh_checks.hpp): on coarse grids, sub-cell slabs and
/// junctions closer than a cell have them legitimately, so it is a statistic.
CaseResult check_case(const RandomCase& c, const CheckOptions& options = {});

} // namespace vm::test
