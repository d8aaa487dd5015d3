#include "fields/volume_scenes.hpp"

#include "voronoimesh/core/errors.hpp"

#include "core/distinct.hpp"
#include "core/huge_pages.hpp"
#include "core/memory.hpp"
#include "core/parallel.hpp"
#include "core/text.hpp"
#include "fields/bcc_fit.hpp"
#include "fields/label_field.hpp"
#include "fields/top_k_grid_field.hpp"
#include "fields/voxel_grid.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <unordered_map>

namespace vm::detail {

namespace {

/// The value `r` names in a volume with these segments: its value, or the
/// label of the one segment of that name.
int32_t label_value(const LabelRef& r, const std::vector<io::Segment>& segments, const char* option,
                    const std::string& path) {
  if (r.value) return *r.value;
  const io::Segment* found = nullptr;
  for (const io::Segment& s : segments) {
    if (s.name != r.name) continue;
    if (found) throw InvalidInput(located(path, cat(option, ": two segments are named ", quote(r.name), "; give its label value")));
    found = &s;
  }
  if (found) return found->label;
  std::string names;
  for (const io::Segment& s : segments) names += cat(names.empty() ? "" : ", ", quote(s.name));
  throw InvalidInput(located(path, cat(option, ": no segment is named ", quote(r.name),
                                       segments.empty() ? std::string(" (this volume names none of its labels: give label values)")
                                                        : cat(" (its segments: ", names, ")"))));
}

/// What each label present becomes after --keep-labels, --drop-labels,
/// --merge-labels and the background rule: a label value (any 32-bit integer),
/// or none for no phase.
std::vector<std::optional<int32_t>> label_targets(const std::vector<int32_t>& present, const InputOptions& o,
                                                  const std::vector<io::Segment>& segments, const std::string& path) {
  auto values = [&](const std::vector<LabelRef>& refs, const char* option) {
    std::vector<int32_t> out;
    for (const LabelRef& r : refs) {
      const int32_t l = label_value(r, segments, option, path);
      if (!std::binary_search(present.begin(), present.end(), l))
        throw InvalidInput(located(path, cat(option, ": label ", l, r.value ? std::string() : cat(" (", quote(r.name), ")"),
                                             " is not in the volume")));
      out.push_back(l);
    }
    return out;
  };
  const std::vector<int32_t> keep = values(o.keep_labels, "--keep-labels"), drop = values(o.drop_labels, "--drop-labels");
  std::vector<std::vector<int32_t>> merges;
  for (const auto& group : o.merge_labels) merges.push_back(values(group, "--merge-labels"));
  auto listed = [](const std::vector<int32_t>& list, int32_t l) { return std::find(list.begin(), list.end(), l) != list.end(); };
  std::vector<std::optional<int32_t>> target(present.size());
  for (size_t i = 0; i < present.size(); ++i) {
    int32_t t = present[i];
    if (listed(drop, t) || (!keep.empty() && !listed(keep, t))) t = o.background;
    for (const auto& group : merges)
      if (listed(group, t)) t = *std::min_element(group.begin(), group.end());
    if (!(o.no_background && t == o.background)) target[i] = t;
  }
  return target;
}

/// A note when --background or --no-background names a label that no voxel has
/// or is given by the label options (a mistyped label would otherwise pass
/// unseen, naming no phase or filling no gap); "" otherwise, and for the default
/// background, which a volume need not have.
std::string absent_background_note(const std::vector<int32_t>& present,
                                   const std::vector<std::optional<int32_t>>& target, const InputOptions& o) {
  if (o.background == InputOptions{}.background && !o.no_background) return {};
  for (size_t i = 0; i < present.size(); ++i)
    if (o.no_background ? !target[i] : target[i] == o.background) return {};
  const bool relabelled = !o.keep_labels.empty() || !o.drop_labels.empty();
  return cat("--background ", o.background, ": no voxel has this label",
             relabelled ? " or is made background by --keep-labels or --drop-labels" : "",
             o.no_background ? ", so --no-background changes nothing" : ", so no phase is the background");
}

/// The name of label l's phase: "background", its segment's name (from
/// `segment_of`, label -> segment), or "label<l>".
std::string label_name(int32_t l, const InputOptions& o,
                       const std::unordered_map<int32_t, const io::Segment*>& segment_of) {
  if (l == o.background) return "background";
  const auto it = segment_of.find(l);
  return it != segment_of.end() ? it->second->name : cat("label", l);
}

/// Refuses, before building them, phase functions that cannot fit in memory:
/// per node K ids (16-bit) and values and a floor (all of them for a distance
/// grid, whose every node is stored), and `extra` bytes per node besides.
void refuse_huge_field(int64_t nodes, int top_k, double extra, const std::string& path) {
  refuse_beyond_memory(double(nodes) * (4.0 + 6.0 * top_k + extra), path,
                       cat("building the phase functions of ", double(nodes), " voxels"));
}

/// A label the bcc lattice would lose more than this share of decides for cube6.
constexpr double kBccLossAllowed = 0.01;

/// How many voxels each phase has, and the first and last of them (indices,
/// x fastest; -1 for a phase without voxels).
struct PhaseCensus {
  std::vector<int64_t> voxels, first, last;
  explicit PhaseCensus(size_t phases) : voxels(phases, 0), first(phases, -1), last(phases, -1) {}
  /// Counts voxels n to n + count - 1, all of phase p.
  void add_run(int16_t p, int64_t n, int64_t count) {
    const auto q = size_t(p);
    voxels[q] += count;
    if (first[q] < 0 || n < first[q]) first[q] = n;
    last[q] = std::max(last[q], n + count - 1);
  }
  void add(const PhaseCensus& other) {
    for (size_t q = 0; q < voxels.size(); ++q) {
      if (other.voxels[q] == 0) continue;
      voxels[q] += other.voxels[q];
      first[q] = first[q] < 0 ? other.first[q] : std::min(first[q], other.first[q]);
      last[q] = std::max(last[q], other.last[q]);
    }
  }
};

/// Scene::phase_around: for each phase of at most kSurroundedUpTo voxels,
/// the phase its voxels touch most often across a face (ties: the lower id).
/// Slices of voxels in parallel, neighbours looked at only for small phases;
/// only the slices between the small phases' first and last voxels (on the
/// liver, two voxels of label 84: one slice of 165).
std::vector<int32_t> phases_around_small_ones(const PhaseVoxels& pv, const PhaseCensus& census) {
  constexpr int64_t kSurroundedUpTo = 100000;
  const std::vector<int64_t>& voxels = census.voxels;
  const size_t phases = voxels.size();
  std::vector<int32_t> around(phases, -1);
  std::vector<uint8_t> small(phases, 0);
  const int64_t nx = pv.size[0], ny = pv.size[1], nz = pv.size[2]; // not a binding: captured below (clang 14)
  int64_t first_slice = nz, last_slice = -1;
  for (size_t p = 0; p < phases; ++p) {
    small[p] = voxels[p] > 0 && voxels[p] <= kSurroundedUpTo;
    if (!small[p]) continue;
    first_slice = std::min(first_slice, census.first[p] / (nx * ny));
    last_slice = std::max(last_slice, census.last[p] / (nx * ny));
  }
  if (last_slice < 0) return around;
  const int64_t strides[3] = {1, nx, nx * ny}, extents[3] = {nx, ny, nz};
  using Contact = std::pair<int16_t, int16_t>; // a small phase's voxel, a face neighbour of another phase
  std::vector<std::vector<Contact>> slices(static_cast<size_t>(last_slice - first_slice + 1));
  parallel_for_each_index(slices.size(), [&](size_t slice) {
    const int64_t k = first_slice + int64_t(slice);
    for (int64_t j = 0; j < ny; ++j)
      for (int64_t i = 0; i < nx; ++i) {
        const int64_t n = i + nx * (j + ny * k);
        const int16_t p = pv.phase[size_t(n)];
        if (p < 0 || !small[size_t(p)]) continue;
        const int64_t at[3] = {i, j, k};
        for (int a = 0; a < 3; ++a)
          for (int64_t step : {-1, 1})
            if (at[a] + step >= 0 && at[a] + step < extents[a])
              if (const int16_t q = pv.phase[size_t(n + step * strides[a])]; q >= 0 && q != p)
                slices[slice].push_back({p, q});
      }
  }, 1); // a slice a task: under the default grain (512) a volume's slices ran as one task
  std::map<Contact, int64_t> count;
  for (const auto& slice : slices)
    for (const Contact& c : slice) ++count[c];
  std::vector<int64_t> most(phases, 0);
  for (const auto& [c, n] : count) // in phase order: ties go to the lower id
    if (n > most[size_t(c.first)]) most[size_t(c.first)] = n, around[size_t(c.first)] = c.second;
  return around;
}

/// Whether create should take every node of the voxel grid, with the line that
/// says so, or says how many voxel centres the bcc lattice cannot hold.
bool needs_every_grid_node(const PhaseVoxels& pv, const PhaseField& field, double snap,
                           const std::vector<int64_t>& voxels, std::vector<std::string>& notes) {
  const std::vector<int64_t> lost = voxels_bcc_cannot_hold(pv, field, snap);
  size_t worst = 0;
  int64_t total = 0;
  for (size_t p = 0; p < lost.size(); ++p) {
    total += lost[p];
    if (double(lost[p]) * double(voxels[worst]) > double(lost[worst]) * double(voxels[p])) worst = p;
  }
  if (total == 0) return false;
  const double share = double(lost[worst]) / double(voxels[worst]);
  const bool every_node = share > kBccLossAllowed;
  notes.push_back(cat(total, " voxel centres lie in structures one voxel thin where the bcc lattice has no node (",
                      "label ", pv.labels[worst], ": ", lost[worst], " of ", voxels[worst], "): ",
                      every_node ? "create takes every grid node (the cube6 lattice; --lattice bcc keeps the coarser one)"
                                 : "the bcc lattice leaves them to the labels around (--lattice cube6 keeps them)"));
  return every_node;
}

void check_phase_count(size_t count, const std::string& source, const char* what) {
  if (count < 2) throw InvalidInput(located(source, cat("has ", count, " phase(s)", what, "; meshing needs 2 or more")));
  if (count > kMaxPhases) throw InvalidInput(located(source, cat("has ", count, " phases; at most ", kMaxPhases)));
}

} // namespace

void check_input_options(const InputOptions& o) {
  if (!(o.smoothing > 0 && o.smoothing <= 8)) throw InvalidInput(cat("--smoothing: must be in (0, 8] voxels, got ", o.smoothing));
  if (!(o.band >= 1 && o.band <= 64)) throw InvalidInput(cat("--band: must be in [1, 64] voxels, got ", o.band));
  if (o.top_k < 1 || o.top_k > 16) throw InvalidInput("--top-k: must be between 1 and 16");
  if (!(o.snap >= 0 && o.snap <= 0.5)) throw InvalidInput(cat("--snap: must be in [0, 0.5] grid spacings, got ", o.snap));
  if (!(o.voxels_per_cell == 0 || (o.voxels_per_cell >= 1 && o.voxels_per_cell <= 64)))
    throw InvalidInput(cat("--voxels-per-cell: must be in [1, 64] (or 0, the default grid), got ", o.voxels_per_cell));
  for (const auto& group : o.merge_labels)
    if (group.size() < 2) throw InvalidInput("--merge-labels: each group needs two labels or more, as A+B");
  if (o.voxel_size && !(o.voxel_size->allFinite() && o.voxel_size->minCoeff() > 0))
    throw InvalidInput(cat("--voxel-size: every size must be above 0, got ", o.voxel_size->x(), ", ",
                           o.voxel_size->y(), ", ", o.voxel_size->z()));
  if (o.world != World::file && o.ignore_direction)
    throw InvalidInput("--world: not with --ignore-direction (the mesh is then in the voxel axes, in no anatomical frame)");
  // An option of the other label function would change nothing: refused, not ignored.
  const InputOptions defaults;
  if (o.label_function == LabelFunction::signed_distance && o.smoothing != defaults.smoothing)
    throw InvalidInput("--smoothing: applies to the smoothed indicator, not with --signed-distance");
  if (o.label_function != LabelFunction::signed_distance && o.band != defaults.band)
    throw InvalidInput("--band: applies to signed distances: give it with --signed-distance");
}

Scene label_volume_scene(io::Volume v, const InputOptions& o, const std::string& path) {
  if (v.components != 1)
    throw InvalidInput(located(path, cat("has ", v.components, " integer components per voxel; a label volume has one")));
  refuse_huge_field(v.voxel_count(), o.top_k, 6, path); // the labels and their phases
  const std::vector<int32_t> present = distinct(v.labels);
  const std::vector<std::optional<int32_t>> target = label_targets(present, o, v.segments, path);
  PhaseVoxels pv{v.size, v.spacing, v.origin, {}, {}, {}, {}};
  for (const auto& t : target)
    if (t) pv.labels.push_back(*t);
  std::sort(pv.labels.begin(), pv.labels.end());
  pv.labels.erase(std::unique(pv.labels.begin(), pv.labels.end()), pv.labels.end());
  check_phase_count(pv.labels.size(), path, " after the label options");
  std::unordered_map<int32_t, const io::Segment*> segment_of;
  for (const io::Segment& s : v.segments) segment_of.emplace(s.label, &s);
  for (int32_t l : pv.labels) pv.names.push_back(label_name(l, o, segment_of));
  // A phase named after its segment shows the segment's colour (the background shows none).
  for (size_t p = 0; p < pv.labels.size(); ++p) {
    const auto it = segment_of.find(pv.labels[p]);
    if (it == segment_of.end() || pv.labels[p] == o.background || !it->second->color) continue;
    pv.colors.resize(p + 1);
    pv.colors[p] = it->second->color;
  }
  std::vector<std::string> notes = std::move(v.notes);
  if (const std::string note = absent_background_note(present, target, o); !note.empty()) notes.push_back(note);
  for (const io::Segment& s : v.segments)
    if (!std::binary_search(present.begin(), present.end(), s.label))
      notes.push_back(cat("segment ", quote(s.name), " (label ", s.label, ") has no voxels: it is no phase"));
  // Label value -> phase id, through the position of the label among `present`.
  std::vector<int32_t> phase_of(present.size());
  for (size_t i = 0; i < present.size(); ++i)
    phase_of[i] = !target[i] ? -1 // no phase
                             : int32_t(std::lower_bound(pv.labels.begin(), pv.labels.end(), *target[i]) - pv.labels.begin());
  resize_on_huge_pages(pv.phase, v.labels.size());
  // Label value -> phase id: a table over the labels' range when it is small (8- and 16-bit files).
  const int64_t first = present.front(), span = int64_t(present.back()) - first + 1;
  std::vector<int16_t> table(span <= (1 << 20) ? size_t(span) : 0);
  for (size_t i = 0; i < present.size() && !table.empty(); ++i) table[size_t(present[i] - first)] = int16_t(phase_of[i]);
  // Each phase's voxels counted on the way, by each thread on its own (a
  // serial count after the map took 50 ms of the liver's 25M voxels), a run of
  // one phase at a time: one counter in memory raised at every voxel chained
  // each addition to the last, a third of the loop's time.
  tbb::enumerable_thread_specific<PhaseCensus> counted(PhaseCensus(pv.labels.size()));
  const tbb::blocked_range<size_t> all_voxels(0, v.labels.size(), 1 << 16);
  auto map_voxels = [&](auto phase_of_label) {
    detail::parallel_for(all_voxels, [&](const tbb::blocked_range<size_t>& r) {
      PhaseCensus& mine = counted.local();
      int16_t run_phase = -1;
      int64_t run_start = int64_t(r.begin());
      for (size_t n = r.begin(); n != r.end(); ++n) {
        const int16_t p = phase_of_label(v.labels[n]);
        pv.phase[n] = p;
        if (p != run_phase) {
          if (run_phase >= 0) mine.add_run(run_phase, run_start, int64_t(n) - run_start);
          run_phase = p, run_start = int64_t(n);
        }
      }
      if (run_phase >= 0) mine.add_run(run_phase, run_start, int64_t(r.end()) - run_start);
    });
  };
  if (!table.empty()) map_voxels([&](int32_t label) { return table[size_t(label - first)]; });
  else
    map_voxels([&](int32_t label) {
      return int16_t(phase_of[size_t(std::lower_bound(present.begin(), present.end(), label) - present.begin())]);
    });
  v.labels = {}; // the phases replace the labels: free them before the field grows
  PhaseCensus census(pv.labels.size());
  for (const PhaseCensus& part : counted) census.add(part);
  LabelFieldParams params;
  params.signed_distance = o.label_function == LabelFunction::signed_distance;
  params.smoothing = o.smoothing;
  params.voxel_faithful = o.voxel_faithful;
  params.band = o.band;
  params.k = o.top_k;
  // Opt-in, and only on the voxel grid (off it no lattice holds every voxel),
  // which is then the default grid of flat voxels too.
  // Signed distances lead at voxel centres already: there the option only asks for the lattice.
  const double per_cell = o.voxel_faithful && o.voxels_per_cell == 0 ? 1 : o.voxels_per_cell;
  auto field = label_field(pv, params, path);
  const bool every_node = o.voxel_faithful && resolved_voxels_per_cell(per_cell, field->grid().spacing()) == 1 &&
                          needs_every_grid_node(pv, *field, o.snap * field->grid().h(), census.voxels, notes);
  std::vector<int32_t> around = phases_around_small_ones(pv, census);
  const GridSpec grid = volume_scene_grid(field->grid(), per_cell, path, notes);
  Scene scene{grid, field, true, std::move(census.voxels), std::move(around), std::move(notes)};
  scene.needs_every_grid_node = every_node;
  return scene;
}

Scene phase_values_scene(const GridSpec& grid, int num_phases, const NodeValues& fill, std::vector<std::string> names,
                         std::vector<int32_t> labels, int top_k, const std::string& source) {
  check_phase_count(size_t(std::max(num_phases, 0)), source, "");
  if (!names.empty() && names.size() != size_t(num_phases))
    throw InvalidInput(located(source, cat(names.size(), " phase names for ", num_phases, " phases")));
  if (!labels.empty() && labels.size() != size_t(num_phases))
    throw InvalidInput(located(source, cat(labels.size(), " phase labels for ", num_phases, " phases")));
  if (std::adjacent_find(labels.begin(), labels.end(), std::greater_equal<>()) != labels.end())
    throw InvalidInput(located(source, "phase labels must be strictly increasing"));
  refuse_huge_field(grid.node_count(), top_k, 0, source);
  for (int i = int(names.size()); i < num_phases; ++i) names.push_back(cat("phase", i));
  auto field = std::make_shared<TopKGridField>(grid, top_k, std::move(names), std::move(labels));
  std::vector<float> values(static_cast<size_t>(num_phases));
  const auto n0 = grid.nodes()[0], n1 = grid.nodes()[1];
  for (int64_t n = 0; n < grid.node_count(); ++n) {
    fill(n, values);
    for (int32_t i = 0; i < num_phases; ++i) {
      if (!std::isfinite(values[size_t(i)]))
        throw InvalidInput(located(source, cat("phase ", i, " at node (", n % n0, ", ", n / n0 % n1, ", ", n / (n0 * n1),
                                               "): value ", values[size_t(i)], " is not a finite float")));
      field->offer(n, i, values[size_t(i)]);
    }
  }
  field->finish(0.f); // every phase was offered everywhere: nothing to pad
  return Scene{even_scene_grid(grid, source), field};
}

} // namespace vm::detail
