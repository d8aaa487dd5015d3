#pragma once
/// @file run/run_job.hpp
/// The parts of run_job() that the distributed run (mpi/) shares: the checks
/// made before any work (check_job(), job_checks.cpp) and the end of a job.

#include "voronoimesh/run/meshing.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <tbb/global_control.h>

namespace vm::detail {

/// Throws InvalidOption for a MeshOptions value out of range: grid, snap,
/// top_k, iterations, threads.
void check_options(const MeshOptions& options);

/// options.stop_when_converged, or where unset the default for `scene`: on for
/// a label volume improved with the default pipeline (neither options.pipeline
/// nor options.size given), off otherwise.
bool stops_when_converged(const MeshOptions& options, const Scene& scene);

/// `input` with what reading it shares with create: options.top_k, and
/// options.snap, on which a voxel-faithful volume's choice of lattice depends.
InputOptions input_options_for(InputOptions input, const MeshOptions& options);

/// Limits TBB to options.threads while alive (none when 0).
std::optional<tbb::global_control> thread_limit(const MeshOptions& options);

/// The pipeline of `options` (pipeline_for() without a scene), parsed against
/// options.passes (or the built-in passes). Throws InvalidInput naming the bad
/// pass or parameter.
Pipeline parse_pipeline(const MeshOptions& options);

/// Throws IoError "<path>: cannot write: ..." when `path` cannot be written: its
/// folder is missing or not writable, or it is a folder.
void check_writable(const std::string& path);

/// Checks the outputs' formats (InvalidInput) and that they can be written (IoError).
void check_outputs(const RunOutputs& outputs);

/// Throws InvalidInput when the mesh or history output is one of `inputs`, or
/// the two are one file, by file identity (a link and its target are one file).
/// The files a .stl mesh or per_phase write, known only once the mesh is made,
/// are refused as they are written (StagedOutputs).
void check_outputs_apart(const RunOutputs& outputs, const std::vector<std::string>& inputs);

/// The note a run ends with when its mesh has slivers (q below 0.1): how many,
/// the worst, and how many of them fill their surface's whole corner at a
/// junction point (WorstTriangle::corner_node), which only moving junctions
/// could open; empty without slivers.
std::string sliver_note(const NodeMesh& mesh);

/// The end of run_job() once the mesh is there: improve it (when there are
/// iterations or a history to record; `field` as improve_mesh() takes it),
/// write the history and the outputs (meshing.cpp).
void finish_job(NodeMesh& mesh, std::shared_ptr<const PhaseField> field, const MeshJob& job, RunObserver* observer);

} // namespace vm::detail
