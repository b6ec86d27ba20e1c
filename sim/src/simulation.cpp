#include "flagsim/sim/simulation.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string_view>

#include "flagsim/coarse_physics/cloth_integrator.hpp"
#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/cloth_state.hpp"
#include "flagsim/coarse_physics/creased_bending.hpp"
#include "flagsim/coarse_physics/fiber_settle.hpp"
#include "flagsim/coarse_physics/obstacles.hpp"
#include "flagsim/core/errors.hpp"
#include "flagsim/core/message.hpp"
#include "flagsim/infill/infill_method.hpp"
#include "flagsim/infill/keyframes.hpp"
#include "flagsim/infill/strain_limit.hpp"
#include "flagsim/sim/divergence.hpp"

namespace flagsim::sim {
namespace {

// Root attributes describing the physics stepping, in every mode that has physics.
std::vector<NamedNumber> stepping_numbers(const physics::ClothIntegrator& physics) {
  return {{"substep_seconds", physics.substep_s(), "s"},
          {"substeps_per_frame", double(physics.substeps_per_frame()), "1", true},
          {"stable_substep_seconds", physics.stable_substep_s(), "s"}};
}

// The integrator the model's mode runs (backend_of: a full-lattice mode names
// its own, hybrid follows solver.backend), on the model's physics cloth.
std::unique_ptr<physics::ClothIntegrator> integrator_for(const Model& model) {
  return physics::make_integrator(with_resolved_backend(model.scene()), model.physics_cloth());
}

// What the summary line says of an integrator's stepping.
std::string stepping_of(const physics::ClothIntegrator& physics) {
  std::string text =
      fmt::format("{}/frame of {:.3g} s", counted(physics.substeps_per_frame(), "substep"),
                  physics.substep_s());
  if (const std::string solver = physics.solver_summary(); !solver.empty())
    text += fmt::format(" ({})", solver);
  return text;
}

// UserError unless `part` of a state given to set_state has `expected` entries.
void check_state_size(std::string_view part, std::size_t size, std::size_t expected) {
  if (size != expected)
    throw UserError(fmt::format("set_state: {}: {} entries where this simulation has {}", part,
                                size, expected));
}

// Checks and sets the physics part of a state, and its wind (a state
// without one leaves the wind as it is).
void set_physics_state(physics::ClothIntegrator& physics, const SimulationState& state) {
  const std::size_t n = physics.state().x_m.size();
  check_state_size("the physics positions", state.physics.x_m.size(), n);
  check_state_size("the physics velocities", state.physics.v_m_s.size(), n);
  check_state_size("the physics memory (crease rest angles)", state.physics.memory.size(),
                   physics.state().memory.size());
  physics.set_state(state.physics);
  if (state.wind && physics.wind_drift()) physics.set_wind_drift(*state.wind);
}

// The physics' state with its wind.
SimulationState physics_state(int frame, const physics::ClothIntegrator& physics) {
  return {frame, physics.state(), {}, {}, {}, physics.wind_drift()};
}

// The wind of `physics`, its field (the scene's speed), or nullptr without [wind].
const physics::WindField* wind_field_of(const physics::ClothIntegrator& physics) {
  for (const std::unique_ptr<physics::ForceTerm>& term : physics.force_terms())
    if (const physics::WindField* field = term->wind_field()) return field;
  return nullptr;
}

std::optional<Vec3> wind_of(const physics::ClothIntegrator& physics) {
  const physics::WindField* field = wind_field_of(physics);
  return field ? std::optional<Vec3>(field->drift().mean_m_s) : std::nullopt;
}

void set_wind_of(physics::ClothIntegrator& physics, const Vec3& velocity_m_s) {
  const physics::WindField* field = wind_field_of(physics);
  if (!field)
    throw UserError(
        "set_wind: the scene has no [wind]; give it one (its velocity is the fastest wind the "
        "stepping is sized for)");
  if (!velocity_m_s.allFinite())
    throw UserError("set_wind: expected a finite velocity [x, y, z] in m/s");
  // The substeps (and XPBD's, Bullet's) were sized for the scene's wind.
  const double limit = field->scene_speed_m_s();
  if (velocity_m_s.norm() > limit * (1.0 + 1e-12))
    throw UserError(fmt::format(
        "set_wind: {:g} m/s is faster than the scene's wind.velocity ({:g} m/s), which the "
        "stepping is sized for; start from a scene whose wind is the fastest you will set",
        velocity_m_s.norm(), limit));
  const physics::WindField::Drift next =
      physics::WindField::with_mean(field->drift(), velocity_m_s, physics.state().time_s);
  if (!physics.set_wind_drift(next))
    throw UserError(
        "set_wind: wind.model = \"vortex\": its wake was shed in the scene's wind, the vortex "
        "air cannot change during a run");
}

// The full-lattice modes (is_full_lattice): physics on every node.
class FullLatticeSimulation final : public Simulation {
 public:
  explicit FullLatticeSimulation(std::shared_ptr<const Model> model)
      : model_(std::move(model)), physics_(integrator_for(*model_)) {}
  const Lattice& lattice() const override { return physics_->model().lattice; }
  std::vector<std::string> effects() const override { return physics_->effects(); }
  std::vector<NamedNumber> numbers() const override { return stepping_numbers(*physics_); }
  void register_stages(StageTimes& times) override { physics_->register_stages(times); }
  void advance_frame(StageTimes* times) override {
    physics_->advance_frame(times);
    ++frame_;
  }
  std::span<const Vec3> positions() const override { return physics_->state().x_m; }
  std::span<const Vec3> velocities() const override { return physics_->state().v_m_s; }
  double kinetic_energy_j() const override { return physics_->kinetic_energy(); }
  std::string stepping_summary() const override { return stepping_of(*physics_); }
  std::optional<physics::SolverNote> physics_failure() const override {
    return physics_->failure();
  }
  std::optional<physics::SolverNote> physics_advice() const override {
    return physics_->divergence_advice();
  }
  SimulationState state() const override { return physics_state(frame_, *physics_); }
  void set_state(const SimulationState& state) override {
    set_physics_state(*physics_, state);
    frame_ = state.frame;
  }
  std::optional<Vec3> wind() const override { return wind_of(*physics_); }
  void set_wind(const Vec3& velocity_m_s) override { set_wind_of(*physics_, velocity_m_s); }

