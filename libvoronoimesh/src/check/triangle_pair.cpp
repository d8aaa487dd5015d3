/// @file check/triangle_pair.cpp
/// The exact decision for one pair of triangles (check/triangle_pair.hpp):
/// orientation predicates with a floating-point filter and an exact
/// expansion-arithmetic fallback, and the closed point-set tests built on them.

#include "check/triangle_pair.hpp"

#include <algorithm>
#include <cmath>

namespace vm::detail {

namespace {

// ---------------------------------------------------------------------------
// Exact arithmetic on expansions (sums of non-overlapping doubles, stored in
// increasing magnitude, zeros left out; the empty expansion is zero), after
// Shewchuk, "Adaptive precision floating-point arithmetic and fast robust
// geometric predicates" (1997). Needs round-to-nearest and no over/underflow.

/// x + y == a + b exactly, x = fl(a + b).
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a;
  const double av = x - bv;
  y = (a - av) + (b - bv);
}

/// x + y == a - b exactly, x = fl(a - b).
inline void two_diff(double a, double b, double& x, double& y) {
  x = a - b;
  const double bv = a - x;
  const double av = x + bv;
  y = (a - av) + (bv - b);
}

/// x + y == a * b exactly, x = fl(a * b).
inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
#if defined(FP_FAST_FMA) || defined(__FMA__)
  y = std::fma(a, b, -x);
#else
  // Dekker's split; without hardware FMA nothing here can be contracted.
  auto split = [](double v, double& hi, double& lo) {
    const double c = 134217729.0 * v; // 2^27 + 1
    hi = c - (c - v);
    lo = v - hi;
  };
  double ahi, alo, bhi, blo;
  split(a, ahi, alo);
  split(b, bhi, blo);
  y = alo * blo - (((x - ahi * bhi) - alo * bhi) - ahi * blo);
#endif
}

/// h = e + f (room for ne + nf components; h is neither e nor f). Returns the
/// length of h. Shewchuk's fast expansion sum: merge the components by
/// magnitude, then carry one running sum through them (exact under IEEE
/// round-to-nearest-even).
int add(const double* e, int ne, const double* f, int nf, double* h) {
  std::merge(e, e + ne, f, f + nf, h, [](double x, double y) { return std::abs(x) < std::abs(y); });
  const int n = ne + nf;
  if (n == 0) return 0;
  int k = 0;
  double q = h[0];
  for (int i = 1; i < n; ++i) { // writes h[k] only behind the read position i
    double sum, err;
    two_sum(q, h[i], sum, err);
    q = sum;
    if (err != 0) h[k++] = err;
  }
  if (q != 0) h[k++] = q;
  return k;
}

/// h = b e (room for 2 n components); h is not e.
int scale(const double* e, int n, double b, double* h) {
  if (n == 0 || b == 0) return 0;
  int k = 0;
  double q, err;
  two_product(e[0], b, q, err);
  if (err != 0) h[k++] = err;
  for (int i = 1; i < n; ++i) {
    double hi, lo, sum;
    two_product(e[i], b, hi, lo);
    two_sum(q, lo, sum, err);
    if (err != 0) h[k++] = err;
    two_sum(hi, sum, q, err);
    if (err != 0) h[k++] = err;
  }
  if (q != 0) h[k++] = q;
  return k;
}

/// h = e f (room for 2 ne nf <= 64 components); h is neither e nor f.
int multiply(const double* e, int ne, const double* f, int nf, double* h) {
  assert(2 * ne * nf <= 64);
  double part[64], sum[2][64];
  int n = 0, cur = 0;
  for (int j = 0; j < nf; ++j) {
    n = add(sum[cur], n, part, scale(e, ne, f[j], part), sum[1 - cur]);
    cur = 1 - cur;
  }
  std::copy(sum[cur], sum[cur] + n, h);
  return n;
}

/// The pair x + y of two_sum, two_diff or two_product as an expansion.
int expansion(double x, double y, double* h) {
  int n = 0;
  if (y != 0) h[n++] = y;
  if (x != 0) h[n++] = x;
  return n;
}

/// a - b as an expansion of at most 2 components.
int difference(double a, double b, double* h) {
  double x, y;
  two_diff(a, b, x, y);
  return expansion(x, y, h);
}

