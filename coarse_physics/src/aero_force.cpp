#include "flagsim/coarse_physics/aero_force.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cassert>
#include <cmath>

#include "flagsim/core/lanes.hpp"

// Lanes (below) are passed by value only between inlined helpers of this
// file, never across an ABI boundary.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace flagsim::physics {

Vec3 triangle_aero_force(const Vec3& x0, const Vec3& x1, const Vec3& x2,
                         const Vec3& relative_velocity, const Wind& wind) {
  // With c = (x1 - x0) x (x2 - x0) = 2 A n and u_n = u.n = (u.c)/|c|:
  //   drag = 1/2 rho C_d A u_n |u_n| n                    = 1/4 rho C_d u_n |u_n| c
  //   lift = 1/2 rho C_l A u_n (|u| n - u_n u/|u|)        = 1/4 rho C_l u_n (|u| c - |c| u_n u/|u|)
  // Written with u.c, |c|^2 and r = |c| |u| only: one square root, two divisions.
  const Vec3 c = (x1 - x0).cross(x2 - x0);
  const Vec3& u = relative_velocity;
  const double c_norm2 = c.squaredNorm(), speed2 = u.squaredNorm();
  if (c_norm2 == 0.0 || speed2 == 0.0) return Vec3::Zero();
  const double u_dot_c = u.dot(c);
  const double product = c_norm2 * speed2;
  const double r = std::sqrt(product);  // |c| |u|
  // |c| |u_t| with u_t = u - (u.c) c/|c|^2, the flow along the plate
  const double tangential = std::sqrt(std::max(0.0, product - u_dot_c * u_dot_c));
  const double inv_c_norm2 = 1.0 / c_norm2;
  const double quarter_rho = 0.25 * wind.air_density_kg_m3;
  // u_n |u_n| = (u.c)|u.c|/|c|^2,  u_n |u| = (u.c) r/|c|^2,  u_n^2 |c|/|u| = (u.c)^2/r;
  // friction 1/4 rho C_f |c| |u_t| u_t = friction (u - (u.c)/|c|^2 c)
  const double friction = quarter_rho * wind.friction * tangential;
  const double along_c =
      quarter_rho * u_dot_c * inv_c_norm2 * (wind.drag * std::abs(u_dot_c) + wind.lift * r) -
      friction * u_dot_c * inv_c_norm2;
  const double along_u = quarter_rho * wind.lift * u_dot_c * u_dot_c / r - friction;
  return along_c * c - along_u * u;
}

Mat3 triangle_aero_velocity_jacobian(const Vec3& x0, const Vec3& x1, const Vec3& x2,
                                     const Vec3& relative_velocity, const Wind& wind) {
  // F = alpha c - beta u with s = u.c, r = |c| |u|:
  //   alpha = q/|c|^2 (C_d s |s| + C_l s r),  beta = q C_l s^2 / r,  q = rho / 4;
  //   ds/du = c,  dr/du = |c|^2 u / r;
  //   dF/du = c (dalpha/du)^T - u (dbeta/du)^T - beta I.
  const Vec3 c = (x1 - x0).cross(x2 - x0);
  const Vec3& u = relative_velocity;
  const double c_norm2 = c.squaredNorm(), speed2 = u.squaredNorm();
  if (c_norm2 == 0.0 || speed2 == 0.0) return Mat3::Zero();
  const double s = u.dot(c);
  const double r = std::sqrt(c_norm2 * speed2);
  const double q = 0.25 * wind.air_density_kg_m3;
  const Vec3 dr = (c_norm2 / r) * u;
  const Vec3 dalpha =
      (q / c_norm2) * (wind.drag * 2.0 * std::abs(s) * c + wind.lift * (r * c + s * dr));
  const double beta = q * wind.lift * s * s / r;
  const Vec3 dbeta = q * wind.lift * ((2.0 * s / r) * c - (s * s / (r * r)) * dr);
  Mat3 jacobian = c * dalpha.transpose() - u * dbeta.transpose() - beta * Mat3::Identity();
  // Friction q C_f g with g = t u_t, t = |c| |u_t| = sqrt(|c|^2 |u|^2 - s^2),
  // u_t = u - s c/|c|^2: dt/du = |c|^2 u_t / t, du_t/du = I - c c^T/|c|^2, so
  //   dg/du = (|c|^2/t) u_t u_t^T + t I - (t/|c|^2) c c^T  (the first term -> 0 as t -> 0).
  const double t = std::sqrt(std::max(0.0, c_norm2 * speed2 - s * s));
  if (wind.friction > 0.0 && t > 0.0) {
    const Vec3 u_t = u - (s / c_norm2) * c;
    jacobian += q * wind.friction *
                ((c_norm2 / t) * u_t * u_t.transpose() + t * Mat3::Identity() -
                 (t / c_norm2) * c * c.transpose());
  }
  return jacobian;
}

