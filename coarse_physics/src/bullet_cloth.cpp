#include "flagsim/coarse_physics/bullet_cloth.hpp"

#include <BulletSoftBody/btDefaultSoftBodySolver.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "flagsim/coarse_physics/cloth_state.hpp"
#include "flagsim/coarse_physics/force_terms.hpp"
#include "flagsim/core/stop_request.hpp"

namespace flagsim::physics {

std::string bullet_version() {
  const int version = btGetVersion();  // e.g. 324
  return fmt::format("{}.{:02d}", version / 100, version % 100);
}
namespace {

btVector3 to_bt(const Vec3& v) {
  return btVector3(v.x(), v.y(), v.z());
}
Vec3 from_bt(const btVector3& v) {
  return Vec3(v.x(), v.y(), v.z());
}

void pre_tick(btDynamicsWorld* world, btScalar dt) {
  static_cast<BulletCloth*>(world->getWorldUserInfo())->before_substep(dt);
}

}  // namespace

double bullet_link_stiffness(double fraction, int iterations) {
  return std::clamp(fraction / double(std::max(1, iterations)), 0.0, 1.0);
}

// Bullet's objects, in construction order (destroyed in reverse).
struct BulletCloth::World {
  btSoftBodyRigidBodyCollisionConfiguration collision_config;
  btCollisionDispatcher dispatcher{&collision_config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver constraint_solver;
  btDefaultSoftBodySolver soft_solver;
  btSoftRigidDynamicsWorld world{&dispatcher, &broadphase, &constraint_solver, &collision_config,
                                 &soft_solver};
  std::unique_ptr<btSoftBody> body;
  double time_s = 0.0;  // time at the start of the coming substep

  ~World() {
    if (body) world.removeSoftBody(body.get());
  }
};

BulletCloth::BulletCloth(const Scene& scene, std::shared_ptr<const ClothModel> model)
    : model_(std::move(model)),
      obstacles_(Obstacles::of(scene, model_->lattice)),
      world_(std::make_unique<World>()) {
  rest_m_ = model_->lattice.rest_positions();
  const std::size_t n = rest_m_.size();
  terms_ = make_force_terms(scene, *model_, {.stretch = false, .gravity = false});
  effects_ = physics_effects(scene, *model_);
  forces_n_.assign(n, Vec3::Zero());

  // Substep: kStabilitySafety of the smallest of the link limit (f = 1) and
  // the explicit terms' limits.
  double link_limit = std::numeric_limits<double>::infinity();
  auto inverse_mass = [&](std::size_t i) {
    return model_->pinned[i] ? 0.0 : 1.0 / model_->mass_kg[i];
  };
  for (const LinkFamily& family : model_->links)
    for_each_link(*model_, family, [&](std::size_t a, std::size_t b, double k, double) {
      const double w = inverse_mass(a) + inverse_mass(b);
      if (w > 0.0 && k > 0.0) link_limit = std::min(link_limit, 1.0 / std::sqrt(k * w));
    });
  stable_substep_s_ = std::min(link_limit, explicit_stability_limit(*model_, terms_));
  frame_s_ = 1.0 / scene.fps;
  substeps_per_frame_ =
      physics::substeps_per_frame(frame_s_, stable_substep_s_, scene.solver.substeps);
  const double dt = substep_s();

  // The world: gravity from the world info, no air (our wind), no collisions.
  btSoftRigidDynamicsWorld& world = world_->world;
  const Vec3 g = scene.gravity ? scene.gravity->acceleration_m_s2 : Vec3::Zero();
  world.setGravity(to_bt(g));
  btSoftBodyWorldInfo& info = world.getWorldInfo();
  info.m_gravity = to_bt(g);
  info.air_density = 0;
  info.water_density = 0;
  info.m_broadphase = &world_->broadphase;
  info.m_dispatcher = &world_->dispatcher;
  info.m_sparsesdf.Initialize();

  // Nodes at rest, with their masses (0: pinned) given up front.
  std::vector<btVector3> x(n);
  std::vector<btScalar> m(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = to_bt(rest_m_[i]);
    m[i] = model_->pinned[i] ? 0.0 : model_->mass_kg[i];
  }
  world_->body = std::make_unique<btSoftBody>(&info, int(n), x.data(), m.data());
  btSoftBody& body = *world_->body;
  // One material per distinct kLST (a handful: families x border x node masses).
  std::vector<std::pair<double, btSoftBody::Material*>> materials;
  auto material_for = [&](double klst) {
    for (auto& [value, material] : materials)
      if (value == klst) return material;
    btSoftBody::Material* material = body.appendMaterial();
    material->m_kLST = klst;
    material->m_kAST = 0;
    material->m_kVST = 0;
    materials.emplace_back(klst, material);
    return material;
  };
  const int iterations = scene.solver.iterations.value_or(10);
  for (const LinkFamily& family : model_->links)
    for_each_link(*model_, family, [&](std::size_t a, std::size_t b, double k, double) {
      const double w = inverse_mass(a) + inverse_mass(b);
      if (w == 0.0 || k <= 0.0) return;  // between two pins: nothing to solve
      body.appendLink(int(a), int(b),
                      material_for(bullet_link_stiffness(k * dt * dt * w, iterations)));
    });
  btSoftBody::Config& cfg = body.m_cfg;
  cfg.piterations = iterations;
  cfg.kDP = 1.0 - model_->velocity_damping(dt);
  cfg.kDG = 0;
  cfg.kLF = 0;
  cfg.collisions = 0;
  // Rest lengths and link constants from the rest positions, now: Bullet
  // would otherwise compute them at the first step, from the perturbed start.
  body.updateConstants();
  body.m_bUpdateRtCst = false;
  world.addSoftBody(&body);
  world.setInternalTickCallback(&pre_tick, this, /*isPreTick=*/true);

  // The start: rest plus the scene's seeded perturbation (free nodes only).
  set_state(initial_state(scene, *model_));
}

BulletCloth::~BulletCloth() = default;

void BulletCloth::set_state(const ClothState& state) {
  state_ = state;
  btSoftBody& body = *world_->body;
  for (std::size_t i = 0; i < rest_m_.size(); ++i) {
    btSoftBody::Node& node = body.m_nodes[int(i)];
    node.m_x = node.m_q = to_bt(state_.x_m[i]);
    node.m_v = to_bt(state_.v_m_s[i]);
  }
  world_->time_s = state_.time_s;
}

void BulletCloth::register_stages(StageTimes& times) {
  term_stage_ = register_term_stages(terms_, times);
  step_stage_ = times.add("bullet_step");
}

void BulletCloth::before_substep(double dt_s) {
  btSoftBody& body = *world_->body;
  const double t = world_->time_s;
  // Pins: at their place now, moving so that Bullet's prediction lands them
  // exactly where they must be after the substep.
  const Vec3 here = model_->pin_motion.offset_m(t);
  const Vec3 velocity = (model_->pin_motion.offset_m(t + dt_s) - here) / dt_s;
  const std::size_t n = rest_m_.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!model_->pinned[i]) continue;
    btSoftBody::Node& node = body.m_nodes[int(i)];
    node.m_x = to_bt(rest_m_[i] + here);
    node.m_v = to_bt(velocity);
  }
  if (terms_.empty()) return;
  for (std::size_t i = 0; i < n; ++i) {
    state_.x_m[i] = from_bt(body.m_nodes[int(i)].m_x);
    state_.v_m_s[i] = from_bt(body.m_nodes[int(i)].m_v);
  }
  std::fill(forces_n_.begin(), forces_n_.end(), Vec3::Zero());
  for (std::size_t k = 0; k < terms_.size(); ++k) {
    const int stage = term_stage_.empty() ? -1 : term_stage_[k];
    run_timed(times_, stage, [&] { terms_[k]->add_forces(state_.x_m, state_.v_m_s, forces_n_); });
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!model_->pinned[i]) body.addForce(to_bt(forces_n_[i]), int(i));
}

