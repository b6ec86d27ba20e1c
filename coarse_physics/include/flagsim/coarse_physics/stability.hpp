#pragma once
// The stability policy of the steppers that integrate some force explicitly:
// the spring-damper (all of them), Bullet (bending, wind), XPBD (gravity,
// wind). Implicit Euler reports the explicit limit for comparison only.
#include <memory>
#include <vector>

#include "flagsim/coarse_physics/cloth_model.hpp"
#include "flagsim/coarse_physics/force_term.hpp"

namespace flagsim::physics {

/// Fraction of the stability limit used as substep. Stability alone would allow
/// ~0.9; accuracy does not: on a released, jiggled 7x9 cloth (spring_damper_test)
/// the energy error after 1000 substeps is 1.6% of the peak kinetic energy at
/// 0.8 of the limit and 0.08% at 0.5 (it falls faster than dt^2). 0.5 also
/// leaves room for the tension (geometric) stiffness the bound leaves out.
inline constexpr double kStabilitySafety = 0.5;

/// Largest stable substep of explicit integration under `terms`, s: 2 / omega_max
/// with omega_max^2 the largest block Gershgorin row sum over mass of a free
/// node, and at most 1 / rate for velocity-dependent terms; infinity if none bounds it.
double explicit_stability_limit(const ClothModel& model,
                                const std::vector<std::unique_ptr<ForceTerm>>& terms);

/// Substeps per frame of `frame_s`: enough for each to be at most
/// kStabilitySafety of `stable_substep_s`, and at least `minimum` (solver.substeps).
/// Throws UserError (exit 2, before any frame) when that is more than
/// limits::kSubstepsPerFrame, with the number and what to change.
int substeps_per_frame(double frame_s, double stable_substep_s, int minimum);

}  // namespace flagsim::physics