 private:
  std::shared_ptr<const Model> model_;
  std::unique_ptr<physics::ClothIntegrator> physics_;
  int frame_ = 0;
};

// Step 3.5's constants from [wrinkles] and the material's yarn, or nullopt
// when the scene has no [wrinkles].
std::optional<infill::WrinkleParams> wrinkle_params(const Scene& scene, const Material& material) {
  if (!scene.wrinkles) return std::nullopt;
  const Wrinkles& w = *scene.wrinkles;
  infill::WrinkleParams params;
  params.k_r4 = infill::bending_constant_k_r4(material.yarn.modulus_pa, material.yarn.radius_m);
  params.k_prime = w.k_prime.value_or(params.k_prime);
  params.tolerance = w.tolerance.value_or(params.tolerance);
  return params;
}

// The ridges of the coarse physics' creases on the dense lattice (hybrid mode
// with [creases]), or nullopt.
std::optional<infill::CreaseRidgeParams> crease_ridge_params(const Scene& scene,
                                                             const Material& material) {
  if ((scene.mode != Mode::kHybrid && scene.mode != Mode::kInfill) || !material.creased())
    return std::nullopt;
  return infill::CreaseRidgeParams{*material.bending_rigidity_j, material.creases->width_m,
                                   material.stretch_modulus_n_m};
}

// Whether the dense lattice keeps its own layers apart: [contact] in hybrid
// mode (infill mode refuses the table: no physics keeps its layers apart).
bool dense_self_contact(const Scene& scene) {
  return scene.contact.has_value() && scene.mode == Mode::kHybrid;
}

// The dense lattice filled by the paper's infill from coarse nodes: shared by
// the infill and hybrid modes. Velocities are the frame-to-frame differences
// (for the divergence checks and /frames/velocity), and the kinetic energy is
// the dense nodes' with them: /stats/kinetic_energy means the same in every
// mode, the energy of the lattice the file holds.
class DenseInfill {
 public:
  DenseInfill(const Model& compiled, int coarse_rows, int coarse_cols)
      : DenseInfill(compiled.scene(), compiled.material(), compiled.dense_cloth(), coarse_rows,
                    coarse_cols) {}

