#include "triangle_intersections.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace flagsim::testing {
namespace {

// A corner this close to the other triangle's plane, relative to the
// triangles' size, is on it (Moeller's epsilon, scaled).
constexpr double kOnPlane = 1e-12;

// The interval [lo, hi] that the line of the two planes cuts from a triangle
// with corners projected to v and signed distances d to the other plane.
// False when the triangle lies in the plane.
bool interval(const std::array<double, 3>& v, const std::array<double, 3>& d, double& lo,
              double& hi) {
  const auto cut = [&](int a, int b, int c) {
    const double t1 = v[a] + (v[b] - v[a]) * d[a] / (d[a] - d[b]);
    const double t2 = v[a] + (v[c] - v[a]) * d[a] / (d[a] - d[c]);
    lo = std::min(t1, t2);
    hi = std::max(t1, t2);
  };
  // The corner alone on its side of the plane, in Moeller's order of cases
  // (-1: every corner in the plane).
  const int alone = d[0] * d[1] > 0.0                  ? 2
                    : d[0] * d[2] > 0.0                ? 1
                    : d[1] * d[2] > 0.0 || d[0] != 0.0 ? 0
                    : d[1] != 0.0                      ? 1
                    : d[2] != 0.0                      ? 2
                                                       : -1;
  if (alone < 0) return false;
  const int others[3][2] = {{1, 2}, {0, 2}, {0, 1}};
  cut(alone, others[alone][0], others[alone][1]);
  return true;
}

// 2D: whether segments ab and cd cross or touch.
bool segments_cross(const std::array<double, 2>& a, const std::array<double, 2>& b,
                    const std::array<double, 2>& c, const std::array<double, 2>& d) {
  const auto orient = [](const std::array<double, 2>& p, const std::array<double, 2>& q,
                         const std::array<double, 2>& r) {
    return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
  };
  const auto on = [](const std::array<double, 2>& p, const std::array<double, 2>& q,
                     const std::array<double, 2>& r) {  // r within pq's box
    return std::min(p[0], q[0]) <= r[0] && r[0] <= std::max(p[0], q[0]) &&
           std::min(p[1], q[1]) <= r[1] && r[1] <= std::max(p[1], q[1]);
  };
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
               o4 = orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
    return true;
  return (o1 == 0 && on(a, b, c)) || (o2 == 0 && on(a, b, d)) || (o3 == 0 && on(c, d, a)) ||
         (o4 == 0 && on(c, d, b));
}

// 2D: whether p is inside or on triangle abc.
bool inside(const std::array<double, 2>& p, const std::array<std::array<double, 2>, 3>& t) {
  double sign = 0.0;
  for (int i = 0; i < 3; ++i) {
    const auto& a = t[std::size_t(i)];
    const auto& b = t[std::size_t((i + 1) % 3)];
    const double o = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
    if (o == 0.0) continue;
    if (sign == 0.0) sign = o;
    if (sign * o < 0.0) return false;
  }
  return true;
}

bool coplanar_intersect(const Vec3& normal, const std::array<Vec3, 3>& p,
                        const std::array<Vec3, 3>& q) {
  // Project onto the plane of the two largest normal components.
  const Vec3 n = normal.cwiseAbs();
  const int drop = n.x() >= n.y() && n.x() >= n.z() ? 0 : (n.y() >= n.z() ? 1 : 2);
  const int u = drop == 0 ? 1 : 0, v = drop == 2 ? 1 : 2;
  std::array<std::array<double, 2>, 3> a, b;
  for (std::size_t i = 0; i < 3; ++i) {
    a[i] = {p[i][u], p[i][v]};
    b[i] = {q[i][u], q[i][v]};
  }
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      if (segments_cross(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3])) return true;
  return inside(a[0], b) || inside(b[0], a);
}

}  // namespace

bool triangles_intersect(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& q0,
                         const Vec3& q1, const Vec3& q2) {
  const std::array<Vec3, 3> p = {p0, p1, p2}, q = {q0, q1, q2};
  double size = 0.0;
  const std::array<Vec3, 5> spans = {p1 - p0, p2 - p0, q1 - q0, q2 - q0, q0 - p0};
  for (const Vec3& x : spans) size = std::max(size, x.cwiseAbs().maxCoeff());
  // The corners of p against q's plane, and of q against p's.
  const Vec3 nq = (q1 - q0).cross(q2 - q0), np = (p1 - p0).cross(p2 - p0);
  std::array<double, 3> dp, dq;
  for (std::size_t i = 0; i < 3; ++i) {
    dp[i] = nq.dot(p[i] - q0);
    if (std::abs(dp[i]) <= kOnPlane * nq.norm() * size) dp[i] = 0.0;
    dq[i] = np.dot(q[i] - p0);
    if (std::abs(dq[i]) <= kOnPlane * np.norm() * size) dq[i] = 0.0;
  }
  if (dp[0] * dp[1] > 0.0 && dp[0] * dp[2] > 0.0) return false;
  if (dq[0] * dq[1] > 0.0 && dq[0] * dq[2] > 0.0) return false;
  // The line where the planes meet, direction D; compare along its largest axis.
  const Vec3 D = np.cross(nq);
  const Vec3 a = D.cwiseAbs();
  const int axis = a.x() >= a.y() && a.x() >= a.z() ? 0 : (a.y() >= a.z() ? 1 : 2);
  const std::array<double, 3> vp = {p0[axis], p1[axis], p2[axis]},
                              vq = {q0[axis], q1[axis], q2[axis]};
  double lo_p = 0.0, hi_p = 0.0, lo_q = 0.0, hi_q = 0.0;
  if (!interval(vp, dp, lo_p, hi_p) || !interval(vq, dq, lo_q, hi_q))
    return coplanar_intersect(np.squaredNorm() > 0.0 ? np : nq, p, q);
  return !(hi_p < lo_q || hi_q < lo_p);
}

