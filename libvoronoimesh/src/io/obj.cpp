/// @file io/obj.cpp
/// Wavefront OBJ: every node once as `v`, then the triangles group by group,
/// one group `g <pair>` per phase pair (io/write_mesh.hpp); with phase
/// colours, a material per group in an .mtl file beside it.

#include "core/text.hpp"
#include "io/output_buffer.hpp"
#include "io/phase_names.hpp"
#include "io/writers.hpp"

#include <filesystem>
#include <numeric>

namespace vm::io::detail {

namespace {

using vm::detail::cat;

/// The colour a pair's surface shows: its second phase's, else its first's.
/// A face can show one colour, though it lies between two phases; the second
/// is the one the normal points into, and the phase of higher label, so in a
/// segmentation the structure rather than the background (label 0) around it,
/// and a phase rather than the exterior of a closed mesh.
std::optional<Rgb> pair_color(const NodeMesh& m, const PhasePair& pair) {
  if (const auto second = phase_color(m, pair[1])) return second;
  return phase_color(m, pair[0]);
}

/// The material library: one material per pair, named as its group, with the
/// pair's colour as its diffuse colour (none when neither phase has one), and
/// every phase's own colour in the comments.
void write_mtl(vm::detail::StagedOutputs& staged, const NodeMesh& m, const std::vector<PhasePair>& pairs,
               const std::string& path, const std::string& obj_name) {
  vm::detail::write_in_chunks(staged, path, [&](vm::detail::ChunkedOutput& out) {
    std::string& buf = out.text();
    buf += cat("# voronoimesh phase colours for ", obj_name, ": one material per phase pair, named as its group.\n",
               "# A surface shows the colour of its pair's second phase (the higher label), else its first's.\n",
               "# The phases' own colours (label-name red green blue):\n");
    const size_t phases = phase_count(m);
    for (size_t p = 0; p < phases; ++p)
      if (const auto color = phase_color(m, int32_t(p))) {
        buf += "#   " + phase_token(m, int32_t(p)) + ' ';
        vm::detail::put_color(buf, *color);
        buf += '\n';
      }
    for (const PhasePair& pair : pairs) {
      buf += "\nnewmtl " + phases_token(m, pair) + '\n';
      if (const auto color = pair_color(m, pair)) {
        buf += "Kd ";
        vm::detail::put_color(buf, *color);
        buf += '\n';
      }
    }
  });
}

} // namespace

std::vector<std::string> write_obj(vm::detail::StagedOutputs& staged, const NodeMesh& m, const std::string& path) {
  const std::vector<PhasePair> pairs = distinct_pairs(m);
  const std::vector<int32_t> index = pair_indices(m, pairs);
  const bool colored = has_phase_colors(m);
  const std::string mtl = std::filesystem::path(path).replace_extension(".mtl").string();
  // Triangles grouped by pair, in their own order within a group.
  std::vector<int32_t> order(m.triangles.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int32_t a, int32_t b) { return index[size_t(a)] < index[size_t(b)]; });
  vm::detail::write_in_chunks(staged, path, [&](vm::detail::ChunkedOutput& out) {
    std::string& buf = out.text();
    buf += cat("# voronoimesh interface mesh: ", m.points.size(), " vertices, ", m.triangles.size(),
               " triangles, ", pairs.size(), " phase pairs\n",
               "# one group per phase pair <a>_<b> (phase label, then -name); the normal of each face\n"
               "# (counter-clockwise order) points from phase a into phase b\n");
    if (colored) buf += "mtllib " + std::filesystem::path(mtl).filename().string() + '\n';
    for (const Vec3& p : m.points) {
      buf += "v ";
      vm::detail::put_point(buf, p);
      buf += '\n';
      out.maybe_flush();
    }
    int32_t group = -1;
    for (int32_t t : order) {
      if (index[size_t(t)] != group) {
        group = index[size_t(t)];
        const std::string name = phases_token(m, pairs[size_t(group)]);
        buf += "g " + name + "\n";
        if (colored) buf += "usemtl " + name + "\n";
      }
      buf += 'f';
      for (int32_t v : m.triangles[size_t(t)]) {
        buf += ' ';
        vm::detail::put_int(buf, v + 1);
      }
      buf += '\n';
      out.maybe_flush();
    }
  });
  if (!colored) return {path};
  write_mtl(staged, m, pairs, mtl, std::filesystem::path(path).filename().string());
  return {path, mtl};
}

} // namespace vm::io::detail
