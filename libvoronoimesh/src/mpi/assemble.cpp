/// @file mpi/assemble.cpp
/// The whole mesh on rank 0, or one file per rank with a ParaView index.

#include "voronoimesh/mpi/distributed.hpp"

#include "core/staged_outputs.hpp"
#include "io/writers.hpp"
#include "mpi/comm.hpp"
#include "voronoimesh/core/errors.hpp"
#include "voronoimesh/io/write_mesh.hpp"

#include <algorithm>
#include <climits>
#include <filesystem>

namespace vm::mpi {

namespace {

NodeMesh mesh_of(const MeshPart& part) {
  NodeMesh m;
  m.points = part.points;
  m.triangles = part.triangles;
  m.pairs = part.pairs;
  m.phase_names = part.phase_names;
  m.phase_labels = part.phase_labels;
  m.phase_colors = part.phase_colors;
  m.domain = part.domain;
  m.grid_spacing = part.grid_spacing;
  m.outside_phase = part.outside_phase;
  return m;
}

} // namespace

NodeMesh assemble(MPI_Comm c, const MeshPart& part) {
  detail::Comm comm(c);
  NodeMesh mesh;
  comm.collectively([&] {
    if (part.global_nodes > INT_MAX || part.global_triangles > INT_MAX)
      throw InvalidInput("mpi: a mesh of " + std::to_string(part.global_nodes) + " nodes and " +
                         std::to_string(part.global_triangles) + " triangles is too large to assemble on one rank");
    // Every vertex once, from its owner, and every triangle, each with its id.
    // Ids ascend as the assembled mesh's indices do; after collapses they have
    // gaps, which the assembled mesh closes (as one process renumbers).
    struct Vertex {
      int64_t id;
      double xyz[3];
    };
    struct Triangle {
      int64_t id;
      int64_t corners[3];
      PhasePair pair;
    };
    std::vector<Vertex> own;
    for (size_t v = 0; v < part.points.size(); ++v)
      if (part.owners[v] == comm.rank())
        own.push_back({part.global_ids[v], {part.points[v].x(), part.points[v].y(), part.points[v].z()}});
    std::vector<Triangle> triangles;
    for (size_t t = 0; t < part.triangles.size(); ++t) {
      const auto& tri = part.triangles[t];
      triangles.push_back({part.triangle_ids[t],
                           {part.global_ids[size_t(tri[0])], part.global_ids[size_t(tri[1])],
                            part.global_ids[size_t(tri[2])]},
                           part.pairs[t]});
    }
    std::vector<Vertex> vertices = comm.gather(std::span<const Vertex>(own));
    std::vector<Triangle> all = comm.gather(std::span<const Triangle>(triangles));
    if (comm.rank() != 0) return;
    auto internal_error = [](const std::string& what) {
      return Error("mpi: internal error: " + what + " (please report this with the input)");
    };
    if (vertices.size() != size_t(part.global_nodes) || all.size() != size_t(part.global_triangles))
      throw internal_error("the parts hold " + std::to_string(vertices.size()) + " vertices and " +
                           std::to_string(all.size()) + " triangles of " + std::to_string(part.global_nodes) +
                           " and " + std::to_string(part.global_triangles));
    std::sort(vertices.begin(), vertices.end(), [](const Vertex& a, const Vertex& b) { return a.id < b.id; });
    std::sort(all.begin(), all.end(), [](const Triangle& a, const Triangle& b) { return a.id < b.id; });
    std::vector<int64_t> ids;
    for (const Vertex& v : vertices) {
      if (!ids.empty() && ids.back() == v.id) throw internal_error("vertex " + std::to_string(v.id) + " has two owners");
      ids.push_back(v.id);
      mesh.points.push_back(Vec3(v.xyz[0], v.xyz[1], v.xyz[2]));
    }
    for (const Triangle& t : all) {
      std::array<int32_t, 3> corners{};
      for (int c = 0; c < 3; ++c) {
        const auto at = std::lower_bound(ids.begin(), ids.end(), t.corners[c]);
        if (at == ids.end() || *at != t.corners[c])
          throw internal_error("triangle " + std::to_string(t.id) + " uses vertex " + std::to_string(t.corners[c]) +
                               ", which no rank owns");
        corners[size_t(c)] = int32_t(at - ids.begin());
      }
      mesh.triangles.push_back(corners);
      mesh.pairs.push_back(t.pair);
    }
    mesh.domain = part.domain;
    mesh.grid_spacing = part.grid_spacing;
    mesh.phase_names = part.phase_names;
    mesh.phase_labels = part.phase_labels;
    mesh.phase_colors = part.phase_colors;
    mesh.outside_phase = part.outside_phase;
  });
  return mesh;
}

void run_collectively(MPI_Comm c, const std::function<void()>& local) {
  detail::Comm comm(c);
  comm.collectively(local);
}

void write_pvtu(MPI_Comm c, const MeshPart& part, const std::string& path) {
  detail::Comm comm(c);
  vm::detail::StagedOutputs staged;
  comm.collectively([&] {
    namespace fs = std::filesystem;
    const fs::path index(path);
    if (index.extension() != ".pvtu")
      throw InvalidInput(located(path, "a parallel VTK index must end in .pvtu"));
    io::detail::write_mesh(staged, mesh_of(part), pvtu_pieces(path, comm.size())[size_t(comm.rank())], {});
    if (comm.rank() != 0) return;
    std::vector<std::string> pieces;
    for (const std::string& piece : pvtu_pieces(path, comm.size()))
      pieces.push_back(fs::path(piece).filename().string());
    io::detail::write_pvtu_index(staged, path, pieces);
  });
  // Every rank has staged its files: they appear together, or (when any rank
  // failed, and every rank threw above) none does.
  comm.collectively([&] { staged.commit(); });
}

std::vector<std::string> pvtu_pieces(const std::string& path, int ranks) {
  namespace fs = std::filesystem;
  const fs::path index(path);
  std::vector<std::string> pieces;
  for (int r = 0; r < ranks; ++r)
    pieces.push_back((index.parent_path() / (index.stem().string() + "_" + std::to_string(r) + ".vtu")).string());
  return pieces;
}

} // namespace vm::mpi
