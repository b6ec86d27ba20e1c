#pragma once
// Bending with creases ([creases], scene.hpp): the bending of
// bending_springs.hpp with a rest angle theta_r on every fiber triple, which
// plastic flow moves (the paper's future work, section 5: "a crease like a
// fold line forms and does not come out").
//
// Per triple (a, b, c) of a row or column, with q = x_a - 2 x_b + x_c (links
// of length s turning by theta: |q| = 2 s sin(theta / 2)):
//
//   E = 1/2 k_b |q|^2 - k_b c (R - eps),   R = sqrt(|q|^2 + eps^2),
//   c = 2 s sin(theta_r / 2),               eps = kCreaseRounding s.
//
// theta_r = 0 (c = 0) is bending_springs' energy exactly. Otherwise E is least
// where R = c, |q| = sqrt(c^2 - eps^2): a fold of theta_r (less by
// eps^2 / (2 s c) rad), about any axis across the fiber. A crease keeps its
// line and its angle, not its side: a real crease also has a side (mountain
// or valley); here the first bending after the fold picks it. eps rounds the
// cusp a sharp rest angle puts at the straight fiber: there the force of
// 1/2 k (|q| - c)^2 jumps and its stiffness is unbounded; with eps, the
// straight fiber is a smooth unstable equilibrium (a crease pulled flat snaps
// to one side) and the stiffness stays below k_b (1 + c / eps).
//
//   dE/dq = k_b (1 - c / R) q,
//   d2E/dq2 = k_b [(1 - c / R) I + c q q^T / R^3]   (along q: 1 - c eps^2 / R^3),
//
// and in the positions, with g = (1, -2, 1): force -g_i dE/dq on node i,
// Hessian g g^T (x) d2E/dq2.
//
// Plastic flow (scene.hpp, Creases): at the start of every output frame, each
// triple's present angle theta = 2 asin(min(1, |q| / 2 s)) moves its held
// angle theta_h (theta low-passed with time constant set_time: what the fold
// has been for a while) and its rest angle, over the frame before (dt = 1 /
// fps): toward theta_h with time constant set_time where theta_h >
// max(theta_r, yield_angle) (a fold held past the yield sets; a flapping
// cloth's kinks, there and gone within a period, do not), and toward theta
// where theta < theta_r (a crease held flatter) with time constant
// relax_time / phi,
//
//   phi = 1 / (1 + sqrt(T_c / T)),   T_c = D / w^2,
//
// T the tension along the fiber (Y times the mean strain of the triple's two
// links, none if compressed; N/m), w the crease's width. Why: a crease is a
// hinge of width w, far narrower than a link; the sheet beside it, pulled by
// T, bends over lambda = sqrt(D / T) (D y'''' = T y''). Unfolding the
// crease by theta_r - theta is shared by the hinge and the sheet as their
// compliances, w / D and lambda / D: the hinge takes w / (w + lambda) = phi of
// it, and only what the hinge takes works on its yarns. So a crease relaxes
// faster the harder the wind pulls it flat, and not at all without tension
// (default: D = 1e-4 N m, w = 1 mm: T_c = 100 N/m; a 10 m/s wind pulls the
// default flag with about 90). The rest and held angles are the term's
// memory, saved and restored with the state (ClothState::memory).
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "flagsim/coarse_physics/bending_springs.hpp"
#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/force_term.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::physics {

/// eps / s: the rounding of a crease's cusp (above). A rest angle under about
/// this many radians makes no fold.
inline constexpr double kCreaseRounding = 0.05;

/// The rest angle, rad, of every triple of bending_triples(lattice) (same
/// order) from `folds`: each fold's angle on the triples its line crosses,
/// shared between the two fiber nodes either side of it in proportion to
/// their nearness (the total turning across the line is the fold's); capped at pi.
/// A line within a link of the edge is moved onto the first interior node.
std::vector<double> fold_rest_angles(std::span<const Fold> folds, const Lattice& lattice);

/// The term's memory at t = 0: the rest angles of `folds` (fold_rest_angles),
/// then the held angles (0: nothing has been held yet), rad.
std::vector<double> initial_crease_memory(std::span<const Fold> folds, const Lattice& lattice);

class CreasedBending;

/// The creased bending of `model` at t = 0 (its rest angles from `scene`'s
/// folds, frames of 1 / fps), or null when its material is not creased.
/// @param plain  as CreasedBending's
std::unique_ptr<CreasedBending> make_creased_bending(const Scene& scene, const ClothModel& model,
                                                     bool plain = true);

class CreasedBending final : public ForceTerm {
 public:
  /// @param rigidity_j  D, N m ([bending])
  /// @param creases     how the rest angles set and relax
  /// @param frame_s     the output frame's length, s: the plastic step
  /// @param memory     [2 triples] the rest and held angles at the start
  ///                    (initial_crease_memory)
  /// @param plain     with the plain bending 1/2 k_b |q|^2 (true), or the crease's
  ///                  part alone (XPBD: its bending is a constraint, the crease a force)
  CreasedBending(const ClothModel& model, double rigidity_j, const Creases& creases, double frame_s,
                 std::vector<double> memory, bool plain = true);

  std::string_view name() const override { return plain_ > 0.0 ? "bending" : "creases"; }
  /// The plastic step over the frame that ended at `time_s` (none at t = 0).
  void begin_frame(double time_s, std::span<const Vec3> x_m) override;
  void add_forces(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s,
                  std::span<Vec3> forces_n) const override;
  double energy(std::span<const Vec3> x_m) const override;
  void add_stiffness_bound(std::span<double> row_sum_n_m) const override;
  void linearize(std::span<const Vec3> x_m, std::span<const Vec3> v_m_s, Definiteness how) override;
  void add_stiffness_product(std::span<const Vec3> dx_m, std::span<Vec3> out_n) const override;
  void add_stiffness_diagonal(std::span<Mat3> diagonal_n_m) const override;
  /// The rest angles, rad, one per triple (bending_triples' order), then the held angles.
  std::span<const double> memory() const override { return memory_; }
  void set_memory(std::span<const double> memory) override;

  /// The present angle of every triple at `x_m`, rad (the plastic step's theta).
  std::vector<double> angles(std::span<const Vec3> x_m) const;
  /// phi of every triple at `x_m`: the share of a crease's unfolding its hinge takes.
  std::vector<double> hinge_shares(std::span<const Vec3> x_m) const;

 private:
  /// c and eps of triple t from its rest angle.
  void set_rest_length(std::size_t t);

  std::vector<BendingTriple> triples_;
  std::vector<double> spacing_m_;  ///< [triples] s, the rest link length along the fiber
  std::vector<double> memory_;     ///< [2 triples] theta_r, then theta_h
  std::vector<double> rest_m_;     ///< [triples] c = 2 s sin(theta_r / 2)
  std::vector<Mat3> hessian_;      ///< [triples] d2E/dq2 at the last linearization
  Creases creases_;
  double stretch_modulus_n_m_ = 0.0;  ///< Y, for the tension across a crease
  double hinge_tension_n_m_ = 0.0;    ///< T_c = D / w^2
  double frame_s_ = 0.0;
  double plain_ = 1.0;  ///< 1 with the plain bending, 0 for the crease's part alone
};

}  // namespace flagsim::physics
