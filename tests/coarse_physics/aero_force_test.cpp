#include "flagsim/coarse_physics/aero_force.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "finite_difference.hpp"
#include "flagsim/coarse_physics/cloth_model.hpp"
#include "scene_fixtures.hpp"
#include "tolerances.hpp"

namespace flagsim::physics {
namespace {

using test::kAnalyticRelTol;
using test::kGridWaveDriveShare;
using test::kPanelSmoothing;
using test::kResolutionAgreement;

Wind air(double drag, double lift, double friction = 0.0) {
  Wind wind;
  wind.drag = drag;
  wind.lift = lift;
  wind.friction = friction;
  wind.air_density_kg_m3 = 1.225;
  return wind;
}

// A right triangle of area 0.5 m^2 in the z = 0 plane, normal +z.
const Vec3 kA(0, 0, 0), kB(1, 0, 0), kC(0, 1, 0);

TEST(AeroForce, FlatPlateFacingTheFlowGetsTheTextbookDrag) {
  const double speed = 10.0, area = 0.5;
  const Vec3 f = triangle_aero_force(kA, kB, kC, Vec3(0, 0, speed), air(1.0, 0.5));
  const double expected = 0.5 * 1.225 * 1.0 * area * speed * speed;  // 1/2 rho C_d A U^2
  EXPECT_NEAR(f.z(), expected, kAnalyticRelTol * expected);
  EXPECT_NEAR(f.x(), 0.0, kAnalyticRelTol * expected);
  EXPECT_NEAR(f.y(), 0.0, kAnalyticRelTol * expected);
}

TEST(AeroForce, BothFacesCatchTheWind) {
  const Vec3 u(3.0, -1.0, 7.0);
  const Vec3 front = triangle_aero_force(kA, kB, kC, u, air(1.0, 0.5));
  const Vec3 back = triangle_aero_force(kA, kC, kB, u, air(1.0, 0.5));  // flipped normal
  EXPECT_LT((front - back).norm(), kAnalyticRelTol * front.norm());
  EXPECT_GT(front.dot(u), 0.0);  // pushed downstream
}

TEST(AeroForce, FlowAlongThePlateGivesNoForceButItsFriction) {
  EXPECT_EQ(triangle_aero_force(kA, kB, kC, Vec3(10, 3, 0), air(1.0, 0.5)).norm(), 0.0);
  EXPECT_EQ(triangle_aero_force(kA, kB, kC, Vec3::Zero(), air(1.0, 0.5, 0.015)).norm(), 0.0);
  // Skin friction: 1/2 rho C_f A |u_t| u_t, along the flow.
  const double area = 0.5, friction = 0.015;
  const Vec3 u(10, 3, 0);
  const Vec3 f = triangle_aero_force(kA, kB, kC, u, air(1.0, 0.5, friction));
  const Vec3 expected = 0.5 * 1.225 * friction * area * u.norm() * u;
  EXPECT_LT((f - expected).norm(), kAnalyticRelTol * expected.norm());
  // Tilted flow: friction takes the tangential part only; the normal part is drag's.
  const Vec3 tilted(6, 0, 8);
  const Vec3 with = triangle_aero_force(kA, kB, kC, tilted, air(1.0, 0.0, friction));
  const Vec3 without = triangle_aero_force(kA, kB, kC, tilted, air(1.0, 0.0));
  const Vec3 tangential(6, 0, 0);
  const Vec3 skin = 0.5 * 1.225 * friction * area * tangential.norm() * tangential;
  EXPECT_LT((with - without - skin).norm(), kAnalyticRelTol * with.norm());
}

TEST(AeroForce, LiftAtFortyFiveDegrees) {
  // u at 45 degrees to the normal: lift = 1/2 rho C_l A U^2 cos sin = 1/4 rho C_l A U^2,
  // perpendicular to u, in the plane of u and n.
  const double speed = 8.0, area = 0.5;
  const Vec3 u = speed * Vec3(1, 0, 1).normalized();
  const Vec3 lift = triangle_aero_force(kA, kB, kC, u, air(0.0, 0.7));
  const double expected = 0.25 * 1.225 * 0.7 * area * speed * speed;
  EXPECT_NEAR(lift.norm(), expected, kAnalyticRelTol * expected);
  EXPECT_NEAR(lift.dot(u), 0.0, kAnalyticRelTol * expected * speed);
  EXPECT_NEAR(lift.y(), 0.0, kAnalyticRelTol * expected);
  // Drag alone at 45 degrees: the normal component of the flow, (U cos 45)^2.
  const Vec3 drag = triangle_aero_force(kA, kB, kC, u, air(1.0, 0.0));
  EXPECT_NEAR(drag.z(), 0.5 * 1.225 * area * speed * speed * 0.5, kAnalyticRelTol * expected);
}

TEST(AeroForce, WholeFlatFlagFacingWindAndMovingWithIt) {
  Scene scene = test::small_cloth(5, 7);
  const ClothModel model = make_cloth_model(scene);
  Wind wind = air(1.0, 0.5);
  wind.velocity_m_s = Vec3(0, 0, 10);
  const AeroForce aero(model, wind, 0, scene.flag.areal_density_kg_m2, 0.0);
  const std::vector<Vec3> x = model.lattice.rest_positions();
  std::vector<Vec3> v(x.size(), Vec3::Zero()), f(x.size(), Vec3::Zero());
  aero.add_forces(x, v, f);
  Vec3 total = Vec3::Zero();
  for (const Vec3& fi : f) total += fi;
  const double expected = 0.5 * 1.225 * 1.0 * (1.0 * 0.8) * 100.0;
  EXPECT_NEAR(total.z(), expected, kAnalyticRelTol * expected * 10);
  // Cloth moving with the air feels nothing.
  std::fill(v.begin(), v.end(), wind.velocity_m_s);
  std::fill(f.begin(), f.end(), Vec3::Zero());
  aero.add_forces(x, v, f);
  for (const Vec3& fi : f) EXPECT_EQ(fi.norm(), 0.0);
}

TEST(AeroForce, TheLatticeForceIsEveryTriangleThirdAddedInTheTriangleLoopsOrderToTheBit) {
  // add_forces computes four triangles side by side and each node sums its
  // six thirds; a row of 10 cells exercises the lanes and the scalar tail, a
  // degenerate (collapsed) triangle and nodes moving with the air the zero
  // cases. Reference: one triangle at a time, as the cells' loop adds them.
  Scene scene = test::small_cloth(5, 11);
  const ClothModel model = make_cloth_model(scene);
  Wind wind = air(1.2, 0.7);
  wind.velocity_m_s = Vec3(9, 1, 2);
  wind.lift_at_pole = true;  // every triangle's lift, the pinned column's too
  const AeroForce aero(model, wind, 0, scene.flag.areal_density_kg_m2, 0.0);
  const Lattice& lattice = model.lattice;
  std::vector<Vec3> x = lattice.rest_positions(), v(x.size()), f(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double s = double(i);
    x[i] += 0.05 * Vec3(std::sin(1.3 * s), std::cos(0.7 * s), std::sin(2.1 * s + 0.4));
    v[i] = Vec3(std::cos(0.9 * s), 0.5 * std::sin(1.7 * s), 3.0 * std::cos(0.3 * s));
    f[i] = Vec3(0.1 * s, -0.2, 1e-3 * s);  // what the terms before it left there
  }
  x[lattice.index(2, 4)] = x[lattice.index(2, 3)];  // cell (2, 3)'s upper triangle collapses
  v[lattice.index(4, 10)] = wind.velocity_m_s;
  std::vector<Vec3> expected = f;
  for (int j = 0; j + 1 < lattice.rows; ++j)
    for (int k = 0; k + 1 < lattice.cols; ++k) {
      const std::size_t n00 = lattice.index(j, k), n01 = n00 + 1, n10 = lattice.index(j + 1, k),
                        n11 = n10 + 1;
      for (const auto& [a, b, c] :
           {std::array<std::size_t, 3>{n00, n01, n10}, std::array<std::size_t, 3>{n01, n11, n10}}) {
        const Vec3 u = (1.0 / 3.0) * ((wind.velocity_m_s + wind.velocity_m_s + wind.velocity_m_s) -
                                      (v[a] + v[b] + v[c]));
        const Vec3 third = (1.0 / 3.0) * triangle_aero_force(x[a], x[b], x[c], u, wind);
        expected[a] += third;
        expected[b] += third;
        expected[c] += third;
      }
    }
  aero.add_forces(x, v, f);
  for (std::size_t i = 0; i < f.size(); ++i) EXPECT_EQ(f[i], expected[i]) << i;
}

TEST(AeroForce, VelocityJacobianOfOneTriangleMatchesFiniteDifferences) {
  const Vec3 x0(0.1, 0.0, 0.02), x1(1.0, 0.1, -0.1), x2(0.0, 0.9, 0.2);
  const Wind wind = air(1.0, 0.5, 0.015);
  for (const Vec3& u : {Vec3(10, 0, 0), Vec3(3, -1, 7), Vec3(-2, 5, -4), Vec3(0.5, 0.2, 9)}) {
    const Mat3 analytic = triangle_aero_velocity_jacobian(x0, x1, x2, u, wind);
    const double h = test::kFiniteDifferenceStep * 10.0;
    for (int c = 0; c < 3; ++c) {
      Vec3 du = Vec3::Zero();
      du[c] = h;
      const Vec3 numeric = (triangle_aero_force(x0, x1, x2, u + du, wind) -
                            triangle_aero_force(x0, x1, x2, u - du, wind)) /
                           (2.0 * h);
      EXPECT_LT((analytic.col(c) - numeric).norm(), test::kFiniteDifferenceRelTol * analytic.norm())
          << "u = " << u.transpose() << " column " << c;
    }
  }
}

// The wind's damping (linearize, add_damping_product, add_damping_diagonal)
// against finite differences of its force in the velocities, on a jiggled
// cloth of `scene` in a 10 m/s wind with a cross component; `on_panels`: the
// cloth is finer than its panels.
void expect_damping_is_minus_force_velocity_jacobian(const Scene& scene, bool on_panels) {
  const ClothModel model = make_cloth_model(scene);
  AeroForce aero(model, *scene.wind, 0, scene.flag.areal_density_kg_m2, 0.0);
  EXPECT_EQ(aero.panels().same_lattice(), !on_panels);
  const std::vector<Vec3> x = test::jiggled(model.lattice, 0.1, 8);
  std::vector<Vec3> v = test::jiggled(model.lattice, 4.0, 9);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] -= model.lattice.rest_positions()[i];
  test::expect_derivative_is_minus_force_jacobian(aero, x, v, test::Wrt::kVelocity);
}

TEST(AeroForce, DampingIsMinusForceVelocityJacobian) {
  Scene scene = test::small_cloth(4, 5);
  scene.wind = Wind{};
  scene.wind->velocity_m_s = Vec3(10, 0, 1);
  expect_damping_is_minus_force_velocity_jacobian(scene, false);
}

TEST(AeroForce, DampingOnPanelsIsMinusForceVelocityJacobian) {
  // A cloth finer than its panels: C = W^T C_panels W, products and diagonal.
  Scene scene = test::small_cloth(9, 11);
  scene.wind = Wind{};
  scene.wind->velocity_m_s = Vec3(10, 0, 1);
  scene.wind->panel_m = 0.25;  // 4 x 4 panels on 1.0 x 0.8 m
  expect_damping_is_minus_force_velocity_jacobian(scene, true);
  // wind.lift_at_pole = true (the default is false): the panels at the held
  // edge keep their lift, in the force and in its velocity Jacobian alike.
  scene.wind->lift_at_pole = true;
  expect_damping_is_minus_force_velocity_jacobian(scene, true);
}

// A flag of the default size (1.5 x 1.0 m) on a rows x cols lattice, in 10 m/s wind.
Scene windy_flag(int rows, int cols) {
  Scene scene = test::small_cloth(rows, cols);
  scene.flag.width_m = 1.5;
  scene.flag.height_m = 1.0;
  scene.wind = Wind{};
  scene.wind->velocity_m_s = Vec3(10, 0, 0);
  return scene;
}

// A smooth flapping shape and motion at rest coordinates (x, y) of the flag: a
// wave of 1.9 flag lengths running toward the fly end at 7 m/s, growing from
// the pole, with a twist along the height.
Vec3 flapping_shape(double x, double y) {
  const double k = 2.0 * M_PI / (1.9 * 1.5);
  return Vec3(x, y, 0.25 * x * std::sin(k * x) * (1.0 + 0.3 * y));
}
Vec3 flapping_velocity(double x, double y) {
  const double k = 2.0 * M_PI / (1.9 * 1.5), omega = 7.0 * k;
  return Vec3(0.0, 0.0, -0.25 * x * omega * std::cos(k * x) * (1.0 + 0.3 * y));
}

TEST(AeroForce, OneShapeAndMotionGetsTheSameForceAtTwoResolutions) {
  // The same flapping cloth on 33 x 49 and 129 x 193 nodes: the same total
  // force, and the same force on each 0.25 m square of the flag (6 x 4
  // squares; a node on a square's side shares its force with its neighbour).
  constexpr std::size_t kSquaresX = 6, kSquaresY = 4;
  struct Result {
    Vec3 total = Vec3::Zero();
    std::vector<Vec3> squares = std::vector<Vec3>(kSquaresX * kSquaresY, Vec3::Zero());
  };
  const auto force_on = [](int rows, int cols) {
    const Scene scene = windy_flag(rows, cols);
    const ClothModel model = make_cloth_model(scene);
    const Lattice& lattice = model.lattice;
    AeroForce aero(model, *scene.wind, 0, scene.flag.areal_density_kg_m2, 0.0);
    std::vector<Vec3> x(lattice.node_count()), v(x.size()), f(x.size(), Vec3::Zero());
    for (int j = 0; j < lattice.rows; ++j)
      for (int k = 0; k < lattice.cols; ++k) {
        const double px = k * lattice.spacing_x_m, py = -j * lattice.spacing_y_m;
        x[lattice.index(j, k)] = flapping_shape(px, py);
        v[lattice.index(j, k)] = flapping_velocity(px, py);
      }
    aero.add_forces(x, v, f);
    Result result;
    const int per_x = (lattice.cols - 1) / int(kSquaresX),
              per_y = (lattice.rows - 1) / int(kSquaresY);
    for (int j = 0; j < lattice.rows; ++j)
      for (int k = 0; k < lattice.cols; ++k) {
        const Vec3& fi = f[lattice.index(j, k)];
        result.total += fi;
        // The squares this node lies in: one, two on a side, four at a corner.
        const auto squares = [](int node, int per, std::size_t count) {
          const std::size_t at = std::size_t(node / per);
          std::vector<std::size_t> in = {std::min(at, count - 1)};
          if (node % per == 0 && node > 0 && at < count) in.push_back(at - 1);
          return in;
        };
        const std::vector<std::size_t> sx = squares(k, per_x, kSquaresX),
                                       sy = squares(j, per_y, kSquaresY);
        for (const std::size_t a : sy)
          for (const std::size_t b : sx)
            result.squares[a * kSquaresX + b] += fi / double(sx.size() * sy.size());
      }
    return result;
  };
  const Result coarse = force_on(33, 49), fine = force_on(129, 193);
  EXPECT_GT(coarse.total.norm(), 5.0);  // N: the shape is loaded (measured 5.8 N)
  EXPECT_LT((coarse.total - fine.total).norm(), kResolutionAgreement * fine.total.norm())
      << coarse.total.transpose() << " vs " << fine.total.transpose();
  double largest = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < fine.squares.size(); ++i) {
    largest = std::max(largest, fine.squares[i].norm());
    worst = std::max(worst, (coarse.squares[i] - fine.squares[i]).norm());
  }
  EXPECT_LT(worst, kResolutionAgreement * largest) << "largest " << largest << " N";
}