 private:
  DenseInfill(const Scene& scene, const Material& material, const physics::ClothModel& model,
              int coarse_rows, int coarse_cols)
      : lattice_(model.lattice),
        solver_(infill::make_infill(
            lattice_, infill::CellGrid::of(lattice_, coarse_rows, coarse_cols),
            {infill_solver_of(scene), paper_relax_sweeps_of(scene), wrinkle_params(scene, material),
             scene.wrinkles ? scene.wrinkles->rounds.value_or(2) : 0,
             crease_ridge_params(scene, material),
             dense_self_contact(scene) ? infill::kContactFoldLimitRad : 0.0})),
        fps_(scene.fps),
        wrinkles_(scene.wrinkles.has_value()),
        sides_from_last_frame_(infill_solver_of(scene) == InfillSolverKind::kPaper),
        obstacles_(physics::Obstacles::of(scene)),
        fixed_(model.lattice.node_count(), 0),
        mass_kg_(model.mass_kg),
        // The same start as the physics' (free nodes perturbed, pinned ones not).
        positions_(physics::initial_state(scene, model).x_m),
        previous_(positions_),
        velocities_(positions_.size(), Vec3::Zero()) {
    if (!dense_self_contact(scene)) return;
    // The dense layers at the cloth's thickness (a quarter of the dense
    // spacing at least, as the physics holds its lattice). The coarse physics
    // holds its layers max(thickness, a quarter of the coarse spacing) apart
    // (obstacles.cpp): parts nearer than half that on the coarse surface are
    // one layer, and keep the side they have.
    const double thickness = scene.contact->thickness_m;
    self_.emplace(lattice_,
                  std::max(thickness, 0.25 * std::min(lattice_.spacing_x_m, lattice_.spacing_y_m)));
    pushed_from_.resize(positions_.size());
    if (sides_from_last_frame_) return;
    const infill::CellGrid& grid = solver_->grid();
    const double coarse_held =
        std::max(thickness, 0.25 * std::min(grid.col_stride * lattice_.spacing_x_m,
                                            grid.row_stride * lattice_.spacing_y_m));
    self_->set_side_reach(0.5 * coarse_held);
    surface_.resize(positions_.size());
  }

