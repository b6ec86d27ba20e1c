#include "flagsim/coarse_physics/vortex_wake.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace flagsim::physics {

Vec3 segment_induced_velocity(const Vec3& point, const Vec3& a, const Vec3& b, double core_m) {
  // K&P eq. 10.115: q = Gamma / (4 pi) (r1 x r2) / |r1 x r2|^2 r0 . (r1/|r1| - r2/|r2|).
  const Vec3 r1 = point - a, r2 = point - b, r0 = b - a;
  const Vec3 cross = r1.cross(r2);
  const double cross2 = cross.squaredNorm();
  const double n1 = r1.norm(), n2 = r2.norm();
  if (n1 < core_m || n2 < core_m || cross2 < core_m * core_m * r0.squaredNorm())
    return Vec3::Zero();
  const double k = r0.dot(r1 / n1 - r2 / n2) / (4.0 * std::numbers::pi * cross2);
  return k * cross;
}

namespace {

/// z velocity at `point` of a ring (counter-clockwise about +z) of unit
/// circulation spanning x in [x0, x1], y in [y_low, y_high] in the plane z = 0.
double ring_w(const Vec3& point, double x0, double x1, double y_low, double y_high, double core) {
  const Vec3 p1(x0, y_low, 0.0), p2(x1, y_low, 0.0), p3(x1, y_high, 0.0), p4(x0, y_high, 0.0);
  return (segment_induced_velocity(point, p1, p2, core) +
          segment_induced_velocity(point, p2, p3, core) +
          segment_induced_velocity(point, p3, p4, core) +
          segment_induced_velocity(point, p4, p1, core))
      .z();
}

/// Index of panel node (row, col) on a lattice of `cols` columns.
std::size_t corner(int row, int col, int cols) {
  return std::size_t(row) * std::size_t(cols) + std::size_t(col);
}

constexpr double kLead = 0.125, kTrail = 0.375;  // bilinear weights at (3/4 chord, mid-span)

}  // namespace

VortexWake::VortexWake(const ClothModel& model, const Wind& wind, std::uint64_t seed,
                       std::span<const double> inverse_mass_1_kg, double wake_lengths)
    : panels_(model.lattice, wind.panel_m),
      wind_(wind),
      field_(wind, seed),
      inverse_mass_(inverse_mass_1_kg.begin(), inverse_mass_1_kg.end()) {
  const Lattice& lattice = panels_.lattice();
  rows_ = lattice.rows - 1;
  cols_ = lattice.cols - 1;
  dx_m_ = lattice.spacing_x_m;
  dy_m_ = lattice.spacing_y_m;
  area_m2_ = dx_m_ * dy_m_;
  speed_m_s_ = wind.velocity_m_s.x();
  assert(speed_m_s_ > 0.0);
  aero_step_s_ = dx_m_ / speed_m_s_;
  const double chord_m = dx_m_ * cols_;
  wake_rows_ = std::max(1, int(std::ceil(wake_lengths * chord_m / dx_m_)));
  const int P = rows_ * cols_;
  const double core = 1e-6 * std::min(dx_m_, dy_m_);

  auto collocation = [&](int p) {
    const int r = p / cols_, c = p % cols_;
    return Vec3((c + 0.75) * dx_m_, -(r + 0.5) * dy_m_, 0.0);
  };
  influence_.resize(P, P);
  for (int i = 0; i < P; ++i) {
    const Vec3 point = collocation(i);
    for (int p = 0; p < P; ++p) {
      const int r = p / cols_, c = p % cols_;
      influence_(i, p) =
          ring_w(point, (c + 0.25) * dx_m_, (c + 1.25) * dx_m_, -(r + 1) * dy_m_, -r * dy_m_, core);
    }
  }
  inverse_ = influence_.partialPivLu().inverse();
  const int S = rows_;
  wake_influence_.resize(P, Eigen::Index(S) * wake_rows_);
  for (int i = 0; i < P; ++i) {
    const Vec3 point = collocation(i);
    for (int m = 0; m < wake_rows_; ++m) {
      const double x0 = (cols_ + 0.25 + m) * dx_m_;
      // The last row stands for the rest of the wake: it reaches far downstream.
      const double x1 = m + 1 == wake_rows_ ? x0 + 1.0e3 * chord_m : x0 + dx_m_;
      for (int r = 0; r < S; ++r)
        wake_influence_(i, m * S + r) = ring_w(point, x0, x1, -(r + 1) * dy_m_, -r * dy_m_, core);
    }
  }
  wake_gamma_ = Eigen::VectorXd::Zero(Eigen::Index(S) * wake_rows_);
  wake_w_ = wake_w_before_ = Eigen::VectorXd::Zero(P);
  gamma_ = rhs_ = rate_rhs_ = rate_ = Eigen::VectorXd::Zero(P);

  const std::size_t panel_nodes = lattice.node_count();
  for (int axis = 0; axis < 3; ++axis) {
    px_[axis].assign(panel_nodes, 0.0);
    pv_[axis].assign(panel_nodes, 0.0);
    pair_[axis].assign(panel_nodes, 0.0);
    scratch_[axis].assign(panel_nodes, 0.0);
  }
  air_m_s_.assign(panel_nodes, wind.velocity_m_s);
  for (std::size_t a = 0; a < panel_nodes; ++a)
    for (int axis = 0; axis < 3; ++axis) pair_[axis][a] = air_m_s_[a][axis];
  cloth_scratch_.assign(model.lattice.node_count(), Vec3::Zero());

  // K = C^-1 + V^T M^-1 U, C^-1 = A diag(1 / A_p) / rho; column p of V^T M^-1 U:
  // panel p's unit force spread to the cloth, over the masses, back at the
  // collocation points.
  Eigen::MatrixXd k_matrix(P, P);
  const double rho = wind.air_density_kg_m3;
  for (int p = 0; p < P; ++p) {
    std::fill(cloth_scratch_.begin(), cloth_scratch_.end(), Vec3::Zero());
    spread_panel_z(Eigen::VectorXd::Unit(P, p), cloth_scratch_);
    for (std::size_t i = 0; i < cloth_scratch_.size(); ++i) cloth_scratch_[i] *= inverse_mass_[i];
    k_matrix.col(p) = sample_collocation_z(cloth_scratch_);
    for (int q = 0; q < P; ++q) k_matrix(q, p) += influence_(q, p) / (rho * area_m2_);
  }
  woodbury_ = k_matrix.partialPivLu().inverse();
  double mass_kg = 0.0;
  for (const double m : model.mass_kg) mass_kg += m;
  areal_density_kg_m2_ = mass_kg / (chord_m * dy_m_ * rows_);
}

