#include "voronoimesh/improve/clamp.hpp"

#include "core/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vm {
namespace {

/// The component of (a - from) orthogonal to the line through a and b: the
/// in-plane direction from `from` straight towards that line.
Vec3 towards_line(const Vec3& from, const Vec3& a, const Vec3& b) {
  const Vec3 e = b - a, d = a - from;
  const double e2 = e.squaredNorm();
  return e2 > 0 ? Vec3(d - (d.dot(e) / e2) * e) : Vec3::Zero();
}

} // namespace

double box_step(const Vec3& delta, const Vec3& x, const Box& domain, uint8_t box_faces) {
  double s = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (box_faces >> (2 * a) & 3u) continue; // held on its face: no move along a
    const double gap = delta[a] > 0 ? domain.max[a] - x[a] : x[a] - domain.min[a];
    if (delta[a] != 0 && gap > 0) s = std::min(s, gap / std::abs(delta[a]));
  }
  return s;
}

double clamp_step(const Vec3& delta, const Vec3& v0, const Vec3& v1, const Vec3& v2) {
  // v0's region (paper Fig. 4) is bounded by three planes through the midlines,
  // perpendicular to the triangle: the midline opposite v0 (normal n0, from v0
  // towards edge v1v2), the one opposite v1 (n1, from v1 towards edge v2v0) and
  // the one opposite v2 (n2, from v2 towards edge v0v1). v0 lies strictly inside
  // each; moving by s*delta it reaches a plane where the signed distance
  // d + s*rate crosses zero. (The paper's Algorithm 3 states the same planes; its
  // printed signs for n1 and n2 are those of the opposite normals.)
  const Vec3 m01 = 0.5 * (v0 + v1), m02 = 0.5 * (v0 + v2);
  const struct {
    Vec3 n, point;
  } planes[3] = {{towards_line(v0, v1, v2), m01}, {towards_line(v1, v2, v0), m01}, {towards_line(v2, v0, v1), m02}};
  double s = std::numeric_limits<double>::infinity();
  for (const auto& p : planes) {
    const double d = p.n.dot(v0 - p.point), rate = p.n.dot(delta);
    if (d == 0) return 0; // degenerate triangle: do not move
    if (d * rate < 0) s = std::min(s, -d / rate);
  }
  return s;
}

void clamp_displacements(const InterfaceMesh& mesh, const ClampParams& params, std::vector<Vec3>& delta) {
  const auto& pos = mesh.positions();
  detail::parallel_for_each_index(mesh.num_nodes(), [&](size_t v) {
    Vec3& d = delta[v];
    if (d.isZero(0)) return;
    double scale = std::min(1.0, params.factor * box_step(d, pos[v], mesh.domain(), mesh.box_faces()[v]));
    mesh.for_each_triangle_at(int32_t(v), [&](int32_t a, int32_t b) {
      scale = std::min(scale, params.factor * clamp_step(d, pos[v], pos[size_t(a)], pos[size_t(b)]));
    });
    d *= scale;
  });
}

} // namespace vm