/// a b as an expansion of at most 2 components.
int product(double a, double b, double* h) {
  double x, y;
  two_product(a, b, x, y);
  return expansion(x, y, h);
}

int sign_of(const double* e, int n) { return n == 0 ? 0 : (e[n - 1] > 0 ? 1 : -1); }
int sign_of(double v) { return (v > 0) - (v < 0); }

// ---------------------------------------------------------------------------
// Orientation predicates. The filters' error bounds are Shewchuk's stage-A
// bounds, (3 + 16 eps) eps and (7 + 56 eps) eps, rounded up (which also covers
// any contraction into fused multiply-adds).

constexpr double kEps = 0x1p-53;
constexpr double kOrient2dBound = 4 * kEps;
constexpr double kOrient3dBound = 8 * kEps;

/// A point projected onto a coordinate plane.
struct P2 {
  double x, y;
};

/// p without coordinate k; the cyclic order keeps orient2d's sign equal to the
/// sign of component k of the normal.
inline P2 drop(const Vec3& p, int k) { return {p[(k + 1) % 3], p[(k + 2) % 3]}; }

int orient2d_exact(const P2& a, const P2& b, const P2& c) {
  double acx[2], acy[2], bcx[2], bcy[2], l[8], r[8], det[16];
  const int nacx = difference(a.x, c.x, acx), nacy = difference(a.y, c.y, acy);
  const int nbcx = difference(b.x, c.x, bcx), nbcy = difference(b.y, c.y, bcy);
  const int nl = multiply(acx, nacx, bcy, nbcy, l);
  int nr = multiply(acy, nacy, bcx, nbcx, r);
  for (int i = 0; i < nr; ++i) r[i] = -r[i];
  return sign_of(det, add(l, nl, r, nr, det));
}

/// Sign of (a - c) x (b - c): positive when a, b, c turn counterclockwise.
int orient2d(const P2& a, const P2& b, const P2& c) {
  const double l = (a.x - c.x) * (b.y - c.y), r = (a.y - c.y) * (b.x - c.x);
  const double det = l - r, sum = std::abs(l) + std::abs(r);
  if (std::abs(det) > kOrient2dBound * sum) return sign_of(det);
  if (sum == 0) return 0; // every product has an exactly zero factor
  return orient2d_exact(a, b, c);
}

} // namespace

int orient2d(const Vec3& a, const Vec3& b, const Vec3& c, int k) {
  return orient2d(drop(a, k), drop(b, k), drop(c, k));
}

namespace {

using detail::orient2d; // the overload above, next to the one on P2

/// Sign of ad . (bd x cd), exactly, for vectors of doubles (the common case of
/// the exact stage: differences of nearby coordinates are exact by Sterbenz' lemma).
int det3_sign(const double* ad, const double* bd, const double* cd) {
  double det[2][24];
  int n = 0, cur = 0;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    double l[2], r[2], cross[4], term[8];
    const int nl = product(bd[i], cd[j], l);
    const int nr = product(-bd[j], cd[i], r);
    const int ncross = add(l, nl, r, nr, cross);
    n = add(det[cur], n, term, scale(cross, ncross, ad[k], term), det[1 - cur]);
    cur = 1 - cur;
  }
  return sign_of(det[cur], n);
}

int orient3d_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  double ad[3][2], bd[3][2], cd[3][2];
  int nad[3], nbd[3], ncd[3];
  bool exact = true;
  for (int k = 0; k < 3; ++k) {
    nad[k] = difference(a[k], d[k], ad[k]);
    nbd[k] = difference(b[k], d[k], bd[k]);
    ncd[k] = difference(c[k], d[k], cd[k]);
    exact = exact && nad[k] <= 1 && nbd[k] <= 1 && ncd[k] <= 1;
  }
  if (exact) {
    const Vec3 x = a - d, y = b - d, z = c - d;
    return det3_sign(x.data(), y.data(), z.data());
  }
  double det[2][192];
  int n = 0, cur = 0;
  for (int k = 0; k < 3; ++k) { // det = ad . (bd x cd)
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    double l[8], r[8], cross[16], term[64];
    const int nl = multiply(bd[i], nbd[i], cd[j], ncd[j], l);
    const int nr = multiply(bd[j], nbd[j], cd[i], ncd[i], r);
    for (int q = 0; q < nr; ++q) r[q] = -r[q];
    const int ncross = add(l, nl, r, nr, cross);
    n = add(det[cur], n, term, multiply(cross, ncross, ad[k], nad[k], term), det[1 - cur]);
    cur = 1 - cur;
  }
  return sign_of(det[cur], n);
}

