#include "flagsim/coarse_physics/obstacles.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "flagsim/coarse_physics/fiber_settle.hpp"

namespace flagsim::physics {
namespace {

// v (m/s) after an inelastic contact with normal n (unit, out of the solid) on
// a solid moving at `solid_v`: no speed into the solid; Coulomb friction takes
// at most mu times the removed speed off the sliding speed.
Vec3 contact_velocity(const Vec3& v, const Vec3& solid_v, const Vec3& n, double mu) {
  const Vec3 relative = v - solid_v;
  const double normal = relative.dot(n);
  if (normal >= 0.0) return v;  // leaving already
  Vec3 tangential = relative - normal * n;
  const double sliding = tangential.norm();
  const double taken = mu * -normal;
  tangential = sliding <= taken ? Vec3::Zero() : Vec3(tangential * (1.0 - taken / sliding));
  return solid_v + tangential;
}

}  // namespace

std::optional<Obstacles> Obstacles::of(const Scene& scene) {
  if (!scene.solid_pole && !scene.ground) return std::nullopt;
  Obstacles obstacles;
  obstacles.pole_ = scene.solid_pole;
  obstacles.ground_ = scene.ground;
  if (scene.solid_pole)
    obstacles.axis_point_m_ = scene.flag.origin_m - Vec3(scene.solid_pole->radius_m, 0.0, 0.0);
  obstacles.pins_ = PinMotion(scene.pole);
  return obstacles;
}

std::optional<Obstacles> Obstacles::of(const Scene& scene, const Lattice& lattice) {
  std::optional<Obstacles> obstacles = of(scene);
  if (scene.contact) {
    if (!obstacles) obstacles = Obstacles();
    // A lattice holds no fold tighter than about a quarter of its spacing:
    // its layers are kept that far apart, the cloth's thickness at least.
    const double held = std::max(scene.contact->thickness_m,
                                 0.25 * std::min(lattice.spacing_x_m, lattice.spacing_y_m));
    obstacles->self_.emplace(lattice, held);
  }
  if (!obstacles || !obstacles->pole_) return obstacles;
  auto& links = obstacles->links_;
  // Rows, columns and both diagonals: the diagonals keep a cell's middle out.
  for (int j = 0; j < lattice.rows; ++j) {
    for (int k = 0; k < lattice.cols; ++k) {
      const auto a = std::uint32_t(lattice.index(j, k));
      if (k + 1 < lattice.cols) links.push_back({a, std::uint32_t(lattice.index(j, k + 1))});
      if (j + 1 < lattice.rows) links.push_back({a, std::uint32_t(lattice.index(j + 1, k))});
      if (j + 1 < lattice.rows && k + 1 < lattice.cols)
        links.push_back({a, std::uint32_t(lattice.index(j + 1, k + 1))});
      if (j + 1 < lattice.rows && k > 0)
        links.push_back({a, std::uint32_t(lattice.index(j + 1, k - 1))});
    }
  }
  return obstacles;
}

int Obstacles::project_links(const Vec3& axis_m, const Vec3& pole_v_m_s, std::span<Vec3> x_m,
                             std::span<Vec3> v_m_s, std::span<const std::uint8_t> pinned) const {
  const double radius = pole_->radius_m;
  const bool velocities = !v_m_s.empty();
  int pushed = 0;
  // Which side of the disc's square each node lies on, seen from above (bit 0
  // x below it, 1 above, 2 z below, 3 above): a link whose two ends share a
  // bit lies wholly beside the square and cannot cut the disc. Most links do:
  // they are passed over on two bytes instead of six coordinates, every substep.
  const auto outcode = [&](const Vec3& p) {
    const double x = p.x() - axis_m.x(), z = p.z() - axis_m.z();
    return std::uint8_t((x < -radius ? 1 : 0) | (x > radius ? 2 : 0) | (z < -radius ? 4 : 0) |
                        (z > radius ? 8 : 0));
  };
  outcodes_.resize(x_m.size());
  for (std::size_t i = 0; i < x_m.size(); ++i) outcodes_[i] = outcode(x_m[i]);
  for (const auto& [a, b] : links_) {
    if (outcodes_[a] & outcodes_[b]) continue;
    const double ma = !pinned.empty() && pinned[a] ? 0.0 : 1.0;  // inverse masses, relative
    const double mb = !pinned.empty() && pinned[b] ? 0.0 : 1.0;
    if (ma + mb == 0.0) continue;
    // Seen from above: the segment p(t) = pa + t (pb - pa) against the disc.
    const double ax = x_m[a].x() - axis_m.x(), az = x_m[a].z() - axis_m.z();
    const double dx = x_m[b].x() - x_m[a].x(), dz = x_m[b].z() - x_m[a].z();
    const double length2 = dx * dx + dz * dz;
    if (length2 == 0.0) continue;
    // Most links are far from the pole: rejected without a division. The
    // closest point is inside the segment when 0 < -a.d < |d|^2 (at an end it
    // is the node pass's), and its distance^2 is (a x d)^2 / |d|^2.
    const double along = -(ax * dx + az * dz), across = ax * dz - az * dx;
    if (along <= 0.0 || along >= length2 || across * across >= radius * radius * length2) continue;
    const double t = along / length2;
    const double cx = ax + t * dx, cz = az + t * dz;
    const double distance2 = cx * cx + cz * cz;
    if (distance2 >= radius * radius) continue;
    const double distance = std::sqrt(distance2);
    // Through the axis (never met in practice): out on the left of a -> b.
    const Vec3 n =
        distance > 0.0 ? Vec3(cx / distance, 0.0, cz / distance) : Vec3(-dz, 0.0, dx).normalized();
    // The constraint (p(t) - axis).n >= R has gradient (1 - t) n at a, t n at b.
    const double wa = (1.0 - t) * ma, wb = t * mb;
    const double lambda = (radius - distance) / ((1.0 - t) * wa + t * wb);
    x_m[a] += lambda * wa * n;
    x_m[b] += lambda * wb * n;
    outcodes_[a] = outcode(x_m[a]);
    outcodes_[b] = outcode(x_m[b]);
    ++pushed;
    if (!velocities) continue;
    // Inelastic: the contact point's speed into the pole is removed the same way.
    const double approach = ((1.0 - t) * v_m_s[a] + t * v_m_s[b] - pole_v_m_s).dot(n);
    if (approach >= 0.0) continue;
    const double impulse = -approach / ((1.0 - t) * wa + t * wb);
    v_m_s[a] += impulse * wa * n;
    v_m_s[b] += impulse * wb * n;
  }
  return pushed;
}

int Obstacles::project(double time_s, std::span<Vec3> x_m, std::span<Vec3> v_m_s,
                       std::span<const std::uint8_t> pinned, std::span<const Vec3> came_from_m,
                       std::span<const Vec3> step_start_m) {
  int moved = project_solids(time_s, x_m, v_m_s, pinned, came_from_m);
  if (self_) moved += self_->project(x_m, v_m_s, pinned, step_start_m);
  return moved;
}

int Obstacles::project_solids(double time_s, std::span<Vec3> x_m, std::span<Vec3> v_m_s,
                              std::span<const std::uint8_t> pinned,
                              std::span<const Vec3> came_from_m) const {
  int moved = 0;
  const bool velocities = !v_m_s.empty();
  Vec3 axis = Vec3::Zero(), pole_v = Vec3::Zero();
  double radius = 0.0;
  if (pole_) {
    axis = axis_point_m_ + pins_.offset_m(time_s);
    pole_v = pins_.velocity_m_s(time_s);
    radius = pole_->radius_m;
  }
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    if (!pinned.empty() && pinned[i]) continue;
    Vec3& x = x_m[i];
    bool moved_this = false;
    if (pole_) {
      const double dx = x.x() - axis.x(), dz = x.z() - axis.z();
      const double r2 = dx * dx + dz * dz;
      if (r2 < radius * radius) {
        // Out along the radius through the node; with `came_from_m`, turned
        // towards where the node came from the deeper it is (through the axis
        // the radius says nothing, and neighbours may sit on either side).
        double ox = dx, oz = dz;
        if (!came_from_m.empty()) {
          const double depth = 1.0 - std::sqrt(r2) / radius;  // 0 on the surface, 1 on the axis
          const double fx = came_from_m[i].x() - axis.x(), fz = came_from_m[i].z() - axis.z();
          const double f = std::hypot(fx, fz), own = std::sqrt(r2);
          ox = (own > 0.0 ? (1.0 - depth) * dx / own : 0.0) + (f > 0.0 ? depth * fx / f : 0.0);
          oz = (own > 0.0 ? (1.0 - depth) * dz / own : 0.0) + (f > 0.0 ? depth * fz / f : 0.0);
        }
        const double r = std::hypot(ox, oz);
        // On the axis itself (never met in practice): out towards the fly end.
        const Vec3 n = r > 0.0 ? Vec3(ox / r, 0.0, oz / r) : Vec3::UnitX();
        x.x() = axis.x() + radius * n.x();
        x.z() = axis.z() + radius * n.z();
        if (velocities) v_m_s[i] = contact_velocity(v_m_s[i], pole_v, n, pole_->friction);
        moved_this = true;
      }
    }
    if (ground_ && x.y() < ground_->height_m) {
      x.y() = ground_->height_m;
      if (velocities)
        v_m_s[i] = contact_velocity(v_m_s[i], Vec3::Zero(), Vec3::UnitY(), ground_->friction);
      moved_this = true;
    }
    moved += moved_this ? 1 : 0;
  }
  // Counted too: a caller that writes back only when something moved (Bullet's)
  // must not drop the links' corrections when no node was inside (it did, and
  // Bullet's coarse links cut the pole by up to 14 mm of its 40).
  if (pole_ && !links_.empty()) moved += project_links(axis, pole_v, x_m, v_m_s, pinned);
  return moved;
}

