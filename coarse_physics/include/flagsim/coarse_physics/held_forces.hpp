#pragma once
// Force terms held over substeps (a multiple-time-step scheme): the
// spring-damper's (spring_damper.hpp). XPBD held its wind with it too on
// 2026-12-08 and was measured, not kept (docs/flag_physics.md).
//
// The substep is set by the cloth's stiffness (the spring-damper's stability
// limit), while the wind on its 0.25 m panels changes on the flap's time
// scale. So the terms whose timing() is kSlow (the wind) or kConstant
// (gravity) are evaluated together once every hold_substeps() substeps, from
// the first substep of each frame, and between two evaluations their sum is extrapolated along its
// change since the evaluation before (second order, as Adams-Bashforth's two steps; a frame's first
// hold is held constant, so that a frame depends only on the state it starts from and a resumed run
// keeps its bits). The other terms are evaluated every substep. The hold is the largest whole
// number of substeps within solver.wind_hold (default 0.1) x 1 / the slow terms' velocity rate
// bound, at least 1 and at most the frame: the extrapolated velocity response (the wind's damping)
// is then well inside its stability interval (rate x hold < 1). Without a slow term nothing is held
// (gravity alone is cheap, and such a scene keeps its bits from before holds); the integrator says
// when nothing may be held (obstacles, whose projections change velocities within a substep; the
// vortex lattice).
#include <algorithm>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "flagsim/coarse_physics/force_term.hpp"
#include "flagsim/core/vec3.hpp"

namespace flagsim::physics {

class HeldForces {
 public:
  /// The hold for `terms` (the integrator's pipeline, kept by the caller and
  /// passed to add() unchanged) at substeps of `substep_s`, at most
  /// `substeps_per_frame`; `may_hold` false holds nothing. `nodes`: the
  /// cloth's node count.
  HeldForces(const std::vector<std::unique_ptr<ForceTerm>>& terms, double wind_hold,
             double substep_s, int substeps_per_frame, bool may_hold, std::size_t nodes);

  /// Substeps over which the slow and constant terms' forces are held (1: none held).
  int hold_substeps() const { return hold_substeps_; }
  /// The next substep is a frame's first.
  void begin_frame() { substep_ = 0; }

  /// forces = the sum of every term's forces at this substep (x, v): the held
  /// terms' at the hold's first substep, extrapolated within it, and the
  /// others evaluated now. run(t, work) runs `work` (term t's part) timed in
  /// term t's stage. With nothing held: every term in pipeline order.
  template <typename Run>
  void add(const std::vector<std::unique_ptr<ForceTerm>>& terms, std::span<const Vec3> x,
           std::span<const Vec3> v, std::vector<Vec3>& forces, Run&& run) {
    if (hold_substeps_ == 1) {
      std::fill(forces.begin(), forces.end(), Vec3::Zero());
      for (std::size_t t = 0; t < terms.size(); ++t)
        run(t, [&] { terms[t]->add_forces(x, v, forces); });
    } else {
      const int into_hold = substep_ % hold_substeps_;
      if (into_hold == 0) {
        extrapolate_ = substep_ > 0;
        if (extrapolate_) held_before_.swap(held_);
        std::fill(held_.begin(), held_.end(), Vec3::Zero());
        for (const std::size_t t : held_terms_) run(t, [&] { terms[t]->add_forces(x, v, held_); });
      }
      // Timed with the slow term (the wind's stage is what the wind costs).
      run(slow_term_, [&] {
        if (extrapolate_) {
          const double along = double(into_hold) / double(hold_substeps_);
          for (std::size_t i = 0; i < forces.size(); ++i)
            forces[i] = held_[i] + along * (held_[i] - held_before_[i]);
        } else {
          std::copy(held_.begin(), held_.end(), forces.begin());
        }
      });
      for (std::size_t t = 0; t < terms.size(); ++t)
        if (terms[t]->timing() == ForceTiming::kEverySubstep)
          run(t, [&] { terms[t]->add_forces(x, v, forces); });
    }
    ++substep_;
  }

 private:
  std::vector<std::size_t> held_terms_;  ///< indices of the kSlow and kConstant terms
  std::vector<Vec3> held_;               ///< their forces' sum, held over hold_substeps_
  std::vector<Vec3> held_before_;        ///< the sum at the hold before, in this frame
  bool extrapolate_ = false;             ///< this hold has one before it in its frame
  std::size_t slow_term_ = 0;  ///< the kSlow term setting the hold (times the extrapolation)
  int hold_substeps_ = 1;
  int substep_ = 0;  ///< substeps since the frame began
};

}  // namespace flagsim::physics
