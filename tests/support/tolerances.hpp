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

/// Bullet's static sag against the spring-damper's, as the README states
/// them: measured 1.58% apart pinned along the top (9.47 vs 9.32 mm) and 0.24%
/// by the corners (53.89 vs 53.76 mm), each held to a little more.
inline constexpr double kBulletSagTopRelTol = 0.02;
inline constexpr double kBulletSagCornersRelTol = 0.004;

/// The CG and the sparse Cholesky on the same implicit steps: the CG stops at a
/// relative residual of 1e-4 (kLinearTolerance), so its states may part by about
/// that share of the motion; 1e-3 of it leaves a margin (measured 7e-5).
inline constexpr double kLinearSolveAgreement = 1e-3;

/// A hanging cloth "at rest": every node slower than 1 mm/s.
inline constexpr double kRestSpeed_m_s = 1e-3;

// Round-off (absolute, on values of order 1 in SI units: m, s, kg, N, J).

/// A value a computation gets right but for its last rounding (a weight of 0
/// or 1/2, a product of short binary fractions, a time of 1/8 s).
inline constexpr double kExact = 1e-15;
/// A closed-form result computed through up to ~1e3 double operations.
inline constexpr double kRoundOff = 1e-12;
/// A value carried through hundreds of substeps of an integrator, or a
/// square root and its square: accumulated round-off, far below any effect.
inline constexpr double kAccumulatedRoundOff = 1e-9;
/// A polynomial the spline surface reproduces, through its QR solve: the
/// null-space basis's condition grows as stride^order (sixth differences since
/// 2026-12-08); at stride 64 (13 -> 769 nodes, 17 -> 1025 with the ghost
/// nodes) values of about 5 come out within 5.9e-8 of the polynomial.
inline constexpr double kSplineSolve = 1e-7;
/// The banded QR's spline matrix against the dense QR's: each solve's round-off
/// times that condition, 4.4e-10 at stride 16 (13 -> 193 nodes).
inline constexpr double kSplineQrAgreement = 2e-9;
/// A value stored as float32 (output positions, strain) of order 0.1-1:
/// 2^-24 relative is 6e-8; 1e-6 absolute leaves room for the conversion of
/// a computed double and of the reference.
inline constexpr double kFloat32 = 1e-6;

// Discretisation and sampling (relative unless the name says otherwise).

/// A lattice's elastic or bending energy against the continuum's it
/// discretises: 9 x 13 to 33 x 49 nodes, strains of 1e-3 (second-order terms).
inline constexpr double kContinuumRelTol = 0.01;
/// The wind on one shape and motion at two lattices (33 x 49 and 129 x 193),
/// through 0.125 m panels: the panel nodes are trapezoid sums of smooth
/// fields under their hats, O(h^2). Measured: total force 0.08% apart, the
/// force on each 0.25 m square within 0.23% of the largest square's.
inline constexpr double kResolutionAgreement = 0.005;
/// The share of the flag-length wave's growth rate that the wind may give a
/// wave of five lattice cells on 0.125 m panels. Measured: 0.4% (the same
/// cloth with its own triangles as panels: 93%).
inline constexpr double kGridWaveDriveShare = 0.02;
/// A wave of 1.9 flag lengths (k = 2.2 /m) seen through 0.125 m hats: its
/// slope is averaged down by about (k l)^2 / 6 = 1.3%. Measured 1.7%.
inline constexpr double kPanelSmoothing = 0.03;
/// The same for a fiber's bending energy of a wave of small slope (400
/// segments, amplitude/wavelength 0.024: the slope's fourth-order terms).
inline constexpr double kWaveContinuumRelTol = 0.02;
/// Eq. (1)'s turning angle against the second finite difference on a helix
/// sampled at 5-20 mm: the two agree to O(h^2) (curvature h)^2 ~ 1e-3.
inline constexpr double kSecondDifferenceRelTol = 0.01;
/// The flap frequency of a sampled sine (300 frames at 30 fps: 0.1 Hz bins,
/// the peak interpolated between them).
inline constexpr double kSpectralRelTol = 0.02;
/// A sine sheet's wrinkle wavelength from its rows' spectra (97 columns).
inline constexpr double kWavelengthRelTol = 0.1;
/// Sample statistics of a seeded turbulent wind of 10 s (finitely many
/// Fourier modes): its mean speed within 1 m/s of 10 m/s (|u| grows with the
/// cross-wind fluctuations), the along-wind intensity within 10%, the
/// cross-wind ones within 25%.
inline constexpr double kTurbulenceMeanAbs_m_s = 1.0;
inline constexpr double kTurbulenceAlongRelTol = 0.1;
inline constexpr double kTurbulenceAcrossRelTol = 0.25;
/// Property 3 and issue 12: the wrinkle wavelength grows as r^2, a log-log
/// slope of 2 +- 0.5 (the half-wave count m is an integer).
inline constexpr double kWavelengthSlopeTol = 0.5;
/// The flap frequency of a flag pinned on the right, wind reversed, against
/// the same flag mirrored (17 x 25 over 2.5 s, zero crossings: measured 14-17% apart).
inline constexpr double kMirroredFlapRelTol = 0.25;
/// ffprobe's duration of an MP4, s: printed to the millisecond.
inline constexpr double kVideoDuration_s = 1e-3;
/// Figures compare and sweep write to their CSV, re-read: printed with
/// enough digits for 1e-4 relative (the 1e-5 ms floor: a printed 0).
inline constexpr double kCsvRelTol = 1e-4;
inline constexpr double kCsvAbs_ms = 1e-5;

// Lengths after a projection or relaxation (relative to the rest length).

/// Property 1: every fiber within 1% of its rest length.
inline constexpr double kFiberLengthRelTol = 0.01;
/// A re-laid wave: the nodes sit on the arc, whose chords are shorter than
/// the arc by ~ (curvature h)^2 / 24 over 96 segments: the fiber's length
/// within 1e-3, each link within the 0.5% band.
inline constexpr double kRelaidLengthRelTol = 1e-3;
inline constexpr double kRelaidLinkRelTol = 0.005;
/// A projection run to 1e-6: a link pulled to its band's edge lands within
/// 1e-5 of it (the damped Gauss-Newton step stops once inside the tolerance).
inline constexpr double kProjectedEdge = 1e-5;

}  // namespace flagsim::test
