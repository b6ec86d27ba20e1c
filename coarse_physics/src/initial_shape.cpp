#include "flagsim/coarse_physics/initial_shape.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "flagsim/coarse_physics/cloth_state.hpp"
#include "flagsim/coarse_physics/creased_bending.hpp"
#include "flagsim/coarse_physics/pin_motion.hpp"

namespace flagsim::physics {
namespace {

// Uniform in [0, 1) from the top 53 bits: the same numbers on every standard
// library (std::uniform_real_distribution is implementation-defined).
double unit_uniform(std::mt19937_64& rng) {
  return double(rng() >> 11) * 0x1.0p-53;
}

}  // namespace

std::vector<double> smooth_perturbation(const Lattice& lattice, std::uint64_t seed,
                                        double amplitude_m) {
  constexpr int kModes = 3;
  std::mt19937_64 rng(seed);
  double weight[kModes], phase_u[kModes], phase_v[kModes];
  for (int m = 0; m < kModes; ++m) {
    weight[m] = 2.0 * unit_uniform(rng) - 1.0;
    phase_u[m] = 2.0 * std::numbers::pi * unit_uniform(rng);
    phase_v[m] = 2.0 * std::numbers::pi * unit_uniform(rng);
  }
  std::vector<double> z(lattice.node_count());
  for (int j = 0; j < lattice.rows; ++j) {
    const double v = double(j) / (lattice.rows - 1);
    for (int k = 0; k < lattice.cols; ++k) {
      const double u = double(k) / (lattice.cols - 1);
      double sum = 0.0;
      for (int m = 0; m < kModes; ++m)
        sum += weight[m] * std::sin((m + 1) * std::numbers::pi * u + phase_u[m]) *
               std::cos(m * std::numbers::pi * v + phase_v[m]);
      z[lattice.index(j, k)] = amplitude_m * u * sum / kModes;
    }
  }
  return z;
}

void begin_frame(const std::vector<std::unique_ptr<ForceTerm>>& terms, ClothState& state) {
  const auto each_memory = [&](auto&& visit) {
    std::size_t at = 0;
    for (const auto& term : terms) {
      const std::size_t size = term->memory().size();
      if (size > 0) visit(*term, std::span<double>(state.memory).subspan(at, size));
      at += size;
    }
  };
  if (!state.memory.empty())
    each_memory([](ForceTerm& term, std::span<double> memory) { term.set_memory(memory); });
  for (const auto& term : terms) term->begin_frame(state.time_s, state.x_m);
  if (!state.memory.empty())
    each_memory([](const ForceTerm& term, std::span<double> memory) {
      std::copy(term.memory().begin(), term.memory().end(), memory.begin());
    });
}

ClothState initial_state(const Scene& scene, const ClothModel& model) {
  ClothState state;
  state.x_m = model.lattice.rest_positions();
  const std::size_t n = state.x_m.size();
  state.v_m_s.assign(n, Vec3::Zero());
  if (scene.flag.initial_perturbation_m > 0.0) {
    const std::vector<double> z =
        smooth_perturbation(model.lattice, scene.seed, scene.flag.initial_perturbation_m);
    for (std::size_t i = 0; i < n; ++i)
      if (!model.pinned[i]) state.x_m[i].z() += z[i];
  }
  const Vec3 pin_velocity = model.pin_motion.velocity_m_s(0.0);
  for (std::size_t i = 0; i < n; ++i)
    if (model.pinned[i]) state.v_m_s[i] = pin_velocity;
  // The terms' memory: the creases' rest angles (the bending term's), from the folds.
  if (model.material.creased())
    state.memory = initial_crease_memory(scene.flag.folds, model.lattice);
  return state;
}

}  // namespace flagsim::physics