// Rate at which the wind feeds a small travelling wave z = a sin(k x - w t)
// (wave speed c = w / k) on the flat flag: P / (2 E), P = sum f.v the power of
// the force's change from the flat cloth's, E = sum 1/2 m v^2; 1/s. For a
// linear mode E ~ exp(2 sigma t): this is sigma.
double wave_growth_rate(const Scene& scene, double wavelength_m, double speed_m_s) {
  const ClothModel model = make_cloth_model(scene);
  const Lattice& lattice = model.lattice;
  const AeroForce aero(model, *scene.wind, 0, scene.flag.areal_density_kg_m2, 0.0);
  const double k = 2.0 * M_PI / wavelength_m, omega = speed_m_s * k, a = 1e-4;
  const std::vector<Vec3> rest = lattice.rest_positions();
  std::vector<Vec3> x = rest, v(x.size(), Vec3::Zero()), base(x.size(), Vec3::Zero());
  aero.add_forces(rest, v, base);
  for (int j = 0; j < lattice.rows; ++j)
    for (int kk = 0; kk < lattice.cols; ++kk) {
      const std::size_t i = lattice.index(j, kk);
      const double px = kk * lattice.spacing_x_m;
      x[i].z() += a * std::sin(k * px);
      v[i].z() = -a * omega * std::cos(k * px);
    }
  std::vector<Vec3> f(x.size(), Vec3::Zero());
  aero.add_forces(x, v, f);
  double power = 0.0, energy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    power += (f[i] - base[i]).dot(v[i]);
    energy += 0.5 * model.mass_kg[i] * v[i].squaredNorm();
  }
  return power / (2.0 * energy);
}

