#pragma once
// The sizes a scene, a command-line flag and an output file may declare, in
// one place: a scene, `--size` and a file read back are checked against the
// same numbers (contract: "Scene keys"; README: ranges of physical keys).
#include <cstddef>

namespace flagsim::limits {

/// Nodes along one side of a lattice, fine or coarse.
inline constexpr long long kLatticeSide = 8193;
/// Nodes of a whole fine lattice (16 Mi: 400 MB of float64 positions).
inline constexpr long long kLatticeNodes = 16'777'216;
/// Frames of one run, including t = 0.
inline constexpr long long kFrames = 10'000'000;
/// Substeps of one frame, as solver.substeps may ask and as a stability limit
/// may need: past this a scene is refused with the number (a 1 um flag once
/// validated at 80 million substeps a frame and ran on for hours).
inline constexpr long long kSubstepsPerFrame = 1'000'000;
/// Pixels along one side of a rendered image ([render] size and --size).
inline constexpr int kImageSideMin = 16;
inline constexpr int kImageSideMax = 8192;
/// |x|, |y|, |z| of any position a scene gives (flag origin, keyframe
/// corners), m: float32 output keeps 1 mm up to here (eps 6e-8 x 1e4 m).
inline constexpr double kCoordinate_m = 1.0e4;
/// Frames per second of a scene, and of a file read back for rendering.
inline constexpr double kFps = 10'000.0;
/// Bytes of an `error:` line after "error: "; longer messages are cut.
inline constexpr std::size_t kMessageBytes = 600;

}  // namespace flagsim::limits