int Obstacles::settle(double time_s, const Lattice& lattice, std::span<Vec3> x_m,
                      std::span<const std::uint8_t> fixed, std::span<const Vec3> came_from_m,
                      int rounds, int reach) const {
  // Node contact only: the per-row projections below index by row.
  assert(links_.empty() && !self_);
  // Which nodes the projection moves: their box, widened by `reach`.
  std::vector<Vec3> before(x_m.begin(), x_m.end());
  // A node under the ground first comes up mirrored above it (y -> 2h - y),
  // not onto it: the part of a wrinkle the infill laid under the floor is
  // relief above it, and a reflection keeps that part's fiber lengths. Laid
  // flat on the floor, a compressed lattice folded over itself in the
  // floor's plane (banner_ground: crossing triangles in 32 of 121 frames,
  // none mirrored; its max strain 2.2% -> 1.2%).
  int mirrored = 0;
  if (ground_) {
    for (std::size_t i = 0; i < x_m.size(); ++i) {
      if ((!fixed.empty() && fixed[i]) || !(x_m[i].y() < ground_->height_m)) continue;
      x_m[i].y() = 2.0 * ground_->height_m - x_m[i].y();
      ++mirrored;
    }
  }
  const int moved = project_solids(time_s, x_m, {}, fixed, came_from_m) + mirrored;
  if (moved == 0 || rounds <= 0) return moved;
  // The projection after each sweep, over the box's rows only (nodes outside
  // it do not move in a sweep): over the whole lattice it was most of the
  // pass's time when the box is a strip along the pole.
  settle_fibers(
      lattice, x_m, before, fixed, rounds, reach,
      [](std::size_t, std::size_t, double rest_m) { return rest_m; },
      [&](int ja, int jb, int ka, int kb) {
        const auto row_part = [&](auto span, int j) {
          return span.empty()
                     ? span
                     : span.subspan(lattice.index(j, ka), std::size_t(kb) - std::size_t(ka) + 1);
        };
        for (int j = ja; j <= jb; ++j)
          project_solids(time_s, row_part(x_m, j), {}, row_part(fixed, j),
                         row_part(came_from_m, j));
        return true;
      });
  return moved;
}

double Obstacles::depth_m(double time_s, const Vec3& x_m) const {
  double depth = 0.0;
  if (pole_) {
    const Vec3 axis = axis_point_m_ + pins_.offset_m(time_s);
    const double r = std::hypot(x_m.x() - axis.x(), x_m.z() - axis.z());
    depth = std::max(depth, pole_->radius_m - r);
  }
  if (ground_) depth = std::max(depth, ground_->height_m - x_m.y());
  return depth;
}

}  // namespace flagsim::physics