 public:
  const Lattice& lattice() const { return lattice_; }
  const infill::InfillMethod& solver() const { return *solver_; }
  /// Pinned dense nodes stay where 3.1 puts them (on the pinned coarse lines).
  void hold_pins(PinSet pin) {
    const std::vector<std::uint8_t> held = physics::pinned_nodes(lattice_, pin);
    solver_->hold(held);
    for (std::size_t i = 0; i < held.size(); ++i) fixed_[i] |= held[i];
  }
  void hold_corners() {
    std::vector<std::uint8_t> corners(lattice_.node_count(), 0);
    for (std::size_t c : lattice_.corners()) corners[c] = fixed_[c] = 1;
    solver_->hold(corners);
  }
  void register_stages(StageTimes& times) {
    solver_->register_stages(times);
    if (obstacles_ || self_) contact_stage_ = times.add("contact", StageGroup::kInfill);
  }
  /// Effects of the infill, after those of whatever drives the coarse nodes.
  void add_effects(std::vector<std::string>& effects) const {
    effects.emplace_back("infill");
    if (wrinkles_) effects.emplace_back("wrinkles");
  }
  /// The coarse physics' crease rest angles (and more, ignored) for the next fills.
  void set_creases(std::span<const double> coarse_rest_rad) {
    solver_->set_creases(coarse_rest_rad);
  }
  /// The dense lattice's own crease rest angles (infill mode) for the next fills.
  void set_dense_creases(std::span<const double> dense_rest_rad) {
    solver_->set_dense_creases(dense_rest_rad);
  }
  /// New dense lattice of frame `frame` from the coarse nodes [Jc*Kc];
  /// velocities over 1/fps. With solids ([pole] radius, [ground]) no dense
  /// node is left inside one: the infill does not undo the physics' contact.
  void fill(std::span<const Vec3> coarse_m, int frame, StageTimes* times) {
    std::copy(positions_.begin(), positions_.end(), previous_.begin());
    solver_->fill(coarse_m, positions_, times);
    if (obstacles_)
      run_timed(times, contact_stage_, [&] {
        obstacles_->settle(frame / fps_, lattice_, positions_, fixed_, previous_, kSettleRounds,
                           kSettleReach);
      });
    if (self_) run_timed(times, contact_stage_, [&] { keep_layers_apart(coarse_m, frame / fps_); });
    for (std::size_t i = 0; i < positions_.size(); ++i)
      velocities_[i] = (positions_[i] - previous_[i]) * fps_;
  }
  /// Self-contact of the dense lattice (hybrid [contact]): the coarse physics
  /// keeps its triangles apart, so its surface seen at dense resolution
  /// (CellGrid::coarse_surface) has no two layers crossing; every dense node
  /// and triangle, and every two dense edges, are kept the thickness apart on
  /// the side they have on it (SelfContact, sides from that surface). The
  /// paper's infill deforms the last frame into the next rather than laying
  /// the lattice anew, and does not follow the coarse cloth's sharp folds (its
  /// layers can lie tens of millimetres off the coarse surface there): its
  /// pairs keep the side they had in the last frame, as a physics step's do
  /// (that frame came out of this pass with none crossing). Where
  /// the pass moved nodes, the fibers around them take back the lengths the
  /// infill gave them, each sweep followed by the pass again (as settle() does
  /// for the solids): a push spread along its fibers rather than into a few
  /// links' stretch.
  void keep_layers_apart(std::span<const Vec3> coarse_m, double time_s) {
    if (!sides_from_last_frame_) solver_->grid().coarse_surface(lattice_, coarse_m, surface_);
    const std::span<const Vec3> sides = sides_from_last_frame_ ? previous_ : surface_;
    std::copy(positions_.begin(), positions_.end(), pushed_from_.begin());
    if (self_->project(positions_, {}, fixed_, sides) == 0) return;
    physics::settle_fibers(
        lattice_, positions_, pushed_from_, fixed_, kSettleRounds, kSettleReach,
        [&](std::size_t a, std::size_t b, double) {
          return (pushed_from_[b] - pushed_from_[a]).norm();
        },
        [&](int, int, int, int) { return self_->project(positions_, {}, fixed_, sides) != 0; });
    // Last, the solids again: the pass and the sweeps may have pushed a node a
    // little into one (tens of micrometres into the pole on pole_wrap with
    // the paper's infill), and no node may end inside a solid.
    if (obstacles_) obstacles_->project(time_s, positions_, {}, fixed_, previous_);
  }
  void forget_velocities() { std::fill(velocities_.begin(), velocities_.end(), Vec3::Zero()); }
  /// The dense part of a SimulationState.
  void save(SimulationState& state) const {
    state.dense_m = positions_;
    state.dense_v_m_s = velocities_;
    state.infill_memory = solver_->memory();
  }
  void restore(const SimulationState& state) {
    check_state_size("the dense positions", state.dense_m.size(), positions_.size());
    check_state_size("the dense velocities", state.dense_v_m_s.size(), velocities_.size());
    check_state_size("the infill's memory", state.infill_memory.size(), solver_->memory().size());
    positions_ = state.dense_m;
    velocities_ = state.dense_v_m_s;
    solver_->set_memory(state.infill_memory);
  }
  std::span<const Vec3> positions() const { return positions_; }
  std::span<const Vec3> velocities() const { return velocities_; }
  /// 1/2 sum m |v|^2 over the dense nodes, J.
  double kinetic_energy_j() const { return physics::kinetic_energy_j(mass_kg_, velocities_); }

