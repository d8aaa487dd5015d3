/// @file report.cpp
/// The tool's progress and summary lines (report.hpp).

#include "report.hpp"

#include "interrupt.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

namespace vmcli {

Report::Report(bool quiet, std::string output, bool tell_input)
    : quiet_(quiet), terminal_(!quiet && isatty(STDERR_FILENO)), tell_input_(tell_input), output_(std::move(output)) {}

void Report::status(const std::string& text) {
  if (!terminal_) return;
  std::fprintf(stderr, "\r\033[K%s", text.c_str());
  std::fflush(stderr);
}

void Report::say(const std::string& line) {
  if (quiet_) return;
  status("");
  std::fprintf(stderr, "%s\n", line.c_str());
}

void Report::stage(vm::Stage, const std::string& what) { status(what); }

void Report::input_read(const std::string&, const vm::Scene& scene, double seconds) {
  if (!tell_input_) return;
  // The input's own grid, which --grid overrides (the create line names the grid used).
  char line[160];
  std::snprintf(line, sizeof line, "input: %d phases, default grid %dx%dx%d; read and phase functions %.3f s",
                scene.field->num_phases(), scene.grid.cells[0], scene.grid.cells[1], scene.grid.cells[2], seconds);
  say(scene.world.empty() ? std::string(line) : std::string(line) + "; world " + scene.world);
}

void Report::created(const vm::CreateReport& r) {
  char line[384];
  std::snprintf(line, sizeof line,
                "create: grid %dx%dx%d (%s), %zu vertices, %zu triangles; sampling %.3f s, create %.3f s "
                "(%llu tets, %llu cut, values held at %llu nodes near them; check %.3f s); snapping undone at %llu "
                "nodes",
                r.grid.cells[0], r.grid.cells[1], r.grid.cells[2], r.lattice == vm::Lattice::cube6 ? "cube6" : "bcc",
                r.nodes, r.triangles, r.sampling_seconds, r.stats.seconds, (unsigned long long)r.stats.tets_visited,
                (unsigned long long)r.stats.tets_cut, (unsigned long long)r.stats.held_nodes, r.stats.check_seconds,
                (unsigned long long)r.stats.unsnapped_nodes);
  std::string text = line;
  if (r.stats.tiny_loop_nodes > 0)
    text += ", triple-curve loops far smaller than a cell closed (at " +
            std::to_string(r.stats.tiny_loop_nodes) + " nodes)";
  say(text);
}

void Report::iteration(const vm::IterationReport& r, const vm::InterfaceMesh&) {
  char line[192];
  std::snprintf(line, sizeof line, "iteration %d/%d: min q %.3f, mean q %.3f, %zu flips, %zu moves undone, %.1f ms",
                r.iteration, r.last_iteration, r.min_quality, r.mean_quality, r.flips, r.undone_moves, r.seconds * 1e3);
  status(line);
}

void Report::improved(const vm::ImproveReport& r) {
  char line[384];
  std::snprintf(line, sizeof line,
                "improve: %d iterations of %s in %.3f s; min q %.3f -> %.3f, mean q %.3f -> %.3f%s", r.iterations,
                r.pipeline.c_str(), r.seconds, r.initial_min_quality, r.min_quality, r.initial_mean_quality,
                r.mean_quality, r.converged ? kConvergedRemark : "");
  say(line);
}

namespace {

/// The files in `dir` named `prefix`*.stl that are not among `written` (an
/// earlier run's, of phase pairs or phases this run does not have), sorted.
std::vector<std::string> other_stl_files(const std::filesystem::path& dir, const std::string& prefix,
                                         const std::vector<std::string>& written) {
  namespace fs = std::filesystem;
  std::vector<std::string> names, others;
  for (const std::string& f : written) names.push_back(fs::path(f).filename().string());
  std::error_code ec;
  for (fs::directory_iterator it(dir.empty() ? fs::path(".") : dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() > prefix.size() + 4 && name.starts_with(prefix) && name.ends_with(".stl") &&
        std::find(names.begin(), names.end(), name) == names.end())
      others.push_back(name);
  }
  std::sort(others.begin(), others.end());
  return others;
}

/// A note on the files of `pattern` beside this run's that it did not write,
/// or nothing: loaded together with them, they would mix two meshes.
std::string stale_note(const std::vector<std::string>& others, const std::filesystem::path& dir,
                       const std::string& pattern) {
  if (others.empty()) return {};
  const std::string where = dir.empty() ? std::string("this folder") : dir.string();
  return "note: " + std::to_string(others.size()) + " other " + pattern + " file" + (others.size() > 1 ? "s" : "") +
         " in " + where + " (such as " + others.front() + ") are not from this run; remove them before loading " +
         pattern + " together";
}

} // namespace

void Report::written(const std::vector<std::string>& mesh_files, const std::vector<std::string>& phase_files) {
  namespace fs = std::filesystem;
  status("");
  if (!mesh_files.empty() && mesh_files != std::vector<std::string>{output_}) {
    const fs::path dir = fs::path(output_).parent_path();
    const std::string stem = fs::path(output_).stem().string();
    say("output: " + std::to_string(mesh_files.size()) + " STL files, one per phase pair (" + (dir / stem).string() +
        "_<pair>.stl)");
    if (const std::string note = stale_note(other_stl_files(dir, stem + "_", mesh_files), dir, stem + "_*.stl");
        !note.empty())
      say(note);
  }
  if (!phase_files.empty()) {
    const fs::path dir = fs::path(phase_files.front()).parent_path();
    say("per-phase: " + std::to_string(phase_files.size()) + " STL files in " + dir.string() + " (phase_<label>.stl)");
    if (const std::string note = stale_note(other_stl_files(dir, "phase_", phase_files), dir, "phase_*.stl");
        !note.empty())
      say(note);
  }
}

void Report::note(const std::string& line) { say(line); }

bool Report::stop_requested() { return interrupted(); }

} // namespace vmcli