/// Sign of det[a - d; b - d; c - d]: zero exactly when the four points are coplanar.
int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double adx = a.x() - d.x(), ady = a.y() - d.y(), adz = a.z() - d.z();
  const double bdx = b.x() - d.x(), bdy = b.y() - d.y(), bdz = b.z() - d.z();
  const double cdx = c.x() - d.x(), cdy = c.y() - d.y(), cdz = c.z() - d.z();
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(adz) +
                           (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bdz) +
                           (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cdz);
  if (std::abs(det) > kOrient3dBound * permanent) return sign_of(det);
  if (permanent == 0) return 0; // every monomial has an exactly zero factor
  return orient3d_exact(a, b, c, d);
}

// ---------------------------------------------------------------------------
// Closed point-set tests built on the predicates.

bool collinear(const Vec3& a, const Vec3& b, const Vec3& c) {
  return orient2d(a, b, c, 0) == 0 && orient2d(a, b, c, 1) == 0 && orient2d(a, b, c, 2) == 0;
}

} // namespace

int8_t projection_axis(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 normal = (b - a).cross(c - a).cwiseAbs();
  std::array<int, 3> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int i, int j) { return normal[i] > normal[j]; });
  for (int k : order)
    if (orient2d(a, b, c, k) != 0) return int8_t(k);
  return -1;
}

namespace {

/// p within the bounding box of a and b (for collinear points: on the segment).
bool in_box(const P2& p, const P2& a, const P2& b) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

bool in_box(const Vec3& p, const Vec3& a, const Vec3& b) {
  return (a.cwiseMin(b).array() <= p.array()).all() && (p.array() <= a.cwiseMax(b).array()).all();
}

/// p on the closed segment [a, b].
bool on_segment(const Vec3& p, const Vec3& a, const Vec3& b) { return collinear(a, b, p) && in_box(p, a, b); }

/// m strictly between a and b on the segment [a, b].
bool strictly_between(const Vec3& a, const Vec3& m, const Vec3& b) { return m != a && m != b && on_segment(m, a, b); }

/// Closed segments [p, q] and [r, s] of the plane meet (either may be a point).
bool segments_meet(const P2& p, const P2& q, const P2& r, const P2& s) {
  const int o1 = orient2d(p, q, r), o2 = orient2d(p, q, s);
  const int o3 = orient2d(r, s, p), o4 = orient2d(r, s, q);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && in_box(r, p, q)) || (o2 == 0 && in_box(s, p, q)) || (o3 == 0 && in_box(p, r, s)) ||
         (o4 == 0 && in_box(q, r, s));
}

/// p in the closed triangle abc of the plane, which turns with sign `turn` != 0.
bool in_triangle(const P2& p, const P2& a, const P2& b, const P2& c, int turn) {
  return orient2d(a, b, p) != -turn && orient2d(b, c, p) != -turn && orient2d(c, a, p) != -turn;
}

/// p - v lies in the closed sector at v from y1 - v to y2 - v, which turns with
/// sign `turn` != 0 (so spans less than a half-turn).
bool in_sector(const P2& v, const P2& y1, const P2& y2, int turn, const P2& p) {
  return orient2d(v, y1, p) != -turn && orient2d(v, p, y2) != -turn;
}

/// Closed non-degenerate triangles of one plane meet: no edge line of either
/// has the other triangle strictly outside. (Disjoint convex polygons always
/// have such a separating edge line: the edge of their Minkowski difference
/// nearest the origin is parallel to an edge of one of them.)
bool triangles_meet(const std::array<P2, 3>& a, const std::array<P2, 3>& b) {
  auto separates = [](const std::array<P2, 3>& x, const std::array<P2, 3>& y) {
    const int turn = orient2d(x[0], x[1], x[2]);
    for (size_t i = 0; i < 3; ++i) {
      const P2 &e0 = x[i], &e1 = x[(i + 1) % 3];
      if (orient2d(e0, e1, y[0]) == -turn && orient2d(e0, e1, y[1]) == -turn && orient2d(e0, e1, y[2]) == -turn)
        return true;
    }
    return false;
  };
  return !separates(a, b) && !separates(b, a);
}

