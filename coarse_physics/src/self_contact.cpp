#include "flagsim/coarse_physics/self_contact.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

namespace flagsim::physics {
namespace {

// The point of triangle (a, b, c) closest to p, as barycentric weights
// (Ericson, Real-Time Collision Detection, 5.1.5); `inside` when it lies
// inside the triangle (not on an edge or a corner).
struct Closest {
  double w[3];
  bool inside;
};

Closest closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {{1.0, 0.0, 0.0}, false};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {{0.0, 1.0, 0.0}, false};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return {{1.0 - v, v, 0.0}, false};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {{0.0, 0.0, 1.0}, false};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return {{1.0 - w, 0.0, w}, false};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {{0.0, 1.0 - w, w}, false};
  }
  const double denom = va + vb + vc;
  if (!(denom > 0.0)) return {{1.0, 0.0, 0.0}, false};  // a degenerate triangle: its corner
  const double v = vb / denom, w = vc / denom;
  return {{1.0 - v - w, v, w}, true};
}

// Parameters (s, u) of the closest points p0 + s (p1 - p0) and q0 + u (q1 -
// q0) of two segments (Ericson 5.1.9), each clamped to [0, 1].
std::array<double, 2> closest_on_segments(const Vec3& p0, const Vec3& p1, const Vec3& q0,
                                          const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  if (a <= 0.0 && e <= 0.0) return {0.0, 0.0};
  if (a <= 0.0) return {0.0, std::clamp(f / e, 0.0, 1.0)};
  const double c = d1.dot(r);
  if (e <= 0.0) return {std::clamp(-c / a, 0.0, 1.0), 0.0};
  const double b = d1.dot(d2), denom = a * e - b * b;
  double s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double u = (b * s + f) / e;
  if (u < 0.0) {
    u = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (u > 1.0) {
    u = 1.0;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return {s, u};
}

// 2D distance between segments ab and cd (rest coordinates), m.
double rest_distance(const std::array<double, 2>& a, const std::array<double, 2>& b,
                     const std::array<double, 2>& c, const std::array<double, 2>& d) {
  const Vec3 p0(a[0], a[1], 0.0), p1(b[0], b[1], 0.0), q0(c[0], c[1], 0.0), q1(d[0], d[1], 0.0);
  const auto [s, u] = closest_on_segments(p0, p1, q0, q1);
  return ((p0 + s * (p1 - p0)) - (q0 + u * (q1 - q0))).norm();
}

// How far outside a triangle (in barycentric weight) a node still counts as
// over it: a node above a shared corner or edge is over every triangle there.
constexpr double kEdgeSlack = 0.02;
// Edge-edge pairs whose closest points are this close to an end are the
// node-triangle pairs' (the end is a node of the triangles around the edge).
constexpr double kEdgeEnd = 1e-6;
// Pairs the first pass finds farther apart than (1 + this) thicknesses are
// not looked at again in that projection: the later passes move nodes by
// what is left of the gaps, a small part of a thickness.
constexpr double kNearPairs = 0.5;

Vec3 unit_or_zero(const Vec3& v) {
  const double n = v.norm();
  return n > 0.0 ? Vec3(v / n) : Vec3::Zero();
}

// Whether one cone about a common axis of half-angle kFlatAngle holds two
// cones (unit axis, half-angle rad; `same`: one cone): half-angle (theta +
// alpha_a + alpha_b) / 2. A zero axis (normals that cancel) is never flat.
bool flat_together(const Vec3& axis_a, double spread_a, const Vec3& axis_b, double spread_b,
                   bool same) {
  if (axis_a.squaredNorm() == 0.0 || axis_b.squaredNorm() == 0.0) return false;
  const double between = std::acos(std::clamp(axis_a.dot(axis_b), -1.0, 1.0));
  const double half_angle = same ? spread_a : 0.5 * (between + spread_a + spread_b);
  return half_angle <= kFlatAngle;
}

// Appends to `pairs` every pair {a, b}, a <= b (each box with itself too),
// of the boxes [low, high] that overlap, by sweep and prune along `axis`: the
// boxes sorted by their low end (`order`, scratch), a box meets only those
// that start before it ends. Unordered.
void overlapping_pairs(std::span<const Vec3> low, std::span<const Vec3> high, int axis,
                       std::vector<std::uint32_t>& order,
                       std::vector<std::array<std::uint32_t, 2>>& pairs) {
  const std::size_t boxes = low.size();
  order.resize(boxes);
  for (std::size_t i = 0; i < boxes; ++i) order[i] = std::uint32_t(i);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return low[a][axis] < low[b][axis] || (low[a][axis] == low[b][axis] && a < b);
  });
  for (std::size_t p = 0; p < boxes; ++p) {
    const std::uint32_t a = order[p];
    pairs.push_back({a, a});
    for (std::size_t q = p + 1; q < boxes && !(low[order[q]][axis] > high[a][axis]); ++q) {
      const std::uint32_t b = order[q];
      if ((low[a].array() > high[b].array()).any() || (low[b].array() > high[a].array()).any())
        continue;
      pairs.push_back({std::min(a, b), std::max(a, b)});
    }
  }
}

}  // namespace

