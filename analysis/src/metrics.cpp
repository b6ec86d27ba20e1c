#include "flagsim/analysis/metrics.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "flagsim/core/strain.hpp"

namespace flagsim::analysis {
namespace {

// Index (fractional) of the strongest non-zero frequency bin of the Hann-windowed,
// mean-removed signal; -1 when the signal does not vary.
double peak_bin(std::span<const double> signal) {
  const std::size_t n = signal.size();
  if (n < 4) return -1.0;
  double mean = 0.0;
  for (double v : signal) mean += v;
  mean /= double(n);
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double hann = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * double(i) / double(n - 1));
    x[i] = (signal[i] - mean) * hann;
  }
  std::vector<double> power(n / 2 + 1, 0.0);
  for (std::size_t f = 1; f < power.size(); ++f) {
    double re = 0.0, im = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double phase = 2.0 * std::numbers::pi * double(f * i % n) / double(n);
      re += x[i] * std::cos(phase);
      im -= x[i] * std::sin(phase);
    }
    power[f] = re * re + im * im;
  }
  const auto best = std::max_element(power.begin() + 1, power.end());
  if (*best <= 1e-30) return -1.0;
  const std::size_t k = std::size_t(best - power.begin());
  if (k == 0 || k + 1 >= power.size()) return double(k);
  // Parabola through the log power of the peak and its neighbours.
  const double a = std::log(power[k - 1] + 1e-300), b = std::log(power[k]),
               c = std::log(power[k + 1] + 1e-300);
  const double denom = a - 2.0 * b + c;
  const double shift = denom != 0.0 ? 0.5 * (a - c) / denom : 0.0;
  return double(k) + std::clamp(shift, -0.5, 0.5);
}

}  // namespace

double rms_distance(std::span<const Vec3> a, std::span<const Vec3> b,
                    std::span<const std::uint8_t> keep) {
  if (a.size() != b.size()) throw std::invalid_argument("rms_distance: different node counts");
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!keep.empty() && !keep[i]) continue;
    sum += (a[i] - b[i]).squaredNorm();
    ++count;
  }
  return count ? std::sqrt(sum / double(count)) : 0.0;
}

double short_horizon_rms(const Frames& a, const Frames& b, int frames) {
  const int last = std::min({frames, int(a.size()) - 1, int(b.size()) - 1});
  double sum = 0.0;
  for (int t = 1; t <= last; ++t) {
    const double r = rms_distance(a[std::size_t(t)], b[std::size_t(t)]);
    sum += r * r;
  }
  return last >= 1 ? std::sqrt(sum / last) : 0.0;
}

double mean_shape_rms(const Frames& a, const Frames& b, int first_frame) {
  const int end = int(std::min(a.size(), b.size()));
  if (first_frame >= end) return 0.0;
  const std::size_t n = a[0].size();
  std::vector<Vec3> mean_a(n, Vec3::Zero()), mean_b(n, Vec3::Zero());
  for (int t = first_frame; t < end; ++t)
    for (std::size_t i = 0; i < n; ++i) {
      mean_a[i] += a[std::size_t(t)][i];
      mean_b[i] += b[std::size_t(t)][i];
    }
  return rms_distance(mean_a, mean_b) / double(end - first_frame);
}

FlapFrequency flap_frequency(std::span<const double> signal, double fps) {
  FlapFrequency result;
  const double bin = peak_bin(signal);
  if (bin < 0.0) return result;  // no variation: no flapping
  result.spectral_hz = bin * fps / double(signal.size());
  double mean = 0.0;
  for (double v : signal) mean += v;
  mean /= double(signal.size());
  // Crossing times (in samples), linear between the two samples either side.
  std::vector<double> crossings;
  for (std::size_t i = 0; i + 1 < signal.size(); ++i) {
    const double a = signal[i] - mean, b = signal[i + 1] - mean;
    if ((a < 0.0) != (b < 0.0)) crossings.push_back(double(i) + a / (a - b));
  }
  result.crossings = int(crossings.size());
  if (crossings.size() < 3) {
    result.hz = result.spectral_hz;  // under a period: the spectrum is all there is
    return result;
  }
  // (n - 1) half periods between the first and the last crossing.
  result.hz = double(crossings.size() - 1) * fps / (2.0 * (crossings.back() - crossings.front()));
  return result;
}

double flap_frequency_hz(std::span<const double> signal, double fps) {
  return flap_frequency(signal, fps).hz;
}

StrainDistribution strain_distribution(const Lattice& lattice, const Frames& frames) {
  std::vector<float> strains;
  for (const auto& x : frames)
    for_each_link(lattice, [&](const Link& link) { strains.push_back(float(strain_of(x, link))); });
  if (strains.empty()) return {};
  const std::size_t at = std::size_t(0.99 * double(strains.size() - 1));
  std::nth_element(strains.begin(), strains.begin() + long(at), strains.end());
  const double p99 = strains[at];
  return {double(*std::max_element(strains.begin(), strains.end())), p99};
}