 private:
  Lattice lattice_;
  std::unique_ptr<infill::InfillMethod> solver_;
  double fps_;
  bool wrinkles_;
  /// [contact]: the pairs keep the side they had in the last frame (the
  /// paper's infill), else the one they have on the coarse surface.
  bool sides_from_last_frame_;
  std::optional<physics::Obstacles> obstacles_;
  std::optional<physics::SelfContact> self_;  ///< hybrid [contact]: the dense lattice's
  std::vector<Vec3> surface_;  ///< [J*K] the coarse surface at each dense node, m (smooth infill)
  std::vector<Vec3> pushed_from_;  ///< [J*K] the dense lattice before the self-contact pass, m
  int contact_stage_ = -1;
  /// [J*K] 1: a node the contact pass leaves where the infill put it: held by
  /// the infill (pins, corners). Not the dense nodes on coarse nodes: the
  /// smooth infill's 3.4 moves those too (by up to 60 mm on a cloth hanging
  /// against the pole), so they can end inside the pole although the physics'
  /// nodes are outside (pole_calm diverged at frame 20 while they were held).
  std::vector<std::uint8_t> fixed_;
  /// The contact pass's fiber sweeps, and how far from the nodes it moved
  /// (links): a coarse cell of the default lattice is 16 links.
  static constexpr int kSettleRounds = 40;
  static constexpr int kSettleReach = 16;
  std::vector<double> mass_kg_;  ///< [J*K] the fine cloth's node masses, kg
  std::vector<Vec3> positions_, previous_, velocities_;
};

// mode "infill": no physics; the corners follow the keyframes and the whole
// lattice comes from the paper's infill (Figs. 9-10). With [creases] the
// dense lattice keeps creases of its own: the plastic flow of
// coarse_physics/creased_bending.hpp on its bending triples, from each filled
// frame (a fold the corners hold past the yield for long enough sets), drawn
// into the next frames as ridges (crease_ridges.hpp: add_dense_ridges). No
// physics pulls them flat: they stay until the corners fold the cloth back.
class InfillSimulation final : public Simulation {
 public:
  explicit InfillSimulation(std::shared_ptr<const Model> model)
      : model_(std::move(model)),
        dense_(*model_, 2, 2),
        creases_(physics::make_creased_bending(model_->scene(), model_->dense_cloth())) {
    dense_.hold_corners();  // the keyframes give them exactly
    fill(0.0, nullptr);     // frame 0: the corners of the first keyframe
    dense_.forget_velocities();
  }
  const Lattice& lattice() const override { return dense_.lattice(); }
  std::vector<std::string> effects() const override {
    std::vector<std::string> effects = {"keyframes"};
    dense_.add_effects(effects);
    if (creases_) effects.emplace_back("creases");
    return effects;
  }
  std::vector<NamedNumber> numbers() const override { return {}; }
  void register_stages(StageTimes& times) override { dense_.register_stages(times); }
  void advance_frame(StageTimes* times) override {
    ++frame_;
    fill(frame_ / model_->scene().fps, times);
  }
  std::span<const Vec3> positions() const override { return dense_.positions(); }
  std::span<const Vec3> velocities() const override { return dense_.velocities(); }
  double kinetic_energy_j() const override { return dense_.kinetic_energy_j(); }
  std::optional<infill::FillReport> infill_report() const override {
    return dense_.solver().last_report();
  }
  std::string stepping_summary() const override {
    return fmt::format("{} relaxation sweeps in the last frame",
                       dense_.solver().last_report().iterations);
  }
  SimulationState state() const override {
    SimulationState state;
    state.frame = frame_;
    dense_.save(state);
    // The dense creases' rest and held angles, where the physics keeps its own.
    if (creases_) state.physics.memory.assign(creases_->memory().begin(), creases_->memory().end());
    return state;
  }
  void set_state(const SimulationState& state) override {
    check_state_size("the physics positions", state.physics.x_m.size(), 0);
    check_state_size("the creases' memory (rest and held angles)", state.physics.memory.size(),
                     creases_ ? creases_->memory().size() : 0);
    dense_.restore(state);
    if (creases_) creases_->set_memory(state.physics.memory);
    frame_ = state.frame;
  }