SelfContact::SelfContact(const Lattice& lattice, double thickness_m)
    : lattice_(lattice), thickness_m_(thickness_m) {
  assert(thickness_m > 0.0 && lattice.rows >= 2 && lattice.cols >= 2);
  const int J = lattice.rows, K = lattice.cols;
  margin_m_ =
      std::max(2.0 * thickness_m, 0.25 * std::min(lattice.spacing_x_m, lattice.spacing_y_m));
  block_cells_ = std::clamp(std::min(J - 1, K - 1) / 4, 1, 4);
  block_rows_ = (J - 2) / block_cells_ + 1;
  block_cols_ = (K - 2) / block_cells_ + 1;
  neighbour_cells_x_ = kNeighbourReach * thickness_m / lattice.spacing_x_m;
  neighbour_cells_y_ = kNeighbourReach * thickness_m / lattice.spacing_y_m;
  const std::size_t blocks = std::size_t(block_rows_) * std::size_t(block_cols_);
  low_.resize(blocks);
  high_.resize(blocks);
  axis_.resize(blocks);
  spread_.resize(blocks);
  normal_sum_.resize(blocks);
  super_rows_ = (block_rows_ - 1) / kSuperBlock + 1;
  super_cols_ = (block_cols_ - 1) / kSuperBlock + 1;
  const std::size_t supers = std::size_t(super_rows_) * std::size_t(super_cols_);
  super_low_.resize(supers);
  super_high_.resize(supers);
  super_axis_.resize(supers);
  super_spread_.resize(supers);
  normals_.resize(std::size_t(J - 1) * std::size_t(K - 1) * 2);
  // Every edge once, owned by a cell: its top, left and diagonal, the right
  // edges of the last column and the bottom edges of the last row.
  std::vector<std::vector<std::uint32_t>> owned(blocks);
  const auto at = [&](int j, int k) { return std::uint32_t(lattice.index(j, k)); };
  for (int j = 0; j + 1 < J; ++j)
    for (int k = 0; k + 1 < K; ++k) {
      const std::size_t block =
          std::size_t(j / block_cells_) * std::size_t(block_cols_) + std::size_t(k / block_cells_);
      const auto add = [&](std::uint32_t a, std::uint32_t b) {
        owned[block].push_back(std::uint32_t(edges_.size()));
        edges_.push_back({a, b});
      };
      add(at(j, k), at(j, k + 1));
      add(at(j, k), at(j + 1, k));
      add(at(j, k), at(j + 1, k + 1));
      if (k + 2 == K) add(at(j, k + 1), at(j + 1, k + 1));
      if (j + 2 == J) add(at(j + 1, k), at(j + 1, k + 1));
    }
  block_edge_start_.push_back(0);
  for (const auto& list : owned) {
    block_edges_.insert(block_edges_.end(), list.begin(), list.end());
    block_edge_start_.push_back(std::uint32_t(block_edges_.size()));
  }
}