AeroForce::AeroForce(const ClothModel& model, const Wind& wind, std::uint64_t seed,
                     double areal_density_kg_m2, double cloth_speed_bound_m_s)
    : panels_(model.lattice, wind.panel_m),
      lattice_(panels_.lattice()),
      cloth_nodes_(model.lattice.node_count()),
      wind_(wind),
      field_(wind, seed),
      areal_density_kg_m2_(areal_density_kg_m2),
      cloth_speed_bound_m_s_(cloth_speed_bound_m_s) {
  air_m_s_.assign(lattice_.node_count(), wind.velocity_m_s);
  const std::size_t nodes = lattice_.node_count();
  const std::size_t cells = std::size_t(lattice_.rows - 1) * std::size_t(lattice_.cols - 1);
  for (int axis = 0; axis < 3; ++axis) {
    work_.x[axis].resize(nodes);
    work_.v[axis].resize(nodes);
    work_.air[axis].resize(nodes);
    work_.f[axis].resize(nodes);
    work_.upper[axis].resize(cells);
    work_.lower[axis].resize(cells);
  }
  panel_x_.resize(nodes);
  panel_v_.resize(nodes);
  panel_out_.resize(nodes);
  cell_scale_.assign(cells, 1.0);
  // wind.lift_at_pole false: no lift on the cells whose rest rectangle holds a
  // held cloth node (at the pole: the column of panels that straddles it).
  cell_lift_.assign(cells, wind.lift);
  if (!wind.lift_at_pole) {
    // The held nodes' rest positions, gathered once: each cell looks only at
    // them (a cloth that is its own panel lattice has as many cells as nodes).
    std::vector<Vec3> held;
    for (int j = 0; j < model.lattice.rows; ++j)
      for (int k = 0; k < model.lattice.cols; ++k)
        if (model.pinned[model.lattice.index(j, k)])
          held.push_back(model.lattice.rest_position(j, k));
    const int Kp = lattice_.cols;
    for (int j = 0; j + 1 < lattice_.rows; ++j)
      for (int k = 0; k + 1 < Kp; ++k) {
        const Vec3 a = lattice_.rest_position(j, k), b = lattice_.rest_position(j + 1, k + 1);
        const Vec3 low = a.cwiseMin(b), high = a.cwiseMax(b);
        const double slack = 1e-9 * (high - low).norm();
        for (const Vec3& p : held)
          if (((p.array() >= low.array() - slack) && (p.array() <= high.array() + slack)).all()) {
            cell_lift_[std::size_t(j) * std::size_t(Kp - 1) + std::size_t(k)] = 0.0;
            break;
          }
      }
  }
  if (!panels_.same_lattice()) {
    const std::vector<Vec3> rest = model.lattice.rest_positions();
    const std::span<const Vec3> sampled = on_panels(rest, panel_x_);
    const int Kp = lattice_.cols;
    for (int j = 0; j + 1 < lattice_.rows; ++j)
      for (int k = 0; k + 1 < Kp; ++k) {
        const Vec3& corner = sampled[lattice_.index(j, k)];
        const double across = (sampled[lattice_.index(j, k + 1)] - corner).norm();
        const double down = (sampled[lattice_.index(j + 1, k)] - corner).norm();
        cell_scale_[std::size_t(j) * std::size_t(Kp - 1) + std::size_t(k)] =
            (lattice_.spacing_x_m * lattice_.spacing_y_m) / (across * down);
      }
  }
  lanes::split(air_m_s_, work_.air);  // the steady wind's, kept while no frame changes it
  begin_frame(0.0, model.lattice.rest_positions());
}

std::span<const Vec3> AeroForce::on_panels(std::span<const Vec3> values,
                                           std::vector<Vec3>& out) const {
  assert(values.size() == cloth_nodes_);
  if (panels_.same_lattice()) return values;
  panels_.sample(values, work_.f);  // work_.f as scratch: add_forces refills it
  lanes::join(work_.f, out);
  return out;
}