void BulletCloth::advance_frame(StageTimes* times) {
  times_ = times;
  const double start = state_.time_s;
  const double dt = substep_s();
  physics::begin_frame(terms_, state_);
  using Clock = std::chrono::steady_clock;
  const Clock::time_point began = Clock::now();
  double in_terms = 0.0;
  if (times)
    for (int stage : term_stage_) in_terms -= times->seconds()[std::size_t(stage)];
  for (int s = 0; s < substeps_per_frame_ && !stop_requested(); ++s) {
    world_->time_s = start + s * dt;
    world_->world.stepSimulation(dt, 0);  // exactly one substep of dt
    if (obstacles_) project_contacts(start + (s + 1) * dt);
  }
  if (times && step_stage_ >= 0) {
    for (int stage : term_stage_) in_terms += times->seconds()[std::size_t(stage)];
    const double total = std::chrono::duration<double>(Clock::now() - began).count();
    times->add_seconds(step_stage_, total - in_terms);
  }
  times_ = nullptr;
  state_.time_s = start + substeps_per_frame_ * dt;
  read_back();
}

void BulletCloth::project_contacts(double time_s) {
  btSoftBody& body = *world_->body;
  const std::size_t n = rest_m_.size();
  contact_x_.resize(n);
  contact_v_.resize(n);
  const bool self_contact = obstacles_->self_contact();
  contact_start_.resize(self_contact ? n : 0);
  for (std::size_t i = 0; i < n; ++i) {
    contact_x_[i] = from_bt(body.m_nodes[int(i)].m_x);
    contact_v_[i] = from_bt(body.m_nodes[int(i)].m_v);
    if (self_contact) contact_start_[i] = from_bt(body.m_nodes[int(i)].m_q);  // the step's start
  }
  if (obstacles_->project(time_s, contact_x_, contact_v_, model_->pinned, {}, contact_start_) == 0)
    return;
  for (std::size_t i = 0; i < n; ++i) {
    if (model_->pinned[i]) continue;
    body.m_nodes[int(i)].m_x = to_bt(contact_x_[i]);
    body.m_nodes[int(i)].m_v = to_bt(contact_v_[i]);
  }
}

void BulletCloth::read_back() {
  const btSoftBody& body = *world_->body;
  const Vec3 pin_velocity = model_->pin_motion.velocity_m_s(state_.time_s);
  for (std::size_t i = 0; i < rest_m_.size(); ++i) {
    state_.x_m[i] = from_bt(body.m_nodes[int(i)].m_x);
    // Bullet's velocity of a pin is its last displacement, damped by kDP; the
    // pole's is exact.
    state_.v_m_s[i] = model_->pinned[i] ? pin_velocity : from_bt(body.m_nodes[int(i)].m_v);
  }
}

}  // namespace flagsim::physics