std::array<std::uint32_t, 3> SelfContact::corners(std::uint32_t cell, int half) const {
  const int cells_across = lattice_.cols - 1;
  const int j = int(cell) / cells_across, k = int(cell) % cells_across;
  const auto at = [&](int jj, int kk) { return std::uint32_t(lattice_.index(jj, kk)); };
  if (half == 0) return {at(j, k), at(j, k + 1), at(j + 1, k + 1)};
  return {at(j, k), at(j + 1, k + 1), at(j + 1, k)};
}

bool SelfContact::neighbours(std::uint32_t node, std::uint32_t cell) const {
  const int cells_across = lattice_.cols - 1;
  const int j = int(node) / lattice_.cols, k = int(node) % lattice_.cols;
  const int jc = int(cell) / cells_across, kc = int(cell) % cells_across;
  // Distance in cells from the node to the cell's rectangle, at rest.
  const double dx = std::max({0.0, double(kc - k), double(k - kc - 1)}) / neighbour_cells_x_;
  const double dy = std::max({0.0, double(jc - j), double(j - jc - 1)}) / neighbour_cells_y_;
  return dx * dx + dy * dy < 1.0;
}

bool SelfContact::edge_neighbours(std::uint32_t a, std::uint32_t b) const {
  const auto& ea = edges_[a];
  const auto& eb = edges_[b];
  if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) return true;
  const auto rest = [&](std::uint32_t node) {
    const int j = int(node) / lattice_.cols, k = int(node) % lattice_.cols;
    return std::array<double, 2>{k * lattice_.spacing_x_m, j * lattice_.spacing_y_m};
  };
  return rest_distance(rest(ea[0]), rest(ea[1]), rest(eb[0]), rest(eb[1])) <
         kNeighbourReach * thickness_m_;
}