 private:
  void fill(double time_s, StageTimes* times) {
    const auto corners = infill::corners_at(model_->scene().keyframes, time_s);
    if (creases_) {  // the rest angles so far; this frame's plastic step after it
      const std::span<const double> memory = creases_->memory();
      dense_.set_dense_creases(memory.first(memory.size() / 2));
    }
    dense_.fill(corners, frame_, times);
    if (creases_) creases_->begin_frame(time_s, dense_.positions());
  }

  std::shared_ptr<const Model> model_;  ///< shared: the caller's Scene may go first
  DenseInfill dense_;
  std::unique_ptr<physics::CreasedBending> creases_;  ///< [creases]: the dense lattice's own
  int frame_ = 0;
};

// mode "hybrid": the physics of solver.backend on flag.coarse, the paper's infill
// on flag.fine every output frame, starting from the previous dense frame.
class HybridSimulation final : public Simulation {
 public:
  /// @param replay  where the coarse nodes come from instead of the physics (make_replay)
  explicit HybridSimulation(std::shared_ptr<const Model> model, CoarseFrames replay = {})
      : model_(std::move(model)),
        physics_(integrator_for(*model_)),
        replay_(std::move(replay)),
        dense_(*model_, physics_->model().lattice.rows, physics_->model().lattice.cols),
        paper_infill_(infill_solver_of(model_->scene()) == InfillSolverKind::kPaper) {
    dense_.hold_pins(model_->scene().flag.pin);
    make_reachable();  // frame 0: the coarse nodes where the physics starts
    dense_.set_creases(coarse_memory());
    dense_.fill(reachable_, 0, nullptr);
    dense_.forget_velocities();
  }
  const Lattice& lattice() const override { return dense_.lattice(); }
  std::vector<std::string> effects() const override {
    std::vector<std::string> effects = physics_->effects();
    dense_.add_effects(effects);
    return effects;
  }
  std::vector<NamedNumber> numbers() const override { return stepping_numbers(*physics_); }
  void register_stages(StageTimes& times) override {
    physics_->register_stages(times);
    if (needs_slack()) slack_stage_ = times.add("coarse_slack", StageGroup::kInfill);
    dense_.register_stages(times);
  }
  void advance_frame(StageTimes* times) override {
    ++frame_;
    if (!replay_) physics_->advance_frame(times);
    run_timed(times, slack_stage_, [&] { make_reachable(); });
    dense_.set_creases(coarse_memory());  // the creases' rest angles, if any
    dense_.fill(reachable_, frame_, times);
  }
  std::span<const Vec3> positions() const override { return dense_.positions(); }
  std::span<const Vec3> velocities() const override { return dense_.velocities(); }
  std::span<const Vec3> coarse_positions() const override { return reachable_; }
  std::span<const double> coarse_memory() const override {
    return replay_ && !replayed_memory_.empty() ? std::span<const double>(replayed_memory_)
                                                : std::span<const double>(physics_->state().memory);
  }
  std::pair<std::vector<int>, std::vector<int>> coarse_indices() const override {
    const infill::CellGrid& grid = dense_.solver().grid();
    std::pair<std::vector<int>, std::vector<int>> indices;
    for (int j = 0; j < grid.coarse_rows; ++j) indices.first.push_back(j * grid.row_stride);
    for (int k = 0; k < grid.coarse_cols; ++k) indices.second.push_back(k * grid.col_stride);
    return indices;
  }
  double kinetic_energy_j() const override { return dense_.kinetic_energy_j(); }
  std::optional<infill::FillReport> infill_report() const override {
    return dense_.solver().last_report();
  }
  std::string stepping_summary() const override {
    return fmt::format("{} on {} x {} coarse nodes", stepping_of(*physics_),
                       physics_->model().lattice.rows, physics_->model().lattice.cols);
  }
  std::optional<physics::SolverNote> physics_failure() const override {
    return physics_->failure();
  }
  std::optional<physics::SolverNote> physics_advice() const override {
    return physics_->divergence_advice();
  }
  SimulationState state() const override {
    SimulationState state = physics_state(frame_, *physics_);
    dense_.save(state);
    return state;
  }
  std::optional<Vec3> wind() const override { return wind_of(*physics_); }
  void set_wind(const Vec3& velocity_m_s) override { set_wind_of(*physics_, velocity_m_s); }
  void set_state(const SimulationState& state) override {
    set_physics_state(*physics_, state);
    dense_.restore(state);
    frame_ = state.frame;
    make_reachable();  // the nodes the last fill used: a function of the physics state
  }

