// Writes a synthetic label volume as a raw NRRD, for the label-volume benchmark.
//
//   make_label_volume ellipsoids|grains SIZE LABELS OUT.nrrd [SEED]
//   make_label_volume ct OUT.nrrd [SEED]
//   make_label_volume thin OUT.nrrd
//
// ellipsoids: LABELS-1 random overlapping ellipsoids (labels 1..) in background 0,
//             like a segmentation of a few organs;
// grains:     a Voronoi polycrystal of LABELS grains (labels 1..LABELS) filling
//             the volume, like a grain map.
// These are uint16 (labels up to 65535), spacing 1, origin 0.
// ct:         a CT-like abdominal/thoracic segmentation, 512 x 512 x 96 voxels
//             (25.2M) of 0.8 mm (isotropic), uint8: 0 air, 1 soft tissue (the
//             body, cut by the first and last slice), 2 bone (spine with discs
//             between vertebrae, ribs as tubes about 6 voxels thick, a sternum),
//             3 an organ (a liver-like lobed blob with a thin lobe), all with
//             smooth random wobbles (ct_volume.hpp).
// thin:       issue 19's structures, 40^3 int16 voxels of 1 mm in background 0: a
//             sheet one voxel thick (label 1, 900 voxels), a tube one voxel wide
//             (label 2, 30), three one-voxel islands (label 3), a 6^3 block
//             (label 4) and a 6^3 block of a negative label (-5).

#include "ct_volume.hpp"

#include <nanoflann.hpp>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace {

struct Seeds {
  std::vector<Eigen::Vector3d> p;
  size_t kdtree_get_point_count() const { return p.size(); }
  double kdtree_get_pt(size_t i, size_t d) const { return p[i][int(d)]; }
  template <class Box> bool kdtree_get_bbox(Box&) const { return false; }
};
using SeedTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Seeds>, Seeds, 3>;

/// Writes `v` (sizes n, x fastest) as a raw little-endian NRRD of `type` ("uchar", "short", "ushort").
template <class T>
int write_nrrd(const char* path, const std::vector<T>& v, const std::array<int, 3>& n, const char* type, double spacing) {
  std::ofstream out(path, std::ios::binary);
  out << "NRRD0004\ntype: " << type << "\ndimension: 3\nsizes: " << n[0] << " " << n[1] << " " << n[2]
      << "\nspacings: " << spacing << " " << spacing << " " << spacing << "\nencoding: raw\nendian: little\n\n";
  out.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(T)));
  return out ? 0 : 1;
}

/// The `thin` volume (see the top of the file), x fastest.
std::vector<int16_t> thin_structures(int n) {
  std::vector<int16_t> v(size_t(n) * size_t(n) * size_t(n), 0);
  auto at = [&](int i, int j, int k) -> int16_t& { return v[size_t(i + n * (j + n * k))]; };
  for (int i = 5; i < 35; ++i)
    for (int j = 5; j < 35; ++j) at(i, j, 10) = 1;
  for (int i = 8; i < 38; ++i) at(i, 30, 30) = 2;
  for (const auto& [i, j, k] : {std::array{30, 8, 20}, std::array{33, 12, 25}, std::array{25, 25, 5}}) at(i, j, k) = 3;
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i) at(15 + i, 15 + j, 20 + k) = 4, at(26 + i, 10 + j, 28 + k) = -5;
  return v;
}

} // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::string(argv[1]) == "thin")
    return write_nrrd(argv[2], thin_structures(40), {40, 40, 40}, "short", 1);
  if (argc >= 3 && std::string(argv[1]) == "ct")
    return write_nrrd(argv[2], ct::volume(argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 1), {ct::nx, ct::ny, ct::nz},
                      "uchar", 0.8);
  if (argc < 5) {
    std::fprintf(stderr, "usage: make_label_volume ellipsoids|grains SIZE LABELS OUT.nrrd [SEED]\n"
                         "       make_label_volume thin OUT.nrrd\n"
                         "       make_label_volume ct OUT.nrrd [SEED]\n");
    return 2;
  }
  const std::string kind = argv[1];
  const int n = std::atoi(argv[2]), labels = std::atoi(argv[3]);
  if ((kind != "ellipsoids" && kind != "grains") || n < 2 || labels < 2 || labels > 65535) {
    std::fprintf(stderr, "make_label_volume: bad arguments\n");
    return 2;
  }
  std::mt19937_64 rng(argc > 5 ? std::strtoull(argv[5], nullptr, 10) : 1);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<uint16_t> v(size_t(n) * size_t(n) * size_t(n), 0);
  if (kind == "ellipsoids") {
    for (int l = 1; l < labels; ++l) {
      const Eigen::Vector3d c(n * (0.25 + 0.5 * unit(rng)), n * (0.25 + 0.5 * unit(rng)), n * (0.25 + 0.5 * unit(rng)));
      const Eigen::Vector3d r(n * (0.1 + 0.2 * unit(rng)), n * (0.1 + 0.2 * unit(rng)), n * (0.1 + 0.2 * unit(rng)));
      for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i)
            if ((Eigen::Vector3d(i, j, k) - c).cwiseQuotient(r).squaredNorm() < 1)
              v[size_t(i) + size_t(n) * (size_t(j) + size_t(n) * size_t(k))] = uint16_t(l);
    }
  } else {
    Seeds seeds;
    for (int l = 0; l < labels; ++l) seeds.p.emplace_back(n * unit(rng), n * unit(rng), n * unit(rng));
    SeedTree tree(3, seeds);
    tree.buildIndex();
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const double q[3] = {double(i), double(j), double(k)};
          unsigned nearest = 0;
          double d2 = 0;
          tree.knnSearch(q, 1, &nearest, &d2);
          v[size_t(i) + size_t(n) * (size_t(j) + size_t(n) * size_t(k))] = uint16_t(nearest + 1);
        }
  }
  return write_nrrd(argv[4], v, {n, n, n}, "ushort", 1);
}