void SelfContact::find_candidates(std::span<const Vec3> x_m, double reach_m) {
  node_triangles_.clear();
  edge_edges_.clear();
  const int J = lattice_.rows, K = lattice_.cols, B = block_cells_;
  const std::size_t cells_across = std::size_t(K - 1);
  // Every triangle's unit normal at x (the corners of corners(), by row).
  for (int j = 0; j + 1 < J; ++j) {
    const Vec3* top = &x_m[lattice_.index(j, 0)];
    const Vec3* bottom = &x_m[lattice_.index(j + 1, 0)];
    Vec3* normal = &normals_[2 * std::size_t(j) * cells_across];
    for (int k = 0; k + 1 < K; ++k, normal += 2) {
      const Vec3 along = top[k + 1] - top[k], across = bottom[k + 1] - top[k],
                 down = bottom[k] - top[k];
      normal[0] = unit_or_zero(along.cross(across));
      normal[1] = unit_or_zero(across.cross(down));
    }
  }
  // Each block's box (its cells' nodes) and normal cone.
  const double infinity = std::numeric_limits<double>::infinity();
  for (int bj = 0; bj < block_rows_; ++bj)
    for (int bk = 0; bk < block_cols_; ++bk) {
      const std::size_t b = std::size_t(bj) * std::size_t(block_cols_) + std::size_t(bk);
      const int j0 = bj * B, j1 = std::min(J - 1, j0 + B), k0 = bk * B,
                k1 = std::min(K - 1, k0 + B);
      Vec3 low = Vec3::Constant(infinity), high = Vec3::Constant(-infinity);
      for (int j = j0; j <= j1; ++j)
        for (int k = k0; k <= k1; ++k) {
          const std::size_t i = lattice_.index(j, k);
          low = low.cwiseMin(x_m[i]);
          high = high.cwiseMax(x_m[i]);
        }
      low_[b] = low - Vec3::Constant(0.5 * reach_m);
      high_[b] = high + Vec3::Constant(0.5 * reach_m);
      Vec3 sum = Vec3::Zero();
      for (int j = j0; j < j1; ++j)
        for (int k = k0; k < k1; ++k) {
          const std::size_t cell = std::size_t(j) * cells_across + std::size_t(k);
          sum += normals_[2 * cell] + normals_[2 * cell + 1];
        }
      normal_sum_[b] = sum;
      const Vec3 axis = unit_or_zero(sum);
      double cos_min = 1.0;
      for (int j = j0; j < j1; ++j)
        for (int k = k0; k < k1; ++k) {
          const std::size_t cell = std::size_t(j) * cells_across + std::size_t(k);
          cos_min =
              std::min({cos_min, normals_[2 * cell].dot(axis), normals_[2 * cell + 1].dot(axis)});
        }
      axis_[b] = axis;
      spread_[b] = std::acos(std::clamp(cos_min, -1.0, 1.0));
    }
  // Nodes against triangles of two blocks: a block owns the nodes of its
  // cells but its last row and column (the next block's first), and the
  // lattice's last row and column go to the blocks along them.
  const auto owned = [&](int blocks, int block, int nodes) {
    const int first = block * B;
    const int last = block + 1 == blocks ? nodes - 1 : std::min(nodes - 1, first + B) - 1;
    return std::pair<int, int>{first, last};
  };
  const double reach2 = reach_m * reach_m;
  const auto test_nodes = [&](int ba_j, int ba_k, int bb_j, int bb_k) {
    const auto [nj0, nj1] = owned(block_rows_, ba_j, J);
    const auto [nk0, nk1] = owned(block_cols_, ba_k, K);
    const int cj0 = bb_j * B, cj1 = std::min(J - 1, cj0 + B);
    const int ck0 = bb_k * B, ck1 = std::min(K - 1, ck0 + B);
    const std::size_t other = std::size_t(bb_j) * std::size_t(block_cols_) + std::size_t(bb_k);
    for (int j = nj0; j <= nj1; ++j)
      for (int k = nk0; k <= nk1; ++k) {
        const auto node = std::uint32_t(lattice_.index(j, k));
        const Vec3& p = x_m[node];
        if ((p.array() < low_[other].array() - 0.5 * reach_m).any() ||
            (p.array() > high_[other].array() + 0.5 * reach_m).any())
          continue;  // nowhere near the other block
        for (int cj = cj0; cj < cj1; ++cj)
          for (int ck = ck0; ck < ck1; ++ck) {
            const auto cell = std::uint32_t(std::size_t(cj) * cells_across + std::size_t(ck));
            if (neighbours(node, cell)) continue;
            for (int half = 0; half < 2; ++half) {
              const auto c = corners(cell, half);
              if (c[0] == node || c[1] == node || c[2] == node) continue;
              const Closest q = closest_on_triangle(p, x_m[c[0]], x_m[c[1]], x_m[c[2]]);
              const Vec3 on = q.w[0] * x_m[c[0]] + q.w[1] * x_m[c[1]] + q.w[2] * x_m[c[2]];
              const double apart2 = (p - on).squaredNorm();
              if (apart2 < reach2)
                node_triangles_.push_back(
                    {node, cell, std::uint8_t(half), float(std::sqrt(apart2))});
            }
          }
      }
  };
  const auto test_edges = [&](std::size_t a, std::size_t b) {
    for (std::uint32_t i = block_edge_start_[a]; i < block_edge_start_[a + 1]; ++i) {
      const std::uint32_t ea = block_edges_[i];
      const Vec3 &p0 = x_m[edges_[ea][0]], &p1 = x_m[edges_[ea][1]];
      const Vec3 lo = p0.cwiseMin(p1) - Vec3::Constant(reach_m),
                 hi = p0.cwiseMax(p1) + Vec3::Constant(reach_m);
      if ((hi.array() < low_[b].array()).any() || (lo.array() > high_[b].array()).any()) continue;
      for (std::uint32_t m = a == b ? i + 1 : block_edge_start_[b]; m < block_edge_start_[b + 1];
           ++m) {
        const std::uint32_t eb = block_edges_[m];
        const Vec3 &q0 = x_m[edges_[eb][0]], &q1 = x_m[edges_[eb][1]];
        if ((q0.cwiseMin(q1).array() > hi.array()).any() ||
            (q0.cwiseMax(q1).array() < lo.array()).any())
          continue;
        const auto [s, u] = closest_on_segments(p0, p1, q0, q1);
        const double apart2 = ((p0 + s * (p1 - p0)) - (q0 + u * (q1 - q0))).squaredNorm();
        if (apart2 >= reach2) continue;
        if (edge_neighbours(ea, eb)) continue;
        edge_edges_.push_back({ea, eb, float(std::sqrt(apart2))});
      }
    }
  };
  // The pairs of blocks whose boxes overlap, found among the pairs of
  // super-blocks whose boxes overlap (sweep and prune along the lattice's
  // longer side), then visited in the order of a loop over every pair a <= b,
  // so the candidates, and so the projection after them, are those of that
  // loop. Two super-blocks (or one) whose normals fit in one cone of
  // kFlatAngle and that touch in the lattice are one flat patch, which cannot
  // touch itself: none of their blocks' pairs is looked into. A flag laid anew
  // each frame (the hybrid's dense lattice, 1536 blocks) finds its pairs every
  // frame, and most of it is flat at 16 cells.
  for (int sj = 0; sj < super_rows_; ++sj)
    for (int sk = 0; sk < super_cols_; ++sk) {
      const std::size_t s = std::size_t(sj) * std::size_t(super_cols_) + std::size_t(sk);
      const int bj0 = sj * kSuperBlock, bj1 = std::min(block_rows_, bj0 + kSuperBlock);
      const int bk0 = sk * kSuperBlock, bk1 = std::min(block_cols_, bk0 + kSuperBlock);
      Vec3 low = Vec3::Constant(infinity), high = Vec3::Constant(-infinity), sum = Vec3::Zero();
      for (int bj = bj0; bj < bj1; ++bj)
        for (int bk = bk0; bk < bk1; ++bk) {
          const std::size_t b = std::size_t(bj) * std::size_t(block_cols_) + std::size_t(bk);
          low = low.cwiseMin(low_[b]);
          high = high.cwiseMax(high_[b]);
          sum += normal_sum_[b];
        }
      // Its cone holds every block's: a normal within alpha_b of its block's
      // axis is within alpha_b + angle(axis, axis_b) of the super-block's.
      const Vec3 axis = unit_or_zero(sum);
      double spread = 0.0;
      for (int bj = bj0; bj < bj1; ++bj)
        for (int bk = bk0; bk < bk1; ++bk) {
          const std::size_t b = std::size_t(bj) * std::size_t(block_cols_) + std::size_t(bk);
          spread = axis_[b].squaredNorm() == 0.0
                       ? std::numbers::pi
                       : std::max(spread, std::acos(std::clamp(axis.dot(axis_[b]), -1.0, 1.0)) +
                                              spread_[b]);
        }
      super_low_[s] = low;
      super_high_[s] = high;
      super_axis_[s] = axis;
      super_spread_[s] = std::min(spread, std::numbers::pi);
    }
  const int axis = lattice_.spacing_x_m * (K - 1) >= lattice_.spacing_y_m * (J - 1) ? 0 : 1;
  super_pairs_.clear();
  overlapping_pairs(super_low_, super_high_, axis, block_order_, super_pairs_);
  block_pairs_.clear();
  for (const auto& [first, second] : super_pairs_) {
    const int aj = int(first) / super_cols_, ak = int(first) % super_cols_;
    const int bj = int(second) / super_cols_, bk = int(second) % super_cols_;
    if (std::abs(aj - bj) <= 1 && std::abs(ak - bk) <= 1 &&
        flat_together(super_axis_[first], super_spread_[first], super_axis_[second],
                      super_spread_[second], first == second))
      continue;
    const auto blocks_of = [&](int sj, int sk) {
      std::array<int, 4> range{sj * kSuperBlock, std::min(block_rows_, (sj + 1) * kSuperBlock),
                               sk * kSuperBlock, std::min(block_cols_, (sk + 1) * kSuperBlock)};
      return range;
    };
    const auto [aj0, aj1, ak0, ak1] = blocks_of(aj, ak);
    const auto [bj0, bj1, bk0, bk1] = blocks_of(bj, bk);
    for (int j = aj0; j < aj1; ++j)
      for (int k = ak0; k < ak1; ++k) {
        const auto a = std::uint32_t(j * block_cols_ + k);
        for (int jj = bj0; jj < bj1; ++jj)
          for (int kk = bk0; kk < bk1; ++kk) {
            const auto b = std::uint32_t(jj * block_cols_ + kk);
            if (first == second && b < a) continue;
            if ((low_[a].array() > high_[b].array()).any() ||
                (low_[b].array() > high_[a].array()).any())
              continue;
            block_pairs_.push_back({std::min(a, b), std::max(a, b)});
          }
      }
  }
  std::sort(block_pairs_.begin(), block_pairs_.end());
  for (const auto& [first, second] : block_pairs_) {
    const std::size_t a = first, b = second;
    const int aj = int(a) / block_cols_, ak = int(a) % block_cols_;
    const int bj = int(b) / block_cols_, bk = int(b) % block_cols_;
    if (std::abs(aj - bj) <= 1 && std::abs(ak - bk) <= 1 &&
        flat_together(axis_[a], spread_[a], axis_[b], spread_[b], a == b))
      continue;
    test_nodes(aj, ak, bj, bk);
    if (a != b) test_nodes(bj, bk, aj, ak);
    test_edges(a, b);
  }
}