void AeroForce::begin_frame(double time_s, std::span<const Vec3> x_m) {
  if (field_.steady()) return;  // the mean wind everywhere, set once
  const std::span<const Vec3> x = on_panels(x_m, panel_x_);
  for (std::size_t i = 0; i < air_m_s_.size(); ++i) air_m_s_[i] = field_.velocity(x[i], time_s);
  lanes::split(air_m_s_, work_.air);
}

bool AeroForce::set_wind_drift(const WindField::Drift& drift, double time_s,
                               std::span<const Vec3> x_m) {
  field_.set_drift(drift);
  if (field_.steady()) {  // the one velocity everywhere, as the constructor sets it
    air_m_s_.assign(air_m_s_.size(), drift.mean_m_s);
    lanes::split(air_m_s_, work_.air);
  } else {
    begin_frame(time_s, x_m);
  }
  return true;
}

template <typename Visit>
void AeroForce::for_each_triangle(Visit&& visit) const {
  const int rows = lattice_.rows, cols = lattice_.cols;
  for (int j = 0; j + 1 < rows; ++j) {
    for (int k = 0; k + 1 < cols; ++k) {
      const std::size_t n00 = lattice_.index(j, k), n01 = n00 + 1;
      const std::size_t n10 = n00 + std::size_t(cols), n11 = n10 + 1;
      visit(n00, n01, n10);
      visit(n01, n11, n10);
    }
  }
}

namespace {
constexpr double kThird = 1.0 / 3.0;  // multiply: Eigen's "/ 3.0" is three divisions
}  // namespace

namespace {

// Four triangles side by side (core/lanes.hpp): the same bits as
// triangle_aero_force's scalar operations, in the same order.
using lanes::Lanes;
using lanes::load;
using lanes::splat;
using lanes::store;
constexpr int kLanes = lanes::kWidth;

// `kLanes` consecutive values of one coordinate, from node `i` on.
struct Lanes3 {
  Lanes x, y, z;
};
// One coordinate of u = ((air0 + air1) + air2 - ((v0 + v1) + v2)) / 3.
[[gnu::always_inline]] inline Lanes mean_relative(const std::vector<double>& air,
                                                  const std::vector<double>& v, std::size_t n0,
                                                  std::size_t n1, std::size_t n2) {
  return splat(kThird) *
         (((load(air.data() + n0) + load(air.data() + n1)) + load(air.data() + n2)) -
          ((load(v.data() + n0) + load(v.data() + n1)) + load(v.data() + n2)));
}
// One coordinate of the edge x[to] - x[from].
[[gnu::always_inline]] inline Lanes edge(const std::vector<double>& x, std::size_t from,
                                         std::size_t to) {
  return load(x.data() + to) - load(x.data() + from);
}

// triangle_aero_force's arithmetic on lanes, times 1/3 (a node's share), for
// the triangles (n0 + l, n1 + l, n2 + l) of lanes l; the air's and the nodes'
// velocities summed in the triangle's order, as Eigen's (p + q + r): (p + q) + r.
// Each value is loaded where it is first used, so that few lanes are live at once.
[[gnu::always_inline]] inline Lanes3 third_of_force(const std::vector<double> (&x)[3],
                                                    const std::vector<double> (&air)[3],
                                                    const std::vector<double> (&v)[3],
                                                    std::size_t n0, std::size_t n1, std::size_t n2,
                                                    const Wind& wind, Lanes lift) {
  const Lanes zero = splat(0.0), one = splat(1.0), third = splat(kThird);
  const Lanes3 u = {mean_relative(air[0], v[0], n0, n1, n2),
                    mean_relative(air[1], v[1], n0, n1, n2),
                    mean_relative(air[2], v[2], n0, n1, n2)};
  const Lanes3 e1 = {edge(x[0], n0, n1), edge(x[1], n0, n1), edge(x[2], n0, n1)};
  const Lanes3 e2 = {edge(x[0], n0, n2), edge(x[1], n0, n2), edge(x[2], n0, n2)};
  const Lanes3 c = {e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z,
                    e1.x * e2.y - e1.y * e2.x};
  const Lanes c_norm2 = (c.x * c.x + c.y * c.y) + c.z * c.z;
  const Lanes speed2 = (u.x * u.x + u.y * u.y) + u.z * u.z;
  const auto degenerate = (c_norm2 == zero) | (speed2 == zero);
  const Lanes u_dot_c = (u.x * c.x + u.y * c.y) + u.z * c.z;
  const Lanes product = c_norm2 * speed2;
  const Lanes tangential2 = product - u_dot_c * u_dot_c;
  const Lanes clamped2 = zero < tangential2 ? tangential2 : zero;  // std::max(0.0, t2)
  Lanes r, tangential;
  for (int l = 0; l < kLanes; ++l) {
    r[l] = std::sqrt(product[l]);
    tangential[l] = std::sqrt(clamped2[l]);
  }
  const Lanes safe_r = degenerate ? one : r;
  const Lanes inv_c_norm2 = one / (degenerate ? one : c_norm2);
  const Lanes quarter_rho = splat(0.25 * wind.air_density_kg_m3);
  const Lanes abs_u_dot_c = u_dot_c < zero ? -u_dot_c : u_dot_c;
  const Lanes friction = quarter_rho * splat(wind.friction) * tangential;
  const Lanes along_c =
      quarter_rho * u_dot_c * inv_c_norm2 * (splat(wind.drag) * abs_u_dot_c + lift * r) -
      friction * u_dot_c * inv_c_norm2;
  const Lanes along_u = quarter_rho * lift * u_dot_c * u_dot_c / safe_r - friction;
  const Lanes3 f = {along_c * c.x - along_u * u.x, along_c * c.y - along_u * u.y,
                    along_c * c.z - along_u * u.z};
  return {degenerate ? zero : third * f.x, degenerate ? zero : third * f.y,
          degenerate ? zero : third * f.z};
}

}  // namespace

