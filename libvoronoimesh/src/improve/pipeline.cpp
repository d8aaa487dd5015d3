#include "voronoimesh/improve/pipeline.hpp"

#include "core/text.hpp"
#include "voronoimesh/core/errors.hpp"

#include "core/fixed_point_sum.hpp"
#include "core/parallel.hpp"
#include "improve/convergence.hpp"
#include "improve/crossing_windows.hpp"
#include "improve/field_checks.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

namespace vm {
namespace {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string part;
  std::istringstream in(s);
  while (std::getline(in, part, sep)) out.push_back(part);
  if (!s.empty() && s.back() == sep) out.emplace_back();
  return out;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

/// A parameter's value: a finite decimal number ("+" allowed; no hex, which
/// std::stod took, "0x10" for 16).
double parameter_value(const std::string& text, const std::string& where) {
  const char* begin = text.data() + (text.starts_with('+') ? 1 : 0);
  const char* end = text.data() + text.size();
  double v = 0;
  const auto [ptr, error] = std::from_chars(begin, end, v);
  if (error == std::errc::result_out_of_range && ptr == end)
    throw InvalidInput(located("pipeline", where + ": " + text + " is out of range"));
  if (error != std::errc() || ptr != end || begin == end || !std::isfinite(v))
    throw InvalidInput(located("pipeline", where + ": '" + text + "' is not a number"));
  return v;
}

} // namespace

Pipeline Pipeline::parse(const std::string& spec, const PassRegistry& registry) {
  Pipeline p;
  for (const std::string& raw : split(spec, ',')) {
    const std::string item = trim(raw);
    if (item.empty()) throw InvalidInput(located("pipeline", "empty pass name in '" + spec + "'"));
    auto parts = split(item, ':');
    const std::string name = trim(parts[0]);
    if (std::isdigit(static_cast<unsigned char>(name[0])) && !p.steps_.empty())
      throw InvalidInput(located("pipeline", "'" + name + "' is not a pass: a decimal comma? Passes are separated by "
                                             "commas, so numbers take a point (1.5, not 1,5)"));
    ParamValues given;
    for (size_t i = 1; i < parts.size(); ++i) {
      const auto eq = parts[i].find('=');
      if (eq == std::string::npos)
        throw InvalidInput(located("pipeline", "'" + parts[i] + "' in '" + item + "': expected key=value"));
      const std::string key = trim(parts[i].substr(0, eq));
      if (given.count(key))
        throw InvalidInput(located("pipeline", "'" + item + "' gives " + name + "." + key + " twice"));
      given[key] = parameter_value(trim(parts[i].substr(eq + 1)), name + "." + key);
    }
    p.steps_.push_back({registry.get(name), registry.resolve(name, given)});
  }
  if (p.steps_.empty()) throw InvalidInput(located("pipeline", "no passes given"));
  return p;
}

bool Pipeline::needs_field() const {
  for (const Step& s : steps_)
    if (s.info.needs_field) return true;
  return false;
}

std::string Pipeline::describe() const {
  std::string out;
  // Appends only: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
  for (const Step& s : steps_) {
    if (!out.empty()) out += ", ";
    out += s.info.name;
    out += "(";
    bool first = true;
    for (const auto& [k, v] : s.params) {
      if (!first) out += ", ";
      out += detail::cat(k, "=", v);
      first = false;
    }
    out += ")";
  }
  return out;
}

int Pipeline::settled_from() const {
  int settled = 1;
  for (const Step& s : steps_)
    if (s.info.scheduled_until) settled = std::max(settled, s.info.scheduled_until(s.params) + 1);
  return settled;
}

std::pair<double, double> quality_summary(const InterfaceMesh& mesh) {
  const OMesh& om = mesh.omesh();
  const size_t n = om.n_faces(), chunk = 8192, chunks = (n + chunk - 1) / chunk;
  std::vector<double> lo(chunks, std::numeric_limits<double>::infinity());
  // Qualities lie in [0, 1]; a fixed-point sum makes the mean independent of the
  // face order (core/fixed_point_sum.hpp), as the stopping rule must be.
  std::vector<detail::FixedPointSum> sum(chunks, detail::FixedPointSum(1.0));
  const std::vector<double>& quality = mesh.qualities();
  detail::parallel_for(size_t(0), chunks, [&](size_t c) {
    // Summed in locals, stored once: through the vectors, every 128-bit add
    // waited on the store before it (6% of an iteration on the 16k scene).
    double lowest = lo[c];
    detail::FixedPointSum chunk_sum(1.0);
    for (size_t f = c * chunk; f < std::min(n, (c + 1) * chunk); ++f) {
      const double q = quality[f];
      lowest = std::min(lowest, q);
      chunk_sum.add(q);
    }
    lo[c] = lowest;
    sum[c] = chunk_sum;
  });
  double min_q = n ? std::numeric_limits<double>::infinity() : 0;
  detail::FixedPointSum total(1.0);
  for (size_t c = 0; c < chunks; ++c) min_q = std::min(min_q, lo[c]), total.add_raw(sum[c].raw());
  return {min_q, n ? total.total() / double(n) : 0};
}

bool Pipeline::distributes() const {
  return std::all_of(steps_.begin(), steps_.end(), [](const Step& s) { return s.info.distributed; });
}

std::vector<std::unique_ptr<Pass>> Pipeline::make_passes() const {
  std::vector<std::unique_ptr<Pass>> passes;
  for (const Step& s : steps_) passes.push_back(s.info.make(s.params));
  return passes;
}

std::vector<double> Pipeline::iterate(PassContext& context, const std::vector<std::unique_ptr<Pass>>& passes) const {
  std::vector<double> pass_seconds(passes.size(), 0.0);
  size_t last_moving = 0;
  auto timed = [&](size_t slot, auto&& work) {
    const auto t0 = std::chrono::steady_clock::now();
    work();
    pass_seconds[slot] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  for (size_t i = 0; i < passes.size(); ++i) {
    // Moves are committed at one point, before anything that looks at positions.
    if (!steps_[i].info.moves_nodes) timed(last_moving, [&] { context.commit(); });
    else last_moving = i;
    timed(i, [&] { passes[i]->run(context); });
  }
  timed(last_moving, [&] { context.commit(); });
  return pass_seconds;
}

int Pipeline::run(InterfaceMesh& mesh, const PhaseField* field, const RunOptions& options) const {
  if (needs_field() && !field)
    throw InvalidInput(located("pipeline", "'" + describe() + "' needs the phase functions (give --field)"));
  if (field) detail::require_phases(*field, mesh);
  const std::vector<std::unique_ptr<Pass>> passes = make_passes();
  PassContext context(mesh, field);
  context.guard_crossings = options.guard_crossings;
  context.floor_pass = std::any_of(steps_.begin(), steps_.end(), [](const Step& s) { return s.info.name == "floor"; });
  const auto [first_min, first_mean] = quality_summary(mesh);
  if (options.observer)
    options.observer({0, first_min, first_mean, 0, 0, 0, std::nullopt, {}, options.iterations}, mesh);
  detail::RunState state{detail::Convergence(options, first_min, first_mean, settled_from()), first_min, 0};
  detail::CrossingWindows windows(options.guard_crossings ? options.check_crossings_every : 1);
  auto crossed = [&] { return !context.guard.crossings(mesh, {}).empty(); };
  for (int it = 1; it <= state.convergence.last(); ++it) {
    context.iterations = state.convergence.last();
    if (options.stop_requested && options.stop_requested()) {
      // The mesh is then that of an iteration checked.
      if (windows.is_open()) windows.close(crossed(), it, mesh, state, context.guard);
      break;
    }
    const auto start = std::chrono::steady_clock::now();
    windows.before(it, mesh, state, context.guard);
    context.iteration = it;
    context.flips = 0;
    context.undone_moves = 0;
    context.stats.reset();
    context.quality_floor = state.worst_now;
    context.guard.forget_floor_exceptions();
    const std::vector<double> pass_seconds = iterate(context, passes);
    state.done = it;
    const auto [min_q, mean_q] = quality_summary(mesh);
    state.worst_now = min_q;
    // Converged: the next iteration is the last, and is told so before it runs.
    state.convergence.after(it, min_q, mean_q);
    const bool deferred = windows.is_open();
    const bool closes = windows.after(it, state.convergence.last(), context.guard);
    const bool crossing = closes && crossed(); // in this iteration's time
    if (options.observer)
      options.observer({it, min_q, mean_q, context.flips, context.undone_moves,
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), context.stats,
                        pass_seconds, state.convergence.last(), deferred, crossing},
                       mesh);
    if (closes) windows.close(crossing, it, mesh, state, context.guard);
  }
  return state.done;
}

} // namespace vm