// wind.lift_at_pole = false takes the lift off the column of panels that
// straddles the pole and nothing else: nodes beyond that column's reach (its
// panel nodes at 0 and 0.25 m spread over 0.5 m) get the same force to the
// bit, nodes within it another, and without lift the key changes nothing.
TEST(AeroForce, WithoutLiftAtThePoleOnlyThePanelsAtThePoleLoseTheirLift) {
  const Scene scene = windy_flag(33, 49);  // pinned on the left, panels of 0.25 m
  const ClothModel model = make_cloth_model(scene);
  std::vector<Vec3> x, v;
  for (int j = 0; j < model.lattice.rows; ++j)
    for (int k = 0; k < model.lattice.cols; ++k) {
      const Vec3 rest = model.lattice.rest_position(j, k);
      x.push_back(flapping_shape(rest.x(), rest.y()));
      v.push_back(flapping_velocity(rest.x(), rest.y()));
    }
  const auto forces = [&](double lift, bool at_pole) {
    Wind wind = *scene.wind;
    wind.lift = lift;
    wind.lift_at_pole = at_pole;
    const AeroForce aero(model, wind, 0, scene.flag.areal_density_kg_m2, 0.0);
    std::vector<Vec3> f(x.size(), Vec3::Zero());
    aero.add_forces(x, v, f);
    return f;
  };
  const std::vector<Vec3> with = forces(0.5, true), without = forces(0.5, false);
  int near_changed = 0, far = 0;
  for (int j = 0; j < model.lattice.rows; ++j)
    for (int k = 0; k < model.lattice.cols; ++k) {
      const std::size_t i = model.lattice.index(j, k);
      if (model.lattice.rest_position(j, k).x() > 0.5 + 1e-9) {
        EXPECT_EQ(with[i], without[i]) << "node " << j << ", " << k;
        ++far;
      } else if ((with[i] - without[i]).norm() > 1e-6 * with[i].norm()) {
        ++near_changed;
      }
    }
  EXPECT_GT(far, 0);
  EXPECT_GT(near_changed, model.lattice.rows * 10);  // most of the 17 columns within 0.5 m
  EXPECT_EQ(forces(0.0, true), forces(0.0, false));
}

