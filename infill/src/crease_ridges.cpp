#include "flagsim/infill/crease_ridges.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace flagsim::infill {
namespace {

// A coarse triple with less rest angle than this holds no crease, rad.
constexpr double kLeastCrease = 1e-3;
// A ridge is laid out to this many decay lengths from its line (e^-8: 3e-4 of its height).
constexpr double kRidgeReach = 8.0;
// The sharpest ridge, rad: slopes of 11.5 degrees either side, 23 degrees of
// turning on the line (the cloth's median is about 1). A crease hidden more than
// this is a fold the coarse cloth is about to show (a folded flag hoisted
// has its creases flat at t = 0; they pop out within tenths of a second), and
// steeper ridges made the projection work longer for nothing more to see.
constexpr double kMostKink = 0.4;

}  // namespace

CreaseRidges::CreaseRidges(const Lattice& fine, const CellGrid& grid,
                           const CreaseRidgeParams& params)
    : fine_(fine),
      grid_(grid),
      params_(params),
      offsets_(fine.node_count(), 0.0),
      row_ridges_(std::size_t(grid.coarse_rows)),
      col_ridges_(std::size_t(grid.coarse_cols)) {}

void CreaseRidges::set_rest(std::span<const double> coarse_rest_rad) {
  const std::size_t triples =
      std::size_t(grid_.coarse_rows) * std::size_t(std::max(0, grid_.coarse_cols - 2)) +
      std::size_t(std::max(0, grid_.coarse_rows - 2)) * std::size_t(grid_.coarse_cols);
  assert(coarse_rest_rad.size() >= triples);
  rest_.assign(coarse_rest_rad.begin(), coarse_rest_rad.begin() + std::ptrdiff_t(triples));
}

bool CreaseRidges::any() const {
  return std::any_of(rest_.begin(), rest_.end(), [](double angle) { return angle > kLeastCrease; });
}

void CreaseRidges::find_ridges(std::span<const Vec3> coarse_m, bool rows, int fiber,
                               std::vector<Ridge>& out) const {
  out.clear();
  const int Jc = grid_.coarse_rows, Kc = grid_.coarse_cols;
  const int nodes = rows ? Kc : Jc;
  if (rest_.empty() || nodes < 3) return;
  const std::size_t row_triples = std::size_t(Jc) * std::size_t(Kc - 2);
  // Rest angle of the triple centred at node i of this fiber, and the node's position.
  const auto rest = [&](int i) {
    return rows ? rest_[std::size_t(fiber) * std::size_t(Kc - 2) + std::size_t(i - 1)]
                : rest_[row_triples + std::size_t(i - 1) * std::size_t(Kc) + std::size_t(fiber)];
  };
  const auto node = [&](int i) -> const Vec3& {
    return coarse_m[rows ? grid_.coarse_index(fiber, i) : grid_.coarse_index(i, fiber)];
  };
  // Dense and coarse rest spacings along the fiber, m.
  const double dense_link = rows ? fine_.spacing_x_m : fine_.spacing_y_m;
  const double spacing = dense_link * (rows ? grid_.col_stride : grid_.row_stride);
  for (int first = 1; first + 1 < nodes; ++first) {
    if (!(rest(first) > kLeastCrease)) continue;
    int last = first;
    while (last + 2 < nodes && rest(last + 1) > kLeastCrease) ++last;
    double angle = 0.0, moment = 0.0;
    for (int i = first; i <= last; ++i) {
      angle += rest(i);
      moment += rest(i) * i;
    }
    // What the coarse cloth shows of it: its turning across the run.
    const Vec3 in = node(first) - node(first - 1), out_link = node(last + 1) - node(last);
    const double shown = std::atan2(in.cross(out_link).norm(), in.dot(out_link));
    // The tension along the fiber there: Y times the mean strain of its links.
    double length = 0.0;
    for (int i = first - 1; i <= last; ++i) length += (node(i + 1) - node(i)).norm();
    const double strain = length / ((last - first + 2) * spacing) - 1.0;
    const double tension = params_.stretch_modulus_n_m * std::max(strain, 0.0);
    double decay = dense_link;
    if (tension > 0.0) decay = std::min(decay, std::sqrt(params_.rigidity_j / tension));
    const double kink =
        std::min(kMostKink, std::max(0.0, angle - shown) / (1.0 + params_.width_m / (2.0 * decay)));
    if (kink > 0.0) out.push_back({moment / angle, 0.5 * kink * decay, decay});
    first = last;
  }
}

void CreaseRidges::add_family(bool rows) {
  // Rows' ridges lie across k, interpolated in j between coarse rows; columns' the other way.
  const int J = fine_.rows, K = fine_.cols;
  const int across_count = rows ? J : K;  // dense fibers of the family
  const int stride_across = rows ? grid_.row_stride : grid_.col_stride;
  const int stride_along = rows ? grid_.col_stride : grid_.row_stride;
  const int along_count = rows ? K : J;
  const double link_m = rows ? fine_.spacing_x_m : fine_.spacing_y_m;
  const std::vector<std::vector<Ridge>>& ridges = rows ? row_ridges_ : col_ridges_;
  const int coarse_fibers = int(ridges.size());
  for (int f = 0; f < across_count; ++f) {
    const int below = std::min(f / stride_across, coarse_fibers - 1);
    const double t = double(f - below * stride_across) / stride_across;
    for (const int c : {below, below + 1}) {
      const double weight = c == below ? 1.0 - t : t;
      if (weight <= 0.0 || c >= coarse_fibers) continue;
      for (const Ridge& ridge : ridges[std::size_t(c)]) {
        const double place = ridge.place * stride_along;  // dense index along the fiber
        const double reach = kRidgeReach * ridge.decay_m / link_m;
        const int from = std::max(0, int(std::ceil(place - reach)));
        const int to = std::min(along_count - 1, int(std::floor(place + reach)));
        for (int i = from; i <= to; ++i) {
          const std::size_t index = rows ? fine_.index(f, i) : fine_.index(i, f);
          offsets_[index] +=
              weight * ridge.height_m * std::exp(-std::abs(i - place) * link_m / ridge.decay_m);
        }
      }
    }
  }
}

const std::vector<double>& CreaseRidges::offsets(std::span<const Vec3> coarse_m) {
  std::fill(offsets_.begin(), offsets_.end(), 0.0);
  for (int jc = 0; jc < grid_.coarse_rows; ++jc)
    find_ridges(coarse_m, true, jc, row_ridges_[std::size_t(jc)]);
  for (int kc = 0; kc < grid_.coarse_cols; ++kc)
    find_ridges(coarse_m, false, kc, col_ridges_[std::size_t(kc)]);
  add_family(true);
  add_family(false);
  return offsets_;
}

}  // namespace flagsim::infill