 private:
  // The coarse nodes handed to the infill are pulled in (infill::limit_stretch)
  // until no coarse row or column link is longer than (1 - kCoarseSlack) of its
  // rest length. A coarse link stretched by the physics leaves the dense fiber
  // between its ends no way to keep its length; 1% of slack also lets 3.4
  // converge where taut fibers made it stall (default scene, 129 x 193: at 0
  // slack the dense strain reached 3.7%, at 1% it stays under the tolerance).
  // The physics state itself is untouched; /coarse/positions holds the nodes
  // the infill used, so the dense lattice passes through them exactly.
  static constexpr double kCoarseSlack = 0.01;
  static constexpr int kSlackPasses = 100;

  std::shared_ptr<const Model> model_;
  std::unique_ptr<physics::ClothIntegrator> physics_;  ///< on model_->physics_cloth()
  CoarseFrames replay_;                  ///< empty: the physics moves the coarse nodes
  std::vector<double> replayed_memory_;  ///< the replayed frame's memory (empty: the physics')
  // Only the paper solver needs slack; with the coarse lattice equal to the
  // fine one there are no fibers to fill between coarse nodes either.
  bool needs_slack() const {
    const infill::CellGrid& grid = dense_.solver().grid();
    return paper_infill_ && (grid.row_stride > 1 || grid.col_stride > 1);
  }
  void make_reachable() {
    if (replay_) {  // stored as the infill took them: after any slack
      replay_(frame_, reachable_, replayed_memory_);
      if (reachable_.size() != physics_->state().x_m.size())
        throw UserError(
            fmt::format("the coarse trajectory's frame {} has {} nodes, the scene's "
                        "coarse lattice {}",
                        frame_, reachable_.size(), physics_->state().x_m.size()));
      if (!replayed_memory_.empty() && replayed_memory_.size() != physics_->state().memory.size())
        throw UserError(fmt::format(
            "the coarse trajectory's frame {} remembers {} values, the scene's physics {}", frame_,
            replayed_memory_.size(), physics_->state().memory.size()));
      return;
    }
    reachable_ = physics_->state().x_m;
    if (!needs_slack()) return;
    infill::limit_stretch(physics_->model().lattice, physics_->model().pinned, reachable_,
                          -kCoarseSlack, kSlackPasses);
  }