/// Closed segment [p, q] and closed non-degenerate triangle abc of one plane meet.
bool segment_meets_triangle(const P2& p, const P2& q, const P2& a, const P2& b, const P2& c) {
  const int turn = orient2d(a, b, c);
  return in_triangle(p, a, b, c, turn) || in_triangle(q, a, b, c, turn) || segments_meet(p, q, a, b) ||
         segments_meet(p, q, b, c) || segments_meet(p, q, c, a);
}

/// Closed segments [p, q] and [r, s] of space meet (either may be a point).
bool segments_meet(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
  if (orient3d(p, q, r, s) != 0) return false;
  // Project along an axis that keeps the common plane (or line) one to one.
  int axis = -1;
  const std::array<std::array<const Vec3*, 3>, 4> triples{{{&p, &q, &r}, {&p, &q, &s}, {&p, &r, &s}, {&q, &r, &s}}};
  for (const auto& t : triples) {
    axis = projection_axis(*t[0], *t[1], *t[2]);
    if (axis >= 0) break;
  }
  if (axis < 0) { // all on one line: keep a coordinate along which it moves
    const Vec3* other = q != p ? &q : r != p ? &r : s != p ? &s : nullptr;
    if (!other) return true; // four times the same point
    int moving = 0;
    while ((*other)[moving] == p[moving]) ++moving;
    axis = (moving + 2) % 3;
  }
  return segments_meet(drop(p, axis), drop(q, axis), drop(r, axis), drop(s, axis));
}

/// Closed segment [p, q] and closed triangle abc meet. `axis` is
/// projection_axis(a, b, c); when it is >= 0, op and oq are orient3d(a, b, c, p)
/// and orient3d(a, b, c, q).
bool segment_meets_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, int axis,
                            int op, int oq) {
  if (axis < 0) // the triangle is the union of its three edges
    return segments_meet(p, q, a, b) || segments_meet(p, q, b, c) || segments_meet(p, q, c, a);
  if (op * oq > 0) return false;
  if (op == 0 && oq == 0)
    return segment_meets_triangle(drop(p, axis), drop(q, axis), drop(a, axis), drop(b, axis), drop(c, axis));
  if (op == 0 || oq == 0) {
    const int turn = orient2d(a, b, c, axis);
    return in_triangle(drop(op == 0 ? p : q, axis), drop(a, axis), drop(b, axis), drop(c, axis), turn);
  }
  // p and q strictly on either side: the line pq passes the closed triangle
  // when it turns the same way around all three edges (zeros allowed).
  const int s1 = orient3d(p, q, a, b), s2 = orient3d(p, q, b, c), s3 = orient3d(p, q, c, a);
  return !((s1 > 0 || s2 > 0 || s3 > 0) && (s1 < 0 || s2 < 0 || s3 < 0));
}

/// p != v and y on the same ray from v (for any v, y, p).
bool same_ray(const Vec3& v, const Vec3& y, const Vec3& p) {
  if (!collinear(v, y, p)) return false;
  for (int k = 0; k < 3; ++k)
    if ((y[k] > v[k]) != (p[k] > v[k]) || (y[k] < v[k]) != (p[k] < v[k])) return false;
  return p != v;
}

/// The direction p - v (p != v) lies in the cone at v spanned by y1 - v and
/// y2 - v: the triangle v y1 y2 (`axis` its projection_axis) holds
/// v + e (p - v) for small e > 0.
bool in_cone(const Vec3& v, const Vec3& y1, const Vec3& y2, int axis, const Vec3& p) {
  if (axis < 0) return (y1 != v && same_ray(v, y1, p)) || (y2 != v && same_ray(v, y2, p));
  if (orient3d(v, y1, y2, p) != 0) return false;
  const P2 pv = drop(v, axis), p1 = drop(y1, axis), p2 = drop(y2, axis);
  return in_sector(pv, p1, p2, orient2d(pv, p1, p2), drop(p, axis));
}