FLAGSIM_LANES_CLONES void AeroForce::row_thirds(int j) const {
  const std::size_t K = std::size_t(lattice_.cols), cells = K - 1;
  const std::size_t top = std::size_t(j) * K, bottom = top + K, out = std::size_t(j) * cells;
  std::size_t k = 0;
  for (; k + kLanes <= cells; k += kLanes) {
    // Nodes 00 (top + k), 01, 10 (bottom + k), 11 of kLanes consecutive cells.
    const std::size_t n00 = top + k, n01 = n00 + 1, n10 = bottom + k, n11 = n10 + 1;
    const Lanes lift = load(cell_lift_.data() + out + k);  // each cell's (wind.lift_at_pole)
    const Lanes3 up = third_of_force(work_.x, work_.air, work_.v, n00, n01, n10, wind_, lift);
    const Lanes3 lo = third_of_force(work_.x, work_.air, work_.v, n01, n11, n10, wind_, lift);
    store(work_.upper[0].data() + out + k, up.x);
    store(work_.upper[1].data() + out + k, up.y);
    store(work_.upper[2].data() + out + k, up.z);
    store(work_.lower[0].data() + out + k, lo.x);
    store(work_.lower[1].data() + out + k, lo.y);
    store(work_.lower[2].data() + out + k, lo.z);
  }
  Wind wind = wind_;        // with each cell's lift (wind.lift_at_pole)
  for (; k < cells; ++k) {  // the row's last cells, one at a time, the same arithmetic
    const auto node = [](const std::vector<double>(&a)[3], std::size_t i) {
      return Vec3(a[0][i], a[1][i], a[2][i]);
    };
    const std::size_t n00 = top + k, n01 = n00 + 1, n10 = bottom + k, n11 = n10 + 1;
    wind.lift = cell_lift_[out + k];
    const auto third = [&](std::size_t a, std::size_t b, std::size_t c) {
      const Vec3 u = kThird * ((node(work_.air, a) + node(work_.air, b) + node(work_.air, c)) -
                               (node(work_.v, a) + node(work_.v, b) + node(work_.v, c)));
      return Vec3(kThird * triangle_aero_force(node(work_.x, a), node(work_.x, b), node(work_.x, c),
                                               u, wind));
    };
    const Vec3 up = third(n00, n01, n10), lo = third(n01, n11, n10);
    for (int axis = 0; axis < 3; ++axis) {
      work_.upper[axis][out + k] = up[axis];
      work_.lower[axis][out + k] = lo[axis];
    }
  }
}

