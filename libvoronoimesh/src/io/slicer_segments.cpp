/// @file io/slicer_segments.cpp
/// Segments of 3D Slicer segmentations (io/slicer_segments.hpp).

#include "io/slicer_segments.hpp"

#include "voronoimesh/core/errors.hpp"

#include "core/text.hpp"

#include <algorithm>
#include <map>
#include <sstream>
#include <utility>

namespace vm::io::slicer {

namespace {

using detail::cat;
using detail::parse_number;

/// The three numbers of a Segment<i>_Color value, or nothing when it is not three numbers in [0, 1].
std::optional<Rgb> parse_color(const std::string& text) {
  std::istringstream in(text);
  Rgb rgb;
  for (float& c : rgb)
    if (!(in >> c) || !(c >= 0 && c <= 1)) return std::nullopt;
  std::string rest;
  if (in >> rest) return std::nullopt;
  return rgb;
}

/// How far past the last segment read_segments() looks for a numbering gap.
constexpr int kGapLooked = 16;

} // namespace

std::vector<Segment> read_segments(const HeaderValue& value_of, int layers, const std::string& path) {
  std::vector<Segment> segments;
  std::map<std::pair<int, int32_t>, size_t> owner; // (layer, label) -> segment
  for (int i = 0;; ++i) {
    const std::string key = cat("Segment", i, "_");
    const auto id = value_of(key + "ID");
    if (!id) {
      // Segments are numbered from 0 without gaps: one missing its ID would
      // silently end the list, and the names of those after it with it.
      for (int later = i + 1; later <= i + kGapLooked; ++later)
        if (value_of(cat("Segment", later, "_ID")))
          throw InvalidInput(located(path, cat("has Segment", later, "_ID but no ", key, "ID: segments are numbered "
                                                                                    "from 0 without gaps")));
      break;
    }
    Segment s;
    s.name = value_of(key + "Name").value_or(*id);
    const auto label = value_of(key + "LabelValue"), layer = value_of(key + "Layer");
    auto field_error = [&](const std::string& field, const std::string& text, const char* expected) {
      return InvalidInput(located(path, cat("segment ", i, " (", detail::quote(s.name), "): ", key, field, " is ",
                                            detail::quote(text), "; expected ", expected)));
    };
    if (label && !parse_number(*label, s.label)) throw field_error("LabelValue", *label, "an integer");
    s.layer = label ? 0 : i; // before label values, each segment had a layer of its own
    if (layer && !parse_number(*layer, s.layer)) throw field_error("Layer", *layer, "an integer");
    if (const auto color = value_of(key + "Color")) {
      s.color = parse_color(*color);
      if (!s.color) throw field_error("Color", *color, "three numbers in [0, 1]");
    }
    if (s.layer < 0 || s.layer >= layers)
      throw InvalidInput(located(path, cat("segment ", i, " (", detail::quote(s.name), ") is in layer ", s.layer,
                                           ", but the file has ", layers, layers == 1 ? " layer" : " layers")));
    if (s.label == 0)
      throw InvalidInput(located(path, cat("segment ", i, " (", detail::quote(s.name),
                                           ") has label value 0, which marks voxels in no segment")));
    if (const auto [at, added] = owner.emplace(std::pair{s.layer, s.label}, segments.size()); !added)
      throw InvalidInput(located(path, cat("segments ", at->second, " and ", i, " both have label value ", s.label,
                                           " in layer ", s.layer)));
    segments.push_back(std::move(s));
  }
  return segments;
}

void flatten_segment_layers(Volume& v, const std::string& path) {
  if (v.segments.empty()) return;
  const int layers = v.components;
  std::map<std::pair<int, int32_t>, int32_t> segment_of; // (layer, value) -> segment
  std::vector<int32_t> values;
  for (size_t s = 0; s < v.segments.size(); ++s) {
    segment_of[{v.segments[s].layer, v.segments[s].label}] = int32_t(s);
    values.push_back(v.segments[s].label);
  }
  std::sort(values.begin(), values.end());
  const bool distinct = std::adjacent_find(values.begin(), values.end()) == values.end();
  if (layers == 1 && distinct) return; // the labels are the segments' values already
  if (!distinct)
    for (size_t s = 0; s < v.segments.size(); ++s) v.segments[s].label = int32_t(s) + 1;
  // Each voxel's segments, one per layer at most, looked up once: the layer
  // values become segment index + 1 in place (0: none). Then the smallest.
  const int64_t voxels = v.voxel_count();
  std::vector<int64_t> size(v.segments.size(), 0);
  for (int64_t n = 0; n < voxels; ++n)
    for (int l = 0; l < layers; ++l) {
      int32_t& value = v.labels[size_t(n * layers + l)];
      if (value == 0) continue;
      const auto it = segment_of.find({l, value});
      if (it == segment_of.end())
        throw InvalidInput(located(path, cat("layer ", l, " holds value ", value, " at voxel ", n,
                                             ", which no segment of the header has")));
      ++size[size_t(it->second)];
      value = it->second + 1;
    }
  std::vector<int32_t> flat(size_t(voxels), 0);
  int64_t contested = 0;
  for (int64_t n = 0; n < voxels; ++n) {
    int32_t best = -1;
    int found = 0;
    for (int l = 0; l < layers; ++l)
      if (const int32_t s = v.labels[size_t(n * layers + l)] - 1; s >= 0) {
        ++found;
        if (best < 0 || std::pair{size[size_t(s)], s} < std::pair{size[size_t(best)], best}) best = s;
      }
    contested += found > 1;
    if (best >= 0) flat[size_t(n)] = v.segments[size_t(best)].label;
  }
  v.labels = std::move(flat);
  v.components = 1;
  if (contested > 0)
    v.notes.push_back(cat(contested, contested == 1 ? " voxel lies" : " voxels lie",
                          " in more than one segment: each went to the smallest segment holding it"));
}

} // namespace vm::io::slicer