double wrinkle_wavelength_m(const Lattice& lattice, const Frames& frames, int first_frame) {
  std::vector<double> wavelengths;
  const int cols = lattice.cols;
  if (cols < 8) return 0.0;
  std::vector<double> offsets(std::size_t(cols - 2));
  for (std::size_t t = std::size_t(std::max(first_frame, 0)); t < frames.size(); ++t) {
    const NodeView x(lattice, frames[t]);
    for (int j = 1; j + 1 < lattice.rows; ++j) {
      for (int k = 1; k + 1 < cols; ++k) {
        // The local normal from the neighbours across and along the row.
        const Vec3 along = x.at(j, k + 1) - x.at(j, k - 1);
        const Vec3 across = x.at(j + 1, k) - x.at(j - 1, k);
        Vec3 normal = along.cross(across);
        const double norm = normal.norm();
        if (norm > 0.0) normal /= norm;
        const Vec3 off = x.at(j, k) - 0.5 * (x.at(j, k - 1) + x.at(j, k + 1));
        offsets[std::size_t(k - 1)] = off.dot(normal);
      }
      const double bin = peak_bin(offsets);
      if (bin > 0.0) wavelengths.push_back(double(offsets.size()) * lattice.spacing_x_m / bin);
    }
  }
  if (wavelengths.empty()) return 0.0;
  std::nth_element(wavelengths.begin(), wavelengths.begin() + long(wavelengths.size() / 2),
                   wavelengths.end());
  return wavelengths[wavelengths.size() / 2];
}

namespace {

// The angle a fiber turns by at b, between a -> b and b -> c, rad.
double turning(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - a, v = c - b;
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

// The median (the mean of the middle two for an even count, as numpy's), 0 if empty.
double median(std::vector<double>& v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  const double upper = v[v.size() / 2];
  if (v.size() % 2) return upper;
  return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2)));
}

}  // namespace

double coarse_line_imprint(const Lattice& lattice, std::span<const Vec3> frame,
                           std::span<const int> coarse_rows, std::span<const int> coarse_cols) {
  const int J = lattice.rows, K = lattice.cols;
  std::vector<char> on_row(std::size_t(J), 0), on_col(std::size_t(K), 0);
  for (int j : coarse_rows) on_row[std::size_t(j)] = 1;
  for (int k : coarse_cols) on_col[std::size_t(k)] = 1;
  std::vector<double> across_rows_on, across_rows_off, across_cols_on, across_cols_off;
  const NodeView x(lattice, frame);
  for (int j = 0; j < J; ++j)
    for (int k = 0; k < K; ++k) {
      const Vec3& p = x.at(j, k);
      if (j > 0 && j + 1 < J)  // the column fiber bending at (j, k)
        (on_row[std::size_t(j)] ? across_rows_on : across_rows_off)
            .push_back(turning(x.at(j - 1, k), p, x.at(j + 1, k)));
      if (k > 0 && k + 1 < K)  // the row fiber bending at (j, k)
        (on_col[std::size_t(k)] ? across_cols_on : across_cols_off)
            .push_back(turning(x.at(j, k - 1), p, x.at(j, k + 1)));
    }
  const auto ratio = [&](std::vector<double>& on, std::vector<double>& off) {
    if (on.empty() || off.empty()) return 1.0;
    return median(on) / std::max(median(off), 1e-9);
  };
  return std::max(ratio(across_rows_on, across_rows_off), ratio(across_cols_on, across_cols_off));
}

double crease_line_ratio(const Lattice& lattice, std::span<const Vec3> frame, int margin) {
  const int J = lattice.rows, K = lattice.cols, e = margin;
  assert(J > 2 * e + 2 && K > 2 * e + 2 && frame.size() == lattice.node_count());
  const NodeView x(lattice, frame);
  // Rows and columns e .. J-1-e (K-1-e): along each such row line the column
  // fibers' turning at it, along each column line the row fibers'.
  std::vector<double> all, line;
  double worst = 0.0;
  for (int j = e; j <= J - 1 - e; ++j) {
    line.clear();
    for (int k = e; k <= K - 1 - e; ++k)
      line.push_back(turning(x.at(j - 1, k), x.at(j, k), x.at(j + 1, k)));
    all.insert(all.end(), line.begin(), line.end());
    worst = std::max(worst, median(line));
  }
  for (int k = e; k <= K - 1 - e; ++k) {
    line.clear();
    for (int j = e; j <= J - 1 - e; ++j)
      line.push_back(turning(x.at(j, k - 1), x.at(j, k), x.at(j, k + 1)));
    all.insert(all.end(), line.begin(), line.end());
    worst = std::max(worst, median(line));
  }
  return worst / std::max(median(all), 1e-12);
}

}  // namespace flagsim::analysis
