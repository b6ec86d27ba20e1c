#pragma once
// The creases of the coarse physics ([creases], coarse_physics/creased_bending.hpp)
// drawn on the dense lattice: each crease line where it lies, at dense
// resolution, as the ridge its hinge leaves in the cloth (issue 32).
//
// Where: a fold line between two coarse nodes is held by the physics as two
// rest angles, shared in proportion to the nodes' nearness
// (fold_rest_angles); along each coarse fiber, a run of creased triples is
// one crease line (a run on one side), at their angle-weighted mean place (which
// gives back the fold's own place, between coarse lines) with their summed angle theta_r.
//
// What: the coarse cloth shows theta_c of it, the signed turning of the coarse
// fiber across the run (on the crease's side, or against it). The rest, theta_r - theta_c, is a
// crease the coarse lattice cannot hold: pulled by the tension T, a hinge of width w in a sheet of
// rigidity D is flattened but for a ridge: the sheet beside it bends back
// over lambda = sqrt(D / T) (D y'''' = T y'', y ~ exp(-|x| / lambda)); the
// hinge's moment (D / w)(theta_r - theta_k) balances the sheet's D theta_k /
// (2 lambda), so the ridge's kink is theta_k = (theta_r - theta_c) / (1 + w /
// (2 lambda)) and its height a = theta_k lambda / 2:
//
//   offset along the normal at distance x from the line:  a exp(-|x| / lambda).
//
// lambda is capped at a dense link (the ridge the dense lattice can show; under
// little tension the coarse cloth itself shows the fold: theta_c ~ theta_r, no
// ridge), theta_k at 0.4 rad (crease_ridges.cpp, kMostKink). With a 10
// m/s wind (T ~ 100 N/m) and D = 1e-4 N m: lambda = 1 mm, a 2.5 rad crease
// flattened by the physics leaves a ridge of 0.8 mm on a dense link of 8 mm:
// 12 degrees of turning on the line against the cloth's median of about 1.
// A crease keeps its side (creased_bending.hpp: a positive rest angle folds
// toward the front, the dense lattice's normal, row tangent x column
// tangent): the ridge of a fold toward the front (a valley seen from it)
// stands behind the surface, against the normal, and one toward the back in front.
//
// The part the coarse cloth shows, theta_c, the smooth surface rounds over the
// coarse cells either side. It is sharpened onto the crease's own line: along
// each dense fiber crossing it, between a coarse cell before and after the
// line, the surface is replaced (along its normal) by its two tangents there,
// which meet in a kink on the line turning by as much as the surface did; in
// full where the coarse cloth shows all of the crease, not at all where it
// shows half or less (there the turning across the line is the cloth's own
// waves, which a flattened crease does not gather): the blend
// clamp(2 theta_c / theta_r - 1, 0, 1).
#include <cstdint>
#include <span>
#include <vector>

#include "flagsim/core/lattice.hpp"
#include "flagsim/infill/cell_grid.hpp"

namespace flagsim::infill {

/// The material the ridges are made of.
struct CreaseRidgeParams {
  double rigidity_j = 1.0e-4;          ///< D, N m ([bending])
  double width_m = 1.0e-3;             ///< w, the hinge ([creases] width)
  double stretch_modulus_n_m = 2.0e4;  ///< Y, for the tension (flag.stretch_modulus)
};

/// Infill mode's creases, on the dense lattice itself: `ridges` made on
/// CellGrid::of(fine, J, K) (a grid of one dense cell a cell, so each dense
/// triple's rest angle is a "coarse" one), their offsets laid on `positions_m`
/// along its own normals (row tangent x column tangent), what the cloth
/// already shows of each crease read from `positions_m` itself. Nodes `held`
/// (the keyframed corners) stay. `normals` and `copy` are scratch [J*K].
void add_dense_ridges(class CreaseRidges& ridges, const Lattice& fine, std::span<Vec3> positions_m,
                      std::span<const std::uint8_t> held, std::vector<Vec3>& normals,
                      std::vector<Vec3>& copy);

class CreaseRidges {
 public:
  CreaseRidges(const Lattice& fine, const CellGrid& grid, const CreaseRidgeParams& params);

  /// The coarse physics' rest angles, rad: every row triple then every column
  /// triple of the coarse lattice (bending_triples' order); more entries (its
  /// held angles) are ignored.
  void set_rest(std::span<const double> coarse_rest_rad);
  /// Whether any coarse triple holds a crease.
  bool any() const;

  /// Every dense node's offset along the surface's normal, m, for the coarse
  /// nodes `coarse_m` [Jc*Kc] (0 where no crease is): the ridges of the
  /// rows' creases (lines along columns) plus those of the columns', and the
  /// folds the coarse cloth shows sharpened onto their lines.
  /// @param surface_m  [J*K] the dense surface the offsets are taken from (3.1)
  /// @param normals    [J*K] its unit normals
  const std::vector<double>& offsets(std::span<const Vec3> coarse_m,
                                     std::span<const Vec3> surface_m,
                                     std::span<const Vec3> normals);

 private:
  /// One crease line on a coarse fiber: its place (coarse node index,
  /// fractional), its ridge's height and decay length.
  struct Ridge {
    double place = 0.0;
    double height_m = 0.0;  ///< along the normal: negative for a fold toward the front
    double decay_m = 0.0;
    double sharpen = 0.0;  ///< how much of the surface's turning across it goes onto the line
  };
  /// The ridges on coarse fiber `fiber` of one family (rows: coarse row
  /// `fiber`, its creases along k), into `out` (cleared first).
  void find_ridges(std::span<const Vec3> coarse_m, bool rows, int fiber,
                   std::vector<Ridge>& out) const;
  /// Adds the ridges of one family to offsets_, and its creases' sharpening.
  void add_family(bool rows, std::span<const Vec3> surface_m, std::span<const Vec3> normals);

  Lattice fine_;
  CellGrid grid_;
  CreaseRidgeParams params_;
  std::vector<double> rest_;                    ///< [coarse triples] theta_r
  std::vector<double> offsets_;                 ///< [J*K], m
  std::vector<std::vector<Ridge>> row_ridges_;  ///< [Jc]: each coarse row's
  std::vector<std::vector<Ridge>> col_ridges_;  ///< [Kc]: each coarse column's
};

}  // namespace flagsim::infill