/// Side of q against the plane of abc; 0 as well when `axis` < 0 marks abc as collinear.
int side(const Vec3& a, const Vec3& b, const Vec3& c, int axis, const Vec3& q) {
  return axis < 0 ? 0 : orient3d(a, b, c, q);
}

bool same_strict_sign(int o1, int o2) { return o1 * o2 > 0; }

/// Decides single pairs of triangles.
class PairTest {
public:
  explicit PairTest(std::span<const Vec3> points) : pts_(points) {}

  /// Triangles A and B (with their projection axes) intersect improperly.
  bool operator()(const Triangle& A, const Triangle& B, int ax, int bx) const {
    int32_t shared[3];
    int k = 0;
    for (int32_t id : A)
      if (std::find(B.begin(), B.end(), id) != B.end() && std::find(shared, shared + k, id) == shared + k)
        shared[k++] = id;
    switch (k) {
    case 0:
      return disjoint_ids(A, B, ax, bx);
    case 1: {
      const auto a = others(A, shared[0]), b = others(B, shared[0]);
      return shared_vertex(p(shared[0]), p(a[0]), p(a[1]), ax, p(b[0]), p(b[1]), bx);
    }
    case 2:
      return shared_edge(A, B, shared[0], shared[1], ax, bx);
    default:
      return true; // the same three nodes
    }
  }

private:
  const Vec3& p(int32_t id) const { return pts_[size_t(id)]; }

  /// The two corners of `tri` other than one occurrence of node v.
  static std::array<int32_t, 2> others(const Triangle& tri, int32_t v) {
    const size_t i = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
    return {tri[(i + 1) % 3], tri[(i + 2) % 3]};
  }

  /// No common node: the closed triangles meet at all. Two closed triangles
  /// meet exactly when an edge of one meets the other (their intersection is
  /// convex, and its extreme points lie on edges).
  bool disjoint_ids(const Triangle& A, const Triangle& B, int ax, int bx) const {
    const std::array<const Vec3*, 3> a{&p(A[0]), &p(A[1]), &p(A[2])}, b{&p(B[0]), &p(B[1]), &p(B[2])};
    std::array<int, 3> oa, ob; // a against the plane of b, and b against that of a
    for (size_t i = 0; i < 3; ++i) oa[i] = side(*b[0], *b[1], *b[2], bx, *a[i]);
    if (same_strict_sign(oa[0], oa[1]) && same_strict_sign(oa[1], oa[2])) return false;
    for (size_t i = 0; i < 3; ++i) ob[i] = side(*a[0], *a[1], *a[2], ax, *b[i]);
    if (same_strict_sign(ob[0], ob[1]) && same_strict_sign(ob[1], ob[2])) return false;
    if (ax >= 0 && bx >= 0 && oa == std::array<int, 3>{0, 0, 0}) // one plane
      return triangles_meet({drop(*a[0], ax), drop(*a[1], ax), drop(*a[2], ax)},
                            {drop(*b[0], ax), drop(*b[1], ax), drop(*b[2], ax)});
    for (size_t i = 0; i < 3; ++i) {
      const size_t j = (i + 1) % 3;
      if (segment_meets_triangle(*a[i], *a[j], *b[0], *b[1], *b[2], bx, oa[i], oa[j])) return true;
      if (segment_meets_triangle(*b[i], *b[j], *a[0], *a[1], *a[2], ax, ob[i], ob[j])) return true;
    }
    return false;
  }

