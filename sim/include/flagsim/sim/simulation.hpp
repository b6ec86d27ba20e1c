#pragma once
// What `flag-sim run` drives, whatever the mode: a state advanced frame by
// frame, read by the run loop (checks, output) but never reached into.
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "flagsim/coarse_physics/cloth_state.hpp"
#include "flagsim/coarse_physics/wind_field.hpp"
#include "flagsim/core/lattice.hpp"
#include "flagsim/core/named_number.hpp"
#include "flagsim/core/stage_times.hpp"
#include "flagsim/core/strain.hpp"
#include "flagsim/infill/infill_method.hpp"
#include "flagsim/scene/scene.hpp"
#include "flagsim/sim/divergence.hpp"
#include "flagsim/sim/model.hpp"

namespace flagsim::sim {

/// Everything a simulation continues from (Simulation::state): stepping on
/// from a restored state gives the same bytes as stepping on from where it was
/// taken. Shapes are the simulation's; set_state checks them.
struct SimulationState {
  int frame = 0;  ///< output frames since t = 0
  /// The integrated lattice's positions [n] m, velocities [n] m/s and time s:
  /// the full lattice's, or the coarse one's in the hybrid; empty in mode "infill".
  physics::ClothState physics;
  /// The dense lattice [J*K] the infill fills from (hybrid, infill), m and
  /// m/s (its frame-to-frame velocities); empty in the full-lattice modes.
  std::vector<Vec3> dense_m, dense_v_m_s;
  std::vector<double> infill_memory;  ///< infill::InfillMethod::memory()
  /// The wind's mean and the turbulence's drift (set_wind); nullopt without [wind].
  std::optional<physics::WindField::Drift> wind;
};

class Simulation {
 public:
  virtual ~Simulation() = default;
  virtual const Lattice& lattice() const = 0;
  /// Effects in pipeline order (root attribute `effects`).
  virtual std::vector<std::string> effects() const = 0;
  /// Numeric root attributes describing the stepping (substep_seconds, ...).
  virtual std::vector<NamedNumber> numbers() const = 0;
  /// One timing column per stage, in pipeline order.
  virtual void register_stages(StageTimes& times) = 0;
  /// Advances to the next output frame (1/fps later).
  virtual void advance_frame(StageTimes* times) = 0;
  /// Dense lattice [J*K], m, and node velocities [J*K], m/s.
  virtual std::span<const Vec3> positions() const = 0;
  virtual std::span<const Vec3> velocities() const = 0;
  virtual double kinetic_energy_j() const = 0;
  /// Positions of the coarse nodes [Jc*Kc], m, in the modes that simulate them; empty otherwise.
  virtual std::span<const Vec3> coarse_positions() const { return {}; }
  /// What the coarse physics remembers besides its nodes and velocities (the
  /// creases' rest and held angles, ClothState::memory) as the infill took it
  /// this frame; empty when nothing is remembered or there is no coarse physics.
  virtual std::span<const double> coarse_memory() const { return {}; }
  /// Dense row and column index of each coarse row and column; empty with no coarse nodes.
  virtual std::pair<std::vector<int>, std::vector<int>> coarse_indices() const { return {}; }
  /// What the infill did in the last frame, in the modes that have one.
  virtual std::optional<infill::FillReport> infill_report() const { return std::nullopt; }
  /// Why the physics' last frame cannot be trusted (ClothIntegrator::failure), or nullopt.
  virtual std::optional<physics::SolverNote> physics_failure() const { return std::nullopt; }
  /// What a diverged frame's reason adds for the physics backend
  /// (ClothIntegrator::divergence_advice); nullopt for nothing.
  virtual std::optional<physics::SolverNote> physics_advice() const { return std::nullopt; }
  /// What the summary line says about the stepping ("1001 substeps/frame of 3.3e-05 s").
  virtual std::string stepping_summary() const = 0;
  /// The mean wind now, m/s; nullopt without [wind].
  virtual std::optional<Vec3> wind() const { return std::nullopt; }
  /// From the next frame on the mean wind is `velocity_m_s` (gusts and
  /// turbulence, if any, ride on it; the turbulence carried on from where the
  /// old wind took it). Throws UserError without [wind], in infill mode, for a
  /// wind faster than the scene's wind.velocity (the substeps are sized for
  /// that), or with wind.model = "vortex".
  virtual void set_wind(const Vec3& velocity_m_s);
  /// A copy of the whole state after the last frame.
  virtual SimulationState state() const = 0;
  /// Continues from `state`, one that state() of a simulation of the same
  /// scene gave (any frame, also one before a divergence). Throws UserError,
  /// naming the part, when a part's size is not this simulation's.
  virtual void set_state(const SimulationState& state) = 0;
};

/// A `note:` line when the scene's [wrinkles] ask for waves finer than its
/// lattice carries: the wavelength step 3.5's balance picks for a row with 1%
/// of slack, against 8 rest spacings (a half-wave needs 4 links, else it is a
/// zigzag of the lattice and 3.5 clamps the wave count); nullopt otherwise.
std::optional<std::string> wrinkle_resolution_note(const Scene& scene);

/// Why the simulation's current frame cannot be trusted, or nullopt: the
/// physics backend's own failure, or find_divergence() with what the backend
/// adds (its advice in Divergence::detail). In infill mode a node too fast
/// under the strain limit is the keyframes' doing (kKeyframeSpeed); links
/// overstretched in a frame where the infill did not reach its tolerance are
/// the infill's failure, not the cloth's (kInfillUnconverged).
std::optional<Divergence> frame_divergence(const Simulation& simulation, const Scene& scene,
                                           const StrainStats& strain);

/// The simulation of the model's mode, at its frame 0. Any number may share one model.
std::unique_ptr<Simulation> make_simulation(std::shared_ptr<const Model> model);
/// The same for `scene`, compiled (Model::compile: checked as a file's is).
std::unique_ptr<Simulation> make_simulation(const Scene& scene);

/// Writes the coarse nodes [Jc*Kc] m the infill takes at simulated frame n
/// (frame 0 first, then one frame at a time) into `nodes`, and what the
/// physics remembered then (Simulation::coarse_memory) into `memory`; an empty
/// `memory` leaves the physics' own (its start, since a replay never steps it).
using CoarseFrames =
    std::function<void(int frame, std::vector<Vec3>& nodes, std::vector<double>& memory)>;

/// The hybrid of `scene` with its coarse nodes read from `coarse` instead of
/// simulated (`flag-sim refine`: the dense frames of a run that kept only its
/// coarse trajectory; bit for bit those of the run at its own lattice, since
/// the infill takes the same nodes in the same order). The physics is built
/// for what the file says of it (effects, stepping) but never stepped.
std::unique_ptr<Simulation> make_replay(const Scene& scene, CoarseFrames coarse);

}  // namespace flagsim::sim