FLAGSIM_LANES_CLONES void AeroForce::gather_thirds() const {
  // Node (j, k) gets its triangles' thirds in the order the cells' loop
  // (row-major, upper then lower) would add them: the lower triangle of cell
  // (j-1, k-1), both of (j-1, k), both of (j, k-1), the upper of (j, k).
  const int J = lattice_.rows, K = lattice_.cols;
  const std::size_t cells = std::size_t(K - 1);
  for (int axis = 0; axis < 3; ++axis) {
    double* const f = work_.f[axis].data();
    const double* const upper = work_.upper[axis].data();
    const double* const lower = work_.lower[axis].data();
    const auto edge_node = [&](int j, int k) {
      double& sum = f[std::size_t(j) * std::size_t(K) + std::size_t(k)];
      const auto cell = [&](int cj, int ck) { return std::size_t(cj) * cells + std::size_t(ck); };
      const bool up = j > 0, left = k > 0, down = j + 1 < J, right = k + 1 < K;
      if (up && left) sum += lower[cell(j - 1, k - 1)];
      if (up && right) {
        sum += upper[cell(j - 1, k)];
        sum += lower[cell(j - 1, k)];
      }
      if (down && left) {
        sum += upper[cell(j, k - 1)];
        sum += lower[cell(j, k - 1)];
      }
      if (down && right) sum += upper[cell(j, k)];
    };
    for (int j = 0; j < J; ++j) {
      if (j == 0 || j + 1 == J) {
        for (int k = 0; k < K; ++k) edge_node(j, k);
        continue;
      }
      edge_node(j, 0);
      // Interior nodes k = 1 .. K-2, kLanes at a time: all six triangles.
      double* const row = f + std::size_t(j) * std::size_t(K);
      const double* const above_upper = upper + std::size_t(j - 1) * cells;
      const double* const above_lower = lower + std::size_t(j - 1) * cells;
      const double* const here_upper = upper + std::size_t(j) * cells;
      const double* const here_lower = lower + std::size_t(j) * cells;
      int k = 1;
      for (; k + kLanes <= K - 1; k += kLanes) {
        const std::size_t c = std::size_t(k);
        Lanes sum = load(row + c);
        sum = sum + load(above_lower + c - 1);
        sum = sum + load(above_upper + c);
        sum = sum + load(above_lower + c);
        sum = sum + load(here_upper + c - 1);
        sum = sum + load(here_lower + c - 1);
        sum = sum + load(here_upper + c);
        store(row + c, sum);
      }
      for (; k < K - 1; ++k) edge_node(j, k);
      edge_node(j, K - 1);
    }
  }
}

void AeroForce::add_forces(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s,
                           std::span<Vec3> forces_n) const {
  if (panels_.same_lattice()) {
    lanes::split(x_m, work_.x);
    lanes::split(v_m_s, work_.v);
    lanes::split(forces_n, work_.f);
    for (int j = 0; j + 1 < lattice_.rows; ++j) row_thirds(j);
    gather_thirds();
    lanes::join(work_.f, forces_n);
    return;
  }
  panels_.sample(x_m, work_.x, v_m_s, work_.v);
  for (auto& f : work_.f) std::fill(f.begin(), f.end(), 0.0);
  for (int j = 0; j + 1 < lattice_.rows; ++j) row_thirds(j);
  for (int axis = 0; axis < 3; ++axis)
    for (std::size_t cell = 0; cell < cell_scale_.size(); ++cell) {
      work_.upper[axis][cell] *= cell_scale_[cell];
      work_.lower[axis][cell] *= cell_scale_[cell];
    }
  gather_thirds();
  panels_.spread(work_.f, forces_n);
}