std::vector<TrianglePair> self_intersections(const Lattice& lattice, std::span<const Vec3> x_m,
                                             std::size_t limit) {
  const int J = lattice.rows, K = lattice.cols;
  const std::size_t cells = std::size_t(J - 1) * std::size_t(K - 1);
  const auto corners = [&](std::size_t t) {
    const std::size_t cell = t / 2;
    const int j = int(cell / std::size_t(K - 1)), k = int(cell % std::size_t(K - 1));
    const auto at = [&](int jj, int kk) { return lattice.index(jj, kk); };
    return t % 2 == 0 ? std::array<std::size_t, 3>{at(j, k), at(j, k + 1), at(j + 1, k + 1)}
                      : std::array<std::size_t, 3>{at(j, k), at(j + 1, k + 1), at(j + 1, k)};
  };
  // Grid cells the size of the longest edge.
  double h = 0.0;
  for (std::size_t t = 0; t < 2 * cells; ++t) {
    const auto c = corners(t);
    for (int i = 0; i < 3; ++i)
      h = std::max(h, (x_m[c[std::size_t(i)]] - x_m[c[std::size_t((i + 1) % 3)]]).norm());
  }
  std::vector<TrianglePair> found;
  if (!(h > 0.0) || !std::isfinite(h)) return found;
  const auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    return (i * 73856093) ^ (j * 19349663) ^ (k * 83492791);
  };
  struct Box {
    std::array<std::int64_t, 3> lo, hi;
  };
  std::vector<Box> boxes(2 * cells);
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid;
  for (std::size_t t = 0; t < 2 * cells; ++t) {
    const auto c = corners(t);
    Vec3 lo = x_m[c[0]].cwiseMin(x_m[c[1]]).cwiseMin(x_m[c[2]]);
    Vec3 hi = x_m[c[0]].cwiseMax(x_m[c[1]]).cwiseMax(x_m[c[2]]);
    Box& b = boxes[t];
    for (int d = 0; d < 3; ++d) {
      b.lo[std::size_t(d)] = std::int64_t(std::floor(lo[d] / h));
      b.hi[std::size_t(d)] = std::int64_t(std::floor(hi[d] / h));
    }
    for (std::int64_t i = b.lo[0]; i <= b.hi[0]; ++i)
      for (std::int64_t j = b.lo[1]; j <= b.hi[1]; ++j)
        for (std::int64_t k = b.lo[2]; k <= b.hi[2]; ++k)
          grid[key(i, j, k)].push_back(std::uint32_t(t));
  }
  for (std::size_t t = 0; t < 2 * cells && found.size() < limit; ++t) {
    const Box& b = boxes[t];
    const auto ct = corners(t);
    for (std::int64_t i = b.lo[0]; i <= b.hi[0]; ++i)
      for (std::int64_t j = b.lo[1]; j <= b.hi[1]; ++j)
        for (std::int64_t k = b.lo[2]; k <= b.hi[2]; ++k) {
          const auto it = grid.find(key(i, j, k));
          if (it == grid.end()) continue;
          for (const std::uint32_t u : it->second) {
            if (u <= t) continue;
            const Box& o = boxes[u];
            // Each pair once: in the first grid cell of its boxes' overlap
            // (and the hash's collisions: only where that cell is this one).
            const std::array<std::int64_t, 3> first = {
                std::max(b.lo[0], o.lo[0]), std::max(b.lo[1], o.lo[1]), std::max(b.lo[2], o.lo[2])};
            if (first[0] != i || first[1] != j || first[2] != k) continue;
            if (std::max(b.lo[0], o.lo[0]) > std::min(b.hi[0], o.hi[0]) ||
                std::max(b.lo[1], o.lo[1]) > std::min(b.hi[1], o.hi[1]) ||
                std::max(b.lo[2], o.lo[2]) > std::min(b.hi[2], o.hi[2]))
              continue;
            const auto cu = corners(u);
            bool shared = false;
            for (std::size_t a = 0; a < 3; ++a)
              for (std::size_t c = 0; c < 3; ++c) shared = shared || ct[a] == cu[c];
            if (shared) continue;
            if (triangles_intersect(x_m[ct[0]], x_m[ct[1]], x_m[ct[2]], x_m[cu[0]], x_m[cu[1]],
                                    x_m[cu[2]])) {
              found.push_back({t, u});
              if (found.size() >= limit) return found;
            }
          }
        }
  }
  return found;
}

}  // namespace flagsim::testing
