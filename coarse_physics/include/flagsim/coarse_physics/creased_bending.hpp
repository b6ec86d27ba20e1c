#pragma once
// Bending with creases ([creases], scene.hpp): the bending of
// bending_springs.hpp with a rest angle theta_r on every fiber triple, which
// plastic flow moves (the paper's future work, section 5: "a crease like a
// fold line forms and does not come out").
//
// Per triple (a, b, c) of a row or column, with e1 = x_b - x_a, e2 = x_c - x_b,
// q = e2 - e1 and the fold axis t across the fiber (the cross fiber's chord
// through b: x(j-1,k) - x(j+1,k) for a row triple, x(j,k+1) - x(j,k-1) for a
// column triple, one-sided on the border), the fiber's signed angle
//
//   phi = atan2(det(e1, e2, t^), e1.e2 - (e1.t^)(e2.t^))
//
// is positive where the fiber turns toward the cloth's front, the side of the
// lattice normal (x(j,k+1) - x(j,k)) x (x(j+1,k) - x(j,k)) (-z for a cloth at
// rest in the xy plane; the infill's normal): a valley seen from the front.
// A crease of rest angle phi_r is the fold's q in each link's own frame
// (u = e / |e| along the link, n = t x e / |t x e| its side's front normal):
//
//   r1 = s ((cos phi_r - 1) u1 + sin phi_r n1),   r2 = s ((1 - cos phi_r) u2 + sin phi_r n2),
//   E = 1/4 k_b |q - r1|^2 + 1/4 k_b |q - r2|^2,
//
// s the rest link length along the fiber. A fiber folded by phi_r (links of
// length s) has q = r1 = r2: no force at all; folded by as much to the other
// side, E = 2 k_b s^2 sin^2 phi_r, so a crease keeps its side (mountain or
// valley); flat, it is pushed toward its side. phi_r = 0 is bending_springs'
// 1/2 k_b |q|^2 exactly (computed as it is: the same bits). The frames are
// those of the links, not of the fold's bisector, so they stay defined folded
// flat (|phi_r| = pi, where both sides are the same fold). The gradient
// (creased_bending.cpp) is written out on the five nodes a, b, c and the
// axis' ends; the Hessian is its forward-mode derivative (Eigen's AutoDiff),
// made only for the creased triples where the implicit stepper linearizes.
//
// Plastic flow (scene.hpp, Creases): at the start of every output frame, each
// triple's present signed angle theta (phi above) moves its held angle theta_h
// (theta low-passed with time constant set_time: what the fold has been for a
// while; a flapping cloth's kinks, there and gone within a period and on
// either side, leave it low) and its rest angle theta_r, over the frame
// before (dt = 1 / fps): toward theta_h with time constant set_time where
// |theta_h| > max(|theta_r|, yield_angle) on theta_r's side (or theta_r = 0):
// a fold held past the yield sets; and toward theta where theta is flatter
// than theta_r or on its other side (a crease held flatter, or turned inside
// out) with time constant relax_time / phi,
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
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "flagsim/coarse_physics/bending_springs.hpp"
#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/force_term.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::physics {

/// The rest angle, rad, of every triple of bending_triples(lattice) (same
/// order) from `folds`: each fold's signed angle (positive: a valley seen from
/// the front, above) on the triples its line crosses, shared between the two
/// fiber nodes either side of it in proportion to their nearness (the total
/// turning across the line is the fold's); held within [-pi, pi].
/// A line within a link of the edge is moved onto the first interior node.
std::vector<double> fold_rest_angles(std::span<const Fold> folds, const Lattice& lattice);

/// The term's memory at t = 0: the rest angles of `folds` (fold_rest_angles),
/// then the held angles (0: nothing has been held yet), rad.
std::vector<double> initial_crease_memory(std::span<const Fold> folds, const Lattice& lattice);

/// Bounds on the absolute row sums of the crease part's Hessian, over k_b,
/// at a triple's fiber nodes and at its axis' ends, for links within 30% of
/// their rest length and any rest angle: the explicit integrators' stability
/// limit (add_stiffness_bound). Sampled in tests/coarse_physics/creased_bending_test.cpp.
inline constexpr double kCreaseRowSum = 56.0;
inline constexpr double kAxisRowSum = 14.0;

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

  /// The present signed angle of every triple at `x_m`, rad (phi above; the
  /// plastic step's theta): positive where the fiber turns toward the front.
  std::vector<double> angles(std::span<const Vec3> x_m) const;
  /// phi of every triple at `x_m`: the share of a crease's unfolding its hinge takes.
  std::vector<double> hinge_shares(std::span<const Vec3> x_m) const;

 private:
  /// Where the implicit stepper linearized a creased triple: its five nodes
  /// (a, b, c, the axis' ends) and the 15 x 15 Hessian of its crease part.
  struct CreasedBlock {
    std::array<std::uint32_t, 5> nodes;
    Eigen::Matrix<double, 15, 15> hessian;
  };

  std::vector<BendingTriple> triples_;
  /// [triples] the ends (p, m) of each triple's fold axis t = x_p - x_m
  std::vector<std::array<std::uint32_t, 2>> axis_;
  std::vector<double> spacing_m_;      ///< [triples] s, the rest link length along the fiber
  std::vector<double> memory_;         ///< [2 triples] theta_r, then theta_h
  std::vector<Mat3> hessian_;          ///< [triples] the plain part's d2E/dq2 (plain k_b I)
  std::vector<CreasedBlock> creased_;  ///< the creased triples at the last linearization
  Creases creases_;
  double stretch_modulus_n_m_ = 0.0;  ///< Y, for the tension across a crease
  double hinge_tension_n_m_ = 0.0;    ///< T_c = D / w^2
  double frame_s_ = 0.0;
  double plain_ = 1.0;  ///< 1 with the plain bending, 0 for the crease's part alone
};

}  // namespace flagsim::physics
