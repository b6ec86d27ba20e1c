#pragma once
// The solids a cloth meets ([pole] radius, [ground]; issue 31): a vertical
// cylinder whose surface touches the pinned edge, and a horizontal plane.
//
// Contact is a projection after each step (every backend, and the infill's
// dense lattice): a node found inside a solid is put back on its surface, the
// part of its velocity (relative to the solid) into the solid is removed
// (inelastic), and Coulomb friction takes at most mu times that removed
// speed off the tangential velocity. Projection adds no stiffness, so no
// stability limit changes; it is exact for the nodes (no node is ever inside
// a solid at the end of a step). Given the lattice, the links are kept out of
// the pole too: a link whose segment cuts the cylinder (seen from above, where
// the cylinder is a disc) has its two ends pushed out along the normal at its
// closest point, in proportion to their barycentric weights (a position-based
// edge contact), so that a coarse cloth wraps the pole as a polygon around it
// rather than as chords through it, and the dense lattice the infill lays
// along those chords stays outside. The ground needs no link pass (a segment
// whose ends are above a plane is above it).
//
// With [contact] (the full-lattice modes) the physics' projection also keeps
// the cloth's non-neighbouring parts apart (self_contact.hpp): at least the
// thickness, and at least a quarter of the lattice's spacing, the tightest
// fold a lattice can hold.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "flagsim/coarse_physics/pin_motion.hpp"
#include "flagsim/coarse_physics/self_contact.hpp"
#include "flagsim/core/lattice.hpp"
#include "flagsim/core/vec3.hpp"
#include "flagsim/scene/scene.hpp"

namespace flagsim::physics {

class Obstacles {
 public:
  /// The scene's solids, or nullopt when it has none (then nothing runs: the
  /// frames are the bits of before).
  static std::optional<Obstacles> of(const Scene& scene);
  /// The physics' contact on `lattice`: the solids, keeping its links (rows,
  /// columns, both diagonals) out of the pole as well as its nodes, and with
  /// [contact] its self-contact; nullopt when the scene has none of them.
  static std::optional<Obstacles> of(const Scene& scene, const Lattice& lattice);

  /// Projects the nodes not `pinned` (all when it is empty) out of the solids at
  /// time t (the pole moves with the pins), positions [n] m, velocities [n]
  /// m/s (may be empty: positions only). Returns how many nodes the node pass
  /// moved plus how many links the link pass pushed out (0: nothing moved).
  /// `came_from_m` [n] (may be empty): where each node was before the move
  /// being corrected, outside the solids; a node found inside the pole then
  /// goes out on the side it came from, not the side nearest to it (a lattice
  /// laid anew each frame, like the infill's, may put neighbours on either
  /// side of the axis, and they must not come out on opposite sides).
  /// With [contact], then keeps the cloth's parts `thickness` apart
  /// (self_contact.hpp), each node on the side of each triangle it was on in
  /// `step_start_m` [n] (the positions the step began from; empty: the side
  /// it is on now); the pushes are counted in the return value too.
  int project(double time_s, std::span<Vec3> x_m, std::span<Vec3> v_m_s,
              std::span<const std::uint8_t> pinned, std::span<const Vec3> came_from_m = {},
              std::span<const Vec3> step_start_m = {});
  /// Whether a step must keep its start for project() ([contact]).
  bool self_contact() const { return self_.has_value(); }

  /// A lattice laid anew each frame (the infill's dense one), at time t, m:
  /// projects its nodes not `fixed` out of the solids as project() does (but
  /// a node under the ground comes up mirrored above it, its depth as
  /// height: the relief the infill gave it, not a fold in the floor), then,
  /// where any moved, lets the fibers around them take their rest lengths
  /// again while staying out (`rounds` Gauss-Seidel sweeps of the row and
  /// column links' lengths, each followed by the projection, over the box of
  /// nodes within `reach` links of a moved one; fixed nodes and those outside
  /// the box stay put). So the excess length a fiber has between coarse nodes
  /// that a solid cuts goes round the solid instead of into a stretch.
  /// Returns the number of nodes the first projection moved. For Obstacles
  /// made by of(scene) (the solids' nodes only: no links, no self-contact,
  /// which is the full-lattice modes' physics alone).
  int settle(double time_s, const Lattice& lattice, std::span<Vec3> x_m,
             std::span<const std::uint8_t> fixed, std::span<const Vec3> came_from_m, int rounds,
             int reach) const;

  /// Distance of `x_m` inside the nearest solid at time t, m (0: outside).
  double depth_m(double time_s, const Vec3& x_m) const;

 private:
  /// project() without the self-contact: the solids alone.
  int project_solids(double time_s, std::span<Vec3> x_m, std::span<Vec3> v_m_s,
                     std::span<const std::uint8_t> pinned, std::span<const Vec3> came_from_m) const;

  std::optional<SolidPole> pole_;
  std::optional<Ground> ground_;
  std::optional<SelfContact> self_;  ///< [contact]
  /// Pushes the links that cut the pole's disc out of it (see the top).
  int project_links(const Vec3& axis_m, const Vec3& pole_v_m_s, std::span<Vec3> x_m,
                    std::span<Vec3> v_m_s, std::span<const std::uint8_t> pinned) const;

  Vec3 axis_point_m_ = Vec3::Zero();                 ///< on the pole's axis, at rest
  std::vector<std::array<std::uint32_t, 2>> links_;  ///< node pairs kept out of the pole
  /// project_links' scratch: each node's side of the pole's square seen from
  /// above (Cohen-Sutherland outcodes). One Obstacles serves one cloth.
  mutable std::vector<std::uint8_t> outcodes_;
  PinMotion pins_{std::nullopt};
};

}  // namespace flagsim::physics
