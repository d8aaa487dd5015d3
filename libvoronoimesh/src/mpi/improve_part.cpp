/// @file mpi/improve_part.cpp
/// vm::mpi::improve_part(): the moving passes of the pipeline over the ranks.
///
/// The ranks split space into bands of z, balanced by vertices; a vertex belongs
/// to the band it lies in (so a vertex that moves across a cut migrates by
/// itself), a triangle to the owner of its corner with the lowest id. Each
/// iteration a rank works on its window: every triangle with a corner within
/// two edge lengths of its band, built afresh with the assembled mesh's vertex
/// and triangle order (ids ascending), so the passes see the rings of its
/// vertices, and the rings of their neighbours, exactly as one process does.
/// The RMS edge length is a fixed-point sum over the ranks' own edges. Two
/// exchanges per iteration: the moved vertices to the ranks whose next window
/// needs them, then the owned triangles to the windows they touch.

#include "voronoimesh/mpi.hpp"

#include "detail/edge_lengths.hpp"
#include "mpi/comm.hpp"
#include "voronoimesh/clamp.hpp"
#include "voronoimesh/errors.hpp"
#include "voronoimesh/guard.hpp"
#include "voronoimesh/project.hpp"
#include "voronoimesh/smooth.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>

namespace vm::mpi {

namespace {

using detail::Comm;

/// A triangle with everything a window needs of it, as sent between ranks.
struct TriangleRecord {
  int64_t id;
  int64_t corners[3]; ///< global vertex ids
  PhasePair pair;
  double xyz[3][3]; ///< the corners' positions
};

/// A vertex's position, as sent by its owner.
struct VertexRecord {
  int64_t id;
  double xyz[3];
};

template <class T> std::vector<T> from_bytes(const std::vector<char>& bytes) {
  std::vector<T> out(bytes.size() / sizeof(T));
  if (!bytes.empty()) std::memcpy(static_cast<void*>(out.data()), bytes.data(), bytes.size());
  return out;
}

template <class T> void append_bytes(std::vector<char>& out, const T& record) {
  const char* p = reinterpret_cast<const char*>(&record);
  out.insert(out.end(), p, p + sizeof(T));
}

/// The bands of z: rank r owns [cuts[r], cuts[r + 1]), the outer cuts infinite.
class Bands {
public:
  /// Cuts at the quantiles of the z of every vertex, from an evenly spaced
  /// sample of each rank's own vertices (weighted by how many each stands for).
  Bands(Comm& comm, std::vector<double> own_z) {
    std::sort(own_z.begin(), own_z.end());
    constexpr size_t kSamples = 1024;
    struct Sample {
      double z, weight;
    };
    std::vector<Sample> mine;
    const size_t step = std::max<size_t>(1, own_z.size() / kSamples);
    for (size_t i = 0; i < own_z.size(); i += step)
      mine.push_back({own_z[i], double(std::min(step, own_z.size() - i))});
    std::vector<Sample> all = comm.all_gather(std::span<const Sample>(mine));
    std::sort(all.begin(), all.end(), [](const Sample& a, const Sample& b) { return a.z < b.z; });
    double total = 0;
    for (const Sample& s : all) total += s.weight;
    cuts_.assign(size_t(comm.size()) + 1, -std::numeric_limits<double>::infinity());
    cuts_.back() = std::numeric_limits<double>::infinity();
    double seen = 0;
    size_t next = 1;
    for (const Sample& s : all) {
      while (next < size_t(comm.size()) && seen >= total * double(next) / comm.size()) cuts_[next++] = s.z;
      seen += s.weight;
    }
    for (; next < size_t(comm.size()); ++next) cuts_[next] = cuts_[next - 1];
  }
  int owner(double z) const {
    return int(std::upper_bound(cuts_.begin() + 1, cuts_.end() - 1, z) - (cuts_.begin() + 1));
  }
  /// True when z is within `margin` of rank r's band.
  bool near(int r, double z, double margin) const {
    return z >= cuts_[size_t(r)] - margin && z < cuts_[size_t(r) + 1] + margin;
  }

private:
  std::vector<double> cuts_;
};

/// One rank's window: a NodeMesh whose vertices and triangles are in id order.
struct Window {
  NodeMesh mesh;
  std::vector<int64_t> vertex_ids, triangle_ids;
};

Window build_window(std::vector<TriangleRecord> records, const MeshPart& part) {
  std::sort(records.begin(), records.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  Window w;
  std::vector<std::pair<int64_t, Vec3>> vertices;
  for (const TriangleRecord& t : records)
    for (int c = 0; c < 3; ++c) vertices.push_back({t.corners[c], Vec3(t.xyz[c][0], t.xyz[c][1], t.xyz[c][2])});
  std::sort(vertices.begin(), vertices.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  vertices.erase(std::unique(vertices.begin(), vertices.end(),
                             [](const auto& a, const auto& b) { return a.first == b.first; }),
                 vertices.end());
  std::unordered_map<int64_t, int32_t> local;
  for (const auto& [id, p] : vertices) {
    local.emplace(id, int32_t(w.vertex_ids.size()));
    w.vertex_ids.push_back(id);
    w.mesh.points.push_back(p);
  }
  for (const TriangleRecord& t : records) {
    w.mesh.triangles.push_back({local.at(t.corners[0]), local.at(t.corners[1]), local.at(t.corners[2])});
    w.mesh.pairs.push_back(t.pair);
    w.triangle_ids.push_back(t.id);
  }
  w.mesh.domain = part.domain;
  w.mesh.phase_names = part.phase_names;
  w.mesh.phase_labels = part.phase_labels;
  return w;
}

double longest_edge(const std::vector<TriangleRecord>& records) {
  double longest = 0;
  for (const TriangleRecord& t : records)
    for (int c = 0; c < 3; ++c) {
      const double* a = t.xyz[c];
      const double* b = t.xyz[(c + 1) % 3];
      longest = std::max(longest, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
    }
  return longest;
}

/// The RMS edge length over every rank's window, each edge counted by the
/// owner of its lower vertex.
double global_rms_edge_length(Comm& comm, const InterfaceMesh& mesh, const std::vector<uint8_t>& own) {
  const vm::detail::SquaredEdgeLengths mine = vm::detail::squared_edge_lengths(mesh, own);
  const auto raw = mine.sum.raw();
  const std::array<uint64_t, 2> halves{uint64_t(raw), uint64_t(raw >> 64)};
  const std::vector<uint64_t> all = comm.all_gather(std::span<const uint64_t>(halves));
  vm::detail::FixedPointSum total(mine.sum.unit());
  for (size_t i = 0; i < all.size(); i += 2)
    total.add_raw(vm::detail::FixedPointSum::Raw((unsigned __int128)all[i + 1] << 64 | all[i]));
  const uint64_t edges = comm.sum(mine.edges);
  return edges ? std::sqrt(total.total() / double(edges)) : 0.0;
}

/// Gives every vertex of the window its owner's move: each rank sends the moves
/// of its own vertices to the ranks whose windows reach them.
void share_moves(Comm& comm, const Window& w, const std::vector<uint8_t>& own, const Bands& bands, double reach,
                 std::vector<Vec3>& delta) {
  std::vector<std::vector<char>> out(size_t(comm.size()));
  for (size_t v = 0; v < own.size(); ++v)
    if (own[v])
      for (int r = 0; r < comm.size(); ++r)
        if (bands.near(r, w.mesh.points[v].z(), reach))
          append_bytes(out[size_t(r)], VertexRecord{w.vertex_ids[v], {delta[v].x(), delta[v].y(), delta[v].z()}});
  size_t given = 0;
  for (const auto& bytes : comm.all_to_all(out))
    for (const VertexRecord& r : from_bytes<VertexRecord>(bytes)) {
      const auto at = std::lower_bound(w.vertex_ids.begin(), w.vertex_ids.end(), r.id);
      if (at == w.vertex_ids.end() || *at != r.id) continue;
      delta[size_t(at - w.vertex_ids.begin())] = Vec3(r.xyz[0], r.xyz[1], r.xyz[2]);
      ++given;
    }
  if (given != delta.size())
    throw Error("mpi: internal error: " + std::to_string(delta.size() - given) +
                " vertices of a window got no move from their owner (please report this)");
}

/// The moving passes this function distributes, with their parameters.
void check_pipeline(const Pipeline& pipeline) {
  for (const Pipeline::Step& s : pipeline.steps())
    if (s.info.name != "smooth" && s.info.name != "project" && s.info.name != "clamp")
      throw InvalidInput("mpi: the pass '" + s.info.name +
                         "' is not distributed yet; improve_part() runs smooth, project and clamp");
}

/// The triangles' first window: each triangle is in exactly one created part.
std::vector<TriangleRecord> records_of(const MeshPart& part) {
  std::vector<TriangleRecord> out;
  for (size_t t = 0; t < part.triangles.size(); ++t) {
    TriangleRecord r{part.triangle_ids[t], {}, part.pairs[t], {}};
    for (int c = 0; c < 3; ++c) {
      const size_t v = size_t(part.triangles[t][size_t(c)]);
      r.corners[c] = part.global_ids[v];
      for (int a = 0; a < 3; ++a) r.xyz[c][a] = part.points[v][a];
    }
    out.push_back(r);
  }
  return out;
}

/// This rank's part: its triangles and vertices (`positions`: of every vertex
/// it knows, by id).
void rebuild_part(MeshPart& part, const std::vector<TriangleRecord>& triangles,
                  const std::unordered_map<int64_t, Vec3>& positions, const Bands& bands, int me) {
  const Window w = build_window(triangles, part);
  part.points = w.mesh.points;
  part.triangles = w.mesh.triangles;
  part.pairs = w.mesh.pairs;
  part.global_ids = w.vertex_ids;
  part.triangle_ids = w.triangle_ids;
  // Its own vertices that none of its triangles use (all theirs belong to
  // lower vertices of other ranks) are in the part too, so that every vertex is.
  std::vector<int64_t> unused;
  for (const auto& [id, p] : positions)
    if (bands.owner(p.z()) == me && !std::binary_search(w.vertex_ids.begin(), w.vertex_ids.end(), id))
      unused.push_back(id);
  std::sort(unused.begin(), unused.end());
  for (int64_t id : unused) {
    part.points.push_back(positions.at(id));
    part.global_ids.push_back(id);
  }
  part.owners.clear();
  for (const Vec3& p : part.points) part.owners.push_back(bands.owner(p.z()));
}

} // namespace

void improve_part(MPI_Comm c, MeshPart& part, const PhaseField& field, const Pipeline& pipeline, int iterations,
                  bool guard_crossings, DistributedStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  Comm comm(c);
  comm.collectively([&] {
    check_pipeline(pipeline);
    if (iterations <= 0) return;
    std::vector<double> own_z;
    for (size_t v = 0; v < part.points.size(); ++v)
      if (part.owners[v] == comm.rank()) own_z.push_back(part.points[v].z());
    const Bands bands(comm, std::move(own_z));
    const int me = comm.rank();
    // The triangles this rank sends to windows: its created ones, then its own.
    std::vector<TriangleRecord> sending = records_of(part);
    double edge = comm.max(longest_edge(sending));
    std::unordered_map<int64_t, Vec3> moved_to;
    const double tolerance = 1e-9 * (part.domain.max - part.domain.min).norm();
    for (int it = 1; it <= iterations; ++it) {
      // A window: every triangle with a corner within two edges of the band, so
      // that the rings of the band's vertices and of their neighbours are whole.
      const double margin = 2 * edge + tolerance;
      std::vector<std::vector<char>> out(size_t(comm.size()));
      for (const TriangleRecord& t : sending)
        for (int r = 0; r < comm.size(); ++r)
          if (bands.near(r, t.xyz[0][2], margin) || bands.near(r, t.xyz[1][2], margin) ||
              bands.near(r, t.xyz[2][2], margin))
            append_bytes(out[size_t(r)], t);
      std::vector<TriangleRecord> received;
      for (const auto& bytes : comm.all_to_all(out)) {
        const auto records = from_bytes<TriangleRecord>(bytes);
        received.insert(received.end(), records.begin(), records.end());
      }
      Window w = build_window(std::move(received), part);
      InterfaceMesh mesh = InterfaceMesh::from_node_mesh(w.mesh);
      std::vector<uint8_t> own(mesh.num_nodes());
      for (size_t v = 0; v < own.size(); ++v) own[v] = bands.owner(mesh.positions()[v].z()) == me;

      // The moving passes, as Pipeline::run() applies them: displacements summed
      // in pipeline order, committed once.
      std::vector<Vec3> delta(mesh.num_nodes(), Vec3::Zero());
      for (const Pipeline::Step& s : pipeline.steps()) {
        if (s.info.name == "smooth")
          add_smoothing_forces_with_rest_length(
              mesh, field, s.params.at("rest_factor") * global_rms_edge_length(comm, mesh, own), delta);
        else if (s.info.name == "project")
          add_projection(mesh, field, ProjectParams{s.params.at("min_gradient_gap")}, delta);
        else
          clamp_displacements(mesh, ClampParams{s.params.at("factor")}, delta);
      }
      double moved = 0;
      for (size_t v = 0; v < own.size(); ++v)
        if (own[v]) moved = std::max(moved, delta[v].norm());
      moved = comm.max(moved);
      // Edges grow by at most the two ends' moves.
      edge += 2 * moved;
      const double reach = 3 * edge + 2 * tolerance;
      if (guard_crossings) {
        // The guard looks at every triangle of the window: each vertex takes its
        // owner's move, and the ranks agree on every round's undone moves.
        share_moves(comm, w, own, bands, reach, delta);
        commit_without_crossings(mesh, delta, &field, [&](std::vector<int32_t>& undone) {
          std::vector<int64_t> ids;
          for (int32_t v : undone) ids.push_back(w.vertex_ids[size_t(v)]);
          std::vector<int64_t> all = comm.all_gather(std::span<const int64_t>(ids));
          std::sort(all.begin(), all.end());
          undone.clear();
          for (int64_t id : all) {
            const auto at = std::lower_bound(w.vertex_ids.begin(), w.vertex_ids.end(), id);
            if (at != w.vertex_ids.end() && *at == id) undone.push_back(int32_t(at - w.vertex_ids.begin()));
          }
          undone.erase(std::unique(undone.begin(), undone.end()), undone.end());
        });
      } else {
        mesh.move_nodes(delta);
      }

      // The moved vertices go to every rank whose next window may use them.
      for (auto& bytes : out) bytes.clear();
      const auto& pos = mesh.positions();
      for (size_t v = 0; v < own.size(); ++v)
        if (own[v])
          for (int r = 0; r < comm.size(); ++r)
            if (bands.near(r, pos[v].z(), reach))
              append_bytes(out[size_t(r)], VertexRecord{w.vertex_ids[v], {pos[v].x(), pos[v].y(), pos[v].z()}});
      moved_to.clear();
      for (const auto& bytes : comm.all_to_all(out))
        for (const VertexRecord& r : from_bytes<VertexRecord>(bytes)) moved_to[r.id] = Vec3(r.xyz[0], r.xyz[1], r.xyz[2]);

      // This rank's triangles now: those whose lowest corner moved into its band.
      // A vertex moves less than a window's margin, so they are all in this window.
      if (moved >= margin)
        throw Error("mpi: internal error: a vertex moved farther than the window reaches (please report this)");
      sending.clear();
      for (size_t t = 0; t < w.mesh.triangles.size(); ++t) {
        const auto& tri = w.mesh.triangles[t];
        const int32_t lowest = *std::min_element(tri.begin(), tri.end()); // local order is id order
        const auto found = moved_to.find(w.vertex_ids[size_t(lowest)]);
        if (found == moved_to.end() || bands.owner(found->second.z()) != me) continue;
        TriangleRecord r{w.triangle_ids[t], {}, w.mesh.pairs[t], {}};
        for (int k = 0; k < 3; ++k) {
          r.corners[k] = w.vertex_ids[size_t(tri[size_t(k)])];
          const auto corner = moved_to.find(r.corners[k]);
          if (corner == moved_to.end())
            throw Error("mpi: internal error: a triangle's corner is missing from its owner's window (please report this)");
          for (int a = 0; a < 3; ++a) r.xyz[k][a] = corner->second[a];
        }
        sending.push_back(r);
      }
    }
    rebuild_part(part, sending, moved_to, bands, me);
  });
  if (stats) {
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats->mpi_seconds = comm.mpi_seconds();
  }
}

} // namespace vm::mpi
