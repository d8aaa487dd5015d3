/// @file run/job_checks.cpp
/// check_job() and its parts: everything a run can be refused for before it
/// reads its input.

#include "run/run_job.hpp"

#include "core/staged_outputs.hpp"
#include "core/text.hpp"
#include "fields/volume_scenes.hpp"
#include "voronoimesh/check/history.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/io/write_mesh.hpp"

#include <unistd.h>

#include <filesystem>

namespace vm {
namespace detail {

void check_options(const MeshOptions& o) {
  if (o.grid)
    for (int n : *o.grid)
      if (n < 1 || n > 4096) throw InvalidOption("grid", cat("must be between 1 and 4096 cells per axis, got ", n));
  if (!(o.snap >= 0 && o.snap <= 0.5))
    throw InvalidOption("snap", cat("must be between 0 and 0.5 (a fraction of the grid spacing h), got ", o.snap));
  if (o.top_k < 1 || o.top_k > 16) throw InvalidOption("top_k", cat("must be between 1 and 16, got ", o.top_k));
  if (o.iterations < 0) throw InvalidOption("iterations", cat("must be 0 or more, got ", o.iterations));
  if (o.check_crossings_every < 1)
    throw InvalidOption("check_crossings_every", cat("must be 1 or more iterations, got ", o.check_crossings_every));
  if (o.threads < 0) throw InvalidOption("threads", cat("must be 0 (all cores) or more, got ", o.threads));
  if (!(o.size >= 0 && o.size < 1e12))
    throw InvalidOption("size", cat("must be a length above 0 in world units (0: none), got ", o.size));
  if (o.size > 0 && !o.pipeline.empty())
    throw InvalidOption("size", "sets the default pipeline's remesh pass; with a pipeline of your own, give "
                                "remesh:length=L in it");
  if (!(o.tolerance >= 0 && o.tolerance < 1e12))
    throw InvalidOption("tolerance", cat("must be a distance above 0 in world units (0: none), got ", o.tolerance));
  if (o.tolerance > 0 && !(o.size > 0))
    throw InvalidOption("tolerance", "needs --size, the longest edge (where surfaces are flat)");
  if (o.tolerance > o.size)
    throw InvalidOption("tolerance", cat("must not exceed --size (", o.size, "), got ", o.tolerance));
  if (!(o.min_size >= 0 && o.min_size < 1e12))
    throw InvalidOption("min_size", cat("must be a length above 0 in world units (0: half of --size), got ", o.min_size));
  if (o.min_size > 0 && !(o.tolerance > 0))
    throw InvalidOption("min_size", "needs --tolerance (without it every edge aims at --size)");
  if (o.min_size > 0 && !(o.min_size >= 0.1 * o.size && o.min_size <= o.size))
    throw InvalidOption("min_size", cat("must lie between a tenth of --size and --size (", 0.1 * o.size, " to ",
                                        o.size, "), got ", o.min_size));
}

InputOptions input_options_for(InputOptions input, const MeshOptions& options) {
  input.top_k = options.top_k;
  input.snap = options.snap;
  return input;
}

std::optional<tbb::global_control> thread_limit(const MeshOptions& o) {
  if (o.threads < 0) throw InvalidOption("threads", cat("must be 0 (all cores) or more, got ", o.threads));
  std::optional<tbb::global_control> limit;
  if (o.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(o.threads));
  return limit;
}

Pipeline parse_pipeline(const MeshOptions& o) {
  const std::string text = pipeline_for(o, nullptr);
  return Pipeline::parse(text, o.passes ? *o.passes : builtin_registry());
}

void check_writable(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw IoError(located(path, "cannot write: directory " + dir.string() + " does not exist"));
  if (access(dir.c_str(), W_OK) != 0)
    throw IoError(located(path, "cannot write: directory " + dir.string() + " is not writable"));
  if (fs::is_directory(path, ec)) throw IoError(located(path, "cannot write: it is a directory"));
}

void check_outputs(const RunOutputs& o) {
  if (!o.mesh.empty()) {
    io::check_output_format(o.mesh);
    check_writable(o.mesh);
  }
  if (!o.history.empty()) {
    QualityHistory::check_format(o.history);
    check_writable(o.history);
  }
  if (!o.per_phase.empty()) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(o.per_phase, ec) && !fs::is_directory(o.per_phase, ec))
      throw IoError(located(o.per_phase, "not a directory, so the per-phase files cannot go in it"));
    // An existing directory must be writable; a new one needs a writable parent.
    check_writable(fs::exists(o.per_phase, ec) ? (fs::path(o.per_phase) / "phase.stl").string() : o.per_phase);
  }
}

void check_outputs_apart(const RunOutputs& outputs, const std::vector<std::string>& inputs) {
  std::vector<std::pair<std::string, FileIdentity>> seen;
  for (const std::string& path : {outputs.mesh, outputs.history}) {
    if (path.empty()) continue;
    const FileIdentity id = file_identity(path);
    for (const std::string& input : inputs)
      if (!input.empty() && file_identity(input) == id)
        throw InvalidInput(located(path, cat("is also an input of this run (", input,
                                             "); an output may not replace what the run reads")));
    for (const auto& [other, other_id] : seen)
      if (other_id == id) throw InvalidInput(located(path, cat("is written twice by this run (also as ", other, ")")));
    seen.emplace_back(path, id);
  }
}

} // namespace detail

void check_job(const MeshJob& job) {
  detail::check_outputs(job.outputs);
  detail::check_outputs_apart(job.outputs, {job.input, job.mesh});
  detail::check_options(job.options);
  detail::check_input_options(detail::input_options_for(job.input_options, job.options));
  const Pipeline pipeline = detail::parse_pipeline(job.options);
  // A mesh improved without the input it was made from has no phase functions.
  if (!job.mesh.empty() && job.input.empty() && job.options.iterations > 0 && pipeline.needs_field())
    throw InvalidOption("pipeline", "'" + pipeline_for(job.options, nullptr) +
                                        "' needs the phase functions: give the input the mesh was made from (--field)");
}

} // namespace vm