double SelfContact::pass(bool first, std::span<Vec3> x_m, std::span<Vec3> v_m_s,
                         std::span<const std::uint8_t> pinned, std::span<const Vec3> before_m,
                         int& pushed) {
  // The first pass looks at every candidate and keeps those within
  // kNearPairs thicknesses of touching; the passes after it at those alone.
  const std::vector<NodeTriangle>& node_triangles = first ? node_triangles_ : near_nt_;
  const std::vector<EdgeEdge>& edge_edges = first ? edge_edges_ : near_ee_;
  if (first) {
    near_nt_.clear();
    near_ee_.clear();
  }
  const double near_gap = -kNearPairs * thickness_m_;
  // Farther apart than near_gap still, whatever their nodes' moves since found
  // (float distances: a part in 1e6 of slack).
  const double far = (1.0 + kNearPairs) * thickness_m_ * (1.0 + 1e-6);
  const bool velocities = !v_m_s.empty();
  const auto weight = [&](std::uint32_t i) { return !pinned.empty() && pinned[i] ? 0.0 : 1.0; };
  double largest_gap = 0.0;
  for (const NodeTriangle& pair : node_triangles) {
    const auto c = corners(pair.cell, pair.half);
    if (pair.apart_m - moved_[pair.node] - std::max({moved_[c[0]], moved_[c[1]], moved_[c[2]]}) >
        far)
      continue;
    Vec3& p = x_m[pair.node];
    const Closest q = closest_on_triangle(p, x_m[c[0]], x_m[c[1]], x_m[c[2]]);
    const Vec3 on = q.w[0] * x_m[c[0]] + q.w[1] * x_m[c[1]] + q.w[2] * x_m[c[2]];
    const Vec3 normal = (x_m[c[1]] - x_m[c[0]]).cross(x_m[c[2]] - x_m[c[0]]);
    const double area2 = normal.squaredNorm();
    // Over the triangle (its plane's foot inside it, or on an edge or a
    // corner, within kEdgeSlack): out along the normal on the node's side,
    // wherever the node is now (it may have passed through). Beside it: out
    // from the nearest point.
    bool over = q.inside;
    if (!over && area2 > 0.0) {
      const Vec3 foot = p - ((p - x_m[c[0]]).dot(normal) / area2) * normal;
      over = true;
      for (int i = 0; i < 3 && over; ++i) {
        const Vec3& e0 = x_m[c[(i + 1) % 3]];
        const Vec3& e1 = x_m[c[(i + 2) % 3]];
        over = (e1 - e0).cross(foot - e0).dot(normal) >= -kEdgeSlack * area2;
      }
    }
    Vec3 direction;
    double gap;  // how far short of the thickness, m
    if (over && area2 > 0.0) {
      // The side the node keeps: where it was at the step's start, else where it is.
      double side = 0.0;
      if (!before_m.empty()) {
        const Vec3 before_normal =
            (before_m[c[1]] - before_m[c[0]]).cross(before_m[c[2]] - before_m[c[0]]);
        side = (before_m[pair.node] - before_m[c[0]]).dot(before_normal);
        // Too close to the triangle's plane there to tell (set_side_reach).
        if (side * side <= side_reach_m_ * side_reach_m_ * before_normal.squaredNorm()) side = 0.0;
      }
      if (side == 0.0) side = (p - x_m[c[0]]).dot(normal);
      direction = (side < 0.0 ? -1.0 : 1.0) * (normal / std::sqrt(area2));
      gap = thickness_m_ - (p - x_m[c[0]]).dot(direction);
    } else {
      const double d = (p - on).norm();
      direction = d > 0.0 ? Vec3((p - on) / d) : Vec3::Zero();
      gap = thickness_m_ - d;
    }
    if (first && gap > near_gap) near_nt_.push_back(pair);
    if (gap <= 0.0 || direction.squaredNorm() == 0.0) continue;
    const double wp = weight(pair.node);
    double denominator = wp;
    for (int i = 0; i < 3; ++i) denominator += weight(c[i]) * q.w[i] * q.w[i];
    if (denominator == 0.0) continue;
    largest_gap = std::max(largest_gap, gap);
    const double lambda = gap / denominator;
    p += wp * lambda * direction;
    for (int i = 0; i < 3; ++i) x_m[c[i]] -= weight(c[i]) * q.w[i] * lambda * direction;
    ++pushed;
    if (!velocities) continue;
    Vec3 relative = v_m_s[pair.node];
    for (int i = 0; i < 3; ++i) relative -= q.w[i] * v_m_s[c[i]];
    const double closing = relative.dot(direction);
    if (closing >= 0.0) continue;
    const double impulse = -closing / denominator;
    v_m_s[pair.node] += wp * impulse * direction;
    for (int i = 0; i < 3; ++i) v_m_s[c[i]] -= weight(c[i]) * q.w[i] * impulse * direction;
  }
  for (const EdgeEdge& pair : edge_edges) {
    const auto [a0, a1] = edges_[pair.a];
    const auto [b0, b1] = edges_[pair.b];
    if (pair.apart_m - std::max(moved_[a0], moved_[a1]) - std::max(moved_[b0], moved_[b1]) > far)
      continue;
    const auto [s, u] = closest_on_segments(x_m[a0], x_m[a1], x_m[b0], x_m[b1]);
    if (s <= kEdgeEnd || s >= 1.0 - kEdgeEnd || u <= kEdgeEnd || u >= 1.0 - kEdgeEnd) {
      if (first) near_ee_.push_back(pair);  // its ends may slide inside in a later pass
      continue;
    }
    const Vec3 w = (x_m[a0] + s * (x_m[a1] - x_m[a0])) - (x_m[b0] + u * (x_m[b1] - x_m[b0]));
    const double d = w.norm();
    // The side they keep: the line between the same points at the step's start.
    Vec3 reference = Vec3::Zero();
    if (!before_m.empty()) {
      const Vec3 between = (before_m[a0] + s * (before_m[a1] - before_m[a0])) -
                           (before_m[b0] + u * (before_m[b1] - before_m[b0]));
      if (between.squaredNorm() > side_reach_m_ * side_reach_m_) reference = unit_or_zero(between);
    }
    Vec3 direction;
    double gap;
    const double along = reference.dot(w);
    if (reference.squaredNorm() > 0.0 && along <= 0.0) {  // crossed: back to the start's side
      direction = reference;
      gap = thickness_m_ - along;
    } else if (d > 0.0) {
      direction = w / d;
      gap = thickness_m_ - d;
    } else {
      continue;
    }
    if (first && gap > near_gap) near_ee_.push_back(pair);
    if (gap <= 0.0) continue;
    const double g[4] = {1.0 - s, s, -(1.0 - u), -u};
    const std::uint32_t n[4] = {a0, a1, b0, b1};
    double denominator = 0.0;
    for (int i = 0; i < 4; ++i) denominator += weight(n[i]) * g[i] * g[i];
    if (denominator == 0.0) continue;
    largest_gap = std::max(largest_gap, gap);
    const double lambda = gap / denominator;
    for (int i = 0; i < 4; ++i) x_m[n[i]] += weight(n[i]) * g[i] * lambda * direction;
    ++pushed;
    if (!velocities) continue;
    Vec3 relative = Vec3::Zero();
    for (int i = 0; i < 4; ++i) relative += g[i] * v_m_s[n[i]];
    const double closing = relative.dot(direction);
    if (closing >= 0.0) continue;
    const double impulse = -closing / denominator;
    for (int i = 0; i < 4; ++i) v_m_s[n[i]] += weight(n[i]) * g[i] * impulse * direction;
  }
  return largest_gap;
}

