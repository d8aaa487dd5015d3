#pragma once
// A synthetic CT segmentation for the label-volume benchmark: the shapes a real
// abdominal/thoracic scan gives (a body of soft tissue, bone inside it, one
// organ) with smooth organic wobbles and thin parts, at the size users mesh
// (512 x 512 x 96 voxels, 25.2M). Every shape is an implicit function of the
// voxel position in voxel units, so slices can be made in parallel.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

namespace ct {

constexpr int nx = 512, ny = 512, nz = 96;
constexpr uint8_t air = 0, tissue = 1, bone = 2, organ = 3;

/// A smooth random wobble: a few low-frequency waves in angle and height.
struct Wobble {
  std::array<double, 4> amp{}, freq{}, phase{}, zfreq{};
  Wobble(std::mt19937_64& rng, double size) {
    std::uniform_real_distribution<double> u(0, 1);
    for (size_t w = 0; w < amp.size(); ++w) {
      amp[w] = size * (0.4 + 0.6 * u(rng)) / double(w + 1);
      freq[w] = double(w + 2);
      phase[w] = 2 * std::numbers::pi * u(rng);
      zfreq[w] = 2 * std::numbers::pi * (0.5 + u(rng)) / nz;
    }
  }
  double operator()(double theta, double z) const {
    double s = 0;
    for (size_t w = 0; w < amp.size(); ++w) s += amp[w] * std::sin(freq[w] * theta + zfreq[w] * z + phase[w]);
    return s;
  }
};

/// The labels, x fastest, y from anterior (0) to posterior, z along the body.
inline std::vector<uint8_t> volume(uint64_t seed) {
  std::mt19937_64 rng(seed);
  const double cx = nx / 2.0, cy = ny / 2.0;
  const double body_a = 215, body_b = 150; // semi-axes of the body's cross-section
  const Wobble body_w(rng, 8), organ_w(rng, 10), spine_w(rng, 2);
  std::uniform_real_distribution<double> u(0, 1);
  const double rib_pitch = 30, rib_start = 8 * u(rng), rib_slope = 10 + 6 * u(rng);
  const double disc_start = 10 * u(rng);
  std::vector<uint8_t> v(size_t(nx) * ny * nz, air);
  auto at = [&](int i, int j, int k) -> uint8_t& { return v[size_t(i) + size_t(nx) * (size_t(j) + size_t(ny) * size_t(k))]; };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double x = i - cx, y = j - cy, z = k;
        const double theta = std::atan2(y / body_b, x / body_a);
        // Body: an ellipse flattened at the back, its outline wobbling.
        const double rb = std::hypot(x / body_a, (y > 0 ? y * 1.15 : y) / body_b);
        const double body_edge = 1 + body_w(theta, z) / body_a;
        if (rb > body_edge) continue;
        uint8_t label = tissue;
        // Organ: a liver-like blob on one side with a thin lobe reaching across.
        const double ox = x + 70, oy = y + 10, oz = z - 50;
        const double ro = std::hypot(ox / 95, oy / 85, oz / 70) - organ_w(std::atan2(oy, ox), z) / 90;
        const double lobe = std::hypot((x - 10) / 75, (y + 55) / 9, (z - 45) / 30);
        if ((ro < 1 || lobe < 1) && rb < 0.8 * body_edge) label = organ;
        // Spine: vertebral bodies with discs between them, and a thin spinous process.
        const double sx = x + spine_w(0.3 * z, z), sy = y - 95;
        const bool disc = std::fmod(z + disc_start, 28.0) < 4;
        if (!disc && std::hypot(sx / 24, sy / 20) < 1) label = bone;
        if (std::abs(sx) < 3 && sy > 18 && sy < 48) label = bone;
        // Ribs: tubes of radius 3 following the body wall, sloping down towards the front.
        const double wall = 0.88 * body_edge, ang = std::abs(std::atan2(x, -y)); // 0 at the front, pi at the back
        if (ang > 0.35 && ang < 2.75) {
          const double drop = rib_slope * (std::numbers::pi - ang);
          const double zr = std::fmod(z + drop + rib_start, rib_pitch) - rib_pitch / 2;
          const double dr = (rb - wall) * std::hypot(x, y) / std::max(rb, 1e-9);
          if (std::hypot(dr, zr) < 3) label = bone;
        }
        // Sternum: a flat bar at the front.
        if (std::abs(x) < 14 && std::abs(rb - 0.9 * body_edge) * body_b < 5) label = bone;
        at(i, j, k) = label;
      }
  return v;
}

} // namespace ct
