#pragma once
// What accuracy means when a flag in wind is chaotic (issue: compare and
// sweep). Each metric compares a run with a reference run of the same dense
// lattice, frame for frame; frames are [J*K] positions in m, row-major.
//
//  - rms_distance: sqrt(mean over nodes of |a_i - b_i|^2), m, over the nodes
//    a mask keeps (all when empty);
//  - short_horizon_rms: the RMS distance over frames 1..n, before the two runs'
//    trajectories decorrelate;
//  - mean_shape_rms: the RMS distance between the two time-averaged shapes over
//    frames first..end;
//  - flap_frequency: the frequency of a signal sampled at fps (the fly end's
//    out-of-plane position, once the flag flaps: the caller leaves the start
//    out): the rate of its zero crossings about its mean,
//    (n - 1) half periods between the first and the last of n crossings
//    (linear between samples), and as a check the peak of its periodogram
//    (mean removed, Hann window, refined by a parabola through the peak and
//    its neighbours). A flapping flag's spectrum is broad: its peak can sit a
//    bin or two from the rate at which the flag actually turns (up to 2.5 Hz
//    apart on the full-lattice references of 2026-12), so the crossings are
//    the figure. 0 for a signal with no variation; the spectral peak when the
//    signal crosses its mean fewer than 3 times;
//  - strain_distribution: max and 99th percentile of abs(d - S)/S over every
//    row and column link of every frame;
//  - wrinkle_wavelength_m: per row and frame, the out-of-plane offsets of the
//    row's nodes from the straight line through its neighbours' mean (a
//    second difference, which removes the flag's large-scale bend), their
//    strongest spatial frequency along the row (periodogram, as above); the
//    median over rows and frames of 1 / frequency, m;
//  - coarse_line_imprint: how much more the cloth bends on the coarse
//    lattice's lines than between them, in one frame: the median turning
//    angle of the column fibers at interior nodes on coarse rows over the
//    median at the other interior rows, the same for row fibers and coarse
//    columns, the larger of the two. About 1 for a cloth that does not show
//    its cells; a per-cell infill with creases on the coarse lines gives 7.
//    (The same figure as ../shared/tools/cloth_checks.py imprint, per frame.)
//  - crease_line_ratio: the straightest crease in one frame: over the dense
//    rows and columns at least `margin` links from the border, each line's
//    median turning angle across it (of the fibers that cross it), the
//    largest, over the median turning of those fibers in that window. About 2
//    for a smoothly flapping flag; a straight crease along one line gives
//    more. (The same figure as ../shared/tools/cloth_checks.py creaseline, per
//    frame; issue 34 asks 2.5 in the median frame and 3.5 at the 90th
//    percentile.)
#include <cstdint>
#include <span>
#include <vector>

#include "flagsim/core/lattice.hpp"
#include "flagsim/core/vec3.hpp"

namespace flagsim::analysis {

using Frames = std::vector<std::vector<Vec3>>;

double rms_distance(std::span<const Vec3> a, std::span<const Vec3> b,
                    std::span<const std::uint8_t> keep = {});

double short_horizon_rms(const Frames& a, const Frames& b, int frames);

double mean_shape_rms(const Frames& a, const Frames& b, int first_frame);

struct FlapFrequency {
  double hz = 0.0;           ///< zero-crossing rate (the spectral peak under 3 crossings)
  double spectral_hz = 0.0;  ///< periodogram peak, the check
  int crossings = 0;
};
FlapFrequency flap_frequency(std::span<const double> signal, double fps);
/// flap_frequency(signal, fps).hz
double flap_frequency_hz(std::span<const double> signal, double fps);

struct StrainDistribution {
  double max = 0.0;
  double p99 = 0.0;
};
StrainDistribution strain_distribution(const Lattice& lattice, const Frames& frames);

double wrinkle_wavelength_m(const Lattice& lattice, const Frames& frames, int first_frame);

/// @param coarse_rows, coarse_cols  dense index of each coarse row and column
double coarse_line_imprint(const Lattice& lattice, std::span<const Vec3> frame,
                           std::span<const int> coarse_rows, std::span<const int> coarse_cols);

/// @param margin  links from the border a line keeps (8 in cloth_checks.py);
///                needs rows and cols > 2 margin + 2
double crease_line_ratio(const Lattice& lattice, std::span<const Vec3> frame, int margin = 8);

}  // namespace flagsim::analysis