  std::vector<Vec3> reachable_;  ///< the coarse nodes handed to the infill
  int slack_stage_ = -1;
  DenseInfill dense_;
  bool paper_infill_;
  int frame_ = 0;
};

}  // namespace

std::optional<Divergence> frame_divergence(const Simulation& simulation, const Scene& scene,
                                           const StrainStats& strain) {
  using Cause = Divergence::Cause;
  if (std::optional<physics::SolverNote> failed = simulation.physics_failure())
    return Divergence{Cause::kPhysicsFailure, 0.0, 0.0, failed};
  std::optional<Divergence> found =
      find_divergence(simulation.positions(), simulation.velocities(), strain, scene.limits);
  if (!found) return found;
  found->solver = simulation.physics_advice();
  if (scene.mode == Mode::kInfill && strain.max <= scene.limits.max_strain) {
    // No physics moves an infill-mode cloth: a node this fast follows the keyframes.
    double fastest = 0.0;
    for (const Vec3& v : simulation.velocities()) fastest = std::max(fastest, v.norm());
    if (std::isfinite(fastest) && fastest > scene.limits.max_speed_m_s)
      return Divergence{Cause::kKeyframeSpeed, fastest, scene.limits.max_speed_m_s, {}};
  }
  const std::optional<infill::FillReport> report = simulation.infill_report();
  if (!report || report->converged || strain.max <= scene.limits.max_strain) return found;
  return Divergence{Cause::kInfillUnconverged, strain.max, scene.limits.max_strain, {}};
}

std::optional<std::string> wrinkle_resolution_note(const Scene& scene) {
  const std::optional<infill::WrinkleParams> params = wrinkle_params(scene, material_of(scene));
  if (!params || params->k_prime <= 0.0) return std::nullopt;
  // Eq. (13)'s balance for a row of chord c with slack dL = 0.01 c:
  // (m pi / c)^2 = k_prime dL / (2 k r^4), wavelength 2 c / m.
  const double chord_m = scene.flag.width_m, slack_m = 0.01 * chord_m;
  const double wavelength_m =
      2.0 * std::numbers::pi * std::sqrt(2.0 * params->k_r4 / (params->k_prime * slack_m));
  const Lattice lattice = scene.fine_lattice();
  const double finest_m = 8.0 * lattice.spacing_x_m;
  if (wavelength_m >= finest_m) return std::nullopt;
  const int columns = int(std::ceil(8.0 * chord_m / wavelength_m)) + 1;
  return fmt::format(
      "note: [wrinkles] asks for waves of {:.3g} m (at 1% slack), finer than the {} x {} "
      "lattice carries ({:.3g} m, 8 spacings): 3.5 will lay broader ones; a lattice of {} or more "
      "columns would carry them",
      wavelength_m, lattice.rows, lattice.cols, finest_m, columns);
}

void Simulation::set_wind(const Vec3& /*velocity_m_s*/) {
  throw UserError("set_wind: infill mode has no wind (the corners follow the keyframes)");
}

std::unique_ptr<Simulation> make_simulation(std::shared_ptr<const Model> model) {
  const Mode mode = model->scene().mode;
  if (mode == Mode::kInfill) return std::make_unique<InfillSimulation>(std::move(model));
  if (mode == Mode::kHybrid) return std::make_unique<HybridSimulation>(std::move(model));
  return std::make_unique<FullLatticeSimulation>(std::move(model));
}

std::unique_ptr<Simulation> make_simulation(const Scene& scene) {
  return make_simulation(Model::compile(scene));  // a Scene built in code is checked as a file's is
}

std::unique_ptr<Simulation> make_replay(const Scene& scene, CoarseFrames coarse) {
  std::shared_ptr<const Model> model = Model::compile(scene);
  if (scene.mode != Mode::kHybrid)
    throw UserError(
        fmt::format("a coarse trajectory is replayed by the hybrid; this scene's mode "
                    "is {}",
                    to_string(scene.mode)));
  return std::make_unique<HybridSimulation>(std::move(model), std::move(coarse));
}

}  // namespace flagsim::sim
