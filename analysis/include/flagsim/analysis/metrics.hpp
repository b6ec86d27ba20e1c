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
//  - flap_frequency_hz: the strongest frequency of a signal sampled at fps (the
//    fly end's out-of-plane position): the peak of the periodogram of the
//    mean-removed, Hann-windowed signal, refined by a parabola through the peak
//    and its neighbours; 0 for a signal with no variation;
//  - strain_distribution: max and 99th percentile of abs(d - S)/S over every
//    row and column link of every frame;
//  - wrinkle_wavelength_m: per row and frame, the out-of-plane offsets of the
//    row's nodes from the straight line through its neighbours' mean (a
//    second difference, which removes the flag's large-scale bend), their
//    strongest spatial frequency along the row (periodogram, as above); the
//    median over rows and frames of 1 / frequency, m.
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

double flap_frequency_hz(std::span<const double> signal, double fps);

struct StrainDistribution {
  double max = 0.0;
  double p99 = 0.0;
};
StrainDistribution strain_distribution(const Lattice& lattice, const Frames& frames);

double wrinkle_wavelength_m(const Lattice& lattice, const Frames& frames, int first_frame);

}  // namespace flagsim::analysis