void VortexWake::to_panels(std::span<const Vec3> cloth, std::vector<double> (&out)[3]) const {
  if (panels_.same_lattice()) {
    for (std::size_t a = 0; a < cloth.size(); ++a)
      for (int axis = 0; axis < 3; ++axis) out[axis][a] = cloth[a][axis];
    return;
  }
  panels_.sample(cloth, out);
}

double VortexWake::at_collocation(const std::vector<double>& nodes, int p) const {
  const int r = p / cols_, c = p % cols_, K = cols_ + 1;
  const std::size_t top = corner(r, c, K), bottom = top + std::size_t(K);
  return kLead * (nodes[top] + nodes[bottom]) + kTrail * (nodes[top + 1] + nodes[bottom + 1]);
}

void VortexWake::begin_frame(double time_s, std::span<const Vec3> x_m) {
  if (field_.steady()) return;
  to_panels(x_m, scratch_);
  for (std::size_t a = 0; a < air_m_s_.size(); ++a) {
    const Vec3 x(scratch_[0][a], scratch_[1][a], scratch_[2][a]);
    air_m_s_[a] = field_.velocity(x, time_s);
    for (int axis = 0; axis < 3; ++axis) pair_[axis][a] = air_m_s_[a][axis];
  }
}

void VortexWake::advance_to(double time_s) {
  const int S = rows_;
  while (time_s >= next_shed_s_ - 1e-9 * aero_step_s_) {
    // Every wake row one panel down the wind; the trailing panels' circulation
    // into the first (the Kutta condition: no vortex left at the trailing edge).
    for (int m = wake_rows_ - 1; m > 0; --m)
      wake_gamma_.segment(Eigen::Index(m) * S, S) = wake_gamma_.segment(Eigen::Index(m - 1) * S, S);
    for (int r = 0; r < S; ++r) wake_gamma_(r) = gamma_(r * cols_ + cols_ - 1);
    wake_w_before_ = wake_w_;
    wake_w_.noalias() = wake_influence_ * wake_gamma_;
    last_shed_s_ = next_shed_s_;
    next_shed_s_ += aero_step_s_;
  }
}

