#pragma once
// The scene: what the user asked for, validated once, immutable afterwards.
//
// Every quantity is SI (m, s, kg, N, Pa). An optional effect table (pole,
// gravity, wind, bending, ...) is present exactly when the scene file has it;
// a stage is built for it only then (contract: "Scene file").
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "flagsim/core/enum_names.hpp"
#include "flagsim/core/lattice.hpp"
#include "flagsim/core/vec3.hpp"

namespace flagsim {

enum class Mode { kHybrid, kMassSpring, kBullet, kImplicit, kXpbd, kInfill };
/// scene.mode's names (contract).
inline constexpr NameTable<Mode, 6> kModeNames = {{{Mode::kHybrid, "hybrid"},
                                                   {Mode::kMassSpring, "mass-spring"},
                                                   {Mode::kBullet, "bullet"},
                                                   {Mode::kImplicit, "implicit"},
                                                   {Mode::kXpbd, "xpbd"},
                                                   {Mode::kInfill, "infill"}}};

/// The modes that simulate every node of flag.fine (the references).
inline bool is_full_lattice(Mode mode) {
  return mode == Mode::kMassSpring || mode == Mode::kBullet || mode == Mode::kImplicit ||
         mode == Mode::kXpbd;
}
enum class PinSet { kLeft, kRight, kTop, kCorners, kNone };
/// flag.pin's names (contract).
inline constexpr NameTable<PinSet, 5> kPinNames = {{{PinSet::kLeft, "left"},
                                                    {PinSet::kRight, "right"},
                                                    {PinSet::kTop, "top"},
                                                    {PinSet::kCorners, "corners"},
                                                    {PinSet::kNone, "none"}}};

/// flag.folds' axis: the fiber family a fold line runs along.
enum class FoldAxis {
  kRow,  ///< the line runs along a row (across the columns, which it bends), at a fraction of the
         ///< height
  kCol,  ///< the line runs along a column (across the rows), at a fraction of the width from the
         ///< pole
};
inline constexpr NameTable<FoldAxis, 2> kFoldAxisNames = {
    {{FoldAxis::kRow, "row"}, {FoldAxis::kCol, "col"}}};

/// One fold line a flag starts with (flag.folds), as if stored folded: a crease
/// of rest angle `angle_rad` across the fibers it crosses ([creases]).
struct Fold {
  FoldAxis axis = FoldAxis::kCol;
  double at = 0.5;  ///< where, as a fraction (0..1) of the height (row) or width (col)
  /// The crease's rest angle, rad: positive toward the cloth's front (a valley
  /// seen from it), negative toward the back; pi: folded flat on itself.
  double angle_rad = 0.0;
  /// The stretch of the line it runs along, fractions (0..1) of the width
  /// (row) or height (col): a flag folded in four has its second fold a
  /// valley on one side of the first and a mountain on the other.
  double from = 0.0, to = 1.0;
};

struct FlagSpec {
  double width_m = 1.5;
  double height_m = 1.0;
  Vec3 origin_m = Vec3(0.0, 2.0, 0.0);
  int fine_rows = 33;                        ///< J
  int fine_cols = 49;                        ///< K
  std::optional<std::array<int, 2>> coarse;  ///< [Jc, Kc], divides the fine lattice
  double areal_density_kg_m2 = 0.2;
  double stretch_modulus_n_m = 2.0e4;  ///< 2D Young's modulus of the cloth, N/m
  double shear_modulus_n_m = 2.0e3;    ///< 2D in-plane shear modulus, N/m (extension key)
  double damping_per_s = 0.1;
  PinSet pin = PinSet::kLeft;
  /// Amplitude of the seeded random out-of-plane (z) displacement of the free
  /// nodes at t = 0, m (extension key). A flat flag in a wind along its plane
  /// is an unstable equilibrium; this is what breaks the symmetry, reproducibly.
  double initial_perturbation_m = 0.0;
  /// Fold lines present at t = 0 (flag.folds; they need [creases]).
  std::vector<Fold> folds;
};

// The optional tables' structs exist only where the scene has the table; each
// member's initializer is the default of its key there (contract), and the
// parser reads it from here (one home per default).

/// [pole]: the pinned nodes move as rest + axis * amplitude * sin(2 pi f t).
struct PoleMotion {
  Vec3 axis_unit = Vec3::UnitY();  ///< normalised from the scene's axis
  double amplitude_m = 0.1;
  double frequency_hz = 1.0;
};

/// [pole] radius: the pole as a solid vertical cylinder whose surface touches
/// the pinned edge (axis at origin.x - radius, origin.z, moving with the pins);
/// no node enters it. Contact is inelastic, with Coulomb friction.
struct SolidPole {
  double radius_m = 0.0;
  double friction = 0.3;  ///< Coulomb coefficient, fabric on a painted pole
};

/// [ground]: a solid horizontal plane y = height that no node goes below.
struct Ground {
  double height_m = 0.0;
  double friction = 0.5;  ///< Coulomb coefficient, fabric on pavement or grass
};

/// [contact]: self-contact (coarse_physics/self_contact.hpp): every node of the
/// cloth stays at least `thickness` from every triangle of it, and every edge
/// from every edge, that is not its neighbour (closer than 2 thicknesses at
/// rest). Inelastic and frictionless. In the full-lattice modes only: the
/// hybrid's dense lattice can still cross itself (scene_checks.cpp refuses it).
struct Contact {
  double thickness_m = 0.005;
};

struct Gravity {
  Vec3 acceleration_m_s2 = Vec3(0.0, -9.81, 0.0);
};

struct Gusts {
  double amplitude = 0.2;  ///< fraction of the mean speed
  double period_s = 2.0;
};

struct Turbulence {
  double intensity = 0.1;  ///< std / mean speed
  double length_scale_m = 1.0;
};

/// What the air is (wind.model): the quasi-steady force on panels
/// (aero_force.hpp) or that one's drag and friction with an unsteady vortex
/// lattice and its shed wake for the lift and the air's inertia (vortex_wake.hpp).
enum class AirModel { kPanels, kVortex };
inline constexpr NameTable<AirModel, 2> kAirModelNames = {
    {{AirModel::kPanels, "panels"}, {AirModel::kVortex, "vortex"}}};

struct Wind {
  Vec3 velocity_m_s = Vec3::Zero();
  AirModel model = AirModel::kPanels;
  double drag = 1.0;  ///< normal-force coefficient of a flat plate
  double lift = 0.5;  ///< lift coefficient
  /// false (the default): no lift on the air panels at the held edge (those
  /// whose rest rectangle holds a pinned node: at the pole, the column that
  /// straddles it, which sits in the pole's wake), their drag and friction
  /// kept. With the lift there (true, the model before 2026-12-07) the pole's
  /// half of the flag shortens its wave as the lattice is refined
  /// (docs/measurements/flag_physics_2026-12-07.md); without it the
  /// full-lattice references converge. The panels model only.
  bool lift_at_pole = false;
  /// Skin friction coefficient of both faces together, on the planform area:
  /// tangential force 1/2 rho C_f A |u_t| u_t. A turbulent flat plate at the
  /// default flag's Reynolds number (U L / nu ~ 1e6) has about 0.0047 a face;
  /// a flapping boundary layer is thinner (Lighthill's drag increase), so 0.015.
  double friction = 0.015;
  /// Side of the panels the air sees the cloth on, m (air_panels.hpp): waves
  /// shorter than about two panels are not driven, at any lattice. A model
  /// constant of the quasi-steady wind (docs/flag_physics.md): in a scene file
  /// its default is a sixth of the flag's length along the wind, flag.size[0]
  /// (the parser's), 0.25 m for the default flag.
  double panel_m = 0.25;
  double air_density_kg_m3 = 1.225;
  std::optional<Gusts> gusts;
  std::optional<Turbulence> turbulence;
};

/// Nodes of the air's panel lattice along a side of `length_m` cut into panels
/// of at most `panel_m` (at least 2): AirPanels' count, and the scene checks'
/// when they ask whether a cloth is finer than its panels.
inline int air_panel_nodes(double length_m, double panel_m) {
  return 1 + std::max(1, int(std::ceil(length_m / panel_m - 1e-9)));
}

/// [bending]: bending rigidity of the cloth in the coarse physics, stated as
/// D (`stiffness`) or as the paper's yarn (`fiber_radius`, `fiber_modulus`:
/// D = pi E r^3 / 8, see scene/material.hpp); the yarn also makes [wrinkles].
struct Bending {
  /// D, N m = J (moment per unit width per unit curvature); the key is "stiffness".
  /// The parser sets it from the yarn when the scene states that instead.
  double rigidity_j = 1.0e-4;
  /// r, m: the yarn's radius, when stated here (with `stiffness`, E follows from D)
  std::optional<double> fiber_radius_m = std::nullopt;
  /// E, Pa: the yarn's modulus, when stated here (with fiber_radius, instead of `stiffness`)
  std::optional<double> fiber_modulus_pa = std::nullopt;
};

/// [wrinkles]: the paper's step 3.5 (eqs. (1)-(13)). Its yarn (r, E) is the
/// cloth's material: stated here or in [bending], not in both (material_of
/// resolves it; neither: kDefaultYarn).
struct Wrinkles {
  std::optional<double> fiber_radius_m = std::nullopt;
  std::optional<double> fiber_modulus_pa = std::nullopt;
  std::optional<double> k_prime;
  std::optional<double> tolerance;
  std::optional<int> rounds;
};

/// [creases]: plastic bending, the paper's future work (its section 5): a fold
/// held sharper than `yield_angle` sets into a crease, the cloth's rest angle
/// there, which relaxes again while the cloth is held flatter than it and
/// pulled. Each fiber's held angle theta_h (its present angle theta low-passed
/// over set_time) and rest angle theta_r move per output frame of dt:
///   setting,  theta_h > max(theta_r, yield):  theta_r += (theta_h - theta_r)(1 - exp(-dt /
///   set_time)) relaxing, theta < theta_r:  theta_r += (theta - theta_r)(1 - exp(-dt phi /
///   relax_time))
/// phi = 1 / (1 + sqrt(T_c / T)) is the share of the crease's unfolding its hinge
/// takes, with T the tension across it (stretch modulus times strain, N/m) and
/// T_c = D / width^2 (coarse_physics/creased_bending.hpp): a crease relaxes
/// faster the harder it is pulled, and not at all without tension.
struct Creases {
  double yield_angle_rad = 1.0;  ///< a fold below it leaves nothing (57 degrees)
  /// Time constant of setting, s: a flag in light wind hangs folded at its hoist
  /// for seconds (the coarse 9 x 13 physics at 5 m/s, by 3 rad) and must not crease there.
  double set_time_s = 60.0;
  double relax_time_s = 60.0;  ///< time constant of relaxing under a tension far above T_c, s
  double width_m = 1.0e-3;     ///< the crease's hinge, the yarns bent past their yield, m
};

/// Which infill fills the dense lattice ([infill] solver).
enum class InfillSolverKind {
  kSmooth,  ///< whole-fiber infill on the coarse nodes' mean surface (hybrid default)
  kPaper,   ///< per-cell steps 3.1-3.5 with point-wise relaxation (infill-mode default)
};
inline constexpr NameTable<InfillSolverKind, 2> kInfillSolverNames = {
    {{InfillSolverKind::kSmooth, "smooth"}, {InfillSolverKind::kPaper, "paper"}}};

struct InfillSettings {
  /// Most passes of the paper solver's step 3.4; absent: its default for the mode.
  std::optional<int> relax_iterations;
  /// Absent: the mode's default (default_infill_solver).
  std::optional<InfillSolverKind> solver;
};

/// The physics integrators (solver.backend in hybrid mode; each full-lattice
/// mode runs one of them).
enum class Backend { kSpringDamper, kBullet, kImplicit, kXpbd };
/// solver.backend's names (contract), in the order users are told them.
inline constexpr NameTable<Backend, 4> kBackendNames = {{{Backend::kSpringDamper, "spring-damper"},
                                                         {Backend::kBullet, "bullet"},
                                                         {Backend::kImplicit, "implicit"},
                                                         {Backend::kXpbd, "xpbd"}}};

/// The implicit backend's linear solver (solver.linear).
enum class LinearSolver {
  kCg,        ///< matrix-free preconditioned conjugate gradient
  kCholesky,  ///< sparse LDL^T of the assembled matrix
};
inline constexpr NameTable<LinearSolver, 2> kLinearSolverNames = {
    {{LinearSolver::kCg, "cg"}, {LinearSolver::kCholesky, "cholesky"}}};

struct Solver {
  Backend backend = Backend::kSpringDamper;
  int substeps = 1;  ///< minimum substeps per output frame
  /// Passes per substep: Bullet's solver iterations (default 10), Newton
  /// iterations of "implicit" (default 1), constraint passes of "xpbd" (default 1).
  std::optional<int> iterations;
  LinearSolver linear = LinearSolver::kCg;
  /// Implicit backend: a step that changes some row or column link's strain
  /// by more than this is undone and taken as two half steps (strain, 1).
  double max_step_strain_change = 0.05;
  /// Spring-damper backend: the wind's force is evaluated once per hold of
  /// several substeps and held between, the hold at most this fraction of the
  /// wind's fastest velocity response (1 / its rate bound, 5.4 ms on the
  /// default scene: held 4 substeps there); 0: every substep (before 2026-12-07).
  double wind_hold = 0.1;
};

struct Keyframe {
  double time_s = 0.0;
  std::array<Vec3, 4> corners_m;  ///< contract corner order
};

struct Output {
  std::string file;      ///< empty: chosen by the app
  int every = 1;         ///< keep every n-th simulated frame
  int flush_every = 10;  ///< frames written between flushes to disk
  /// Per-node fields written besides the positions: "strain" (/frames/strain)
  /// and "velocity" (/frames/velocity); both unless the scene lists fewer.
  std::vector<std::string> fields = {"strain", "velocity"};
  /// false (hybrid only): the file keeps the coarse trajectory that the infill
  /// reproduces the dense frames from (/coarse/trajectory, float64, every
  /// simulated frame), not the dense frames; `flag-sim refine` recomputes them.
  bool dense = true;
  /// HDF5's deflate level (0-9, with the shuffle filter before it) for the
  /// per-node datasets (/frames/positions, velocity, strain, /coarse/*),
  /// chunked one frame a chunk; 0: stored as they are.
  int compression = 0;
  /// The simulation's state (/checkpoint, float64) at the first frame, before a
  /// flush once a second, and at the end, so that `run --resume` can continue
  /// the run; false: none.
  bool checkpoint = true;
  bool has_field(std::string_view name) const {
    return std::find(fields.begin(), fields.end(), name) != fields.end();
  }
};

/// How frames are drawn (render.style, --style).
enum class RenderStyle { kWireframe, kShaded, kTextured };
inline constexpr NameTable<RenderStyle, 3> kRenderStyleNames = {
    {{RenderStyle::kWireframe, "wireframe"},
     {RenderStyle::kShaded, "shaded"},
     {RenderStyle::kTextured, "textured"}}};

struct Render {
  RenderStyle style = RenderStyle::kShaded;
  std::array<int, 2> size_px = {1280, 720};
  std::string texture;
};

struct Limits {
  double max_strain = 0.3;       ///< past it the run stops as diverged
  double max_speed_m_s = 340.0;  ///< a node faster than this is a numerical blow-up
};

struct Scene {
  std::string name;
  Mode mode = Mode::kMassSpring;
  double duration_s = 10.0;
  double fps = 30.0;
  std::uint64_t seed = 0;