TEST(AeroForce, TheShortestLatticeWavesAreNotDrivenByTheWind) {
  // The lift feeds a travelling wave slower than the wind at a rate that does
  // not fall with its wavenumber (rho C_l U (U - c) / (2 mu c) in a
  // linearisation): evaluated on the cloth's own triangles it drove the
  // lattice's shortest waves as hard as the flag-length wave. On 0.125 m panels a
  // wave of 5 cells (78 mm at 65 x 97) is not seen.
  Scene scene = windy_flag(65, 97);
  scene.wind->panel_m = 0.125;
  // The lift on the whole flag: without it at the pole the two panel sizes
  // would leave columns of different widths unlifted (0.125 m, half a cell).
  scene.wind->lift_at_pole = true;
  const double cell = 1.5 / 96.0, c = 7.0;
  const double long_wave = wave_growth_rate(scene, 1.9 * 1.5, c);
  const double short_wave = wave_growth_rate(scene, 5.0 * cell, c);
  EXPECT_GT(long_wave, 0.0);
  EXPECT_LT(std::abs(short_wave), kGridWaveDriveShare * long_wave)
      << short_wave << " against " << long_wave << " 1/s";
  // The same cloth with its own triangles as panels: the short wave grows as
  // fast as the long one (the artefact this test guards against).
  scene.wind->panel_m = 0.5 * cell;
  const double own_long = wave_growth_rate(scene, 1.9 * 1.5, c);
  const double own_short = wave_growth_rate(scene, 5.0 * cell, c);
  EXPECT_GT(own_short, 0.5 * own_long);
  // The long wave's rate hardly changes: 0.125 m hats average its slope.
  EXPECT_NEAR(long_wave, own_long, kPanelSmoothing * own_long);
  // The default, without the lift on the panels at the pole, likewise.
  scene.wind->panel_m = 0.125;
  scene.wind->lift_at_pole = false;
  const double default_long = wave_growth_rate(scene, 1.9 * 1.5, c);
  EXPECT_GT(default_long, 0.0);
  EXPECT_LT(std::abs(wave_growth_rate(scene, 5.0 * cell, c)), kGridWaveDriveShare * default_long);
}