int SelfContact::project(std::span<Vec3> x_m, std::span<Vec3> v_m_s,
                         std::span<const std::uint8_t> pinned, std::span<const Vec3> before_m) {
  assert(x_m.size() == lattice_.node_count());
  // New candidates once some node has moved half the margin since the last.
  double moved = std::numeric_limits<double>::infinity();
  if (anchor_.size() == x_m.size()) {
    moved = 0.0;
    for (std::size_t i = 0; i < x_m.size(); ++i) {
      moved_[i] = (x_m[i] - anchor_[i]).norm();
      moved = std::max(moved, moved_[i]);
    }
  }
  if (!(moved <= 0.5 * margin_m_)) {
    find_candidates(x_m, thickness_m_ + margin_m_);
    anchor_.assign(x_m.begin(), x_m.end());
    moved_.assign(x_m.size(), 0.0);
  }
  if (node_triangles_.empty() && edge_edges_.empty()) return 0;
  int pushed = 0;
  for (int pass_index = 0; pass_index < kContactPasses; ++pass_index)
    if (pass(pass_index == 0, x_m, v_m_s, pinned, before_m, pushed) <=
        kContactTolerance * thickness_m_)
      break;
  return pushed;
}

double SelfContact::closest_m(std::span<const Vec3> x_m, double reach_m) {
  find_candidates(x_m, reach_m);
  anchor_.clear();  // the candidates are not project()'s any more
  double closest = reach_m;
  for (const NodeTriangle& pair : node_triangles_) {
    const auto c = corners(pair.cell, pair.half);
    const Closest q = closest_on_triangle(x_m[pair.node], x_m[c[0]], x_m[c[1]], x_m[c[2]]);
    const Vec3 on = q.w[0] * x_m[c[0]] + q.w[1] * x_m[c[1]] + q.w[2] * x_m[c[2]];
    closest = std::min(closest, (x_m[pair.node] - on).norm());
  }
  for (const EdgeEdge& pair : edge_edges_) {
    const auto [a0, a1] = edges_[pair.a];
    const auto [b0, b1] = edges_[pair.b];
    const auto [s, u] = closest_on_segments(x_m[a0], x_m[a1], x_m[b0], x_m[b1]);
    if (s <= kEdgeEnd || s >= 1.0 - kEdgeEnd || u <= kEdgeEnd || u >= 1.0 - kEdgeEnd) continue;
    closest = std::min(
        closest,
        ((x_m[a0] + s * (x_m[a1] - x_m[a0])) - (x_m[b0] + u * (x_m[b1] - x_m[b0]))).norm());
  }
  return closest;
}

}  // namespace flagsim::physics
