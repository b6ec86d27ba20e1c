#pragma once
// Every numeric tolerance of the test suite, with its reason (STYLE.md, 5).

namespace flagsim::test {

/// Central finite differences in double: step h gives truncation O(h^2) and
/// round-off O(eps/h); h = 1e-6 m on O(1) m coordinates balances both near 1e-9
/// relative to the force scale, so 1e-6 relative leaves a wide margin.
inline constexpr double kFiniteDifferenceStep = 1e-6;
inline constexpr double kFiniteDifferenceRelTol = 1e-6;

/// Closed-form force values, e.g. the flat plate: only round-off differs.
inline constexpr double kAnalyticRelTol = 1e-12;

/// The bound on energy drift without damping or wind over 1000 substeps.
inline constexpr double kEnergyDriftRelTol = 0.01;

/// Issue 14's bound on how far another integrator's static sag may be from the
/// explicit one's: 1%.
inline constexpr double kSagRelTol = 0.01;

/// The CG and the sparse Cholesky on the same implicit steps: the CG stops at a
/// relative residual of 1e-4 (kLinearTolerance), so its states may part by about
/// that share of the motion; 1e-3 of it leaves a margin (measured 7e-5).
inline constexpr double kLinearSolveAgreement = 1e-3;

/// A hanging cloth "at rest": every node slower than 1 mm/s.
inline constexpr double kRestSpeed_m_s = 1e-3;

}  // namespace flagsim::test