TEST(AeroForce, ProjectedDampingIsPositiveSemidefinite) {
  // The lift's response is not symmetric; the projection keeps a damping
  // matrix the implicit stepper can solve with conjugate gradients.
  Scene scene = test::small_cloth(4, 5);
  scene.wind = Wind{};
  scene.wind->velocity_m_s = Vec3(10, 0, 3);
  const ClothModel model = make_cloth_model(scene);
  AeroForce aero(model, *scene.wind, 0, scene.flag.areal_density_kg_m2, 0.0);
  const std::vector<Vec3> x = test::jiggled(model.lattice, 0.1, 10);
  const std::vector<Vec3> v(x.size(), Vec3::Zero());
  aero.linearize(x, v, Definiteness::kProjected);
  double loaded = 0.0;
  for (unsigned seed = 0; seed < 50; ++seed) {
    const std::vector<Vec3> dv = test::jiggled(model.lattice, 1.0, 100 + seed);
    std::vector<Vec3> out(x.size(), Vec3::Zero());
    aero.add_damping_product(dv, out);
    double quadratic = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) quadratic += dv[i].dot(out[i]);
    EXPECT_GE(quadratic, 0.0);
    loaded = std::max(loaded, quadratic);
  }
  EXPECT_GT(loaded, 0.0);
}

}  // namespace
}  // namespace flagsim::physics
