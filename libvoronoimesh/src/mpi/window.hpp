#pragma once
/// @file mpi/window.hpp
/// What distributed improvement (improve_part.cpp) works on: bands of z that
/// the ranks own, and each rank's window of the mesh around its band, built
/// afresh every iteration from the triangles the ranks send, in the assembled
/// mesh's id order (so that the passes see what one process sees).

#include "mpi/comm.hpp"
#include "voronoimesh/mpi/distributed.hpp"

#include <cstring>
#include <vector>

namespace vm::mpi::detail {

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
  Bands(Comm& comm, std::vector<double> own_z);
  /// The rank whose band holds z.
  int owner(double z) const;
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
  /// The local index of vertex `id`, or -1.
  int32_t local(int64_t id) const;
};

/// The window of `records` (each triangle once), with `part`'s domain and phases.
Window build_window(std::vector<TriangleRecord> records, const MeshPart& part);

/// Longest edge of the triangles.
double longest_edge(const std::vector<TriangleRecord>& records);

/// The triangles of a created part, each with its corners' positions.
std::vector<TriangleRecord> records_of(const MeshPart& part);

/// Sends each rank's records to the ranks `to` picks for them; returns what arrived.
template <class T, class To> std::vector<T> exchange(Comm& comm, const std::vector<T>& records, To&& to) {
  std::vector<std::vector<char>> out(size_t(comm.size()));
  for (const T& t : records)
    for (int r = 0; r < comm.size(); ++r)
      if (to(t, r)) append_bytes(out[size_t(r)], t);
  std::vector<T> received;
  for (const auto& bytes : comm.all_to_all(out)) {
    const auto part = from_bytes<T>(bytes);
    received.insert(received.end(), part.begin(), part.end());
  }
  return received;
}

} // namespace vm::mpi::detail