  /// Triangles v a1 a2 and v b1 b2 sharing only v: a common point other than v.
  /// If there is one, the (convex) intersection holds a segment from v, whose
  /// far end lies on an edge of one triangle: an edge through v then points into
  /// the other triangle's cone at v, or the opposite edge meets the other triangle.
  static bool shared_vertex(const Vec3& v, const Vec3& a1, const Vec3& a2, int ax, const Vec3& b1, const Vec3& b2,
                            int bx) {
    // Seen along a's projection axis (one to one on a), a common point x != v
    // would show as a common point x' != v' of both shadows, so a line through
    // v' along one of the four edges at v with one shadow strictly on each side
    // rules it out. Exact 2D tests, cheap where the 3D ones below are not (fans
    // in one plane).
    if (ax >= 0) {
      const struct {
        const Vec3 &edge, &own, &x, &y;
      } lines[4] = {{a1, a2, b1, b2}, {a2, a1, b1, b2}, {b1, b2, a1, a2}, {b2, b1, a1, a2}};
      for (const auto& l : lines) {
        const int own = orient2d(v, l.edge, l.own, ax);
        if (own != 0 && orient2d(v, l.edge, l.x, ax) == -own && orient2d(v, l.edge, l.y, ax) == -own) return false;
      }
    }
    // Strictly on one side of the other's plane but for v: nothing else in common.
    const int oa1 = side(v, b1, b2, bx, a1), oa2 = side(v, b1, b2, bx, a2);
    if (same_strict_sign(oa1, oa2)) return false;
    const int ob1 = side(v, a1, a2, ax, b1), ob2 = side(v, a1, a2, ax, b2);
    if (same_strict_sign(ob1, ob2)) return false;
    if (ax >= 0 && bx >= 0 && oa1 == 0 && oa2 == 0) {
      // One plane: the sectors at v overlap when one holds a side of the other.
      const P2 pv = drop(v, ax), pa1 = drop(a1, ax), pa2 = drop(a2, ax), pb1 = drop(b1, ax), pb2 = drop(b2, ax);
      const int ta = orient2d(pv, pa1, pa2), tb = orient2d(pv, pb1, pb2);
      return in_sector(pv, pb1, pb2, tb, pa1) || in_sector(pv, pb1, pb2, tb, pa2) ||
             in_sector(pv, pa1, pa2, ta, pb1) || in_sector(pv, pa1, pa2, ta, pb2);
    }
    // (A non-degenerate triangle's opposite edge never holds v.)
    if ((ax >= 0 || !on_segment(v, a1, a2)) && segment_meets_triangle(a1, a2, v, b1, b2, bx, oa1, oa2)) return true;
    if ((bx >= 0 || !on_segment(v, b1, b2)) && segment_meets_triangle(b1, b2, v, a1, a2, ax, ob1, ob2)) return true;
    for (const Vec3* x : {&a1, &a2})
      if (*x != v && in_cone(v, b1, b2, bx, *x)) return true;
    for (const Vec3* x : {&b1, &b2})
      if (*x != v && in_cone(v, a1, a2, ax, *x)) return true;
    return false;
  }

  /// Triangles sharing nodes u and w: a common point off the segment uw.
  bool shared_edge(const Triangle& A, const Triangle& B, int32_t u, int32_t w, int ax,
                   int bx) const {
    const auto au = others(A, u), bu = others(B, u);
    if (p(u) == p(w)) // the hull of the shared nodes is the point u
      return shared_vertex(p(u), p(au[0]), p(au[1]), ax, p(bu[0]), p(bu[1]), bx);
    const Vec3& a = p(au[0] == w ? au[1] : au[0]);
    const Vec3& b = p(bu[0] == w ? bu[1] : bu[0]);
    // Folded onto each other: one plane, same side of uw. The 2D test first: on
    // flat surfaces the 3D one is near zero and needs exact arithmetic.
    if (ax >= 0 && bx >= 0)
      return orient2d(p(u), p(w), a, ax) == orient2d(p(u), p(w), b, ax) && orient3d(p(u), p(w), a, b) == 0;
    // A collinear triangle reaches off uw only along its line, beyond u or w.
    return (strictly_between(p(u), p(w), a) && strictly_between(p(u), p(w), b)) ||
           (strictly_between(p(w), p(u), a) && strictly_between(p(w), p(u), b));
  }

  std::span<const Vec3> pts_;
};


} // namespace

bool intersect_improperly(std::span<const Vec3> points, const Triangle& a, const Triangle& b, int8_t a_axis,
                          int8_t b_axis) {
  return PairTest(points)(a, b, a_axis, b_axis);
}

bool intersect_improperly(std::span<const Vec3> points, const Triangle& a, const Triangle& b) {
  auto axis = [&](const Triangle& t) {
    return projection_axis(points[size_t(t[0])], points[size_t(t[1])], points[size_t(t[2])]);
  };
  return intersect_improperly(points, a, b, axis(a), axis(b));
}

} // namespace vm::detail