  FlagSpec flag;
  std::optional<PoleMotion> pole;       ///< [pole] with motion keys (or none at all)
  std::optional<SolidPole> solid_pole;  ///< [pole] radius
  std::optional<Ground> ground;
  std::optional<Contact> contact;  ///< [contact]: self-contact
  std::optional<Gravity> gravity;  ///< absent, or present with zero acceleration: none
  std::optional<Wind> wind;
  std::optional<Bending> bending;
  std::optional<Wrinkles> wrinkles;
  std::optional<Creases> creases;
  std::optional<InfillSettings> infill;
  Solver solver;
  std::vector<Keyframe> keyframes;
  Output output;
  std::optional<Render> render;
  Limits limits;

  /// The scene as run (file plus --set overrides), as TOML text.
  std::string toml_text;
  /// `note:` lines for the user about how the scene was read (tables a mode
  /// chosen on the command line does not use); printed by validate and run.
  std::vector<std::string> notes;

  /// Number of simulated frames, t = 0, 1/fps, ..., including the initial state.
  int simulated_frames() const;
  /// Dense lattice at rest.
  Lattice fine_lattice() const;
};

// Each enum's name as the scene file spells it (null-terminated).
const char* to_string(Mode mode);
const char* to_string(PinSet pin);
const char* to_string(FoldAxis axis);
const char* to_string(InfillSolverKind kind);
const char* to_string(Backend backend);
const char* to_string(LinearSolver linear);
const char* to_string(RenderStyle style);

/// Throws UserError, naming the key, when a Scene cannot be run: a lattice side
/// under 2 or a coarse lattice that does not divide the fine one, a hybrid
/// without flag.coarse, an infill mode without keyframes, a size, time or
/// material constant that is not a positive finite number. The parser checks
/// all this and more; this is the check for a Scene built in code (library
/// users), which make_simulation runs on every scene.
void check_scene(const Scene& scene);

/// The physics backend the scene runs: the one its full-lattice mode names
/// ("mass-spring" runs spring-damper), solver.backend in hybrid mode, none in
/// infill mode (no physics).
std::optional<Backend> backend_of(const Scene& scene);
/// backend_of's name, "" in infill mode (the reports' backend column).
std::string backend_name_of(const Scene& scene);

/// The infill a scene runs: [infill] solver, else smooth in hybrid mode (it
/// follows many coarse nodes) and paper in infill mode (corners only, Figs. 9-10).
InfillSolverKind infill_solver_of(const Scene& scene);
/// The paper solver's 3.4 cap: [infill] relax_iterations, else the mode's default.
int paper_relax_sweeps_of(const Scene& scene);

// Variants of a scene, each derived by one named function here rather than
// by editing a copy where it is needed.

/// The same scene run in `mode` (compare's tracking run, the run records'
/// full-lattice replay). Its checks were made for the scene's own mode.
Scene in_mode(const Scene& scene, Mode mode);
/// The same scene at `substeps` steps per frame at least (compare doubling a
/// reference's substeps until it is as accurate as the hybrid).
Scene with_substeps(const Scene& scene, int substeps);
/// The same scene with solver.backend the integrator its mode runs
/// (backend_of; unchanged in infill mode): what an integrator factory takes
/// in every mode.
Scene with_resolved_backend(const Scene& scene);
/// A hybrid scene's cloth on its coarse lattice (flag.coarse) as a
/// full-lattice scene: the same continuum parameters, so the same cloth
/// (masses and springs follow the spacing). flag.coarse must be set.
Scene on_coarse_lattice(const Scene& scene);

}  // namespace flagsim
