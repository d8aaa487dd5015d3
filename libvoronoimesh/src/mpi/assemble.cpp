/// @file mpi/assemble.cpp
/// The whole mesh on rank 0, or one file per rank with a ParaView index.

#include "voronoimesh/mpi.hpp"

#include "detail/atomic_write.hpp"
#include "mpi/comm.hpp"
#include "voronoimesh/errors.hpp"
#include "voronoimesh/io/write_mesh.hpp"

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
  m.domain = part.domain;
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
    // Each rank's own vertices hold consecutive ids, in the order of its part.
    std::vector<Vec3> own;
    for (size_t v = 0; v < part.points.size(); ++v)
      if (part.owners[v] == comm.rank()) own.push_back(part.points[v]);
    std::vector<std::array<int32_t, 3>> triangles;
    for (const auto& t : part.triangles)
      triangles.push_back({int32_t(part.global_ids[size_t(t[0])]), int32_t(part.global_ids[size_t(t[1])]),
                           int32_t(part.global_ids[size_t(t[2])])});
    mesh.points = comm.gather(std::span<const Vec3>(own));
    mesh.triangles = comm.gather(std::span<const std::array<int32_t, 3>>(triangles));
    mesh.pairs = comm.gather(std::span<const PhasePair>(part.pairs));
    if (comm.rank() != 0) return;
    mesh.domain = part.domain;
    mesh.phase_names = part.phase_names;
    mesh.phase_labels = part.phase_labels;
  });
  return mesh;
}

void run_collectively(MPI_Comm c, const std::function<void()>& local) {
  detail::Comm comm(c);
  comm.collectively(local);
}

void write_pvtu(MPI_Comm c, const MeshPart& part, const std::string& path) {
  detail::Comm comm(c);
  comm.collectively([&] {
    namespace fs = std::filesystem;
    const fs::path index(path);
    if (index.extension() != ".pvtu")
      throw InvalidInput(located(path, "a parallel VTK index must end in .pvtu"));
    auto piece = [&](int rank) { return index.stem().string() + "_" + std::to_string(rank) + ".vtu"; };
    io::write_mesh(mesh_of(part), (index.parent_path() / piece(comm.rank())).string());
    comm.check_in(); // every piece is there before the index names it
    if (comm.rank() != 0) return;
    // The arrays every piece has (io/vtk_xml.cpp).
    vm::detail::write_atomically(path, [&](std::ostream& out) {
      out << "<?xml version=\"1.0\"?>\n"
             "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
             "  <PUnstructuredGrid GhostLevel=\"0\">\n"
             "    <PPointData Scalars=\"junction_order\">\n"
             "      <PDataArray type=\"Int32\" Name=\"junction_order\"/>\n"
             "    </PPointData>\n"
             "    <PCellData Scalars=\"phase0\">\n"
             "      <PDataArray type=\"Int32\" Name=\"phase0\"/>\n"
             "      <PDataArray type=\"Int32\" Name=\"phase1\"/>\n"
             "    </PCellData>\n"
             "    <PPoints>\n"
             "      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n"
             "    </PPoints>\n";
      for (int r = 0; r < comm.size(); ++r) out << "    <Piece Source=\"" << piece(r) << "\"/>\n";
      out << "  </PUnstructuredGrid>\n</VTKFile>\n";
    });
  });
}

} // namespace vm::mpi