void VortexWake::add_forces(double time_s, std::span<const Vec3> x_m, std::span<const Vec3> v_m_s,
                            std::span<Vec3> forces_n) {
  to_panels(x_m, px_);
  to_panels(v_m_s, pv_);
  const int P = rows_ * cols_, K = cols_ + 1;
  const double theta = std::clamp((time_s - last_shed_s_) / aero_step_s_, 0.0, 1.0);
  auto node = [&](const std::vector<double>(&f)[3], std::size_t a) {
    return Vec3(f[0][a], f[1][a], f[2][a]);
  };
  Eigen::VectorXd along(P);
  for (int p = 0; p < P; ++p) {
    const int r = p / cols_, c = p % cols_;
    const std::size_t n00 = corner(r, c, K), n01 = n00 + 1, n10 = n00 + std::size_t(K),
                      n11 = n10 + 1;
    const Vec3 d1 = node(px_, n11) - node(px_, n00), d2 = node(px_, n01) - node(px_, n10);
    const Vec3 cross = d1.cross(d2);
    const double length = cross.norm();
    const Vec3 n = cross / length;
    const Vec3 cross_rate =
        (node(pv_, n11) - node(pv_, n00)).cross(d2) + d1.cross(node(pv_, n01) - node(pv_, n10));
    const Vec3 n_rate = (cross_rate - n * n.dot(cross_rate)) / length;
    Vec3 relative;
    for (int axis = 0; axis < 3; ++axis)
      relative[axis] = at_collocation(pv_[axis], p) - at_collocation(pair_[axis], p);
    rhs_(p) = relative.dot(n) - (wake_w_before_(p) + theta * (wake_w_(p) - wake_w_before_(p)));
    rate_rhs_(p) = relative.dot(n_rate) - (wake_w_(p) - wake_w_before_(p)) / aero_step_s_;
    along(p) = -relative.x();  // the air's speed along the chord, relative to the panel
  }
  gamma_.noalias() = inverse_ * rhs_;
  rate_.noalias() = inverse_ * rate_rhs_;
  const double rho = wind_.air_density_kg_m3;
  Eigen::VectorXd force(P);
  for (int p = 0; p < P; ++p) {
    const double ahead = p % cols_ == 0 ? 0.0 : gamma_(p - 1);
    force(p) = -rho * area_m2_ * (along(p) * (gamma_(p) - ahead) / dx_m_ + rate_(p));
  }
  spread_panel_z(force, forces_n);
}

void VortexWake::spread_panel_z(const Eigen::VectorXd& per_panel, std::span<Vec3> out) const {
  const int P = rows_ * cols_, K = cols_ + 1;
  std::fill(scratch_[2].begin(), scratch_[2].end(), 0.0);
  for (int p = 0; p < P; ++p) {
    const std::size_t n00 = corner(p / cols_, p % cols_, K);
    for (const std::size_t a : {n00, n00 + 1, n00 + std::size_t(K), n00 + std::size_t(K) + 1})
      scratch_[2][a] += 0.25 * per_panel(p);
  }
  if (panels_.same_lattice()) {
    for (std::size_t a = 0; a < out.size(); ++a) out[a].z() += scratch_[2][a];
    return;
  }
  std::fill(scratch_[0].begin(), scratch_[0].end(), 0.0);
  std::fill(scratch_[1].begin(), scratch_[1].end(), 0.0);
  panels_.spread(scratch_, out);
}

Eigen::VectorXd VortexWake::sample_collocation_z(std::span<const Vec3> cloth) const {
  to_panels(cloth, scratch_);
  Eigen::VectorXd sampled(rows_ * cols_);
  for (int q = 0; q < sampled.size(); ++q) sampled(q) = at_collocation(scratch_[2], q);
  return sampled;
}

void VortexWake::add_air_inertia(std::span<Vec3> a_m_s2) const {
  const Eigen::VectorXd s = woodbury_ * sample_collocation_z(a_m_s2);
  std::fill(cloth_scratch_.begin(), cloth_scratch_.end(), Vec3::Zero());
  spread_panel_z(s, cloth_scratch_);
  for (std::size_t i = 0; i < a_m_s2.size(); ++i)
    a_m_s2[i].z() -= inverse_mass_[i] * cloth_scratch_[i].z();
}

void VortexWake::add_added_mass_force(std::span<const Vec3> a_m_s2,
                                      std::span<Vec3> forces_n) const {
  const Eigen::VectorXd force = -added_mass() * sample_collocation_z(a_m_s2);
  spread_panel_z(force, forces_n);
}

Eigen::MatrixXd VortexWake::added_mass() const {
  return wind_.air_density_kg_m3 * area_m2_ * inverse_;
}

double VortexWake::velocity_rate_bound() const {
  // A plate's circulatory force per area is at most about rho pi U w (2D thin
  // aerofoil theory: Gamma = pi c w); 2 pi for a margin, over the cloth's mass per area.
  return wind_.air_density_kg_m3 * 2.0 * std::numbers::pi * field_.speed_bound_m_s() /
         areal_density_kg_m2_;
}

}  // namespace flagsim::physics
