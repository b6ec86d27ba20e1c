#pragma once
// What a physics backend says about its own stepping, as data: a failure that
// makes a frame untrustworthy though its state may look sound, or, when a run
// diverged, the backend's setting that buys it stability or accuracy. The
// library never words it; sim::describe does, for the command line and Python
// alike, and a program branches on `kind` and the numbers.
namespace flagsim::physics {

struct SolverNote {
  enum class Kind {
    /// Implicit Euler's conjugate-gradient solve stopped at `residual`
    /// (relative) above `tolerance` after `cg_iterations`, in a step of
    /// `step_s` at `time_s` (a failure).
    kCgNotConverged,
    /// Implicit Euler's sparse Cholesky factorisation failed at `time_s`: the
    /// system is not positive definite (a failure).
    kCholeskyFailed,
    /// XPBD's links stretch more the longer its substep (advice).
    kXpbdSubstep,
    /// Implicit Euler linearizes each step once per Newton iteration (advice).
    kImplicitLinearization,
  };
  Kind kind = Kind::kXpbdSubstep;
  int substeps = 0;    ///< the backend's substeps (implicit: steps) a frame now
  int iterations = 0;  ///< solver.iterations now (XPBD's passes, implicit's Newton iterations)
  int cg_iterations = 0;
  double time_s = 0.0;
  double step_s = 0.0;
  double residual = 0.0;
  double tolerance = 0.0;
};

}  // namespace flagsim::physics