void AeroForce::linearize(std::span<const Vec3> x_cloth_m, std::span<const Vec3> v_cloth_m_s,
                          Definiteness how) {
  // On the panels: C = W^T C_panels W for the cloth (W the sampling).
  const std::span<const Vec3> x_m = on_panels(x_cloth_m, panel_x_);
  const std::span<const Vec3> v_m_s = on_panels(v_cloth_m_s, panel_v_);
  damping_.resize(2 * std::size_t(lattice_.rows - 1) * std::size_t(lattice_.cols - 1));
  std::size_t t = 0;
  Wind wind = wind_;  // with each cell's lift (wind.lift_at_pole)
  for_each_triangle([&](std::size_t a, std::size_t b, std::size_t c) {
    const Vec3 u =
        kThird * ((air_m_s_[a] + air_m_s_[b] + air_m_s_[c]) - (v_m_s[a] + v_m_s[b] + v_m_s[c]));
    wind.lift = cell_lift_[t / 2];
    Mat3 block = (cell_scale_[t / 2] / 9.0) *
                 triangle_aero_velocity_jacobian(x_m[a], x_m[b], x_m[c], u, wind);
    if (how == Definiteness::kProjected) {
      const Mat3 symmetric = 0.5 * (block + block.transpose());
      Eigen::SelfAdjointEigenSolver<Mat3> eigen;
      eigen.computeDirect(symmetric);
      const Vec3 clamped = eigen.eigenvalues().cwiseMax(0.0);
      block = eigen.eigenvectors() * clamped.asDiagonal() * eigen.eigenvectors().transpose();
    }
    damping_[t++] = block;
  });
}

void AeroForce::add_damping_product(std::span<const Vec3> dv_cloth_m_s,
                                    std::span<Vec3> out_cloth_n) const {
  const std::span<const Vec3> dv_m_s = on_panels(dv_cloth_m_s, panel_v_);
  const bool same = panels_.same_lattice();
  if (!same) std::fill(panel_out_.begin(), panel_out_.end(), Vec3::Zero());
  const std::span<Vec3> out_n = same ? out_cloth_n : std::span<Vec3>(panel_out_);
  std::size_t t = 0;
  for_each_triangle([&](std::size_t a, std::size_t b, std::size_t c) {
    const Vec3 w = damping_[t++] * (dv_m_s[a] + dv_m_s[b] + dv_m_s[c]);
    out_n[a] += w;
    out_n[b] += w;
    out_n[c] += w;
  });
  if (same) return;
  lanes::split(panel_out_, work_.f);
  panels_.spread(work_.f, out_cloth_n);
}

void AeroForce::add_damping_diagonal(std::span<Mat3> diagonal_n_s_m) const {
  std::size_t t = 0;
  if (panels_.same_lattice()) {
    for_each_triangle([&](std::size_t a, std::size_t b, std::size_t c) {
      const Mat3& block = damping_[t++];
      diagonal_n_s_m[a] += block;
      diagonal_n_s_m[b] += block;
      diagonal_n_s_m[c] += block;
    });
    return;
  }
  // (W^T C W)_ii = sum over triangles of block (W_ai + W_bi + W_ci)^2, over the
  // cloth nodes under the triangle's three hats.
  const int cloth_cols = panels_.cloth_cols();
  const int Kp = lattice_.cols;
  for_each_triangle([&](std::size_t a, std::size_t b, std::size_t c) {
    const Mat3& block = damping_[t++];
    const int rows[3] = {int(a) / Kp, int(b) / Kp, int(c) / Kp};
    const int cols[3] = {int(a) % Kp, int(b) % Kp, int(c) % Kp};
    const int row_lo = panels_.cloth_rows_of(*std::min_element(rows, rows + 3)).first;
    const int row_hi = panels_.cloth_rows_of(*std::max_element(rows, rows + 3)).second;
    const int col_lo = panels_.cloth_cols_of(*std::min_element(cols, cols + 3)).first;
    const int col_hi = panels_.cloth_cols_of(*std::max_element(cols, cols + 3)).second;
    for (int j = row_lo; j <= row_hi; ++j)
      for (int k = col_lo; k <= col_hi; ++k) {
        double share = 0.0;
        for (int n = 0; n < 3; ++n)
          share += panels_.row_weight(rows[n], j) * panels_.col_weight(cols[n], k);
        if (share != 0.0)
          diagonal_n_s_m[std::size_t(j) * std::size_t(cloth_cols) + std::size_t(k)] +=
              (share * share) * block;
      }
  });
}

double AeroForce::velocity_rate_bound() const {
  // |dF/dv| of a node ~ (its share of area) rho (C_d + C_l + C_f) |u|, over its mass
  // (density * area): rho (C_d + C_l + C_f) |u| / density, with |u| <= |wind| + cloth speed.
  // On panels the node's share of each panel's force is its share of the area: the same bound.
  const double relative_speed = field_.speed_bound_m_s() + cloth_speed_bound_m_s_;
  return wind_.air_density_kg_m3 * (wind_.drag + wind_.lift + wind_.friction) * relative_speed /
         areal_density_kg_m2_;
}

}  // namespace flagsim::physics
